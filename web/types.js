// What the web page draws and plots of each body type: the one place of the page that names a type. Every
// fact the core's description has (keys, units, defaults, whether a type races, its state fields) comes from
// the server's hello (body_types.json), not from here; an entry holds what the description cannot say: how
// the body is drawn, what its plots show and which of its type's events they mark (`marks`: an event kind's
// name, and its legend's words). When anything happened, and at what speed, comes from the node's events:
// nothing here computes an instant.
// view.js dispatches through BODY_TYPES[b.type]; a type missing here is drawn as its name alone.
// Entries use view.js's drawing helpers (text, wrap, width, panelFrame, stroke, textPx, fixed3, COLOURS,
// PLOT_COLOURS), which exist by the time anything is drawn.
"use strict";

// The bodies' colours: a roller's by its shape, the rod's and its marked end A, the block's.
const COLOURS = { sphere: "#f0a030", cylinder: "#4fa3ff", ring: "#e05080", spherical_shell: "#6bd06b",
                  custom: "#c0a0ff", rod: "#4f8cff", rod_end: "#ff8a3d", block: "#ff66cc" };

const BODY_TYPES = {
  rod: {
    scene: "floor", // a band of its own across the scene's width, below the slopes
    kinetic(b, s) {
      return 0.5 * b.mass * (s.vx * s.vx + s.vy * s.vy) + 0.5 * (b.mass * b.length * b.length / 12) * s.omega * s.omega;
    },
    ends(b, s) {
      const h = 0.5 * b.length;
      return { a: s.y + h * Math.sin(s.theta), b: s.y - h * Math.sin(s.theta) };
    },
    mode(b, s) {
      const e = this.ends(b, s);
      return e.a < 0 || e.b < 0 ? "on the floor" : "in the air";
    },
    plotValues(b, s, p) {
      const e = this.ends(b, s);
      p.end_a = e.a;
      p.end_b = e.b;
    },
    motion(series) {
      return { title: "height of each end", unit: "m",
               lines: [{ key: "end_a", name: "end A (orange)", colour: COLOURS.rod_end, pts: series("end_a") },
                       { key: "end_b", name: "end B", colour: PLOT_COLOURS.first, pts: series("end_b") }] };
    },
    potentialZero: "floor level",
    drawPanel(ctx, rect, name, b, s, lineH, type, size) { drawFloorPanel(ctx, rect, name, b, s, lineH, type, size); },
    // The least height of its panel `w` wide: its label, the floor's band, and the rod's world three texts high.
    minHeight(ctx, name, b, w, lineH, size) {
      return 8 + floorLabel(ctx, name, b, null, w, size).kept * lineH + floorBandPx() + 3 * textPx() + 4;
    },
  },

  roller: {
    scene: "slope",
    kind: (b) => b.shape, // its title's word beside its name
    halfSize: (b) => b.radius,
    tanCritical: (b) => b.mu_s * (1 + b.inertia_factor) / b.inertia_factor, // rolls without slipping
    verdicts: ["can roll", "slips"],
    kinetic(b, s) {
      return 0.5 * b.mass * s.v * s.v + 0.5 * b.inertia_factor * b.mass * b.radius * b.radius * s.omega * s.omega;
    },
    plotValues(b, s, p) {
      p.v = s.v;
      p.minus_omega_r = -s.omega * b.radius;
    },
    motion(series) {
      return { title: "v and \u2212\u03c9R", unit: "m/s",
               lines: [{ key: "v", name: "v", colour: PLOT_COLOURS.first, pts: series("v") },
                       { key: "minus_omega_r", name: "\u2212\u03c9R", colour: PLOT_COLOURS.second, dash: [10, 6],
                         pts: series("minus_omega_r") }] };
    },
    marks: { slip_to_roll: "slip \u2192 roll" }, // a dot on the motion plot at the event's instant and state
    potentialZero: "the slope's top",
    // A disc with a spoke at its rotation theta about the slope's z; a ring or a shell as its rim.
    drawBody(ctx, cx, cy, rad, phi, b, s) {
      const a = s.theta - phi;
      const sx = cx + rad * Math.cos(a);
      const sy = cy - rad * Math.sin(a);
      const colour = COLOURS[b.shape] || COLOURS.custom;
      ctx.beginPath();
      ctx.arc(cx, cy, rad, 0, 2 * Math.PI);
      if (b.shape === "ring" || b.shape === "spherical_shell") {
        ctx.strokeStyle = colour;
        ctx.lineWidth = Math.max(stroke(), rad * (b.shape === "ring" ? 0.3 : 0.2));
        ctx.stroke();
      } else {
        ctx.fillStyle = colour;
        ctx.fill();
      }
      ctx.strokeStyle = "#ffffff";
      ctx.lineWidth = Math.max(2, rad * 0.12);
      ctx.beginPath();
      ctx.moveTo(cx, cy);
      ctx.lineTo(sx, sy);
      ctx.stroke();
      return { sx, sy };
    },
  },

  block: {
    scene: "slope",
    kind: () => "block",
    halfSize: (b) => 0.5 * b.size,
    tanCritical: (b) => b.mu_s, // at rest, static friction holds it
    verdicts: ["can stick", "slides"],
    kinetic(b, s) { return 0.5 * b.mass * s.v * s.v; },
    plotValues(b, s, p) { p.v = s.v; },
    motion(series) {
      return { title: "v", unit: "m/s",
               lines: [{ key: "v", name: "v", colour: PLOT_COLOURS.first, pts: series("v") }] };
    },
    marks: { came_to_rest: "comes to rest" },
    potentialZero: "the slope's top",
    // A square resting on the slope, turned with it.
    drawBody(ctx, cx, cy, rad, phi) {
      ctx.save();
      ctx.translate(cx, cy);
      ctx.rotate(phi);
      ctx.fillStyle = COLOURS.block;
      ctx.fillRect(-rad, -rad, 2 * rad, 2 * rad);
      ctx.restore();
      return { sx: cx, sy: cy };
    },
  },
};

// The floor's band, with the metre marks (px).
function floorBandPx() { return 1.6 * textPx() + 10; }

// A rod's label in its panel `w` wide: its lines, and the lines kept for it (keepLines, under `size`).
function floorLabel(ctx, name, b, s, w, size) {
  const mode = s ? BODY_TYPES.rod.mode(b, s) : "\u2013";
  const energy = s ? `E = ${fixed3(s.energy)} J \u00b7` : "E = \u2013 \u00b7";
  const head = wrap(ctx, [`${titleOf(name, b)}: ${mode}`], w - 12, true);
  const info = wrap(ctx, [energy, `k = ${withUnit(b, "k")} \u00b7`, `L = ${withUnit(b, "length")}`], w - 12, false);
  // Room for its label in either mode, at an energy of three digits: the scale stays when the mode changes.
  const heads = ["on the floor", "in the air"].map((m) => wrap(ctx, [`${titleOf(name, b)}: ${m}`], w - 12, true));
  const infos = wrap(ctx, ["E = -888.888 J \u00b7", `k = ${withUnit(b, "k")} \u00b7`, `L = ${withUnit(b, "length")}`],
                     w - 12, false);
  const widest = Math.max(...heads.map((h) => h.length)) + infos.length;
  return { head, info, kept: keepLines(size, Math.max(widest, head.length + info.length)) };
}

// A metre marks' step: 1, 2 or 5 times a power of ten metres, the least at least `least` m (marks no closer
// than a label's width, so a frame draws as many as fit its width, whatever its scale).
function markStep(least) {
  const power = Math.pow(10, Math.floor(Math.log10(Math.max(least, 1))));
  return [1, 2, 5, 10].map((n) => n * power).find((n) => n >= least);
}

// The rod from the side (section 16.3.3): the floor's band with its metre marks, followed along x (a bounded
// floor whole where it fits), the rod with its end A marked; `size` names the panel's size (keepLines). The
// panel is at least its type's minHeight high (drawScene).
function drawFloorPanel(ctx, rect, name, b, s, lineH, type, size) {
  const { head, info, kept } = floorLabel(ctx, name, b, s, rect.w, size);
  const areaTop = panelFrame(ctx, rect, head, info, lineH, kept);
  const area = { x: rect.x + 6, y: areaTop, w: rect.w - 12, h: rect.y + rect.h - areaTop - 4 };
  const top = Math.max(b.y0 + 0.5 * b.length, 1.5) * 1.1;
  const floorPx = floorBandPx();
  const scale = Math.min(Math.max(area.h - floorPx, textPx()) / top, area.w / (2.5 * b.length));
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
  ctx.restore();
  // The metre marks, every metre or every few where they would crowd; a label only where it fits whole.
  ctx.strokeStyle = "#c9ced6";
  ctx.lineWidth = 0.7 * stroke();
  const every = markStep((width(ctx, `${-Math.ceil(Math.abs(left) + span)} m`, false) + 12) / scale);
  let lastRight = -Infinity;
  for (let m = Math.ceil(floorFrom / every) * every; m <= floorTo; m += every) {
    if (X(m) < area.x || X(m) > area.x + area.w) continue;
    ctx.beginPath();
    ctx.moveTo(X(m), Y(0));
    ctx.lineTo(X(m), Y(0) + 0.4 * textPx());
    ctx.stroke();
    const words = `${m} m`;
    const w = width(ctx, words, false);
    const at = Math.min(X(m) + 3, area.x + area.w - w);
    if (at >= area.x && at > lastRight + 6) {
      text(ctx, words, at, Y(0) + 0.5 * textPx(), "#e8e8e8", false);
      lastRight = at + w;
    }
  }
  rbs.panels[name] = { scale, ox, oy, left, rect };
  if (s) {
    ctx.save();
    ctx.beginPath();
    ctx.rect(area.x, area.y, area.w, area.h);
    ctx.clip();
    const h = 0.5 * b.length;
    const ax = X(s.x + h * Math.cos(s.theta));
    const ay = Y(s.y + h * Math.sin(s.theta));
    const bx = X(s.x - h * Math.cos(s.theta));
    const by = Y(s.y - h * Math.sin(s.theta));
    ctx.strokeStyle = COLOURS.rod;
    ctx.lineWidth = Math.max(7, 0.35 * textPx());
    ctx.lineCap = "round";
    ctx.beginPath();
    ctx.moveTo(bx, by);
    ctx.lineTo(ax, ay);
    ctx.stroke();
    ctx.fillStyle = COLOURS.rod_end;
    ctx.beginPath();
    ctx.arc(ax, ay, Math.max(6, 0.3 * textPx()), 0, 2 * Math.PI);
    ctx.fill();
    ctx.restore();
    rbs.drawn[name] = Object.assign({}, s, { cx: X(s.x), cy: Y(s.y), ax, ay, bx, by });
  }
}
