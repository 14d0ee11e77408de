"""Debian's Chromium, headless, driven over the DevTools protocol (websocket-client): load a page, evaluate
JavaScript in it, click and type as a person does (mouse and key events at an element's place), log in as the
teacher through the web view's form, resize it to a phone's screen, take screenshots, and read what its profile
kept of the addresses it visited (its History database). Every wait has a deadline and names what it waited
for."""
import base64
import json
import os
import shutil
import signal
import sqlite3
import subprocess
import tempfile
import time
import urllib.request
from typing import Any, Dict, List, NamedTuple, Optional

import websocket

CHROMIUM_FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                  "--disable-background-networking", "--disable-component-update", "--disable-sync",
                  "--hide-scrollbars", "--remote-debugging-address=127.0.0.1", "--remote-debugging-port=0"]


def end(process: "subprocess.Popen[Any]", sig: int, timeout: float) -> None:
    """Asks a process to end with `sig`, and kills it if it has not after `timeout` seconds."""
    process.send_signal(sig)
    try:
        process.wait(timeout=timeout)
    except subprocess.TimeoutExpired:
        process.kill()
        process.wait()


def chromium_binary() -> str:
    for name in ("chromium", "chromium-browser"):
        found = shutil.which(name)
        if found:
            return found
    raise FileNotFoundError("no chromium on PATH (scripts/install-deps test installs Debian's)")


class History(NamedTuple):
    """What a profile's History database holds: the addresses of its `urls` table, and the bytes of its files
    (the database and any journal: every table, and what SQLite has not overwritten yet)."""
    urls: List[str]
    raw: bytes


class Browser:
    def __init__(self, width: int, height: int) -> None:
        self.profile = tempfile.mkdtemp(prefix="rbs_chromium_")
        self.process = subprocess.Popen(
            [chromium_binary(), *CHROMIUM_FLAGS, f"--user-data-dir={self.profile}", f"--window-size={width},{height}",
             "about:blank"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        port_file = os.path.join(self.profile, "DevToolsActivePort")
        deadline = time.monotonic() + 60
        while not self.port_written(port_file):
            if self.process.poll() is not None or time.monotonic() > deadline:
                ended = self.process.poll() is not None
                raise RuntimeError("chromium ended before it opened its DevTools port" if ended
                                   else "chromium: no DevTools port in 60 s")
            time.sleep(0.05)
        with open(port_file) as written:
            port = int(written.read().split("\n")[0])
        with urllib.request.urlopen(f"http://127.0.0.1:{port}/json/list", timeout=10) as answer:
            targets = json.load(answer)
        page = next(t for t in targets if t["type"] == "page")
        self.socket = websocket.create_connection(page["webSocketDebuggerUrl"], timeout=30, suppress_origin=True)
        self.next_id = 0
        self.events: List[Dict[str, Any]] = []
        self.call("Page.enable")
        self.call("Runtime.enable")

    @staticmethod
    def port_written(path: str) -> bool:
        """Chromium writes its port, a newline and its browser target's path."""
        if not os.path.exists(path):
            return False
        with open(path) as written:
            return written.read().count("\n") >= 1

    def close(self) -> None:
        try:
            self.socket.close()
        finally:
            end(self.process, signal.SIGTERM, 20)
            shutil.rmtree(self.profile, ignore_errors=True)

    def quit(self, timeout: float) -> None:
        """Ends Chromium as its window's close does (Browser.close: it writes its profile's databases first),
        the profile kept (close removes it)."""
        with open(os.path.join(self.profile, "DevToolsActivePort")) as written:
            port, path = written.read().split("\n")[:2]
        self.socket.close()
        browser = websocket.create_connection(f"ws://127.0.0.1:{port}{path.strip()}", timeout=timeout,
                                              suppress_origin=True)
        try:
            browser.send(json.dumps({"id": 1, "method": "Browser.close"}))
            self.process.wait(timeout=timeout)
        finally:
            browser.close()

    def history(self) -> Optional[History]:
        """The profile's History database, read from a copy (Chromium locks it while it runs); None where this
        Chromium keeps none (its old headless mode, Debian 11's: it records no visit)."""
        folder = os.path.join(self.profile, "Default")
        names = [n for n in sorted(os.listdir(folder)) if n == "History" or n.startswith("History-")]
        if "History" not in names:
            return None
        with tempfile.TemporaryDirectory(prefix="rbs_history_") as copy:
            raw = b""
            for name in names:
                shutil.copy(os.path.join(folder, name), os.path.join(copy, name))
                with open(os.path.join(copy, name), "rb") as file:
                    raw += file.read()
            database = sqlite3.connect(os.path.join(copy, "History"))
            try:
                urls = [str(row[0]) for row in database.execute("SELECT url FROM urls")]
            finally:
                database.close()
        return History(urls, raw)

    def profile_files(self) -> Dict[str, bytes]:
        """Every file of the profile (its databases, caches, sessions, storage), by its path in the profile, once
        Chromium has ended (quit)."""
        files: Dict[str, bytes] = {}
        for folder, _, names in os.walk(self.profile):
            for name in names:
                path = os.path.join(folder, name)
                if os.path.isfile(path) and not os.path.islink(path):
                    with open(path, "rb") as file:
                        files[os.path.relpath(path, self.profile)] = file.read()
        return files

    def call(self, method: str, timeout: float = 30.0, **params: Any) -> Dict[str, Any]:
        self.next_id += 1
        self.socket.send(json.dumps({"id": self.next_id, "method": method, "params": params}))
        deadline = time.monotonic() + timeout
        while True:
            left = deadline - time.monotonic()
            if left <= 0:
                raise TimeoutError(f"no answer to {method} in {timeout:g} s")
            self.socket.settimeout(left)
            message = json.loads(self.socket.recv())
            if message.get("id") == self.next_id:
                if "error" in message:
                    raise RuntimeError(f"{method}: {message['error']}")
                result: Dict[str, Any] = message.get("result", {})
                return result
            if "method" in message:
                self.events.append(message)

    def evaluate(self, expression: str) -> Any:
        result = self.call("Runtime.evaluate", expression=expression, returnByValue=True, awaitPromise=True)
        if "exceptionDetails" in result:
            raise RuntimeError(f"{expression}: {result['exceptionDetails']}")
        return result["result"].get("value")

    def wait(self, what: str, expression: str, timeout: float) -> Any:
        """Until `expression` is truthy in the page: its value."""
        deadline = time.monotonic() + timeout
        while True:
            value = self.evaluate(expression)
            if value:
                return value
            if time.monotonic() > deadline:
                raise TimeoutError(f"timed out after {timeout:g} s waiting for {what} ({expression})")
            time.sleep(0.05)

    def navigate(self, url: str) -> None:
        self.call("Page.navigate", url=url)

    def load(self, url: str, what: str, timeout: float) -> None:
        """Navigates to `url` and waits for its page's load event."""
        since = len(self.events)
        self.navigate(url)
        self.wait_event("Page.loadEventFired", since, what, timeout)

    def log_in(self, login: str, token: str, timeout: float) -> None:
        """The teacher's login: the form at `login` loaded, the token typed into its field and its button
        clicked, then the page it leads to loading (its cookie given)."""
        self.load(login, "the login form", timeout)
        self.type_into("token", token)
        self.submit("login-submit", timeout)
        self.wait("the page after the login", "location.pathname === '/' && window.rbs !== undefined", timeout)

    def submit(self, button_id: str, timeout: float) -> None:
        """Clicks a form's button, then waits for the page its answer is to load (its load event: nothing is
        asked of the tab meanwhile, whose old page goes away under any question)."""
        since = len(self.events)
        self.click(button_id)
        self.wait_event("Page.loadEventFired", since, f"the answer to #{button_id} loaded", timeout)

    def wait_event(self, method: str, since: int, what: str, timeout: float) -> None:
        """Until an event `method` came, after the first `since` events."""
        deadline = time.monotonic() + timeout
        while not any(event["method"] == method for event in self.events[since:]):
            left = deadline - time.monotonic()
            if left <= 0:
                raise TimeoutError(f"timed out after {timeout:g} s waiting for {what} ({method})")
            self.socket.settimeout(left)
            message = json.loads(self.socket.recv())
            if "method" in message:
                self.events.append(message)

    def console_errors(self) -> List[str]:
        """What the page logged as an error or threw, so far."""
        lines = []
        for event in self.events:
            if event["method"] == "Runtime.exceptionThrown":
                lines.append(str(event["params"]["exceptionDetails"].get("exception", {}).get("description")))
            elif event["method"] == "Runtime.consoleAPICalled" and event["params"]["type"] == "error":
                lines.append(" ".join(str(a.get("value")) for a in event["params"]["args"]))
        return lines

    def centre(self, element_id: str) -> Optional[Dict[str, float]]:
        """The middle of a visible element, scrolled into view, in the viewport's CSS pixels."""
        box = self.evaluate(f"""(() => {{ const e = document.getElementById({json.dumps(element_id)});
            if (!e || e.offsetParent === null) return null; e.scrollIntoView({{block: "center"}});
            const r = e.getBoundingClientRect(); return {{x: r.x + r.width / 2, y: r.y + r.height / 2}}; }})()""")
        return box if isinstance(box, dict) else None

    def click(self, element_id: str) -> None:
        """A left click where a person would click the element."""
        at = self.centre(element_id)
        if at is None:
            raise RuntimeError(f"#{element_id} is not shown")
        for kind in ("mousePressed", "mouseReleased"):
            self.call("Input.dispatchMouseEvent", type=kind, x=at["x"], y=at["y"], button="left", clickCount=1)

    def type_into(self, element_id: str, text: str) -> None:
        """Clicks into a text field, selects what it holds and types `text` over it."""
        self.click(element_id)
        self.evaluate(f"document.getElementById({json.dumps(element_id)}).select()")
        self.call("Input.insertText", text=text)

    def choose(self, element_id: str, value: str) -> None:
        """Chooses an option of a <select>, as picking it from the list does (its change event)."""
        self.evaluate(f"""(() => {{ const s = document.getElementById({json.dumps(element_id)});
            s.value = {json.dumps(value)}; s.dispatchEvent(new Event("change")); }})()""")

    def resize(self, width: int, height: int, scale: float, mobile: bool) -> None:
        self.call("Emulation.setDeviceMetricsOverride", width=width, height=height, deviceScaleFactor=scale,
                  mobile=mobile)

    def screenshot(self, path: str) -> None:
        data = self.call("Page.captureScreenshot", format="png", timeout=60)["data"]
        with open(path, "wb") as out:
            out.write(base64.b64decode(data))
