// The live playground in a real browser: headless Chromium, driven by playwright-core,
// run by `cargo xtask browser` against `viewray serve`. Usage:
//
//   node playground.mjs URL VIEWRAY_BINARY OUT_DIR
//
// Checks: the page loads with no console errors; the render appears; moving a control
// changes the image and the URL; reloading the URL restores the camera and the image;
// clicking a pixel shows the same ray `viewray rays` prints and the trace `viewray trace`
// prints; every family and preset renders without an error. Saves screenshots in OUT_DIR. Exits 1 on the first failure.

import { chromium } from "playwright-core";
import { execFileSync } from "node:child_process";
import { mkdtempSync, mkdirSync, rmSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";

const [url, viewray, out] = process.argv.slice(2);
if (!url || !viewray || !out) {
  console.error("usage: node playground.mjs URL VIEWRAY_BINARY OUT_DIR");
  process.exit(2);
}
mkdirSync(out, { recursive: true });

let checks = 0;
function check(condition, what) {
  if (!condition) throw new Error(`FAILED: ${what}`);
  checks += 1;
  console.log(`ok   ${what}`);
}

const profile = mkdtempSync(join(tmpdir(), "viewray-chromium-"));
const context = await chromium.launchPersistentContext(profile, {
  executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
  headless: true,
  viewport: { width: 1280, height: 800 },
  args: ["--no-sandbox", "--disable-gpu", "--disable-background-networking",
    "--disable-component-update", "--no-first-run", "--disable-sync"],
});
const consoleErrors = [];
let page;

// Waits until the page has shown `count` renders and nothing is in flight.
async function settled(count) {
  await page.waitForFunction(
    (n) => Number(document.body.dataset.renders) >= n && document.body.dataset.busy === "0"
      && document.body.dataset.shown === "full",
    count, { timeout: 60000 });
}
const renders = () => page.evaluate(() => Number(document.body.dataset.renders));
const renderShot = () => page.locator("#render").screenshot();
const errorsShown = () => page.evaluate(
  () => [...document.querySelectorAll("output.error")].map((o) => o.textContent).filter((t) => t));

try {
  page = context.pages()[0] || await context.newPage();
  page.on("console", (message) => {
    if (message.type() === "error") consoleErrors.push(message.text());
  });
  page.on("pageerror", (error) => consoleErrors.push(String(error)));

  // The page loads and the render appears.
  await page.goto(url);
  await settled(1);
  const natural = await page.evaluate(() => {
    const image = document.getElementById("render");
    return [image.naturalWidth, image.naturalHeight];
  });
  check(natural[0] > 0 && natural[1] > 0, `the render appears (${natural.join(" x ")})`);
  await page.screenshot({ path: join(out, "loaded-1280x800.png") });

  // Moving a control changes the image and the URL.
  const hashBefore = await page.evaluate(() => location.hash);
  const imageBefore = await renderShot();
  const before = await renders();
  const eyeX = page.locator("#range-eye-x");
  const box = await eyeX.boundingBox();
  // Drag the slider: previews while it moves, the full image when it is let go.
  await page.mouse.move(box.x + box.width * 0.62, box.y + box.height / 2);
  await page.mouse.down();
  for (let k = 1; k <= 6; k++) {
    await page.mouse.move(box.x + box.width * (0.62 - k * 0.04), box.y + box.height / 2);
  }
  await page.mouse.up();
  await settled(before + 1);
  const hashAfter = await page.evaluate(() => location.hash);
  const imageAfter = await renderShot();
  check(hashAfter !== hashBefore, "moving the eye's x slider changes the URL");
  check(!imageAfter.equals(imageBefore), "moving the eye's x slider changes the image");
  const ron = await page.locator("#ron").inputValue();
  check(/eye: \(-?\d/.test(ron) && !ron.includes("eye: (5.2,"), "the RON follows the slider");

  // Reloading the URL restores the camera and the picture.
  await page.reload();
  await settled(1);
  check(await page.evaluate(() => location.hash) === hashAfter, "the URL survives a reload");
  check(await page.locator("#ron").inputValue() === ron, "reloading restores the camera");
  check((await renderShot()).equals(imageAfter), "reloading restores the same image");

  // Clicking a pixel shows its viewing ray, digit for digit as `viewray rays` prints it.
  const frame = await page.locator("#render").boundingBox();
  await page.mouse.click(frame.x + frame.width * 0.37, frame.y + frame.height * 0.61);
  await page.waitForFunction(() => document.getElementById("ray-json").textContent.includes("direction"));
  const state = await page.evaluate(() => Object.fromEntries(new URLSearchParams(location.hash.slice(1))));
  const shown = (await page.locator("#ray-json").textContent()).split("\n")[1];
  const dir = mkdtempSync(join(tmpdir(), "viewray-rays-"));
  const scene = join(dir, "camera.ron");
  writeFileSync(scene, `(image: (width: ${state.width}, height: ${state.height}), camera: ${state.camera})`);
  const printed = execFileSync(viewray, ["rays", scene, "--pixel", `${state.row},${state.col}`], { encoding: "utf8" }).trim();
  rmSync(dir, { recursive: true, force: true });
  check(shown === printed, `pixel (${state.row}, ${state.col}) shows the ray viewray rays prints:\n     ${printed}`);

  // The same click shows the pixel's trace, as `viewray trace` prints it for the served
  // scene through the page's camera (the render named in the playground's words).
  await page.waitForFunction(
    () => /writes it: \(\d+, \d+, \d+\)\n$/.test(document.getElementById("trace").textContent));
  const traced = await page.locator("#trace").textContent();
  const served = await page.evaluate(() => JSON.parse(document.getElementById("served").textContent));
  const sceneText = await page.evaluate(() => fetch("/api/scene").then((r) => r.text()));
  check(sceneText.includes(served.camera) && state.shading === served.shading
    && Number(state.width) === served.width && Number(state.height) === served.height,
    "the trace's scene is the served scene with the page's camera");
  const traceDir = mkdtempSync(join(tmpdir(), "viewray-trace-"));
  const traceScene = join(traceDir, "scene.ron");
  writeFileSync(traceScene, sceneText.replace(served.camera, () => state.camera));
  const printedTrace = execFileSync(viewray, ["trace", traceScene, "--pixel", `${state.row},${state.col}`],
    { encoding: "utf8" });
  rmSync(traceDir, { recursive: true, force: true });
  check(traced === printedTrace.replace("`viewray render --samples 1`", "a one-sample render"),
    `pixel (${state.row}, ${state.col}) shows the trace viewray trace prints:\n     ${traced.split("\n").slice(-2).join("\n     ")}`);
  await page.waitForFunction(() => document.body.dataset.busy === "0");
  await page.screenshot({ path: join(out, "playground-ray-1280x800.png") });

  // Every family and every preset renders, with no error next to any control.
  for (const kind of ["ThinLens", "Orthographic", "Oblique", "Fisheye", "Equirectangular", "Isometric",
    "Cabinet", "ThreePoint", "Top", "Perspective"]) {
    const n = await renders();
    await page.selectOption("#kind", kind);
    await settled(n + 1);
    const errors = await errorsShown();
    check(errors.length === 0, `${kind} renders with no error shown${errors.length ? ": " + errors : ""}`);
  }

  check(consoleErrors.length === 0, `no console errors${consoleErrors.length ? ": " + consoleErrors.join(" | ") : ""}`);

  // A bad value is refused by the server and shown next to the control that caused it
  // (Chromium logs each refused request: those, and only those, are expected here).
  await page.selectOption("#size-preset", "");
  await page.fill("#width", "100000");
  await page.locator("#width").dispatchEvent("change");
  await page.waitForFunction(() => document.querySelector('output.error[data-for="size"]').textContent !== "");
  const sizeError = await page.locator('output.error[data-for="size"]').textContent();
  check(sizeError.startsWith("width: 100000 x ") && sizeError.includes("at most 4096 pixels"),
    `a too large width is shown at the size: ${sizeError}`);
  const refused = consoleErrors.splice(0);
  check(refused.every((e) => e.includes("status of 400")), "the only console errors are the refused requests");
  await page.fill("#width", "640");
  await page.fill("#height", "360");
  await page.locator("#height").dispatchEvent("change");
  await settled(1);

  // The default scene through a thin lens with a pixel chosen, as a lecturer would
  // show it, at 1280 x 800 and 1920 x 1080 (a link holds all of it).
  const camera = "(eye: (5.2, 1.6, 6.0), view: (-5.2, 0.0, -6.0), up: (0.0, 1.0, 0.0), "
    + "projection: ThinLens(fov_y: 32.0, shift: (0.0, -0.17), aperture: 0.06, focus: 7.0))";
  const link = new URLSearchParams({ camera, width: 640, height: 360, samples: 16, shading: "Lit",
    row: 212, col: 352 });
  for (const [width, height] of [[1280, 800], [1920, 1080]]) {
    await page.setViewportSize({ width, height });
    await page.goto(`${url}#${link}`);
    await page.reload();
    await settled(1);
    await page.waitForFunction(() => document.getElementById("ray-json").textContent.includes("direction"));
    await page.waitForFunction(() => document.body.dataset.busy === "0");
    await page.screenshot({ path: join(out, `playground-${width}x${height}.png`) });
  }
  check(await page.locator("#kind").inputValue() === "ThinLens", "a link opens the thin lens it holds");

  check(consoleErrors.length === 0, `no console errors${consoleErrors.length ? ": " + consoleErrors.join(" | ") : ""}`);
  console.log(`browser: ${checks} checks passed; screenshots in ${out}`);
} catch (error) {
  if (page) await page.screenshot({ path: join(out, "failure.png") }).catch(() => {});
  console.error(error.message);
  if (consoleErrors.length) console.error(`console errors: ${consoleErrors.join(" | ")}`);
  await context.close();
  rmSync(profile, { recursive: true, force: true });
  process.exit(1);
}
await context.close();
rmSync(profile, { recursive: true, force: true });
