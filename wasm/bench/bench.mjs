// antcd-wasm against two JavaScript peers on the same mesh pairs and poses, in one node process:
// three-mesh-bvh's MeshBVH.intersectsGeometry (BVH against BVH) and Rapier's trimesh-trimesh
// intersection (@dimforge/rapier3d-compat: two sensor colliders on kinematic bodies in a World,
// one step per query),
// with the native library (antcd_wasm_bench_native) for the reference verdicts and time.
//
// Usage: node bench/bench.mjs --native BUILD/wasm_bench_native_binary [--quick]
//   (after `npm ci` in wasm/ for the peers; ANTCD_ASSIMP_MODELS overrides the test-model folder)
// Prints one Markdown table: time per boolean query (mean over every pose, repeated for at least
// half a second per library, the native library's too), ratios, and verdicts that differ from
// the native library's; and for antcd-wasm against native, the median over the poses of the
// per-pose time ratio (each pose's time: the best of 5 rounds of repeated calls at that pose, on
// both sides), which the few colliding poses do not dominate as they do the means.
import { execFileSync } from 'node:child_process';
import { existsSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';

import RAPIER from '@dimforge/rapier3d-compat';
import * as THREE from 'three';
import { MeshBVH } from 'three-mesh-bvh';

import { antcd, packagedModels, readObj, rng, workdir, writeObj } from '../test/helpers.mjs';

const argv = process.argv.slice(2);
const nativeBin = argv[argv.indexOf('--native') + 1];
if (!argv.includes('--native') || !nativeBin) {
  console.error('usage: node bench/bench.mjs --native PATH/antcd_wasm_bench_native [--quick]');
  process.exit(2);
}
const quick = argv.includes('--quick');
const POSES = quick ? 40 : 200;
const MIN_MS = quick ? 100 : 500;
const SAME_POSE = quick ? 5 : 20; // calls per round at one pose (per-pose times)

await RAPIER.init();

function radiusOf(positions) {
  let r = 0;
  for (let k = 0; k < positions.length; k += 3) r = Math.max(r, Math.hypot(positions[k], positions[k + 1], positions[k + 2]));
  return r;
}

// A uniformly random rotation (unit quaternion) and a translation within reach of both meshes.
function randomPoses(seed, reach) {
  const random = rng(seed);
  const poses = [];
  for (let k = 0; k < POSES; ++k) {
    const q = new THREE.Quaternion(random() - 0.5, random() - 0.5, random() - 0.5, random() - 0.5).normalize();
    const t = new THREE.Vector3(random() - 0.5, random() - 0.5, random() - 0.5).multiplyScalar(2 * reach);
    poses.push(new THREE.Matrix4().compose(t, q, new THREE.Vector3(1, 1, 1)).elements);
  }
  return poses;
}

function timed(queries) {
  let passes = 0;
  const start = performance.now();
  let elapsed = 0;
  do {
    queries();
    ++passes;
    elapsed = performance.now() - start;
  } while (elapsed < MIN_MS);
  return (elapsed * 1e6) / (passes * POSES);
}

function geometry(mesh) {
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(Float32Array.from(mesh.positions), 3));
  g.setIndex(new THREE.BufferAttribute(Uint32Array.from(mesh.indices), 1));
  return g;
}

function runCase(name, meshA, meshB, seed) {
  const a = new antcd.Model(meshA.positions, meshA.indices, { name: `${name} A` });
  const b = new antcd.Model(meshB.positions, meshB.indices, { name: `${name} B` });
  const reach = 0.6 * (radiusOf(meshA.positions) + radiusOf(meshB.positions));
  const poses = randomPoses(seed, reach);
  const identity = new THREE.Matrix4().elements;

  // Native: reference verdicts and time.
  const fileA = writeObj(`${name}-a.obj`, meshA.positions, meshA.indices);
  const fileB = writeObj(`${name}-b.obj`, meshB.positions, meshB.indices);
  const poseFile = join(workdir, `${name}-poses.txt`);
  writeFileSync(poseFile, poses.map((p) => [...identity, ...p].join(' ')).join('\n') + '\n');
  const native = JSON.parse(execFileSync(nativeBin, [fileA, fileB, poseFile, String(MIN_MS), String(SAME_POSE)], { encoding: 'utf8' }));

  // antcd-wasm: the boolean query (collides: the verdict alone, as the peers answer).
  const wasmVerdicts = poses.map((p) => antcd.collides(a, identity, b, p));
  const wasmNs = timed(() => {
    for (const p of poses) antcd.collides(a, identity, b, p);
  });
  const perPoseRatio = median(poses.map((p, k) => {
    let best = Infinity;
    for (let round = 0; round < 5; ++round) {
      const start = performance.now();
      for (let r = 0; r < SAME_POSE; ++r) antcd.collides(a, identity, b, p);
      best = Math.min(best, ((performance.now() - start) * 1e6) / SAME_POSE);
    }
    return best / native.per_query_ns[k];
  }));

  // three-mesh-bvh: B's geometry carries its own BVH (boundsTree), so the query is BVH against BVH.
  const gA = geometry(meshA);
  const gB = geometry(meshB);
  const bvhA = new MeshBVH(gA);
  gB.boundsTree = new MeshBVH(gB);
  const matrices = poses.map((p) => new THREE.Matrix4().fromArray(p));
  const bvhVerdicts = matrices.map((m) => bvhA.intersectsGeometry(gB, m));
  const bvhNs = timed(() => {
    for (const m of matrices) bvhA.intersectsGeometry(gB, m);
  });

  // Rapier: sensor trimesh colliders on two kinematic bodies (Rapier computes sensor
  // intersections only for colliders attached to bodies); a query moves B's body, steps the world
  // (broad and narrow phase) and reads the pair's intersection flag.
  const world = new RAPIER.World({ x: 0, y: 0, z: 0 });
  const desc = (mesh) => RAPIER.ColliderDesc.trimesh(Float32Array.from(mesh.positions), Uint32Array.from(mesh.indices))
    .setSensor(true).setActiveCollisionTypes(RAPIER.ActiveCollisionTypes.ALL);
  const bodyA = world.createRigidBody(RAPIER.RigidBodyDesc.kinematicPositionBased());
  const bodyB = world.createRigidBody(RAPIER.RigidBodyDesc.kinematicPositionBased());
  const cA = world.createCollider(desc(meshA), bodyA);
  const cB = world.createCollider(desc(meshB), bodyB);
  const rq = poses.map((p) => {
    const m = new THREE.Matrix4().fromArray(p);
    const t = new THREE.Vector3();
    const q = new THREE.Quaternion();
    m.decompose(t, q, new THREE.Vector3());
    return { t: { x: t.x, y: t.y, z: t.z }, q: { x: q.x, y: q.y, z: q.z, w: q.w } };
  });
  const rapierQuery = (p) => {
    bodyB.setTranslation(p.t, true);
    bodyB.setRotation(p.q, true);
    world.step();
    return world.intersectionPair(cA, cB);
  };
  const rapierVerdicts = rq.map(rapierQuery);
  const rapierNs = timed(() => {
    for (const p of rq) rapierQuery(p);
  });
  world.free();

  const differ = (v) => v.reduce((n, x, k) => n + (Boolean(x) !== Boolean(native.verdicts[k]) ? 1 : 0), 0);
  const row = {
    name, trianglesA: a.triangleCount, trianglesB: b.triangleCount,
    colliding: native.verdicts.reduce((s, v) => s + v, 0),
    nativeNs: native.ns_per_query, wasmNs, bvhNs, rapierNs, perPoseRatio,
    wasmDiffer: differ(wasmVerdicts), bvhDiffer: differ(bvhVerdicts), rapierDiffer: differ(rapierVerdicts),
  };
  a.delete();
  b.delete();
  return row;
}

function median(values) {
  const s = [...values].sort((x, y) => x - y);
  return s[s.length >> 1];
}

function generated(triangles) {
  // A UV sphere and a torus of about `triangles` triangles each (2 * slices * (stacks - 1)).
  const n = Math.round(Math.sqrt(triangles / 4));
  const sphere = antcd.Model.sphere(1, 2 * n, n + 1);
  const torus = antcd.Model.torus(1, 0.35, 2 * n, n);
  const meshes = [sphere.mesh(), torus.mesh()];
  sphere.delete();
  torus.delete();
  return meshes;
}

const rows = [];
for (const [k, size] of [1000, 10000, 100000].entries()) {
  const [s, t] = generated(size);
  rows.push(runCase(`sphere-torus ${size / 1000}k`, s, t, 11 + k));
}
const spider = join(packagedModels, 'OBJ', 'spider.obj');
const wuson = join(packagedModels, 'OBJ', 'WusonOBJ.obj');
if (existsSync(spider) && existsSync(wuson)) {
  rows.push(runCase('spider-wuson (assimp)', readObj(spider), readObj(wuson), 5));
}

const f = (ns) => (ns >= 1e5 ? `${(ns / 1e3).toFixed(0)} µs` : ns >= 1e3 ? `${(ns / 1e3).toFixed(1)} µs` : `${ns.toFixed(0)} ns`);
const x = (r) => `${r.toFixed(r >= 10 ? 0 : 1)}x`;
console.log(`node ${process.version}, ${POSES} poses per pair (A fixed, B at random rotations and translations), boolean queries`);
console.log('| pair | triangles A / B | colliding | native antcd | antcd-wasm | wasm / native | wasm / native per pose (median) | three-mesh-bvh | bvh / wasm | Rapier | Rapier / wasm | verdicts differing from native (wasm, bvh, Rapier) |');
console.log('|---|---|---|---|---|---|---|---|---|---|---|---|');
for (const r of rows) {
  console.log(`| ${r.name} | ${r.trianglesA} / ${r.trianglesB} | ${r.colliding}/${POSES} | ${f(r.nativeNs)} | ${f(r.wasmNs)} | ${x(r.wasmNs / r.nativeNs)} | ${x(r.perPoseRatio)} | ` +
    `${f(r.bvhNs)} | ${x(r.bvhNs / r.wasmNs)} | ${f(r.rapierNs)} | ${x(r.rapierNs / r.wasmNs)} | ${r.wasmDiffer}, ${r.bvhDiffer}, ${r.rapierDiffer} |`);
}
if (rows.some((r) => r.wasmDiffer !== 0)) {
  console.error('error: antcd-wasm verdicts differ from the native library');
  process.exit(1);
}
