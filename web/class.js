// The teacher's view of the whole class (the page with the token): every student's lab as a point, its outcome
// (an event's value: a finish's lap time, the instant it rolled...) against the key the students varied, each
// with the student's name where the pointer is, over the curve the server computed with the core over that
// key's values (the closed form every point must lie on), and the points' mean and standard deviation.
// "Predict, then run": the teacher asks a question, the students answer from their pages, the answers come
// here as a histogram, then the teacher reveals them. The teacher shows one student's lab to the class, and
// clears the results. What is drawn is kept in rbs.classView (the browser test reads it).
"use strict";

const classView = {
  results: [], // the server's: [{lab, name, varied: {"body.key": value}, outcomes: [{body, kind, value_name, value, t}]}]
  curves: {}, // {"body.key": {"body.kind.value_name": {x: [...], y: [...]}}}
  lesson: {}, // {"body.key": the value of the config the labs were opened from}
  xKey: "", yKey: "", // the keys drawn
  wanted: { x: "", y: "" }, // the teacher's choices: kept while results come and go
  points: [], // [{lab, name, x, y, others, px, py}] as drawn
  curve: null, // {x, y} drawn
  stats: null, // {n, mean, sd}
  hover: null, // the point the pointer is on
  question: null, answers: null,
  area: null, // the plot's area on the canvas
};
rbs.classView = classView;

const outcomeKey = (o) => `${o.body}.${o.kind}.${o.value_name}`;

function classMessage(m) {
  if (m.type === "hello") {
    $("class-toggle").hidden = !m.control;
  } else if (m.type === "class") {
    classView.results = m.results || [];
    classView.curves = m.curves || {};
    classView.lesson = m.lesson || {};
    fillClassMenus();
    fillShowChoice();
  } else if (m.type === "question") {
    if (!classView.question || classView.question.question !== m.question || (m.open && !classView.question.open)) {
      classView.answers = null;
    }
    classView.question = m;
    showAnswers();
  } else if (m.type === "answers") {
    classView.answers = m;
    showAnswers();
  }
}

// --- the menus -----------------------------------------------------------------------------------------------
function fillMenu(sel, values, words, wanted) {
  const was = sel.value;
  const texts = values.map(words);
  if (sel.options.length !== values.length
      || [...sel.options].some((o, i) => o.value !== values[i] || o.textContent !== texts[i])) {
    sel.replaceChildren(...values.map((v, i) => new Option(texts[i], v)));
  }
  if (values.includes(wanted)) sel.value = wanted;
  else if (values.includes(was)) sel.value = was;
  return sel.value;
}

function fillClassMenus() {
  const xs = new Set(Object.keys(classView.curves));
  const ys = new Set();
  for (const r of classView.results) {
    for (const key of Object.keys(r.varied || {})) xs.add(key);
    for (const o of r.outcomes || []) ys.add(outcomeKey(o));
  }
  for (const byY of Object.values(classView.curves)) for (const y of Object.keys(byY)) ys.add(y);
  classView.xKey = fillMenu($("class-x"), [...xs].sort(), (k) => axisWords(k, keyUnit(k)), classView.wanted.x);
  // An outcome with a curve for this x first.
  const withCurve = Object.keys(classView.curves[classView.xKey] || {});
  const order = [...ys].sort((a, b) => Number(withCurve.includes(b)) - Number(withCurve.includes(a)) || (a < b ? -1 : 1));
  classView.yKey = fillMenu($("class-y"), order, (k) => axisWords(k, outcomeUnit(k)), classView.wanted.y);
  scheduleDraw();
}

function fillShowChoice() {
  const labs = classView.results.map((r) => r.lab);
  fillMenu($("show-lab-choice"), labs, (id) => {
    const r = classView.results.find((q) => q.lab === id);
    const varied = Object.entries(r.varied || {}).map(([k, v]) => `${k} = ${v}`).join(", ");
    return varied ? `${r.name} (${varied})` : r.name;
  }, "");
}

// A key's unit ("body.key"), and an outcome's ("body.kind.value_name"), as the description gives them.
function bodyType(body) {
  const b = stores.class.world && stores.class.world.bodies[body];
  return b ? rbs.description && rbs.description.types[b.type] : null;
}
function keyUnit(key) {
  const [body, name] = key.split(".");
  const type = bodyType(body);
  const found = type && type.keys.find((k) => k.name === name);
  return found ? found.unit : "";
}
function outcomeUnit(key) {
  const [body, , value] = key.split(".");
  if (["t", "lap_time", "closed_form"].includes(value)) return "s";
  const type = bodyType(body);
  const field = type && (type.state_fields || []).find((f) => f.name === value);
  return field ? field.unit : "";
}
function axisWords(key, unit) { return `${key.split(".").join(" ")}${unit ? ` (${unit})` : ""}`; }

// --- the points --------------------------------------------------------------------------------------------
function classPoints() {
  const points = [];
  for (const r of classView.results) {
    const varied = r.varied || {};
    const x = classView.xKey in varied ? varied[classView.xKey] : classView.lesson[classView.xKey];
    const outcome = (r.outcomes || []).find((o) => outcomeKey(o) === classView.yKey);
    if (typeof x !== "number" || !outcome || typeof outcome.value !== "number") continue;
    const others = Object.keys(varied).filter((k) => k !== classView.xKey);
    if (r.on_curves === false) others.push("opened from another config"); // not of the curve's lesson
    points.push({ lab: r.lab, name: r.name, x, y: outcome.value, others });
  }
  return points;
}

function meanSd(values) {
  if (!values.length) return null;
  const mean = values.reduce((a, b) => a + b, 0) / values.length;
  const sd = values.length > 1 ? Math.sqrt(values.reduce((a, v) => a + (v - mean) ** 2, 0) / (values.length - 1)) : 0;
  return { n: values.length, mean, sd };
}

function short(v) { return Number(v.toPrecision(4)).toString(); }

function drawClass() {
  if ($("class-panel").hidden) return;
  const canvas = $("class-canvas");
  const fs = textPx();
  const top = canvas.getBoundingClientRect().top + window.scrollY;
  const wide = window.innerWidth >= 900 && window.innerWidth / window.innerHeight >= 4 / 3;
  const height = wide ? Math.max(window.innerHeight - top - 0.5 * fs, 14 * fs)
    : Math.max(16 * fs, Math.min(canvas.clientWidth, 0.7 * window.innerHeight));
  const ctx = fitCanvas(canvas, height);
  const W = canvas.clientWidth;
  ctx.fillStyle = "#1d2129";
  ctx.fillRect(0, 0, W, height);
  const points = classPoints();
  const curveData = (classView.curves[classView.xKey] || {})[classView.yKey] || null;
  const curve = curveData ? curveData.x.map((x, i) => [x, curveData.y[i]]).filter((p) => typeof p[1] === "number") : [];
  classView.curve = curveData;
  classView.stats = meanSd(points.map((p) => p.y));
  const yUnit = outcomeUnit(classView.yKey);
  $("class-stats").textContent = classView.stats
    ? `n = ${classView.stats.n} \u00b7 mean ${short(classView.stats.mean)} ${yUnit} \u00b7 sd ${short(classView.stats.sd)} ${yUnit}`
    : "no results yet: each student opens a lab, changes a key and runs it";
  // The legend on top, wrapped.
  const lineH = 1.25 * fs;
  const entries = [
    { name: "a student's lab", draw: (x, cy) => classDot(ctx, x + 0.65 * fs, cy, false, false) },
    { name: "closed form (the core)", draw: (x, cy) => legendLine(ctx, x, cy, PLOT_COLOURS.third) },
    { name: "mean \u00b1 sd", draw: (x, cy) => meanKey(ctx, x, cy, fs) },
  ];
  if (points.some((p) => p.others.length)) {
    entries.push({ name: "other keys changed too (or another config)", draw: (x, cy) => classDot(ctx, x + 0.65 * fs, cy, true, false) });
  }
  let y = 4;
  let x = 6;
  const key = 1.3 * fs;
  for (const entry of entries) {
    const w = key + 0.3 * fs + width(ctx, entry.name, false);
    if (x > 6 && x + w > W - 6) { x = 6; y += lineH; }
    entry.draw(x, y + 0.5 * fs);
    text(ctx, entry.name, x + key + 0.3 * fs, y, "#e8e8e8", false);
    x += w + 0.9 * fs;
  }
  y += lineH + 0.3 * fs;
  const yTitle = axisWords(classView.yKey, yUnit);
  text(ctx, yTitle, 6, y, "#c9ced6", false);
  y += lineH;
  const tickW = width(ctx, "-88.88", false) + 10;
  const area = { x: tickW, y: y + 0.5 * fs, w: W - tickW - fs, h: height - y - 3.2 * fs };
  classView.area = area;
  if (area.h < 3 * fs || area.w < 6 * fs) return;
  // The ranges: every point and the curve's.
  const xs = points.map((p) => p.x).concat(curve.map((p) => p[0]));
  const ys = points.map((p) => p.y).concat(curve.map((p) => p[1]));
  if (classView.stats) ys.push(classView.stats.mean - classView.stats.sd, classView.stats.mean + classView.stats.sd);
  let [x0, x1] = xs.length ? [Math.min(...xs), Math.max(...xs)] : [0, 1];
  let [y0, y1] = ys.length ? [Math.min(...ys), Math.max(...ys)] : [0, 1];
  if (x1 - x0 < 1e-12) { x0 -= 0.5 * Math.abs(x0 || 1); x1 += 0.5 * Math.abs(x1 || 1); }
  if (y1 - y0 < 1e-12) { y0 -= 0.5 * Math.abs(y0 || 1); y1 += 0.5 * Math.abs(y1 || 1); }
  const padX = 0.05 * (x1 - x0);
  const padY = 0.08 * (y1 - y0);
  x0 -= padX; x1 += padX; y0 -= padY; y1 += padY;
  const X = (v) => area.x + ((v - x0) / (x1 - x0)) * area.w;
  const Y = (v) => area.y + (1 - (v - y0) / (y1 - y0)) * area.h;
  ctx.strokeStyle = "#3a404c";
  ctx.lineWidth = Math.max(1, 0.05 * fs);
  ticks(y0, y1, Math.max(2, Math.min(6, Math.floor(area.h / (2 * fs))))).forEach((v) => {
    ctx.beginPath();
    ctx.moveTo(area.x, Y(v));
    ctx.lineTo(area.x + area.w, Y(v));
    ctx.stroke();
    const words = short(v);
    text(ctx, words, area.x - 6 - width(ctx, words, false), Y(v) - 0.5 * fs, "#c9ced6", false);
  });
  const xTitle = axisWords(classView.xKey, keyUnit(classView.xKey));
  const xTitleW = width(ctx, xTitle, false);
  let right = area.x + area.w - xTitleW;
  const placed = [];
  ticks(x0, x1, Math.max(2, Math.min(8, Math.floor(area.w / (5 * fs))))).forEach((v) => {
    ctx.beginPath();
    ctx.moveTo(X(v), area.y);
    ctx.lineTo(X(v), area.y + area.h);
    ctx.stroke();
    const words = short(v);
    const w = width(ctx, words, false);
    const at = Math.max(area.x, X(v) - w / 2);
    if (at + w < right - 0.5 * fs && placed.every((b) => at > b + 0.5 * fs)) {
      text(ctx, words, at, area.y + area.h + 4, "#c9ced6", false);
      placed.push(at + w);
    }
  });
  text(ctx, xTitle, area.x + area.w - xTitleW, area.y + area.h + 4 + 1.2 * fs, "#c9ced6", false);
  right = 0;
  ctx.save();
  ctx.beginPath();
  ctx.rect(area.x, area.y, area.w, area.h);
  ctx.clip();
  if (classView.stats) {
    const { mean, sd } = classView.stats;
    ctx.fillStyle = "rgba(255, 224, 102, 0.16)";
    ctx.fillRect(area.x, Y(mean + sd), area.w, Math.max(1, Y(mean - sd) - Y(mean + sd)));
    ctx.strokeStyle = PLOT_COLOURS.second;
    ctx.lineWidth = 0.7 * stroke();
    ctx.setLineDash([10, 8]);
    ctx.beginPath();
    ctx.moveTo(area.x, Y(mean));
    ctx.lineTo(area.x + area.w, Y(mean));
    ctx.stroke();
    ctx.setLineDash([]);
  }
  if (curve.length) {
    ctx.strokeStyle = PLOT_COLOURS.third;
    ctx.lineWidth = stroke();
    ctx.beginPath();
    curve.forEach((p, i) => (i ? ctx.lineTo(X(p[0]), Y(p[1])) : ctx.moveTo(X(p[0]), Y(p[1]))));
    ctx.stroke();
  }
  classView.points = points.map((p) => Object.assign(p, { px: X(p.x), py: Y(p.y) }));
  classView.pointsOf = [classView.xKey, classView.yKey]; // what the points drawn are (a test waits for its choice)
  const hover = classView.hover && classView.points.find((p) => p.lab === classView.hover.lab);
  for (const p of classView.points) classDot(ctx, p.px, p.py, p.others.length > 0, hover === p);
  ctx.restore();
  if (hover) tooltip(ctx, hover, W, height, yUnit);
}

// Round values between lo and hi, about `count` of them.
function ticks(lo, hi, count) {
  const step = niceStep(hi - lo, count);
  const list = [];
  for (let v = Math.ceil(lo / step) * step; v <= hi + 1e-9 * step; v += step) list.push(Math.abs(v) < 1e-12 * step ? 0 : v);
  return list;
}

function classDot(ctx, x, y, hollow, lit) {
  const r = (lit ? 0.5 : 0.36) * textPx();
  ctx.beginPath();
  ctx.arc(x, y, r, 0, 2 * Math.PI);
  ctx.lineWidth = Math.max(2, 0.1 * textPx());
  if (hollow) {
    ctx.strokeStyle = "#ffffff";
    ctx.stroke();
  } else {
    ctx.fillStyle = lit ? "#ffe066" : "#ffffff";
    ctx.strokeStyle = "#15181d";
    ctx.fill();
    ctx.stroke();
  }
}

function meanKey(ctx, x, cy, fs) {
  ctx.fillStyle = "rgba(255, 224, 102, 0.3)";
  ctx.fillRect(x, cy - 0.4 * fs, 1.3 * fs, 0.8 * fs);
  ctx.strokeStyle = PLOT_COLOURS.second;
  ctx.lineWidth = 0.7 * stroke();
  ctx.setLineDash([4, 3]);
  ctx.beginPath();
  ctx.moveTo(x, cy);
  ctx.lineTo(x + 1.3 * fs, cy);
  ctx.stroke();
  ctx.setLineDash([]);
}

// The student's name and values beside their point, inside the canvas.
function tooltip(ctx, p, W, H, yUnit) {
  const fs = textPx();
  const lines = [p.name, `${p.x} ${keyUnit(classView.xKey)}`.trim(), `${short(p.y)} ${yUnit}`.trim()];
  if (p.others.length) lines.push(`also: ${p.others.join(", ")}`);
  const w = Math.max(...lines.map((l, i) => width(ctx, l, i === 0))) + fs;
  const h = lines.length * 1.25 * fs + 0.5 * fs;
  let x = p.px + fs;
  let y = p.py - h - 0.5 * fs;
  if (x + w > W - 4) x = p.px - fs - w;
  if (y < 4) y = p.py + fs;
  x = Math.max(4, x);
  y = Math.min(H - h - 4, y);
  ctx.fillStyle = "#0b0d10";
  ctx.strokeStyle = "#ffe066";
  ctx.lineWidth = 2;
  ctx.fillRect(x, y, w, h);
  ctx.strokeRect(x, y, w, h);
  lines.forEach((l, i) => text(ctx, l, x + 0.5 * fs, y + 0.25 * fs + i * 1.25 * fs, i ? "#e8e8e8" : "#ffe066", i === 0));
}

function hoverAt(event) {
  const box = $("class-canvas").getBoundingClientRect();
  const x = event.clientX - box.left;
  const y = event.clientY - box.top;
  let best = null;
  let bestD = 1.2 * textPx();
  for (const p of classView.points) {
    const d = Math.hypot(p.px - x, p.py - y);
    if (d <= bestD) { best = p; bestD = d; }
  }
  if ((best && best.lab) !== (classView.hover && classView.hover.lab)) {
    classView.hover = best && { lab: best.lab, name: best.name };
    scheduleDraw();
  }
}

// --- predict, then run ---------------------------------------------------------------------------------------
function showAnswers() {
  const q = classView.question;
  const a = classView.answers;
  const state = !q ? "no question asked" : q.open ? "open" : "revealed";
  $("answers-title").textContent = q ? `${q.question} (${state}): ${a ? a.n : 0} answers` : state;
  drawHistogram($("answers"), a, q);
  if (q && q.open) $("reveal").disabled = false;
}

function ask() {
  const question = $("ask-question").value.trim();
  const choices = $("ask-choices").value.split(",").map((c) => c.trim()).filter((c) => c);
  send({ op: "ask", question, choices: choices.length ? choices : null, unit: $("ask-unit").value.trim() });
}

function showClassPanel(open) {
  $("class-panel").hidden = !open;
  $("world-view").hidden = open;
  $("class-toggle").setAttribute("aria-expanded", String(open));
  $("class-toggle").textContent = open ? "Back to the world" : "Class results";
  showQuestion();
  scheduleDraw();
}

function wireClass() {
  $("class-toggle").onclick = () => showClassPanel($("class-panel").hidden);
  $("class-x").onchange = () => { classView.wanted.x = $("class-x").value; fillClassMenus(); };
  $("class-y").onchange = () => { classView.wanted.y = $("class-y").value; fillClassMenus(); };
  $("class-canvas").addEventListener("pointermove", hoverAt);
  $("class-canvas").addEventListener("pointerdown", hoverAt);
  $("class-canvas").addEventListener("pointerleave", () => { classView.hover = null; scheduleDraw(); });
  $("ask").onclick = ask;
  $("reveal").onclick = () => send({ op: "reveal" });
  $("show-lab").onclick = () => {
    if (!$("show-lab-choice").value) return;
    send({ op: "show_lab", lab: $("show-lab-choice").value });
    showClassPanel(false); // the projected page shows it
  };
  $("show-lab-back").onclick = () => send({ op: "show_lab", lab: null });
  $("class-clear").onclick = () => send({ op: "class_clear" });
}

wireClass();
onMessage(classMessage);
onDraw(drawClass);
