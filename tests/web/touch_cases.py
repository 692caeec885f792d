"""The page on a tablet and a phone, used by touch as a class uses it (browser_test.py runs
these cases): headless Chromium emulates the screen (its size and pixel density) and a touch
screen, and the test's fingers are Input.dispatchTouchEvent's. What the app shows is read from
the page's own answer, softbodyState() (app/gui/app_shell.h, state_json): the bodies and where
they are drawn, the camera, the canvas, the panel's items by label and where they are.

Positions: the state gives the canvas's pixels; a finger lands in CSS pixels (the canvas's
pixels over the device's pixel ratio; the canvas starts at the page's corner).
"""
import json
import os
import subprocess
import time
import urllib.parse

from chromium import BrowserError

DESKTOP = {"width": 1280, "height": 800, "scale": 1, "mobile": False}
TABLET = {"width": 1024, "height": 768, "scale": 2, "mobile": True}
PHONE = {"width": 390, "height": 844, "scale": 2, "mobile": True}
LAPTOP_TOUCH = {"width": 800, "height": 600, "scale": 1, "mobile": False}
# A projector's laptop in fullscreen: the page as large as the screen, 1600x900.
FULLSCREEN = {"width": 1600, "height": 900, "scale": 1, "mobile": False, "fullscreen": True}
SMALL = {"width": 480, "height": 360, "scale": 1, "mobile": True}  # quick to draw, where the size does not matter
DEFAULT_SCENE = {"scene": "assets/scenes/default.json"}
# The default ball at rest on the ground from the start (not thrown, not dropped): where it is
# drawn does not change between the test's look and its finger.
BALL_AT_REST = {"scene": "assets/scenes/default.json", "set": ["body.initial_velocity=0,0,0", "body.init_height=0.5"]}


class Failure(Exception):
    pass


# --- Driving the page ----------------------------------------------------------------------------

def state(page):
    return page.evaluate("window.softbodyState ? softbodyState() : null")


def wait_state(page, predicate, what, timeout=60):
    """The first state for which predicate(state) holds, read as the page draws its frames."""
    deadline = time.monotonic() + timeout
    last = None
    while True:
        last = state(page)
        if last and last.get("frame") is not None and predicate(last):
            return last
        if page.exceptions:
            raise Failure(f"{what}: the page threw: {page.exceptions[0]}")
        if time.monotonic() > deadline:
            shown = {k: last.get(k) for k in ("frame", "paused", "grabbing", "camera", "panel", "notice", "error")} if last else None
            raise Failure(f"{what}: not within {timeout} s; the app showed {json.dumps(shown)}; the page said:\n  " +
                          "\n  ".join(page.console[-10:]))
        page.browser.pump(0.05)


def frames_later(page, count, what):
    """The state `count` frames from now (the app's gestures and the panel take a frame each)."""
    start = state(page)["frame"]
    return wait_state(page, lambda s: s["frame"] >= start + count, what)


def open_app(browser, base, args, device, what):
    return open_url(browser, base + "index.html?" + urllib.parse.urlencode(args, doseq=True), device, what)


def open_url(browser, url, device, what):
    page = browser.open(url, device=device)
    page.call("Emulation.setFocusEmulationEnabled", {"enabled": True})  # the clipboard wants a focused page
    wait_state(page, lambda s: s["frame"] >= 3 and s.get("ui"), what + ": the app did not start", timeout=120)
    return page


def ratio(s):
    return s["ui_scale"]


def touch_event(kind, points=()):
    """points: (x, y) in CSS pixels, one per finger, ids 0, 1, ... (touchEnd: none)."""
    return ("Input.dispatchTouchEvent", {
        "type": kind,
        "touchPoints": [{"x": x, "y": y, "id": i, "radiusX": 4, "radiusY": 4, "force": 1} for i, (x, y) in enumerate(points)],
    })


def finger(page, kind, points=()):
    page.call(*touch_event(kind, points))


# A gesture's touches are sent at once (Page.call_all): each waits in the browser for the page
# to take the one before, not for the test to hear back. On a slow page (SwiftShader draws the
# tests' frames, a second each on a busy machine) a finger that paused a whole frame between
# its touches would be a long press.

def tap(page, x, y):
    page.call_all([touch_event("touchStart", [(x, y)]), touch_event("touchEnd")])


def glide(page, start, end, steps, what):
    """Fingers from `start` to `end` (lists of (x, y), one per finger) in `steps` moves, then a
    frame or two for the app to act; not lifted."""
    moves = [touch_event("touchStart", start)]
    for step in range(1, steps + 1):
        t = step / steps
        moves.append(touch_event("touchMove", [(a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t) for a, b in zip(start, end)]))
    page.call_all(moves)
    return frames_later(page, 2, what)


def find_item(s, label, window="softbody", prefix=False):
    for item in s.get("ui") or []:
        if (item["label"].startswith(label) if prefix else item["label"] == label) and item["window"] == window:
            return item
    raise Failure(f"no '{label}' in the panel's items: " + ", ".join(sorted({i["label"] for i in s.get("ui") or []})))


def item_centre(s, item):
    """Where a finger taps an item, in CSS pixels; it must be on the canvas."""
    x, y = item["x"] + 0.5 * item["w"], item["y"] + 0.5 * item["h"]
    if not (0 <= x < s["canvas"]["width"] and 0 <= y < s["canvas"]["height"]):
        raise Failure(f"'{item['label']}' is off the screen at ({x:.0f}, {y:.0f})")
    return x / ratio(s), y / ratio(s)


def tap_item(page, label, what, window="softbody", prefix=False):
    s = state(page)
    x, y = item_centre(s, find_item(s, label, window, prefix))
    tap(page, x, y)
    return frames_later(page, 4, what)  # seen, pressed, released: a frame each, then acted on


def scroll_to(page, label, what, tries=12, up=True):
    """Scrolls the panel by a finger's swipes on it (upward: further down the panel) until
    `label` is on the screen."""
    for _ in range(tries):
        s = state(page)
        # Below the panel's title bar (an item scrolled under it is covered: a tap there folds
        # the panel), and above the bottom of the screen.
        top = 0
        for item in s.get("ui") or []:
            if item["label"] == "#COLLAPSE" and item["window"] == "softbody":
                top = item["y"] + item["h"]
        try:
            item = find_item(s, label)
            if item["y"] >= top and item["y"] + item["h"] < s["canvas"]["height"]:
                return s
        except Failure:
            pass
        x = 0.5 * s["panel"]["width"] / ratio(s)
        height = s["canvas"]["height"] / ratio(s)
        ends = [(x, 0.8 * height)], [(x, 0.35 * height)]
        glide(page, *(ends if up else ends[::-1]), 5, what)
        finger(page, "touchEnd")
        frames_later(page, 2, what)
    s = state(page)
    shown = [i["label"] for i in s.get("ui") or [] if i["window"] == "softbody" and 0 <= i["y"] < s["canvas"]["height"]]
    raise Failure(f"{what}: swiping {'up' if up else 'down'} the panel did not bring '{label}' on the screen "
                  f"(on it: {', '.join(shown)})")


def view_centre(s):
    """The middle of the view right of the panel, in CSS pixels."""
    left = s["panel"]["width"]
    return (left + 0.5 * (s["canvas"]["width"] - left)) / ratio(s), 0.5 * s["canvas"]["height"] / ratio(s)


def check_canvas(page, s, device, what):
    """The canvas covers the page and has a pixel for each of the screen's."""
    css = page.evaluate("(() => { const c = document.getElementById('canvas'); const r = c.getBoundingClientRect();"
                        " return [r.width, r.height, c.width, c.height, window.devicePixelRatio]; })()")
    width, height, pixels_x, pixels_y, dpr = css
    if (round(width), round(height)) != (device["width"], device["height"]):
        raise Failure(f"{what}: the canvas is {width}x{height} CSS pixels on a {device['width']}x{device['height']} screen")
    if dpr != device["scale"] or (pixels_x, pixels_y) != (round(width * dpr), round(height * dpr)):
        raise Failure(f"{what}: the canvas has {pixels_x}x{pixels_y} pixels for {width}x{height} CSS pixels at ratio {dpr}")
    if (s["canvas"]["width"], s["canvas"]["height"]) != (pixels_x, pixels_y) or s["ui_scale"] != dpr:
        raise Failure(f"{what}: the app draws at {s['canvas']} with UI scale {s['ui_scale']}, the canvas has "
                      f"{pixels_x}x{pixels_y} at ratio {dpr}")
    return f"canvas {pixels_x}x{pixels_y} for {width:.0f}x{height:.0f} CSS px at ratio {dpr:g}"


# --- The cases -----------------------------------------------------------------------------------

def tablet(browser, base, work):
    """On a tablet: the canvas at the density, rows for fingers, a finger drags the ball, the
    panel's buttons answer taps, a long press inspects, a pinch zooms, two fingers pan, one
    orbits."""
    what = "tablet"
    page = open_app(browser, base, BALL_AT_REST, TABLET, what)
    s = state(page)
    notes = [check_canvas(page, s, TABLET, what)]
    # On a touch screen the panel's rows are for fingers: a button at least 36 CSS px tall
    # (a mouse's are 20).
    pause = find_item(s, "Pause")
    if pause["h"] / ratio(s) < 36:
        raise Failure(f"{what}: the Pause button is {pause['h'] / ratio(s):.0f} CSS px tall on a touch screen (36 at least)")
    notes.append(f"Pause {pause['h'] / ratio(s):.0f} CSS px tall")

    # One finger on the ball drags it up: the particle under the finger follows it, and the
    # ball's centre rises.
    ball = s["bodies"][0]
    x, y = ball["screen"][0] / ratio(s), ball["screen"][1] / ratio(s)
    height = ball["position"][2]
    glide(page, [(x, y)], [(x, y - 120)], 6, what + ": drag")
    held = frames_later(page, 4, what + ": drag")
    finger(page, "touchEnd")
    lifted = held["bodies"][0]["position"][2] - height
    if not held["grabbing"] or lifted < 0.01:
        raise Failure(f"{what}: a finger on the ball did not drag it up (grabbing {held['grabbing']}, "
                      f"its centre rose {lifted:.3f} m)")
    s = frames_later(page, 2, what)
    if s["grabbing"]:
        raise Failure(f"{what}: the ball is still held after the finger lifted")
    notes.append(f"drag lifted the ball's centre {lifted:.3f} m")

    # The panel's buttons: Pause stops the ticks, Reset takes the world back to tick 0.
    s = tap_item(page, "Pause", what + ": Pause")
    ticks = s["ticks"]
    s = frames_later(page, 3, what + ": paused")
    if not s["paused"] or s["ticks"] != ticks:
        raise Failure(f"{what}: tapping Pause did not pause (paused {s['paused']}, ticks {ticks} then {s['ticks']})")
    # A long press on the (paused) ball: the inspector. (The camera still catches up with the
    # ball after the drag: the finger goes where the ball stays drawn.)
    s = state(page)
    for _ in range(12):
        later = frames_later(page, 1, what + ": the view settles")
        a, b = s["bodies"][0]["screen"], later["bodies"][0]["screen"]
        s = later
        if abs(a[0] - b[0]) + abs(a[1] - b[1]) < 2:
            break
    ball = s["bodies"][0]
    finger(page, "touchStart", [(ball["screen"][0] / ratio(s), ball["screen"][1] / ratio(s))])
    time.sleep(0.8)
    s = frames_later(page, 2, what + ": long press")
    finger(page, "touchEnd")
    if not s["inspecting"] or s["grabbing"]:
        raise Failure(f"{what}: a long press on the ball did not inspect it (inspecting {s['inspecting']}, grabbing {s['grabbing']})")
    notes.append("long press inspects")
    s = tap_item(page, "Reset", what + ": Reset")
    if s["ticks"] != 0:
        raise Failure(f"{what}: tapping Reset left the world at tick {s['ticks']}")
    notes.append(f"Pause stopped at tick {ticks}, Reset went to tick 0")

    # One finger on the sky turns the view (before the pinch brings the ball close: a finger on
    # the ball grabs it); two fingers spread apart: closer; moved together: the view slides.
    s = state(page)
    cx, cy = view_centre(s)
    before = s["camera"]
    sky = (cx, 0.12 * s["canvas"]["height"] / ratio(s))
    glide(page, [sky], [(sky[0] + 120, sky[1])], 4, what + ": orbit")
    finger(page, "touchEnd")
    s = frames_later(page, 2, what + ": orbit")
    if abs(s["camera"]["yaw"] - before["yaw"]) < 0.1:
        raise Failure(f"{what}: one finger on the sky did not turn the view (yaw {before['yaw']:.3f} to {s['camera']['yaw']:.3f})")
    notes.append(f"orbit turned {s['camera']['yaw'] - before['yaw']:+.2f} rad")
    before = s["camera"]
    glide(page, [(cx - 40, cy), (cx + 40, cy)], [(cx - 120, cy), (cx + 120, cy)], 6, what + ": pinch")
    finger(page, "touchEnd")
    s = frames_later(page, 2, what + ": pinch")
    zoom = s["camera"]["distance"] / before["distance"]
    if not 0.2 < zoom < 0.5:  # three times as far apart: a third as far away
        raise Failure(f"{what}: a pinch from 80 to 240 px took the camera from {before['distance']:.3f} to "
                      f"{s['camera']['distance']:.3f} m")
    notes.append(f"pinch 3x: distance x{zoom:.2f}")
    before = s["camera"]
    glide(page, [(cx - 60, cy), (cx + 60, cy)], [(cx - 60, cy + 80), (cx + 60, cy + 80)], 4, what + ": pan")
    finger(page, "touchEnd")
    s = frames_later(page, 2, what + ": pan")
    moved = sum((a - b) ** 2 for a, b in zip(s["camera"]["target"], before["target"])) ** 0.5
    if moved < 1e-3 or abs(s["camera"]["distance"] - before["distance"]) > 1e-3 * before["distance"]:
        raise Failure(f"{what}: two fingers moved together did not pan (target moved {moved:.4f} m, distance "
                      f"{before['distance']:.3f} to {s['camera']['distance']:.3f})")
    notes.append(f"pan moved the target {moved:.2f} m")

    page.screenshot(os.path.join(work, "touch_tablet.png"))
    print(f"{what}: ok, " + "; ".join(notes), flush=True)


def phone(browser, base, work):
    """On a phone held upright: the panel starts folded, a tap on its arrow unfolds it across the
    screen, and its buttons answer taps there."""
    what = "phone"
    page = open_app(browser, base, DEFAULT_SCENE, PHONE, what)
    s = state(page)
    notes = [check_canvas(page, s, PHONE, what)]
    if s["panel"]["width"] != 0:
        raise Failure(f"{what}: the panel does not start folded on a phone (it covers {s['panel']['width']} px)")
    page.screenshot(os.path.join(work, "touch_phone_folded.png"))
    s = tap_item(page, "#COLLAPSE", what + ": unfold")
    if s["panel"]["width"] < 0.8 * s["canvas"]["width"]:
        raise Failure(f"{what}: tapping the panel's arrow did not unfold it across the screen (width {s['panel']['width']})")
    s = tap_item(page, "Pause", what + ": Pause")
    if not s["paused"]:
        raise Failure(f"{what}: tapping Pause in the unfolded panel did not pause")
    page.screenshot(os.path.join(work, "touch_phone_panel.png"))
    print(f"{what}: ok, " + notes[0] + "; the panel unfolds by a tap and Pause pauses", flush=True)


def fullscreen(browser, base, work):
    """A page as large as the screen (fullscreen, a kiosk, a projector): the canvas takes the
    screen's pixels and the picture keeps its shape: the spring lesson's ball is as wide as it is
    tall on the screen, not an egg."""
    what = "fullscreen"
    page = open_app(browser, base, {"lesson": "1"}, FULLSCREEN, what)
    s = frames_later(page, 3, what)
    notes = [check_canvas(page, s, FULLSCREEN, what)]
    ball = next(b for b in s["bodies"] if b["name"] == "bob")
    centre, right, up = ball["screen"], ball["screen_right"], ball["screen_up"]
    across = ((right[0] - centre[0]) ** 2 + (right[1] - centre[1]) ** 2) ** 0.5
    upward = ((up[0] - centre[0]) ** 2 + (up[1] - centre[1]) ** 2) ** 0.5
    if not across > 2 or abs(across / upward - 1) > 0.02:
        raise Failure(f"{what}: the ball is drawn {2 * across:.1f} px wide and {2 * upward:.1f} px tall on a screen-sized page")
    page.screenshot(os.path.join(work, "fullscreen.png"))
    print(f"{what}: ok, " + notes[0] + f"; the ball {2 * across:.1f} px wide and {2 * upward:.1f} px tall", flush=True)


def copy_link(browser, base, work, softbody, native):
    """A slider dragged by a finger changes a key; Share > Copy link puts on the clipboard an
    address that opens the same setup: the same scene and keys, and after 60 frames the native
    build's state hash for the same command line."""
    what = "copy_link"
    origin = base.rstrip("/")
    browser.call("Browser.grantPermissions", {"origin": origin, "permissions": ["clipboardReadWrite", "clipboardSanitizedWrite"]})
    start = {"scene": "assets/scenes/default.json", "set": "body.damping=0.1"}
    page = open_app(browser, base, start, LAPTOP_TOUCH, what)  # a touch screen at ratio 1: quick to draw
    tap_item(page, "Simulation", what + ": fold Simulation")  # room for All keys below it
    scroll_to(page, "All keys", what + ": swipe to All keys")
    tap_item(page, "All keys", what + ": open All keys")
    s = scroll_to(page, "dt", what + ": swipe to the dt slider")
    slider = find_item(s, "dt")  # a key's slider is listed by its key (its words stand above it)
    x, y = item_centre(s, slider)
    glide(page, [(x, y)], [(x + 40, y)], 4, what + ": slider")
    finger(page, "touchEnd")
    s = frames_later(page, 4, what + ": slider")
    keys = dict(s["changed_keys"]["keys"])
    if "dt" not in keys:
        raise Failure(f"{what}: dragging the dt slider changed no key: {s['changed_keys']}")
    scroll_to(page, "Share", what + ": swipe back to Share", up=False)
    tap_item(page, "Share", what + ": open Share")
    scroll_to(page, "Copy link", what + ": swipe to Copy link")  # rows for fingers: it may be below
    s = tap_item(page, "Copy link", what + ": Copy link")
    link = None
    deadline = time.monotonic() + 10
    while not link:
        link = page.evaluate("navigator.clipboard.readText()")
        if time.monotonic() > deadline:
            raise Failure(f"{what}: nothing on the clipboard after Copy link (notice '{s['notice']}', error '{s['error']}')")
    query = urllib.parse.urlsplit(link).query
    if query != s["setup"]["query"] or not link.startswith(base + "index.html?"):
        raise Failure(f"{what}: the clipboard has {link}, the app's setup is {s['setup']['query']}")
    pairs = urllib.parse.parse_qsl(query)
    if ("set", "body.damping=0.1") not in pairs or ("set", f"dt={keys['dt']}") not in pairs:
        raise Failure(f"{what}: the link {link} lacks the start's key or the slider's")

    # The link in a new page: the same setup (its own link is the same).
    opened = open_url(browser, link, SMALL, what + ": the link")
    again = state(opened)
    if again["setup"]["query"] != query or again["source"] != s["source"]:
        raise Failure(f"{what}: the link opened {again['source']} with setup {again['setup']['query']}, "
                      f"not {s['source']} with {query}")
    # And the same world: 60 fixed frames give the native build's state hash.
    fixed = pairs + [("frames", "60"), ("frame_time", "0.02"), ("size", "320x240")]  # (the size changes no physics)
    summary_page = browser.open(link + "&frames=60&frame_time=0.02&size=320x240")
    line = summary_page.wait_for_console(lambda text: text.startswith("{"), timeout=300)
    web = json.loads(line)
    expected = native(softbody, fixed)
    if web.get("state_hash") != expected.get("state_hash") or web.get("ticks") != expected.get("ticks"):
        raise Failure(f"{what}: the link's run ends at hash {web.get('state_hash')} after {web.get('ticks')} ticks, the "
                      f"native build's at {expected.get('state_hash')} after {expected.get('ticks')}")
    print(f"{what}: ok, {link} opens the same setup; after 60 frames state_hash {web['state_hash']}, "
          "as the native build's", flush=True)


def presets(browser, base, work, softbody):
    """Share > Download preset: a scene file in the downloads folder that the native build loads;
    Share > Upload: the file chooser takes it back and the page opens it; swipes scroll the panel
    down to Presets, and a preset saved there is still there in the next page of the site (the
    browser's storage)."""
    what = "presets"
    downloads = os.path.join(work, "preset_downloads")
    os.makedirs(downloads, exist_ok=True)
    for name in os.listdir(downloads):
        os.remove(os.path.join(downloads, name))
    browser.call("Browser.setDownloadBehavior", {"behavior": "allow", "downloadPath": downloads})
    # A touch screen at ratio 1, quick to draw: a file chooser opens only within a few seconds
    # of the tap that asked for it, which a tablet's frames on a busy test machine can outlast.
    page = open_app(browser, base, {"scene": "assets/scenes/pile.json", "set": "gravity=0,0,-3.7"}, LAPTOP_TOUCH, what)
    tap_item(page, "Share", what + ": open Share")
    scroll_to(page, "Download preset", what + ": swipe to Download preset")
    tap_item(page, "Download preset", what + ": Download preset")
    path = os.path.join(downloads, "pile.json")
    deadline = time.monotonic() + 20
    while not os.path.exists(path):
        if time.monotonic() > deadline:
            raise Failure(f"{what}: no pile.json downloaded: {os.listdir(downloads)}")
        browser.pump(0.2)
    with open(path) as f:
        scene = json.load(f)
    gravity = (scene.get("world") or {}).get("gravity")
    if not scene.get("rigid_bodies") or gravity != [0, 0, -3.7]:
        raise Failure(f"{what}: the downloaded preset is not the scene shown (gravity {gravity}, "
                      f"{len(scene.get('rigid_bodies') or [])} rigid bodies)")
    check = subprocess.run([softbody, "simulate", "--scene", path, "--ticks", "5"], capture_output=True, text=True, timeout=120)
    if check.returncode != 0:
        raise Failure(f"{what}: the native build does not load the downloaded preset: {check.stderr.strip()}")

    # Upload it back (the page's file chooser, answered by the test).
    page.call("Page.setInterceptFileChooserDialog", {"enabled": True})
    loads = state(page)["loads"]
    scroll_to(page, "Upload", what + ": swipe to Upload")
    tap_item(page, "Upload", what + ": Upload")
    deadline = time.monotonic() + 10
    while not any(method == "Page.fileChooserOpened" for method, _ in page.events):
        if time.monotonic() > deadline:
            raise Failure(f"{what}: tapping Upload opened no file chooser")
        browser.pump(0.2)
    chooser = next(params for method, params in page.events if method == "Page.fileChooserOpened")
    page.call("DOM.setFileInputFiles", {"files": [os.path.abspath(path)], "backendNodeId": chooser["backendNodeId"]})
    s = wait_state(page, lambda s: s["loads"] > loads, what + ": the uploaded preset did not open", timeout=30)
    if not s["source"].endswith("/pile.json") or s["error"]:
        raise Failure(f"{what}: the upload opened '{s['source']}' (error '{s['error']}')")

    # Saved in the page, kept by the browser: there in the next page of the site.
    scroll_to(page, "Presets", what + ": swipe to Presets")
    tap_item(page, "Presets", what + ": open Presets")
    scroll_to(page, "Save", what + ": swipe to Save")
    s = tap_item(page, "Save", what + ": Save")
    if "my_scene.json" not in " ".join(s["presets"]):
        raise Failure(f"{what}: Presets > Save saved nothing: {s['presets']} (notice '{s['notice']}', error '{s['error']}')")
    frames_later(page, 40, what + ": stored")  # the page stores the folder within 30 frames of a change
    time.sleep(0.5)
    s = state(open_app(browser, base, DEFAULT_SCENE, SMALL, what + ": the next page"))
    if "my_scene.json" not in " ".join(s["presets"]):
        raise Failure(f"{what}: the saved preset is gone in the next page of the site: {s['presets']}")
    print(f"{what}: ok, downloaded pile.json (gravity {gravity}, loads natively), uploaded it back, "
          "and a saved preset is there in the next page", flush=True)


def screenshots(browser, base, work):
    """The page at a desktop's, a tablet's and a phone's size, for a person to look at."""
    names = []
    for name, device in (("desktop", DESKTOP), ("tablet", TABLET), ("phone", PHONE)):
        page = open_app(browser, base, {"lesson": "1"}, device, "screenshot " + name)
        frames_later(page, 20, "screenshot " + name)
        shot = os.path.join(work, f"page_{name}.png")
        page.screenshot(shot)
        names.append(os.path.basename(shot))
    print("screenshots: " + ", ".join(names) + " in " + work, flush=True)


CASES = ("tablet", "phone", "fullscreen", "copy_link", "presets", "screenshots")


def run(name, browser, base, work, softbody, native):
    try:
        if name == "tablet":
            tablet(browser, base, work)
        elif name == "phone":
            phone(browser, base, work)
        elif name == "fullscreen":
            fullscreen(browser, base, work)
        elif name == "copy_link":
            copy_link(browser, base, work, softbody, native)
        elif name == "presets":
            presets(browser, base, work, softbody)
        elif name == "screenshots":
            screenshots(browser, base, work)
    except BrowserError as e:
        raise Failure(f"{name}: {e}")
