#!/usr/bin/python3
"""WebSocket clients of the web view, for bench/web_load.py: N pages that read every frame, in one process (its
own, so that their work does not share the bench's interpreter). Prints `connected N` once every client has its
first frame, counts each client's frames and the rod's states in them for SECONDS from then, and prints one JSON
line: the frames and states each client received, the frames' sequence gaps (frames the server dropped for it),
and the seconds counted.

With --drain, N pages that read every byte the server sends and parse none of it (a class's worth of pages at
little cost to this machine's cores, which the server shares): the JSON line gives the bytes each received.

Usage: web_clients.py URL N SECONDS [--drain]   (URL: ws://127.0.0.1:PORT/ws)"""
import asyncio
import base64
import json
import os
import sys
import time
from typing import Any, Dict, List

import tornado.httpclient
import tornado.websocket


async def client(url: str, origin: str, counts: List[int], states: List[int], gaps: List[int], index: int,
                 ready: asyncio.Event, connected: List[int], stop: List[float]) -> None:
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
            states[index] += len(message["states"].get("rod", []))
            if last_seq is not None and message["seq"] > last_seq + 1:
                gaps[index] += message["seq"] - last_seq - 1
        last_seq = message["seq"]
        if time.monotonic() >= stop[0]:
            connection.close()
            return


async def main(url: str, n: int, seconds: float) -> None:
    origin = "http://" + url.split("/")[2]
    counts, states, gaps, connected = [0] * n, [0] * n, [0] * n, [0]
    ready = asyncio.Event()
    stop = [float("inf")]
    tasks = [asyncio.ensure_future(client(url, origin, counts, states, gaps, i, ready, connected, stop))
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


if __name__ == "__main__":
    if "--drain" in sys.argv:
        sys.argv.remove("--drain")
        asyncio.run(drain(sys.argv[1], int(sys.argv[2]), float(sys.argv[3])))
    else:
        asyncio.run(main(sys.argv[1], int(sys.argv[2]), float(sys.argv[3])))
