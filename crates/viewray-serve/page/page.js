// viewray's live playground, part 3 of 4: the controls of each topic, built from the
// camera's RON tree, and switching the projection kind without losing the picture.

// ---------------------------------------------------------------------------------
// Controls.

function commit(mode, fromRonBox) {
  if (restoring) return; // a control taken off the page as the state goes back
  if (model && !fromRonBox) state.camera = writeRon(model, false);
  if (!fromRonBox) $("ron").value = model ? writeRon(model, true) : state.camera;
  // A camera of another kind offers its own mistakes; those it cannot make go.
  dropUnfittingMistakes();
  buildMistakes();
  showViews();
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
  if (kind === "ThinLens") lensMovementControls(params, projection);
}

// A thin lens's tilt and swing (a physical lens's: they need its focal length) and its
// aperture's blades and their rotation. Zero tilt, swing and rotation and a round
// aperture are left out of the RON.
function lensMovementControls(container, projection) {
  const degrees = (key, title, label, min, max, step) => {
    const g = group(container, key, title);
    slider(g.div, {
      id: key, group: key, name: key, label, min, max, step,
      get: () => numberOf(field(projection, key), 0),
      set: (v) => (v === 0 ? removeField(projection, key) : setField(projection, key, num(v))),
    });
    g.finish();
  };
  if (field(projection, "focal_length")) {
    degrees("lens_tilt", "lens tilt <i>α</i> (degrees, about <b>u</b>: + turns its top toward the scene)",
      "<i>α</i>", -30, 30, 0.1);
    degrees("lens_swing", "lens swing <i>β</i> (degrees, about <b>v</b>: + turns its right toward the scene)",
      "<i>β</i>", -30, 30, 0.1);
  } else {
    note(container, "Tilt and swing move a physical lens: give it a <code>focal_length</code> (mm) in the RON.");
  }
  const blades = numberOf(field(projection, "blades"), 0);
  const g = group(container, "blades", "aperture blades (a polygon, as Cycles' <i>aperture_blades</i>)");
  const label = document.createElement("label");
  label.className = "row wide";
  label.textContent = "blades ";
  const select = document.createElement("select");
  select.id = "blades";
  for (const n of [0, 3, 4, 5, 6, 7, 8, 9, 10, 12, 16]) {
    const option = document.createElement("option");
    option.value = String(n);
    option.textContent = n === 0 ? "round" : String(n);
    select.append(option);
  }
  if (![...select.options].some((o) => Number(o.value) === blades)) {
    const option = document.createElement("option");
    option.value = String(blades);
    option.textContent = String(blades);
    select.append(option);
  }
  select.value = String(blades);
  label.append(select);
  g.div.append(label);
  select.addEventListener("change", () => {
    lastCameraControl = "blades";
    const n = Number(select.value);
    if (n === 0) removeField(projection, "blades");
    else setField(projection, "blades", { kind: "num", value: n, text: String(n) });
    buildControls();
    commit("full");
  });
  g.finish();
  if (blades !== 0) {
    degrees("blade_rotation", "blade rotation (degrees, from <b>u</b> toward <b>v</b>)", "rot", -180, 180, 1);
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

// Switches to the projection `to`, keeping the picture: first asks the server how far
// the scene lies along the view (what the middle of the picture shows), which sets a thin
// lens's focus and a parallel view's height.
async function switchKind(to) {
  lastCameraControl = "kind";
  const asked = state.camera;
  let depth = null;
  try {
    const response = await fetch(`/api/depth?${cameraQuery({}, true)}`);
    if (response.ok) depth = (await response.json()).depth;
  } catch {
    // Without the server's answer, the page's own estimate.
  }
  if (state.camera !== asked) return; // something else changed the camera meanwhile
  convertKind(to, depth);
  buildControls();
  commit("full");
}

// The height of a projection's window: `vh` on the image plane (at `d`) for the
// perspective families, the view's height for the parallel ones.
function windowHeight(projection) {
  const d = numberOf(field(projection, "distance"), 1);
  const fovY = numberOf(field(projection, "fov_y"), null);
  const fovX = numberOf(field(projection, "fov_x"), null);
  if (fovY !== null) return 2 * d * Math.tan(fovY * Math.PI / 360);
  if (fovX !== null) return 2 * d * Math.tan(fovX * Math.PI / 360) * state.height / state.width;
  return numberOf(field(projection, "height"), vecOf(field(projection, "viewport"), [1, 1])[1]);
}

// The camera of another kind, keeping what carries over; `depth` is how far the scene
// lies along the view (null when the server could not say).
function convertKind(to, depth) {
  const from = kindOf(model);
  const round = (v) => v.map((x) => Math.round(x * 1e4) / 1e4);
  const distanceTo = (eye, target) => Math.hypot(...eye.map((x, k) => x - target[k])) || 5;
  const eyeOf = () => vecOf(field(model, "eye"), [0, 0, 5]);
  const look = field(model, "look_at");
  const distance = depth !== null && depth > 0 ? depth : look ? distanceTo(eyeOf(), vecOf(look, [0, 0, 0])) : 5;
  const perspectiveFrom = from === "Perspective" || from === "ThinLens";
  if (PRESETS.includes(to)) {
    let target = [0, 0, 0], size = 4;
    if (from && PRESETS.includes(from)) {
      target = vecOf(field(model, "target"), target);
      size = numberOf(field(model, "size"), size);
    } else if (from) {
      // What the middle of the picture shows, `distance` along the view, and the view's
      // height there.
      const e = lastFrame ? lastFrame.e : eyeOf();
      const w = lastFrame ? lastFrame.w : [0, 0, 1];
      target = round(e.map((x, k) => x - w[k] * distance));
      const projection = field(model, "projection");
      const d = numberOf(field(projection, "distance"), 1);
      const height = windowHeight(projection);
      if (perspectiveFrom || from === "Orthographic" || from === "Oblique") {
        size = Math.round((perspectiveFrom ? height * distance / d : height) * 100) / 100;
      }
    }
    const fields = [{ key: "target", value: vec(target) }, { key: "size", value: num(size) }];
    model = { kind: "struct", name: to, fields };
    return;
  }
  // An explicit camera.
  if (from && !PRESETS.includes(from)) {
    setField(model, "projection", newProjection(to, field(model, "projection"), from, distance));
    return;
  }
  // From a preset: its frame, from the server's last answer, and its view's height.
  const presetTarget = from ? vecOf(field(model, "target"), [0, 0, 0]) : [0, 0, 0];
  const eye = lastFrame ? round(lastFrame.e) : [0, 1, 5];
  const up = lastFrame ? round(lastFrame.v) : [0, 1, 0];
  const size = from ? numberOf(field(model, "size"), 4) : 4;
  const parallel = { kind: "struct", name: "Orthographic", fields: [{ key: "height", value: num(size) }] };
  model = {
    kind: "struct", name: null, fields: [
      { key: "eye", value: vec(eye) },
      { key: "look_at", value: vec(presetTarget) },
      { key: "up", value: vec(up) },
      { key: "projection", value: newProjection(to, parallel, "Orthographic", distance) },
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
          // The perspective view's height at the scene.
          h = windowHeight(old) * distance / numberOf(field(old, "distance"), 1);
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

