// viewray's live playground, part 2 of 4: the state and the requests. The state is the
// camera as RON text (a scene file's `camera:` value) with the image size, samples,
// shading, the catalogue's mistakes the camera makes, the chosen pixel and how the page
// shows them; the URL fragment holds all of it. The server computes every number and picture: this page only edits the RON, sends
// it, and shows what comes back. Each view has a channel where the newest request wins;
// the render comes in passes of 1, then 4, then 16... samples, each shown as it
// finishes; a camera the server refuses is shown with its error beside the control, and
// everything (controls, numbers, picture, URL) goes back to the last camera it rendered.

const served = JSON.parse(document.getElementById("served").textContent);
const $ = (id) => document.getElementById(id);

const PRESETS = ["Front", "Top", "Side", "Isometric", "Dimetric", "Trimetric", "Cavalier",
  "Cabinet", "OnePoint", "TwoPoint", "ThreePoint"];
const FAMILIES = ["Perspective", "ThinLens", "Orthographic", "Oblique", "Fisheye", "Equirectangular"];
const TOPICS = ["projection", "pose", "image", "ron"];

const state = {
  camera: served.camera,
  width: served.width,
  height: served.height,
  samples: served.samples,
  shading: served.shading,
  mistakes: "", // the catalogue's ids, comma-separated in its order ("" for none)
  pixel: null, // [row, col], 0-based
  top: null, // the top view: true or false as chosen, null as the kind suggests
  pixels: false, // show the image's own W x H pixels rather than render at the size shown
  topic: "projection",
};
let model = null; // the camera's RON tree, when the page can read it
let lastFrame = null; // {e, u, v, w} as numbers
let lastCameraControl = "ron";
let accepted = null; // the last settings the server took: their render and their frame
let lastRefused = null; // the settings the server last refused
let rendered = null; // the settings of the last picture rendered
let framed = null; // the settings of the last frame answered

// The settings shown are accepted once both their picture (at the size shown) and their
// frame (the camera at W x H) came back: the errors beside the controls go.
function acceptIfBoth() {
  const current = settingsOf(state);
  if (sameSettings(rendered, current) && sameSettings(framed, current) && !sameSettings(accepted, current)) {
    accepted = current;
    clearErrors();
  }
}
let samplesAsked = null; // samples a link asked for beyond what the server renders

// What a render depends on.
function settingsOf(s) {
  return {
    camera: s.camera, width: s.width, height: s.height, samples: s.samples, shading: s.shading,
    mistakes: s.mistakes || "",
  };
}
function sameSettings(a, b) {
  return a !== null && b !== null
    && ["camera", "width", "height", "samples", "shading", "mistakes"].every((k) => a[k] === b[k]);
}

// The catalogue's ids in `text` (comma-separated), known ones only, in its order.
function mistakesOf(text) {
  const ids = (text || "").split(",").map((id) => id.trim());
  return served.catalogue.filter((entry) => ids.includes(entry.id)).map((entry) => entry.id).join(",");
}

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
  // A link asking for more samples than the server renders at its size gets the most it
  // does, and says so.
  const most = mostSamples(state.width, state.height);
  samplesAsked = state.samples > most && state.width > 0 && state.height > 0 ? state.samples : null;
  if (samplesAsked !== null) state.samples = most;
  state.shading = params.get("shading") || served.shading;
  state.mistakes = mistakesOf(params.get("mistakes"));
  const row = int("row", -1), col = int("col", -1);
  state.pixel = row >= 0 && col >= 0 ? [row, col] : null;
  const top = params.get("top");
  state.top = top === "1" ? true : top === "0" ? false : null;
  state.pixels = params.get("pixels") === "image";
  state.topic = TOPICS.includes(params.get("topic")) ? params.get("topic") : "projection";
}

function writeFragment() {
  const params = new URLSearchParams();
  params.set("camera", state.camera);
  params.set("width", state.width);
  params.set("height", state.height);
  params.set("samples", state.samples);
  params.set("shading", state.shading);
  if (state.mistakes) params.set("mistakes", state.mistakes);
  if (state.pixel) { params.set("row", state.pixel[0]); params.set("col", state.pixel[1]); }
  if (state.top !== null) params.set("top", state.top ? "1" : "0");
  if (state.pixels) params.set("pixels", "image");
  if (state.topic !== "projection") params.set("topic", state.topic);
  const hash = "#" + params.toString();
  if (location.hash !== hash) history.replaceState(null, "", hash);
  updateSaveLinks();
}

// The query of the camera at W x H, with the mistakes it makes unless `right` asks for
// the camera as written.
function cameraQuery(extra, right) {
  const params = new URLSearchParams();
  params.set("camera", state.camera);
  params.set("width", state.width);
  params.set("height", state.height);
  if (state.mistakes && !right) params.set("mistakes", state.mistakes);
  for (const [k, v] of Object.entries(extra || {})) params.set(k, v);
  return params.toString();
}

// ---------------------------------------------------------------------------------
// Requests: one channel per view; the newest request wins. A render pass in flight is
// aborted by a newer request; a preview in flight finishes (it is quick, and shows the
// motion), and is shown unless something newer has been shown. The renders carry this
// page's ticket, its name and the render's turn: the server stops a render it is still
// making for this page as soon as a later one comes (answering the abandoned one 409), so
// an abandoned picture holds no render slot.

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
      // No cache at all: the answers change with the camera, and a browser holding a
      // second request for a URL until the first comes back would stall a view.
      response = await fetch(job.url, { signal: job.controller.signal, cache: "no-store" });
      if (response.ok) body = await (job.meta.blob ? response.blob() : response.text());
      else body = await response.json().catch(() => ({ error: response.statusText }));
    } catch (error) {
      if (error.name === "AbortError") aborted = true; else failure = error;
    }
    this.inflight = null;
    if (!aborted) {
      const superseded = this.pending !== null;
      if (failure) {
        if (!superseded) setResult(`cannot reach the server: ${failure.message}`, "error");
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

// The status line: "rendering..." while anything is in flight, else what the last
// render (or refusal) said.
let result = { text: "", kind: "" };
function setResult(text, kind) {
  result = { text, kind: kind || "" };
  updateBusy();
}
function updateBusy() {
  const busy = channels.some((c) => c.busy());
  document.body.dataset.busy = busy ? "1" : "0";
  if (busy) showStatus(renderChannel.busy() && passShowing ? `${passShowing} · refining…` : "rendering…", "busy");
  else showStatus(result.text, result.kind);
}
function showStatus(text, kind) {
  const status = $("status");
  status.textContent = text;
  status.className = kind || "";
}

// The size the picture is rendered at: the size it is shown at on this screen (the
// render box's device pixels at the image's aspect ratio), so nothing is scaled up; or,
// showing the image's own pixels, W x H.
function displaySize() {
  if (state.pixels) return [state.width, state.height];
  const box = $("render").getBoundingClientRect();
  if (box.width < 8 || box.height < 8) return [state.width, state.height];
  const ratio = Math.min(window.devicePixelRatio || 1, 2);
  let scale = Math.min(box.width / state.width, box.height / state.height) * ratio;
  const limits = served.limits;
  scale = Math.min(scale, limits.max_side / state.width, limits.max_side / state.height,
    Math.sqrt(limits.max_pixels / (state.width * state.height)));
  return [Math.max(1, Math.floor(state.width * scale)), Math.max(1, Math.floor(state.height * scale))];
}

// The canvas for the view in the box `id`: its shape, 540 pixels tall (the labels' sizes
// are the canvas's, so a box of a given height reads the same whatever its width).
function canvasFor(id) {
  const box = $(id).getBoundingClientRect();
  if (box.width < 50 || box.height < 50) return {};
  const height = 540;
  const width = Math.round(Math.min(4000, Math.max(300, height * box.width / box.height)));
  return { canvas: `${width}x${height}` };
}

// The passes of a render: 1, 4, 16, ... samples, then the count asked for (at most what
// one frame of this size may take).
function passes(samples, [w, h]) {
  const most = Math.max(1, Math.min(served.limits.max_samples,
    Math.floor(served.limits.max_frame_samples / (w * h))));
  const last = Math.min(samples, most);
  const plan = [];
  for (let n = 1; n < last; n *= 4) plan.push(n);
  plan.push(last);
  return plan;
}

let renderUrl = null;
let generation = 0; // counts the requests for new pictures; a pass of an old one stops
let passShowing = ""; // what the picture shown is, while it is refined
const TICKET = `${Date.now().toString(36)}-${Math.random().toString(36).slice(2, 10)}-render`;
let turn = 0;
const renderChannel = new Channel((job, response, body, superseded) => {
  const meta = job.meta;
  if (response.status === 409) return; // superseded on the server by a newer render
  if (!response.ok) {
    if (!superseded && response.status === 400) refuse(meta.settings, body.error);
    else if (!superseded) setResult(`error: ${body.error}`, "error");
    return;
  }
  // A picture of settings refused meanwhile (the frame said so first) is not shown.
  if (sameSettings(meta.settings, lastRefused)) return;
  const url = URL.createObjectURL(body);
  const image = $("render");
  const previous = renderUrl;
  renderUrl = url;
  image.onload = () => {
    if (previous) URL.revokeObjectURL(previous);
    placeMarker();
  };
  image.src = url;
  document.body.dataset.renders = String(Number(document.body.dataset.renders) + 1);
  if (superseded) return;
  rendered = meta.settings;
  acceptIfBoth();
  const timing = /render;dur=([\d.]+)/.exec(response.headers.get("Server-Timing") || "");
  const ms = timing ? ` · ${Math.round(Number(timing[1]))} ms` : "";
  const [w, h] = meta.size;
  const shown = state.pixels || (w === meta.settings.width && h === meta.settings.height)
    ? `${w} × ${h}` : `${meta.settings.width} × ${meta.settings.height} shown at ${w} × ${h}`;
  const samples = `${meta.samples} sample${meta.samples > 1 ? "s" : ""}`;
  const last = meta.preview || meta.pass === meta.plan.length - 1;
  passShowing = last ? "" : `${shown}, ${samples}`;
  setResult(`${meta.preview ? "preview " : ""}${shown}, ${samples}${ms}`);
  document.body.dataset.shown = meta.preview ? "preview" : last ? "full" : "partial";
  if (!last && meta.generation === generation) sendPass(meta, meta.pass + 1);
});

function sendPass(meta, pass) {
  const samples = meta.plan[pass];
  const params = new URLSearchParams();
  params.set("camera", meta.settings.camera);
  params.set("width", meta.size[0]);
  params.set("height", meta.size[1]);
  params.set("samples", samples);
  params.set("shading", meta.settings.shading);
  if (meta.settings.mistakes) params.set("mistakes", meta.settings.mistakes);
  params.set("ticket", `${TICKET}.${++turn}`);
  renderChannel.send(`/api/render?${params}`, { ...meta, pass, samples, blob: true, abortable: !meta.preview });
}

function diagramChannel(id) {
  let shownUrl = null;
  return new Channel((job, response, body) => {
    if (!response.ok) return; // the render reports the same error
    const url = URL.createObjectURL(body);
    const previous = shownUrl;
    shownUrl = url;
    $(id).onload = () => { if (previous) URL.revokeObjectURL(previous); };
    $(id).src = url;
  });
}
const sideChannel = diagramChannel("diagram");
const topChannel = diagramChannel("top-diagram");

// The frame is the camera at the image's size, W x H (the render is at the size shown):
// a camera or a size the server refuses is refused here.
const frameChannel = new Channel((job, response, body, superseded) => {
  if (!response.ok) {
    if (!superseded && response.status === 400) refuse(job.meta.settings, body.error);
    return;
  }
  framed = job.meta.settings;
  acceptIfBoth();
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

const channels = [renderChannel, sideChannel, topChannel, frameChannel, rayChannel];

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

// Asks for what the state shows: `mode` "full" (the render in passes, and the numbers),
// "preview" (one quick pass while a control moves, and the numbers), "render" (the render
// alone, when the picture's size on screen changed) or "numbers" (the views, the frame
// and the ray).
function request(mode) {
  if (mode !== "numbers") {
    generation += 1;
    const size = displaySize();
    const preview = mode === "preview";
    const plan = preview ? [1] : passes(state.samples, size);
    sendPass({ settings: settingsOf(state), size, plan, preview, generation }, 0);
  }
  if (mode === "render") return;
  const pixel = state.pixel ? { row: state.pixel[0], col: state.pixel[1] } : {};
  sideChannel.send(`/api/diagram.svg?${cameraQuery({ ...pixel, ...canvasFor("side-frame") })}`, { blob: true });
  if (topShown()) {
    const query = cameraQuery({ ...pixel, view: "top", ...canvasFor("top-frame") });
    topChannel.send(`/api/diagram.svg?${query}`, { blob: true });
  }
  frameChannel.send(`/api/frame?${cameraQuery()}`, { settings: settingsOf(state) });
  if (state.pixel) rayChannel.send(`/api/rays?${cameraQuery(pixel)}`, { pixel: state.pixel });
  requestTrace();
}

// The server refused the render of `settings` for `message`: says so beside the control
// that caused it, and, unless the state has moved on, goes back to the last settings it
// rendered (the served scene's, if none yet), so that controls, numbers, picture and URL
// agree. A camera typed in the RON box stays there to be corrected.
function refuse(settings, message) {
  lastRefused = settings;
  generation += 1; // no more passes of it
  if (!sameSettings(settings, settingsOf(state))) {
    showError(message);
    return;
  }
  const back = accepted && !sameSettings(accepted, settings) ? accepted : settingsOf({ ...served });
  const typed = lastCameraControl === "ron" ? $("ron").value : null;
  Object.assign(state, back);
  restoreState(typed);
  showError(message);
  if (typed !== null) $("ron").classList.add("invalid");
  setResult("refused: showing the last camera rendered", "error");
  if (accepted) request("numbers"); else request("full");
}

// ---------------------------------------------------------------------------------
// Errors, shown next to the control that caused them.

function errorTarget(message, fallback) {
  const name = (/^(\w+)/.exec(message) || [])[1];
  if (name === "width" || name === "height") return "size";
  if (name === "samples" || name === "shading" || name === "mistakes") return name;
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
  document.querySelectorAll(".invalid").forEach((e) => e.classList.remove("invalid"));
  const control = document.querySelector(`[data-control="${target}"]`);
  if (control) control.classList.add("invalid");
  if (target === "mistakes") $("mistakes-menu").open = true;
  // The topic holding the control comes forward.
  const topic = (document.querySelector(`output.error[data-for="${target}"]`) || $("ron"))
    .closest("[data-topic]");
  if (topic) showTopic(topic.dataset.topic);
}

function clearErrors() {
  document.querySelectorAll("output.error").forEach((o) => {
    if (o.dataset.for !== "pixel") o.textContent = "";
  });
  document.querySelectorAll(".invalid").forEach((e) => e.classList.remove("invalid"));
}
