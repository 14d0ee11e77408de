// The web view's page: the followed world from the side, as the text poses its problems, and live plots.
// Everything comes from this page's server (scripts/web_view.py) over one WebSocket; nothing from elsewhere.
// What is drawn is kept in window.rbs (the browser test reads it): the latest frame, each body's drawn state
// and place on the canvas, the node's events, each plot's last points, marks and time axis, and every text
// drawn on a canvas with its box. When something happened (a grip, a finish, a restart) and the state then
// come from the node's events: the page computes no instant.
"use strict";

const PLOT_WINDOW = 10; // s of simulated time in the plots, as the rviz panel's
const KEEP = 12; // s of points kept per body
const MIN_RADIUS = 10; // px: a body is drawn at least 20 px across (larger than to scale, its panel says so)
// The plots' lines: white, yellow and teal, none a body's colour (a type's own plot lines excepted).
const PLOT_COLOURS = { first: "#f2f2f2", second: "#ffe066", third: "#3fd0c0" };
const TEXT_SCALES = [0.8, 1, 1.25, 1.5, 2];
const LINE_SHOWN = 10000; // ms a reply's or a node's line stays on the page
const FINISH_DASH = [3, 5]; // a finish's dotted line
// A restart with one of these causes begins a run (the node's get_events forgets what came before): the plots
// lose what came before it, and their time axis counts from it.
const RUN_STARTS = ["reset", "config"];

// A world the page can show: the class's (the node's, through the server), the student's own lab, or the lab the
// teacher shows the class (lab.js). Each keeps what it was sent; the page draws one of them, `showing`.
function newStore(kind) {
  return {
    kind,
    world: null, // {source, paused, settings, bodies: {name: its keys}, parts, part}
    paused: false,
    latest: {}, // body -> its last state
    points: {}, // body -> [{t, ...the plotted values}] of its states
    events: {}, // body -> its events of the run, oldest first
    eventKeys: new Set(),
    resetT: -Infinity, // the run's start (a reset): no state at or before it is plotted
  };
}
const stores = { class: newStore("class"), lab: newStore("lab"), shown: newStore("shown") };
let showing = stores.class;
const rbs = {
  frames: 0, lastFrame: null, control: false, line: "", lineOk: true,
  drawn: {}, plotLast: {}, panels: {}, replies: [], sent: [], finishes: {}, texts: [], ended: false,
  shared: {}, description: null, stores, showing: "class",
};
// What is drawn: the shown world, its pause and its events.
Object.defineProperty(rbs, "world", { get: () => showing.world, enumerable: true });
Object.defineProperty(rbs, "paused", { get: () => showing.paused, enumerable: true });
Object.defineProperty(rbs, "events", { get: () => showing.events, enumerable: true });
window.rbs = rbs;
// The plotted states' t, a reset's earlier ones gone.
rbs.times = (body) => (showing.points[body] || []).map((p) => p.t);

const keptLines = {}; // the most lines each panel's label had at its size (keepLines)
const messageHooks = []; // lab.js's and class.js's: each message after view.js took it (onMessage)
const drawHooks = []; // theirs: each drawing of the page (onDraw)
const linesShownElsewhere = new Set(); // ops whose replies lab.js shows in its own line
let socket = null;
let nextId = 1;
let drawPending = false;
let lineTimer = null;
let ownChoice = false; // this page chose its plotted body itself (a student's: until the teacher chooses again)

const $ = (id) => document.getElementById(id);

// --- physics the labels and plots show (docs/rviz.md: the panel's) -----------------------------------------
// A body's entry in types.js, and what the server's description (body_types.json) says of its type.
function typeOf(b) { return BODY_TYPES[b.type] || null; }
function described(b) { return (rbs.description && rbs.description.types[b.type]) || { keys: [], races: false }; }
// A key's value with its unit as the description gives it ("1 m", "2000 N/m", "0.3" for a pure number).
function withUnit(b, key) {
  const found = described(b).keys.find((k) => k.name === key);
  return found && found.unit ? `${b[key]} ${found.unit}` : `${b[key]}`;
}
// A body's title: its name, with its kind (its entry's word, else its type) where the name is not that.
function titleOf(name, b) {
  const type = typeOf(b);
  const kind = type && type.kind ? type.kind(b) : b.type;
  return name === kind ? name : `${name} (${kind})`;
}
// The steepest slope static friction holds (its entry's tanCritical).
function criticalAngle(b) { return Math.atan(typeOf(b).tanCritical(b)); }
function deg(rad) { return (rad * 180 / Math.PI).toFixed(1) + "\u00b0"; }
// Three decimals, without the "-0.000" of a tiny negative number.
function fixed3(x) { return Math.abs(x) < 0.0005 ? "0.000" : x.toFixed(3); }
function ordinal(n) {
  const tens = n % 100;
  const last = n % 10;
  const suffix = (tens >= 11 && tens <= 13) || last === 0 || last > 3 ? "th" : ["", "st", "nd", "rd"][last];
  return `${n}${suffix}`;
}

// --- the connection --------------------------------------------------------------------------------------
function connect() {
  const scheme = location.protocol === "https:" ? "wss" : "ws";
  socket = new WebSocket(`${scheme}://${location.host}/ws`); // a teacher's page: its cookie says so
  socket.onmessage = (event) => receive(JSON.parse(event.data));
  socket.onclose = () => {
    // A replay's end may end the web view with it: the last frame stays, and says so.
    const world = stores.class.world;
    if (world && (world.source === "replay" || world.source === "ended")) rbs.ended = true;
    else setStatus("disconnected: the web view is gone (retrying)", true);
    scheduleDraw();
    setTimeout(connect, 2000);
  };
}

function onMessage(hook) { messageHooks.push(hook); }

// The page shows `store` (one of stores): its world is drawn and plotted.
function showStore(store) {
  showing = store;
  rbs.showing = store.kind;
  rbs.drawn = {};
  rbs.panels = {};
  if (store.world) fillSelects();
  scheduleDraw();
}

function receive(m) {
  if (m.type === "frame") {
    rbs.frames += 1;
    rbs.lastFrame = m;
    rbs.ended = false;
    for (const [body, states] of Object.entries(m.states)) for (const s of states) addState(stores.class, body, s);
  } else if (m.type === "hello") {
    rbs.control = m.control;
    rbs.description = m.description; // the core's body_types.json: every key's unit, whether a type races
    $("controls").hidden = !m.control;
    document.body.classList.toggle("control", m.control);
    showAddresses(m.addresses || []);
    rbs.shared = m.view || {};
  } else if (m.type === "world") {
    stores.class.world = m;
    stores.class.paused = m.paused;
    rbs.ended = m.source === "ended";
    for (const body of Object.keys(stores.class.latest)) if (!(body in m.bodies)) delete stores.class.latest[body];
    fillSelects();
    showPart(m.parts || [], m.part || "");
  } else if (m.type === "view") {
    rbs.shared = { plot_body: m.plot_body };
    // A student's page takes the teacher's new choice over its own; the teacher's page has it already (and
    // an echo of an earlier choice must not undo a later one).
    if (!rbs.control) {
      ownChoice = false;
      followTeacher();
    }
  } else if (m.type === "events") {
    setEvents(stores.class, m.events, m.all);
  } else if (m.type === "paused") {
    stores.class.paused = m.paused;
  } else if (m.type === "reply") {
    rbs.replies.push(m);
    if (!m.ok) showKeyValue(); // a refused value: the field shows the one that runs again
    const sent = rbs.sent.find((r) => r.id === m.id);
    if (!sent || !linesShownElsewhere.has(sent.op)) showLine(m.line, m.ok);
  } else if (m.type === "line") {
    showLine(m.line, false); // the node's WARN line: sent to the teacher's page alone
  }
  for (const hook of messageHooks) hook(m);
  scheduleDraw();
}

// Events for a store: `all`, the run's events as the server keeps them, which replace the store's.
function setEvents(store, records, all) {
  if (all) {
    for (const body of Object.keys(store.events)) delete store.events[body];
    store.eventKeys.clear();
    store.resetT = -Infinity;
  }
  for (const e of records) addEvent(store, e);
}

// A store's world starts again at t = 0 (a lab's change or reset): what it had goes.
function restartStore(store) {
  for (const key of ["latest", "points", "events"]) for (const body of Object.keys(store[key])) delete store[key][body];
  store.eventKeys.clear();
  store.resetT = -Infinity;
}

function addState(store, body, s) {
  store.latest[body] = s;
  const b = store.world && store.world.bodies[body];
  const type = b && typeOf(b);
  // A reset's restarts come on their own topic, and may overtake states from before it: those are not plotted.
  if (!type || s.t <= store.resetT) return;
  const list = (store.points[body] = store.points[body] || []);
  list.push(plotted(type, b, s, s.t));
  while (list.length && list[0].t < s.t - KEEP) list.shift();
  trimEvents(store, body, s.t - KEEP);
}

// A plotted point of a state at t: what the body's plots show of it, the energy split into its parts.
function plotted(type, b, s, t) {
  const kinetic = type.kinetic(b, s);
  const p = { t, energy: s.energy, kinetic, potential: s.energy - kinetic };
  type.plotValues(b, s, p);
  return p;
}

// --- the node's events -------------------------------------------------------------------------------------
// An event's role, as the description declares its kind: "finish", "restart" or "".
function roleOf(e) {
  const type = rbs.description && rbs.description.types[e.type];
  const kind = type && (type.event_kinds || []).find((k) => k.name === e.kind);
  return kind ? kind.role : "";
}
function startsRun(e) { return roleOf(e) === "restart" && RUN_STARTS.includes(e.values.cause); }
function eventKey(e) {
  return JSON.stringify([e.t, e.body, e.kind, Object.keys(e.values).sort().map((k) => [k, e.values[k]])]);
}

// Each event once (the server's replay of the run and the topic may both bring it), in time order; a run's
// start takes what came before it away.
function addEvent(store, e) {
  const key = eventKey(e);
  if (store.eventKeys.has(key) || e.t < store.resetT) return;
  store.eventKeys.add(key);
  const events = store.events;
  const list = (events[e.body] = events[e.body] || []);
  let i = list.length;
  while (i > 0 && list[i - 1].t > e.t) i -= 1;
  list.splice(i, 0, e);
  if (startsRun(e) && e.t > store.resetT) {
    store.resetT = e.t;
    const points = store.points;
    for (const body of Object.keys(points)) points[body] = points[body].filter((p) => p.t > e.t);
    // At its instant too, what came before it is of the run before (the step that ended at the reset).
    for (const body of Object.keys(events)) events[body] = events[body].filter((f) => f.t > e.t || f === e);
  }
}

// Before `cutoff`, only its last finish and last restart (the finish a waiting racer shows; where the time
// axis of its plots counts from).
function trimEvents(store, body, cutoff) {
  const list = store.events[body];
  if (!list || !list.length || list[0].t >= cutoff) return;
  const last = new Set();
  const kept = [];
  for (let i = list.length - 1; i >= 0; i -= 1) {
    const role = roleOf(list[i]);
    if (list[i].t >= cutoff || (role && !last.has(role))) {
      kept.push(list[i]);
      if (list[i].t < cutoff) last.add(role);
    } else {
      store.eventKeys.delete(eventKey(list[i]));
    }
  }
  store.events[body] = kept.reverse();
}

// The finish a body's label shows: its last since its lap started (a racer waiting at the end of its slope).
function finishOf(name) {
  const list = showing.events[name] || [];
  for (let i = list.length - 1; i >= 0; i -= 1) {
    const role = roleOf(list[i]);
    if (role === "restart") return null;
    if (role === "finish") return list[i];
  }
  return null;
}

// Whether the lesson is a race for this body: its plots count lap times, and mark its finishes.
function races(b) { return Boolean(rbs.world.settings.race) && Boolean(described(b).races); }

function send(request) {
  request.id = nextId++;
  rbs.sent.push({ op: request.op, id: request.id });
  if (socket && socket.readyState === WebSocket.OPEN) socket.send(JSON.stringify(request));
  return request.id;
}

function showLine(text, ok) {
  rbs.line = text;
  rbs.lineOk = ok;
  const el = $("line");
  el.textContent = text;
  el.className = ok ? "ok" : "refused";
  clearTimeout(lineTimer);
  lineTimer = setTimeout(() => { el.textContent = ""; rbs.line = ""; scheduleDraw(); }, LINE_SHOWN);
}

function setStatus(text, stopped) {
  const el = $("status");
  el.textContent = text;
  el.className = stopped ? "stopped" : "";
}

function showAddresses(urls) {
  $("class-address").hidden = !urls.length;
  if (!urls.length) return;
  // The loopback alone: no other machine reaches it, and a QR code of it would mislead a phone.
  const local = urls.every((u) => /^http:\/\/(127\.|\[::1\])/.test(u));
  const lines = local ? [...urls, "this machine only: web_host:=0.0.0.0 opens it to the class"] : urls;
  $("addresses").replaceChildren(...lines.map((u) => {
    const item = document.createElement("li");
    item.textContent = u;
    return item;
  }));
  $("qr").hidden = local;
  if (!local) $("qr").src = "qr.svg";
}

// --- controls ----------------------------------------------------------------------------------------------
function fillSelects() {
  // The teacher's keys are the class world's; the plots, the shown world's.
  for (const [id, world] of [["set-body", stores.class.world], ["plot-body", showing.world]]) {
    if (!world) continue;
    const names = Object.keys(world.bodies);
    const sel = $(id);
    const was = sel.value;
    sel.replaceChildren(...names.map((n) => new Option(n, n)));
    if (names.includes(was)) sel.value = was;
  }
  if (!ownChoice) followTeacher();
  fillKeys();
}

// The lesson part the world is in, for every page; the teacher's choice of another (lesson.launch's parts
// these bodies can take: the server sets their keys and starts the race again).
function showPart(parts, part) {
  $("part").textContent = part ? `part: ${part}` : "";
  const sel = $("part-choice");
  sel.hidden = parts.length < 2;
  const names = part ? parts : ["(keys changed)", ...parts];
  sel.replaceChildren(...names.map((n) => new Option(n === part || parts.includes(n) ? `part ${n}` : n, n)));
  sel.value = part || names[0];
}

function followTeacher() {
  const body = rbs.shared.plot_body;
  if (body && showing.world && body in showing.world.bodies) $("plot-body").value = body;
}

function fillKeys() {
  const world = stores.class.world;
  const b = world && world.bodies[$("set-body").value];
  if (!b) return;
  const sel = $("set-key");
  const was = sel.value;
  const keys = described(b).keys.filter((k) => k.lesson).map((k) => k.name);
  sel.replaceChildren(...keys.map((k) => new Option(k, k)));
  if (keys.includes(was)) sel.value = was;
  showKeyValue();
}

function showKeyValue() {
  // The value that runs, unless the teacher is typing one (a world update comes whenever anything changes).
  const world = stores.class.world;
  const b = world && world.bodies[$("set-body").value];
  const key = $("set-key").value;
  if (!b || !key) return;
  if (document.activeElement !== $("set-value")) $("set-value").value = String(b[key]);
  const found = described(b).keys.find((k) => k.name === key);
  const unit = found ? found.unit : "";
  $("set-unit").textContent = unit === "rad" ? `rad (${deg(Number(b[key]))})` : unit;
}

function textScale(step) {
  let i = TEXT_SCALES.indexOf(Number(localStorage.getItem("rbs_text_scale") || 1));
  i = Math.min(TEXT_SCALES.length - 1, Math.max(0, (i < 0 ? 1 : i) + step));
  localStorage.setItem("rbs_text_scale", String(TEXT_SCALES[i]));
  document.documentElement.style.setProperty("--text-scale", String(TEXT_SCALES[i]));
  scheduleDraw();
}

function wireControls() {
  $("pause").onclick = () => send({ op: "pause" });
  $("run").onclick = () => send({ op: "run" });
  $("reset").onclick = () => send({ op: "reset" });
  $("step").onclick = () => send({ op: "step", steps: Number($("steps").value) });
  $("set").onclick = () => send({ op: "set", body: $("set-body").value, key: $("set-key").value,
                                  value: Number($("set-value").value) });
  $("set-body").onchange = fillKeys;
  $("part-choice").onchange = () => {
    if (stores.class.world.parts.includes($("part-choice").value)) send({ op: "part", part: $("part-choice").value });
  };
  $("set-key").onchange = showKeyValue;
  $("plot-body").onchange = () => {
    ownChoice = true;
    if (rbs.control) send({ op: "view", plot_body: $("plot-body").value }); // the class plots it too
    scheduleDraw();
  };
  $("text-smaller").onclick = () => textScale(-1);
  $("text-larger").onclick = () => textScale(1);
  $("full-screen").onclick = () => {
    if (document.fullscreenElement) document.exitFullscreen();
    else document.documentElement.requestFullscreen();
  };
  document.addEventListener("fullscreenchange", () => {
    $("full-screen").textContent = document.fullscreenElement ? "Leave full screen" : "Full screen";
  });
  window.addEventListener("resize", scheduleDraw);
  $("class-address").addEventListener("toggle", scheduleDraw);
  textScale(0);
}

// --- drawing -----------------------------------------------------------------------------------------------
function scheduleDraw() {
  if (drawPending) return;
  drawPending = true;
  requestAnimationFrame(() => { drawPending = false; draw(); });
}

// The page's text size (view.css): every canvas text is drawn at it, none smaller.
function textPx() { return parseFloat(getComputedStyle(document.documentElement).fontSize); }
function font(bold) { return `${bold ? "bold " : ""}${textPx()}px 'DejaVu Sans', sans-serif`; }

function fitCanvas(canvas, height) {
  const ratio = window.devicePixelRatio || 1;
  const width = canvas.clientWidth;
  height = Math.max(1, Math.floor(height));
  canvas.style.height = height + "px";
  if (canvas.width !== Math.round(width * ratio) || canvas.height !== Math.round(height * ratio)) {
    canvas.width = Math.round(width * ratio);
    canvas.height = Math.round(height * ratio);
  }
  const ctx = canvas.getContext("2d");
  ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
  ctx.clearRect(0, 0, width, height);
  ctx.canvasId = canvas.id;
  return ctx;
}

// Every text on a canvas goes through here: drawn with its top-left at (x, y), its box kept in rbs.texts
// (the page's own geometry, which the browser test checks: inside its canvas, not over a body or a text).
function text(ctx, words, x, y, colour, bold) {
  ctx.font = font(bold);
  ctx.fillStyle = colour;
  ctx.textBaseline = "top";
  ctx.fillText(words, x, y);
  const w = ctx.measureText(words).width;
  rbs.texts.push({ canvas: ctx.canvasId, text: words, x, y, w, h: textPx(), px: textPx() });
  return w;
}
function width(ctx, words, bold) { ctx.font = font(bold); return ctx.measureText(words).width; }

// Words in pieces, wrapped at the pieces' joins into lines no wider than `max` (a piece wider alone is
// wrapped at its spaces).
function wrap(ctx, pieces, max, bold) {
  const lines = [];
  let line = "";
  const words = [];
  for (const piece of pieces) {
    if (width(ctx, piece, bold) <= max) words.push(piece);
    else for (const word of piece.split(" ")) words.push(...breakWord(ctx, word, max, bold));
  }
  for (const piece of words) {
    const next = line ? `${line} ${piece}` : piece;
    if (line && width(ctx, next, bold) > max) {
      lines.push(line);
      line = piece;
    } else {
      line = next;
    }
  }
  if (line) lines.push(line);
  return lines;
}

function onDraw(hook) { drawHooks.push(hook); }

// A word in pieces no wider than `max` (a long name in a narrow panel), at least a letter each.
function breakWord(ctx, word, max, bold) {
  const pieces = [];
  let piece = "";
  for (const letter of word) {
    if (piece && width(ctx, piece + letter, bold) > max) {
      pieces.push(piece);
      piece = "";
    }
    piece += letter;
  }
  if (piece) pieces.push(piece);
  return pieces;
}

function draw() {
  const begun = performance.now();
  rbs.drawCount = (rbs.drawCount || 0) + 1;
  rbs.texts = [];
  for (const hook of drawHooks) hook();
  if (!rbs.world || $("world-view").hidden) return;
  const names = Object.keys(rbs.world.bodies);
  const latest = showing.latest;
  const ts = names.filter((n) => latest[n]).map((n) => latest[n].t);
  const t = ts.length ? Math.max(...ts) : null;
  $("clock").textContent = t === null ? "t = \u2013" : `t = ${t.toFixed(2)} s`;
  const source = rbs.world.source;
  const paused = rbs.paused ? "paused" : "running";
  if (rbs.ended) setStatus("end of recording: its last frame", true);
  else if (socket && socket.readyState === WebSocket.OPEN) {
    setStatus(source === "replay" ? `replay of a recording, ${paused}` : source === "none" ? "no simulation found"
              : paused, source === "none");
  }
  // The scene and the plots take the screen's height below the page's top lines: beside each other on a wide
  // screen where both plots fit there whole at this text size; else the plots below the scene, side by side
  // on a wide screen (view.css, body.plots-below), and on a narrow one the first of them on the first screen.
  const fs = textPx();
  const specs = plotSpecs($("plot-body").value);
  document.body.classList.remove("plots-below");
  let beside = $("plots").getBoundingClientRect().top < $("scene").getBoundingClientRect().bottom;
  const top = $("scene").getBoundingClientRect().top + window.scrollY;
  const room = Math.max(window.innerHeight - top - 0.5 * fs, 12 * fs);
  const label = () => $("plot-label").getBoundingClientRect().height;
  let need = plotsNeed(specs);
  if (beside && 2 * (need + 4) + label() > room) {
    document.body.classList.add("plots-below");
    beside = false;
    need = plotsNeed(specs);
  }
  const sideBySide = !beside && $("plot-energy").getBoundingClientRect().top < $("plot-motion").getBoundingClientRect().bottom;
  const plotHeight = beside ? (room - label()) / 2 - 4 : sideBySide ? Math.max(need, window.innerHeight - label() - fs)
    : need;
  const sceneRoom = beside || sideBySide ? room : room - label() - plotHeight - fs;
  const sceneHeight = drawScene(names, sceneRoom);
  drawPlots(specs, plotHeight);
  rbs.sceneLayout = { beside, sideBySide, room: sceneRoom, height: sceneHeight, plotHeight, plotNeed: need };
  rbs.drawMs = performance.now() - begun;
}

// The height a chart of each of the plots takes at least: its title and legend as wrapped at its width, and an
// area for its lines five texts high.
function plotsNeed(specs) {
  const canvas = $("plot-motion");
  const ctx = canvas.getContext("2d");
  const W = canvas.clientWidth;
  const fs = textPx();
  return Math.max(...[specs.motion, specs.energy].map((spec) => chartHead(ctx, spec, W, false) + 1.25 * fs + 7.1 * fs + 8));
}

// --- the scene ---------------------------------------------------------------------------------------------
function slopeBox(b) {
  const phi = b.incline_angle;
  const R = typeOf(b).halfSize(b);
  const L = b.incline_length;
  const pad = Math.max(2 * R, 0.05 * L);
  // Above the top: a body starting there; below the foot: one waiting at a steep slope's foot (R below it).
  const below = Math.max(0.3 * pad, R);
  return { x0: -pad, y0: -L * Math.sin(phi) - below, w: L * Math.cos(phi) + 2 * pad,
           h: L * Math.sin(phi) + below + pad + 2 * R };
}

// A place as its label says it: "=1st" where racers share it (a tie: the node gives them one place).
function placeWords(name, place) {
  const shared = Object.entries(rbs.finishes).some(([n, f]) => n !== name && f.place === place);
  return `${shared ? "=" : ""}${ordinal(place)}`;
}

// A finisher's head: its place (in a race), its lap's time and the speed it arrived at, then the closed
// form's time (when the lap ran as configured): the values of its finish event.
function finishHead(title, place, f) {
  const closed = typeof f.closed_form === "number" ? [`(closed form ${f.closed_form.toFixed(4)} s)`] : [];
  return [place ? `${title}: ${place},` : `${title}: finished,`,
          `${f.lap_time.toFixed(4)} s at ${f.speed.toFixed(2)} m/s`, ...closed];
}

const WIDEST_FINISH = { lap_time: 88.8888, speed: -88.88, closed_form: 88.8888 };
// Its label's lines; `widest`, the widest its label takes in a lesson (a racer's at its finish, an energy of
// three digits and three decimals), for the room kept for it (slopeLinesKept).
function slopeLines(ctx, name, b, max, widest) {
  const s = showing.latest[name];
  const type = typeOf(b);
  const title = titleOf(name, b);
  const finish = rbs.finishes[name];
  const head = widest && races(b) ? finishHead(title, "=88th", WIDEST_FINISH)
    : finish ? finishHead(title, finish.place && placeWords(name, finish.place), finish)
      : [`${title}: ${s ? s.mode : "\u2013"}`];
  const energy = widest ? "E = -888.888 J \u00b7" : s ? `E = ${fixed3(s.energy)} J \u00b7` : "E = \u2013 \u00b7";
  const holds = Math.tan(b.incline_angle) <= type.tanCritical(b);
  const info = [energy, `\u03c6c = ${deg(criticalAngle(b))}`, `(slope ${deg(b.incline_angle)}:`,
                `${type.verdicts[holds ? 0 : 1]})`];
  return { head: wrap(ctx, head, max, true), info: wrap(ctx, info, max, false) };
}

// The lines a panel keeps for its label at its size: the most it has had there, or would have at its widest,
// so that the scene keeps its scale when a label gains a line (a finish) or loses one (a new lap).
function keepLines(key, lines) {
  keptLines[key] = Math.max(keptLines[key] || 0, lines);
  return keptLines[key];
}
function slopeLinesKept(ctx, name, b, max, size) {
  const count = (lines) => lines.head.length + lines.info.length;
  return keepLines(`${size}|${name}|${max}`,
                   Math.max(count(slopeLines(ctx, name, b, max, false)), count(slopeLines(ctx, name, b, max, true))));
}

function drawScene(names, room) {
  const canvas = $("scene-canvas");
  const W = canvas.clientWidth;
  const ctx = canvas.getContext("2d"); // to measure the labels: the canvas is fitted to the panels' height after
  const fs = textPx();
  const scene = (n) => (typeOf(rbs.world.bodies[n]) || {}).scene;
  const slopes = names.filter((n) => scene(n) === "slope");
  const floors = names.filter((n) => scene(n) === "floor");
  const gap = 6;
  const lineH = 1.25 * fs;
  // The panels' size: a label keeps its lines while it stays (keepLines).
  const size = JSON.stringify([W, room, fs, rbs.world.bodies]);
  // Only the world's bodies: one deleted is no longer drawn, so no longer where it was.
  for (const name of Object.keys(rbs.drawn)) if (!names.includes(name)) delete rbs.drawn[name];
  rbs.finishes = {};
  for (const name of names) {
    const f = finishOf(name);
    if (f) rbs.finishes[name] = { t: f.t, ...f.values };
  }
  // The floors in one band at the bottom (a third of the height beside slopes, all of it alone), the slopes
  // in the grid of columns that draws them largest. Every panel has room for its label and its drawing: where
  // the height has not that room, the scene is higher than it (the page scrolls).
  const floorNeed = floors.map((n) => {
    const b = rbs.world.bodies[n];
    return typeOf(b).minHeight(ctx, n, b, W, lineH, `${size}|${n}`);
  });
  const floorShare = ((slopes.length ? room / 3 - gap : room) - (floors.length - 1) * gap) / Math.max(1, floors.length);
  const floorH = floors.length ? Math.max(floorShare, ...floorNeed) : 0;
  const floorBand = floors.length ? floors.length * floorH + (floors.length - 1 + (slopes.length ? 1 : 0)) * gap : 0;
  const slopeRoom = room - floorBand;
  // At least ten texts wide (a label's words whole), and high enough for the label, the line of a body drawn
  // larger than to scale, and the slope a text and a half high.
  const minW = Math.min(W, 10 * fs);
  let best = null;
  for (let cols = 1; cols <= slopes.length; cols += 1) {
    const rows = Math.ceil(slopes.length / cols);
    const w = (W - (cols - 1) * gap) / cols;
    if (cols > 1 && w < minW) break;
    let headLines = 0;
    for (const name of slopes) {
      headLines = Math.max(headLines, slopeLinesKept(ctx, name, rbs.world.bodies[name], w - 12, size));
    }
    const h = Math.max((slopeRoom - (rows - 1) * gap) / rows, 12 + (headLines + 1) * lineH + 4 * MIN_RADIUS + 1.5 * fs);
    let scale = Infinity;
    for (const name of slopes) {
      const box = slopeBox(rbs.world.bodies[name]);
      scale = Math.min(scale, (w - 12) / box.w, (h - headLines * lineH - 10) / box.h);
    }
    const over = Math.max(0, rows * h + (rows - 1) * gap - slopeRoom);
    if (!best || over < best.over - 0.5 || (over <= best.over + 0.5 && scale > best.scale)) {
      best = { cols, rows, w, h, scale, headLines, over };
    }
  }
  const slopeHeight = slopes.length ? best.rows * best.h + (best.rows - 1) * gap : 0;
  const height = Math.max(room, slopeHeight + floorBand);
  rbs.layout = best && { cols: best.cols, w: best.w, h: best.h, scale: best.scale, lines: best.headLines };
  rbs.sceneNeed = slopeHeight + floorBand;
  fitCanvas(canvas, height);
  // The last row's panels share its width (no empty cell), each slope drawn no larger than in a cell of the
  // others' width: a race's slopes at one scale.
  slopes.forEach((name, i) => {
    const row = Math.floor(i / best.cols);
    const inRow = row === best.rows - 1 ? slopes.length - row * best.cols : best.cols;
    const w = (W - (inRow - 1) * gap) / inRow;
    const rect = { x: (i % best.cols) * (w + gap), y: row * (best.h + gap), w, h: best.h };
    drawSlopePanel(ctx, rect, name, rbs.world.bodies[name], showing.latest[name], lineH, best.headLines, best.w);
  });
  floors.forEach((name, i) => {
    const rect = { x: 0, y: height - floorBand + (slopes.length ? gap : 0) + i * (floorH + gap), w: W, h: floorH };
    const b = rbs.world.bodies[name];
    typeOf(b).drawPanel(ctx, rect, name, b, showing.latest[name], lineH, typeOf(b), `${size}|${name}`);
  });
  return height;
}

// The panel's label, and the top of what is drawn below it: below `keep` lines (keepLines) or its own, if more.
function panelFrame(ctx, rect, head, info, lineH, keep) {
  ctx.fillStyle = "#1d2129";
  ctx.fillRect(rect.x, rect.y, rect.w, rect.h);
  let y = rect.y + 4;
  for (const line of head) { text(ctx, line, rect.x + 6, y, "#f2f2f2", true); y += lineH; }
  for (const line of info) { text(ctx, line, rect.x + 6, y, "#c9ced6", false); y += lineH; }
  return Math.max(y, rect.y + 4 + (keep || 0) * lineH) + 4;
}

// `cellW`: the width its scale is fitted to (a wider panel of a last row draws its slope as large as the others).
function drawSlopePanel(ctx, rect, name, b, s, lineH, keep, cellW) {
  const phi = b.incline_angle;
  const L = b.incline_length;
  const R = typeOf(b).halfSize(b);
  const box = slopeBox(b);
  const lines = slopeLines(ctx, name, b, rect.w - 12);
  const fitW = Math.min(rect.w, cellW || rect.w) - 12 - 2 * MIN_RADIUS;
  const scale0 = Math.min(fitW / box.w, (rect.h - keep * lineH - 10 - 3 * MIN_RADIUS) / box.h);
  // A body smaller than MIN_RADIUS px is drawn that large (on its slope), and its panel says so where that
  // shows (5 % or more): a line more kept for it.
  let kept = keep;
  if (scale0 > 0 && R * scale0 * 1.05 <= MIN_RADIUS) {
    lines.info = wrap(ctx, [...lines.info, `(body drawn \u00d7${(MIN_RADIUS / (R * scale0)).toFixed(1)})`],
                      rect.w - 12, false);
    kept += 1;
  }
  const areaTop = panelFrame(ctx, rect, lines.head, lines.info, lineH, kept);
  // Inset by the smallest drawn radius (below the label, by its diameter: a body at the slope's top sits on
  // it): a body drawn larger than to scale stays inside the panel and off its label too.
  const area = { x: rect.x + 6 + MIN_RADIUS, y: areaTop + 2 * MIN_RADIUS, w: rect.w - 12 - 2 * MIN_RADIUS,
                 h: rect.y + rect.h - areaTop - 4 - 3 * MIN_RADIUS };
  const scale = Math.min(fitW / box.w, area.h / box.h); // positive: drawScene gave the panel its room
  // Side view: the slope's top at the origin, downhill to the right; canvas y grows downwards. The slope in
  // the middle of its area.
  const ox = area.x + 0.5 * (area.w - box.w * scale) - box.x0 * scale;
  const oy = area.y + 0.5 * (area.h - box.h * scale) + (box.h + box.y0) * scale;
  const X = (wx) => ox + wx * scale;
  const Y = (wy) => oy - wy * scale;
  const bottom = { x: L * Math.cos(phi), y: -L * Math.sin(phi) };
  ctx.fillStyle = "#6b4a2b";
  ctx.beginPath();
  ctx.moveTo(X(0), Y(0));
  ctx.lineTo(X(bottom.x), Y(bottom.y));
  ctx.lineTo(X(0), Y(bottom.y));
  ctx.closePath();
  ctx.fill();
  ctx.strokeStyle = "#c8a27a";
  ctx.lineWidth = stroke();
  ctx.beginPath();
  ctx.moveTo(X(0), Y(0));
  ctx.lineTo(X(bottom.x), Y(bottom.y));
  ctx.stroke();
  angleLabel(ctx, phi, X(0), Y(0), X(bottom.x), Y(bottom.y));
  rbs.panels[name] = { scale, ox, oy, phi, rect };
  if (!s) return;
  // The centre: x along the slope, r above it (R to scale); the spoke at the rotation theta about the slope's z.
  const rad = Math.max(R * scale, MIN_RADIUS);
  const cx = X(s.x * Math.cos(phi)) + rad * Math.sin(phi);
  const cy = Y(-s.x * Math.sin(phi)) - rad * Math.cos(phi);
  const spoke = typeOf(b).drawBody(ctx, cx, cy, rad, phi, b, s);
  rbs.drawn[name] = Object.assign({}, s, { cx, cy, sx: spoke.sx, sy: spoke.sy, r: rad });
}

// The slope's angle inside its triangle, left of its foot: under the slope's line, where no body ever is;
// too flat a slope for it has its angle in its panel's lines alone.
function angleLabel(ctx, phi, topX, topY, footX, footY) {
  const words = `${deg(phi)}`;
  const w = width(ctx, words, false);
  const h = textPx();
  const pad = 4;
  const tan = (footY - topY) / Math.max(1e-9, footX - topX);
  // The box's top right corner must lie under the slope's line: y_line(x2) <= footY - h - pad.
  const x2 = Math.min(footX - 3 * pad, topX + (footY - h - 2 * pad - topY) / Math.max(tan, 1e-9));
  const x1 = x2 - w;
  if (x1 < topX + pad || footY - h - pad < topY) return;
  ctx.strokeStyle = "#c8a27a";
  ctx.lineWidth = 0.7 * stroke();
  ctx.beginPath();
  ctx.arc(footX, footY, Math.min(3 * h, footX - x2 - pad), Math.PI, Math.PI + phi);
  ctx.stroke();
  text(ctx, words, x1, footY - h - pad, "#f2e0c8", false);
}

// --- plots -------------------------------------------------------------------------------------------------
// A body's plots: its states of the last PLOT_WINDOW s since the run's start, and its state at each of its
// events there that its plots show: a restart (where a new line starts), a finish, a mark of its entry's
// (`marks`: a dot). In a race a finish is a dotted line too. Every one stays while its window holds it.
function plotSpecs(name) {
  const b = rbs.world.bodies[name];
  const type = b && typeOf(b);
  const resetT = showing.resetT;
  const list = showing.points[name] || [];
  const start = isFinite(resetT) ? resetT : 0;
  const last = list.length ? list[list.length - 1].t : start;
  const t0 = Math.max(start, last - PLOT_WINDOW);
  const race = Boolean(b) && races(b);
  // The time axis is the lesson's: from 0 at the run's start (a Reset), a racer's lap times from 0 at each
  // lap's start (the node's lap_time counts from there).
  let origins = [start];
  const instants = [];
  const dotted = [];
  const finishes = [];
  for (const e of type ? showing.events[name] || [] : []) {
    const role = roleOf(e);
    if (role === "restart" && (race || startsRun(e)) && e.t > origins[origins.length - 1]) origins.push(e.t);
    const mark = type.marks && type.marks[e.kind];
    if (e.t < t0 || !(role || mark)) continue;
    const p = Object.assign(plotted(type, b, e.state, e.t), { gap: role === "restart", event: true });
    instants.push(p);
    if (mark) dotted.push([p, mark]);
    if (role === "finish" && race) finishes.push(e.t);
  }
  // Those in the window, and the last before it (where its first stretch counts from).
  origins = origins.filter((o, i) => o <= t0 + PLOT_WINDOW && (i + 1 === origins.length || origins[i + 1] > t0));
  // Where an event and a state share an instant, the event's point comes first (a restart's line starts there).
  const shown = list.filter((p) => p.t >= t0).concat(instants)
    .sort((p, q) => p.t - q.t || (q.event ? 1 : 0) - (p.event ? 1 : 0));
  const series = (key) => shown.map((p) => [p.t, p[key], p.gap]);
  // No body to plot (no simulation found yet): the plots' frames, titled so, with no line.
  const motion = type ? type.motion(series) : { title: "no body to plot", unit: "", lines: [] };
  const dotKey = motion.lines.length ? motion.lines[0].key : "";
  motion.dots = dotted.map(([p, words]) => [p.t, p[dotKey], words]);
  motion.finishes = finishes;
  const energy = { title: type ? `energy, potential 0 at ${type.potentialZero}` : "energy", unit: "J",
                   lines: [{ key: "energy", name: "total", colour: PLOT_COLOURS.first, pts: series("energy") },
                           { key: "kinetic", name: "kinetic", colour: PLOT_COLOURS.second, pts: series("kinetic") },
                           { key: "potential", name: "potential", colour: PLOT_COLOURS.third, dash: [10, 6],
                             pts: series("potential") }],
                   finishes };
  const axis = { origins, title: race ? "lap time (s)" : isFinite(resetT) ? "t since reset (s)" : "t (s)" };
  // The last state plotted, each plotted value of it (not the events' points).
  const lastPoints = {};
  const newest = list.length && list[list.length - 1].t >= t0 ? list[list.length - 1] : null;
  for (const spec of [motion, energy]) {
    for (const line of spec.lines) {
      if (newest && line.key in newest) lastPoints[line.key] = [newest.t, newest[line.key]];
    }
  }
  return { name, motion, energy, t0, axis, lastPoints };
}

function drawPlots(specs, height) {
  const { name, motion, energy, t0, axis, lastPoints } = specs;
  rbs.charts = {};
  const ticks = chart($("plot-motion"), height, motion, t0, axis);
  chart($("plot-energy"), height, energy, t0, axis);
  rbs.plotLast = { body: name, points: lastPoints, t0, origins: axis.origins, axis: axis.title, ticks,
                   finishes: motion.finishes, marks: motion.dots.map(([t, v, words]) => ({ t, v, name: words })) };
}

function niceStep(span, count) {
  const raw = span / count;
  const mag = Math.pow(10, Math.floor(Math.log10(raw)));
  const norm = raw / mag;
  return (norm < 1.5 ? 1 : norm < 3.5 ? 2 : norm < 7.5 ? 5 : 10) * mag;
}

// A chart's title with its unit, then its legend's entries, wrapped to its width W: drawn, or only measured;
// the height they take.
function chartHead(ctx, spec, W, drawn) {
  const fs = textPx();
  const lineH = 1.25 * fs;
  let y = 4;
  for (const line of wrap(ctx, [spec.unit ? `${spec.title} (${spec.unit})` : spec.title], W - 12, true)) {
    if (drawn) text(ctx, line, 6, y, "#f2f2f2", true);
    y += lineH;
  }
  const entries = spec.lines.map((l) => ({ name: l.name, draw: (x, cy) => legendLine(ctx, x, cy, l.colour, l.dash) }));
  const key = 1.3 * fs; // a legend entry's line, then its name
  for (const words of new Set((spec.dots || []).map((d) => d[2]))) {
    entries.push({ name: words, draw: (x, cy) => dot(ctx, x + key / 2, cy) });
  }
  if (spec.finishes && spec.finishes.length) {
    entries.push({ name: "finish",
                   draw: (x, cy) => instantLine(ctx, x + key / 2, cy - 0.5 * fs, cy + 0.5 * fs, FINISH_DASH) });
  }
  let x = 6;
  for (const entry of entries) {
    const w = key + 0.3 * fs + width(ctx, entry.name, false);
    if (x > 6 && x + w > W - 6) { x = 6; y += lineH; }
    if (drawn) {
      entry.draw(x, y + 0.5 * fs);
      text(ctx, entry.name, x + key + 0.3 * fs, y, "#e8e8e8", false);
    }
    x += w + 0.7 * fs;
  }
  y += lineH + 0.4 * fs;
  return y;
}

// A chart of spec's lines over [t0, t0 + PLOT_WINDOW], its time axis counting from each of axis.origins; the
// [t, label] of each time tick labelled.
function chart(canvas, height, spec, t0, axis) {
  const ctx = fitCanvas(canvas, height);
  const W = canvas.clientWidth;
  const fs = textPx();
  const lineH = 1.25 * fs;
  ctx.fillStyle = "#1d2129";
  ctx.fillRect(0, 0, W, height);
  let y = chartHead(ctx, spec, W, true);
  // The value axis' ticks at the left, its unit above them; the time axis' below, its title at its right end.
  const tickW = width(ctx, "-88.8", false) + 10;
  const area = { x: tickW, y: y + lineH + 0.5 * fs, w: W - tickW - 10, h: height - y - lineH - 2.1 * fs - 8 };
  rbs.charts[canvas.id] = { area, lines: [], ticks: 0, text: fs };
  if (area.h < 2 * fs || area.w < 4 * fs) return [];
  let lo = Infinity;
  let hi = -Infinity;
  for (const line of spec.lines) for (const p of line.pts) { lo = Math.min(lo, p[1]); hi = Math.max(hi, p[1]); }
  if (!isFinite(lo)) { lo = 0; hi = 1; }
  if (hi - lo < 1e-9) { lo -= 0.5; hi += 0.5; }
  const pad = 0.06 * (hi - lo);
  lo -= pad;
  hi += pad;
  const X = (t) => area.x + ((t - t0) / PLOT_WINDOW) * area.w;
  const Y = (v) => area.y + (1 - (v - lo) / (hi - lo)) * area.h;
  text(ctx, spec.unit, 6, y, "#c9ced6", false);
  ctx.strokeStyle = "#3a404c";
  ctx.lineWidth = Math.max(1, 0.05 * fs);
  // As many ticks as fit a text's height and a half apart, at most 5, and at least 2: an axis with one tick
  // tells no scale.
  const ticksOf = (step) => Math.floor(hi / step) - Math.ceil(lo / step) + 1;
  let yStep = niceStep(hi - lo, 5);
  for (let n = 4; n >= 1 && (yStep / (hi - lo)) * area.h < 1.5 * fs; n -= 1) {
    if (ticksOf(niceStep(hi - lo, n)) < 2) break;
    yStep = niceStep(hi - lo, n);
  }
  for (let v = Math.ceil(lo / yStep) * yStep; v <= hi; v += yStep) {
    ctx.beginPath();
    ctx.moveTo(area.x, Y(v));
    ctx.lineTo(area.x + area.w, Y(v));
    ctx.stroke();
    const words = Math.abs(v) < 1e-12 ? "0" : Number(v.toPrecision(3)).toString();
    rbs.charts[canvas.id].ticks += 1;
    text(ctx, words, area.x - 6 - width(ctx, words, false), Y(v) - 0.5 * fs, "#c9ced6", false);
  }
  // Each stretch of the time axis counts from its origin (the run's start, a lap's): ticks at whole steps from
  // it, each origin's 0 labelled first, then the others where they fit.
  const unitT = axis.title;
  const unitW = width(ctx, unitT, false);
  const tStep = niceStep(PLOT_WINDOW, Math.max(2, Math.min(5, Math.floor(area.w / (4 * fs)))));
  const end = t0 + PLOT_WINDOW;
  const ticks = [];
  axis.origins.forEach((o, i) => {
    const to = i + 1 < axis.origins.length ? axis.origins[i + 1] : Infinity;
    for (let k = Math.max(0, Math.ceil((t0 - o) / tStep - 1e-9)); o + k * tStep <= end + 1e-9; k += 1) {
      if (o + k * tStep >= to - 1e-9) break;
      ticks.push({ t: o + k * tStep, label: `${Number((k * tStep).toPrecision(6))}`, origin: k === 0 });
    }
  });
  const placed = [];
  const labelled = [];
  for (const tick of ticks.filter((k) => k.origin).concat(ticks.filter((k) => !k.origin))) {
    ctx.beginPath();
    ctx.moveTo(X(tick.t), area.y);
    ctx.lineTo(X(tick.t), area.y + area.h);
    ctx.stroke();
    const w = width(ctx, tick.label, false);
    const at = Math.max(area.x, X(tick.t) - w / 2);
    const free = placed.every(([a, b]) => at + w + 0.5 * fs < a || at > b + 0.5 * fs);
    if (at + w < area.x + area.w - unitW - 8 && free) {
      text(ctx, tick.label, at, area.y + area.h + 4, "#c9ced6", false);
      placed.push([at, at + w]);
      labelled.push([tick.t, tick.label]);
    }
  }
  text(ctx, unitT, area.x + area.w - unitW, area.y + area.h + 4, "#c9ced6", false);
  ctx.save();
  ctx.beginPath();
  ctx.rect(area.x, area.y, area.w, area.h);
  ctx.clip();
  for (const line of spec.lines) {
    ctx.strokeStyle = line.colour;
    ctx.lineWidth = stroke();
    ctx.setLineDash((line.dash || []).map((d) => d * stroke() / 3));
    ctx.beginPath();
    line.pts.forEach((p, i) => (i && !p[2] ? ctx.lineTo(X(p[0]), Y(p[1])) : ctx.moveTo(X(p[0]), Y(p[1]))));
    ctx.stroke();
    // What the test reads: each line's points inside the area.
    rbs.charts[canvas.id].lines.push({ key: line.key, points: line.pts.filter((p) => X(p[0]) >= area.x - 0.5
      && X(p[0]) <= area.x + area.w + 0.5 && Y(p[1]) >= area.y - 0.5 && Y(p[1]) <= area.y + area.h + 0.5).length });
  }
  ctx.setLineDash([]);
  for (const t of spec.finishes || []) instantLine(ctx, X(t), area.y, area.y + area.h, FINISH_DASH);
  for (const d of spec.dots || []) dot(ctx, X(d[0]), Y(d[1]));
  ctx.restore();
  return labelled.sort((p, q) => p[0] - q[0]);
}

// Lines and marks grow with the text (a 4K screen's are as thick, to the eye, as a laptop's).
function stroke() { return Math.max(3, 0.14 * textPx()); }

function legendLine(ctx, x, y, colour, dash) {
  ctx.strokeStyle = colour;
  ctx.lineWidth = stroke();
  ctx.setLineDash(dash ? dash.map((d) => d * stroke() / 3) : []);
  ctx.beginPath();
  ctx.moveTo(x, y);
  ctx.lineTo(x + 1.3 * textPx(), y);
  ctx.stroke();
  ctx.setLineDash([]);
}

function dot(ctx, x, y) {
  ctx.fillStyle = "#ffffff";
  ctx.strokeStyle = "#15181d";
  ctx.lineWidth = 2;
  ctx.beginPath();
  ctx.arc(x, y, 0.32 * textPx(), 0, 2 * Math.PI);
  ctx.fill();
  ctx.stroke();
}

function instantLine(ctx, x, y1, y2, dash) {
  ctx.strokeStyle = "#ffffff";
  ctx.lineWidth = 0.7 * stroke();
  ctx.setLineDash(dash.map((d) => d * stroke() / 3));
  ctx.beginPath();
  ctx.moveTo(x, y1);
  ctx.lineTo(x, y2);
  ctx.stroke();
  ctx.setLineDash([]);
}

// The token goes in the form at /login, never in an address (a browser keeps every address it visits in its
// history): an address with ?token= gives no control, and the page says where it goes. An address with a query
// is replaced by the page's own (what the address bar shows, the tab's later entries).
if (new URLSearchParams(location.search).has("token")) {
  showLine("no control from an address: the token goes in the form at /login (an address stays in the "
           + "browser's history)", false);
}
if (location.search || location.hash) history.replaceState(null, "", location.pathname);
wireControls();
// Once every script of the page has run (lab.js and class.js hook into the messages).
document.addEventListener("DOMContentLoaded", connect);
