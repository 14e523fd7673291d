// The live playground in a real browser: headless Chromium, driven by playwright-core,
// run by `cargo xtask browser` against `viewray serve`. Usage:
//
//   node playground.mjs URL VIEWRAY_BINARY OUT_DIR
//
// Checks: the page loads with no console errors; the render appears, refined in passes of
// 1, 4 and 16 samples, at the size it is shown; moving a control changes the image and
// the URL; reloading the URL restores the camera and the image; clicking a pixel shows the
// same ray `viewray rays` prints and the trace `viewray trace` prints; every family and preset renders without an error;
// switching the projection kind keeps the picture (a thin lens focused on what the middle
// of the picture shows, a parallel view as tall there); a refused camera leaves the page
// on the last camera rendered (controls, numbers, picture, URL, status); the samples menu
// offers only what the server renders; the presenter fits one screen at 1024 x 768 and
// 1280 x 720; the keys work; the slide and the views save; the catalogue's mistakes (only
// those the camera can make offered, the picture, the numbers and the top view the
// mistaken camera's, held by the URL, a refused one undone); a thin lens's slider moved
// quickly over many values ends on the last value's picture with no request refused as
// busy (the server stops each abandoned render); the lens's tilt, swing, blades and
// rotation controls. Saves screenshots at 1024 x 768,
// 1280 x 720 and 1920 x 1080 in OUT_DIR. Exits 1 on the first failure.

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
  acceptDownloads: true,
  args: ["--no-sandbox", "--disable-gpu", "--disable-background-networking",
    "--disable-component-update", "--no-first-run", "--disable-sync"],
});
const consoleErrors = [];
const unanswered = new Map();
let page;

// Waits until the page has shown `count` renders, the last pass is shown and nothing is
// in flight.
async function settled(count) {
  await page.waitForFunction(
    (n) => Number(document.body.dataset.renders) >= n && document.body.dataset.busy === "0"
      && document.body.dataset.shown === "full",
    count, { timeout: 120000 });
}
const renders = () => page.evaluate(() => Number(document.body.dataset.renders));
const renderShot = () => page.locator("#render").screenshot();
const errorsShown = () => page.evaluate(
  () => [...document.querySelectorAll("output.error")].map((o) => o.textContent).filter((t) => t));
const hash = () => page.evaluate(() => location.hash);
const fragment = () => page.evaluate(() => Object.fromEntries(new URLSearchParams(location.hash.slice(1))));
const numberBox = async (id) => Number(await page.locator(`#number-${id}`).inputValue());
// Presses a key with nothing focused, as a lecturer would between controls.
async function key(name) {
  await page.evaluate(() => document.activeElement && document.activeElement.blur());
  await page.keyboard.press(name);
}
// Where the picture is drawn, and the image's natural size.
const picture = () => page.evaluate(() => {
  const image = document.getElementById("render");
  const box = image.getBoundingClientRect();
  const natural = [image.naturalWidth, image.naturalHeight];
  const scale = Math.min(box.width / natural[0], box.height / natural[1]);
  return { natural, shown: [natural[0] * scale, natural[1] * scale], box: [box.x, box.y, box.width, box.height],
    ratio: window.devicePixelRatio };
});
// The width and height of a PNG from its header.
const pngSize = (bytes) => [bytes.readUInt32BE(16), bytes.readUInt32BE(20)];

try {
  page = context.pages()[0] || await context.newPage();
  page.on("console", (message) => {
    if (message.type() === "error") consoleErrors.push(message.text());
  });
  page.on("pageerror", (error) => consoleErrors.push(String(error)));
  // The requests sent and not yet answered (told on a failure).
  page.on("request", (request) => unanswered.set(request, Date.now()));
  page.on("requestfinished", (request) => unanswered.delete(request));
  page.on("requestfailed", (request) => unanswered.delete(request));
  const renderRequests = [];
  page.on("request", (request) => {
    if (request.url().includes("/api/render?")) {
      renderRequests.push(Number(new URL(request.url()).searchParams.get("samples")));
    }
  });

  // The page loads; the render appears in passes of 1, 4 and 16 samples (the scene's).
  await page.goto(url);
  await settled(1);
  const first = await picture();
  check(first.natural[0] > 0 && first.natural[1] > 0, `the render appears (${first.natural.join(" x ")})`);
  check(JSON.stringify(renderRequests.slice(0, 3)) === "[1,4,16]",
    `the picture is refined in passes of 1, 4, 16 samples: ${renderRequests}`);
  check(Math.abs(first.natural[0] - first.shown[0] * first.ratio) <= 1,
    `the picture is rendered at the size it is shown (${first.natural[0]} px for ${first.shown[0].toFixed(1)} px)`);
  await page.screenshot({ path: join(out, "loaded-1280x800.png") });

  // Moving a control changes the image and the URL.
  const hashBefore = await hash();
  const imageBefore = await renderShot();
  const before = await renders();
  await key("2");
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
  const hashAfter = await hash();
  const imageAfter = await renderShot();
  check(hashAfter !== hashBefore, "moving the eye's x slider changes the URL");
  check(!imageAfter.equals(imageBefore), "moving the eye's x slider changes the image");
  const ron = await page.locator("#ron").inputValue();
  check(/eye: \(-?\d/.test(ron) && !ron.includes("eye: (5.2,"), "the RON follows the slider");

  // Reloading the URL restores the camera and the picture.
  await page.reload();
  await settled(1);
  check(await hash() === hashAfter, "the URL survives a reload");
  check(await page.locator("#ron").inputValue() === ron, "reloading restores the camera");
  check((await renderShot()).equals(imageAfter), "reloading restores the same image");

  // Clicking a pixel shows its viewing ray, digit for digit as `viewray rays` prints it.
  const frame = await page.locator("#render").boundingBox();
  await page.mouse.click(frame.x + frame.width * 0.37, frame.y + frame.height * 0.61);
  await page.waitForFunction(() => document.getElementById("ray-json").textContent.includes("direction"));
  const state = await fragment();
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
  await key("1");
  for (const kind of ["ThinLens", "Orthographic", "Oblique", "Fisheye", "Equirectangular", "Isometric",
    "Cabinet", "ThreePoint", "Top", "Perspective"]) {
    const n = await renders();
    await page.selectOption("#kind", kind);
    await settled(n + 1);
    const errors = await errorsShown();
    check(errors.length === 0, `${kind} renders with no error shown${errors.length ? ": " + errors : ""}`);
  }
  check(consoleErrors.length === 0, `no console errors${consoleErrors.length ? ": " + consoleErrors.join(" | ") : ""}`);

  // Switching the kind keeps the picture: from the served perspective camera, a thin lens
  // focused where the middle of the picture is (the server's depth there, about 7), an
  // orthographic view as tall there as the perspective one (vh d'/d at that depth).
  await page.goto(url);
  await page.reload();
  await settled(1);
  const depth = await page.evaluate(async () => {
    const response = await fetch(`/api/depth?${cameraQuery()}`);
    return (await response.json()).depth;
  });
  check(depth > 5 && depth < 10, `the scene lies ${depth} along the view at the picture's middle`);
  let n = await renders();
  await page.selectOption("#kind", "ThinLens");
  await settled(n + 1);
  const focus = await numberBox("focus");
  check(Math.abs(focus - depth) < 0.01, `a thin lens is focused on it: f = ${focus}`);
  n = await renders();
  await page.selectOption("#kind", "Perspective");
  await settled(n + 1);
  n = await renders();
  await page.selectOption("#kind", "Orthographic");
  await settled(n + 1);
  const vh = 2 * Math.tan(32 * Math.PI / 360);
  const height = await numberBox("height-world");
  check(Math.abs(height - vh * depth) < 0.01,
    `an orthographic view is as tall as the perspective one there: vh = ${height}, ${(vh * depth).toFixed(3)} expected`);
  n = await renders();
  await page.selectOption("#kind", "Oblique");
  await settled(n + 1);
  check(Math.abs(await numberBox("height-world") - height) < 1e-9, "oblique keeps the view's height");

  // A refused camera: its error beside the control, and the page stays on the last camera
  // rendered: controls, numbers, picture and URL agree, the status says so, and a reload
  // brings no error back.
  await page.goto(url);
  await page.reload();
  await settled(1);
  await page.selectOption("#window-mode", "viewport");
  await settled(1);
  const goodHash = await hash();
  const goodVh = await numberBox("viewport-vh");
  const goodFrame = await page.locator("#frame-e").textContent();
  await page.fill("#number-viewport-vh", "-3");
  await page.locator("#number-viewport-vh").dispatchEvent("change");
  await page.waitForFunction(() => document.querySelector('output.error[data-for="window"]')?.textContent);
  await page.waitForFunction(() => document.body.dataset.busy === "0");
  const windowError = await page.locator('output.error[data-for="window"]').textContent();
  check(windowError.startsWith("camera:"), `vh = -3 is refused beside the window: ${windowError}`);
  check(await numberBox("viewport-vh") === goodVh, `the vh box goes back to ${goodVh}`);
  check(await hash() === goodHash, "the URL keeps the last camera rendered");
  check(await page.locator("#frame-e").textContent() === goodFrame, "the numbers are the camera shown");
  const status = await page.evaluate(() => [document.getElementById("status").textContent,
    document.getElementById("status").className]);
  check(!status[0].includes("rendering") && status[1] === "error", `the status says so: ${status[0]}`);
  check(await page.evaluate(() => getComputedStyle(document.getElementById("render")).opacity) === "1",
    "the picture is not dimmed");
  await page.reload();
  await settled(1);
  check((await errorsShown()).length === 0 && await hash() === goodHash, "a reload brings no error back");
  // A typo in the RON box: refused beside it, kept there to be corrected.
  await key("4");
  const typo = "(eye: (0.0, 1.0, 5.0), lok_at: (0.0, 0.0, 0.0), projection: Perspective(fov_y: 40.0))";
  await page.fill("#ron", typo);
  await page.click("#apply-ron");
  await page.waitForFunction(() => document.querySelector('output.error[data-for="ron"]').textContent);
  await page.waitForFunction(() => document.body.dataset.busy === "0");
  check(await page.locator("#ron").inputValue() === typo, "the RON with its typo stays in the box");
  const goodCamera = new URLSearchParams(goodHash.slice(1)).get("camera");
  check((await fragment()).camera === goodCamera, "the typo does not reach the URL");
  check((await page.locator('output.error[data-for="ron"]').textContent()).includes("lok_at"),
    "the typo's error names it");
  // A size too large: refused beside the size, the size boxes back to the last one.
  await key("3");
  await page.selectOption("#size-preset", "");
  await page.fill("#width", "100000");
  await page.locator("#width").dispatchEvent("change");
  await page.waitForFunction(() => document.querySelector('output.error[data-for="size"]').textContent !== "");
  await page.waitForFunction(() => document.body.dataset.busy === "0");
  const sizeError = await page.locator('output.error[data-for="size"]').textContent();
  check(sizeError.startsWith("width: 100000 x ") && sizeError.includes("each side can be at most"),
    `a too large width is shown at the size: ${sizeError}`);
  check(await page.locator("#width").inputValue() === "640" && (await fragment()).width === "640"
    && (await fragment()).camera === goodCamera, "the width goes back to 640, the URL with it");
  const refused = consoleErrors.splice(0);
  check(refused.every((e) => e.includes("status of 400")), "the only console errors are the refused requests");

  // The samples menu offers what the server renders for the size: at 640 x 480 at most
  // 2^26 / (640 x 480) = 218, so not 256; a link asking for 256 gets 218.
  const offered = await page.evaluate(() => [...document.getElementById("samples").options].map((o) => Number(o.value)));
  check(Math.max(...offered) <= 218 && !offered.includes(256), `640 x 480 offers ${offered}`);
  const asking = new URLSearchParams({ ...(await fragment()), samples: 256, width: 640, height: 480 });
  await page.goto(`${url}#${asking}`);
  await page.reload();
  await page.waitForFunction(() => Number(document.body.dataset.renders) >= 1);
  check((await fragment()).samples === "218" && (await errorsShown()).length === 0,
    "a link asking for 256 samples at 640 x 480 gets 218, and no refusal");
  await key("3");
  await page.selectOption("#samples", "4");
  await settled(1);
  // A small image is rendered at the size shown, not scaled up.
  await page.selectOption("#size-preset", "");
  await page.fill("#width", "240");
  await page.fill("#height", "180");
  await page.locator("#height").dispatchEvent("change");
  await settled(1);
  const small = await picture();
  check(small.natural[0] > 240 && Math.abs(small.natural[0] - small.shown[0] * small.ratio) <= 1,
    `a 240 x 180 image is rendered at the ${small.shown[0].toFixed(0)} px it is shown (${small.natural.join(" x ")})`);
  // Its own pixels, on P: 240 x 180, drawn as sharp squares.
  await key("p");
  await settled(1);
  const pixels = await picture();
  check(pixels.natural[0] === 240 && pixels.natural[1] === 180, "P shows the image's own 240 x 180 pixels");
  check(await page.evaluate(() => getComputedStyle(document.getElementById("render")).imageRendering) === "pixelated",
    "drawn as sharp squares");
  await key("p");
  await settled(1);

  // The presenter fits one screen: at 1024 x 768 and 1280 x 720 nothing scrolls the page,
  // the picture and the side view are large, and the controls of every topic are reached
  // without moving the picture.
  for (const [width, height] of [[1024, 768], [1280, 720]]) {
    await page.setViewportSize({ width, height });
    await page.goto(url);
    await page.reload();
    await settled(1);
    const layout = await page.evaluate(() => {
      const rect = (id) => document.getElementById(id).getBoundingClientRect();
      return { scroll: document.documentElement.scrollHeight, inner: innerHeight, render: rect("render-frame"),
        side: rect("side-frame") };
    });
    check(layout.scroll <= layout.inner, `${width} x ${height}: the page does not scroll (${layout.scroll} px)`);
    check(layout.render.width >= 0.55 * width && layout.render.bottom <= height,
      `${width} x ${height}: the picture is ${layout.render.width.toFixed(0)} px wide, on screen`);
    check(layout.side.height >= 0.28 * height && layout.side.bottom <= height,
      `${width} x ${height}: the side view is ${layout.side.height.toFixed(0)} px tall, on screen`);
    for (const topic of ["1", "2", "3", "4"]) {
      await key(topic);
      const controls = page.locator("#controls fieldset:not([hidden]) input, #controls fieldset:not([hidden]) select, #controls fieldset:not([hidden]) textarea");
      const last = controls.last();
      await last.scrollIntoViewIfNeeded();
      const [control, render] = await Promise.all([last.boundingBox(), page.locator("#render-frame").boundingBox()]);
      check(control.y >= 0 && control.y + control.height <= height && render.y === layout.render.y,
        `${width} x ${height}: topic ${topic}'s last control is on screen and the picture stays`);
    }
    await key("1");
  }

  // Keys: the top view, the keys' help.
  await key("t");
  await page.waitForFunction(() => !document.getElementById("top-frame").hidden
    && document.getElementById("top-diagram").naturalWidth > 0 && document.body.dataset.busy === "0");
  check((await fragment()).top === "1", "T shows the top view, and the URL says so");
  await key("?");
  check(await page.locator("#keys").isVisible(), "? shows the keys");
  await key("Escape");
  check(!await page.locator("#keys").isVisible(), "Escape hides them");
  await key("t");
  check(await page.locator("#top-frame").isHidden(), "T hides the top view again");

  // Save as slide: a 1920 x 1080 PNG of this camera; the views as SVG.
  const links = await page.evaluate(() => ["save-slide", "save-side", "save-top"].map((id) => document.getElementById(id).href));
  const saved = await page.evaluate(async (hrefs) => Promise.all(hrefs.map(async (href) => {
    const response = await fetch(href);
    const bytes = new Uint8Array(await response.arrayBuffer());
    return { status: response.status, type: response.headers.get("content-type"), head: [...bytes.slice(0, 24)] };
  })), links);
  check(saved[0].status === 200 && saved[0].type === "image/png"
    && pngSize(Buffer.from(saved[0].head)).join("x") === "1920x1080", "the slide is a 1920 x 1080 PNG");
  check(saved.slice(1).every((s) => s.status === 200 && s.type === "image/svg+xml"), "the views save as SVG");
  const [download] = await Promise.all([page.waitForEvent("download"), key("s")]);
  check(download.suggestedFilename() === "viewray-slide.png", "S saves the slide");

  // The catalogue's mistakes: the menu offers those the camera can make; one made changes
  // the picture, shows the top view (u-sign mirrors the picture left to right) and names
  // itself and its lecture line over the picture; the numbers are the mistaken camera's;
  // the URL holds it and a reload restores it.
  await page.setViewportSize({ width: 1024, height: 768 });
  await page.goto(url);
  await page.reload();
  await settled(1);
  const rightPicture = await renderShot();
  const offeredMistakes = () => page.evaluate(
    () => [...document.querySelectorAll("#mistakes-list input")].map((box) => box.value));
  const perspectiveOffers = await offeredMistakes();
  check(perspectiveOffers.includes("u-sign") && perspectiveOffers.includes("distance-sign")
    && !perspectiveOffers.some((id) => id.startsWith("ortho-") || id.startsWith("oblique-")),
  `a perspective camera is offered ${perspectiveOffers.length} mistakes, none of the parallel cameras'`);
  check(await page.locator("#top-frame").isHidden() && await page.locator("#mistakes-list").isHidden(),
    "no top view for the right perspective camera, the menu closed");
  await key("m");
  check(await page.locator("#mistakes-list").isVisible(), "M opens the mistakes");
  n = await renders();
  await page.click('#mistakes-list input[value="u-sign"]');
  await settled(n + 1);
  await page.waitForFunction(() => !document.getElementById("top-frame").hidden
    && document.getElementById("top-diagram").naturalWidth > 0 && document.body.dataset.busy === "0");
  check(!(await renderShot()).equals(rightPicture), "u-sign changes the picture");
  check(await page.locator("#top-frame").isVisible(), "u-sign shows the top view");
  check((await fragment()).mistakes === "u-sign" && (await fragment()).top === undefined,
    "the URL holds the mistake (and the top view follows from it)");
  const label = await page.locator("#mistake-label").textContent();
  check(label.includes("u-sign") && label.includes("u = ((j - 1/2)/W - 1/2) vw"),
    `a label names it and its lecture line: ${label}`);
  await key("Escape");
  check(await page.locator("#mistakes-list").isHidden(), "Escape closes the menu");
  // The pixel's ray is the mistaken camera's: u-sign's ray through column c is the right
  // camera's through column W - 1 - c.
  const mistakenFrame = await page.locator("#render").boundingBox();
  await page.mouse.click(mistakenFrame.x + mistakenFrame.width * 0.3, mistakenFrame.y + mistakenFrame.height * 0.5);
  await page.waitForFunction(() => document.getElementById("ray-json").textContent.includes("direction")
    && document.body.dataset.busy === "0");
  const mistakenState = await fragment();
  const mistakenRay = JSON.parse((await page.locator("#ray-json").textContent()).split("\n")[1]);
  const mirroredCol = Number(mistakenState.width) - 1 - Number(mistakenState.col);
  const rayDir = mkdtempSync(join(tmpdir(), "viewray-rays-"));
  const rayScene = join(rayDir, "camera.ron");
  writeFileSync(rayScene, `(image: (width: ${mistakenState.width}, height: ${mistakenState.height}), camera: ${mistakenState.camera})`);
  const mirroredRay = JSON.parse(execFileSync(viewray, ["rays", rayScene, "--pixel", `${mistakenState.row},${mirroredCol}`],
    { encoding: "utf8" }));
  rmSync(rayDir, { recursive: true, force: true });
  check(mistakenRay.direction.every((x, k) => Math.abs(x - mirroredRay.direction[k]) < 1e-12)
    && Math.abs(mistakenRay.u - mirroredRay.u) < 1e-12,
  `pixel (${mistakenState.row}, ${mistakenState.col}) shows u-sign's u and ray: viewray rays' for column ${mirroredCol}`);
  check((await page.locator("#trace").textContent()).includes("untick them"),
    "the trace, the lecture's formulas, waits for the mistakes to be unticked");
  // A basis mistake shows in the frame: u = w x up flips u.
  const rightU = await page.locator("#frame-u").textContent();
  await key("m");
  await page.click('#mistakes-list input[value="u-cross-order"]');
  await page.waitForFunction((u) => document.getElementById("frame-u").textContent !== u
    && document.body.dataset.busy === "0", rightU);
  const flipped = (text) => text.replace(/[()]/g, "").split(",").map(Number);
  check(flipped(await page.locator("#frame-u").textContent()).every((x, k) => x === -flipped(rightU)[k]),
    `u-cross-order's frame has u = w x up: ${await page.locator("#frame-u").textContent()}`);
  check((await fragment()).mistakes === "u-sign,u-cross-order", "two mistakes, in the catalogue's order, in the URL");
  const twoMistakes = await hash();
  await page.reload();
  await settled(1);
  check(await hash() === twoMistakes && await page.locator('#mistakes-list input[value="u-cross-order"]').isChecked()
    && (await page.locator("#mistake-label").textContent()).includes("u-cross-order"),
  "a reload restores both, ticked and named");
  await page.screenshot({ path: join(out, "mistakes-1024x768.png") });
  // Another kind of camera offers its own: an orthographic one not distance-sign but
  // ortho-origin-fixed; the mistakes it can make stay.
  n = await renders();
  await key("1");
  await page.selectOption("#kind", "Orthographic");
  await settled(n + 1);
  const orthographicOffers = await offeredMistakes();
  check(!orthographicOffers.includes("distance-sign") && orthographicOffers.includes("ortho-origin-fixed"),
    "an orthographic camera is offered ortho-origin-fixed, not distance-sign");
  check((await fragment()).mistakes === "u-sign,u-cross-order" && (await errorsShown()).length === 0,
    "the mistakes it can make stay, with no error");
  // A link with a mistake its camera cannot make is refused beside the menu, and the page
  // goes back to the last camera it rendered, with its mistakes.
  const madeHash = await hash();
  const unfitting = new URLSearchParams({ ...(await fragment()), mistakes: "distance-sign" });
  await page.evaluate((h) => { location.hash = h; }, unfitting.toString());
  await page.waitForFunction(() => document.querySelector('output.error[data-for="mistakes"]').textContent
    && document.body.dataset.busy === "0");
  const mistakeError = await page.locator('output.error[data-for="mistakes"]').textContent();
  check(mistakeError.startsWith("mistakes:") && mistakeError.includes("distance-sign"),
    `distance-sign is refused beside the menu: ${mistakeError}`);
  check(await hash() === madeHash && (await page.locator("#mistake-label").textContent()).includes("u-cross-order"),
    "the URL and the label go back to the camera last rendered, with its mistakes");
  const unfittingErrors = consoleErrors.splice(0);
  check(unfittingErrors.every((e) => e.includes("status of 400")), "the only console errors are the refused requests");

  // A thin lens's focus moved quickly over many values at 256 samples (each value's
  // render abandoned for the next): the last value's picture arrives, and no request was
  // told the server is busy (it stops each abandoned render at once).
  const serverRenders = () => page.evaluate(() => fetch("/api/status").then((r) => r.json()).then((s) => s.renders));
  const lensLink = new URLSearchParams({ camera: "(eye: (5.2, 1.6, 6.0), view: (-5.2, 0.0, -6.0), "
    + "projection: ThinLens(fov_y: 32.0, aperture: 0.2, focus: 5.0))", width: 640, height: 360, samples: 256,
  shading: "Lit" });
  await page.goto(`${url}#${lensLink}`);
  await page.reload();
  await settled(1);
  const before503 = await serverRenders();
  const focusSlider = page.locator("#range-focus");
  await focusSlider.focus();
  for (let k = 0; k < 24; k++) await page.keyboard.press("ArrowRight");
  await page.waitForFunction(() => sameSettings(rendered, settingsOf(state)) && document.body.dataset.busy === "0"
    && document.body.dataset.shown === "full", null, { timeout: 120000 });
  const after503 = await serverRenders();
  check(Math.abs(await numberBox("focus") - 6.2) < 1e-9 && (await fragment()).camera.includes("focus: 6.2"),
    "24 steps of the focus slider end at f = 6.2, in the URL");
  check(after503.busy === before503.busy && !consoleErrors.some((e) => e.includes("503")),
    `no render was refused as busy (the server stopped ${after503.superseded - before503.superseded} abandoned ones)`);
  check(after503.running === 0 && after503.waiting === 0, "and nothing is left rendering");

  // The lens's movements: tilt and swing (with a focal length), blades and their rotation,
  // each a control that changes the camera, the URL and the picture.
  const movable = new URLSearchParams({ camera: "(eye: (5.2, 1.6, 6.0), view: (-5.2, 0.0, -6.0), "
    + "projection: ThinLens(focal_length: 35.0, aperture: 0.2, focus: 7.0))", width: 320,
  height: 180, samples: 16, shading: "Lit" });
  await page.goto(`${url}#${movable}`);
  await page.reload();
  await settled(1);
  for (const [id, value, written] of [["lens_tilt", "8", "lens_tilt: 8"], ["lens_swing", "-6", "lens_swing: -6"]]) {
    const unmoved = await renderShot();
    n = await renders();
    await page.fill(`#number-${id}`, value);
    await page.locator(`#number-${id}`).dispatchEvent("change");
    await settled(n + 1);
    check((await fragment()).camera.includes(written) && !(await renderShot()).equals(unmoved),
      `${id} = ${value} reaches the camera, the URL and the picture`);
  }
  let picture6 = await renderShot();
  n = await renders();
  await page.selectOption("#blades", "6");
  await settled(n + 1);
  check((await fragment()).camera.includes("blades: 6") && !(await renderShot()).equals(picture6)
    && await page.locator("#number-blade_rotation").isVisible(), "6 blades reach the camera and offer their rotation");
  picture6 = await renderShot();
  n = await renders();
  await page.fill("#number-blade_rotation", "30");
  await page.locator("#number-blade_rotation").dispatchEvent("change");
  await settled(n + 1);
  check((await fragment()).camera.includes("blade_rotation: 30") && !(await renderShot()).equals(picture6),
    "the blades' rotation reaches the camera and the picture");
  n = await renders();
  await page.selectOption("#blades", "0");
  await settled(n + 1);
  check(!(await fragment()).camera.includes("blades") && await page.locator("#number-blade_rotation").count() === 0,
    "a round aperture leaves blades and their rotation out of the RON");
  check((await errorsShown()).length === 0 && consoleErrors.length === 0, "the lens controls raise no error");

  // The default scene through a thin lens with a pixel chosen, as a lecturer would show
  // it, at 1024 x 768, 1280 x 720 and 1920 x 1080 (a link holds all of it); the largest
  // with the top view.
  const camera = "(eye: (5.2, 1.6, 6.0), view: (-5.2, 0.0, -6.0), up: (0.0, 1.0, 0.0), "
    + "projection: ThinLens(fov_y: 32.0, shift: (0.0, -0.17), aperture: 0.06, focus: 7.0))";
  const link = new URLSearchParams({ camera, width: 640, height: 360, samples: 16, shading: "Lit",
    row: 212, col: 352 });
  for (const [width, height] of [[1024, 768], [1280, 720], [1920, 1080]]) {
    await page.setViewportSize({ width, height });
    if (width === 1920) link.set("top", "1");
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
  // What the page still waits for, and what the server is doing.
  const waiting = page && await page.evaluate(async () => ({
    inFlight: channels.map((c) => (c.inflight || c.pending || { url: "" }).url.split("?")[0]),
    status: await fetch("/api/status").then((r) => r.text()).catch(() => "no answer"),
  })).catch(() => null);
  if (waiting) console.error(`the page waits for: ${waiting.inFlight.join(", ")}; the server: ${waiting.status}`);
  for (const [request, sent] of unanswered) {
    const [path, query] = request.url().split("?");
    console.error(`unanswered after ${((Date.now() - sent) / 1000).toFixed(1)} s: ${path}?${decodeURIComponent(query || "")}`);
  }
  if (consoleErrors.length) console.error(`console errors: ${consoleErrors.join(" | ")}`);
  await context.close();
  rmSync(profile, { recursive: true, force: true });
  process.exit(1);
}
await context.close();
rmSync(profile, { recursive: true, force: true });
