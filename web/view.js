// The web view's page: the followed world from the side, as the text poses its problems, and live plots.
// Everything comes from this page's server (scripts/web_view.py) over one WebSocket; nothing from elsewhere.
// What is drawn is kept in window.rbs (the browser test reads it): the latest frame, each body's drawn state
// and place on the canvas, each plot's last points.
"use strict";

const PLOT_WINDOW = 10; // s of simulated time in the plots, as the rviz panel's
const KEEP = 12; // s of points kept per body
const MIN_RADIUS = 9; // px: a body drawn smaller is lost on a projector or a phone
const COLOURS = { sphere: "#f0a030", cylinder: "#4fa3ff", ring: "#e05080", spherical_shell: "#6bd06b",
                  custom: "#c0a0ff", rod: "#4f8cff" };

const rbs = {
  frames: 0, lastFrame: null, world: null, paused: false, control: false, line: "", lineOk: true,
  drawn: {}, plotLast: {}, panels: {}, replies: [], finishes: {},
};
window.rbs = rbs;
rbs.times = (body) => (points[body] || []).map((p) => p.t); // the plotted states' t, a reset's earlier ones gone

const token = new URLSearchParams(location.search).get("token") || "";
if (token) history.replaceState(null, "", location.pathname); // the token off a projected address bar

const latest = {}; // body -> its last state
const points = {}; // body -> [{t, ...the plotted values}]
const marks = {}; // body -> [[t, v]] slip -> roll instants
const lastMode = {}; // body -> the mode of its previous state
let resetT = -Infinity; // the latest reset's t: no point at or before it is plotted
let socket = null;
let nextId = 1;
let drawPending = false;
let lessonKeys = {};
let keyUnits = {};

const $ = (id) => document.getElementById(id);

// --- physics the labels and plots show (docs/rviz.md: the panel's) -----------------------------------------
function criticalAngle(b) { return Math.atan(b.mu_s * (1 + b.inertia_factor) / b.inertia_factor); }
function deg(rad) { return (rad * 180 / Math.PI).toFixed(1) + "\u00b0"; }
// Three decimals, without the "-0.000" of a tiny negative number.
function fixed3(x) { return Math.abs(x) < 0.0005 ? "0.000" : x.toFixed(3); }
function kinetic(b, s) {
  if (b.type === "rod") {
    return 0.5 * b.mass * (s.vx * s.vx + s.vy * s.vy) + 0.5 * (b.mass * b.length * b.length / 12) * s.omega * s.omega;
  }
  return 0.5 * b.mass * s.v * s.v + 0.5 * b.inertia_factor * b.mass * b.radius * b.radius * s.omega * s.omega;
}
function rodEnds(b, s) {
  const h = 0.5 * b.length;
  return { a: s.y + h * Math.sin(s.theta), b: s.y - h * Math.sin(s.theta) };
}
function modeOf(b, s) {
  if (b.type !== "rod") return s.mode;
  const e = rodEnds(b, s);
  return e.a < 0 || e.b < 0 ? "on the floor" : "in the air";
}

// --- the connection --------------------------------------------------------------------------------------
function connect() {
  const scheme = location.protocol === "https:" ? "wss" : "ws";
  socket = new WebSocket(`${scheme}://${location.host}/ws${token ? "?token=" + encodeURIComponent(token) : ""}`);
  socket.onmessage = (event) => receive(JSON.parse(event.data));
  socket.onclose = () => {
    setStatus("disconnected: the web view is gone (retrying)", true);
    setTimeout(connect, 2000);
  };
}

function receive(m) {
  if (m.type === "frame") {
    rbs.frames += 1;
    rbs.lastFrame = m;
    for (const [body, states] of Object.entries(m.states)) for (const s of states) addState(body, s);
  } else if (m.type === "hello") {
    rbs.control = m.control;
    lessonKeys = m.lesson_keys;
    keyUnits = m.key_units;
    $("controls").hidden = !m.control;
  } else if (m.type === "world") {
    rbs.world = m;
    rbs.paused = m.paused;
    for (const body of Object.keys(latest)) if (!(body in m.bodies)) delete latest[body];
    fillSelects();
  } else if (m.type === "finishes") {
    rbs.finishes = m.finishes; // a race's results, in the node's own words: "1st, 2.0439 s (closed form ...)"
  } else if (m.type === "paused") {
    rbs.paused = m.paused;
  } else if (m.type === "reset") {
    resetT = Math.max(resetT, m.t);
    for (const body of Object.keys(points)) {
      points[body] = points[body].filter((p) => p.t > m.t);
      marks[body] = (marks[body] || []).filter((p) => p[0] > m.t);
      delete lastMode[body];
    }
  } else if (m.type === "reply") {
    rbs.replies.push(m);
    if (!m.ok) showKeyValue(); // a refused value: the field shows the one that runs again
    showLine(m.line, m.ok);
  } else if (m.type === "line") {
    showLine(m.line, false);
  }
  scheduleDraw();
}

function addState(body, s) {
  latest[body] = s;
  const b = rbs.world && rbs.world.bodies[body];
  // The reset comes on its own topic, and may overtake states from before it: those are not plotted.
  if (!b || s.t <= resetT) return;
  const K = kinetic(b, s);
  const p = { t: s.t, energy: s.energy, kinetic: K, potential: s.energy - K };
  if (b.type === "rod") {
    const e = rodEnds(b, s);
    p.end_a = e.a;
    p.end_b = e.b;
  } else {
    p.v = s.v;
    p.minus_omega_r = -s.omega * b.radius;
    if (lastMode[body] === "slipping" && s.mode === "rolling") (marks[body] = marks[body] || []).push([s.t, s.v]);
    lastMode[body] = s.mode;
  }
  const list = (points[body] = points[body] || []);
  list.push(p);
  while (list.length && list[0].t < s.t - KEEP) list.shift();
}

function send(request) {
  request.id = nextId++;
  if (socket && socket.readyState === WebSocket.OPEN) socket.send(JSON.stringify(request));
  return request.id;
}

function showLine(text, ok) {
  rbs.line = text;
  rbs.lineOk = ok;
  const el = $("line");
  el.textContent = text;
  el.className = ok ? "ok" : "refused";
}

function setStatus(text, stopped) {
  const el = $("status");
  el.textContent = text;
  el.className = stopped ? "stopped" : "";
}

// --- controls ----------------------------------------------------------------------------------------------
function fillSelects() {
  const names = Object.keys(rbs.world.bodies);
  for (const id of ["set-body", "plot-body"]) {
    const sel = $(id);
    const was = sel.value;
    sel.replaceChildren(...names.map((n) => new Option(n, n)));
    if (names.includes(was)) sel.value = was;
  }
  fillKeys();
}

function fillKeys() {
  const b = rbs.world && rbs.world.bodies[$("set-body").value];
  if (!b) return;
  const sel = $("set-key");
  const was = sel.value;
  const keys = lessonKeys[b.type] || [];
  sel.replaceChildren(...keys.map((k) => new Option(k, k)));
  if (keys.includes(was)) sel.value = was;
  showKeyValue();
}

function showKeyValue() {
  // The value that runs, unless the teacher is typing one (a world update comes whenever anything changes).
  const b = rbs.world && rbs.world.bodies[$("set-body").value];
  const key = $("set-key").value;
  if (!b || !key) return;
  if (document.activeElement !== $("set-value")) $("set-value").value = String(b[key]);
  const unit = (keyUnits[b.type] || {})[key] || "";
  $("set-unit").textContent = unit === "rad" ? `rad (${deg(Number(b[key]))})` : unit;
}

function wireControls() {
  $("pause").onclick = () => send({ op: "pause" });
  $("run").onclick = () => send({ op: "run" });
  $("reset").onclick = () => send({ op: "reset" });
  $("step").onclick = () => send({ op: "step", steps: Number($("steps").value) });
  $("set").onclick = () => send({ op: "set", body: $("set-body").value, key: $("set-key").value,
                                  value: Number($("set-value").value) });
  $("set-body").onchange = fillKeys;
  $("set-key").onchange = showKeyValue;
  $("plot-body").onchange = scheduleDraw;
  window.addEventListener("resize", scheduleDraw);
}

// --- drawing -----------------------------------------------------------------------------------------------
function scheduleDraw() {
  if (drawPending) return;
  drawPending = true;
  requestAnimationFrame(() => { drawPending = false; draw(); });
}

function fitCanvas(canvas, height) {
  const ratio = window.devicePixelRatio || 1;
  const width = canvas.clientWidth;
  canvas.style.height = height + "px";
  if (canvas.width !== Math.round(width * ratio) || canvas.height !== Math.round(height * ratio)) {
    canvas.width = Math.round(width * ratio);
    canvas.height = Math.round(height * ratio);
  }
  const ctx = canvas.getContext("2d");
  ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
  ctx.clearRect(0, 0, width, height);
  return ctx;
}

function draw() {
  if (!rbs.world) return;
  const names = Object.keys(rbs.world.bodies);
  const ts = names.filter((n) => latest[n]).map((n) => latest[n].t);
  const t = ts.length ? Math.max(...ts) : null;
  $("clock").textContent = t === null ? "t = \u2013" : `t = ${t.toFixed(2)} s`;
  const source = rbs.world.source;
  const paused = rbs.paused ? "paused" : "running";
  setStatus(source === "replay" ? `replay of a recording, ${paused}` : source === "none" ? "no simulation found"
            : paused, source === "none");
  drawScene(names);
  drawPlots($("plot-body").value);
}

function panelSize(b, width, alone) {
  // A panel's height for its width: the slope or the floor to scale; a rod's panel spans the whole width, and
  // a rod alone (lesson.launch part:=rod) may take more of the screen's height.
  const label = 46;
  if (b.type === "rod") return label + Math.min(Math.max((alone ? 0.6 : 0.42) * width, 260), alone ? 600 : 420);
  const box = slopeBox(b);
  const s = Math.min((width - 16) / box.w, (0.4 * width) / box.h);
  return label + box.h * s + 8;
}

function slopeBox(b) {
  const phi = b.incline_angle;
  const R = b.radius;
  const L = b.incline_length;
  const pad = Math.max(2 * R, 0.05 * L);
  return { x0: -pad, y0: -L * Math.sin(phi) - 0.3 * pad, w: L * Math.cos(phi) + 2 * pad,
           h: L * Math.sin(phi) + 1.3 * pad + 2 * R };
}

function drawScene(names) {
  // The rollers two to a row on a wide screen, one on a narrow one; then each rod in a row of its own.
  const canvas = $("scene-canvas");
  const width = canvas.clientWidth;
  const cols = width >= 880 ? 2 : 1;
  const rows = [];
  let row = [];
  for (const name of names.filter((n) => rbs.world.bodies[n].type !== "rod")) {
    row.push(name);
    if (row.length === cols) { rows.push(row); row = []; }
  }
  if (row.length) rows.push(row);
  for (const name of names.filter((n) => rbs.world.bodies[n].type === "rod")) rows.push([name]);
  const colWidth = (width - (cols - 1) * 10) / cols;
  const wide = (row) => rbs.world.bodies[row[0]].type === "rod";
  const heights = rows.map((r) => Math.max(...r.map((n) => panelSize(rbs.world.bodies[n], wide(r) ? width : colWidth,
                                                                      names.length === 1))));
  const ctx = fitCanvas(canvas, heights.reduce((a, h) => a + h + 10, 0));
  let top = 0;
  rows.forEach((r, i) => {
    r.forEach((name, c) => {
      const w = wide(r) ? width : colWidth;
      const rect = { x: c * (colWidth + 10), y: top, w, h: heights[i] };
      const b = rbs.world.bodies[name];
      if (b.type === "rod") drawRod(ctx, rect, name, b, latest[name]);
      else drawRoller(ctx, rect, name, b, latest[name]);
    });
    top += heights[i] + 10;
  });
}

function panelFrame(ctx, rect, lines) {
  ctx.fillStyle = "#1d2129";
  ctx.fillRect(rect.x, rect.y, rect.w, rect.h);
  ctx.fillStyle = "#f2f2f2";
  ctx.font = "bold 16px 'DejaVu Sans', sans-serif";
  ctx.fillText(lines[0], rect.x + 8, rect.y + 19);
  ctx.font = "15px 'DejaVu Sans', sans-serif";
  ctx.fillText(lines[1], rect.x + 8, rect.y + 39);
}

function drawRoller(ctx, rect, name, b, s) {
  const phi = b.incline_angle;
  const L = b.incline_length;
  const R = b.radius;
  const c = b.inertia_factor;
  const phiC = criticalAngle(b);
  const verdict = Math.tan(phi) <= b.mu_s * (1 + c) / c ? "can roll" : "slips";
  const mode = s ? s.mode : "\u2013";
  const energy = s ? `E = ${fixed3(s.energy)} J` : "E = \u2013";
  const box = slopeBox(b);
  const area = { x: rect.x + 8, y: rect.y + 46, w: rect.w - 16, h: rect.h - 54 };
  const scale = Math.min(area.w / box.w, area.h / box.h);
  // A body much smaller than MIN_RADIUS px is drawn that large (on its slope), and its panel says so.
  const r = R * scale < 0.9 * MIN_RADIUS ? MIN_RADIUS : R * scale;
  const title = name === b.shape ? name : `${name} (${b.shape})`;
  const finish = rbs.finishes && rbs.finishes[name];
  panelFrame(ctx, rect, [finish ? `${title}: ${finish}` : `${title}: ${mode}`,
                         `${energy} \u00b7 \u03c6c = ${deg(phiC)} (slope ${deg(phi)}: ${verdict})`]);
  // Side view: the slope's top at the origin, downhill to the right; canvas y grows downwards.
  const ox = area.x - box.x0 * scale;
  const oy = area.y + (box.h + box.y0) * scale;
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
  ctx.lineWidth = 3;
  ctx.beginPath();
  ctx.moveTo(X(0), Y(0));
  ctx.lineTo(X(bottom.x), Y(bottom.y));
  ctx.stroke();
  ctx.font = "14px 'DejaVu Sans', sans-serif";
  if (-bottom.y * scale >= 30) { // inside the slope's foot; a flatter one has it in its label alone
    ctx.fillStyle = "#c8a27a";
    ctx.fillText(deg(phi), X(bottom.x) - 80, Y(bottom.y) - 6);
  }
  rbs.panels[name] = { scale, ox, oy, phi };
  if (r > R * scale) {
    const note = `body drawn \u00d7${(r / (R * scale)).toFixed(1)}`;
    ctx.fillStyle = "#c9ced6";
    ctx.fillText(note, rect.x + rect.w - 10 - ctx.measureText(note).width, rect.y + 64);
  }
  if (!s) return;
  // The centre: x along the slope, r above it (R to scale); the spoke at the rotation theta about the slope's z.
  const cx = X(s.x * Math.cos(phi)) + r * Math.sin(phi);
  const cy = Y(-s.x * Math.sin(phi)) - r * Math.cos(phi);
  const a = s.theta - phi;
  const sx = cx + r * Math.cos(a);
  const sy = cy - r * Math.sin(a);
  const colour = COLOURS[b.shape] || COLOURS.custom;
  ctx.beginPath();
  ctx.arc(cx, cy, r, 0, 2 * Math.PI);
  if (b.shape === "ring" || b.shape === "spherical_shell") {
    ctx.strokeStyle = colour;
    ctx.lineWidth = Math.max(2, r * (b.shape === "ring" ? 0.25 : 0.15));
    ctx.stroke();
  } else {
    ctx.fillStyle = colour;
    ctx.fill();
  }
  ctx.strokeStyle = "#ffffff";
  ctx.lineWidth = Math.max(2, r * 0.12);
  ctx.beginPath();
  ctx.moveTo(cx, cy);
  ctx.lineTo(sx, sy);
  ctx.stroke();
  rbs.drawn[name] = Object.assign({}, s, { cx, cy, sx, sy, r });
}

function drawRod(ctx, rect, name, b, s) {
  const mode = s ? modeOf(b, s) : "\u2013";
  const energy = s ? `E = ${fixed3(s.energy)} J` : "E = \u2013";
  panelFrame(ctx, rect, [`${name === "rod" ? name : name + " (rod)"}: ${mode}`, `${energy} \u00b7 k = ${b.k} N/m \u00b7 L = ${b.length} m`]);
  const area = { x: rect.x + 8, y: rect.y + 46, w: rect.w - 16, h: rect.h - 54 };
  const top = Math.max(b.y0 + 0.5 * b.length, 1.5) * 1.1;
  const floorPx = 30; // the floor's band, with the metre marks
  const scale = Math.min((area.h - floorPx) / top, area.w / (2.5 * b.length));
  const floorDepth = floorPx / scale;
  const span = area.w / scale;
  const x = s ? s.x : b.x0;
  const bounded = b.floor_length > 0;
  let left = x - span / 2;
  if (bounded && b.floor_length + 1 <= span) left = -0.5;
  else if (bounded) left = Math.min(Math.max(left, -0.5), b.floor_length + 0.5 - span);
  const ox = area.x - left * scale;
  const oy = area.y + top * scale;
  const X = (wx) => ox + wx * scale;
  const Y = (wy) => oy - wy * scale;
  ctx.save();
  ctx.beginPath();
  ctx.rect(area.x, area.y, area.w, area.h);
  ctx.clip();
  const floorFrom = bounded ? Math.max(0, left) : left;
  const floorTo = bounded ? Math.min(b.floor_length, left + span) : left + span;
  ctx.fillStyle = "#555b66";
  ctx.fillRect(X(floorFrom), Y(0), (floorTo - floorFrom) * scale, floorDepth * scale);
  ctx.strokeStyle = "#c9ced6";
  ctx.fillStyle = "#c9ced6";
  ctx.lineWidth = 2;
  ctx.font = "14px 'DejaVu Sans', sans-serif";
  for (let m = Math.ceil(floorFrom); m <= floorTo; m += 1) {
    ctx.beginPath();
    ctx.moveTo(X(m), Y(0));
    ctx.lineTo(X(m), Y(0) + 8);
    ctx.stroke();
    ctx.fillText(`${m} m`, X(m) + 3, Y(0) + 22);
  }
  rbs.panels[name] = { scale, ox, oy, left };
  if (s) {
    const h = 0.5 * b.length;
    const ax = X(s.x + h * Math.cos(s.theta));
    const ay = Y(s.y + h * Math.sin(s.theta));
    const bx = X(s.x - h * Math.cos(s.theta));
    const by = Y(s.y - h * Math.sin(s.theta));
    ctx.strokeStyle = COLOURS.rod;
    ctx.lineWidth = 7;
    ctx.lineCap = "round";
    ctx.beginPath();
    ctx.moveTo(bx, by);
    ctx.lineTo(ax, ay);
    ctx.stroke();
    ctx.fillStyle = "#ff8a3d";
    ctx.beginPath();
    ctx.arc(ax, ay, 6, 0, 2 * Math.PI);
    ctx.fill();
    rbs.drawn[name] = Object.assign({}, s, { cx: X(s.x), cy: Y(s.y), ax, ay, bx, by });
  }
  ctx.restore();
}

// --- plots -------------------------------------------------------------------------------------------------
function drawPlots(name) {
  const b = rbs.world.bodies[name];
  const list = points[name] || [];
  const narrow = $("plot-motion").clientWidth < 600;
  const height = narrow ? 210 : 260;
  const last = list.length ? list[list.length - 1].t : 0;
  const t0 = last > PLOT_WINDOW ? last - PLOT_WINDOW : 0;
  const shown = list.filter((p) => p.t >= t0);
  const series = (key) => shown.map((p) => [p.t, p[key]]);
  let motion;
  if (!b) {
    motion = { title: "", lines: [] };
  } else if (b.type === "rod") {
    motion = { title: "height of each end (m)",
               lines: [{ key: "end_a", name: "end A (orange)", colour: "#ff8a3d", pts: series("end_a") },
                       { key: "end_b", name: "end B", colour: "#4f8cff", pts: series("end_b") }] };
  } else {
    motion = { title: "v and \u2212\u03c9R (m/s), \u25cf slip \u2192 roll",
               lines: [{ key: "v", name: "v", colour: "#f0a030", pts: series("v") },
                       { key: "minus_omega_r", name: "\u2212\u03c9R", colour: "#7fd4ff", dash: [8, 6],
                         pts: series("minus_omega_r") }],
               marks: (marks[name] || []).filter((m) => m[0] >= t0) };
  }
  const zero = b && b.type === "rod" ? "floor level" : "the slope's top";
  const energy = { title: `energy (J), potential 0 at ${zero}`,
                   lines: [{ key: "energy", name: "total", colour: "#f2f2f2", pts: series("energy") },
                           { key: "kinetic", name: "kinetic", colour: "#6bd06b", pts: series("kinetic") },
                           { key: "potential", name: "potential", colour: "#e05080", pts: series("potential") }] };
  const lastPoints = {};
  for (const chart of [motion, energy]) {
    for (const line of chart.lines) if (line.pts.length) lastPoints[line.key] = line.pts[line.pts.length - 1];
  }
  if (motion.marks && motion.marks.length) lastPoints.slip_to_roll = motion.marks[motion.marks.length - 1];
  rbs.plotLast = { body: name, points: lastPoints };
  chart($("plot-motion"), height, motion, t0);
  chart($("plot-energy"), height, energy, t0);
}

function niceStep(span, count) {
  const raw = span / count;
  const mag = Math.pow(10, Math.floor(Math.log10(raw)));
  const norm = raw / mag;
  return (norm < 1.5 ? 1 : norm < 3.5 ? 2 : norm < 7.5 ? 5 : 10) * mag;
}

function chart(canvas, height, spec, t0) {
  const ctx = fitCanvas(canvas, height);
  const width = canvas.clientWidth;
  ctx.fillStyle = "#1d2129";
  ctx.fillRect(0, 0, width, height);
  const area = { x: 62, y: 48, w: width - 74, h: height - 82 };
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
  ctx.font = "bold 15px 'DejaVu Sans', sans-serif";
  ctx.fillStyle = "#f2f2f2";
  ctx.fillText(spec.title, 8, 18);
  ctx.font = "14px 'DejaVu Sans', sans-serif";
  let lx = 8;
  for (const line of spec.lines) {
    ctx.strokeStyle = line.colour;
    ctx.lineWidth = 3;
    ctx.setLineDash(line.dash || []);
    ctx.beginPath();
    ctx.moveTo(lx, 34);
    ctx.lineTo(lx + 22, 34);
    ctx.stroke();
    ctx.setLineDash([]);
    ctx.fillStyle = "#e8e8e8";
    ctx.fillText(line.name, lx + 27, 39);
    lx += 40 + ctx.measureText(line.name).width;
  }
  ctx.strokeStyle = "#3a404c";
  ctx.lineWidth = 1;
  ctx.fillStyle = "#c9ced6";
  const yStep = niceStep(hi - lo, 4);
  for (let v = Math.ceil(lo / yStep) * yStep; v <= hi; v += yStep) {
    ctx.beginPath();
    ctx.moveTo(area.x, Y(v));
    ctx.lineTo(area.x + area.w, Y(v));
    ctx.stroke();
    const text = Math.abs(v) < 1e-12 ? "0" : Number(v.toPrecision(3)).toString();
    ctx.fillText(text, area.x - 6 - ctx.measureText(text).width, Y(v) + 5);
  }
  for (let t = Math.ceil(t0 / 2) * 2; t <= t0 + PLOT_WINDOW + 1e-9; t += 2) {
    ctx.beginPath();
    ctx.moveTo(X(t), area.y);
    ctx.lineTo(X(t), area.y + area.h);
    ctx.stroke();
    ctx.fillText(`${t}`, X(t) - 4, area.y + area.h + 18);
  }
  ctx.fillText("t (s)", 8, area.y + area.h + 18);
  ctx.save();
  ctx.beginPath();
  ctx.rect(area.x, area.y, area.w, area.h);
  ctx.clip();
  for (const line of spec.lines) {
    ctx.strokeStyle = line.colour;
    ctx.lineWidth = 3;
    ctx.setLineDash(line.dash || []);
    ctx.beginPath();
    line.pts.forEach((p, i) => (i ? ctx.lineTo(X(p[0]), Y(p[1])) : ctx.moveTo(X(p[0]), Y(p[1]))));
    ctx.stroke();
  }
  ctx.setLineDash([]);
  ctx.fillStyle = "#ffffff";
  for (const m of spec.marks || []) {
    ctx.beginPath();
    ctx.arc(X(m[0]), Y(m[1]), 6, 0, 2 * Math.PI);
    ctx.fill();
  }
  ctx.restore();
}

wireControls();
connect();
