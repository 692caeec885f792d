#!/usr/bin/env python3
"""The browser build tested in a real browser: headless Chromium (tests/web/chromium.py) loads
the page from the project's own static server (web/serve.py) and the test reads what the app
prints to the console. Run by `./dev.sh test` after building build-web/site:

    python3 tests/web/browser_test.py --site build-web/site --softbody build/app/softbody \\
        --compare build/tests/render/softbody_image_compare [--module build/app/python] [--work DIR] [--bless]

Cases (all must pass):
  pile        the issue's scripted run, on the threaded build (the page cross-origin isolated):
              index.html?scene=assets/scenes/pile.json&frames=120&frame_time=0.02 prints the run
              summary of `softbody run --frames 120 --frame-time 0.02`; its state hash and the
              rigid bodies' states must be those of the native build run now with the same
              arguments and the portable pair tile (SOFTBODY_KERNEL=portable), not a number kept
              here (the physics changes; the equality must not). Then the page's picture,
              panels included, against tests/render/references/web_pile.png, with the
              screenshot tests' comparison (tests/render/README.md).
  threads     a soft body of 700 particles (three blocks of the pair kernel, one ragged) and a
              pile of rigid bodies, `softbody simulate`, on the threaded build with its SIMD
              tile: the native portable tile's state hash.
  one_thread  the same on a page that is not cross-origin isolated: the page must pick the
              one-thread build, and reach the same hash.
  module      the same scene and ticks in the Python module (app/python, built in --module):
              the same state hash again, so that the desktop build, the page and the module are
              compared in one place. Skipped, saying so, only when the module was not built.
  drop_record a mesh file dropped onto the page (an HTML drop event carrying assets/meshes/cube.obj)
              becomes the body (the summary's mesh and 8 particles), and the M key records:
              the summary's recording, and a WebM file the browser downloads.
  tablet      a 1024x768 tablet at pixel ratio 2, by touch (tests/web/touch_cases.py): the canvas
              has a pixel for each of the screen's; a finger drags the ball up; taps on the
              panel's Pause and Reset work; a pinch zooms, two fingers pan, one on the sky orbits;
              a long press inspects.
  phone       a 390x844 phone at ratio 2: the panel starts folded, a tap on its arrow unfolds it,
              and Pause answers a tap there.
  copy_link   a finger drags a slider (a changed key); Share > Copy link puts an address on the
              clipboard whose page has the same setup, and whose run of 60 fixed frames has the
              native build's state hash for the same command line.
  presets     Share > Download preset saves a scene file the native build loads; Share > Upload
              opens it again through the file chooser; a preset saved in the page is there in
              the site's next page.
  screenshots lesson 1 at a desktop's, a tablet's and a phone's size, saved in --work to look at.

--only runs the named cases alone. --bless writes the pile's picture to the reference instead of comparing (only on purpose,
after looking at it). Exit 0 when every case passes, 1 otherwise.
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import urllib.parse

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from chromium import BrowserError, Chromium  # noqa: E402
import touch_cases  # noqa: E402

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
REFERENCE = os.path.join(ROOT, "tests", "render", "references", "web_pile.png")
VIEW = (960, 600)  # the browser's window: the canvas fills it
# The picture may differ from the reference in the panel's wall-clock read-out (physics
# ms/tick) and its thread count, a few glyphs: between runs 0.006 % to 0.025 % of the pixels
# over 16, mean 0.005 to 0.025; the one-thread build against the threaded one's reference
# (a whole line of that text moved) 0.09 %, mean 0.095. The picture checks the drawing (the
# physics is checked to the bit by the hash): a camera framed for another window size differs
# by 9 %, mean 4.8. Same per-pixel threshold as the OSMesa tests, a larger fraction and mean.
THRESHOLDS = ["--pixel-threshold", "16", "--max-fraction", "0.002", "--max-mean", "0.3"]

PILE_ARGS = {"scene": "assets/scenes/pile.json", "frames": "120", "frame_time": "0.02"}
MIXED_ARGS = {"command": "simulate", "scene": "pile:12+cloud:700", "ticks": "100"}
COMPARED_FIELDS = ("ticks", "sim_time", "status", "state_hash", "com", "particles", "rigid_bodies")
DROP_ARGS = {"scene": "assets/scenes/default.json", "frames": "90", "frame_time": "0.02", "size": "320x240"}


class Skip(Exception):
    """A case left out by --only."""


class Failure(Exception):
    pass


ALL_CASES = ("pile", "threads", "one_thread", "module", "drop_record") + touch_cases.CASES


def start_server(site, isolated):
    """web/serve.py on a free port; returns (process, base URL)."""
    args = [sys.executable, os.path.join(ROOT, "web", "serve.py"), "--port", "0", "--quiet", site]
    if not isolated:
        args.insert(-1, "--no-isolation")
    errors = tempfile.TemporaryFile(mode="w+")
    process = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=errors, text=True)
    line = process.stdout.readline()  # the one line it prints: where it serves
    match = re.search(r"at (http://\S+/)", line)
    if not match:
        process.kill()
        process.wait()
        errors.seek(0)
        raise Failure("web/serve.py did not start: " + (line + errors.read()).strip())
    return process, match.group(1)


def native(softbody, args):
    """The native build's summary for the same command, with the portable pair tile. args: the
    page's address's parameters, a dict or (name, value) pairs (a name may repeat: set)."""
    pairs = list(args.items()) if isinstance(args, dict) else list(args)
    argv = [softbody, dict(pairs).get("command", "run")]
    for name, value in pairs:
        if name != "command":
            argv += ["--" + name.replace("_", "-"), value]
    if argv[1] == "run" and not os.environ.get("DISPLAY"):
        argv = ["xvfb-run", "-a", "-s", "-screen 0 1280x800x24"] + argv
    env = dict(os.environ, SOFTBODY_KERNEL="portable")
    result = subprocess.run(argv, cwd=ROOT, env=env, capture_output=True, text=True, timeout=600)
    if result.returncode != 0:
        raise Failure(f"native {' '.join(argv)} failed ({result.returncode}): {result.stderr.strip()}")
    return json.loads(result.stdout.strip().splitlines()[-1])


def module_run(module_dir, args):
    """The Python module's summary for a `simulate` command (scene and ticks), with the portable
    pair tile; None when the module was not built. Run by the interpreter it was built for."""
    if not os.path.isdir(module_dir) or not any(f.startswith("softbody.") and f.endswith(".so") for f in os.listdir(module_dir)):
        return None
    interpreter = sys.executable
    if os.path.exists(os.path.join(module_dir, "interpreter")):
        with open(os.path.join(module_dir, "interpreter")) as f:
            interpreter = f.read().strip() or interpreter
    code = ("import json, sys, softbody\n"
            "world = softbody.World(sys.argv[1])\n"
            "world.step(int(sys.argv[2]))\n"
            "print(json.dumps({'ticks': world.ticks, 'status': world.status, 'state_hash': world.state_hash}))\n")
    env = dict(os.environ, SOFTBODY_KERNEL="portable", PYTHONPATH=os.path.abspath(module_dir))
    result = subprocess.run([interpreter, "-c", code, args["scene"], args["ticks"]], cwd=ROOT, env=env,
                            capture_output=True, text=True, timeout=600)
    if result.returncode != 0:
        raise Failure(f"module: the Python module's run failed ({result.returncode}): {result.stderr.strip()}")
    return json.loads(result.stdout.strip().splitlines()[-1])


def browser_run(browser, base, args):
    """Loads the page with args; returns (summary, console lines)."""
    url = base + "index.html?" + urllib.parse.urlencode(args)
    page = browser.open(url)

    def done(line):
        # The summary, or an error line of the app or the page (not the page's first line).
        return line.startswith("{") or (line.startswith("softbody: ") and not line.startswith("softbody: the "))

    line = page.wait_for_console(done, timeout=600)
    if not line.startswith("{"):
        raise Failure(f"{url}: {line}\n  " + "\n  ".join(page.console))
    return page, json.loads(line)


def press(page, key):
    code = ord(key.upper())
    for kind in ("keyDown", "keyUp"):
        page.call("Input.dispatchKeyEvent", {"type": kind, "key": key, "code": "Key" + key.upper(),
                                             "windowsVirtualKeyCode": code, "nativeVirtualKeyCode": code})


def drop_and_record(browser, base, downloads):
    """Drops a mesh onto the running page and records a second of it with the M key."""
    browser.call("Browser.setDownloadBehavior", {"behavior": "allow", "downloadPath": downloads})
    page = browser.open(base + "index.html?" + urllib.parse.urlencode(DROP_ARGS))
    deadline = time.monotonic() + 60
    while not page.evaluate("typeof Module === 'object' && !!Module.calledRun"):
        if time.monotonic() > deadline:
            raise Failure("drop_record: the app did not start:\n  " + "\n  ".join(page.console))
        browser.pump(0.2)
    with open(os.path.join(ROOT, "assets", "meshes", "cube.obj")) as f:
        cube = f.read()
    # What a browser does when a file is dropped: dragover, then drop with the file in it.
    page.evaluate("(() => { const data = new DataTransfer(); data.items.add(new File([%s], 'cube.obj'));"
                  " const canvas = document.getElementById('canvas');"
                  " for (const type of ['dragover', 'drop'])"
                  "   canvas.dispatchEvent(new DragEvent(type, {dataTransfer: data, bubbles: true, cancelable: true}));"
                  " })()" % json.dumps(cube))
    press(page, "m")
    time.sleep(1.0)
    press(page, "m")
    line = page.wait_for_console(lambda text: text.startswith("{"), timeout=300)
    web = json.loads(line)
    bodies = web.get("soft_bodies") or [{}]
    if len(bodies) != 1 or not bodies[0].get("mesh", "").endswith("/cube.obj") or bodies[0].get("particles") != 8:
        raise Failure(f"drop_record: the dropped cube did not become the soft body: {json.dumps(bodies)}")
    recording = web.get("recording") or {}
    if not recording.get("video") or recording.get("frames", 0) < 1:
        raise Failure(f"drop_record: the M key recorded nothing: {json.dumps(recording)}")
    deadline = time.monotonic() + 30
    name = os.path.basename(recording["path"])
    while not os.path.exists(os.path.join(downloads, name)):
        if time.monotonic() > deadline:
            raise Failure(f"drop_record: {name} was not downloaded: {os.listdir(downloads)}")
        browser.pump(0.5)
    with open(os.path.join(downloads, name), "rb") as f:
        head = f.read(4)
    if head != b"\x1a\x45\xdf\xa3":
        raise Failure(f"drop_record: {name} is not a WebM file (starts {head!r})")
    print(f"drop_record: ok, the dropped cube simulated ({web['particles']} particles), "
          f"{recording['frames']} frames recorded and downloaded as {name}", flush=True)


def pile(browser, isolated, options, case_start):
    """The issue's scripted run on the threaded build: its summary and its picture."""
    page, web = browser_run(browser, isolated, PILE_ARGS)
    if not any("the threaded build" in line for line in page.console):
        raise Failure("pile: the isolated page did not load the threaded build:\n  " + "\n  ".join(page.console))
    # The native run in a small window: the size changes no physics, and software GL draws
    # the default 1280x800 several times slower.
    compare_summaries("pile", web, native(options.softbody, {**PILE_ARGS, "size": "320x240"}), case_start)
    shot = os.path.join(options.work, "web_pile.png")
    page.screenshot(shot)
    if options.bless:
        shutil.copyfile(shot, REFERENCE)
        print(f"pile: blessed {os.path.relpath(REFERENCE, ROOT)} ({os.path.getsize(REFERENCE)} bytes)")
    else:
        result = subprocess.run([options.compare, shot, REFERENCE, "--name", "web_pile", "--failures",
                                 os.path.join(options.work, "failures"), *THRESHOLDS],
                                capture_output=True, text=True)
        print(result.stdout.strip(), flush=True)
        if result.returncode != 0:
            raise Failure("pile: the page's picture differs from its reference. If the new one is the "
                          "intended one, re-bless on purpose: python3 tests/web/browser_test.py --bless "
                          "(see tests/render/README.md)")


def compare_summaries(name, web, native_summary, since):
    if web.get("status") != "ok":
        raise Failure(f"{name}: the browser's run ended '{web.get('status')}': {web.get('error')}")
    different = [f for f in COMPARED_FIELDS if web.get(f) != native_summary.get(f)]
    if different:
        lines = [f"  {f}: browser {json.dumps(web.get(f))[:200]}, native {json.dumps(native_summary.get(f))[:200]}"
                 for f in different]
        raise Failure(f"{name}: the browser's summary differs from the native build's (SOFTBODY_KERNEL=portable):\n" +
                      "\n".join(lines) + "\n  (a C library function in the simulation's path? physics/portable_math.h)")
    print(f"{name}: ok, state_hash {web['state_hash']} after {web['ticks']} ticks, as the native build's "
          f"({time.monotonic() - since:.0f} s)", flush=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--site", default=os.path.join(ROOT, "build-web", "site"))
    parser.add_argument("--softbody", default=os.path.join(ROOT, "build", "app", "softbody"))
    parser.add_argument("--compare", default=os.path.join(ROOT, "build", "tests", "render", "softbody_image_compare"))
    parser.add_argument("--module", default=os.path.join(ROOT, "build", "app", "python"),
                        help="the built Python module's folder (its state hash is compared too)")
    parser.add_argument("--work", default=os.path.join(ROOT, "build-web", "tests"))
    parser.add_argument("--bless", action="store_true", help="write the pile's picture to its reference")
    parser.add_argument("--only", metavar="CASE[,CASE]", help="run these cases alone: " + ", ".join(ALL_CASES))
    options = parser.parse_args()
    # By default every case that checks something; "screenshots" (pages at three sizes for a
    # person to look at) runs when asked for.
    chosen = options.only.split(",") if options.only else [c for c in ALL_CASES if c != "screenshots"]
    unknown = [c for c in chosen if c not in ALL_CASES]
    if unknown:
        parser.error("no case " + ", ".join(unknown) + " (the cases: " + ", ".join(ALL_CASES) + ")")
    for path in (options.site, options.softbody, options.compare):
        if not os.path.exists(path):
            print(f"browser_test.py: {path} is missing (./dev.sh test builds it)", file=sys.stderr)
            return 2
    os.makedirs(options.work, exist_ok=True)

    start = time.monotonic()
    servers = []
    failures = []
    try:
        isolated_server, isolated = start_server(options.site, True)
        servers.append(isolated_server)
        plain_server, plain = start_server(options.site, False)
        servers.append(plain_server)
        with Chromium(*VIEW) as browser:
            # pile: the scripted run of the issue, its summary and its picture.
            if "pile" in chosen:
                try:
                    pile(browser, isolated, options, time.monotonic())
                except (Failure, BrowserError) as e:
                    failures.append(str(e))
                browser.close_pages()
            # threads and one_thread: the SIMD tile over several blocks, on each build.
            expected = native(options.softbody, MIXED_ARGS) if {"threads", "one_thread", "module"} & set(chosen) else None
            # module: the third runtime, against the same native summary as the two pages.
            case_start = time.monotonic()
            try:
                if "module" not in chosen:
                    raise Skip()
                module = module_run(options.module, MIXED_ARGS)
                if module is None:
                    print(f"module: skipped, the Python module was not built in {options.module} "
                          "(it needs pybind11-dev, python3-dev and python3-numpy)", flush=True)
                else:
                    different = [f for f in ("ticks", "status", "state_hash") if module[f] != expected.get(f)]
                    if different:
                        raise Failure("module: the Python module's run differs from the native build's: " +
                                      ", ".join(f"{f} {module[f]} against {expected.get(f)}" for f in different))
                    print(f"module: ok, state_hash {module['state_hash']} after {module['ticks']} ticks, as the native "
                          f"build's ({time.monotonic() - case_start:.0f} s)", flush=True)
            except Skip:
                pass
            except Failure as e:
                failures.append(str(e))
            for name, base, build in (("threads", isolated, "the threaded build"), ("one_thread", plain, "the one-thread build")):
                if name not in chosen:
                    continue
                case_start = time.monotonic()
                try:
                    page, web = browser_run(browser, base, MIXED_ARGS)
                    if not any(build in line for line in page.console):
                        raise Failure(f"{name}: the page did not load {build}:\n  " + "\n  ".join(page.console))
                    compare_summaries(name, web, expected, case_start)
                except (Failure, BrowserError) as e:
                    failures.append(str(e))
                browser.close_pages()
            try:
                if "drop_record" in chosen:
                    downloads = os.path.join(options.work, "downloads")
                    shutil.rmtree(downloads, ignore_errors=True)
                    os.makedirs(downloads)
                    drop_and_record(browser, isolated, downloads)
            except (Failure, BrowserError) as e:
                failures.append(str(e))
            browser.close_pages()
            # By touch, on a tablet and a phone, on the one-thread build (any static host's).
            for name in touch_cases.CASES:
                if name not in chosen:
                    continue
                case_start = time.monotonic()
                try:
                    touch_cases.run(name, browser, plain, options.work, options.softbody, native)
                    print(f"{name}: {time.monotonic() - case_start:.0f} s", flush=True)
                except (touch_cases.Failure, Failure, BrowserError) as e:
                    failures.append(str(e))
                browser.close_pages()
    except Failure as e:
        failures.append(str(e))
    finally:
        for server in servers:
            server.terminate()
            server.wait()
    for failure in failures:
        print("FAIL " + failure, file=sys.stderr)
    print(f"browser_test.py: {'FAILED' if failures else 'passed'} in {time.monotonic() - start:.0f} s", flush=True)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
