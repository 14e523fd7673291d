// The first step's formulas: one pixel through the pseudocode (generate, intersect,
// colour), every number from the lines of /api/trace, which are those of
// `viewray trace --json --one-based`, shown as printed. A number on the page is named
// `trace.K.PATH` (line K of the trace, then the keys and indices within it) for the
// tests that compare it with the command line.

// A trace line read with every number kept as the text it was printed as ("1.0" stays
// "1.0"): in these lines a number only follows `:`, `[` or `,` and ends at `,`, `]` or `}`.
function rawJson(line) {
  return JSON.parse(line.replace(/(?<=[:[,])(-?[0-9][0-9.eE+-]*)(?=[,\]}])/g, "\"$1\""));
}

// The trace's lines, each read by `rawJson`, with its index for the numbers' names.
function traceLines(text) {
  return text.trim().split("\n").map((line, k) => ({ k, ...rawJson(line) }));
}

// The number at `path` of `line` (keys joined by "."), typeset as the command line's.
function traceNumber(line, path) {
  const value = path.split(".").reduce((x, key) => (x == null ? x : x[key]), line);
  return M.cli(value, `trace.${line.k}.${path}`);
}
// The vector at `path`, as a column (long numbers) or a row.
function traceColumn(line, path) {
  const value = path.split(".").reduce((x, key) => (x == null ? x : x[key]), line);
  return value ? M.column(value.map((_, n) => traceNumber(line, `${path}.${n}`))) : M.text("?");
}
function traceRow(line, path) {
  const value = path.split(".").reduce((x, key) => (x == null ? x : x[key]), line);
  if (!value) return M.text("?");
  return M.p(...value.map((_, n) => traceNumber(line, `${path}.${n}`)).flatMap((x, n) => (n ? [M.o(","), x] : [x])));
}
// The same, inside HTML text.
const traceSpan = (line, key) => `<span class="cli" data-cli="trace.${line.k}.${key}">${esc(line[key])}</span>`;

// One stage of the pseudocode: its line of code and what it computes (HTML), then its formulas.
const stage = (code, what, body) => `<section class="stage"><h3><code>${esc(code)}</code> <span>${what}</span></h3>${body}</section>`;

// A pixel's trace as the pseudocode's three stages; `cameraText` tells a perspective
// camera (whose direction is u U + v V − d W) from the others.
function traceFormulas(ctx, cameraText) {
  if (!ctx.trace) return note(ctx.error ? esc(ctx.error) : "Tracing the pixel…");
  const all = traceLines(ctx.trace);
  const first = all.filter((l) => l.bounce === "0");
  const ray = first.find((l) => l.step === "viewing-ray");
  const pixel = all[all.length - 1];
  const lit = first.some((l) => l.step === "surface");
  return stage("ray = generate(i, j)", "the pixel's centre", generateStage(ray, cameraText))
    + stage("hit = intersect(ray, scene)", "the nearest", intersectStage(first))
    + stage("colour = shade(hit)", lit ? "each light, then ambient" : "the shading's value", colourStage(first, pixel));
}

function generateStage(ray, cameraText) {
  if (!ray) return note("No viewing ray.");
  let html = "";
  if (ray.u !== undefined) {
    html += eq(M.i("u", "u"), M.r(M.p(M.f(M.r(M.i("j"), M.o("−"), M.n("½")), M.i("W")), M.o("−"), M.n("½")), M.o("⁢"), M.i("vw")),
      traceNumber(ray, "u"))
      + eq(M.i("v", "v"), M.r(M.o("−"), M.p(M.f(M.r(M.i("i"), M.o("−"), M.n("½")), M.i("H")), M.o("−"), M.n("½")), M.o("⁢"), M.i("vh")),
        traceNumber(ray, "v"));
  } else {
    // A panoramic camera: its angles instead of an image-plane point.
    const keys = ["longitude", "latitude", "a", "b", "r", "theta"].filter((key) => ray[key] !== undefined);
    html += eq(...keys.map((key) => M.r(M.i(key), M.o(":"), traceNumber(ray, key))));
  }
  const perspective = /Perspective|fov_y/.test(cameraText) && !/ThinLens|Orthographic|Oblique|Fisheye|Equirectangular/.test(cameraText);
  const direction = perspective ? [M.b("d"), generalDirection(), traceColumn(ray, "direction")] : [M.b("d"), traceColumn(ray, "direction")];
  html += `<div class="pair">${eq(M.b("o"), ...(perspective ? [M.b("e")] : []), traceRow(ray, "origin"))}${eq(...direction)}</div>`;
  return html;
}

// The objects tested, the hits (the first few) and the closest.
function intersectStage(first) {
  const tests = first.filter((l) => l.step === "test");
  const hits = tests.filter((l) => l.t !== null);
  const shown = hits.slice(0, 4).map((l) => `${traceSpan(l, "t")} (${esc(l.shape.toLowerCase())} ${esc(l.object)})`);
  const more = hits.length > shown.length ? `, … ${hits.length - shown.length} more` : "";
  let html = note(`${tests.length} object${tests.length === 1 ? "" : "s"} tested, ${hits.length} hit${hits.length === 1 ? "" : "s"}${hits.length ? `: t = ${shown.join(", ")}${more}` : ""}.`);
  const closest = first.find((l) => l.step === "closest");
  if (!closest) return html + note("The ray misses everything: the pixel is the background.");
  html += eq(M.i("t"), M.r(M.i("min"), "<mspace width=\"0.2em\"></mspace>", M.i("t")), M.r(traceNumber(closest, "t"), M.text(`: object ${closest.object}, ${closest.shape.toLowerCase()}`)))
    + `<div class="pair">${eq(M.b("p"), M.r(M.b("o"), M.o("+"), M.i("t"), M.b("d")), traceRow(closest, "point"))}${eq(M.b("n"), traceRow(closest, "normal"))}</div>`;
  return html;
}

// Each term the shading adds, then the pixel's value.
function colourStage(first, pixel) {
  let html = "";
  let mix = null;
  for (const l of first) {
    if (l.step === "background") html += eq(M.i("c"), M.text("background"), traceRow(l, "color"));
    else if (l.step === "surface" || l.step === "flat") html += eq(M.i("c"), M.r(traceRow(l, "color"), M.text(`, material ${l.material}`)));
    else if (l.step === "normals") html += eq(M.f(M.r(M.b("n"), M.o("+"), M.n("1")), M.n("2")), traceRow(l, "value"));
    else if (l.step === "depth") html += eq(M.text("depth value"), traceNumber(l, "value"));
    else if (l.step === "headlight") html += eq(M.text("headlight"), traceRow(l, "term"));
    else if (l.step === "ambient") html += eq(M.r(M.text(`light ${l.light}`), M.o(":"), M.i("c"), M.o("⁢"), M.sub(M.b("I"), M.i("a"))), traceRow(l, "term"));
    else if (l.step === "light" && l.lit) {
      html += eq(M.text(`light ${l.light}`), traceRow(l, "lit.term"));
    } else if (l.step === "light") {
      const blocked = l.shadow_ray && l.shadow_ray.blocked;
      html += note(`light ${esc(l.light)}: ${blocked ? "in shadow, its shadow ray blocked" : "behind the surface"}, adds nothing`);
    } else if (l.step === "reflect") html += note(`a mirror, m = ${traceSpan(l, "mirror")}: colour = (1 − m) c<sub>here</sub> + m c<sub>reflected</sub>`);
    else if (l.step === "mix") mix = l;
  }
  const [r, g, b] = pixel.srgb8 || [];
  const swatch = `<span class="swatch" title="the pixel in a one-sample render" style="background: rgb(${Number(r)}, ${Number(g)}, ${Number(b)})"></span>`;
  // A mirror's mix (its formula in the mirror's note) is the pixel's colour.
  const colour = mix ? eq(M.text("colour"), traceRow(mix, "color")) : eq(M.text("colour"), traceRow(pixel, "linear"));
  return html + `<div class="pair">${colour}`
    + `<div class="line">${swatch}<math display="block"><mrow><mtext>8-bit sRGB</mtext><mo>=</mo>${traceRow(pixel, "srgb8")}</mrow></math></div></div>`;
}
