// The live page's work per frame, in node: the scene's objects in an antcd-wasm World, every frame
// the moving objects' poses set and collideAll asked (as the page asks it: every contact, at most
// 4 per pair; also with 16 per pair, and as a boolean query), against the native exact runner on the same scene
// (`antcd run --method exact --threads 1`, its per-frame time) and its pairs.
//
// Usage: node bench/scene.mjs --antcd BIN --scene SCENE.json   (OBJ meshes, as `antcd scene
// generate` writes them)
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join, resolve } from 'node:path';

import { antcd, readObj } from '../test/helpers.mjs';

const argv = process.argv.slice(2);
const arg = (k) => argv[argv.indexOf(k) + 1];
if (!argv.includes('--antcd') || !argv.includes('--scene')) {
  console.error('usage: node bench/scene.mjs --antcd BIN --scene SCENE.json');
  process.exit(2);
}
const scenePath = resolve(arg('--scene'));
const scene = JSON.parse(readFileSync(scenePath, 'utf8'));
if (scene.objects.some((o) => o.scale !== undefined && o.scale !== 1)) throw new Error('scaled objects are not supported here');

// Column-major matrix of a scene pose: the rotation as the native loader builds it (Eigen's
// quaternion-to-matrix formula on the normalised quaternion) and the translation.
function matrixOf(p) {
  const [w0, x0, y0, z0] = p.rotation_wxyz ?? [1, 0, 0, 0];
  const n = Math.sqrt(w0 * w0 + x0 * x0 + y0 * y0 + z0 * z0);
  const [w, x, y, z] = [w0 / n, x0 / n, y0 / n, z0 / n];
  const tx = 2 * x, ty = 2 * y, tz = 2 * z;
  const twx = tx * w, twy = ty * w, twz = tz * w, txx = tx * x, txy = ty * x, txz = tz * x;
  const tyy = ty * y, tyz = tz * y, tzz = tz * z;
  const t = p.translation ?? [0, 0, 0];
  return [1 - (tyy + tzz), txy + twz, txz - twy, 0, txy - twz, 1 - (txx + tzz), tyz + twx, 0,
    txz + twy, tyz - twx, 1 - (txx + tyy), 0, t[0], t[1], t[2], 1];
}

const models = new Map();
const world = new antcd.World();
const objects = scene.objects.map((o) => {
  if (!models.has(o.mesh)) {
    const m = readObj(join(dirname(scenePath), o.mesh));
    models.set(o.mesh, new antcd.Model(m.positions, m.indices, { name: o.mesh }));
  }
  const poses = o.poses.map(matrixOf);
  return { name: o.name, poses, handle: world.add(models.get(o.mesh), poses[0], { name: o.name }) };
});
const names = new Map(objects.map((o) => [o.handle, o.name]));

function run(options, record) {
  const times = [];
  const pairs = [];
  for (let f = 0; f < scene.frames; ++f) {
    const t0 = performance.now();
    for (const o of objects) if (o.poses.length > 1) world.setPose(o.handle, o.poses[f]);
    const r = world.collideAll(options);
    times.push(performance.now() - t0);
    if (record) {
      const list = [];
      for (let k = 0; k < r.pairs.length; k += 2) list.push([names.get(r.pairs[k]), names.get(r.pairs[k + 1])].sort().join('|'));
      pairs.push(list.sort());
    }
  }
  times.sort((a, b) => a - b);
  return { mean: times.reduce((s, t) => s + t, 0) / times.length, median: times[times.length >> 1], max: times[times.length - 1], pairs };
}

// Each measured after a pass over every frame (the engine's tier-up compilation, grown buffers).
run({}, false);
const boolean = run({}, true);
run({ allContacts: true, maxContacts: 16 }, false);
const page = run({ allContacts: true, maxContacts: 16 }, false);
const four = run({ allContacts: true, maxContacts: 4 }, false);

const out = join(mkdtempSync(join(tmpdir(), 'antcd-scene-bench-')), 'exact.json');
execFileSync(resolve(arg('--antcd')), ['run', scenePath, '--method', 'exact', '--threads', '1', '--out', out], { stdio: 'ignore' });
const exact = JSON.parse(readFileSync(out, 'utf8'));
let differing = 0;
for (const fr of exact.frames) {
  const ref = fr.pairs.map((p) => [...p].sort().join('|')).sort();
  if (JSON.stringify(ref) !== JSON.stringify(boolean.pairs[fr.frame])) ++differing;
}
const nativeTimes = exact.frames.map((fr) => fr.time_ms ?? fr.query_ms).filter((t) => typeof t === 'number');
const nativeMean = nativeTimes.length ? nativeTimes.reduce((s, t) => s + t, 0) / nativeTimes.length : NaN;
const ms = (t) => `${t.toFixed(3)} ms`;
console.log(`${scene.objects.length} objects, ${scene.frames} frames, node ${process.version}`);
console.log(`antcd-wasm World, boolean collideAll:               mean ${ms(boolean.mean)}, median ${ms(boolean.median)}, max ${ms(boolean.max)} per frame`);
console.log(`antcd-wasm World, all contacts (<= 16/pair):        mean ${ms(page.mean)}, median ${ms(page.median)}, max ${ms(page.max)} per frame`);
console.log(`antcd-wasm World, all contacts (<= 4/pair, page):  mean ${ms(four.mean)}, median ${ms(four.median)}, max ${ms(four.max)} per frame`);
console.log(`native antcd run --method exact --threads 1:        mean ${ms(nativeMean)} per frame`);
console.log(`frames whose colliding pairs differ from native exact: ${differing} of ${exact.frames.length}`);
if (differing !== 0) process.exit(1);
