#!/usr/bin/python3
"""WebSocket clients of the web view, for bench/web_load.py: N pages that read every frame, in one process (its
own, so that their work does not share the bench's interpreter). Prints `connected N` once every client has its
first frame, counts each client's frames and BODY's states in them (--body, default rod) for SECONDS from then,
and prints one JSON line: the frames and states each client received, the frames' sequence gaps (frames the
server dropped for it), and the seconds counted.

With --drain, N pages that read every byte the server sends and parse none of it (a class's worth of pages at
little cost to this machine's cores, which the server shares): the JSON line gives the bytes each received.

With --labs, N pages that each open a lab of their own (a cookie each, from GET /; lab_open from the lesson
part's start), and with --probe, one page that sends refused requests (a pause without the token) and times
their replies: both read every frame (WebSocket frames parsed by hand, JSON only where rare), answer the
server's pings, print `connected N` and then take commands on stdin, each answered by one line:
  count S   count for S seconds: per page, the class's frames and their sequence gaps; with --labs its own
            lab's frames, their samples and sequence gaps; with --probe the refused requests' reply times (ms,
            one request every PROBE_PERIOD s). One JSON line.
  open      (--labs) every page opens its lab once the world has a lesson part: `opened N` when every page
            has its reply and its lab's first frame, or `refused LINE`.
End of stdin ends them.

Usage: web_clients.py URL N SECONDS [--drain | --body BODY]   (URL: ws://127.0.0.1:PORT/ws)
       web_clients.py URL N --labs | URL 1 --probe"""
import asyncio
import base64
import json
import os
import re
import struct
import sys
import time
from typing import Any, Dict, List, Optional, Tuple

import tornado.httpclient
import tornado.websocket


async def client(url: str, origin: str, counts: List[int], states: List[int], gaps: List[int], index: int,
                 ready: asyncio.Event, connected: List[int], stop: List[float], body: str) -> None:
    request = tornado.httpclient.HTTPRequest(url, headers={"Origin": origin})
    connection = await tornado.websocket.websocket_connect(request)
    last_seq = None
    first = True
    while True:
        text = await connection.read_message()
        if text is None:
            return
        message: Dict[str, Any] = json.loads(text)
        if message.get("type") != "frame":
            continue
        if first:
            first = False
            connected[0] += 1
            if connected[0] == len(counts):
                ready.set()
        if ready.is_set() and time.monotonic() < stop[0]:
            counts[index] += 1
            states[index] += len(message["states"].get(body, []))
            if last_seq is not None and message["seq"] > last_seq + 1:
                gaps[index] += message["seq"] - last_seq - 1
        last_seq = message["seq"]
        if time.monotonic() >= stop[0]:
            connection.close()
            return


async def main(url: str, n: int, seconds: float, body: str) -> None:
    origin = "http://" + url.split("/")[2]
    counts, states, gaps, connected = [0] * n, [0] * n, [0] * n, [0]
    ready = asyncio.Event()
    stop = [float("inf")]
    tasks = [asyncio.ensure_future(client(url, origin, counts, states, gaps, i, ready, connected, stop, body))
             for i in range(n)]
    await asyncio.wait_for(ready.wait(), 60)
    start = time.monotonic()
    stop[0] = start + seconds
    print(f"connected {n}", flush=True)
    await asyncio.wait(tasks, timeout=seconds + 30)
    counted = {"frames": counts, "states": states, "gaps": gaps, "seconds": time.monotonic() - start}
    print(json.dumps(counted), flush=True)


async def drain(url: str, n: int, seconds: float) -> None:
    host, port = url.split("/")[2].rsplit(":", 1)
    received = [0] * n
    stop = [float("inf")]

    async def page(index: int, connected: asyncio.Queue) -> None:
        reader, writer = await asyncio.open_connection(host, int(port))
        key = base64.b64encode(os.urandom(16)).decode()
        writer.write((f"GET /ws HTTP/1.1\r\nHost: {host}:{port}\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
                      f"Sec-WebSocket-Key: {key}\r\nSec-WebSocket-Version: 13\r\nOrigin: http://{host}:{port}\r\n\r\n")
                     .encode())
        head = await reader.readuntil(b"\r\n\r\n")
        if b" 101 " not in head.split(b"\r\n")[0]:
            raise RuntimeError(f"handshake: {head!r}")
        await connected.put(index)
        while time.monotonic() < stop[0]:
            data = await reader.read(1 << 16)
            if not data:
                break
            if time.monotonic() >= start[0]:
                received[index] += len(data)
        writer.close()

    start = [float("inf")]
    connected: asyncio.Queue = asyncio.Queue()
    tasks = [asyncio.ensure_future(page(i, connected)) for i in range(n)]
    for _ in range(n):
        await asyncio.wait_for(connected.get(), 60)
    start[0] = time.monotonic()
    stop[0] = start[0] + seconds
    print(f"connected {n}", flush=True)
    await asyncio.wait(tasks, timeout=seconds + 30)
    print(json.dumps({"bytes": received, "seconds": time.monotonic() - start[0]}), flush=True)


PROBE_PERIOD = 0.05  # s between the probe's refused requests
# The start of a frame's or a lab frame's text (json.dumps with compact separators: the server's).
FRAME_HEAD = re.compile(rb'\{"type":"(frame|lab_frame)",(?:"lab":"[^"]*",)?"seq":(\d+),')
SAMPLE = b'{"t":'  # each state or sample of a frame begins so (its first field)


def masked(opcode: int, payload: bytes) -> bytes:
    """A client's WebSocket frame (RFC 6455 5.2: masked)."""
    mask = os.urandom(4)
    n = len(payload)
    head = bytes((0x80 | opcode,)) + (bytes((0x80 | n,)) if n < 126 else bytes((0x80 | 126,)) + struct.pack(">H", n))
    return head + mask + bytes(b ^ mask[i % 4] for i, b in enumerate(payload))


class RawPage:
    """A page on a bare socket: the cookie GET / gives, the handshake with it, the server's frames parsed from
    a buffer (text, ping; no fragments: the server sends none), counts while `counting`."""

    def __init__(self, host: str, port: int) -> None:
        self.host, self.port = host, port
        self.cookie = ""
        self.writer: Optional[asyncio.StreamWriter] = None
        self.counting = False
        self.counts: Dict[str, int] = {"frames": 0, "frame_gaps": 0, "lab_frames": 0, "lab_samples": 0,
                                       "lab_gaps": 0}
        self.last_seq: Dict[bytes, int] = {}
        self.part = ""  # the world's lesson part, from its `world` messages
        self.bodies = 0  # its lab's bodies
        self.replies: "asyncio.Queue[Dict[str, Any]]" = asyncio.Queue()
        self.first_lab_frame = asyncio.Event()

    async def get_cookie(self) -> None:
        reader, writer = await asyncio.open_connection(self.host, self.port)
        writer.write(f"GET / HTTP/1.1\r\nHost: {self.host}:{self.port}\r\nConnection: close\r\n\r\n".encode())
        answer = await reader.read()
        writer.close()
        found = re.search(rb"Set-Cookie: rbs_lab=([^;\r\n]+)", answer.split(b"\r\n\r\n", 1)[0], re.IGNORECASE)
        if found is None:
            raise RuntimeError(f"GET / gave no rbs_lab cookie: {answer[:300]!r}")
        self.cookie = found[1].decode()

    async def connect(self) -> asyncio.StreamReader:
        reader, writer = await asyncio.open_connection(self.host, self.port)
        key = base64.b64encode(os.urandom(16)).decode()
        cookie = f"Cookie: rbs_lab={self.cookie}\r\n" if self.cookie else ""
        writer.write((f"GET /ws HTTP/1.1\r\nHost: {self.host}:{self.port}\r\nUpgrade: websocket\r\n"
                      f"Connection: Upgrade\r\nSec-WebSocket-Key: {key}\r\nSec-WebSocket-Version: 13\r\n"
                      f"Origin: http://{self.host}:{self.port}\r\n{cookie}\r\n").encode())
        head = await reader.readuntil(b"\r\n\r\n")
        if b" 101 " not in head.split(b"\r\n")[0]:
            raise RuntimeError(f"handshake: {head!r}")
        self.writer = writer
        return reader

    def send(self, request: Dict[str, Any]) -> None:
        assert self.writer is not None
        self.writer.write(masked(0x1, json.dumps(request).encode()))

    async def read(self, reader: asyncio.StreamReader) -> None:
        buffer = b""
        while True:
            data = await reader.read(1 << 16)
            if not data:
                return
            buffer += data
            while True:
                parsed = self.frame_of(buffer)
                if parsed is None:
                    break
                opcode, payload, used = parsed
                buffer = buffer[used:]
                if opcode == 0x1:
                    self.take(payload)
                elif opcode == 0x9 and self.writer is not None:
                    self.writer.write(masked(0xA, payload))
                elif opcode == 0x8:
                    return

    @staticmethod
    def frame_of(buffer: bytes) -> Optional[Tuple[int, bytes, int]]:
        """(opcode, payload, bytes used) of the buffer's first whole frame, or None."""
        if len(buffer) < 2:
            return None
        n, at = buffer[1] & 0x7F, 2
        if n == 126:
            if len(buffer) < 4:
                return None
            n, at = struct.unpack(">H", buffer[2:4])[0], 4
        elif n == 127:
            if len(buffer) < 10:
                return None
            n, at = struct.unpack(">Q", buffer[2:10])[0], 10
        if len(buffer) < at + n:
            return None
        return buffer[0] & 0x0F, buffer[at:at + n], at + n

    def take(self, payload: bytes) -> None:
        head = FRAME_HEAD.match(payload, 0, 80)
        if head is None:  # rare: parsed whole
            message = json.loads(payload)
            kind = message.get("type")
            if kind == "world":
                self.part = message.get("part") or ""
            elif kind == "lab":
                self.bodies = len(message["bodies"])
            elif kind == "reply":
                self.replies.put_nowait({**message, "at": time.monotonic()})
            return
        kind, seq = head[1], int(head[2])
        last = self.last_seq.get(kind)
        self.last_seq[kind] = seq
        if kind == b"lab_frame":
            self.first_lab_frame.set()
        if not self.counting:
            return
        gap = seq - last - 1 if last is not None and seq > last + 1 else 0
        if kind == b"frame":
            self.counts["frames"] += 1
            self.counts["frame_gaps"] += gap
        else:
            self.counts["lab_frames"] += 1
            self.counts["lab_gaps"] += gap
            self.counts["lab_samples"] += payload.count(SAMPLE)


async def commands() -> "asyncio.Queue[str]":
    """stdin's lines, as they come ("" at its end)."""
    lines: "asyncio.Queue[str]" = asyncio.Queue()
    loop = asyncio.get_running_loop()

    async def read() -> None:
        while True:
            line = await loop.run_in_executor(None, sys.stdin.readline)
            await lines.put(line.strip())
            if not line:
                return
    asyncio.ensure_future(read())
    return lines


async def open_labs(pages: List[RawPage]) -> str:
    """Every page's lab_open from the lesson part's start: `opened N`, or `refused LINE`."""
    loop = asyncio.get_running_loop()
    deadline = loop.time() + 60
    while not pages[0].part:
        if loop.time() > deadline:
            return "refused the world had no lesson part in 60 s"
        await asyncio.sleep(0.1)
    for index, page in enumerate(pages):
        page.send({"op": "lab_open", "id": 1, "from": "start", "name": f"s{index}"})
    for page in pages:
        reply = await asyncio.wait_for(page.replies.get(), 60)
        if not reply["ok"]:
            return f"refused {reply['line']}"
    await asyncio.wait_for(asyncio.gather(*(page.first_lab_frame.wait() for page in pages)), 60)
    return f"opened {len(pages)}"


async def lab_pages(url: str, n: int, probe: bool) -> None:
    """The --labs pages (or the --probe page): see the docstring's commands."""
    host, port = url.split("/")[2].rsplit(":", 1)
    pages = [RawPage(host, int(port)) for _ in range(n)]
    if not probe:
        await asyncio.gather(*(page.get_cookie() for page in pages))
    readers = await asyncio.gather(*(page.connect() for page in pages))
    tasks = [asyncio.ensure_future(page.read(reader)) for page, reader in zip(pages, readers)]
    print(f"connected {n}", flush=True)
    lines = await commands()
    while True:
        line = await lines.get()
        if not line:
            break
        if line == "open":
            print(await open_labs(pages), flush=True)
        elif line.startswith("count "):
            seconds = float(line.split()[1])
            for page in pages:
                page.counts = dict.fromkeys(page.counts, 0)
                page.counting = True
            start = time.monotonic()
            times = await probe_for(pages[0], seconds) if probe else []
            await asyncio.sleep(max(0.0, start + seconds - time.monotonic()))
            for page in pages:
                page.counting = False
            counted: Dict[str, Any] = {key: [page.counts[key] for page in pages] for key in pages[0].counts}
            counted.update(seconds=time.monotonic() - start, bodies=[page.bodies for page in pages],
                           reply_ms=times)
            print(json.dumps(counted), flush=True)
    for page in pages:
        if page.writer is not None:
            page.writer.close()
    for task in tasks:
        task.cancel()


async def probe_for(page: RawPage, seconds: float) -> List[float]:
    """A refused request every PROBE_PERIOD s for `seconds`: each reply's time after its request (ms)."""
    loop = asyncio.get_running_loop()
    stop = loop.time() + seconds
    sent: Dict[int, float] = {}
    times: List[float] = []
    request_id = 0

    async def collect() -> None:
        while True:
            reply = await page.replies.get()
            asked = sent.pop(int(reply.get("id") or 0), None)
            if asked is not None:
                times.append(1000.0 * (reply["at"] - asked))
    collector = asyncio.ensure_future(collect())
    while loop.time() < stop:
        request_id += 1
        sent[request_id] = time.monotonic()
        page.send({"op": "pause", "id": request_id})
        await asyncio.sleep(PROBE_PERIOD)
    await asyncio.sleep(1.0)  # the last replies
    collector.cancel()
    if sent:  # a request never answered counts as a reply at the window's end
        times += [1000.0 * (time.monotonic() - asked) for asked in sent.values()]
    return times


if __name__ == "__main__":
    if "--labs" in sys.argv or "--probe" in sys.argv:
        asyncio.run(lab_pages(sys.argv[1], int(sys.argv[2]), "--probe" in sys.argv))
    elif "--drain" in sys.argv:
        sys.argv.remove("--drain")
        asyncio.run(drain(sys.argv[1], int(sys.argv[2]), float(sys.argv[3])))
    else:
        watched = sys.argv[sys.argv.index("--body") + 1] if "--body" in sys.argv else "rod"
        asyncio.run(main(sys.argv[1], int(sys.argv[2]), float(sys.argv[3]), watched))
