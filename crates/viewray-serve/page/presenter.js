// viewray's live playground, part 4 of 4: the presenter. The image settings, the RON
// box, the chosen pixel, the topics (one set of controls at a time beside the picture),
// the top view, the picture's pixels, "save as slide", the keyboard, and the start.

// ---------------------------------------------------------------------------------
// The image settings.

const SIZES = [[320, 180], [320, 240], [640, 360], [640, 480], [800, 600], [960, 540],
  [1280, 720], [1920, 1080]];
const SAMPLE_COUNTS = [1, 2, 4, 8, 16, 32, 64, 128, 256, 512, 1024];

// The most samples per pixel the server renders for a `width x height` image.
function mostSamples(width, height) {
  const limits = served.limits;
  return Math.max(1, Math.min(limits.max_samples, Math.floor(limits.max_frame_samples / (width * height))));
}

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
  const shading = $("shading");
  shading.replaceChildren();
  for (const name of served.shadings) {
    const option = document.createElement("option");
    option.value = option.textContent = name;
    shading.append(option);
  }
  $("size-preset").parentElement.dataset.control = "size";
  $("width").parentElement.parentElement.dataset.control = "size";
  $("samples").parentElement.dataset.control = "samples";
  shading.parentElement.dataset.control = "shading";
}

// The samples menu offers the counts the server renders at this size, and no more.
function buildSamplesMenu() {
  const samples = $("samples");
  samples.replaceChildren();
  const most = mostSamples(state.width, state.height);
  const counts = SAMPLE_COUNTS.filter((n) => n <= most);
  for (const n of [served.samples, state.samples]) {
    if (n <= most && !counts.includes(n)) counts.push(n);
  }
  counts.sort((a, b) => a - b);
  for (const n of counts) {
    const option = document.createElement("option");
    option.value = n;
    option.textContent = n === 1 ? "1 (the pixel centre)" : String(n);
    samples.append(option);
  }
  const asked = samplesAsked !== null ? `${samplesAsked} asked for; ` : "";
  $("samples-most").textContent = `${asked}at most ${most} at ${state.width} × ${state.height}`;
}

function showImageSettings() {
  $("width").value = state.width;
  $("height").value = state.height;
  const key = `${state.width}x${state.height}`;
  const select = $("size-preset");
  select.value = [...select.options].some((o) => o.value === key) ? key : "";
  buildSamplesMenu();
  $("samples").value = state.samples;
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
  // Fewer samples where the server would refuse as many for the new size.
  const most = mostSamples(width, height);
  samplesAsked = null;
  if (width > 0 && height > 0 && state.samples > most) state.samples = most;
  showImageSettings();
  commit("full");
}

// ---------------------------------------------------------------------------------
// Loading a state, and going back to one.

function loadState() {
  try {
    model = parseRon(state.camera);
    setError("ron", "");
  } catch (error) {
    model = null;
    setError("ron", error.message);
  }
  $("ron").value = model && kindOf(model) ? writeRon(model, true) : state.camera;
  $("ron").classList.remove("invalid");
  buildControls();
  buildMistakes();
  showImageSettings();
  if (!state.pixel) {
    $("ray").hidden = true;
    $("ray-title").textContent = "Viewing ray: click a pixel";
    $("ray-json").textContent = "";
  }
  showViews();
  placeMarker();
}

// Back to the state in `state` after a refusal; the RON box keeps `typed` if given.
// While the controls are rebuilt, nothing commits: a browser tells of a change to the
// control in focus (holding the refused value) as it is taken off the page.
let restoring = false;
function restoreState(typed) {
  if (state.pixel) {
    state.pixel = [Math.min(state.pixel[0], state.height - 1), Math.min(state.pixel[1], state.width - 1)];
  }
  restoring = true;
  try {
    loadState();
  } finally {
    restoring = false;
  }
  if (typed !== null) $("ron").value = typed;
  writeFragment();
}

// ---------------------------------------------------------------------------------
// The picture and the chosen pixel.

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
  request("numbers");
}

// ---------------------------------------------------------------------------------
// The RON box.

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
    $("ron").classList.add("invalid");
    return;
  }
  $("ron").classList.remove("invalid");
  state.camera = text;
  buildControls();
  commit("full", true);
}

// ---------------------------------------------------------------------------------
// The presenter: topics, views, pixels, slides.

function showTopic(topic) {
  if (!TOPICS.includes(topic)) return;
  state.topic = topic;
  for (const panel of document.querySelectorAll("#controls [data-topic]")) {
    panel.hidden = panel.dataset.topic !== topic;
  }
  for (const tab of document.querySelectorAll("#topics [data-topic]")) {
    tab.setAttribute("aria-selected", tab.dataset.topic === topic ? "true" : "false");
  }
  writeFragment();
}

// Whether the top view stands beside the side view: as chosen, or where it helps
// (oblique and axonometric views, whose receding axis the side view cannot show, and
// mistakes that move the picture left or right).
function topShown() {
  if (state.top !== null) return state.top;
  const kind = kindOf(model);
  return ["Oblique", "Isometric", "Dimetric", "Trimetric", "Cavalier", "Cabinet"].includes(kind)
    || sidewaysMistake();
}

function showViews() {
  const top = topShown();
  $("top-frame").hidden = !top;
  $("views").classList.toggle("both", top);
  $("toggle-top").setAttribute("aria-pressed", top ? "true" : "false");
  $("save-top").hidden = !top;
  document.body.classList.toggle("pixels", state.pixels);
  $("toggle-pixels").setAttribute("aria-pressed", state.pixels ? "true" : "false");
}

function toggleTop() {
  state.top = !topShown();
  showViews();
  writeFragment();
  request("numbers");
}

function togglePixels() {
  state.pixels = !state.pixels;
  showViews();
  writeFragment();
  request("render");
}

// The links that save the slide (PNG, 1920 x 1080) and the views (SVG).
function updateSaveLinks() {
  const pixel = state.pixel ? { row: state.pixel[0], col: state.pixel[1] } : {};
  const slide = new URLSearchParams({
    camera: state.camera, width: state.width, height: state.height, samples: state.samples,
    shading: state.shading, ...pixel, top: topShown() ? "1" : "0",
    ...(state.mistakes ? { mistakes: state.mistakes } : {}),
  });
  $("save-slide").href = `/api/slide.png?${slide}`;
  $("save-side").href = `/api/diagram.svg?${cameraQuery(pixel)}`;
  $("save-top").href = `/api/diagram.svg?${cameraQuery({ ...pixel, view: "top" })}`;
}

// The projection kind before or after the current one in the menu.
function stepKind(step) {
  const select = $("kind");
  if (select.disabled) return;
  const values = [...select.options].map((o) => o.value);
  const at = values.indexOf(select.value);
  const next = values[(at + step + values.length) % values.length];
  select.value = next;
  switchKind(next);
}

// The keys a lecturer presses, with no control focused.
const KEYS = {
  "1": () => showTopic("projection"),
  "2": () => showTopic("pose"),
  "3": () => showTopic("image"),
  "4": () => showTopic("ron"),
  t: toggleTop,
  m: () => { $("mistakes-menu").open = !$("mistakes-menu").open; },
  p: togglePixels,
  s: () => $("save-slide").click(),
  "[": () => stepKind(-1),
  "]": () => stepKind(1),
  f: () => (document.fullscreenElement ? document.exitFullscreen() : document.documentElement.requestFullscreen()),
  "?": () => { $("keys").hidden = !$("keys").hidden; },
  k: () => { $("keys").hidden = !$("keys").hidden; },
};

function onKey(event) {
  if (event.key === "Escape") {
    $("keys").hidden = true;
    $("mistakes-menu").open = false;
    if (document.activeElement && document.activeElement !== document.body) document.activeElement.blur();
    return;
  }
  const target = event.target;
  const typing = target instanceof HTMLTextAreaElement || target instanceof HTMLSelectElement
    || (target instanceof HTMLInputElement && target.type !== "range" && target.type !== "checkbox");
  if (typing || event.ctrlKey || event.metaKey || event.altKey) return;
  const action = KEYS[event.key.length === 1 ? event.key.toLowerCase() : event.key];
  if (action) {
    event.preventDefault();
    Promise.resolve(action()).catch(() => {});
  }
}

// Re-renders at the new size when the picture's box changes (a window resized, a
// projector plugged in), once it has settled.
let resizeTimer = null;
let lastSize = null;
function onResize() {
  placeMarker();
  clearTimeout(resizeTimer);
  resizeTimer = setTimeout(() => {
    const size = displaySize();
    if (!lastSize || size[0] !== lastSize[0] || size[1] !== lastSize[1]) {
      lastSize = size;
      request("render");
    }
    const views = ["side-frame", "top-frame"].map((id) => canvasFor(id).canvas).join();
    if (views !== lastViews) {
      lastViews = views;
      request("numbers");
    }
  }, 250);
}
let lastViews = null;

// ---------------------------------------------------------------------------------
// The start.

function start() {
  buildImageControls();
  readFragment();
  loadState();
  showTopic(state.topic);
  writeFragment();
  lastSize = displaySize();
  lastViews = ["side-frame", "top-frame"].map((id) => canvasFor(id).canvas).join();
  request("full");

  $("render").addEventListener("click", pickPixel);
  const resized = new ResizeObserver(onResize);
  for (const id of ["render-frame", "side-frame", "top-frame"]) resized.observe($(id));
  $("kind").addEventListener("change", () => switchKind($("kind").value));
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
  $("samples").addEventListener("change", () => {
    state.samples = Number($("samples").value);
    samplesAsked = null;
    showImageSettings();
    commit("full");
  });
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
    showTopic(state.topic);
    commit("full", true);
  });
  for (const tab of document.querySelectorAll("#topics [data-topic]")) {
    tab.addEventListener("click", () => showTopic(tab.dataset.topic));
  }
  $("toggle-top").addEventListener("click", toggleTop);
  $("toggle-pixels").addEventListener("click", togglePixels);
  $("show-keys").addEventListener("click", () => { $("keys").hidden = !$("keys").hidden; });
  $("close-keys").addEventListener("click", () => { $("keys").hidden = true; });
  document.addEventListener("keydown", onKey);
  window.addEventListener("hashchange", () => {
    readFragment();
    loadState();
    showTopic(state.topic);
    request("full");
  });
}

start();
