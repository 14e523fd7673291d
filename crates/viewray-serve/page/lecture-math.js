// The lecture's formulas: MathML written as strings (Chromium, Firefox and Safari typeset
// MathML Core; nothing is fetched), and the command line's numbers read from its JSON
// lines as the text it printed, so the page shows its digits, never JavaScript's.

const served = JSON.parse(document.getElementById("served").textContent);
const $ = (id) => document.getElementById(id);

// The lecture's image: 640 x 360, a projector's shape.
const W = 640;
const H = 360;

// `text` safe inside HTML.
function esc(text) {
  return String(text).replace(/&/g, "&amp;").replace(/</g, "&lt;").replace(/>/g, "&gt;").replace(/"/g, "&quot;");
}

// A number the page computed itself (not the command line's): up to 4 decimals.
function fmt(x) {
  if (!Number.isFinite(x)) return String(x);
  const r = Number(x.toFixed(4));
  return String(Object.is(r, -0) ? 0 : r);
}

// A number as RON writes a float: always with a point.
function ronNumber(x) {
  const r = Math.round(x * 10000) / 10000;
  return Number.isInteger(r) ? r.toFixed(1) : String(r);
}
const ronVec = (a) => `(${a.map(ronNumber).join(", ")})`;

// The scalar printed for `key` in a JSON line, as printed ("1.0" stays "1.0").
function rawValue(line, key) {
  const m = new RegExp(`"${key}":(-?[0-9][0-9.eE+-]*|null)`).exec(line || "");
  return m ? m[1] : null;
}
// The array printed for `key`, each number as printed.
function rawArray(line, key) {
  const m = new RegExp(`"${key}":\\[([^\\]]*)\\]`).exec(line || "");
  return m ? m[1].split(",") : null;
}

// MathML pieces. `cls` colours a symbol as the figures do (u, v, w).
const M = {
  i: (s, cls) => `<mi${cls ? ` class="${cls}"` : ""}>${esc(s)}</mi>`,
  b: (s, cls) => `<mi mathvariant="bold"${cls ? ` class="${cls}"` : ""}>${esc(s)}</mi>`,
  n: (s) => `<mn>${esc(s)}</mn>`,
  o: (s) => `<mo>${esc(s)}</mo>`,
  r: (...xs) => `<mrow>${xs.join("")}</mrow>`,
  f: (a, b) => `<mfrac>${a}${b}</mfrac>`,
  p: (...xs) => `<mrow><mo>(</mo>${xs.join("")}<mo>)</mo></mrow>`,
  abs: (...xs) => `<mrow><mo>|</mo>${xs.join("")}<mo>|</mo></mrow>`,
  sqrt: (x) => `<msqrt>${x}</msqrt>`,
  sub: (a, b) => `<msub>${a}${b}</msub>`,
  text: (s) => `<mtext>${esc(s)}</mtext>`,
  half: () => `<mfrac><mn>1</mn><mn>2</mn></mfrac>`,
  // A number the command line printed, named `key` for the tests that compare it.
  cli: (s, key) => `<mn class="cli" data-cli="${esc(key)}">${esc(s ?? "?")}</mn>`,
  // A column vector of MathML `cells`.
  column: (cells) => `<mrow><mo>(</mo><mtable>${cells.map((c) => `<mtr><mtd>${c}</mtd></mtr>`).join("")}</mtable><mo>)</mo></mrow>`,
  // A vector the command line printed, as a column.
  cliVec: (parts, key) => (parts ? M.column(parts.map((s, k) => M.cli(s, `${key}.${k}`))) : M.text("?")),
  // A vector the page computed, as a column.
  vec: (a) => M.column(a.map((x) => M.n(fmt(x)))),
};
// A displayed equation: `parts` joined by "=".
const eq = (...parts) => `<div class="line"><math display="block"><mrow>${parts.join("<mo>=</mo>")}</mrow></math></div>`;
const note = (html) => `<p class="note">${html}</p>`;

// The lecture's pixel formulas, substituted: u from j, W and vw; v from i, H and vh.
function uFormula(j, vw, u) {
  return eq(
    M.i("u", "u"),
    M.r(M.p(M.f(M.r(M.i("j"), M.o("−"), M.half()), M.i("W")), M.o("−"), M.half()), M.o("⁢"), M.i("vw")),
    M.r(M.p(M.f(M.r(M.n(String(j)), M.o("−"), M.n("0.5")), M.n(String(W))), M.o("−"), M.n("0.5")), M.o("×"), M.n(vw)),
    M.cli(u, "ray.u"),
  );
}
function vFormula(i, vh, v) {
  return eq(
    M.i("v", "v"),
    M.r(M.o("−"), M.p(M.f(M.r(M.i("i"), M.o("−"), M.half()), M.i("H")), M.o("−"), M.half()), M.o("⁢"), M.i("vh")),
    M.r(M.o("−"), M.p(M.f(M.r(M.n(String(i)), M.o("−"), M.n("0.5")), M.n(String(H))), M.o("−"), M.n("0.5")), M.o("×"), M.n(vh)),
    M.cli(v, "ray.v"),
  );
}
// The ray's origin and direction as the command line printed them.
// `originSymbolic` and `directionSymbolic` (null: none) are the formulas they come from.
function rayLines(ctx, originSymbolic, directionSymbolic) {
  const line = (symbol, symbolic, key) => eq(...[M.b(symbol), symbolic, M.cliVec(rawArray(ctx.ray, key), `ray.${key}`)]
    .filter((part) => part !== null));
  return line("o", originSymbolic, "origin") + line("d", directionSymbolic, "direction");
}
// The frame's vectors as the command line printed them.
function frameLine(ctx, name, cls) {
  const symbol = name === "e" ? "e" : name.toUpperCase();
  return eq(M.b(symbol, cls), M.cliVec(rawArray(ctx.frame, name), `frame.${name}`));
}

// Vector arithmetic for the intermediate steps the page shows.
const sub3 = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const norm = (a) => Math.hypot(a[0], a[1], a[2]);
const deg = (x) => (x * Math.PI) / 180;
