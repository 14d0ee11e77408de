// A lab for every student: the page's own private world (the server's, built from the class's config), opened
// with the student's name from the class's world as it is now or from the lesson's start. Its controls come
// from the description of the body types (each lesson key's name, unit, range and choices); the page draws
// and plots the lab with view.js's code instead of the class's world, and can go back. The server keeps the
// lab for the page's cookie: a reload attaches the page to it again. The question the teacher poses ("predict,
// then run") is answered here too.
// What the page got of its lab is kept in rbs.lab (the browser test reads it): the lab's last message, every
// state of its run (at most LAB_STATES_KEPT a body) and every event.
"use strict";

const LAB_STATES_KEPT = 30000; // a body's states kept of the lab's run: 10 minutes at 50 Hz
const LAB_OPS = ["lab_open", "lab_run", "lab_pause", "lab_reset", "lab_close", "lab_step", "lab_set"];

const lab = {
  info: null, // the server's last `lab` message: {lab, name, config, bodies, settings, world, t, paused, from}
  opened: null, // its settings when the page first saw it: what the student changed since
  states: {}, // body -> every state of the run the page got, oldest first
  dropped: 0, // states beyond LAB_STATES_KEPT
  events: [], // the run's events
  shown: null, // the lab the teacher shows the class: {lab, name, ...} or null
  question: null, // {question, choices, unit, open}
  answer: null, // this page's answer to the open question
  hidden: "", // the question whose box the student hid
  result: null, // the answers' result, once revealed
  line: "", lineOk: true,
};
rbs.lab = lab;

// The world a lab's message describes, as view.js draws a world: every body's keys as its config has them,
// a key it leaves out as the class world's body of that name and type has it (its shape's inertia factor...),
// else the description's default; the world's settings (race...).
function labWorld(m) {
  const classWorld = stores.class.world || { settings: {}, bodies: {} };
  const bodies = {};
  for (const [name, kind] of Object.entries(m.bodies || {})) {
    const base = classWorld.bodies[name] && classWorld.bodies[name].type === kind ? classWorld.bodies[name] : {};
    const defaults = {};
    const type = rbs.description && rbs.description.types[kind];
    for (const key of type ? type.keys : []) if (key.default !== null && key.default !== undefined) defaults[key.name] = key.default;
    bodies[name] = Object.assign(defaults, base, (m.settings || {})[name] || {}, { type: kind });
  }
  return { source: "lab", paused: m.paused, settings: Object.assign({}, classWorld.settings, m.world || {}), bodies,
           parts: [], part: "" };
}

// A store takes a lab's message: the lab's world; what it had goes when the lab started again (another lab, a
// new config, or its time went back: a reset).
function takeLab(store, m, previous) {
  const latestT = Math.max(-Infinity, ...Object.values(store.latest).map((s) => s.t));
  const restarted = !previous || previous.lab !== m.lab || previous.config !== m.config || m.t < latestT;
  if (restarted) restartStore(store);
  store.world = labWorld(m);
  store.paused = m.paused;
  return restarted;
}

// A lab's last sample, which its message may carry (a paused lab's state for a page that attaches to it).
function takeLastStates(store, m) {
  for (const [body, s] of Object.entries(m.states || {})) {
    const last = store.latest[body];
    if (s && (!last || s.t > last.t)) addState(store, body, s);
  }
}

function labStoresOf(id) {
  const found = [];
  if (lab.info && lab.info.lab === id) found.push(stores.lab);
  if (lab.shown && lab.shown.lab === id) found.push(stores.shown);
  return found;
}

function labMessage(m) {
  if (m.type === "lab") {
    const first = !lab.info || lab.info.lab !== m.lab;
    if (takeLab(stores.lab, m, lab.info)) {
      lab.states = {};
      lab.dropped = 0;
      lab.events = [];
    }
    lab.info = m;
    takeLastStates(stores.lab, m);
    if (first) {
      lab.opened = JSON.parse(JSON.stringify(m.settings || {}));
      $("lab-panel").hidden = false;
      showStore(stores.lab);
    }
    if (showing === stores.lab) fillSelects();
    showLabControls();
  } else if (m.type === "lab_frame") {
    for (const store of labStoresOf(m.lab)) {
      for (const [body, states] of Object.entries(m.states)) {
        for (const s of states) {
          const last = store.latest[body];
          if (last && s.t < last.t) restartStore(store); // a restart the page has not heard of yet
          if (!last || s.t !== last.t) addState(store, body, s);
        }
      }
    }
    if (lab.info && lab.info.lab === m.lab) {
      for (const [body, states] of Object.entries(m.states)) {
        const list = (lab.states[body] = lab.states[body] || []);
        for (const s of states) {
          if (list.length && s.t < list[list.length - 1].t) list.length = 0;
          if (list.length && s.t === list[list.length - 1].t) continue; // its last sample, sent again
          if (list.length < LAB_STATES_KEPT) list.push(s);
          else lab.dropped += 1;
        }
      }
      showLabState();
    }
  } else if (m.type === "lab_events") {
    for (const store of labStoresOf(m.lab)) setEvents(store, m.events, m.all);
    if (lab.info && lab.info.lab === m.lab) lab.events = m.all ? m.events.slice() : lab.events.concat(m.events);
  } else if (m.type === "lab_closed") {
    if (lab.info && lab.info.lab === m.lab) {
      lab.info = null;
      restartStore(stores.lab);
      stores.lab.world = null;
      if (showing === stores.lab) showStore(lab.shown ? stores.shown : stores.class);
      showLabControls();
    }
    labLine(m.line, true);
  } else if (m.type === "shown_lab") {
    showTheLab(m);
  } else if (m.type === "question") {
    if (!lab.question || lab.question.question !== m.question || m.open && !lab.question.open) {
      lab.answer = null;
      lab.result = null;
    }
    lab.question = m;
    showQuestion();
  } else if (m.type === "answers") {
    if (lab.question && !lab.question.open) {
      lab.result = m;
      showQuestion();
    }
  } else if (m.type === "reply") {
    const op = opOf(m.id);
    if (LAB_OPS.includes(op) || op === "answer") labLine(m.line, m.ok);
    if (op === "lab_set" && !m.ok) showLabValue(true); // the field shows the value that runs again
  }
}

// The lab the teacher shows: every page watching the class's world shows it; a student in their own lab
// keeps it (the switch above the scene goes to it).
function showTheLab(m) {
  if (m.lab === null || m.lab === undefined) {
    lab.shown = null;
    restartStore(stores.shown);
    stores.shown.world = null;
    if (showing === stores.shown) showStore(stores.class);
  } else {
    takeLab(stores.shown, m, lab.shown);
    takeLastStates(stores.shown, m);
    lab.shown = m;
    if (showing === stores.class || showing === stores.shown) showStore(stores.shown);
  }
  showLabControls();
}

function opOf(id) {
  const sent = rbs.sent.find((r) => r.id === id);
  return sent ? sent.op : "";
}

function labLine(text, ok) {
  lab.line = text;
  lab.lineOk = ok;
  const el = $("lab-line");
  el.textContent = text;
  el.className = ok ? "ok" : "refused";
}

// --- the panel ---------------------------------------------------------------------------------------------
function showLabControls() {
  const open = Boolean(lab.info);
  $("lab-open-form").hidden = open;
  $("lab-controls").hidden = !open;
  $("lab-toggle").textContent = open ? `My lab (${lab.info.name})` : "My lab";
  $("lab-toggle").setAttribute("aria-expanded", String(!$("lab-panel").hidden));
  const shown = $("showing");
  const words = showing === stores.lab ? `showing: my lab (${lab.info ? lab.info.name : ""})`
    : showing === stores.shown && lab.shown ? `showing: ${lab.shown.name}'s lab` : "";
  shown.textContent = words;
  shown.hidden = !words;
  shown.className = showing === stores.lab ? "mine" : "theirs";
  if (!open) return;
  $("lab-title").textContent = `${lab.info.name}'s lab`;
  $("lab-download").href = `lab/${encodeURIComponent(lab.info.lab)}.zip`;
  $("lab-download").setAttribute("download", `lab_${lab.info.lab}.zip`);
  $("lab-show").hidden = showing === stores.lab;
  $("lab-show-class").hidden = showing !== stores.lab;
  $("lab-show-class").textContent = lab.shown ? `Show ${lab.shown.name}'s lab` : "Show the class's world";
  fillLabBodies();
  showChanged();
  showLabState();
}

function showLabState() {
  if (!lab.info) return;
  const list = Object.values(stores.lab.latest);
  const t = list.length ? Math.max(...list.map((s) => s.t)) : lab.info.t;
  $("lab-state").textContent = `t = ${t.toFixed(2)} s, ${stores.lab.paused ? "paused" : "running"}`;
}

function fillLabBodies() {
  const sel = $("lab-body");
  const names = Object.keys(stores.lab.world ? stores.lab.world.bodies : {});
  const was = sel.value;
  if (sel.options.length !== names.length || [...sel.options].some((o, i) => o.value !== names[i])) {
    sel.replaceChildren(...names.map((n) => new Option(n, n)));
  }
  if (names.includes(was)) sel.value = was;
  fillLabKeys();
}

// The lesson keys of the chosen body's type, as the description gives them.
function lessonKeys(b) { return b ? described(b).keys.filter((k) => k.lesson) : []; }
function labBody() { return stores.lab.world && stores.lab.world.bodies[$("lab-body").value]; }

function fillLabKeys() {
  const keys = lessonKeys(labBody()).map((k) => k.name);
  const sel = $("lab-key");
  const was = sel.value;
  if (sel.options.length !== keys.length || [...sel.options].some((o, i) => o.value !== keys[i])) {
    sel.replaceChildren(...keys.map((k) => new Option(k, k)));
  }
  if (keys.includes(was)) sel.value = was;
  showLabValue(false);
}

// The chosen key's field: a menu of its choices, or a number's field, with its unit and what is allowed; the
// value that runs, unless the student is typing another (or `refused`: a refusal puts it back).
function showLabValue(refused) {
  const b = labBody();
  const key = lessonKeys(b).find((k) => k.name === $("lab-key").value);
  const box = $("lab-value-box");
  if (!key) { box.replaceChildren(); return; }
  const choices = key.choices && key.choices.length ? key.choices : null;
  let field = $("lab-value");
  const wanted = choices ? "SELECT" : "INPUT";
  if (!field || field.tagName !== wanted || field.dataset.key !== key.name) {
    field = document.createElement(wanted.toLowerCase());
    field.id = "lab-value";
    field.dataset.key = key.name;
    field.setAttribute("aria-label", `${key.name} (${key.meaning})`);
    if (choices) field.replaceChildren(...choices.map((c) => new Option(c, c)));
    else {
      field.type = "text";
      field.inputMode = "decimal";
      field.addEventListener("keydown", (e) => { if (e.key === "Enter") setLabKey(); });
    }
    box.replaceChildren(field);
    refused = true;
  }
  if (refused || document.activeElement !== field) field.value = String(b[key.name]);
  $("lab-unit").textContent = key.unit === "rad" ? `rad (${deg(Number(b[key.name]))})` : key.unit;
  $("lab-allowed").textContent = `${key.meaning}: ${key.allowed}`;
}

function setLabKey() {
  const field = $("lab-value");
  if (!field) return;
  const text = field.value.trim();
  const choices = field.tagName === "SELECT";
  // A number field's text as JSON's number (an empty or unreadable one is sent as it is: the server refuses it).
  const value = choices || text === "" || !isFinite(Number(text)) ? text : Number(text);
  send({ op: "lab_set", body: $("lab-body").value, key: $("lab-key").value, value });
  field.blur();
}

// The student's changes since the lab opened: each key that differs.
function showChanged() {
  const changes = [];
  for (const [body, keys] of Object.entries((lab.info && lab.info.settings) || {})) {
    const before = (lab.opened || {})[body] || {};
    for (const [key, value] of Object.entries(keys)) {
      if (key in before && before[key] !== value) changes.push(`${body} ${key} ${before[key]} \u2192 ${value}`);
    }
  }
  $("lab-changed").textContent = changes.length ? `changed: ${changes.join("; ")}` : "";
}

function openLab() {
  const name = $("lab-name").value.trim();
  if (!name) {
    labLine("type your name first, then Open my lab", false);
    $("lab-name").focus();
    return;
  }
  localStorage.setItem("rbs_lab_name", name);
  send({ op: "lab_open", from: $("lab-from").value, name });
}

// --- predict, then run ---------------------------------------------------------------------------------------
function showQuestion() {
  const q = lab.question;
  const box = $("question-box");
  // The teacher's page shows the answers in the class's view while it is open.
  box.hidden = !q || (!q.open && !lab.result) || lab.hidden === q.question
    || (rbs.control && !$("class-panel").hidden);
  if (box.hidden) return;
  $("question-text").textContent = q.open ? q.question : `${q.question} (answers closed)`;
  const choices = q.choices && q.choices.length ? q.choices : null;
  const answering = q.open && !rbs.control; // the teacher's page shows the question, and its answers in class.js
  $("question-choices").hidden = !answering || !choices;
  $("question-number").hidden = !answering || Boolean(choices);
  if (answering && choices) {
    const shown = [...$("question-choices").children].map((b) => b.dataset.choice);
    if (shown.join("\u0000") !== choices.join("\u0000")) {
      $("question-choices").replaceChildren(...choices.map((c, i) => {
        const button = document.createElement("button");
        button.type = "button";
        button.id = `answer-${i}`;
        button.dataset.choice = c;
        button.textContent = c;
        button.onclick = () => answer(c);
        return button;
      }));
    }
    for (const button of $("question-choices").children) {
      button.classList.toggle("chosen", button.dataset.choice === lab.answer);
    }
  }
  $("answer-unit").textContent = q.unit || "";
  $("question-mine").textContent = lab.answer === null ? ""
    : `your answer: ${lab.answer}${choices ? "" : ` ${q.unit || ""}`}${q.open ? " (you may change it until the reveal)" : ""}`;
  drawHistogram($("question-result"), lab.result, q);
}

function answer(value) {
  lab.answer = value;
  send({ op: "answer", answer: value });
  showQuestion();
}

function answerNumber() {
  const text = $("answer-value").value.trim();
  const value = text !== "" && isFinite(Number(text)) ? Number(text) : text; // the server refuses a non-number
  answer(value);
}

// The answers as bars: each choice's count, or the numbers in at most 8 bins of a round width. Shared with
// class.js (the teacher's view of the answers as they come).
function histogramRows(result, q) {
  if (!result) return [];
  if (result.counts) {
    const names = q && q.choices ? q.choices.slice() : [];
    for (const name of Object.keys(result.counts)) if (!names.includes(name)) names.push(name);
    return names.map((name) => ({ label: name, n: result.counts[name] || 0 }));
  }
  const values = (result.values || []).filter((v) => typeof v === "number" && isFinite(v));
  if (!values.length) return [];
  const lo = Math.min(...values);
  const hi = Math.max(...values);
  if (hi === lo) return [{ label: `${lo}`, n: values.length }];
  const step = niceStep(hi - lo, Math.min(6, Math.max(2, values.length)));
  const first = Math.floor(lo / step) * step;
  const bins = Math.max(1, Math.min(12, Math.floor((hi - first) / step) + 1));
  const rows = [];
  const digits = Math.max(0, -Math.floor(Math.log10(step) + 1e-9));
  for (let i = 0; i < bins; i += 1) {
    const a = first + i * step;
    rows.push({ label: `${a.toFixed(digits)} to ${(a + step).toFixed(digits)}`, n: 0, lo: a, hi: a + step });
  }
  for (const v of values) rows[Math.min(bins - 1, Math.floor((v - first) / step))].n += 1;
  return rows;
}

function drawHistogram(el, result, q) {
  const rows = histogramRows(result, q);
  const most = Math.max(1, ...rows.map((r) => r.n));
  const unit = q && q.unit && !(q.choices && q.choices.length) ? ` ${q.unit}` : "";
  el.replaceChildren(...rows.map((r) => {
    const row = document.createElement("div");
    row.className = "bar-row";
    const label = document.createElement("span");
    label.className = "bar-label";
    label.textContent = `${r.label}${unit}`;
    const bar = document.createElement("span");
    bar.className = "bar";
    bar.style.width = `${(70 * r.n) / most}%`; // CSSOM: the page's policy allows no inline style attribute
    const count = document.createElement("span");
    count.className = "bar-count";
    count.textContent = String(r.n);
    row.append(label, bar, count);
    return row;
  }));
  if (result) el.dataset.n = String(result.n);
  return rows;
}

// --- wiring --------------------------------------------------------------------------------------------------
function wireLab() {
  $("lab-name").value = localStorage.getItem("rbs_lab_name") || "";
  $("lab-toggle").onclick = () => {
    $("lab-panel").hidden = !$("lab-panel").hidden;
    showLabControls();
    scheduleDraw();
  };
  $("lab-open").onclick = openLab;
  $("lab-name").addEventListener("keydown", (e) => { if (e.key === "Enter") openLab(); });
  $("lab-run").onclick = () => send({ op: "lab_run" });
  $("lab-pause").onclick = () => send({ op: "lab_pause" });
  $("lab-reset").onclick = () => send({ op: "lab_reset" });
  $("lab-close").onclick = () => send({ op: "lab_close" });
  $("lab-step").onclick = () => send({ op: "lab_step", steps: Number($("lab-steps").value) });
  $("lab-set").onclick = setLabKey;
  $("lab-body").onchange = fillLabKeys;
  $("lab-key").onchange = () => showLabValue(true);
  $("lab-show").onclick = () => { showStore(stores.lab); showLabControls(); };
  $("lab-show-class").onclick = () => { showStore(lab.shown ? stores.shown : stores.class); showLabControls(); };
  $("answer-send").onclick = answerNumber;
  $("question-hide").onclick = () => { lab.hidden = lab.question ? lab.question.question : ""; showQuestion(); scheduleDraw(); };
  $("answer-value").addEventListener("keydown", (e) => { if (e.key === "Enter") answerNumber(); });
}

wireLab();
onMessage(labMessage);
for (const op of [...LAB_OPS, "answer"]) linesShownElsewhere.add(op);
