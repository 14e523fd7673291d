// three.js's own projections of the scenes `cargo xtask interop` exported, and cameras
// made in three.js for the importer to read.
//
// Usage: node three_check.mjs THREE_MODULE JOB.json RESULT.json
//
// JOB: {"cases": [{"name", "file", "points": [[x, y, z]...], "roundtrip": path | null}],
//       "made": [{"name", "camera": {...}, "out": path, "points": [[x, y, z]...]}]}
// RESULT: {"cases": {name: {"points": [[x, y] | null...], "size": [W, H]}},
//          "made": {name: {"points": [...], "size": [W, H]}}}
// Points are Vector3.project(camera), NDC turned into image coordinates of the camera's
// view (fullWidth x fullHeight; x from the left, y from the top, in pixels).
import { readFileSync, writeFileSync } from 'node:fs';
import { pathToFileURL } from 'node:url';

const [, , threePath, jobPath, resultPath] = process.argv;
const THREE = await import(pathToFileURL(threePath).href);

function findCamera(object) {
  let camera = null;
  object.traverse((o) => { if (!camera && o.isCamera) camera = o; });
  return camera;
}

function project(camera, points, size) {
  camera.updateMatrixWorld(true);
  camera.updateProjectionMatrix();
  const [width, height] = size;
  return points.map(([x, y, z]) => {
    const local = new THREE.Vector3(x, y, z).applyMatrix4(camera.matrixWorldInverse);
    if (camera.isPerspectiveCamera ? local.z >= 0 : false) return null;
    const ndc = new THREE.Vector3(x, y, z).project(camera);
    return [(ndc.x + 1) / 2 * width, (1 - ndc.y) / 2 * height];
  });
}

function size(camera) {
  if (camera.view && camera.view.enabled) return [camera.view.fullWidth, camera.view.fullHeight];
  return [480 * camera.aspect, 480];
}

const job = JSON.parse(readFileSync(jobPath, 'utf8'));
const result = { cases: {}, made: {} };
const loader = new THREE.ObjectLoader();
for (const c of job.cases) {
  const object = loader.parse(JSON.parse(readFileSync(c.file, 'utf8')));
  object.updateMatrixWorld(true);
  const camera = findCamera(object);
  result.cases[c.name] = { points: project(camera, c.points, size(camera)), size: size(camera) };
  if (c.roundtrip) writeFileSync(c.roundtrip, JSON.stringify(object.toJSON()));
}
for (const m of job.made ?? []) {
  const d = m.camera;
  let camera;
  if (d.type === 'perspective') {
    camera = new THREE.PerspectiveCamera(d.fov, d.aspect, 0.1, 1000);
    if (d.zoom) camera.zoom = d.zoom;
    if (d.filmOffset) camera.filmOffset = d.filmOffset;
  } else {
    camera = new THREE.OrthographicCamera(d.left, d.right, d.top, d.bottom, d.near, 1000);
    if (d.zoom) camera.zoom = d.zoom;
  }
  if (d.view) camera.setViewOffset(...d.view);
  camera.position.set(...d.position);
  camera.up.set(...d.up);
  camera.lookAt(...d.target);
  camera.updateMatrixWorld(true);
  camera.updateProjectionMatrix();
  const object = d.inScene ? new THREE.Scene().add(camera) : camera;
  object.updateMatrixWorld(true);
  writeFileSync(m.out, JSON.stringify(object.toJSON()));
  result.made[m.name] = { points: project(camera, m.points, size(camera)), size: size(camera) };
}
writeFileSync(resultPath, JSON.stringify(result));
