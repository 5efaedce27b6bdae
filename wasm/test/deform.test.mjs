// Deforming continuous collision from JS: deformSweep (self, two deforming models, a rigid one
// between two poses) and collisionFreeStep on motions with a known time of impact, against the
// native CLI (`antcd deform-ccd --json --all-pairs`), and the refusal of bad input with an Error
// naming the argument, the module answering as before afterwards.
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { test } from 'node:test';

import { antcd, cli, writeObj } from './helpers.mjs';

const I = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];
const at = (x, y = 0, z = 0) => [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, x, y, z, 1];
const TOL = 1e-6;

// Triangle 0 lies still in z = 0; triangle 1 stands in the plane y = 0.2 above it, and only its
// vertex 3 moves: from z = 1 to z = endZ (through triangle 0 at t = 0.5 for endZ = -1).
const FLOOR = [0, 0, 0, 1, 0, 0, 0, 1, 0];
const MOVER = [0.2, 0.2, 1, 0.2, 0.2, 5, 0.3, 0.2, 5];
function crossing(endZ = -1) {
  const v0 = new Float64Array([...FLOOR, ...MOVER]);
  const v1 = v0.slice();
  v1[11] = endZ;
  return { v0, v1, indices: new Uint32Array([0, 1, 2, 3, 4, 5]) };
}

function assertToiNear(toi, tStar, tol = TOL) {
  assert.ok(toi <= tStar, `toi ${toi} later than ${tStar}`);
  assert.ok(tStar - toi <= tol + 1e-12, `toi ${toi} more than ${tol} before ${tStar}`);
}

// A sheet of nx x ny vertices, flat in z = 0 (t = 0) or bent through itself along the curve
// (t^2 - 1, t^3 - t) (t = 1), with vertices numbered in order of first use by the triangles, as
// the CLI's loader numbers them, so that indices compare directly.
function foldingSheet(nx, ny) {
  const cells = [];
  for (let i = 0; i + 1 < nx; ++i) {
    for (let j = 0; j + 1 < ny; ++j) {
      const a = i * ny + j;
      const b = (i + 1) * ny + j;
      cells.push(a, b, b + 1, a, b + 1, a + 1);
    }
  }
  const order = new Map();
  for (const v of cells) if (!order.has(v)) order.set(v, order.size);
  const indices = new Uint32Array(cells.map((v) => order.get(v)));
  const v0 = new Float64Array(3 * order.size);
  const v1 = new Float64Array(3 * order.size);
  for (const [v, k] of order) {
    const i = Math.floor(v / ny);
    const j = v % ny;
    const t = -1.3 + (2.55 * i) / (nx - 1);
    v0.set([t, j / (ny - 1), 0], 3 * k);
    v1.set([t * t - 1, j / (ny - 1), t * t * t - t], 3 * k);
  }
  return { v0, v1, indices };
}

function nativeDeform(name, mesh, extra = []) {
  const p0 = writeObj(`${name}-t0.obj`, mesh.v0, mesh.indices);
  const p1 = writeObj(`${name}-t1.obj`, mesh.v1, mesh.indices);
  return JSON.parse(execFileSync(cli, ['deform-ccd', p0, p1, '--json', '--all-pairs', ...extra],
    { encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] }));
}

test('deformSweep (self): a vertex through a triangle at t = 0.5, a miss, a separation', () => {
  const { v0, v1, indices } = crossing();
  const m = new antcd.Model(v0, indices, { name: 'crossing' });
  const r = antcd.deformSweep(m, v0, v1);
  assert.equal(r.hit, true);
  assertToiNear(r.toi, 0.5);
  assert.deepEqual([r.pair.kind, r.pair.indices, r.pair.toi], ['vertexFace', [3, 0], r.toi]);
  assert.deepEqual(r.pairs, []);
  // Two triangles share one leaf: no node pair, the leaf's primitive queries only.
  assert.ok(r.primitiveQueries > 0 && r.tasks >= 1 && r.scratchBytes > 0);
  const all = antcd.deformSweep(m, v0, v1, { allPairs: true });
  assert.deepEqual(all.pairs.map((p) => [p.kind, p.indices, p.toi]), [['vertexFace', [3, 0], r.toi]]);
  // Stopping 0.1 above the floor: a miss, a full step; within 0.2 from t* = 8/9 on.
  const stop = crossing(0.1);
  const miss = antcd.deformSweep(m, stop.v0, stop.v1);
  assert.deepEqual([miss.hit, miss.toi, miss.pair], [false, 1, null]);
  assert.equal(antcd.collisionFreeStep(m, stop.v0, stop.v1, 0), 1);
  const near = antcd.deformSweep(m, stop.v0, stop.v1, { minSeparation: 0.2 });
  assert.equal(near.hit, true);
  assertToiNear(near.toi, 8 / 9);
  assert.equal(antcd.collisionFreeStep(m, stop.v0, stop.v1, 0.2), near.toi);
  assertToiNear(antcd.collisionFreeStep(m, stop.v0, stop.v1, 0.2, { timeTolerance: 1e-2 }), 8 / 9, 1e-2);
  m.delete();
});

test('deformSweep against a second deforming model and a rigid one', () => {
  const { v0, v1 } = crossing();
  const a = new antcd.Model(v0.slice(9), [0, 1, 2], { name: 'mover' });
  const b = new antcd.Model(v0.slice(0, 9), [0, 1, 2], { name: 'floor' });
  const r = antcd.deformSweep(a, v0.slice(9), v1.slice(9), b, v0.slice(0, 9), v1.slice(0, 9));
  assertToiNear(r.toi, 0.5);
  assert.deepEqual([r.hit, r.pair.kind, r.pair.indices, r.pair.vertexInFirst], [true, 'vertexFace', [0, 0], true]);
  const swapped = antcd.deformSweep(b, v0.slice(0, 9), v1.slice(0, 9), a, v0.slice(9), v1.slice(9), {});
  assert.deepEqual([swapped.toi, swapped.pair.indices, swapped.pair.vertexInFirst], [r.toi, [0, 0], false]);
  // The floor rising rigidly from z = 0 to z = 1 under a still vertex at z = 0.5; to z = 0.4 a miss.
  const still = new Float64Array(MOVER);
  still[2] = 0.5;
  const lift = antcd.deformSweep(a, still, still, b, I, at(0, 0, 1));
  assertToiNear(lift.toi, 0.5);
  assert.deepEqual([lift.hit, lift.pair.indices], [true, [0, 0]]);
  assert.equal(antcd.deformSweep(a, still, still, b, new Float64Array(I), at(0, 0, 0.4)).hit, false);
  // A quarter turn about x: the floor reaches the vertex when tan(angle) = 2.5; the chords make
  // the hit tolerance-decided and a little early, never late.
  const quarter = [1, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1];
  const turn = antcd.deformSweep(a, still, still, b, I, quarter);
  const tStar = Math.atan2(0.5, 0.2) / (Math.PI / 2);
  assert.ok(turn.hit && turn.toleranceDecided && turn.toi <= tStar && turn.toi > tStar - 0.01, JSON.stringify(turn));
  a.delete();
  b.delete();
});

for (const [name, extra] of [['fold', []], ['fold-separation', ['--min-separation', '0.05']], ['crossing', []],
  ['slide', []]]) {
  test(`deformSweep equals the native CLI: ${name}`, { skip: cli === null && 'ANTCD_CLI not set' }, () => {
    let mesh;
    if (name.startsWith('fold')) {
      mesh = foldingSheet(15, 4);
    } else if (name === 'crossing') {
      mesh = crossing();
    } else {
      mesh = foldingSheet(15, 4);
      mesh.v1 = mesh.v0.map((x, k) => x + [0.3, -0.1, 0][k % 3]);
    }
    const expected = nativeDeform(name, mesh, extra);
    const m = new antcd.Model(mesh.v0, mesh.indices);
    const opts = { allPairs: true, minSeparation: extra.length ? Number(extra[1]) : 0 };
    const r = antcd.deformSweep(m, mesh.v0, mesh.v1, opts);
    assert.equal(r.hit, expected.hit);
    assert.equal(r.hit, name !== 'slide');
    // WebAssembly's and the native build's last bits may differ: tois within the time tolerance.
    assert.ok(Math.abs(r.toi - expected.toi) <= TOL, `${r.toi} vs ${expected.toi}`);
    const vf = r.pairs.filter((p) => p.kind === 'vertexFace');
    const ee = r.pairs.filter((p) => p.kind === 'edgeEdge');
    assert.deepEqual(vf.map((p) => p.indices), expected.vertex_face.map((row) => row.slice(0, 2)));
    assert.deepEqual(ee.map((p) => p.indices), expected.edge_edge.map((row) => row.slice(0, 4)));
    vf.forEach((p, k) => assert.ok(Math.abs(p.toi - expected.vertex_face[k][2]) <= TOL));
    ee.forEach((p, k) => assert.ok(Math.abs(p.toi - expected.edge_edge[k][4]) <= TOL));
    const one = antcd.deformSweep(m, mesh.v0, mesh.v1, { minSeparation: opts.minSeparation });
    assert.equal(one.toi, r.toi);
    if (r.hit) assert.deepEqual(one.pair, r.pairs[0]);
    m.delete();
  });
}

test('deformSweep and collisionFreeStep refuse bad input with an Error naming it', () => {
  const { v0, v1, indices } = crossing();
  const m = new antcd.Model(v0, indices, { name: 'crossing' });
  const b = new antcd.Model(v0.slice(0, 9), [0, 1, 2], { name: 'floor' });
  const before = antcd.deformSweep(m, v0, v1, { allPairs: true });
  const nan = v1.slice();
  nan[4] = NaN;
  const huge = v0.slice();
  huge[3] = 1e151;
  const cases = [
    [() => antcd.deformSweep(m, Array.from(v0), v1), /^deformSweep: a0 must be a Float64Array/],
    [() => antcd.deformSweep(m, v0, new Float32Array(v1)), /^deformSweep: a1 must be a Float64Array/],
    [() => antcd.deformSweep(m, v0, v1.subarray(3)), /^deformSweep: a1 has 15 numbers, model 'crossing' has 6 vertices \(18\)/],
    [() => antcd.deformSweep(m, v0, nan), /^deformSweep: a1\[4\] = nan is not finite/i],
    [() => antcd.deformSweep(m, huge, v1), /^deformSweep: a0\[3\] = 1e\+?151 is not finite with \|x\| <= 1e150/],
    [() => antcd.deformSweep(m, v0, v1, { minSeparation: -1 }), /^deformSweep: minSeparation must be a finite number >= 0/],
    [() => antcd.deformSweep(m, v0, v1, { timeTolerance: 0 }), /^deformSweep: timeTolerance must be a finite number > 0/],
    [() => antcd.deformSweep(m, v0, v1, { timeTolerance: Infinity }), /^deformSweep: timeTolerance/],
    [() => antcd.deformSweep(m, v0, v1, { posePathTolerance: NaN }), /^deformSweep: posePathTolerance must be a number/],
    [() => antcd.deformSweep(m, v0, v1, 'fast'), /^deformSweep: options must be an object/],
    [() => antcd.deformSweep(m, v0, v1, b, v0.slice(0, 9)), /^deformSweep: b1 must be a Float64Array/],
    [() => antcd.deformSweep(m, v0, v1, b, I, v1.slice(0, 9)), /^deformSweep: b0 and b1 must both be poses/],
    [() => antcd.deformSweep(m, v0, v1, b, v0, v1), /^deformSweep: b0 has 18 numbers, model 'floor' has 3 vertices/],
    [() => antcd.deformSweep(m, v0, v1, b, I, [2, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]), /^deformSweep: poseB1 /],
    [() => antcd.deformSweep('model', v0, v1), /^deformSweep: a must be a live antcd Model/],
    [() => antcd.deformSweep(m, v0, v1, null, v0, v1), /^deformSweep: the 4th argument must be a Model/],
    [() => antcd.collisionFreeStep(m, v0, v1), /^collisionFreeStep: minSeparation is required/],
    [() => antcd.collisionFreeStep(m, v0, v1.subarray(1), 0), /^collisionFreeStep: v1 has 17 numbers/],
    [() => antcd.collisionFreeStep(m, v0, nan, 0), /^collisionFreeStep: v1\[4\]/],
    [() => antcd.collisionFreeStep(m, v0, v1, -0.5), /^collisionFreeStep: minSeparation must be a finite number >= 0/],
  ];
  for (const [call, message] of cases) assert.throws(call, (e) => e instanceof Error && message.test(e.message), String(message));
  b.delete();
  assert.throws(() => antcd.deformSweep(m, v0, v1, b, v0.slice(0, 9), v1.slice(0, 9)), /^Error: deformSweep: b must be a live antcd Model \(it was deleted\)/);
  // Still answering as before.
  assert.deepEqual(antcd.deformSweep(m, v0, v1, { allPairs: true }), before);
  m.delete();
});

test('a rigid model passing through at huge translations: a hit or an Error, never a miss', () => {
  // The mover's vertex 0 at (0.2, 0.2, 0) on the floor's path from x = -far to x = +far.
  const still = new Float64Array(MOVER);
  for (let k = 2; k < 9; k += 3) still[k] -= 1;
  const a = new antcd.Model(still, [0, 1, 2]);
  const b = new antcd.Model(new Float64Array(FLOOR), [0, 1, 2]);
  for (const far of [1e140, 1e155, 1e300]) {
    let r;
    try {
      r = antcd.deformSweep(a, still, still, b, at(-far), at(far));
    } catch (e) {
      assert.match(e.message, /^deformSweep: .*pose_b/);
      continue;
    }
    assert.ok(r.hit && r.toi <= 0.5, `a miss at +-${far}: ${JSON.stringify(r)}`);
  }
  a.delete();
  b.delete();
});
