// viewray's live playground. The state is the camera as RON text (a scene file's
// `camera:` value) with the image size, samples, shading and the chosen pixel; the URL
// fragment holds all of it. The server computes every number and picture: this page
// only edits the RON, sends it, and shows what comes back.
"use strict";

const served = JSON.parse(document.getElementById("served").textContent);
const $ = (id) => document.getElementById(id);

// ---------------------------------------------------------------------------------
// RON: a small reader and writer for camera values (numbers, identifiers, strings,
// tuples and structs, named or not, lists and maps, comments).

class RonError extends Error {
  constructor(message, offset, text) {
    const before = text.slice(0, offset);
    const line = before.split("\n").length;
    const column = offset - before.lastIndexOf("\n");
    super(`camera:${line}:${column}: ${message}`);
  }
}

function parseRon(text) {
  let i = 0;
  const fail = (message) => { throw new RonError(message, i, text); };
  const skip = () => {
    for (;;) {
      while (i < text.length && /\s/.test(text[i])) i++;
      if (text.startsWith("//", i)) {
        const end = text.indexOf("\n", i);
        i = end < 0 ? text.length : end + 1;
      } else if (text.startsWith("/*", i)) {
        const end = text.indexOf("*/", i + 2);
        if (end < 0) fail("unterminated comment");
        i = end + 2;
      } else return;
    }
  };
  const peek = () => { skip(); return text[i]; };
  const expect = (c) => { if (peek() !== c) fail(`expected \`${c}\``); i++; };
  const ident = () => {
    skip();
    const m = /^[A-Za-z_][A-Za-z0-9_]*/.exec(text.slice(i));
    if (!m) fail("expected a name");
    i += m[0].length;
    return m[0];
  };
  const isFieldStart = () => {
    skip();
    const m = /^[A-Za-z_][A-Za-z0-9_]*\s*:(?!:)/.exec(text.slice(i));
    return m !== null;
  };
  const inner = (name, close) => {
    // After `(`: a struct's fields or a tuple's items.
    if (isFieldStart()) {
      const fields = [];
      while (peek() !== close) {
        const key = ident();
        expect(":");
        fields.push({ key, value: value() });
        if (peek() === ",") i++; else break;
      }
      expect(close);
      return { kind: "struct", name, fields };
    }
    const items = [];
    while (peek() !== close) {
      items.push(value());
      if (peek() === ",") i++; else break;
    }
    expect(close);
    return { kind: "tuple", name, items };
  };
  const value = () => {
    const c = peek();
    if (c === undefined) fail("unexpected end of the camera");
    if (c === "(") { i++; return inner(null, ")"); }
    if (c === "[") {
      i++;
      const items = [];
      while (peek() !== "]") { items.push(value()); if (peek() === ",") i++; else break; }
      expect("]");
      return { kind: "list", items };
    }
    if (c === "{") {
      i++;
      const entries = [];
      while (peek() !== "}") {
        const key = value(); expect(":"); entries.push({ key, value: value() });
        if (peek() === ",") i++; else break;
      }
      expect("}");
      return { kind: "map", entries };
    }
    if (c === '"') {
      const m = /^"(?:[^"\\]|\\.)*"/.exec(text.slice(i));
      if (!m) fail("unterminated string");
      i += m[0].length;
      return { kind: "str", text: m[0] };
    }
    const number = /^[+-]?(?:\d+\.?\d*(?:[eE][+-]?\d+)?|\.\d+(?:[eE][+-]?\d+)?|inf|NaN)/.exec(text.slice(i));
    if (number && /[-+.\d]/.test(c) || (number && /^(inf|NaN)$/.test(number[0]))) {
      i += number[0].length;
      return { kind: "num", value: Number(number[0].replace("inf", "Infinity")), text: number[0] };
    }
    const name = ident();
    if (peek() === "(") { i++; return inner(name, ")"); }
    return { kind: "ident", name };
  };
  const result = value();
  if (peek() !== undefined) fail("unexpected text after the camera");
  return result;
}

function formatNumber(x) {
  if (!Number.isFinite(x)) return String(x);
  let s = String(Math.round(x * 1e6) / 1e6);
  if (s.includes("e")) s = x.toFixed(9).replace(/0+$/, "");
  if (s === "-0") s = "0";
  return /[.]/.test(s) ? s : s + ".0";
}

function writeRon(node, pretty) {
  const w = (n) => writeRon(n, false);
  switch (node.kind) {
    case "num": return node.text !== undefined ? node.text : formatNumber(node.value);
    case "ident": return node.name;
    case "str": return node.text;
    case "list": return `[${node.items.map(w).join(", ")}]`;
    case "map": return `{${node.entries.map((e) => `${w(e.key)}: ${w(e.value)}`).join(", ")}}`;
    case "tuple": return `${node.name || ""}(${node.items.map(w).join(", ")})`;
    case "struct": {
      const fields = node.fields.map((f) => `${f.key}: ${w(f.value)}`);
      if (pretty && !node.name) return `(\n    ${fields.join(",\n    ")},\n)`;
      return `${node.name || ""}(${fields.join(", ")})`;
    }
  }
  return "";
}

const num = (value) => ({ kind: "num", value });
const vec = (values) => ({ kind: "tuple", name: null, items: values.map(num) });

function field(node, key) {
  if (!node || node.kind !== "struct") return undefined;
  const f = node.fields.find((f) => f.key === key);
  return f && f.value;
}
function setField(node, key, value, after) {
  const f = node.fields.find((f) => f.key === key);
  if (f) { f.value = value; return; }
  let at = node.fields.length;
  if (after) {
    const k = node.fields.findIndex((f) => f.key === after);
    if (k >= 0) at = k + 1;
  }
  node.fields.splice(at, 0, { key, value });
}
function removeField(node, key) {
  node.fields = node.fields.filter((f) => f.key !== key);
}
function numberOf(node, fallback) {
  return node && node.kind === "num" ? node.value : fallback;
}
function vecOf(node, fallback) {
  if (node && node.kind === "tuple" && node.items.every((n) => n.kind === "num")) {
    return node.items.map((n) => n.value);
  }
  return fallback;
}

// ---------------------------------------------------------------------------------
// The state.

const PRESETS = ["Front", "Top", "Side", "Isometric", "Dimetric", "Trimetric", "Cavalier",
  "Cabinet", "OnePoint", "TwoPoint", "ThreePoint"];
const FAMILIES = ["Perspective", "ThinLens", "Orthographic", "Oblique", "Fisheye", "Equirectangular"];

const state = {
  camera: served.camera,
  width: served.width,
  height: served.height,
  samples: served.samples,
  shading: served.shading,
  pixel: null, // [row, col], 0-based
};
let model = null; // the camera's RON tree, when the page can read it
let lastFrame = null; // {e, u, v, w} as numbers
let lastCameraControl = "ron";

function readFragment() {
  const params = new URLSearchParams(location.hash.slice(1));
  const int = (name, fallback) => {
    const v = params.get(name);
    return v !== null && /^\d+$/.test(v) ? Number(v) : fallback;
  };
  state.camera = params.get("camera") || served.camera;
  state.width = int("width", served.width);
  state.height = int("height", served.height);
  state.samples = int("samples", served.samples);
  state.shading = params.get("shading") || served.shading;
  const row = int("row", -1), col = int("col", -1);
  state.pixel = row >= 0 && col >= 0 ? [row, col] : null;
}

function writeFragment() {
  const params = new URLSearchParams();
  params.set("camera", state.camera);
  params.set("width", state.width);
  params.set("height", state.height);
  params.set("samples", state.samples);
  params.set("shading", state.shading);
  if (state.pixel) { params.set("row", state.pixel[0]); params.set("col", state.pixel[1]); }
  const hash = "#" + params.toString();
  if (location.hash !== hash) history.replaceState(null, "", hash);
}

function cameraQuery(extra) {
  const params = new URLSearchParams();
  params.set("camera", state.camera);
  params.set("width", state.width);
  params.set("height", state.height);
  for (const [k, v] of Object.entries(extra || {})) params.set(k, v);
  return params.toString();
}

// ---------------------------------------------------------------------------------
// Requests: one channel per view; the newest request wins. A full-size render in
// flight is aborted by a newer request; a preview in flight finishes (it is quick, and
// shows the motion), and is shown unless something newer has been shown.

class Channel {
  constructor(handle) {
    this.handle = handle;
    this.inflight = null;
    this.pending = null;
    this.retry = null;
  }
  send(url, meta) {
    clearTimeout(this.retry);
    if (this.inflight && this.inflight.meta.abortable) this.inflight.controller.abort();
    this.pending = { url, meta: meta || {} };
    this.pump();
  }
  busy() { return this.inflight !== null || this.pending !== null; }
  async pump() {
    if (this.inflight || !this.pending) return;
    const job = this.pending;
    this.pending = null;
    job.controller = new AbortController();
    this.inflight = job;
    updateBusy();
    let response = null, body = null, aborted = false, failure = null;
    try {
      response = await fetch(job.url, { signal: job.controller.signal });
      if (response.ok) body = await (job.meta.blob ? response.blob() : response.text());
      else body = await response.json().catch(() => ({ error: response.statusText }));
    } catch (error) {
      if (error.name === "AbortError") aborted = true; else failure = error;
    }
    this.inflight = null;
    if (!aborted) {
      const superseded = this.pending !== null;
      if (failure) {
        if (!superseded) showStatus(`cannot reach the server: ${failure.message}`, "error");
      } else if (response.status === 503 && !superseded) {
        showStatus("the server is busy: retrying", "busy");
        this.retry = setTimeout(() => this.send(job.url, job.meta), 1000);
      } else {
        this.handle(job, response, body, superseded);
      }
    }
    updateBusy();
    this.pump();
  }
}

function updateBusy() {
  const busy = channels.some((c) => c.busy());
  document.body.dataset.busy = busy ? "1" : "0";
  if (busy) showStatus("rendering…", "busy");
}

function showStatus(text, kind) {
  const status = $("status");
  status.textContent = text;
  status.className = kind || "";
}

let renderUrl = null;
let renderedSize = null; // [width, height] of the image shown
const renderChannel = new Channel((job, response, body, superseded) => {
  if (!response.ok) {
    if (!superseded) { showError(body.error); document.body.classList.add("stale"); }
    return;
  }
  const url = URL.createObjectURL(body);
  const image = $("render");
  const previous = renderUrl;
  renderUrl = url;
  image.onload = () => {
    if (previous) URL.revokeObjectURL(previous);
    placeMarker();
  };
  image.src = url;
  renderedSize = job.meta.size;
  document.body.dataset.renders = String(Number(document.body.dataset.renders) + 1);
  if (!superseded) {
    clearErrors();
    document.body.classList.remove("stale");
    const timing = /render;dur=([\d.]+)/.exec(response.headers.get("Server-Timing") || "");
    const ms = timing ? ` · ${Math.round(Number(timing[1]))} ms` : "";
    const [w, h] = job.meta.size;
    const kind = job.meta.preview ? "preview " : "";
    showStatus(`${kind}${w} × ${h}, ${job.meta.samples} sample${job.meta.samples > 1 ? "s" : ""}${ms}`);
    document.body.dataset.shown = job.meta.preview ? "preview" : "full";
  }
});

let diagramUrl = null;
const diagramChannel = new Channel((job, response, body) => {
  if (!response.ok) return; // the render reports the same error
  const url = URL.createObjectURL(body);
  const previous = diagramUrl;
  diagramUrl = url;
  $("diagram").onload = () => { if (previous) URL.revokeObjectURL(previous); };
  $("diagram").src = url;
});

const frameChannel = new Channel((job, response, body) => {
  if (!response.ok) return;
  for (const key of ["e", "u", "v", "w"]) {
    $(`frame-${key}`).textContent = tupleText(rawArray(body, key));
  }
  lastFrame = JSON.parse(body);
});

const rayChannel = new Channel((job, response, body, superseded) => {
  if (!response.ok) {
    // Errors of the camera or the size are the render's to show.
    if (!superseded && errorTarget(body.error, "camera") === "pixel") showError(body.error, "pixel");
    return;
  }
  const [row, col] = job.meta.pixel;
  $("ray-title").innerHTML =
    `Pixel row ${row}, col ${col} <span class="ij">· lecture (<i>i</i>, <i>j</i>) = (${row + 1}, ${col + 1})</span>`;
  $("ray").hidden = false;
  $("ray-uv").textContent = `${rawValue(body, "u")}, ${rawValue(body, "v")}`;
  $("ray-origin").textContent = tupleText(rawArray(body, "origin"));
  $("ray-direction").textContent = tupleText(rawArray(body, "direction"));
  $("ray-json").textContent = `$ viewray rays SCENE --pixel ${row},${col}\n${body.trim()}`;
  setError("pixel", "");
});

// The clicked pixel's trace, as `viewray trace` prints it: the lecture's pseudocode for
// the pixel of a one-sample render, every number beside its formula (the server's text,
// from the same code as the command line's).
const traceChannel = new Channel((job, response, body) => {
  if (!response.ok) return; // the ray's request shows the same pixel error
  const [row, col] = job.meta.pixel;
  $("trace-title").textContent = `The pixel's trace: viewray trace SCENE --pixel ${row},${col}`;
  $("trace").textContent = body;
  $("trace-box").hidden = false;
});

function requestTrace() {
  if (!state.pixel) { $("trace-box").hidden = true; return; }
  const [row, col] = state.pixel;
  const query = cameraQuery({ shading: state.shading, row, col, format: "text" });
  traceChannel.send(`/api/trace?${query}`, { pixel: state.pixel });
}

const channels = [renderChannel, diagramChannel, frameChannel, rayChannel, traceChannel];

// The numbers exactly as the server printed them (the command line's digits).
function rawArray(text, key) {
  const m = new RegExp(`"${key}":(null|\\[[^\\]]*\\])`).exec(text);
  if (!m || m[1] === "null") return null;
  return m[1].slice(1, -1).split(",");
}
function rawValue(text, key) {
  const m = new RegExp(`"${key}":(null|[-+0-9.eE]+)`).exec(text);
  return m ? (m[1] === "null" ? "none" : m[1]) : "";
}
function tupleText(parts) {
  return parts ? `(${parts.join(", ")})` : "none (no ray)";
}

// What to render now: a preview while a control moves, the full image when it stops.
function previewSize() {
  const budget = 320 * 200;
  const scale = Math.min(1, Math.sqrt(budget / (state.width * state.height)));
  return [Math.max(1, Math.round(state.width * scale)), Math.max(1, Math.round(state.height * scale))];
}

function request(mode) {
  const preview = mode === "preview";
  const size = preview ? previewSize() : [state.width, state.height];
  const samples = preview ? 1 : state.samples;
  const params = new URLSearchParams();
  params.set("camera", state.camera);
  params.set("width", size[0]);
  params.set("height", size[1]);
  params.set("samples", samples);
  params.set("shading", state.shading);
  renderChannel.send(`/api/render?${params}`, {
    blob: true, preview, size, samples, abortable: !preview,
  });
  const pixel = state.pixel ? { row: state.pixel[0], col: state.pixel[1] } : {};
  diagramChannel.send(`/api/diagram.svg?${cameraQuery(pixel)}`, { blob: true });
  frameChannel.send(`/api/frame?${cameraQuery()}`);
  if (state.pixel) {
    rayChannel.send(`/api/rays?${cameraQuery(pixel)}`, { pixel: state.pixel });
  }
  requestTrace();
}

// ---------------------------------------------------------------------------------
// Errors, shown next to the control that caused them.

function errorTarget(message, fallback) {
  const name = (/^(\w+)/.exec(message) || [])[1];
  if (name === "width" || name === "height") return "size";
  if (name === "samples" || name === "shading") return name;
  if (name === "row" || name === "col" || name === "i" || name === "j") return "pixel";
  return fallback || lastCameraControl;
}

function setError(target, message) {
  let output = document.querySelector(`output.error[data-for="${target}"]`);
  if (!output) output = document.querySelector('output.error[data-for="ron"]');
  output.textContent = message;
}

function showError(message, fallback) {
  clearErrors();
  const target = errorTarget(message, fallback);
  setError(target, message);
  showStatus("error: see the control", "error");
  document.querySelectorAll(".invalid").forEach((e) => e.classList.remove("invalid"));
  const control = document.querySelector(`[data-control="${target}"]`);
  if (control) control.classList.add("invalid");
}

function clearErrors() {
  document.querySelectorAll("output.error").forEach((o) => {
    if (o.dataset.for !== "pixel") o.textContent = "";
  });
  document.querySelectorAll(".invalid").forEach((e) => e.classList.remove("invalid"));
}

// ---------------------------------------------------------------------------------
// Controls.

function commit(mode, fromRonBox) {
  if (model && !fromRonBox) state.camera = writeRon(model, false);
  if (!fromRonBox) $("ron").value = model ? writeRon(model, true) : state.camera;
  writeFragment();
  request(mode);
}

// A labelled slider with a number box, for `get`/`set` of one number.
function slider(container, spec) {
  const row = document.createElement("div");
  row.className = "slider";
  const label = document.createElement("span");
  label.innerHTML = spec.label;
  const range = document.createElement("input");
  range.type = "range";
  const box = document.createElement("input");
  box.type = "number";
  box.step = "any";
  range.min = spec.min; range.max = spec.max; range.step = spec.step;
  range.setAttribute("aria-label", spec.name);
  box.setAttribute("aria-label", spec.name);
  range.id = `range-${spec.id}`;
  box.id = `number-${spec.id}`;
  const show = () => {
    const v = spec.get();
    if (v < Number(range.min)) range.min = v;
    if (v > Number(range.max)) range.max = v;
    range.value = v;
    box.value = formatNumber(v).replace(/\.0$/, "");
  };
  const quantize = (v) => {
    const decimals = (String(spec.step).split(".")[1] || "").length;
    return Number(Number(v).toFixed(decimals));
  };
  range.addEventListener("input", () => {
    lastCameraControl = spec.group;
    spec.set(quantize(range.value));
    box.value = formatNumber(spec.get()).replace(/\.0$/, "");
    commit("preview");
  });
  range.addEventListener("change", () => { lastCameraControl = spec.group; commit("full"); });
  box.addEventListener("change", () => {
    const v = Number(box.value);
    if (box.value.trim() === "" || !Number.isFinite(v)) { show(); return; }
    lastCameraControl = spec.group;
    spec.set(v);
    show();
    commit("full");
  });
  row.append(label, range, box);
  container.append(row);
  show();
  return show;
}

// A group of sliders for one parameter, with its error line.
function group(container, id, title) {
  const div = document.createElement("div");
  div.dataset.control = id;
  if (title) {
    const t = document.createElement("div");
    t.className = "group-title";
    t.innerHTML = title;
    div.append(t);
  }
  const error = document.createElement("output");
  error.className = "error";
  error.dataset.for = id;
  container.append(div);
  return { div, finish: () => div.append(error) };
}

function vectorSliders(container, node, key, title, range, step, fallback) {
  const g = group(container, key, title);
  const axes = ["x", "y", "z"];
  for (let k = 0; k < 3; k++) {
    slider(g.div, {
      id: `${key}-${axes[k]}`, group: key, name: `${key} ${axes[k]}`, label: axes[k],
      min: -range, max: range, step,
      get: () => vecOf(field(node, key), fallback)[k],
      set: (v) => {
        const value = vecOf(field(node, key), fallback).slice();
        value[k] = v;
        setField(node, key, vec(value));
      },
    });
  }
  g.finish();
}

function numberSlider(container, node, key, spec) {
  const g = group(container, key, spec.title);
  slider(g.div, {
    id: key, group: key, name: key, label: spec.label, min: spec.min, max: spec.max, step: spec.step,
    get: () => numberOf(field(node, key), spec.fallback),
    set: (v) => setField(node, key, num(v), spec.after),
  });
  g.finish();
}

function note(container, html) {
  const p = document.createElement("p");
  p.className = "note";
  p.innerHTML = html;
  container.append(p);
}

function kindOf(node) {
  if (!node || node.kind !== "struct") return null;
  if (node.name) return PRESETS.includes(node.name) ? node.name : null;
  const projection = field(node, "projection");
  if (!projection) return null;
  const name = projection.kind === "ident" ? projection.name : projection.name;
  return FAMILIES.includes(name) ? name : null;
}

function buildControls() {
  const params = $("projection-params");
  const pose = $("pose-params");
  params.replaceChildren();
  pose.replaceChildren();
  const kind = kindOf(model);
  $("kind").value = kind || "";
  $("kind").disabled = kind === null;
  if (kind === null) {
    note(params, "This camera is beyond the controls: edit its RON below.");
    return;
  }
  if (PRESETS.includes(kind)) {
    vectorSliders(pose, model, "target", "target (the point looked at)", 20, 0.01, [0, 0, 0]);
    numberSlider(pose, model, "size", {
      title: "size (the extent the view spans)", label: "size", min: 0.1, max: 40, step: 0.05, fallback: 4,
    });
    if (kind === "Cavalier" || kind === "Cabinet") {
      numberSlider(params, model, "angle", {
        title: "receding axis angle <i>φ</i> (degrees)", label: "<i>φ</i>", min: -180, max: 180,
        step: 1, fallback: 45,
      });
    }
    note(params, presetNote(kind));
    return;
  }
  // An explicit camera: eye, look-at or view, up; then the projection's parameters.
  vectorSliders(pose, model, "eye", "eye <b>e</b>", 20, 0.01, [0, 0, 0]);
  if (field(model, "view")) {
    vectorSliders(pose, model, "view", "view direction", 10, 0.01, [0, 0, -1]);
  } else {
    vectorSliders(pose, model, "look_at", "look-at point", 20, 0.01, [0, 0, 0]);
  }
  vectorSliders(pose, model, "up", "up", 1, 0.01, [0, 1, 0]);
  const projection = field(model, "projection");
  if (kind === "Equirectangular") {
    note(params, "Every direction: longitude across, latitude up and down.");
    return;
  }
  if (kind === "Fisheye") {
    numberSlider(params, projection, "fov", {
      title: "field of view (degrees)", label: "fov", min: 1, max: 360, step: 1, fallback: 180,
    });
    return;
  }
  const perspective = kind === "Perspective" || kind === "ThinLens";
  if (perspective) {
    numberSlider(params, projection, "distance", {
      title: "distance to the image plane <i>d</i>", label: "<i>d</i>", min: 0.05, max: 5, step: 0.01,
      fallback: 1,
    });
  }
  windowControls(params, projection, perspective);
  if (perspective) {
    const g = group(params, "shift", "shift <i>s<sub>x</sub></i>, <i>s<sub>y</sub></i> (on the image plane)");
    for (const [k, axis] of [[0, "x"], [1, "y"]]) {
      slider(g.div, {
        id: `shift-${axis}`, group: "shift", name: `shift ${axis}`, label: `<i>s<sub>${axis}</sub></i>`,
        min: -2, max: 2, step: 0.01,
        get: () => vecOf(field(projection, "shift"), [0, 0])[k],
        set: (v) => {
          const s = vecOf(field(projection, "shift"), [0, 0]).slice();
          s[k] = v;
          setField(projection, "shift", vec(s));
        },
      });
    }
    g.finish();
  }
  if (kind === "Oblique") {
    numberSlider(params, projection, "ratio", {
      title: "ratio <i>L</i> (1 cavalier, ½ cabinet)", label: "<i>L</i>", min: 0, max: 2, step: 0.01,
      fallback: 0.5,
    });
    numberSlider(params, projection, "angle", {
      title: "angle <i>φ</i> (degrees)", label: "<i>φ</i>", min: -180, max: 180, step: 1, fallback: 45,
    });
  }
  if (kind === "ThinLens" || (kind === "Orthographic" && field(projection, "aperture"))) {
    numberSlider(params, projection, "aperture", {
      title: "aperture (lens radius <i>r</i>)", label: "<i>r</i>", min: 0.001, max: 1, step: 0.001,
      fallback: 0.1,
    });
    numberSlider(params, projection, "focus", {
      title: "focus distance <i>f</i>", label: "<i>f</i>", min: 0.1, max: 40, step: 0.05, fallback: 5,
    });
  }
}

function presetNote(kind) {
  const notes = {
    Front: "Multiview orthographic: the image plane perpendicular to z.",
    Top: "Multiview orthographic: looking straight down.",
    Side: "Multiview orthographic: the image plane perpendicular to x.",
    Isometric: "Axonometric: every axis foreshortened by √(2/3) ≈ 0.8165, 120° apart.",
    Dimetric: "Axonometric: two axes at the same scale (0.9428), the third at 0.4714.",
    Trimetric: "Axonometric: three different scales.",
    Cavalier: "Oblique, <i>L</i> = 1: depth at full length, projectors at 45°.",
    Cabinet: "Oblique, <i>L</i> = ½: depth at half length, projectors at 63.4°.",
    OnePoint: "Perspective with the image plane parallel to two principal axes.",
    TwoPoint: "Perspective with verticals parallel to the image plane: they stay parallel.",
    ThreePoint: "Perspective, camera tilted: verticals converge.",
  };
  return `${notes[kind]} Pick a family above to edit every parameter.`;
}

// The image window: viewport vw × vh, or a field of view, or a height.
function windowControls(container, projection, perspective) {
  const modes = perspective
    ? [["viewport", "viewport <i>vw</i> × <i>vh</i>"], ["fov_y", "vertical field of view"],
       ["fov_x", "horizontal field of view"]]
    : [["viewport", "viewport <i>vw</i> × <i>vh</i>"], ["height", "height <i>vh</i> (vw follows the image)"]];
  const present = modes.find(([key]) => field(projection, key));
  const mode = present ? present[0] : null;
  const g = group(container, "window", null);
  const label = document.createElement("label");
  label.className = "row wide";
  label.textContent = "window ";
  const select = document.createElement("select");
  select.id = "window-mode";
  for (const [key, text] of modes) {
    const option = document.createElement("option");
    option.value = key;
    option.innerHTML = text;
    select.append(option);
  }
  if (!mode) {
    const option = document.createElement("option");
    option.value = "";
    option.textContent = "as written in the RON";
    select.append(option);
  }
  select.value = mode || "";
  label.append(select);
  g.div.append(label);
  select.addEventListener("change", () => {
    lastCameraControl = "window";
    convertWindow(projection, mode, select.value, perspective);
    buildControls();
    commit("full");
  });
  if (mode === "viewport") {
    for (const [k, name] of [[0, "vw"], [1, "vh"]]) {
      slider(g.div, {
        id: `viewport-${name}`, group: "window", name, label: `<i>${name}</i>`,
        min: 0.05, max: perspective ? 5 : 40, step: 0.01,
        get: () => vecOf(field(projection, "viewport"), [1, 0.75])[k],
        set: (v) => {
          const value = vecOf(field(projection, "viewport"), [1, 0.75]).slice();
          value[k] = v;
          setField(projection, "viewport", vec(value));
        },
      });
    }
  } else if (mode === "fov_y" || mode === "fov_x") {
    slider(g.div, {
      id: mode, group: "window", name: mode, label: "degrees", min: 1, max: 179, step: 0.5,
      get: () => numberOf(field(projection, mode), 40),
      set: (v) => setField(projection, mode, num(v)),
    });
  } else if (mode === "height") {
    slider(g.div, {
      id: "height-world", group: "window", name: "height", label: "<i>vh</i>", min: 0.1, max: 40, step: 0.05,
      get: () => numberOf(field(projection, "height"), 3),
      set: (v) => setField(projection, "height", num(v)),
    });
  }
  g.finish();
}

// Converts the window from one way of writing it to another, keeping the picture.
function convertWindow(projection, from, to, perspective) {
  const aspect = state.width / state.height;
  const d = numberOf(field(projection, "distance"), 1);
  let vh = 1;
  if (from === "viewport") vh = vecOf(field(projection, "viewport"), [1, 1])[1];
  if (from === "height") vh = numberOf(field(projection, "height"), 1);
  if (from === "fov_y") vh = 2 * d * Math.tan(numberOf(field(projection, "fov_y"), 40) * Math.PI / 360);
  if (from === "fov_x") vh = 2 * d * Math.tan(numberOf(field(projection, "fov_x"), 40) * Math.PI / 360) / aspect;
  for (const key of ["viewport", "fov_y", "fov_x", "height"]) removeField(projection, key);
  const round = (x) => Math.round(x * 1e4) / 1e4;
  const after = perspective ? "distance" : undefined;
  if (to === "viewport") setField(projection, "viewport", vec([round(vh * aspect), round(vh)]), after);
  if (to === "height") setField(projection, "height", num(round(vh)));
  if (to === "fov_y") setField(projection, "fov_y", num(round(2 * Math.atan(vh / (2 * d)) * 180 / Math.PI)), after);
  if (to === "fov_x") setField(projection, "fov_x", num(round(2 * Math.atan(vh * aspect / (2 * d)) * 180 / Math.PI)), after);
}

// The camera of another kind, keeping what carries over.
function convertKind(to) {
  const from = kindOf(model);
  const round = (v) => v.map((x) => Math.round(x * 1e4) / 1e4);
  const distanceTo = (eye, target) => Math.hypot(...eye.map((x, k) => x - target[k])) || 5;
  if (PRESETS.includes(to)) {
    let target = [0, 0, 0], size = 4;
    if (from && PRESETS.includes(from)) {
      target = vecOf(field(model, "target"), target);
      size = numberOf(field(model, "size"), size);
    } else if (from) {
      const eye = vecOf(field(model, "eye"), [0, 0, 5]);
      const look = field(model, "look_at");
      const view = vecOf(field(model, "view"), [0, 0, -1]);
      target = look ? vecOf(look, target) : round(eye.map((x, k) => x + view[k] * 5 / Math.hypot(...view)));
      const projection = field(model, "projection");
      size = numberOf(field(projection, "height"), vecOf(field(projection, "viewport"), [0, size])[1]);
      if (from === "Perspective" || from === "ThinLens") size = 4;
    }
    const fields = [{ key: "target", value: vec(target) }, { key: "size", value: num(size) }];
    model = { kind: "struct", name: to, fields };
    return;
  }
  // An explicit camera.
  let eye, target, up;
  if (from && !PRESETS.includes(from)) {
    const projection = field(model, "projection");
    const old = projection;
    const distance = distanceTo(vecOf(field(model, "eye"), [0, 0, 5]),
      vecOf(field(model, "look_at"), vecOf(field(model, "eye"), [0, 0, 5]).map((x, k) => x + vecOf(field(model, "view"), [0, 0, -1])[k] * 5)));
    setField(model, "projection", newProjection(to, old, from, distance));
    return;
  }
  // From a preset: its frame, from the server's last answer.
  const presetTarget = from ? vecOf(field(model, "target"), [0, 0, 0]) : [0, 0, 0];
  if (lastFrame) {
    eye = round(lastFrame.e);
    up = round(lastFrame.v);
    target = presetTarget;
  } else {
    eye = [0, 1, 5]; target = presetTarget; up = [0, 1, 0];
  }
  model = {
    kind: "struct", name: null, fields: [
      { key: "eye", value: vec(eye) },
      { key: "look_at", value: vec(target) },
      { key: "up", value: vec(up) },
      { key: "projection", value: newProjection(to, null, from, distanceTo(eye, target)) },
    ],
  };
}

function newProjection(to, old, from, distance) {
  const keep = (keys) => (old && old.kind === "struct" ? old.fields.filter((f) => keys.includes(f.key)) : []);
  const struct = (fields) => ({ kind: "struct", name: to, fields });
  const perspectiveFrom = from === "Perspective" || from === "ThinLens";
  const windowOf = () => {
    // A parallel window `height` seen at `distance` is a field of view, and back.
    if (perspectiveFrom) return keep(["distance", "viewport", "fov_y", "fov_x", "shift"]);
    const h = old ? numberOf(field(old, "height"), vecOf(field(old, "viewport"), [0, 4])[1]) : 4;
    return [{ key: "fov_y", value: num(Math.round(2 * Math.atan(h / (2 * distance)) * 1800 / Math.PI) / 10) }];
  };
  switch (to) {
    case "Perspective": return struct(windowOf());
    case "ThinLens": return struct([...windowOf(),
      { key: "aperture", value: num(0.1) },
      { key: "focus", value: num(Math.round(distance * 100) / 100) }]);
    case "Orthographic":
    case "Oblique": {
      let fields = keep(["viewport", "height"]);
      if (fields.length === 0) {
        let h = 4;
        if (old && perspectiveFrom) {
          const d = numberOf(field(old, "distance"), 1);
          const fov = numberOf(field(old, "fov_y"), null);
          const vh = fov !== null ? 2 * d * Math.tan(fov * Math.PI / 360) : vecOf(field(old, "viewport"), [1, 1])[1];
          h = vh * distance / d;
        }
        fields = [{ key: "height", value: num(Math.round(h * 100) / 100) }];
      }
      if (to === "Oblique") {
        fields.push({ key: "ratio", value: num(0.5) }, { key: "angle", value: num(45) });
      }
      return struct(fields);
    }
    case "Fisheye": return struct([{ key: "fov", value: num(180) }]);
    default: return { kind: "ident", name: "Equirectangular" };
  }
}

// ---------------------------------------------------------------------------------
// The image settings, the RON box, the buttons, the pixel.

const SIZES = [[320, 180], [320, 240], [640, 360], [640, 480], [800, 600], [960, 540],
  [1280, 720], [1920, 1080]];

function buildImageControls() {
  const select = $("size-preset");
  select.replaceChildren();
  const sizes = SIZES.slice();
  if (!sizes.some(([w, h]) => w === served.width && h === served.height)) {
    sizes.unshift([served.width, served.height]);
  }
  for (const [w, h] of sizes) {
    const option = document.createElement("option");
    option.value = `${w}x${h}`;
    option.textContent = `${w} × ${h}${w === served.width && h === served.height ? " (the scene's)" : ""}`;
    select.append(option);
  }
  const custom = document.createElement("option");
  custom.value = "";
  custom.textContent = "other (type below)";
  select.append(custom);
  const samples = $("samples");
  samples.replaceChildren();
  const counts = [1, 2, 4, 8, 16, 32, 64, 128, 256];
  if (!counts.includes(served.samples)) counts.push(served.samples);
  counts.sort((a, b) => a - b);
  for (const n of counts) {
    const option = document.createElement("option");
    option.value = n;
    option.textContent = n === 1 ? "1 (the pixel centre)" : String(n);
    samples.append(option);
  }
  const shading = $("shading");
  shading.replaceChildren();
  for (const name of served.shadings) {
    const option = document.createElement("option");
    option.value = option.textContent = name;
    shading.append(option);
  }
  $("size-preset").parentElement.dataset.control = "size";
  $("width").parentElement.parentElement.dataset.control = "size";
  samples.parentElement.dataset.control = "samples";
  shading.parentElement.dataset.control = "shading";
}

function showImageSettings() {
  $("width").value = state.width;
  $("height").value = state.height;
  const key = `${state.width}x${state.height}`;
  const select = $("size-preset");
  select.value = [...select.options].some((o) => o.value === key) ? key : "";
  const samples = $("samples");
  if (![...samples.options].some((o) => Number(o.value) === state.samples)) {
    const option = document.createElement("option");
    option.value = option.textContent = state.samples;
    samples.append(option);
  }
  samples.value = state.samples;
  $("shading").value = state.shading;
}

function setSize(width, height) {
  const [oldWidth, oldHeight] = [state.width, state.height];
  state.width = width;
  state.height = height;
  if (state.pixel) {
    // Keep the chosen pixel where it was in the picture.
    const [row, col] = state.pixel;
    state.pixel = [Math.min(height - 1, Math.floor((row + 0.5) / oldHeight * height)),
      Math.min(width - 1, Math.floor((col + 0.5) / oldWidth * width))];
  }
  showImageSettings();
  commit("full");
}

function loadState() {
  try {
    model = parseRon(state.camera);
    setError("ron", "");
  } catch (error) {
    model = null;
    setError("ron", error.message);
  }
  $("ron").value = model && kindOf(model) ? writeRon(model, true) : state.camera;
  buildControls();
  showImageSettings();
  if (!state.pixel) {
    $("ray").hidden = true;
    $("ray-title").textContent = "Viewing ray: click a pixel";
    $("ray-json").textContent = "";
  }
  placeMarker();
}

function imageGeometry() {
  const image = $("render");
  const box = image.getBoundingClientRect();
  const natural = [image.naturalWidth || state.width, image.naturalHeight || state.height];
  const scale = Math.min(box.width / natural[0], box.height / natural[1]);
  const content = [natural[0] * scale, natural[1] * scale];
  return { box, left: (box.width - content[0]) / 2, top: (box.height - content[1]) / 2, content };
}

function placeMarker() {
  const marker = $("marker");
  if (!state.pixel || !$("render").naturalWidth) { marker.hidden = true; return; }
  const g = imageGeometry();
  const [row, col] = state.pixel;
  marker.style.left = `${g.left + (col + 0.5) / state.width * g.content[0]}px`;
  marker.style.top = `${g.top + (row + 0.5) / state.height * g.content[1]}px`;
  marker.hidden = false;
}

function pickPixel(event) {
  const g = imageGeometry();
  const x = (event.clientX - g.box.left - g.left) / g.content[0];
  const y = (event.clientY - g.box.top - g.top) / g.content[1];
  if (x < 0 || x >= 1 || y < 0 || y >= 1) return;
  state.pixel = [Math.floor(y * state.height), Math.floor(x * state.width)];
  placeMarker();
  writeFragment();
  const pixel = { row: state.pixel[0], col: state.pixel[1] };
  rayChannel.send(`/api/rays?${cameraQuery(pixel)}`, { pixel: state.pixel });
  diagramChannel.send(`/api/diagram.svg?${cameraQuery(pixel)}`, { blob: true });
  requestTrace();
}

async function copyRon() {
  const text = $("ron").value;
  const button = $("copy-ron");
  try {
    await navigator.clipboard.writeText(text);
  } catch {
    // Outside a secure context (a class reaching the lecturer's laptop by address).
    const area = $("ron");
    area.focus();
    area.select();
    document.execCommand("copy");
  }
  button.textContent = "Copied";
  button.classList.add("done");
  setTimeout(() => { button.textContent = "Copy as RON"; button.classList.remove("done"); }, 1500);
}

function applyRon() {
  const text = $("ron").value.trim();
  lastCameraControl = "ron";
  try {
    model = parseRon(text);
  } catch (error) {
    setError("ron", error.message);
    return;
  }
  state.camera = text;
  buildControls();
  commit("full", true);
}

function start() {
  buildImageControls();
  readFragment();
  loadState();
  writeFragment();
  request("full");

  $("render").addEventListener("click", pickPixel);
  window.addEventListener("resize", placeMarker);
  $("kind").addEventListener("change", () => {
    lastCameraControl = "kind";
    convertKind($("kind").value);
    buildControls();
    commit("full");
  });
  $("size-preset").addEventListener("change", () => {
    const value = $("size-preset").value;
    if (!value) return;
    const [w, h] = value.split("x").map(Number);
    setSize(w, h);
  });
  for (const id of ["width", "height"]) {
    $(id).addEventListener("change", () => {
      const w = Number($("width").value), h = Number($("height").value);
      if (!Number.isInteger(w) || !Number.isInteger(h)) return;
      setSize(w, h);
    });
  }
  $("samples").addEventListener("change", () => { state.samples = Number($("samples").value); commit("full"); });
  $("shading").addEventListener("change", () => { state.shading = $("shading").value; commit("full"); });
  $("apply-ron").addEventListener("click", applyRon);
  $("ron").addEventListener("keydown", (event) => {
    if (event.key === "Enter" && (event.ctrlKey || event.metaKey)) { event.preventDefault(); applyRon(); }
  });
  $("copy-ron").addEventListener("click", copyRon);
  $("reset").addEventListener("click", () => {
    history.replaceState(null, "", location.pathname);
    readFragment();
    loadState();
    clearErrors();
    commit("full", true);
  });
  window.addEventListener("hashchange", () => {
    readFragment();
    loadState();
    request("full");
  });
}

start();
