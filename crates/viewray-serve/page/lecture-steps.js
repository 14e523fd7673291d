// The lecture's steps, in its order. Each step names the one thing it changes (its
// controls), the camera those controls make (a scene file's `camera:` value), whether the
// top view helps, and its formulas with the current numbers: the page's own arithmetic
// for the intermediate steps, the command line's printed digits for every result.
//
// A step: { id, title, lead, group (steps sharing controls), controls: [{key, label, min,
// max, step, value} | {key, label, choices, value}], buttons, camera(p), top(p),
// project(p) (world points for /api/project), trace (the pixel's trace wanted),
// formulas(ctx) }. ctx: { p, i, j, ray, frame, project, trace, error }, `ray`, `frame`,
// `project` and `trace` the command line's lines.

// Straight down -z from in front of the default scene's objects: the canonical camera's
// basis, its eye moved back so that it sees them (it would sit inside the cube).
const FRONT_EYE = [0, 0.6, 5];
const LOOK_AT = [0, 0.5, 0];

function pose(eye, view, up) {
  return `eye: ${ronVec(eye)}, view: ${ronVec(view)}, up: ${ronVec(up || [0, 1, 0])}`;
}
function perspective(d, vw, vh, shift) {
  const s = shift ? `, shift: ${ronVec(shift)}` : "";
  return `Perspective(distance: ${ronNumber(d)}, viewport: ${ronVec([vw, vh])}${s})`;
}
const pixelControls = [
  { key: "i", label: "row i", min: 1, max: H, step: 1, value: 200, pixel: true },
  { key: "j", label: "column j", min: 1, max: W, step: 1, value: 353, pixel: true },
];
const PRESETS = ["Front", "Top", "Side", "Isometric", "Dimetric", "Trimetric", "Cavalier", "Cabinet",
  "OnePoint", "TwoPoint", "ThreePoint"];
const PRESET_NOTES = {
  Front: "Multiview: the image plane perpendicular to z.",
  Top: "Multiview: looking straight down.",
  Side: "Multiview: the image plane perpendicular to x.",
  Isometric: "Axonometric: the three axes equally foreshortened, 120° apart.",
  Dimetric: "Axonometric: two axes at one scale, the third at another.",
  Trimetric: "Axonometric: three scales.",
  Cavalier: "Oblique, L = 1: depth at full length.",
  Cabinet: "Oblique, L = ½: depth at half length.",
  OnePoint: "Perspective, the image plane parallel to two axes: one vanishing point.",
  TwoPoint: "Perspective, verticals parallel to the image plane: two vanishing points.",
  ThreePoint: "Perspective, the camera tilted: verticals converge too.",
};

// The pixel's u, v and ray, for a viewport vw x vh.
function pixelLines(ctx, vw, vh) {
  return uFormula(ctx.j, vw, rawValue(ctx.ray, "u")) + vFormula(ctx.i, vh, rawValue(ctx.ray, "v"));
}
// The pixel's image-plane point as the command line printed it.
const uvLines = (ctx) => eq(M.i("u", "u"), M.cli(rawValue(ctx.ray, "u"), "ray.u"))
  + eq(M.i("v", "v"), M.cli(rawValue(ctx.ray, "v"), "ray.v"));
// direction = u U + v V - d W, symbolically.
const generalDirection = () => M.r(M.i("u", "u"), M.b("U", "u"), M.o("+"), M.i("v", "v"), M.b("V", "v"), M.o("−"), M.i("d"), M.b("W", "w"));

const STEPS = [
  {
    id: "pseudocode",
    title: "A ray tracer, one pixel at a time",
    lead: "Generate a pixel's ray, intersect it with the scene, colour what it hits: as viewray trace prints it. Click the picture for another pixel.",
    controls: pixelControls,
    camera: () => served.camera,
    trace: true,
    formulas: (ctx) => traceFormulas(ctx, served.camera),
  },
  {
    id: "canonical",
    title: "The canonical camera",
    lead: "Looking down −z with u, v, w the world's x, y, z, the image plane at d = 1, a 1 × 1 viewport. (Its eye is moved back to e = (0, 0.6, 5) so that it sees the objects.) Pick a pixel: its point (u, v) on the image plane is the ray's direction.",
    controls: pixelControls,
    camera: () => `(${pose(FRONT_EYE, [0, 0, -1])}, projection: ${perspective(1, 1, 1)})`,
    formulas: (ctx) => pixelLines(ctx, "1", "1")
      + rayLines(ctx, M.b("e"), M.p(M.i("u", "u"), M.o(","), M.i("v", "v"), M.o(","), M.o("−"), M.n("1")))
      + note("Square image plane, 16:9 image: the picture is stretched sideways. Two steps on, vw and vh fix it."),
  },
  {
    id: "distance",
    title: "The image plane at d ≠ 1",
    lead: "Move the image plane: the direction's last coordinate is −d. A longer d is a narrower field of view.",
    controls: [{ key: "d", label: "d", min: 0.3, max: 3, step: 0.05, value: 1.5 }],
    camera: (p) => `(${pose(FRONT_EYE, [0, 0, -1])}, projection: ${perspective(p.d, 1, 1)})`,
    formulas: (ctx) => pixelLines(ctx, "1", "1")
      + rayLines(ctx, M.b("e"), M.p(M.i("u", "u"), M.o(","), M.i("v", "v"), M.o(","), M.o("−"), M.n(fmt(ctx.p.d))))
      + eq(M.sub(M.i("fov"), M.i("y")), M.r(M.n("2"), M.i("atan"), M.f(M.i("vh"), M.r(M.n("2"), M.i("d")))),
        M.r(M.n("2"), M.i("atan"), M.f(M.n("1"), M.n(fmt(2 * ctx.p.d)))), M.r(M.n(fmt((2 * Math.atan(1 / (2 * ctx.p.d)) * 180) / Math.PI)), M.o("°"))),
  },
  {
    id: "viewport",
    title: "Any viewport vw × vh",
    lead: "Stretch the window on the image plane. The pixels are square when vw / vh = W / H.",
    controls: [
      { key: "vw", label: "vw", min: 0.2, max: 4, step: 0.02, value: 1.02 },
      { key: "vh", label: "vh", min: 0.2, max: 4, step: 0.02, value: 0.58 },
    ],
    camera: (p) => `(${pose(FRONT_EYE, [0, 0, -1])}, projection: ${perspective(1, p.vw, p.vh)})`,
    formulas: (ctx) => pixelLines(ctx, fmt(ctx.p.vw), fmt(ctx.p.vh))
      + rayLines(ctx, M.b("e"), M.p(M.i("u", "u"), M.o(","), M.i("v", "v"), M.o(","), M.o("−"), M.n("1")))
      + eq(M.f(M.i("vw"), M.i("vh")), M.n(fmt(ctx.p.vw / ctx.p.vh)))
      + note(`W / H = ${fmt(W / H)}: ${Math.abs(ctx.p.vw / ctx.p.vh - W / H) < 0.02 ? "square pixels" : "the picture is stretched"}.`),
  },
  {
    id: "eye",
    title: "The eye anywhere: e ≠ 0",
    lead: "Move the eye: every ray starts at e; the directions stay the same.",
    controls: [
      { key: "x", label: "e x", min: -4, max: 4, step: 0.1, value: 1 },
      { key: "y", label: "e y", min: 0.1, max: 4, step: 0.1, value: 0.6 },
      { key: "z", label: "e z", min: 2, max: 10, step: 0.1, value: 5 },
    ],
    camera: (p) => `(${pose([p.x, p.y, p.z], [0, 0, -1])}, projection: ${perspective(1, 1.78, 1)})`,
    formulas: (ctx) => pixelLines(ctx, "1.78", "1")
      + rayLines(ctx, M.r(M.b("e"), M.o("="), M.vec([ctx.p.x, ctx.p.y, ctx.p.z])), M.p(M.i("u", "u"), M.o(","), M.i("v", "v"), M.o(","), M.o("−"), M.n("1"))),
  },
  {
    id: "rotated",
    title: "A rotated basis",
    lead: "Turn the camera: the image plane's point is u U + v V − d W in the world, with the frame's U, V, W.",
    controls: [{ key: "yaw", label: "turn (°)", min: -45, max: 45, step: 1, value: 20 }],
    top: () => true,
    camera: (p) => `(${pose(FRONT_EYE, [-Math.sin(deg(p.yaw)), 0, -Math.cos(deg(p.yaw))])}, projection: ${perspective(1, 1.78, 1)})`,
    formulas: (ctx) => frameLine(ctx, "u", "u") + frameLine(ctx, "v", "v") + frameLine(ctx, "w", "w")
      + pixelLines(ctx, "1.78", "1")
      + rayLines(ctx, M.b("e"), M.r(generalDirection(), M.o(","), M.i("d"), M.o("="), M.n("1"))),
  },
  ...["w", "u", "v"].map((which, k) => ({
    id: `basis-${which}`,
    group: "basis",
    title: `Problem 2: the basis from eye, view, up (${k + 1} of 3: ${which})`,
    lead: [
      "First w: the camera looks along −w, so w is the view reversed, made unit.",
      "Then u: perpendicular to up and to w, pointing right. When up is parallel to the view, up × w is zero: no direction is “right”, every roll about w is as good, and viewray refuses the camera.",
      "Last v = w × u: already unit, perpendicular to both; up only chose the roll.",
    ][k],
    controls: [
      { key: "ex", label: "eye x", min: -6, max: 6, step: 0.1, value: 3 },
      { key: "ey", label: "eye y", min: 0.2, max: 8, step: 0.1, value: 2 },
      { key: "ez", label: "eye z", min: -6, max: 6, step: 0.1, value: 4 },
      { key: "ux", label: "up x", min: -1, max: 1, step: 0.05, value: 0 },
      { key: "uy", label: "up y", min: -1, max: 1, step: 0.05, value: 1 },
      { key: "uz", label: "up z", min: -1, max: 1, step: 0.05, value: 0 },
    ],
    buttons: [
      // The view itself (up need not be a unit vector), as the RON writes it: parallel to
      // the server's look_at - eye well within its tolerance, so the camera is refused.
      { label: "up along the view", apply: (p) => {
        [p.ux, p.uy, p.uz] = sub3(LOOK_AT, [p.ex, p.ey, p.ez]).map((x) => Number(ronNumber(x)));
      } },
      { label: "up = y", apply: (p) => { p.ux = 0; p.uy = 1; p.uz = 0; } },
    ],
    top: () => true,
    camera: (p) => `(eye: ${ronVec([p.ex, p.ey, p.ez])}, look_at: ${ronVec(LOOK_AT)}, up: ${ronVec([p.ux, p.uy, p.uz])}, projection: Perspective(fov_y: 40.0))`,
    formulas: (ctx) => basisFormulas(ctx, k),
  })),
  {
    id: "thin-lens",
    title: "The thin lens",
    lead: "A lens of radius r instead of a pinhole: rays of one image point start anywhere on the lens and meet on the plane in focus, f along the view. Out of that plane, blur.",
    controls: [
      { key: "r", label: "aperture r", min: 0, max: 0.3, step: 0.01, value: 0.12 },
      { key: "f", label: "focus f", min: 2, max: 14, step: 0.1, value: 7.9 },
    ],
    camera: (p) => `(eye: (5.2, 1.6, 6.0), view: (-5.2, 0.0, -6.0), projection: ThinLens(distance: 1.0, fov_y: 32.0, aperture: ${ronNumber(p.r)}, focus: ${ronNumber(p.f)}))`,
    formulas: (ctx) => eq(M.b("o"), M.r(M.b("e"), M.o("+"), M.i("r"), M.p(M.sub(M.i("l"), M.i("x")), M.b("U", "u"), M.o("+"), M.sub(M.i("l"), M.i("y")), M.b("V", "v"))))
      + eq(M.b("d"), M.r(M.f(M.i("f"), M.i("d")), M.p(generalDirection()), M.o("−"), M.i("r"), M.p(M.sub(M.i("l"), M.i("x")), M.b("U", "u"), M.o("+"), M.sub(M.i("l"), M.i("y")), M.b("V", "v"))))
      + note("Through the lens's centre, (l<sub>x</sub>, l<sub>y</sub>) = (0, 0), as viewray rays prints it: the pinhole ray scaled by f / d.")
      + eq(M.f(M.i("f"), M.i("d")), M.f(M.n(fmt(ctx.p.f)), M.n("1")))
      + rayLines(ctx, M.b("e"), M.r(M.f(M.i("f"), M.i("d")), M.p(generalDirection()))),
  },
  {
    id: "taxonomy",
    title: "The classical projections",
    lead: "Each leaf of the taxonomy is a camera: pick one.",
    controls: [{ key: "preset", label: "projection", choices: PRESETS, value: "Isometric" }],
    top: (p) => !["Front", "Top", "Side", "OnePoint"].includes(p.preset),
    camera: (p) => `${p.preset}(target: ${ronVec(LOOK_AT)}, size: 4.0)`,
    formulas: (ctx) => note(esc(PRESET_NOTES[ctx.p.preset] || ""))
      + frameLine(ctx, "e") + frameLine(ctx, "u", "u") + frameLine(ctx, "v", "v") + frameLine(ctx, "w", "w")
      + uvLines(ctx)
      + rayLines(ctx, null, null),
  },
  {
    id: "parallel",
    title: "Parallel projections: orthographic to oblique",
    lead: "The eye on the image plane, every ray in one direction. Tilt the rays by L along the angle φ: orthographic (L = 0) becomes oblique (cabinet L = ½, cavalier L = 1).",
    controls: [
      { key: "L", label: "L", min: 0, max: 1, step: 0.05, value: 0.5 },
      { key: "phi", label: "φ (°)", min: 0, max: 90, step: 1, value: 45 },
    ],
    top: () => true,
    camera: (p) => `(${pose([0, 0.6, 5], [0, 0, -1])}, projection: Oblique(height: 3.0, ratio: ${ronNumber(p.L)}, angle: ${ronNumber(p.phi)}))`,
    formulas: (ctx) => uvLines(ctx)
      + rayLines(ctx, M.r(M.b("e"), M.o("+"), M.i("u", "u"), M.b("U", "u"), M.o("+"), M.i("v", "v"), M.b("V", "v")),
        M.r(M.o("−"), M.b("W", "w"), M.o("−"), M.i("L"), M.p(M.i("cos"), M.i("φ"), M.b("U", "u"), M.o("+"), M.i("sin"), M.i("φ"), M.b("V", "v"))))
      + eq(M.r(M.i("L"), M.i("cos"), M.i("φ")), M.n(fmt(ctx.p.L * Math.cos(deg(ctx.p.phi)))))
      + eq(M.r(M.i("L"), M.i("sin"), M.i("φ")), M.n(fmt(ctx.p.L * Math.sin(deg(ctx.p.phi))))),
  },
  {
    id: "shift",
    title: "Shifted perspective",
    lead: "Slide the window on the image plane without turning the camera: the view moves, verticals stay vertical.",
    controls: [
      { key: "sx", label: "shift sx", min: -0.6, max: 0.6, step: 0.02, value: 0 },
      { key: "sy", label: "shift sy", min: -0.6, max: 0.6, step: 0.02, value: 0.2 },
    ],
    camera: (p) => `(${pose([0, 0.6, 4], [0, 0, -1])}, projection: ${perspective(1, 1.78, 1, [p.sx, p.sy])})`,
    formulas: (ctx) => pixelLines(ctx, "1.78", "1")
      + rayLines(ctx, M.b("e"), M.r(M.p(M.i("u", "u"), M.o("+"), M.sub(M.i("s"), M.i("x"))), M.b("U", "u"), M.o("+"), M.p(M.i("v", "v"), M.o("+"), M.sub(M.i("s"), M.i("y"))), M.b("V", "v"), M.o("−"), M.i("d"), M.b("W", "w")))
      + note("viewray rays prints u, v without the shift; the direction has it."),
  },
  {
    id: "foreshortening",
    title: "Distortions: foreshortening",
    lead: "Move the eye away from the cube: its image shrinks as 1 / depth.",
    controls: [{ key: "z", label: "eye z", min: 2, max: 14, step: 0.2, value: 4 }],
    camera: (p) => `(${pose([0, 0.6, p.z], [0, 0, -1])}, projection: ${perspective(1, 1.78, 1)})`,
    project: () => [[0, 1.2, 0.6], [0, 0, 0.6]],
    formulas: (ctx) => {
      const depth = ctx.p.z - 0.6;
      const ys = (ctx.project || "").split("\n").map((line) => rawValue(line, "y"));
      return eq(M.r(M.text("image height")), M.f(M.r(M.i("d"), M.o("⋅"), M.i("h")), M.text("depth")),
        M.f(M.r(M.n("1"), M.o("×"), M.n("1.2")), M.n(fmt(depth))), M.n(fmt(1.2 / depth)))
        + eq(M.text("in pixels"), M.r(M.n(fmt(1.2 / depth)), M.o("×"), M.f(M.i("H"), M.i("vh"))), M.n(fmt((1.2 / depth) * H)))
        + note("Where viewray project puts the front edge's top and foot (y, in pixels from the top):")
        + eq(M.sub(M.i("y"), M.text("top")), M.cli(ys[0], "project.0.y"))
        + eq(M.sub(M.i("y"), M.text("foot")), M.cli(ys[1], "project.1.y"));
    },
  },
  {
    id: "tilt-shift",
    title: "Distortions: tilt versus shift",
    lead: "To see the top of something tall, tilt the camera up (verticals converge) or shift the lens up (they stay parallel).",
    controls: [
      { key: "how", label: "by", choices: ["tilt", "shift"], value: "tilt" },
      { key: "a", label: "angle (°)", min: 0, max: 30, step: 1, value: 20 },
    ],
    camera: (p) => p.how === "tilt"
      ? `(${pose([0, 0.6, 2.6], [0, Math.sin(deg(p.a)), -Math.cos(deg(p.a))])}, projection: ${perspective(1, 1.78, 1)})`
      : `(${pose([0, 0.6, 2.6], [0, 0, -1])}, projection: ${perspective(1, 1.78, 1, [0, Math.tan(deg(p.a))])})`,
    formulas: (ctx) => (ctx.p.how === "tilt"
      ? note("Tilted: V leans back, so the image plane is not vertical and verticals converge.")
      : eq(M.sub(M.i("s"), M.i("y")), M.r(M.i("d"), M.i("tan"), M.i("θ")), M.r(M.n("1"), M.o("×"), M.i("tan"), M.n(`${fmt(ctx.p.a)}°`)), M.n(fmt(Math.tan(deg(ctx.p.a)))))
        + note("Shifted: V stays (0, 1, 0), the image plane vertical, verticals parallel."))
      + frameLine(ctx, "v", "v") + frameLine(ctx, "w", "w")
      + rayLines(ctx, M.b("e"), generalDirection()),
  },
];

// Problem 2's formulas up to step `k` (0: w, 1: u, 2: v).
function basisFormulas(ctx, k) {
  const p = ctx.p;
  const eye = [p.ex, p.ey, p.ez];
  const up = [p.ux, p.uy, p.uz];
  const view = sub3(LOOK_AT, eye);
  const w = view.map((x) => -x / norm(view));
  let html = eq(M.b("view"), M.r(M.b("look_at"), M.o("−"), M.b("e")), M.vec(view))
    + eq(M.abs(M.b("view")), M.n(fmt(norm(view))))
    + eq(M.b("w", "w"), M.r(M.o("−"), M.f(M.b("view"), M.abs(M.b("view")))), ctx.frame ? M.cliVec(rawArray(ctx.frame, "w"), "frame.w") : M.vec(w));
  if (k >= 1) {
    const c = cross(up, w);
    html += eq(M.r(M.b("up"), M.o("×"), M.b("w", "w")), M.r(M.vec(up), M.o("×"), M.vec(w)), M.vec(c))
      + eq(M.abs(M.r(M.b("up"), M.o("×"), M.b("w", "w"))), M.n(fmt(norm(c))));
    if (ctx.error) {
      html += `<p class="note refusal">${esc(ctx.error)}</p>`
        + note("up × w = 0: up is parallel to the view, so it says nothing about which way is right. Every roll about w is as good; pick another up.");
    } else {
      html += eq(M.b("u", "u"), M.f(M.r(M.b("up"), M.o("×"), M.b("w", "w")), M.abs(M.r(M.b("up"), M.o("×"), M.b("w", "w")))), M.cliVec(rawArray(ctx.frame, "u"), "frame.u"));
    }
  }
  if (k >= 2 && !ctx.error) {
    html += eq(M.b("v", "v"), M.r(M.b("w", "w"), M.o("×"), M.b("u", "u")), M.cliVec(rawArray(ctx.frame, "v"), "frame.v"));
  }
  return html;
}
