"""Debian's Chromium, headless, driven over the DevTools protocol (websocket-client): load a page, evaluate
JavaScript in it, click and type as a person does (mouse and key events at an element's place), resize it
to a phone's screen, and take screenshots. Every wait has a deadline and names what it waited for."""
import base64
import json
import os
import shutil
import signal
import subprocess
import tempfile
import time
import urllib.request
from typing import Any, Dict, List, Optional

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
