#!/usr/bin/env python3
"""`softbody bench` in headless Chromium: the browser build's timings, printed as the native
command prints them, to set beside `build/app/softbody bench` on the same machine.

    python3 tests/web/browser_bench.py [--build threads|single] [--kernel NAME] [--site DIR] -- BENCH ARGS

    python3 tests/web/browser_bench.py -- --sizes 1000,2500,5000 --no-meshes --no-bodies
    python3 tests/web/browser_bench.py --build single -- --sizes 2500 --no-search

--build threads serves the page cross-origin isolated (web/serve.py's headers), single without
them; --kernel sets SOFTBODY_KERNEL in the page (portable, simd128). The bench runs in the
page's main thread, as the demo does; headless Chromium compiles the WebAssembly with the
same optimising compiler as a visible one. Timings are the page's performance.now() (5 us
steps on an isolated page, 100 us on another). Not a test: nothing here can fail on speed.
"""
import argparse
import os
import sys
import time
import urllib.parse

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from browser_test import ROOT, start_server  # noqa: E402
from chromium import Chromium  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description="softbody bench in headless Chromium")
    parser.add_argument("--build", choices=("threads", "single"), default="threads")
    parser.add_argument("--kernel", help="SOFTBODY_KERNEL in the page")
    parser.add_argument("--site", default=os.path.join(ROOT, "build-web", "site"))
    parser.add_argument("--timeout", type=float, default=1800, help="seconds to wait for the bench")
    parser.add_argument("bench", nargs=argparse.REMAINDER, help="-- then softbody bench's options")
    options = parser.parse_args()
    bench = [a for a in options.bench if a != "--"] if options.bench[:1] == ["--"] else options.bench

    # The bench's options as the page reads them: --name value as name=value, a flag as name.
    query = [("command", "bench"), ("build", options.build)]
    if options.kernel:
        query.append(("kernel", options.kernel))
    i = 0
    while i < len(bench):
        name = bench[i][2:].replace("-", "_")
        if i + 1 < len(bench) and not bench[i + 1].startswith("--"):
            query.append((name, bench[i + 1]))
            i += 2
        else:
            query.append((name, ""))
            i += 1
    server, base = start_server(options.site, options.build == "threads")
    start = time.monotonic()
    try:
        with Chromium() as browser:
            page = browser.open(base + "index.html?" + urllib.parse.urlencode(query).replace("=&", "&").rstrip("="))
            shown = 0
            deadline = time.monotonic() + options.timeout
            # The bench prints its tables as it goes; it has finished when main() has returned.
            while time.monotonic() < deadline:
                browser.pump(1.0)
                for line in page.console[shown:]:
                    print(line, flush=True)
                shown = len(page.console)
                if page.evaluate("typeof Module === 'object' && Module.mainReturned === true"):
                    for line in page.console[shown:]:
                        print(line, flush=True)
                    break
                if page.exceptions:
                    print("the page threw: " + page.exceptions[0], file=sys.stderr)
                    return 1
    finally:
        server.terminate()
        server.wait()
    print(f"browser_bench.py: {time.monotonic() - start:.0f} s in headless Chromium ({options.build})", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
