"""Headless Chromium driven over its DevTools protocol, for the browser tests and benchmarks.

Chromium is started with --remote-debugging-pipe: it reads commands on file descriptor 3 and
writes answers and events on 4, as JSON messages ended by a NUL byte. No network port, no
third-party client: a page is loaded, its console lines are read as they come, and the page
is photographed when the caller has seen what it waited for.

    with Chromium(width=1024, height=640) as browser:
        page = browser.open("http://127.0.0.1:8080/index.html?scene=...")
        line = page.wait_for_console(lambda text: text.startswith("{"), timeout=120)
        page.screenshot("shot.png")

The flags are those that work headless on Debian 12's chromium package: WebGL2 on SwiftShader
(the CPU), no GPU, no sandbox (the tests run as any user, root included), a fresh profile in a
temporary folder, and nothing fetched from the network by the browser itself.
"""
import base64
import json
import os
import select
import shutil
import subprocess
import tempfile
import time


class BrowserError(RuntimeError):
    pass


# The page's events kept for the tests (the others are dropped): a file chooser the page opened.
WATCHED = {"Page.fileChooserOpened"}


def find_chromium():
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    raise BrowserError("no chromium on PATH (sudo apt install chromium)")


class Page:
    def __init__(self, browser, session, target):
        self.browser = browser
        self.session = session
        self.target = target
        self.console = []     # every console line so far, in order
        self.exceptions = []  # uncaught exceptions' descriptions
        self.events = []      # (method, params) of the events a test waits for (WATCHED)

    def call(self, method, params=None, timeout=60):
        return self.browser.call(method, params, session=self.session, timeout=timeout)

    def _take(self, message):
        method = message.get("method")
        params = message.get("params", {})
        if method == "Runtime.consoleAPICalled":
            parts = []
            for arg in params.get("args", []):
                parts.append(str(arg["value"]) if "value" in arg else arg.get("description", arg.get("type", "")))
            self.console.append(" ".join(parts))
        elif method in WATCHED:
            self.events.append((method, params))
        elif method == "Runtime.exceptionThrown":
            details = params.get("exceptionDetails", {})
            exception = details.get("exception", {})
            self.exceptions.append(exception.get("description") or details.get("text", "exception"))

    def wait_for_console(self, predicate, timeout):
        """The first console line (from the start) for which predicate(line) is true."""
        deadline = time.monotonic() + timeout
        seen = 0
        while True:
            for line in self.console[seen:]:
                if predicate(line):
                    return line
            seen = len(self.console)
            if self.exceptions:
                raise BrowserError("the page threw: " + self.exceptions[0])
            left = deadline - time.monotonic()
            if left <= 0:
                raise BrowserError(f"no such console line within {timeout} s; the page said:\n  " +
                                   "\n  ".join(self.console[-20:]))
            self.browser.pump(min(left, 1.0))

    def call_all(self, calls, timeout=60):
        """Several commands sent at once, as [(method, params)], their results in order: the
        browser gets each without waiting for the test to read the answer to the one before
        (a finger's touches come as fast as the page takes them)."""
        return self.browser.call_all(calls, session=self.session, timeout=timeout)

    def evaluate(self, expression, timeout=60):
        result = self.call("Runtime.evaluate", {"expression": expression, "returnByValue": True,
                                                "awaitPromise": True}, timeout=timeout)
        if "exceptionDetails" in result:
            raise BrowserError("evaluating " + expression + ": " + json.dumps(result["exceptionDetails"]))
        return result.get("result", {}).get("value")

    def screenshot(self, path):
        data = self.call("Page.captureScreenshot", {"format": "png"})["data"]
        with open(path, "wb") as f:
            f.write(base64.b64decode(data))


class Chromium:
    def __init__(self, width=1024, height=640, extra_args=()):
        self.width, self.height = width, height
        self.profile = tempfile.mkdtemp(prefix="softbody-chromium-")
        to_browser_r, self._to_browser = os.pipe()
        self._from_browser, from_browser_w = os.pipe()
        args = [find_chromium(), "--headless=new", "--no-sandbox", "--use-angle=swiftshader",
                "--enable-unsafe-swiftshader", "--disable-gpu", "--disable-quic", "--no-first-run",
                "--disable-background-networking", "--disable-component-update", "--disable-sync",
                "--disable-extensions", "--mute-audio", "--hide-scrollbars",
                f"--window-size={width},{height}", f"--user-data-dir={self.profile}",
                "--remote-debugging-pipe", *extra_args, "about:blank"]

        def plumb():  # in the child: the protocol's two pipes on descriptors 3 and 4, inherited
            read_end, write_end = os.dup(to_browser_r), os.dup(from_browser_w)  # out of the way of 3 and 4
            os.dup2(read_end, 3, inheritable=True)
            os.dup2(write_end, 4, inheritable=True)

        self.log = tempfile.TemporaryFile()
        self.process = subprocess.Popen(args, stdin=subprocess.DEVNULL, stdout=self.log, stderr=self.log,
                                        preexec_fn=plumb, close_fds=False)
        os.close(to_browser_r)
        os.close(from_browser_w)
        self._buffer = b""
        self._next_id = 0
        self._answers = {}
        self.pages = {}

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self):
        if self.process.poll() is None:
            try:
                self.call("Browser.close", timeout=10)
            except BrowserError:
                pass
            try:
                self.process.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        for fd in (self._to_browser, self._from_browser):
            try:
                os.close(fd)
            except OSError:
                pass
        shutil.rmtree(self.profile, ignore_errors=True)

    def close_pages(self):
        """Closes every tab opened so far. A headless tab is never hidden: one left open goes on
        drawing its frames (on the CPU, SwiftShader's) and slows every case after it."""
        for page in list(self.pages.values()):
            self.call("Target.closeTarget", {"targetId": page.target})
        self.pages.clear()

    def browser_log(self):
        self.log.seek(0)
        return self.log.read().decode(errors="replace")

    def _send(self, message):
        data = json.dumps(message).encode() + b"\0"
        while data:
            written = os.write(self._to_browser, data)
            data = data[written:]

    def pump(self, timeout):
        """Reads what the browser has sent within `timeout` seconds and dispatches it."""
        ready, _, _ = select.select([self._from_browser], [], [], timeout)
        if not ready:
            if self.process.poll() is not None:
                raise BrowserError(f"chromium exited ({self.process.returncode}):\n" + self.browser_log()[-3000:])
            return
        chunk = os.read(self._from_browser, 1 << 20)
        if not chunk:
            raise BrowserError("chromium closed its protocol pipe:\n" + self.browser_log()[-3000:])
        self._buffer += chunk
        while b"\0" in self._buffer:
            raw, self._buffer = self._buffer.split(b"\0", 1)
            message = json.loads(raw)
            if "id" in message:
                self._answers[message["id"]] = message
            elif message.get("sessionId") in self.pages:
                self.pages[message["sessionId"]]._take(message)

    def call(self, method, params=None, session=None, timeout=60):
        self._next_id += 1
        ident = self._next_id
        message = {"id": ident, "method": method, "params": params or {}}
        if session:
            message["sessionId"] = session
        self._send(message)
        deadline = time.monotonic() + timeout
        while ident not in self._answers:
            left = deadline - time.monotonic()
            if left <= 0:
                raise BrowserError(f"{method}: no answer within {timeout} s")
            self.pump(min(left, 1.0))
        answer = self._answers.pop(ident)
        if "error" in answer:
            raise BrowserError(f"{method}: {answer['error'].get('message')}")
        return answer.get("result", {})

    def call_all(self, calls, session=None, timeout=60):
        idents = []
        for method, params in calls:
            self._next_id += 1
            message = {"id": self._next_id, "method": method, "params": params or {}}
            if session:
                message["sessionId"] = session
            self._send(message)
            idents.append((self._next_id, method))
        deadline = time.monotonic() + timeout
        results = []
        for ident, method in idents:
            while ident not in self._answers:
                left = deadline - time.monotonic()
                if left <= 0:
                    raise BrowserError(f"{method}: no answer within {timeout} s")
                self.pump(min(left, 1.0))
            answer = self._answers.pop(ident)
            if "error" in answer:
                raise BrowserError(f"{method}: {answer['error'].get('message')}")
            results.append(answer.get("result", {}))
        return results

    def open(self, url, device=None):
        """A new tab at the browser's size, its console and exceptions watched, loading url.

        device: a tablet or phone to emulate instead, {"width", "height", "scale", "mobile"} (CSS
        pixels, device pixels per CSS pixel): that screen, with a touch screen (the page gets touch
        events, and Input.dispatchTouchEvent drives it); with "fullscreen" true, a page as large as
        the screen (a projector's laptop in fullscreen or kiosk mode)."""
        target = self.call("Target.createTarget", {"url": "about:blank"})["targetId"]
        session = self.call("Target.attachToTarget", {"targetId": target, "flatten": True})["sessionId"]
        page = Page(self, session, target)
        self.pages[session] = page
        if device:
            metrics = {"width": device["width"], "height": device["height"], "deviceScaleFactor": device["scale"],
                       "mobile": device.get("mobile", True)}
            if device.get("fullscreen"):
                metrics.update(screenWidth=device["width"], screenHeight=device["height"])
            page.call("Emulation.setDeviceMetricsOverride", metrics)
            page.call("Emulation.setTouchEmulationEnabled", {"enabled": True, "maxTouchPoints": 5})
        else:
            page.call("Emulation.setDeviceMetricsOverride", {"width": self.width, "height": self.height,
                                                             "deviceScaleFactor": 1, "mobile": False})
        page.call("Runtime.enable")
        page.call("Page.enable")
        page.call("Page.navigate", {"url": url})
        return page
