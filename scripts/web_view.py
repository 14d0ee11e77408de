#!/usr/bin/env python3
"""The web view: serves one page (web/) over HTTP and streams the running world to it over a WebSocket.

It follows the simulation node `~node` (default `sim`: the launch's own) as the rviz panel does: the bodies
from the master's `<node>/<body>/state` topics (a live node's or a played bag's), their keys from the
config on `<node>/commands` (and `<node>/get_config` when it missed some), `<node>/paused`, and the node's
WARN lines on /rosout. Every state goes to every page in frames at `~frame_rate`; a page that cannot keep up
loses frames (a queue of `~queue` frames each), never slows the others or the simulation, which sees one
subscriber per topic whatever the number of pages. The node's events (`<node>/events`: a grip, a finish with
its lap time and place, a restart, each at its exact instant) go to every page as they come, and the run's
(`<node>/get_events`, read when the node is found and kept since) to a page that opens: the page draws them
and computes none.

With `~control` the teacher's browser, once the token this node prints is typed into the form at /login,
may pause, run, step, reset and change the keys a lesson changes, each through the node's own services and
reconfigure servers, choose the body every following page plots and switch to another lesson part the bodies
can take (its config's keys, from the config/ beside ~web_root); any other request, or any from a page without
the token, is refused in one line (rigid_body_sim.web_protocol), on that page alone. The token goes only to this
process's standard output (the launching terminal), never to /rosout or a log file, and never into an address:
a browser keeps every address it visits in its history (a shared laptop's would keep the token), so the form
POSTs it (tornado's XSRF check: no other site's form can) and the answer is an HttpOnly cookie for the page's
WebSocket alone (a reload stays the teacher's page). An address with ?token= gives no control.

The Host a request names must be one of this machine's names or addresses (on every address too: DNS
rebinding); a request's head must come whole within HEAD_TIMEOUT, and an overlong target or header is
answered 414 or 431, a body over MAX_BODY 413.

Every page may open a lab of its own (rigid_body_sim.labs): a private rigid_body_sim.core.World of the class's
config (as it runs now, or its lesson part's file), stepped in real time at the frame timer on the server's loop
(within LAB_TICK_SHARE of a frame: a lab left out catches up at the next tick), its requests carried out on a
worker thread (each page's paced to LAB_THREAD_SHARE of it, all together to LAB_THREAD_TOTAL_SHARE:
rigid_body_sim.web_protocol), its frames and
events to its page(s) alone; a page acts on its own lab only (the `rbs_lab` cookie, HttpOnly, that GET /
gives), and downloads it at /lab/<id>.zip (its config and `simulate`'s files of its run so far).
The teacher's page gets the class's results and the curves they lie on, asks the class a question and shows
one lab to every page. web_protocol's docstring is the protocol.

Listening on every address (0.0.0.0 or ::), it listens on IPv4 and, where the machine has it, IPv6: the
addresses it offers are ones it listens on.

Parameters: ~host (127.0.0.1), ~port (8080), ~control (false), ~node (sim), ~web_root (the package's web/),
~frame_rate (50 Hz), ~queue (4 frames), ~max_labs (60), ~labs_per_address (8; the loopback's exempt),
~simulate (the package's simulate, found in the workspaces of CMAKE_PREFIX_PATH)."""
from __future__ import annotations

import asyncio
import concurrent.futures
import functools
import hmac
import io
import ipaddress
import json
import math
import os
import re
import resource
import secrets
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time
import zipfile
from typing import Any, Callable, Dict, List, Optional, Set, Tuple, TypeVar

import qrcode
import qrcode.image.svg
import rosgraph
import rospy
import tornado.httpserver
import tornado.httputil
import tornado.ioloop
import tornado.iostream
import tornado.log
import tornado.netutil
import tornado.web
import tornado.websocket
import yaml
from dynamic_reconfigure.msg import Config as ReconfigureConfig
from dynamic_reconfigure.msg import DoubleParameter
from dynamic_reconfigure.srv import Reconfigure
from rigid_body_sim import description, labs
from rigid_body_sim.msg import Command, Event
from rigid_body_sim.runs import event_record
from rigid_body_sim.sim_tools import WORLD_DEFAULTS, rospy_on_python39, state_message, with_defaults
from rigid_body_sim.web_protocol import (LAB_OPS, LAB_THREAD_SHARE, LAB_THREAD_TOTAL_SHARE, LESSON_KEYS,
                                         MAX_REQUEST_BYTES, EventLog, FrameQueue, Pacer, Record, Refusal, Request,
                                         event_roles, events_message, frame_message, lab_events_message,
                                         lab_frame_message, parse_request, part_config, part_of_config,
                                         websocket_text_frame)
from rigid_body_sim.srv import GetConfig, GetEvents, Step
from rosgraph_msgs.msg import Log
from std_msgs.msg import Bool
from std_srvs.srv import Empty, SetBool


# The state messages' types ("rigid_body_sim/RodState") -> (the body type, the message).
STATE_TYPES = {message._type: (name, message) for name, message in
               ((name, state_message(name)) for name in description.body_types())}
# The core's description of the body types (body_types.json), for every page: each key's unit and whether a
# lesson changes it, each type's state fields and whether it races. The page restates none of it.
DESCRIPTION = description.load()
NODE_LINE_WAIT = 3.0  # s: the node logs a refusal before it answers, but /rosout may bring it later
MAX_PENDING_REQUESTS = 8  # per page: more waiting for the node are refused
MAX_REPLIES = 64  # per page: replies and world updates not yet written; a page that leaves more is closed
# The page's files: the view, and the lab's and the class's parts.
WEB_FILES = ("index.html", "types.js", "view.js", "view.css", "lab.js", "class.js", "lab.css")
LAB_COOKIE = "rbs_lab"
# The ops that go to the labs (the page's own, the poll, the teacher's lab ops), never to the node.
LABS_OPS = (*LAB_OPS, "lab_open", "answer", "ask", "reveal", "show_lab", "class_clear")
CLASS_PERIOD = 1.0  # s: the class's results go to the teacher at most this often
# Of each frame's time, the loop's CPU time the labs' tick takes at most (those left go first at the next tick);
# its wall time, a frame at most (a busy machine's other processes take a core from it meanwhile). On the loop,
# not a worker thread: there a tick waits for the loop's GIL at each core step (some 30 ms for the 2 ms of 60
# labs' work), and a frame that finds it still running has none for the labs' pages.
LAB_TICK_SHARE = 0.5
MAX_DOWNLOADS = 2  # simulate runs for downloads at once
SIMULATE_TIMEOUT = 120.0  # s
SEND_BUFFER = 64 * 1024  # bytes of a page's socket buffer (Linux doubles it): some 3 s of frames at 50 Hz
CONTROL_COOKIE = "rbs_control"
LOGIN_PAGE = "login.html"  # the teacher's form at /login (a tornado template: its XSRF field, its refusal)
MAX_BODY = 4 * 1024  # bytes of a request's body (the login form's is some 100): more is answered 413
LOGIN_LOG_PERIOD = 10.0  # s: a refused login is logged at most this often (those between are counted)
NO_CONTROL = "refused control: this web view gives none (started without web_control:=true): every page only shows"
MAX_URL = 8 * 1024  # bytes of a request's target: longer is answered 414
MAX_HEADERS = 16 * 1024  # bytes of its header lines: more is answered 431
# What tornado reads of a request's head before it gives up and closes the socket without a status: past
# MAX_URL and MAX_HEADERS, so that an overlong one is answered (within HEAD_TIMEOUT, whatever its pace).
READ_HEAD_LIMIT = 4 * 1024 * 1024
HEAD_TIMEOUT = 10.0  # s for a request's whole head, and for an idle kept-alive connection


def state_dict(msg: Any) -> Dict[str, Any]:
    return {field: getattr(msg, field) for field in msg.__slots__ if field != "header"}


def lesson_parts(config_dir: str) -> Dict[str, Dict[str, Dict[str, Any]]]:
    """lesson.launch's parts, {part: {body: its keys, defaults filled in}}, from their configs (part_config:
    race_below.yaml is part below)."""
    parts = {}
    for name in sorted(os.listdir(config_dir)) if os.path.isdir(config_dir) else []:
        part = part_of_config(name)
        if part:
            with open(os.path.join(config_dir, name)) as text:
                config = yaml.safe_load(text) or {}
            parts[part] = {body: with_defaults(keys or {}) for body, keys in (config.get("bodies") or {}).items()}
    return parts


class World:
    """What the view knows of the followed world, on the server's thread."""

    def __init__(self, parts: Optional[Dict[str, Dict[str, Dict[str, Any]]]] = None) -> None:
        self.lesson_parts = parts or {}
        self.settings: Dict[str, Any] = dict(WORLD_DEFAULTS)
        self.bodies: Dict[str, Dict[str, Any]] = {}  # from the config and the commands
        self.topics: Dict[str, str] = {}  # body -> its type, from the master's state topics
        self.source = "none"  # node (a live node), replay (a played bag), ended (a replay that ended), none
        self.player = ""  # in a replay: the node that plays the state topics (rosbag play: pause_playback)
        self.paused = False
        self.paused_at = 0.0  # when a page paused the player (monotonic s)
        self.last_seq = -1

    def set_config(self, config: Dict[str, Any]) -> None:
        self.settings = {key: config.get(key, value) for key, value in WORLD_DEFAULTS.items()}
        self.bodies = {name: with_defaults(body or {}) for name, body in (config.get("bodies") or {}).items()}

    def kinds(self) -> Dict[str, str]:
        """{body: its type}: the bodies with a state topic."""
        return dict(self.topics)

    def parts(self) -> List[str]:
        """The lesson parts this world's bodies can take: the same bodies, of the same shapes (a node's world;
        a recording cannot change)."""
        if self.source != "node":
            return []
        return [part for part, bodies in self.lesson_parts.items()
                if set(bodies) == set(self.bodies) == set(self.topics)
                and all(b["type"] == self.bodies[n]["type"] and b.get("shape") == self.bodies[n].get("shape")
                        for n, b in bodies.items())]

    def part(self) -> str:
        """The lesson part whose keys the world has, or "" (none, or keys a teacher changed since)."""
        return next((part for part in self.parts()
                     if all(self.bodies[n].get(key) == b.get(key)
                            for n, b in self.lesson_parts[part].items() for key in LESSON_KEYS[b["type"]])), "")

    def message(self) -> str:
        bodies = {}
        for name, kind in sorted(self.topics.items()):
            known = self.bodies.get(name)
            bodies[name] = known if known and known["type"] == kind else with_defaults({"type": kind})
        return json.dumps({"type": "world", "source": self.source, "paused": self.paused,
                           "settings": self.settings, "bodies": bodies, "parts": self.parts(), "part": self.part()})


def summary_without_query(handler: tornado.web.RequestHandler) -> str:
    """What tornado's warnings say of a request (a refused Host, a failed XSRF check): its path, not its query
    (log_request)."""
    return f"{handler.request.method} {handler.request.path} ({handler.request.remote_ip})"


class Page(tornado.websocket.WebSocketHandler):
    """One open page."""

    _request_summary = summary_without_query

    view: "WebView"
    pages_opened = 0

    def initialize(self, view: "WebView") -> None:
        self.view = view

    def prepare(self) -> None:
        refuse_foreign_host(self, self.view)

    def open(self, *args: str, **kwargs: str) -> None:
        Page.pages_opened += 1
        # Each reply at once: with Nagle's algorithm a small reply waited for the page's delayed ack (40 ms).
        self.set_nodelay(True)
        self.number = Page.pages_opened
        self.frames = FrameQueue(self.view.queue_bound)
        self.replies: List[str] = []
        self.wake = asyncio.Event()
        self.pending = 0
        self.sent = 0
        self.writing = False  # send_loop waits for a write of this page's
        self.refused: Dict[str, int] = {}
        token = self.get_cookie(CONTROL_COOKIE, "") or ""
        self.control = self.view.is_token(token)
        refused_token = None
        if token and not self.control:  # a login from before a restart (a new token each start), or a guess
            refused_token = Refusal("token", "refused control: this browser's token is not this view's (a login "
                                             "from before it restarted? log in again at /login): this page only "
                                             "shows")
            self.note_refusal(refused_token)
        # tornado closes the connection on a message over its limit without a word to the handler.
        connection: Any = self.ws_connection
        close = connection.close

        def close_noting_size(code: Optional[int] = None, reason: Optional[str] = None) -> None:
            if code == 1009:
                self.note_refusal(Refusal("too big", f"refused: a message of more than {64 * MAX_REQUEST_BYTES} "
                                                     "bytes (connection closed)"))
            close(code, reason)
        connection.close = close_noting_size
        # The kernel's buffer for a page that reads nothing: a few seconds of frames, then its queue drops them.
        stream: Any = self.ws_connection.stream if self.ws_connection else None
        if stream is not None and stream.socket is not None:
            stream.socket.setsockopt(socket.SOL_SOCKET, socket.SO_SNDBUF, SEND_BUFFER)
        self.view.pages.add(self)
        rospy.loginfo(f"web view: page {self.number} opened from {self.request.remote_ip}"
                      f"{' with control' if self.control else ''} ({len(self.view.pages)} open)")
        hello = {"type": "hello", "control": self.control, "node": self.view.node, "frame_rate": self.view.frame_rate,
                 "description": DESCRIPTION, "view": self.view.shared}
        if self.control:  # where the class finds this page (a QR code of the first: /qr.svg)
            hello["addresses"] = self.view.watch_urls
        self.reply(hello)
        self.reply_text(self.view.world.message())
        self.reply_text(events_message(self.view.events.records(), True))  # the run's so far: marks, finishes
        if refused_token:
            self.reply({"type": "reply", "id": None, "ok": False, "line": str(refused_token)})
        latest = self.view.latest_frame()
        if latest:
            self.frames.offer(latest)
        # Its lab (a reload re-attaches it), the question, the lab the teacher shows, the class's results.
        self.lab_cookie = self.get_cookie(LAB_COOKIE, "") or ""
        self.view.attach(self)
        asyncio.ensure_future(self.send_loop())

    def on_close(self) -> None:
        if self in self.view.pages:
            self.view.detach(self)
        self.view.pages.discard(self)
        self.wake.set()
        more = sum(self.refused.values()) - len(self.refused)
        rospy.loginfo(f"web view: page {self.number} closed: {self.sent} messages sent, {self.frames.dropped} "
                      f"frames dropped, {sum(self.refused.values())} requests refused"
                      f"{f' ({more} not logged)' if more else ''}")

    def note_refusal(self, refusal: Refusal) -> None:
        """The first refusal of each kind from a page is logged; the rest are counted (on_close)."""
        if refusal.kind not in self.refused:
            rospy.logwarn(f"web view: page {self.number} ({self.request.remote_ip}): {refusal}")
        self.refused[refusal.kind] = self.refused.get(refusal.kind, 0) + 1

    def on_message(self, message: Any) -> None:
        request_id = None
        try:
            lab = self.view.room.of(self.lab_cookie)
            request = parse_request(message, self.control, self.view.world.kinds(), self.view.world.parts(),
                                    lab.bodies if lab else None)
            request_id = request.id
            if request.op in LABS_OPS:
                if self.pending >= MAX_PENDING_REQUESTS:
                    raise Refusal("busy", f"refused: {MAX_PENDING_REQUESTS} requests already wait")
                self.pending += 1
                asyncio.ensure_future(self.carry_out_lab(request))
                return
            if request.op == "view":  # the teacher's choice for every following page: the server's own
                self.view.shared = {"plot_body": request.body}
                self.view.broadcast({"type": "view", **self.view.shared})
                self.reply({"type": "reply", "id": request.id, "ok": True, "line": f"the class plots {request.body}"})
                return
            source = self.view.world.source
            if source == "replay" and request.op not in ("pause", "run"):
                raise Refusal("replay", "refused: a recording cannot be changed, only paused and run (no node "
                                        f"serves {self.view.node}/pause)")
            if source in ("none", "ended"):
                raise Refusal("none", f"refused: no simulation found ({self.view.node})")
            if self.pending >= MAX_PENDING_REQUESTS:
                raise Refusal("busy", f"refused: {MAX_PENDING_REQUESTS} requests already wait for the node")
        except Refusal as refusal:
            self.note_refusal(refusal)
            self.reply({"type": "reply", "id": request_id if request_id is not None else refusal.id, "ok": False,
                        "line": str(refusal)})
            return
        self.pending += 1
        asyncio.ensure_future(self.carry_out(request))

    async def carry_out_lab(self, request: Request) -> None:
        try:
            ok, line = await self.view.carry_out_lab(self, request)
        finally:
            self.pending -= 1
        if not ok:
            self.note_refusal(Refusal(request.op, line))
        self.reply({"type": "reply", "id": request.id, "ok": ok, "line": line})

    async def carry_out(self, request: Request) -> None:
        try:
            ok, line = await self.view.carry_out(request)
        finally:
            self.pending -= 1
        self.reply({"type": "reply", "id": request.id, "ok": ok, "line": line})

    def reply(self, message: Dict[str, Any]) -> None:
        self.reply_text(json.dumps(message))

    def reply_text(self, text: str) -> None:
        if len(self.replies) >= MAX_REPLIES:
            self.note_refusal(Refusal("frozen", f"closed: {MAX_REPLIES} replies not taken"))
            self.close(1008, "replies not taken")
            return
        self.replies.append(text)
        self.wake.set()

    def offer(self, frame: bytes) -> None:
        """A frame for this page: written at once when nothing of this page's waits (the socket takes it, or
        tornado holds this one frame until it does), else queued for send_loop. At once, a frame costs a
        page one write, not a wake of its loop: 300 pages at 50 frames a second."""
        connection: Any = self.ws_connection
        stream = connection.stream if connection is not None and not connection.is_closing() else None
        if not self.writing and not self.replies and not self.frames.frames and stream and not stream.writing():
            try:  # the socket itself (non-blocking): tornado's write costs several times more
                sent = stream.socket.send(frame)
            except BlockingIOError:
                sent = 0
            except OSError:
                return  # closed: on_close follows
            if sent < len(frame):  # tornado holds the rest until the socket takes it
                stream.write(frame[sent:]).add_done_callback(lambda done: done.exception())
            self.sent += 1
            return
        self.frames.offer(frame)
        self.wake.set()

    async def send_loop(self) -> None:
        """Writes one message at a time: a page whose socket is full holds one write here, its frames wait
        in its bounded queue, and no other page waits for it. A frame comes as the WebSocket frame's bytes,
        built once for every page (tornado's write_message would frame it again for each)."""
        while self in self.view.pages:
            message: Any = self.replies.pop(0) if self.replies else self.frames.take()
            if message is None:
                self.wake.clear()
                await self.wake.wait()
                continue
            self.writing = True
            try:
                if isinstance(message, bytes):
                    connection: Any = self.ws_connection
                    if connection is None or connection.is_closing():
                        return
                    await connection.stream.write(message)
                else:
                    await self.write_message(message)
            except (tornado.websocket.WebSocketClosedError, tornado.iostream.StreamClosedError):
                return
            finally:
                self.writing = False
            self.sent += 1


# A lab's news of a tick: the lab, its frame, its events, its `lab` and `shown_lab` messages if it changed.
LabOutput = Tuple[labs.Lab, Optional[bytes], Optional[str], Optional[Tuple[str, str]]]
T = TypeVar("T")


class WebView:
    def __init__(self) -> None:
        self.host = str(rospy.get_param("~host", "127.0.0.1"))
        self.port = int(rospy.get_param("~port", 8080))
        self.control = bool(rospy.get_param("~control", False))
        self.node = rospy.resolve_name(str(rospy.get_param("~node", "sim"))).rstrip("/")
        here = os.path.dirname(os.path.realpath(__file__))
        self.web_root = str(rospy.get_param("~web_root", os.path.join(here, "..", "web")))
        self.frame_rate = float(rospy.get_param("~frame_rate", 50.0))
        self.queue_bound = int(rospy.get_param("~queue", 4))
        if not 0 < self.frame_rate <= 1000 or not 1 <= self.queue_bound <= 1000:
            raise ValueError(f"frame_rate {self.frame_rate} not in (0, 1000] or queue {self.queue_bound} "
                             "not in [1, 1000]")
        self.token = secrets.token_urlsafe(18) if self.control else ""
        # The names a request may give as its Host: this machine's (DNS rebinding: a foreign name that points
        # here is refused), and the addresses a student's browser can use (every one but the loopback's when
        # listening on all of them).
        addresses = own_addresses() if self.host in ("0.0.0.0", "::", "") else [self.host]
        names = {"127.0.0.1", "localhost", "[::1]", socket.gethostname(), socket.getfqdn(),
                 socket.gethostname() + ".local"} | {f"[{a}]" if ":" in a else a for a in addresses}
        self.local_hosts = {f"{name.lower()}:{self.port}" for name in names}
        if self.port == 80:
            self.local_hosts |= {name.lower() for name in names}
        remote = [a for a in addresses if not a.startswith("127.") and a != "::1"] or addresses
        self.watch_urls = [f"http://{f'[{a}]' if ':' in a else a}:{self.port}/" for a in remote]
        self.shared: Dict[str, str] = {}  # the teacher's choices every following page takes: plot_body
        self.world = World(lesson_parts(os.path.join(self.web_root, "..", "config")))
        self.pages: Set[Page] = set()
        self.pending: Dict[str, List[Dict[str, Any]]] = {}  # states since the last frame, by body
        self.latest: Dict[str, Dict[str, Any]] = {}  # each body's last state
        self.seq = 0
        self.node_lines: List[Tuple[float, str]] = []  # (arrival, the node's WARN or ERROR line)
        self.line_came: asyncio.Event  # made on the server's loop (serve)
        self.subscribers: Dict[str, Any] = {}
        self.held: Dict[str, Any] = {}  # a player's other topics (take_the_rest)
        self.events = EventLog(event_roles(DESCRIPTION["types"]))  # the run's, for a page that opens
        self.new_events: List[Record] = []  # since the last frame
        self.ended_at = 0  # the events that had come when a recording ended
        self.need_config = threading.Event()
        self.calls = concurrent.futures.ThreadPoolExecutor(max_workers=1)  # one request at a time, in order
        self.loop: tornado.ioloop.IOLoop  # the server's loop (serve), to which every ROS callback hands its news
        state_topic = re.escape(self.node) + r"/([A-Za-z][A-Za-z0-9_]*)/state"
        self.state_topic = re.compile(state_topic + "$")
        # The labs: ticked on the loop, their requests on their own thread (one at a time, in order), the
        # class's results and curves on another.
        self.room = labs.LabRoom(int(rospy.get_param("~max_labs", labs.MAX_LABS)),
                                 int(rospy.get_param("~labs_per_address", labs.LABS_PER_ADDRESS)))
        self.simulate = str(rospy.get_param("~simulate", "")) or labs.find_simulate()
        self.config_dir = os.path.join(self.web_root, "..", "config")
        self.lab_thread = concurrent.futures.ThreadPoolExecutor(max_workers=1)
        self.class_thread = concurrent.futures.ThreadPoolExecutor(max_workers=1)
        self.lab_pages: Dict[str, Set[Page]] = {}  # lab cookie -> its pages
        # lab cookie -> its requests (and whole messages) under way on the lab thread: its frames and events
        # wait for them, so that a page gets a run's `lab` message before the run's samples.
        self.lab_busy: Dict[str, int] = {}
        self.tick_budget = LAB_TICK_SHARE / self.frame_rate  # s of CPU time
        # Each page's (lab cookie's) requests, and all of them together.
        self.lab_pacer = Pacer(self.lab_thread, LAB_THREAD_SHARE, LAB_THREAD_TOTAL_SHARE)
        self.login_refusals = 0  # refused logins not logged yet (LOGIN_LOG_PERIOD)
        self.login_logged_at = -math.inf  # monotonic s
        self.shown: Optional[str] = None  # the lab the teacher shows every page
        self.poll = labs.Poll()
        self.curves = labs.Curves()
        self.class_text = ""
        self.class_due = False
        self.class_busy = False
        self.last_part = ""  # the lesson part the world last had: a lab's "start"
        self.downloads: asyncio.Semaphore  # made on the server's loop (serve)

    # --- ROS: every callback hands its news to the server's thread ------------------------------------------
    def start_ros(self) -> None:
        rospy.Subscriber(self.node + "/paused", Bool, lambda m: self.loop.add_callback(self.on_paused, m.data))
        rospy.Subscriber(self.node + "/commands", Command, lambda m: self.loop.add_callback(self.on_command, m),
                         queue_size=1000)
        rospy.Subscriber("/rosout", Log, self.on_log, queue_size=100)
        # A burst (a reset: one restart a body) waits in the queue, none dropped: the node drops none either.
        rospy.Subscriber(self.node + "/events", Event,
                         lambda m: self.loop.add_callback(self.on_event, event_record(m)), queue_size=10000)
        threading.Thread(target=self.discover, daemon=True).start()

    def discover(self) -> None:
        """Every second: the state topics and whether a node serves them (else a player does)."""
        master = rosgraph.Master(rospy.get_name())
        while not rospy.is_shutdown():
            try:
                topics = {topic: kind for topic, kind in master.getPublishedTopics(self.node)}
                try:
                    master.lookupService(self.node + "/pause")
                    live = True
                except rosgraph.MasterError:
                    live = False
                if live and (self.world.source != "node" or self.need_config.is_set()):
                    self.need_config.clear()
                    self.fetch_config()
                    self.fetch_events()
                bodies = {}
                for topic, kind in topics.items():
                    match = self.state_topic.match(topic)
                    if match and kind in STATE_TYPES:
                        bodies[match.group(1)] = kind
                for body, kind in bodies.items():
                    if body not in self.subscribers:
                        self.subscribers[body] = rospy.Subscriber(
                            f"{self.node}/{body}/state", STATE_TYPES[kind][1],
                            lambda m, b=body: self.loop.add_callback(self.on_state, b, m), queue_size=100)
                for body in set(self.subscribers) - set(bodies):
                    self.subscribers.pop(body).unregister()
                kinds = {body: STATE_TYPES[kind][0] for body, kind in bodies.items()}
                player = "" if live or not bodies else self.player_of(master, sorted(bodies)[0])
                if player:
                    self.take_the_rest(master, player)
                self.loop.add_callback(self.on_discovered, kinds, "node" if live else "replay" if kinds else "none",
                                       player)
            except (OSError, rosgraph.MasterError) as error:
                rospy.logwarn_throttle(10, f"web view: the master: {error}")
            time.sleep(1.0)

    def take_the_rest(self, master: rosgraph.Master, player: str) -> None:
        """Subscribes (the messages dropped) to every other topic the player publishes: playback.launch plays
        nothing until each topic of the bag has a subscriber (rosbag play --wait-for-subscribers), and a web
        view without rviz is the only one there."""
        mine = {self.node + "/commands", self.node + "/paused", self.node + "/events", "/rosout", "/clock"}
        for topic, nodes in master.getSystemState()[0]:
            if player in nodes and topic not in mine and topic not in self.held and not self.state_topic.match(topic):
                self.held[topic] = rospy.Subscriber(topic, rospy.AnyMsg, lambda _: None)

    def player_of(self, master: rosgraph.Master, body: str) -> str:
        """The node that publishes a body's states in a replay (as the rviz panel finds it), or ""."""
        topic = f"{self.node}/{body}/state"
        publishers = dict((name, nodes) for name, nodes in master.getSystemState()[0])
        return next((n for n in publishers.get(topic, []) if n != rospy.get_name()), "")

    def fetch_config(self) -> None:
        try:
            rospy.wait_for_service(self.node + "/get_config", timeout=5.0)
            config = yaml.safe_load(rospy.ServiceProxy(self.node + "/get_config", GetConfig)().yaml)
        except (rospy.ROSException, rospy.ServiceException, yaml.YAMLError) as error:
            rospy.logwarn(f"web view: {self.node}/get_config: {error}")
            return
        self.loop.add_callback(self.on_config, config)

    def fetch_events(self) -> None:
        """The run's events as the node kept them: what came before this view subscribed (it started later
        than the node, or the node restarted)."""
        since = self.events.arrivals  # those that come on the topic from now on stay (EventLog.replace)
        try:
            rospy.wait_for_service(self.node + "/get_events", timeout=5.0)
            answer = rospy.ServiceProxy(self.node + "/get_events", GetEvents)()
        except (rospy.ROSException, rospy.ServiceException) as error:
            rospy.logwarn(f"web view: {self.node}/get_events: {error}")
            return
        self.loop.add_callback(self.on_events_fetched, [event_record(m) for m in answer.events], since)

    def on_log(self, line: Log) -> None:
        if line.name == self.node and line.level >= Log.WARN:
            self.loop.add_callback(self.on_node_line, line.msg)

    # --- on the server's thread ---------------------------------------------------------------------------
    def on_node_line(self, text: str) -> None:
        self.node_lines = self.node_lines[-49:] + [(time.monotonic(), text)]
        self.line_came.set()
        self.broadcast({"type": "line", "line": text}, control_only=True)  # the teacher's, not the class's

    def on_config(self, config: Dict[str, Any]) -> None:
        self.world.set_config(config)
        self.send_world()

    def on_discovered(self, kinds: Dict[str, str], source: str, player: str) -> None:
        self.world.player = player
        if source == "none" and self.world.source in ("replay", "ended"):
            source, kinds = "ended", self.world.topics  # the recording's last frame stays, and says so
        if kinds != self.world.topics or source != self.world.source:
            for body in set(self.latest) - set(kinds):
                del self.latest[body]
            if source == "ended":
                self.ended_at = self.events.arrivals
            elif source == "replay" and self.world.source == "ended":  # played again: from its start
                self.events.replace([], self.ended_at)  # the events that came since its end stay
                self.broadcast_text(events_message(self.events.records(), True))
            self.world.topics = kinds
            self.world.source = source
            self.send_world()

    def on_paused(self, paused: bool) -> None:
        self.world.paused = paused
        self.broadcast({"type": "paused", "paused": paused})

    def on_command(self, msg: Command) -> None:
        seq = msg.header.seq
        if msg.kind != "config" and seq != self.world.last_seq + 1:
            self.need_config.set()  # joined late, or a command lost: the node's whole config
        self.world.last_seq = seq
        try:
            payload = yaml.safe_load(msg.yaml) if msg.yaml else None
        except yaml.YAMLError:
            payload = None
        if msg.kind == "config" and isinstance(payload, dict):
            self.world.set_config(payload)
        elif msg.kind in ("reconfigure", "spawn") and isinstance(payload, dict):
            self.world.bodies[msg.body] = with_defaults(payload)
        elif msg.kind == "delete":
            self.world.bodies.pop(msg.body, None)
        else:
            return  # no key changed (a reset: its restart events say it, at its instant: on_event)
        self.send_world()

    def on_event(self, record: Record) -> None:
        if self.events.add(record):
            self.new_events.append(record)

    def on_events_fetched(self, records: List[Record], since: int) -> None:
        self.events.replace(records, since)
        self.new_events = []
        self.broadcast_text(events_message(self.events.records(), True))

    def on_state(self, body: str, msg: Any) -> None:
        state = state_dict(msg)
        if not all(math.isfinite(v) for v in state.values() if isinstance(v, float)):
            return  # the node's NaN guard holds such a body: nothing a page could draw
        self.pending.setdefault(body, []).append(state)
        self.latest[body] = state
        # A replay that a page paused plays again when states come (run by someone else, rviz's panel), once
        # those already on their way at the pause are in.
        if self.world.source == "replay" and self.world.paused and time.monotonic() > self.world.paused_at + 0.5:
            self.on_paused(False)

    def latest_frame(self) -> Optional[bytes]:
        if not self.latest:
            return None
        return websocket_text_frame(frame_message(self.seq, {b: [s] for b, s in self.latest.items()}))

    def flush(self, frame_time: float) -> None:
        """One frame of every state since the last, serialised once for every page; the events since the last
        before it, in one message (a reset's burst of restarts is one reply, not one a body); each lab's
        frame, the lab stepped to the frame's time on the timer's schedule (frame_timer)."""
        if self.room.labs:
            self.tick_labs(frame_time)
        if self.new_events and self.pages:
            self.broadcast_text(events_message(self.new_events, False))
        self.new_events = []
        if not self.pending or not self.pages:
            self.pending = {}
            return
        self.seq += 1
        frame = websocket_text_frame(frame_message(self.seq, self.pending))
        self.pending = {}
        for page in list(self.pages):
            page.offer(frame)

    def send_world(self) -> None:
        self.last_part = self.world.part() or self.last_part
        text = self.world.message()
        for page in list(self.pages):
            page.reply_text(text)

    def broadcast(self, message: Dict[str, Any], control_only: bool = False) -> None:
        self.broadcast_text(json.dumps(message), control_only)

    def broadcast_text(self, text: str, control_only: bool = False) -> None:
        for page in list(self.pages):
            if page.control or not control_only:
                page.reply_text(text)

    async def carry_out(self, request: Request) -> Tuple[bool, str]:
        """One request through the node's own services or the body's reconfigure server: (accepted, the line
        to show: the node's own WARN line for a refusal)."""
        asked_at = time.monotonic()
        ok, fallback = await asyncio.get_running_loop().run_in_executor(self.calls, self.call, request)
        if ok:
            return True, fallback
        words = f"'{request.body}'" if request.op == "set" else "~step" if request.op == "step" else ""
        deadline = asked_at + NODE_LINE_WAIT
        while True:
            for arrival, text in reversed(self.node_lines):
                if arrival >= asked_at and words in text:
                    return False, text
            left = deadline - time.monotonic()
            if left <= 0:
                return False, fallback
            self.line_came.clear()
            try:
                await asyncio.wait_for(self.line_came.wait(), left)
            except asyncio.TimeoutError:
                pass

    def call(self, request: Request) -> Tuple[bool, str]:
        """On the calls thread: the service call. (accepted, what to show)."""
        try:
            if self.world.source == "replay":  # pause or run: the player's pause_playback, as rviz's panel does
                player = self.world.player
                answer = rospy.ServiceProxy(f"{player}/pause_playback", SetBool)(request.op == "pause")
                if answer.success:
                    self.world.paused_at = time.monotonic()
                    self.loop.add_callback(self.on_paused, request.op == "pause")
                return bool(answer.success), f"{player}: {answer.message}"
            if request.op == "part":
                return self.start_part(request.key)
            if request.op in ("pause", "run", "reset"):
                name = {"pause": "pause", "run": "unpause", "reset": "reset"}[request.op]
                rospy.ServiceProxy(f"{self.node}/{name}", Empty)()
                return True, f"{name}: done"
            if request.op == "step":
                answer = rospy.ServiceProxy(f"{self.node}/step", Step)(request.steps)
                return bool(answer.success), (f"stepped to t = {answer.t:g} s" if answer.success
                                              else f"~step {answer.message}")
            asked = ReconfigureConfig(doubles=[DoubleParameter(name=request.key, value=request.value)])
            shown = rospy.ServiceProxy(f"{self.node}/{request.body}/set_parameters", Reconfigure)(asked).config
            now = next((p.value for p in shown.doubles if p.name == request.key), math.nan)
            if now == request.value:
                return True, f"{request.body}: {request.key} = {request.value:g}"
            return False, f"refused {request.key} = {request.value:g}: snapped back to {now:g}"
        except (rospy.ServiceException, rospy.ROSException, OSError) as error:
            return False, f"no answer from {self.node}: {error}"

    def start_part(self, part: str) -> Tuple[bool, str]:
        """On the calls thread: every body's lesson keys as the part's config has them (one reconfigure
        each), then a reset: the race starts afresh, and every page shows it."""
        for body, keys in self.world.lesson_parts[part].items():
            names = LESSON_KEYS[keys["type"]]
            asked = ReconfigureConfig(doubles=[DoubleParameter(name=k, value=float(keys[k])) for k in names])
            shown = rospy.ServiceProxy(f"{self.node}/{body}/set_parameters", Reconfigure)(asked).config
            now = {p.name: p.value for p in shown.doubles}
            wrong = [k for k in names if now.get(k) != float(keys[k])]
            if wrong:
                return False, f"refused part {part}: {body}'s {', '.join(wrong)} snapped back"
        rospy.ServiceProxy(f"{self.node}/reset", Empty)()
        return True, f"part {part}: every body's keys set, the race started again"

    # --- labs: the tick on the loop, every other world call on the lab thread ----------------------------------
    async def on_lab_thread(self, page: Page, cookies: List[str], work: Callable[..., T], *args: Any) -> T:
        """work(*args) on the lab thread in the page's turn: once the page's (its lab cookie's) rest after its
        last request there is over (lab_pacer, on the loop: other pages' requests wait for none of it). From
        then until it is done the labs of these cookies send nothing (tick_labs): the caller's messages of its
        result, sent before it awaits anything else, come before their news."""
        held: List[str] = []

        def hold() -> None:
            for cookie in cookies:
                self.lab_busy[cookie] = self.lab_busy.get(cookie, 0) + 1
                held.append(cookie)
        try:
            return await self.lab_pacer.run(page.lab_cookie, functools.partial(work, *args), hold)
        finally:
            for cookie in held:
                self.lab_busy[cookie] -= 1
                if not self.lab_busy[cookie]:
                    del self.lab_busy[cookie]

    def pages_of(self, lab: labs.Lab) -> List[Page]:
        return list(self.lab_pages.get(lab.cookie, ()))

    def attach(self, page: Page) -> None:
        """A page that opens: its lab (a reload re-attaches it), the question, the lab shown, the class."""
        lab = self.room.attach(page.lab_cookie)
        if lab is not None:
            self.lab_pages.setdefault(page.lab_cookie, set()).add(page)
        if self.poll.question:
            page.reply(self.poll.question_message())
            if page.control or not self.poll.open:
                page.reply(self.poll.answers_message())
        if page.control and self.class_text:
            page.reply_text(self.class_text)
        shown = self.room.by_id.get(self.shown or "")
        if lab is not None or shown is not None:
            asyncio.ensure_future(self.send_labs(page, lab, shown))

    def detach(self, page: Page) -> None:
        pages = self.lab_pages.get(page.lab_cookie)
        if pages is not None and page in pages:
            pages.discard(page)
            self.room.detach(page.lab_cookie)

    async def send_labs(self, page: Page, own: Optional[labs.Lab], shown: Optional[labs.Lab]) -> None:
        """A page's own lab and the shown one, whole: each lab message and its run's events."""
        texts = await self.on_lab_thread(page, [lab.cookie for lab in (own, shown) if lab is not None],
                                         self.lab_texts, own, shown)
        if page in self.pages:
            for text in texts:
                page.reply_text(text)

    @staticmethod
    def lab_texts(own: Optional[labs.Lab], shown: Optional[labs.Lab]) -> List[str]:
        texts = []
        for lab, kind in ((own, "lab"), (shown, "shown_lab")):
            if lab is not None:
                with lab.lock:
                    texts.append(json.dumps(lab.message(kind)))
                    texts.append(lab_events_message(lab.id, list(lab.events), True))
        return texts

    def lab_config(self, source: str) -> str:
        """The config a lab opens from: the world's as it runs ("now") or its lesson part's file ("start")."""
        if source == "now":
            if self.world.source != "node" or not self.world.bodies:
                raise labs.LabRefusal(f"refused: no simulation's config to open a lab from ({self.node})")
            return labs.dump_yaml({**self.world.settings, "bodies": self.world.bodies})
        if not self.last_part:
            raise labs.LabRefusal("refused: the world has had no lesson part's keys: open a lab from now")
        with open(os.path.join(self.config_dir, part_config(self.last_part))) as text:
            return text.read()

    def lab_gone(self, lab: labs.Lab, line: str) -> None:
        message = {"type": "lab_closed", "lab": lab.id, "line": line}
        for page in self.pages_of(lab):
            page.reply(message)
        if self.shown == lab.id:
            self.shown = None
            self.broadcast({"type": "shown_lab", "lab": None})
        self.class_due = True

    def lab_changed(self, lab: labs.Lab, texts: Tuple[str, str]) -> None:
        """Its `lab` message to its pages, and `shown_lab` to every page if shown."""
        for page in self.pages_of(lab):
            page.reply_text(texts[0])
        if self.shown == lab.id:
            self.broadcast_text(texts[1])
        self.class_due = True

    @staticmethod
    def lab_messages(lab: labs.Lab) -> Tuple[str, str]:
        """On the lab thread, its lock held: its `lab` and `shown_lab` messages."""
        lab.changed = False
        return json.dumps(lab.message("lab")), json.dumps(lab.message("shown_lab"))

    def lab_op(self, lab: labs.Lab, request: Request) -> Tuple[str, LabOutput]:
        """On the lab thread: a request of the page's own lab. (its line, its news: a long step's samples are
        made into their frame here, not on the loop)."""
        with lab.lock:
            self.room.touch(lab)
            now = self.room.clock()
            if request.op == "lab_run":
                line = lab.run(now)
            elif request.op == "lab_pause":
                line = lab.pause()
            elif request.op == "lab_reset":
                line = lab.reset(now)
            elif request.op == "lab_step":
                line = lab.step(request.steps)
            else:
                line = lab.set(request.body, request.key, request.value, now)
            return line, self.take_news(lab, messages=True)

    def open_lab(self, page: Page, request: Request, config: str) -> Tuple[LabOutput, Optional[labs.Lab]]:
        """On the lab thread: a new lab for the page's cookie (its news, the lab it replaces)."""
        lab, old = self.room.open(page.lab_cookie, page.request.remote_ip or "", request.name, request.source, config)
        with lab.lock:
            return self.take_news(lab, messages=True), old

    async def carry_out_lab(self, page: Page, request: Request) -> Tuple[bool, str]:
        """A lab's, the poll's or the class's request: (accepted, its line)."""
        op = request.op
        try:
            if op == "lab_open":
                config = self.lab_config(request.source)
                news, old = await self.on_lab_thread(page, [page.lab_cookie], self.open_lab, page, request, config)
                lab = news[0]
                if old is not None:
                    self.lab_gone(old, f"lab {old.id} closed: a new one opened")
                pages = self.lab_pages.setdefault(lab.cookie, set())
                pages.update(p for p in self.pages if p.lab_cookie == lab.cookie)
                lab.attached = len(pages)
                self.send_news(news)
                return True, f"lab {lab.id} opened from {request.source}: t = 0, running"
            if op == "answer":
                line = self.poll.answer(page.lab_cookie, request.answer if request.answer is not None else "")
                self.broadcast(self.poll.answers_message(), control_only=True)
                return True, line
            if op == "ask":
                line = self.poll.ask(request.question, request.choices, request.unit)
                self.broadcast(self.poll.question_message())
                self.broadcast(self.poll.answers_message(), control_only=True)
                return True, line
            if op == "reveal":
                line = self.poll.reveal()
                self.broadcast(self.poll.question_message())
                self.broadcast(self.poll.answers_message())
                return True, line
            if op == "show_lab":
                return await self.show_lab(page, request.lab)
            if op == "class_clear":
                await self.on_lab_thread(page, [], self.room.clear_results)
                self.class_due = True
                return True, "the class's results cleared (the labs go on)"
            own = self.room.of(page.lab_cookie)
            if own is None:
                raise labs.LabRefusal("refused: this page has no lab (open one first)")
            if op == "lab_close":
                self.room.close(own.cookie)
                self.lab_gone(own, f"lab {own.id} closed")
                return True, f"lab {own.id} closed"
            line, news = await self.on_lab_thread(page, [own.cookie], self.lab_op, own, request)
            self.send_news(news)
            return True, line
        except labs.LabRefusal as refusal:
            return False, str(refusal)
        except OSError as error:  # a lesson part's config that cannot be read
            return False, f"refused: {error}"

    async def show_lab(self, teacher: Page, lab_id: Optional[str]) -> Tuple[bool, str]:
        """The lab every page shows (None: the class's world): its messages, made once on the lab thread in the
        teacher's turn, to every page."""
        if lab_id is None:
            self.shown = None
            self.broadcast({"type": "shown_lab", "lab": None})
            return True, "the class sees its world again"
        lab = self.room.by_id.get(lab_id)
        if lab is None:
            raise labs.LabRefusal(f"refused: no lab {lab_id!r}")
        texts = await self.on_lab_thread(teacher, [lab.cookie], self.lab_texts, None, lab)
        if self.room.by_id.get(lab.id) is not lab:
            raise labs.LabRefusal(f"refused: lab {lab_id!r} closed meanwhile")
        self.shown = lab.id  # from now on its frames and events go to every page, after these
        for text in texts:
            self.broadcast_text(text)
        return True, f"the class sees {lab.name}'s lab"

    def tick_labs(self, frame_time: float) -> None:
        """On the loop, at each frame: every running lab stepped to the frame's time (within the tick's budgets,
        LabRoom.tick), its news to its pages (the shown lab's to every page): its messages if it changed, its
        frame, its events; the labs idle past their time ended."""
        started, cpu = time.perf_counter(), time.thread_time()
        for lab in self.room.expire():
            self.lab_gone(lab, f"lab {lab.id} ended: {labs.IDLE / 60:g} minutes idle")
            self.lab_pages.pop(lab.cookie, None)
        out: List[Optional[LabOutput]] = self.room.tick(self.lab_news, frame_time, self.tick_budget,
                                                        1.0 / self.frame_rate)
        for news in out:
            if news is not None:
                self.send_news(news)
        seconds, cpu = time.perf_counter() - started, time.thread_time() - cpu
        if cpu >= self.tick_budget or seconds >= 1.0 / self.frame_rate:
            rospy.logwarn_throttle(60, f"web view: a tick of {len(out)} of {len(self.room.labs)} labs took "
                                       f"{1000 * seconds:.1f} ms, {1000 * cpu:.1f} ms of CPU time (its budget "
                                       f"{1000 * self.tick_budget:.0f} ms, a frame's {1000 / self.frame_rate:.0f} "
                                       "ms of wall time at most)")
        if self.class_due and not self.class_busy and any(page.control for page in self.pages):
            self.class_due, self.class_busy = False, True
            asyncio.ensure_future(self.send_class())

    def lab_news(self, lab: labs.Lab) -> Optional[LabOutput]:
        """Its lock held (LabRoom.tick): its news, or None while the lab thread works for it (they wait:
        on_lab_thread)."""
        return None if lab.cookie in self.lab_busy else self.take_news(lab)

    def send_news(self, news: LabOutput) -> None:
        """A lab's news to its pages (the shown lab's to every page): its messages if it changed, then its
        frame and its events."""
        lab, frame, events, texts = news
        if texts is not None:
            self.lab_changed(lab, texts)
        pages = list(self.pages) if self.shown == lab.id else self.pages_of(lab)
        for page in pages:
            if frame is not None:
                page.offer(frame)
            if events is not None:
                page.reply_text(events)
        if lab.results_changed:
            self.class_due = True

    def take_news(self, lab: labs.Lab, messages: bool = False) -> LabOutput:
        """Its lock held: its frame of the samples since its last, its events, its messages if it changed (or
        `messages`: after each request of it)."""
        samples = lab.take_samples()
        frame = None
        if samples:
            lab.seq += 1
            frame = websocket_text_frame(lab_frame_message(lab.id, lab.seq, samples))
        whole, records = lab.take_events()
        events = lab_events_message(lab.id, records, whole) if whole or records else None
        return lab, frame, events, self.lab_messages(lab) if lab.changed or messages else None

    async def send_class(self) -> None:
        """The class's results and curves (on the class thread) to the teacher's pages, at most every
        CLASS_PERIOD s."""
        try:
            text = await asyncio.get_running_loop().run_in_executor(self.class_thread, self.class_message)
            if text != self.class_text:
                self.class_text = text
                self.broadcast_text(text, control_only=True)
            await asyncio.sleep(CLASS_PERIOD)
        finally:
            self.class_busy = False

    def class_message(self) -> str:
        results = self.room.class_results()
        with self.room.lock:
            by_id = dict(self.room.by_id)
        lesson = labs.lesson_of(results, by_id)
        on_lesson = [r for r in results if r["lab"] in by_id and by_id[r["lab"]].origin == lesson]
        curves = self.curves.compute(lesson, on_lesson) if lesson else {}
        return labs.class_message(results, lesson, by_id, curves)

    def lab_zip(self, lab: labs.Lab) -> bytes:
        """On a worker thread: the lab's config and the files `simulate` writes of its run so far, zipped."""
        with lab.lock:
            config, duration = lab.config, lab.sampled_t
        with tempfile.TemporaryDirectory(prefix="rbs_lab_") as folder:
            path = os.path.join(folder, "config.yaml")
            with open(path, "w") as file:
                file.write(config)
            run = os.path.join(folder, "run")
            os.mkdir(run)
            done = subprocess.run([self.simulate, path, "--duration", repr(duration), "--out-dir", run],
                                  capture_output=True, text=True, timeout=SIMULATE_TIMEOUT, check=False)
            if done.returncode != 0:
                raise RuntimeError(f"simulate: {(done.stderr.strip().splitlines() or ['failed'])[-1]}")
            packed = io.BytesIO()
            with zipfile.ZipFile(packed, "w", zipfile.ZIP_DEFLATED) as archive:
                archive.write(path, "config.yaml")
                for name in sorted(os.listdir(run)):
                    archive.write(os.path.join(run, name), name)
            return packed.getvalue()

    # --- HTTP -----------------------------------------------------------------------------------------------
    def application(self) -> tornado.web.Application:
        root = os.path.realpath(self.web_root)
        missing = [name for name in (*WEB_FILES, LOGIN_PAGE) if not os.path.isfile(os.path.join(root, name))]
        if missing:
            raise FileNotFoundError(f"web view: {', '.join(missing)} not in {root}")
        return tornado.web.Application(
            [(r"/ws", Page, {"view": self}),
             (r"/()", File, {"path": root, "default_filename": "index.html", "view": self}),
             (r"/(" + "|".join(re.escape(name) for name in WEB_FILES if name != "index.html") + ")", File,
              {"path": root, "view": self}),
             (r"/login", Login, {"view": self}),
             (r"/qr\.svg", QrCode, {"view": self}),
             (r"/lab/([0-9a-f]{1,40})\.zip", LabZip, {"view": self})],
            # Beyond the size tornado closes the connection; a page that answers no ping for 20 s is closed.
            websocket_max_message_size=64 * MAX_REQUEST_BYTES, websocket_ping_interval=5, websocket_ping_timeout=20,
            # A POST (the login's, the only one) carries the _xsrf cookie's value as a field: another site's form
            # cannot. GET and the WebSocket's handshake are not checked.
            xsrf_cookies=True, xsrf_cookie_kwargs={"httponly": True, "samesite": "Strict", "path": "/login"},
            template_path=root, compiled_template_cache=False, log_function=log_request)

    def offer_only(self, families: Set[int]) -> None:
        """The addresses offered: only those of the families it listens on."""
        listened = [u for u in self.watch_urls if (socket.AF_INET6 if "[" in u else socket.AF_INET) in families]
        self.watch_urls = listened or self.watch_urls

    def urls(self) -> Tuple[str, str]:
        """The class's address and the teacher's login form."""
        base = self.watch_urls[0]
        return base, f"{base}login"

    def is_token(self, given: str) -> bool:
        """Whether `given` is this view's token (none without ~control), in time that tells nothing of it."""
        return bool(self.token) and bool(given) and hmac.compare_digest(given.encode(), self.token.encode())

    def note_login_refusal(self, address: str, refusal: str) -> None:
        """A refused login's line, at most every LOGIN_LOG_PERIOD s (a guesser's would fill the log), with the
        count of those not logged since; never the token given."""
        self.login_refusals += 1
        now = time.monotonic()
        if now < self.login_logged_at + LOGIN_LOG_PERIOD:
            return
        more = self.login_refusals - 1
        rospy.logwarn(f"web view: login from {address}: {refusal}{f' ({more} more refused since)' if more else ''}")
        self.login_refusals, self.login_logged_at = 0, now


def log_request(handler: tornado.web.RequestHandler) -> None:
    """tornado's access log line without the query (an address someone typed a token into) and without any
    body (the login form's token): rospy writes this log to a file every user can read."""
    request = handler.request
    status = handler.get_status()
    log = tornado.log.access_log.info if status < 400 else tornado.log.access_log.warning
    log("%d %s %s (%s) %.2fms", status, request.method, request.path, request.remote_ip,
        1000.0 * request.request_time())


def own_addresses() -> List[str]:
    """This machine's IPv4 and global IPv6 addresses (the loopback's first), from the kernel's tables."""
    import fcntl
    import struct
    found: List[str] = []
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as probe:
        for _, name in socket.if_nameindex():
            try:  # SIOCGIFADDR: the interface's IPv4 address
                packed = fcntl.ioctl(probe.fileno(), 0x8915, struct.pack("256s", name.encode()[:15]))
                found.append(socket.inet_ntoa(packed[20:24]))
            except OSError:
                pass  # no IPv4 address on it
    try:
        with open("/proc/net/if_inet6") as table:
            for line in table:
                raw, scope = line.split()[0], int(line.split()[3], 16)
                if scope == 0:  # global: a link-local one needs its interface named in the address
                    found.append(socket.inet_ntop(socket.AF_INET6, bytes.fromhex(raw)))
    except OSError:
        pass  # no IPv6
    loopback = [a for a in found if a.startswith("127.") or a == "::1"]
    return loopback + [a for a in found if a not in loopback]


def refuse_foreign_host(handler: tornado.web.RequestHandler, view: "WebView") -> None:
    """A request must name this machine (one of its names or addresses) as its host: a site whose name was
    made to point here (DNS rebinding) gets neither the page nor a connection."""
    host = handler.request.host.lower()
    if host not in view.local_hosts and not loopback_literal(host, view.port):
        raise tornado.web.HTTPError(403, "host %s is not this web view's", handler.request.host)


def loopback_literal(host: str, port: int) -> bool:
    """A loopback address written as such with this port (127.0.1.1, which Debian gives this machine's name,
    or any other of 127/8): a numeric host no rebinding site can have."""
    name, _, given = host.rpartition(":")
    try:
        return given == str(port) and ipaddress.ip_address(name.strip("[]")).is_loopback
    except ValueError:
        return False


class File(tornado.web.StaticFileHandler):
    """The page's files, never cached (a rebuilt package serves its new page), with nothing but this server
    allowed to the page (no script, style or connection from anywhere else). An address's ?token= gives no
    control (the page says where the token goes: Login)."""

    _request_summary = summary_without_query

    def initialize(self, path: str, default_filename: Optional[str] = None,
                   view: Optional["WebView"] = None) -> None:
        super().initialize(path, default_filename)
        self.view = view

    async def get(self, path: str, include_body: bool = True) -> None:
        if path == "" and not self.get_cookie(LAB_COOKIE):
            # The page's lab is the cookie's: a random secret its script cannot read; a reload keeps it.
            self.set_cookie(LAB_COOKIE, secrets.token_urlsafe(18), path="/", httponly=True, samesite="Strict",
                            expires_days=1)
        await super().get(path, include_body)

    def prepare(self) -> None:
        if self.view:
            refuse_foreign_host(self, self.view)

    def set_extra_headers(self, path: str) -> None:
        self.set_header("Cache-Control", "no-store")
        self.set_header("X-Content-Type-Options", "nosniff")
        self.set_header("Referrer-Policy", "no-referrer")
        self.set_header("Content-Security-Policy",
                        "default-src 'none'; script-src 'self'; style-src 'self'; connect-src 'self'; "
                        "img-src 'self'; frame-ancestors 'none'")


class Login(tornado.web.RequestHandler):
    """GET /login: the teacher's form (web/login.html: one password field). POST /login with this view's token:
    the token as a cookie that only the page's WebSocket gets back (the page's script cannot read it), then
    303 to the page; a wrong or empty one: the form again with its one-line refusal (403), logged without it.
    The token never in an address: a browser keeps every address it visits in its history."""

    _request_summary = summary_without_query

    def initialize(self, view: "WebView") -> None:
        self.view = view

    def prepare(self) -> None:
        refuse_foreign_host(self, self.view)

    def set_default_headers(self) -> None:
        self.set_header("Cache-Control", "no-store")
        self.set_header("X-Content-Type-Options", "nosniff")
        self.set_header("Referrer-Policy", "no-referrer")
        self.set_header("Content-Security-Policy", "default-src 'none'; style-src 'self'; img-src 'self'; "
                                                   "form-action 'self'; frame-ancestors 'none'")

    def get(self) -> None:
        self.form("" if self.view.token else NO_CONTROL)

    def post(self) -> None:
        given = self.get_body_argument("token", "") or ""
        if self.view.is_token(given):
            self.set_cookie(CONTROL_COOKIE, given, path="/ws", httponly=True, samesite="Strict", expires_days=1)
            rospy.loginfo(f"web view: login from {self.request.remote_ip}: control")
            self.redirect("/", status=303)
            return
        refusal = (NO_CONTROL if not self.view.token else
                   "refused control: no token given (the one the web view printed on its terminal)" if not given
                   else "refused control: not this web view's token (a new one at each start: see its terminal)")
        self.view.note_login_refusal(self.request.remote_ip or "", refusal)
        self.set_status(403)
        self.form(refusal)

    def form(self, refusal: str) -> None:
        self.render(LOGIN_PAGE, refusal=refusal, control=bool(self.view.token))


class QrCode(tornado.web.RequestHandler):
    """The address a student's phone uses (the first of watch_urls), as a QR code the teacher's page shows."""

    _request_summary = summary_without_query

    def initialize(self, view: "WebView") -> None:
        self.view = view

    def prepare(self) -> None:
        refuse_foreign_host(self, self.view)

    def get(self) -> None:
        image = qrcode.make(self.view.watch_urls[0], image_factory=qrcode.image.svg.SvgPathImage, border=2)
        svg = io.BytesIO()
        image.save(svg)
        self.set_header("Content-Type", "image/svg+xml")
        self.set_header("Cache-Control", "no-store")
        self.set_header("X-Content-Type-Options", "nosniff")
        self.write(svg.getvalue())


class LabZip(tornado.web.RequestHandler):
    """GET /lab/<id>.zip: the cookie's own lab (any other is 404): its config.yaml and the files `simulate
    config.yaml --duration <its last sample's t>` writes, its run so far."""

    _request_summary = summary_without_query

    def initialize(self, view: "WebView") -> None:
        self.view = view

    def prepare(self) -> None:
        refuse_foreign_host(self, self.view)

    async def get(self, lab_id: str) -> None:
        lab = self.view.room.of(self.get_cookie(LAB_COOKIE, "") or "")
        if lab is None or not hmac.compare_digest(lab.id, lab_id):
            raise tornado.web.HTTPError(404, "no lab %s of this page's", lab_id)
        if not self.view.simulate:
            raise tornado.web.HTTPError(503, "simulate not found (CMAKE_PREFIX_PATH, ~simulate)")
        self.view.room.touch(lab)
        async with self.view.downloads:
            try:
                data = await asyncio.get_running_loop().run_in_executor(None, self.view.lab_zip, lab)
            except (RuntimeError, OSError, subprocess.SubprocessError) as error:
                rospy.logwarn(f"web view: lab {lab.id}'s download: {error}")
                raise tornado.web.HTTPError(500, "%s", error) from None
        self.set_header("Content-Type", "application/zip")
        self.set_header("Content-Disposition", f'attachment; filename="lab-{lab.id}.zip"')
        self.set_header("Cache-Control", "no-store")
        self.set_header("X-Content-Type-Options", "nosniff")
        self.write(data)


class SizeGuard(tornado.httputil.HTTPMessageDelegate):
    """Answers a request whose target or header lines are too long with 414 or 431 (RFC 6585), or whose
    Content-Length is over MAX_BODY with 413, and closes its connection, before any handler sees it (tornado
    itself answers a chunked body over MAX_BODY 400)."""

    def __init__(self, inner: tornado.httputil.HTTPMessageDelegate,
                 connection: tornado.httputil.HTTPConnection) -> None:
        self.inner = inner
        self.connection = connection
        self.refused = False

    def headers_received(self, start_line: Any, headers: tornado.httputil.HTTPHeaders) -> Optional[Any]:
        size = sum(len(name) + len(value) + 4 for name, value in headers.get_all())
        length = headers.get("Content-Length", "0")
        status = (414, "URI Too Long") if len(start_line.path) > MAX_URL else (
            (431, "Request Header Fields Too Large") if size > MAX_HEADERS else
            (413, "Content Too Large") if length.isdigit() and int(length) > MAX_BODY else None)
        if status is None:
            return self.inner.headers_received(start_line, headers)
        self.refused = True
        body = f"{status[0]} {status[1]}\n".encode()
        self.connection.write_headers(
            tornado.httputil.ResponseStartLine("HTTP/1.1", *status),
            tornado.httputil.HTTPHeaders({"Content-Type": "text/plain", "Content-Length": str(len(body)),
                                          "Connection": "close"}), body)
        self.connection.finish()
        return None

    def data_received(self, chunk: bytes) -> Optional[Any]:
        return None if self.refused else self.inner.data_received(chunk)

    def finish(self) -> None:
        if not self.refused:
            self.inner.finish()

    def on_connection_close(self) -> None:
        if not self.refused:
            self.inner.on_connection_close()


class Server(tornado.httpserver.HTTPServer):
    def start_request(self, server_conn: object,
                      request_conn: tornado.httputil.HTTPConnection) -> tornado.httputil.HTTPMessageDelegate:
        return SizeGuard(super().start_request(server_conn, request_conn), request_conn)


def listening_sockets(host: str, port: int) -> List[socket.socket]:
    """The sockets to listen on: every address (0.0.0.0, :: or "") is IPv4's and, where the machine has
    IPv6, IPv6's (a socket of its own, IPv6 only: tornado sets IPV6_V6ONLY); else the host's."""
    if host not in ("0.0.0.0", "::", ""):
        return tornado.netutil.bind_sockets(port, host)
    sockets = tornado.netutil.bind_sockets(port, "0.0.0.0", family=socket.AF_INET)
    if socket.has_ipv6 and os.path.exists("/proc/net/if_inet6"):
        try:
            sockets += tornado.netutil.bind_sockets(port, "::", family=socket.AF_INET6)
        except OSError as error:  # IPv6 disabled: its addresses are not offered
            rospy.logwarn(f"web view: not listening on IPv6 ({error}): IPv4 addresses alone")
    return sockets


def frame_timer(view: WebView) -> None:
    """view.flush at every frame of ~frame_rate, given the frame's time on the timer's schedule (the loop's
    monotonic clock, the labs' too): a call the loop delays steps the labs to its frame's time all the same,
    so that each frame brings a running lab the same count of samples whatever the delay (stepped to its call's
    time, a lab whose samples fall near the frames' times would get two in one frame, none in the next). A call
    late by a whole frame skips to the schedule's next, as tornado's PeriodicCallback does."""
    loop = asyncio.get_running_loop()
    period = 1.0 / view.frame_rate
    start = loop.time()

    def frame(index: int) -> None:
        try:
            view.flush(start + index * period)
        except Exception:  # the frames go on, as a PeriodicCallback's do
            tornado.log.app_log.error("web view: a frame failed", exc_info=True)
        index = max(index + 1, math.floor((loop.time() - start) / period) + 1)
        loop.call_at(start + index * period, frame, index)

    loop.call_at(start + period, frame, 1)


async def serve(view: WebView) -> None:
    """Runs the server on this thread's event loop until ROS shuts down."""
    view.loop = tornado.ioloop.IOLoop.current()
    view.line_came = asyncio.Event()
    view.downloads = asyncio.Semaphore(MAX_DOWNLOADS)
    done = asyncio.Event()
    try:
        # An idle or half-sent request's connection is closed HEAD_TIMEOUT s after it began.
        server = Server(view.application(), xheaders=False, max_header_size=READ_HEAD_LIMIT,
                        idle_connection_timeout=HEAD_TIMEOUT, body_timeout=HEAD_TIMEOUT, max_body_size=MAX_BODY)
        sockets = listening_sockets(view.host, view.port)
    except OSError as error:
        rospy.logfatal(f"web view: cannot listen on {view.host}:{view.port}: {error}")
        sys.exit(1)
    server.add_sockets(sockets)
    view.offer_only({s.family for s in sockets})
    view.start_ros()
    frame_timer(view)
    watch, login = view.urls()
    rospy.loginfo(f"web view of {view.node} on {view.host}:{view.port}: watch at {watch}")
    if view.host not in ("127.0.0.1", "localhost"):
        rospy.logwarn(f"web view: open to the network on {view.host}:{view.port} (plain HTTP): the class watches "
                      f"at {' or '.join(view.watch_urls)}")
    if view.control:
        # Standard output alone: the launching terminal. rospy's log would put it on /rosout and in log files
        # every user can read; an address would keep it in the browser's history: the teacher types it in.
        print(f"[INFO] web view: control (keep it to the teacher): {login} token {view.token}", flush=True)
    rospy.on_shutdown(lambda: view.loop.add_callback(done.set))
    await done.wait()


def main() -> None:
    rospy_on_python39()  # Debian 11: rospy.signal_shutdown (the handlers below) calls Thread.isAlive
    rospy.init_node("web", disable_signals=True)
    # disable_signals: rospy's own handlers would not end the server's loop; these end ROS, which ends it.
    signal.signal(signal.SIGINT, lambda *_: rospy.signal_shutdown("SIGINT"))
    signal.signal(signal.SIGTERM, lambda *_: rospy.signal_shutdown("SIGTERM"))
    # Every open file the system lets it have: a class's pages and slow clients each hold a socket (a
    # desktop's soft limit of 1024 would stop it accepting any), until HEAD_TIMEOUT closes the slow.
    _, hard = resource.getrlimit(resource.RLIMIT_NOFILE)
    resource.setrlimit(resource.RLIMIT_NOFILE, (hard, hard))
    asyncio.run(serve(WebView()))


if __name__ == "__main__":
    main()
