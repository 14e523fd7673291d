// The lecture as a live page: one step at a time, its camera sent to the server as RON,
// its render (1 sample, then 16, at the size shown), side view, top view, and the command
// line's lines for its frame, the picked pixel's ray and (the first step) its trace,
// typeset into the step's formulas.
// The URL fragment names the step, its controls' values, the pixel and the camera, so a reload
// or a link on a slide comes back to the same state.

const state = { step: 0, params: {}, i: 200, j: 353 };
const SAMPLES = [1, 16];
const enc = encodeURIComponent;

const stepOf = () => STEPS[state.step];
const groupOf = (step) => step.group || step.id;

// The current values of `step`'s controls (its group's), defaults filled in.
function paramsOf(step) {
  const group = groupOf(step);
  const p = (state.params[group] = state.params[group] || {});
  for (const c of step.controls || []) {
    if (!c.pixel && p[c.key] === undefined) p[c.key] = c.value;
  }
  return p;
}
const cameraOf = (step) => step.camera(paramsOf(step));

function readFragment() {
  const q = new URLSearchParams(location.hash.slice(1));
  const found = STEPS.findIndex((s) => s.id === q.get("step"));
  state.step = found >= 0 ? found : 0;
  const whole = (name, max, fallback) => {
    const v = Number(q.get(name));
    return Number.isInteger(v) && v >= 1 && v <= max ? v : fallback;
  };
  state.i = whole("i", H, state.i);
  state.j = whole("j", W, state.j);
  const step = stepOf();
  const p = paramsOf(step);
  for (const c of step.controls || []) {
    const v = q.get(c.key);
    if (c.pixel || v === null) continue;
    if (c.choices) {
      if (c.choices.includes(v)) p[c.key] = v;
    } else if (Number.isFinite(Number(v)) && v !== "") {
      // As written: a button may set a value beyond its slider's range.
      p[c.key] = Number(v);
    }
  }
}

function writeFragment() {
  const step = stepOf();
  const q = new URLSearchParams();
  q.set("step", step.id);
  q.set("i", state.i);
  q.set("j", state.j);
  const p = paramsOf(step);
  for (const c of step.controls || []) if (!c.pixel) q.set(c.key, p[c.key]);
  q.set("camera", cameraOf(step));
  const hash = "#" + q.toString();
  if (location.hash !== hash) history.replaceState(null, "", hash);
  $("to-playground").href = `/#${new URLSearchParams({ camera: cameraOf(step), width: W, height: H,
    row: state.i - 1, col: state.j - 1 })}`;
}

// The step buttons across the header.
function buildNav() {
  const nav = $("steps");
  STEPS.forEach((step, k) => {
    const b = document.createElement("button");
    b.type = "button";
    b.textContent = String(k + 1);
    b.title = step.title;
    b.dataset.step = step.id;
    b.addEventListener("click", () => go(k));
    nav.append(b);
  });
}

// The step's controls: a slider with its number, or a menu; each change renders at once.
function buildControls() {
  const step = stepOf();
  const p = paramsOf(step);
  const box = $("controls");
  box.replaceChildren();
  // Many sliders (the basis's eye and up) stand in two columns, to leave room for the formulas.
  box.classList.toggle("two", (step.controls || []).length > 4);
  // The pixel's row and column side by side.
  box.classList.toggle("side", (step.controls || []).every((c) => c.pixel));
  for (const c of step.controls || []) {
    const label = document.createElement("label");
    label.append(c.label);
    if (c.choices) {
      const select = document.createElement("select");
      select.id = `control-${c.key}`;
      for (const choice of c.choices) select.append(new Option(choice, choice, false, choice === p[c.key]));
      select.addEventListener("change", () => { p[c.key] = select.value; changed(); });
      label.append(select, document.createElement("span"));
    } else {
      const value = () => (c.pixel ? state[c.key] : p[c.key]);
      const set = (v) => {
        const x = Math.min(c.max, Math.max(c.min, v));
        if (c.pixel) state[c.key] = Math.round(x); else p[c.key] = x;
      };
      const range = document.createElement("input");
      Object.assign(range, { type: "range", min: c.min, max: c.max, step: c.step, value: value() });
      range.id = `control-${c.key}`;
      const number = document.createElement("input");
      Object.assign(number, { type: "number", min: c.min, max: c.max, step: c.step, value: value() });
      number.id = `number-${c.key}`;
      range.addEventListener("input", () => { set(Number(range.value)); number.value = value(); changed(); });
      number.addEventListener("change", () => {
        if (number.value === "" || !Number.isFinite(Number(number.value))) { number.value = value(); return; }
        set(Number(number.value)); number.value = value(); range.value = value(); changed();
      });
      label.append(range, number);
    }
    box.append(label);
  }
  if (step.buttons) {
    const row = document.createElement("div");
    row.className = "buttons";
    for (const b of step.buttons) {
      const button = document.createElement("button");
      button.type = "button";
      button.textContent = b.label;
      button.addEventListener("click", () => { b.apply(p); buildControls(); changed(); });
      row.append(button);
    }
    box.append(row);
  }
}

// Shows step `k`.
function go(k) {
  state.step = Math.max(0, Math.min(STEPS.length - 1, k));
  showStep();
  changed(true);
}

function showStep() {
  const step = stepOf();
  document.body.dataset.step = step.id;
  $("title").textContent = step.title;
  $("lead").textContent = step.lead;
  $("counter").textContent = `${state.step + 1} / ${STEPS.length}`;
  for (const b of $("steps").children) {
    if (b.dataset.step === step.id) b.setAttribute("aria-current", "step"); else b.removeAttribute("aria-current");
  }
  buildControls();
}

// Requests ------------------------------------------------------------------------------

let generation = 0;
let pending = 0;
let controller = null;
let timer = null;
const lines = { frame: null, ray: null, project: null, trace: null, error: null };

function busy(delta) {
  pending += delta;
  document.body.dataset.busy = pending > 0 ? "1" : "0";
  const status = $("status");
  status.className = lines.error ? "error" : "";
  status.textContent = lines.error ? "refused: the last picture is dimmed" : pending > 0 ? "rendering…" : "";
}

// A GET that counts as busy while it runs; resolves to [ok, body as text or blob].
async function get(url, signal, asBlob) {
  busy(1);
  try {
    const response = await fetch(url, { signal, cache: "no-store" });
    const body = asBlob && response.ok ? await response.blob() : await response.text();
    return [response.ok, body];
  } finally {
    busy(-1);
  }
}
const errorOf = (body) => {
  try { return JSON.parse(body).error; } catch { return String(body); }
};

// The canvas for a view box: its shape, 540 pixels tall, as the playground's (the labels'
// sizes are the canvas's, so a box of a given height reads the same whatever its width).
function canvasFor(box) {
  const r = box.getBoundingClientRect();
  const height = 540;
  const width = r.height > 50 ? Math.round(Math.min(4000, Math.max(300, (height * r.width) / r.height))) : 900;
  return `${width}x${height}`;
}

// The picture's size: the render box's, at the lecture's W : H, in device pixels (no
// scaled-up blur); the numbers stay those of the W x H image, whose pixels it shows finer.
function pictureSize() {
  const r = $("render-box").getBoundingClientRect();
  const ratio = Math.min(window.devicePixelRatio || 1, 2);
  const scale = Math.max(0.25, Math.min(3, Math.min(r.width / W, r.height / H) * ratio));
  return [Math.round(W * scale), Math.round(H * scale)];
}

// Something changed: everything is asked for again (after a short pause while a slider
// moves, at once otherwise).
function changed(now) {
  writeFragment();
  placeMarker();
  clearTimeout(timer);
  timer = setTimeout(update, now ? 0 : 40);
}

async function update() {
  const gen = ++generation;
  if (controller) controller.abort();
  controller = new AbortController();
  const signal = controller.signal;
  const step = stepOf();
  const p = paramsOf(step);
  const base = `camera=${enc(cameraOf(step))}&width=${W}&height=${H}`;
  const pixel = `row=${state.i - 1}&col=${state.j - 1}`;
  const top = step.top ? step.top(p) : false;
  $("top-box").hidden = !top;
  document.body.dataset.shown = "";
  const points = step.project ? step.project(p) : [];
  try {
    const asks = [
      get(`/api/frame?${base}`, signal),
      get(`/api/rays?${base}&i=${state.i}&j=${state.j}`, signal),
      points.length ? get(`/api/project?${base}&${points.map((x) => `point=${x.join(",")}`).join("&")}`, signal) : null,
      step.trace ? get(`/api/trace?${base}&i=${state.i}&j=${state.j}`, signal) : null,
    ];
    const [frame, ray, project, trace] = await Promise.all(asks);
    if (gen !== generation) return;
    const refused = [frame, ray, project, trace].find((answer) => answer && !answer[0]);
    lines.error = refused ? errorOf(refused[1]) : null;
    lines.frame = frame[0] ? frame[1].trim() : null;
    lines.ray = ray[0] ? ray[1].trim() : null;
    lines.project = project && project[0] ? project[1].trim() : null;
    lines.trace = trace && trace[0] ? trace[1].trim() : null;
    showNumbers();
    $("refused").hidden = !lines.error;
    $("refused").textContent = lines.error ? `Refused: ${lines.error}` : "";
    $("render").classList.toggle("stale", Boolean(lines.error));
    busy(0);
    if (lines.error) {
      document.body.dataset.shown = "refused";
      return;
    }
    const views = [
      image("side", `/api/diagram.svg?${base}&${pixel}&canvas=${canvasFor($("side").parentElement)}`, signal, gen),
      top ? image("top", `/api/diagram.svg?${base}&${pixel}&view=top&canvas=${canvasFor($("top-box"))}`, signal, gen) : null,
    ];
    const [width, height] = pictureSize();
    const shown = `camera=${enc(cameraOf(step))}&width=${width}&height=${height}`;
    for (const samples of SAMPLES) {
      await image("render", `/api/render?${shown}&samples=${samples}`, signal, gen);
      if (gen !== generation) return;
    }
    await Promise.all(views);
    if (gen !== generation) return;
    document.body.dataset.renders = String(Number(document.body.dataset.renders) + 1);
    document.body.dataset.shown = "full";
  } catch (error) {
    if (error.name !== "AbortError") throw error;
  }
}

// Fetches an image into the element `id`, unless a newer update came first.
async function image(id, url, signal, gen) {
  let answer;
  try {
    answer = await get(url, signal, true);
  } catch (error) {
    if (error.name === "AbortError") return;
    throw error;
  }
  const [ok, body] = answer;
  if (gen !== generation) return;
  if (!ok) {
    lines.error = errorOf(body);
    $("refused").hidden = false;
    $("refused").textContent = `Refused: ${lines.error}`;
    busy(0);
    return;
  }
  const element = $(id);
  const old = element.src;
  element.src = URL.createObjectURL(body);
  await element.decode().catch(() => {});
  if (old.startsWith("blob:")) URL.revokeObjectURL(old);
  if (id === "render") placeMarker();
}

// The formulas and the command line's lines.
function showNumbers() {
  const step = stepOf();
  const ctx = { p: paramsOf(step), i: state.i, j: state.j, ray: lines.ray, frame: lines.frame,
    project: lines.project, trace: lines.trace, error: lines.error };
  $("formulas").innerHTML = step.formulas(ctx);
  $("frame-line").textContent = lines.frame || "";
  $("ray-line").textContent = lines.ray || "";
  $("trace-line").textContent = (step.trace && lines.trace) || "";
  $("trace-line").hidden = !step.trace;
}

// The picture and the pixel --------------------------------------------------------------

function imageBox() {
  const img = $("render");
  const r = img.getBoundingClientRect();
  const box = $("render-box").getBoundingClientRect();
  return { x: r.left - box.left, y: r.top - box.top, w: r.width, h: r.height, left: r.left, top: r.top };
}

function placeMarker() {
  const b = imageBox();
  const marker = $("marker");
  marker.hidden = !(b.w > 0);
  marker.style.left = `${b.x + ((state.j - 0.5) / W) * b.w}px`;
  marker.style.top = `${b.y + ((state.i - 0.5) / H) * b.h}px`;
}

function pickPixel(event) {
  const b = imageBox();
  const j = Math.floor(((event.clientX - b.left) / b.w) * W) + 1;
  const i = Math.floor(((event.clientY - b.top) / b.h) * H) + 1;
  if (i < 1 || i > H || j < 1 || j > W) return;
  state.i = i;
  state.j = j;
  for (const [key, value] of [["i", i], ["j", j]]) {
    for (const id of [`control-${key}`, `number-${key}`]) if ($(id)) $(id).value = value;
  }
  changed(true);
}

// Keys: arrows and PageUp/PageDown step (arrows move a slider that has the focus).
function onKey(event) {
  if (event.altKey || event.ctrlKey || event.metaKey) return;
  const inControl = event.target instanceof HTMLInputElement || event.target instanceof HTMLSelectElement;
  const moves = { PageDown: 1, PageUp: -1, ArrowRight: 1, ArrowLeft: -1, Home: -Infinity, End: Infinity };
  if (!(event.key in moves)) return;
  if (inControl && event.key.startsWith("Arrow")) return;
  if (inControl && (event.key === "Home" || event.key === "End")) return;
  event.preventDefault();
  const to = moves[event.key];
  go(to === -Infinity ? 0 : to === Infinity ? STEPS.length - 1 : state.step + to);
}

function start() {
  readFragment();
  buildNav();
  showStep();
  $("render").addEventListener("click", pickPixel);
  document.addEventListener("keydown", onKey);
  window.addEventListener("hashchange", () => { readFragment(); showStep(); changed(true); });
  window.addEventListener("resize", () => { placeMarker(); clearTimeout(timer); timer = setTimeout(update, 300); });
  changed(true);
}

start();
