// The lecture (`/lecture`) in a real browser: headless Chromium, driven by playwright-core,
// run by `cargo xtask browser` against `viewray serve`. Usage:
//
//   node lecture.mjs URL VIEWRAY_BINARY OUT_DIR
//
// Checks: every step, reached with the keyboard, renders with no console errors, shows its
// formulas as MathML, and every number the page marks as the command line's equals what
// `viewray rays`, `viewray frame` and `viewray project` print for the step's camera (from
// the URL), and on the first step what `viewray trace --json` prints for the served scene
// through that camera at the lecture's size (generate, intersect, colour), also for a
// clicked pixel and one that misses everything; moving a control changes the camera, the numbers and the URL; a reload comes
// back to the step and the camera; a clicked pixel is followed; up along the view is
// refused, as by the command line, and said to be the roll ambiguity; PageUp, PageDown,
// Home and End step. Saves screenshots at 1024 x 768, 1280 x 720 and 1920 x 1080, and of
// the first step at 1024 x 768.

import { chromium } from "playwright-core";
import { execFileSync } from "node:child_process";
import { mkdtempSync, mkdirSync, rmSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";

const [url, viewray, out] = process.argv.slice(2);
if (!url || !viewray || !out) {
  console.error("usage: node lecture.mjs URL VIEWRAY_BINARY OUT_DIR");
  process.exit(2);
}
mkdirSync(out, { recursive: true });
const lecture = new URL("/lecture", url).href;

let checks = 0;
function check(condition, what) {
  if (!condition) throw new Error(`FAILED: ${what}`);
  checks += 1;
  console.log(`ok   ${what}`);
}

const STEPS = ["pseudocode", "canonical", "distance", "viewport", "eye", "rotated", "basis-w", "basis-u",
  "basis-v", "thin-lens", "taxonomy", "parallel", "shift", "foreshortening", "tilt-shift"];

const profile = mkdtempSync(join(tmpdir(), "viewray-chromium-"));
const context = await chromium.launchPersistentContext(profile, {
  executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
  headless: true,
  viewport: { width: 1024, height: 768 },
  args: ["--no-sandbox", "--disable-gpu", "--disable-background-networking",
    "--disable-component-update", "--no-first-run", "--disable-sync"],
});
const consoleErrors = [];
let page;

// Waits until the page has shown `count` renders, the last in full, and nothing is in flight.
async function settled(count) {
  await page.waitForFunction(
    (n) => document.body.dataset.busy === "0" && document.body.dataset.shown === "full"
      && Number(document.body.dataset.renders) >= n,
    count, { timeout: 120000 });
}
const renders = () => page.evaluate(() => Number(document.body.dataset.renders));
const fragment = () => page.evaluate(() => Object.fromEntries(new URLSearchParams(location.hash.slice(1))));
async function key(name) {
  await page.evaluate(() => document.activeElement && document.activeElement.blur());
  await page.keyboard.press(name);
}

// The scalar or array printed for `key` in a JSON line, as printed.
function raw(line, key) {
  const array = new RegExp(`"${key}":\\[([^\\]]*)\\]`).exec(line);
  if (array) return array[1].split(",");
  const m = new RegExp(`"${key}":(-?[0-9][0-9.eE+-]*|null)`).exec(line);
  return m ? m[1] : undefined;
}

// `viewray ARGS` on a scene holding only `camera` at 640 x 360: [ok, stdout or stderr].
function cli(camera, args) {
  const dir = mkdtempSync(join(tmpdir(), "viewray-lecture-"));
  const scene = join(dir, "camera.ron");
  writeFileSync(scene, `(image: (width: 640, height: 360), camera: ${camera})`);
  try {
    return [true, execFileSync(viewray, [args[0], scene, ...args.slice(1)], { encoding: "utf8", stdio: "pipe" }).trim()];
  } catch (error) {
    return [false, String(error.stderr)];
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
}

// A trace line read with every number kept as printed (numbers follow `:`, `[` or `,`).
function rawJson(line) {
  return JSON.parse(line.replace(/(?<=[:[,])(-?[0-9][0-9.eE+-]*)(?=[,\]}])/g, "\"$1\""));
}

// `viewray trace --json --one-based` for pixel (i, j) of the served scene seen through
// `camera` at the lecture's 640 x 360: its lines.
async function traceOf(camera, i, j) {
  const served = await page.evaluate(() => JSON.parse(document.getElementById("served").textContent));
  const sceneText = await page.evaluate(() => fetch("/api/scene").then((r) => r.text()));
  check(sceneText.includes(served.camera) && /image:\s*\([^)]*\)/.test(sceneText),
    "the trace's scene is the served scene, its camera and image size replaced");
  const dir = mkdtempSync(join(tmpdir(), "viewray-lecture-trace-"));
  const scene = join(dir, "scene.ron");
  writeFileSync(scene, sceneText.replace(served.camera, () => camera)
    .replace(/image:\s*\([^)]*\)/, "image: (width: 640, height: 360)"));
  try {
    return execFileSync(viewray, ["trace", scene, "--one-based", "--json", "--pixel", `${i},${j}`],
      { encoding: "utf8", stdio: "pipe" }).trim();
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
}

// Every number the page marks as the command line's equals the command line's, and the
// lines it shows are the command line's lines.
async function numbersAreTheCommandLines(what) {
  const f = await fragment();
  const shown = await page.evaluate(() => ({
    frame: document.getElementById("frame-line").textContent,
    ray: document.getElementById("ray-line").textContent,
    trace: document.getElementById("trace-line").textContent,
    cli: [...document.querySelectorAll("[data-cli]")].map((e) => [e.dataset.cli, e.textContent]),
    maths: document.querySelectorAll("#formulas math").length,
  }));
  check(shown.maths > 0, `${what}: formulas typeset as MathML (${shown.maths})`);
  const [rayOk, rays] = cli(f.camera, ["rays", "--one-based", "--pixel", `${f.i},${f.j}`]);
  const [frameOk, frame] = cli(f.camera, ["frame"]);
  check(rayOk && frameOk, `${what}: the command line takes the URL's camera ${f.camera}`);
  check(shown.ray === rays, `${what}: the ray line is viewray rays's: ${rays}`);
  check(shown.frame === frame, `${what}: the frame line is viewray frame's`);
  let compared = 0;
  let traced = null;
  if (f.step === "pseudocode") {
    traced = (await traceOf(f.camera, f.i, f.j)).split("\n");
    check(shown.trace === traced.join("\n"), `${what}: the trace's lines are viewray trace --json's (${traced.length})`);
    const stages = await page.locator("#formulas .stage h3 code").allTextContents();
    check(stages.join(" | ") === "ray = generate(i, j) | hit = intersect(ray, scene) | colour = shade(hit)",
      `${what}: the pseudocode's three stages: ${stages.join(" | ")}`);
    const names = shown.cli.map(([name]) => name);
    const last = traced.length - 1;
    check(names.includes("trace.0.direction.2") && names.includes(`trace.${last}.srgb8.2`)
      && names.includes(`trace.${last}.linear.0`), `${what}: the ray's direction and the pixel's value are shown`);
  }
  for (const [name, text] of shown.cli) {
    const [source, key, index] = name.split(".");
    let expected;
    if (source === "trace") {
      const path = name.split(".").slice(2);
      expected = path.reduce((x, k) => (x == null ? undefined : x[k]), rawJson(traced[Number(key)] || "{}"));
      check(text === expected, `${what}: ${name} = ${text}, as viewray trace prints`);
      compared += 1;
      continue;
    }
    if (source === "ray") expected = raw(rays, key);
    else if (source === "frame") expected = raw(frame, key);
    else if (source === "project") {
      const points = await page.evaluate(() => STEPS.find((s) => s.id === document.body.dataset.step)
        .project().map((p) => p.join(",")));
      const [ok, lines] = cli(f.camera, ["project", ...points.flatMap((p) => ["--point", p])]);
      check(ok, `${what}: viewray project runs`);
      expected = raw(lines.split("\n")[Number(key)], index);
      check(text === expected, `${what}: ${name} = ${text}, as viewray project prints`);
      compared += 1;
      continue;
    }
    if (Array.isArray(expected)) expected = expected[Number(index)];
    check(text === expected, `${what}: ${name} = ${text}, as the command line prints`);
    compared += 1;
  }
  check(compared > 0, `${what}: ${compared} numbers compared with the command line`);
}

try {
  page = await context.newPage();
  page.on("console", (m) => { if (m.type() === "error") consoleErrors.push(m.text()); });
  page.on("pageerror", (e) => consoleErrors.push(String(e)));

  await page.goto(lecture);
  await settled(1);
  check((await fragment()).step === "pseudocode", "the lecture starts at the pseudocode");
  const hit = await page.locator("#formulas").textContent();
  check(/objects tested/.test(hit) && /8-bit sRGB/.test(hit) && !/misses everything/.test(hit),
    "the first step follows its pixel to an object and the colour written for it");

  // The first step follows a clicked pixel: one on the ground, one in the sky.
  for (const [x, y, sky] of [[0.62, 0.9, false], [0.5, 0.04, true]]) {
    const picture = await page.locator("#render").boundingBox();
    const n = await renders();
    const before = await fragment();
    await page.mouse.click(picture.x + picture.width * x, picture.y + picture.height * y);
    await settled(n + 1);
    const clicked = await fragment();
    check(clicked.step === "pseudocode" && (clicked.i !== before.i || clicked.j !== before.j)
      && Math.abs(Number(clicked.j) - 640 * x) <= 2 && Math.abs(Number(clicked.i) - 360 * y) <= 2,
      `the first step: a click picks (i, j) = (${clicked.i}, ${clicked.j})`);
    await numbersAreTheCommandLines(`the first step at the clicked (${clicked.i}, ${clicked.j})`);
    const said = await page.locator("#formulas").textContent();
    check(/misses everything/.test(said) === sky, `(${clicked.i}, ${clicked.j}) ${sky ? "misses everything" : "hits an object"}`);
    if (!sky) await page.screenshot({ path: join(out, "lecture-pseudocode-1024x768.png") });
  }
  // Back to the lecture's pixel, (i, j) = (200, 353), for the walk through the steps.
  await page.goto(`${lecture}#step=pseudocode&i=200&j=353`);
  await page.reload();
  await settled(1);
  check((await fragment()).i === "200", "a link sets the first step's pixel");

  // Every step, with the keyboard, in the lecture's order.
  for (const [k, id] of STEPS.entries()) {
    if (k > 0) {
      const n = await renders();
      await key(k % 2 ? "ArrowRight" : "PageDown");
      await settled(n + 1);
    }
    check(await page.evaluate(() => document.body.dataset.step) === id, `step ${k + 1} is ${id}`);
    await numbersAreTheCommandLines(id);
    check(consoleErrors.length === 0, `${id}: no console errors ${consoleErrors.join(" | ")}`);
  }
  await key("PageUp");
  check((await fragment()).step === STEPS[STEPS.length - 2], "PageUp steps back");
  await key("Home");
  check((await fragment()).step === "pseudocode", "Home goes to the first step");
  await key("End");
  check((await fragment()).step === STEPS[STEPS.length - 1], "End goes to the last step");

  // One thing at a time: the distance step's d changes the camera, the URL and the numbers.
  await page.goto(`${lecture}#step=distance`);
  await page.reload();
  await settled(1);
  const before = await fragment();
  let n = await renders();
  await page.locator("#number-d").fill("2.5");
  await page.locator("#number-d").press("Enter");
  await page.locator("#number-d").blur();
  await settled(n + 1);
  const after = await fragment();
  check(after.d === "2.5" && after.camera.includes("distance: 2.5") && after.camera !== before.camera,
    `moving d changes the camera and the URL: ${after.camera}`);
  await numbersAreTheCommandLines("distance at d = 2.5");

  // A clicked pixel is followed.
  const box = await page.locator("#render").boundingBox();
  n = await renders();
  await page.mouse.click(box.x + box.width * 0.25, box.y + box.height * 0.75);
  await settled(n + 1);
  const clicked = await fragment();
  check(Math.abs(Number(clicked.j) - 160) <= 2 && Math.abs(Number(clicked.i) - 270) <= 2,
    `a click picks its pixel (i, j) = (${clicked.i}, ${clicked.j})`);
  await numbersAreTheCommandLines("the clicked pixel");

  // A reload comes back to the step, the camera and the pixel.
  await page.reload();
  await settled(1);
  const reloaded = await fragment();
  check(reloaded.step === "distance" && reloaded.camera === clicked.camera && reloaded.i === clicked.i
    && reloaded.j === clicked.j, "a reload restores the step, the camera and the pixel");
  check(await page.locator("#number-d").inputValue() === "2.5", "and the control's value");
  await numbersAreTheCommandLines("after the reload");

  // Problem 2: up along the view is the roll ambiguity, refused as the command line does.
  await page.goto(`${lecture}#step=basis-u`);
  await page.reload();
  await settled(1);
  await page.getByRole("button", { name: "up along the view" }).click();
  await page.waitForFunction(() => document.body.dataset.shown === "refused" && document.body.dataset.busy === "0");
  const refused = await fragment();
  check(await page.evaluate(() => document.body.dataset.shown) === "refused", "up along the view is refused");
  check(!cli(refused.camera, ["frame"])[0], "as the command line refuses it");
  const said = await page.locator("#formulas").textContent();
  check(/every roll about w is as good/i.test(said), "the page says it is the roll ambiguity");
  check(await page.locator("#refused").isVisible(), "the refusal is shown over the picture");
  // The browser logs the refused requests (400) as errors; nothing else may be logged.
  const logged = consoleErrors.splice(0);
  check(logged.every((e) => /status of 400/.test(e)), `the refusal logs only its 400s ${logged.join(" | ")}`);
  n = await renders();
  await page.getByRole("button", { name: "up = y" }).click();
  await settled(n + 1);
  check(await page.evaluate(() => document.body.dataset.shown) === "full", "up = y renders again");
  await numbersAreTheCommandLines("basis-u with up = y");

  // Fit for a projector: nothing scrolls the page; screenshots.
  for (const [width, height, step] of [[1024, 768, "basis-u"], [1280, 720, "thin-lens"], [1920, 1080, "taxonomy"]]) {
    await page.setViewportSize({ width, height });
    await page.goto(`${lecture}#step=${step}`);
    await page.reload();
    await settled(1);
    const fits = await page.evaluate(() => ({
      page: document.documentElement.scrollHeight <= innerHeight && document.documentElement.scrollWidth <= innerWidth,
      render: document.getElementById("render").getBoundingClientRect().height,
      side: document.getElementById("side").getBoundingClientRect().height,
    }));
    check(fits.page && fits.render > 200 && fits.side > 150,
      `${width} x ${height}: one screen, the render ${Math.round(fits.render)} px tall, the side view ${Math.round(fits.side)} px`);
    await page.screenshot({ path: join(out, `lecture-${width}x${height}.png`) });
  }
  check(consoleErrors.length === 0, `no console errors ${consoleErrors.join(" | ")}`);
  console.log(`lecture: ${checks} checks passed`);
} catch (error) {
  console.error(String(error.stack || error));
  if (page) await page.screenshot({ path: join(out, "lecture-failure.png") }).catch(() => {});
  await context.close();
  rmSync(profile, { recursive: true, force: true });
  process.exit(1);
}
await context.close();
rmSync(profile, { recursive: true, force: true });
