// The npm package's WebAssembly builds against each other and against the native library, on
// queries that do work: two tori of 10k and 100k triangles each, posed to touch (collide with
// every contact: many node pairs and triangle tests) and posed just apart (the boolean collides:
// a traversal down to the leaves that ends without a contact).
//
// Usage: node bench/simd.mjs --native PATH/antcd_wasm_bench_native [--variant NAME=DIR ...] [--quick]
//   the package's own dist/ is the variant "package"; each --variant DIR holds another build's
//   antcd_core.cjs and antcd_core.wasm (e.g. made with -DANTCD_WASM_SSE2=OFF or
//   -DANTCD_WASM_SIMD=OFF, docs/javascript.md "SIMD128" gives the commands).
// Interleaved: every round times each variant and the native library (antcd_wasm_bench_native,
// one process per round) in turn, the order rotating from round to round, so that the load of a
// shared machine falls on all of them alike. A pose's time in a round: SAME consecutive calls
// divided by SAME; per pose, the median over the rounds; each table cell: the median over the
// poses. Ratios are medians over the poses of the per-pose ratios. Every variant's verdicts, and
// with all contacts each pose's contact count and triangle pairs (FNV-1a digests), must equal the
// native library's, and its contacts (triangles, points, distances: the bytes of the doubles) the
// first variant's: the script exits 1 otherwise. The last column counts the poses whose contact
// points differ from the native library's in some bit (WebAssembly and x86-64 builds are not
// promised the same last bits of a point; the pairs are).
import { execFileSync } from 'node:child_process';
import { copyFileSync, mkdirSync, writeFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

import { antcd, rng, workdir, writeObj } from '../test/helpers.mjs';

const here = dirname(fileURLToPath(import.meta.url));
const argv = process.argv.slice(2);
const arg = (name) => (argv.includes(name) ? argv[argv.indexOf(name) + 1] : undefined);
const nativeBin = arg('--native');
if (!nativeBin) {
  console.error('usage: node bench/simd.mjs --native PATH/antcd_wasm_bench_native [--variant NAME=DIR ...] [--quick]');
  process.exit(2);
}
const quick = argv.includes('--quick');
const ROUNDS = quick ? 3 : 9;
const POSES = quick ? 6 : 16;
const TARGET_MS = quick ? 2 : 5; // per pose and round: SAME calls take about this long

// Each variant: a copy of the package (its .mjs files) around that build's dist/, imported anew.
const variants = [{ name: 'package', api: antcd }];
for (let k = 0; k < argv.length; ++k) {
  if (argv[k] !== '--variant') continue;
  const [name, dir] = argv[k + 1].split('=');
  const copy = join(workdir, `variant-${name}`);
  mkdirSync(join(copy, 'dist'), { recursive: true });
  for (const f of ['index.mjs', 'deform.mjs', 'world.mjs', 'package.json']) copyFileSync(join(here, '..', f), join(copy, f));
  for (const f of ['antcd_core.cjs', 'antcd_core.wasm']) copyFileSync(join(resolve(dir), f), join(copy, 'dist', f));
  const createAntcd = (await import(pathToFileURL(join(copy, 'index.mjs')).href)).default;
  variants.push({ name, api: await createAntcd() });
}

// A uniformly random rotation (unit quaternion) and a unit direction, as a column-major pose with
// translation s * direction.
function randomFrame(random) {
  let q;
  do {
    q = [random() - 0.5, random() - 0.5, random() - 0.5, random() - 0.5];
  } while (Math.hypot(...q) < 0.1);
  const n = Math.hypot(...q);
  const [w, x, y, z] = q.map((v) => v / n);
  const m = [1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y), 0,
    2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x), 0,
    2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y), 0];
  let d;
  do {
    d = [random() - 0.5, random() - 0.5, random() - 0.5];
  } while (Math.hypot(...d) < 0.1);
  const dn = Math.hypot(...d);
  return { m, d: d.map((v) => v / dn) };
}
const posed = (f, s) => [...f.m, s * f.d[0], s * f.d[1], s * f.d[2], 1];

// Poses along random directions at the boundary between touching and apart, found by bisection
// on the distance of B from A: `touching` just inside (s = 0.98 s*), otherwise just outside
// (1.002 s*), where the traversal goes deepest.
function boundaryPoses(a, b, reach, seed, touching) {
  const random = rng(seed);
  const identity = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];
  const poses = [];
  while (poses.length < POSES) {
    const f = randomFrame(random);
    let lo = 0;
    let hi = reach;
    if (!antcd.collides(a, identity, b, posed(f, lo)) || antcd.collides(a, identity, b, posed(f, hi))) continue;
    for (let k = 0; k < 30; ++k) {
      const mid = 0.5 * (lo + hi);
      if (antcd.collides(a, identity, b, posed(f, mid))) lo = mid;
      else hi = mid;
    }
    const p = posed(f, (touching ? 0.98 : 1.002) * lo);
    if (antcd.collides(a, identity, b, p) === touching) poses.push(p);
  }
  return poses;
}

// FNV-1a (64-bit) of the first `fields` numbers of each contact (triangles, point, distance) as
// little-endian doubles: native_collide.cpp's contact_digest.
function digest(contacts, fields) {
  let h = 0xcbf29ce484222325n;
  const bytes = new Uint8Array(8);
  const view = new DataView(bytes.buffer);
  for (let c = 0; c < contacts.length; c += 10) {
    for (let k = 0; k < fields; ++k) {
      view.setFloat64(0, contacts[c + k], true);
      for (const byte of bytes) h = BigInt.asUintN(64, (h ^ BigInt(byte)) * 0x100000001b3n);
    }
  }
  return h.toString(16).padStart(16, '0');
}

const median = (values) => {
  const s = [...values].sort((x, y) => x - y);
  return s.length % 2 ? s[s.length >> 1] : 0.5 * (s[s.length / 2 - 1] + s[s.length / 2]);
};

function runCase(name, meshA, meshB, touching, seed) {
  const allContacts = touching;
  const identity = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];
  const models = variants.map((v) => ({
    a: new v.api.Model(meshA.positions, meshA.indices),
    b: new v.api.Model(meshB.positions, meshB.indices),
  }));
  const reach = 3;
  const poses = boundaryPoses(models[0].a, models[0].b, reach, seed, touching);
  const fileA = writeObj(`${name}-a.obj`, meshA.positions, meshA.indices);
  const fileB = writeObj(`${name}-b.obj`, meshB.positions, meshB.indices);
  const poseFile = join(workdir, `${name}-poses.txt`);
  writeFileSync(poseFile, poses.map((p) => [...identity, ...p].join(' ')).join('\n') + '\n');

  const query = (v, k) => {
    const { a, b } = models[v];
    return allContacts ? variants[v].api.collide(a, identity, b, poses[k], { allContacts: true })
      : variants[v].api.collides(a, identity, b, poses[k]);
  };
  // SAME from the first variant's time of one call per pose.
  const same = poses.map((_, k) => {
    const start = performance.now();
    query(0, k);
    return Math.max(3, Math.ceil(TARGET_MS / Math.max(1e-3, performance.now() - start)));
  });
  const sameAll = Math.max(...same);

  // Answers: verdicts and contact triangle pairs equal to the native library's, and every
  // variant's contacts bit-identical (points, distances) to the first variant's; poses whose
  // points differ from the native library's in some bit are counted (pointsOffNative).
  let differ = 0;
  let pointsOffNative = 0;
  const flags = allContacts ? ['--all-contacts'] : [];
  const nativeRun = () => JSON.parse(execFileSync(nativeBin, [...flags, '--rounds', '1', fileA, fileB, poseFile, '0', String(sameAll)],
    { encoding: 'utf8', maxBuffer: 1 << 26 }));
  const reference = nativeRun();
  const first = [];
  for (let v = 0; v < variants.length; ++v) {
    for (let k = 0; k < poses.length; ++k) {
      const r = query(v, k);
      const colliding = allContacts ? r.colliding : r;
      if (colliding !== Boolean(reference.verdicts[k])) ++differ;
      if (!allContacts) continue;
      const full = digest(r.contacts, 6);
      if (v === 0) {
        first.push(full);
        if (full !== reference.digests[k]) ++pointsOffNative;
      }
      if (r.contacts.length / 10 !== reference.contacts[k] || digest(r.contacts, 2) !== reference.pair_digests[k] || full !== first[k]) {
        if (process.env.DEBUG) console.error(variants[v].name, k, r.contacts.length / 10, reference.contacts[k], full, first[k]);
        ++differ;
      }
    }
  }

  // Interleaved rounds: times[runner][pose] = one time per round (runner variants.length: native).
  const runners = variants.length + 1;
  const times = Array.from({ length: runners }, () => poses.map(() => []));
  for (let round = 0; round < ROUNDS; ++round) {
    for (let j = 0; j < runners; ++j) {
      const v = (round + j) % runners;
      if (v === variants.length) {
        const n = nativeRun();
        n.per_query_ns.forEach((ns, k) => times[v][k].push(ns));
        continue;
      }
      for (let k = 0; k < poses.length; ++k) {
        const start = performance.now();
        for (let r = 0; r < sameAll; ++r) query(v, k);
        times[v][k].push(((performance.now() - start) * 1e6) / sameAll);
      }
    }
  }
  for (const m of models) {
    m.a.delete();
    m.b.delete();
  }
  const perPose = times.map((t) => t.map(median));
  const native = perPose[variants.length];
  return {
    name, touching, triangles: meshA.indices.length / 3, poses: poses.length, same: sameAll, differ, pointsOffNative,
    contacts: allContacts ? median(reference.contacts) : 0,
    ns: perPose.map(median),
    overNative: perPose.slice(0, variants.length).map((t) => median(t.map((x, k) => x / native[k]))),
    overFirst: perPose.slice(0, variants.length).map((t) => median(t.map((x, k) => x / perPose[0][k]))),
  };
}

function torus(triangles) {
  // 2 * slices * stacks triangles, slices = 2 * stacks.
  const n = Math.round(Math.sqrt(triangles / 4));
  const t = antcd.Model.torus(1, 0.35, 2 * n, n);
  const mesh = t.mesh();
  t.delete();
  return mesh;
}

const rows = [];
for (const [k, size] of [10000, 100000].entries()) {
  const mesh = torus(size);
  rows.push(runCase(`torus ${size / 1000}k touching`, mesh, mesh, true, 21 + k));
  rows.push(runCase(`torus ${size / 1000}k apart`, mesh, mesh, false, 31 + k));
}

const f = (ns) => (ns >= 1e5 ? `${(ns / 1e3).toFixed(0)} µs` : ns >= 1e3 ? `${(ns / 1e3).toFixed(1)} µs` : `${ns.toFixed(0)} ns`);
const x = (r) => `${r.toFixed(2)}x`;
const names = variants.map((v) => v.name);
console.log(`node ${process.version}, ${ROUNDS} interleaved rounds, median over poses of the per-pose median over rounds`);
console.log(`| case | triangles (each) | poses | calls per pose and round | contacts (median) | native | ${names.join(' | ')} | ` +
  `${names.map((n) => `${n} / native`).join(' | ')} | ${names.slice(1).map((n) => `${n} / ${names[0]}`).join(' | ')} | answers differing | poses with points not bit-equal to native |`);
console.log(`|${'---|'.repeat(8 + 3 * names.length - 1)}`);
for (const r of rows) {
  const cells = [r.name + (r.touching ? ' (collide, all contacts)' : ' (collides)'), r.triangles, r.poses, r.same, r.touching ? r.contacts : '-',
    f(r.ns[names.length]), ...r.ns.slice(0, names.length).map(f), ...r.overNative.map(x), ...r.overFirst.slice(1).map(x), r.differ, r.touching ? r.pointsOffNative : '-'];
  console.log(`| ${cells.join(' | ')} |`);
}
if (rows.some((r) => r.differ !== 0)) {
  console.error('error: answers of a WebAssembly build differ from the native library');
  process.exit(1);
}
