// Self-collision from JS: selfIntersections against the native CLI (`antcd self-intersect
// --json`), selfProximity against `antcd self-proximity --json`, Model.setVertices against a
// model built from the moved mesh, and the refusal of bad input with the model unchanged.
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { test } from 'node:test';

import { antcd, cli, sheet, writeObj } from './helpers.mjs';

const I = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];

// A strip whose cross-section (t^2 - 1, t^3 - t), t in [-1.3, 1.25], passes through itself;
// folded = false: the same grid flat in z = 0.
function alphaSheet(nx, ny, folded = true) {
  return sheet(nx, ny, (u, v) => {
    const t = -1.3 + 2.55 * u;
    return folded ? [t * t - 1, v, t * t * t - t] : [t, v, 0];
  });
}

function nativeJson(args) {
  return JSON.parse(execFileSync(cli, args, { encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] }));
}

test('selfIntersections equals the native CLI, with firstOnly one of its pairs', () => {
  const sheet = alphaSheet(23, 5);
  const path = writeObj('alpha.obj', sheet.positions, sheet.indices);
  const expected = nativeJson(['self-intersect', path, '--json']);
  const m = new antcd.Model(sheet.positions, sheet.indices, { name: 'alpha' });
  const r = antcd.selfIntersections(m);
  assert.ok(r.pairs instanceof Uint32Array);
  assert.ok(expected.count > 0 && r.intersecting);
  assert.deepEqual(Array.from(r.pairs), expected.pairs.flat());
  assert.deepEqual(Array.from(r.degenerateTriangles), expected.degenerate_triangles);
  assert.ok(r.stats.trianglePairs > 0 && Object.keys(r.stats).length === 7);
  const first = antcd.selfIntersections(m, { firstOnly: true });
  assert.equal(first.pairs.length, 2);
  assert.ok(expected.pairs.some(([i, j]) => i === first.pairs[0] && j === first.pairs[1]));
  const box = antcd.Model.box(0.5, 0.5, 0.5);
  const none = antcd.selfIntersections(box);
  assert.equal(none.intersecting, false);
  assert.equal(none.pairs.length, 0);
  box.delete();
  m.delete();
});

test('selfProximity equals the native CLI', () => {
  const sheet = alphaSheet(9, 3);
  const path = writeObj('alpha-small.obj', sheet.positions, sheet.indices);
  const expected = nativeJson(['self-proximity', path, '--delta', '0.35', '--json']);
  const m = new antcd.Model(sheet.positions, sheet.indices);
  const r = antcd.selfProximity(m, 0.35);
  assert.ok(expected.vertex_triangle.length > 0 && expected.edge_edge.length > 0);
  assert.equal(r.vertexTrianglePairs.length, 2 * expected.vertex_triangle.length);
  assert.equal(r.edgeEdgePairs.length, 2 * expected.edge_edge.length);
  // The CLI's loader numbers vertices in order of first use, so vertices are compared by their
  // coordinates (triangles keep the file's order), edge pairs by their closest points; numbers
  // within 1e-12 (WebAssembly's and the native build's last bits may differ).
  const vertexAt = (v) => Array.from(sheet.positions.subarray(3 * v, 3 * v + 3));
  const near = (x, y, what) => {
    assert.equal(x.length, y.length, what);
    x.forEach((v, k) => assert.ok(Math.abs(v - y[k]) <= 1e-12, `${what}: ${x} vs ${y}`));
  };
  const byKey = (rows) => rows.sort((p, q) => (p.key < q.key ? -1 : p.key > q.key ? 1 : 0));
  const mineVt = [];
  for (let k = 0; k < r.vertexTrianglePairs.length / 2; ++k) {
    const v = vertexAt(r.vertexTrianglePairs[2 * k]);
    mineVt.push({ key: `${v} ${r.vertexTrianglePairs[2 * k + 1]}`,
      numbers: [r.vertexTriangleDistances[k], ...r.vertexTrianglePoints.subarray(3 * k, 3 * k + 3)] });
  }
  const cliVt = expected.vertex_triangle.map((row) => ({ key: `${row.point_a} ${row.triangle}`, numbers: [row.distance, ...row.point_b] }));
  byKey(mineVt).forEach((row, k) => {
    assert.equal(row.key, byKey(cliVt)[k].key);
    near(row.numbers, cliVt[k].numbers, row.key);
  });
  const rounded = (xs) => xs.map((x) => x.toFixed(9)).join(',');
  const mineEe = [];
  for (let k = 0; k < r.edgeEdgePairs.length / 2; ++k) {
    const a = Array.from(r.edgeEdgePointsA.subarray(3 * k, 3 * k + 3));
    const b = Array.from(r.edgeEdgePointsB.subarray(3 * k, 3 * k + 3));
    mineEe.push({ key: `${rounded(a)} ${rounded(b)}`, numbers: [r.edgeEdgeDistances[k], ...a, ...b] });
  }
  const cliEe = expected.edge_edge.map((row) => ({ key: `${rounded(row.point_a)} ${rounded(row.point_b)}`,
    numbers: [row.distance, ...row.point_a, ...row.point_b] }));
  byKey(mineEe).forEach((row, k) => {
    assert.equal(row.key, byKey(cliEe)[k].key);
    near(row.numbers, cliEe[k].numbers, row.key);
  });
  for (const bad of [-1, NaN, Infinity]) {
    assert.throws(() => antcd.selfProximity(m, bad), (e) => e instanceof Error && /^selfProximity: .*delta/.test(e.message), String(bad));
  }
  assert.throws(() => antcd.selfProximity(m, '0.1'), /^Error: selfProximity: delta must be a number/);
  m.delete();
});

test('setVertices: queries answer as on a model built from the moved mesh', () => {
  const flat = alphaSheet(23, 5, false);
  const folded = alphaSheet(23, 5, true);
  const m = new antcd.Model(flat.positions, flat.indices, { name: 'sheet' });
  assert.equal(antcd.selfIntersections(m).pairs.length, 0);
  assert.equal(m.refitGrowth, 1);
  m.setVertices(folded.positions);
  const fresh = new antcd.Model(folded.positions, folded.indices);
  assert.deepEqual(Array.from(antcd.selfIntersections(m).pairs), Array.from(antcd.selfIntersections(fresh).pairs));
  assert.deepEqual(Array.from(m.mesh().positions), Array.from(folded.positions));
  const ball = antcd.Model.sphere(0.2, 12, 6);
  const at = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0.5, 0.1, 1];
  // The same contacts (records compared as a set: the two trees visit them in different orders).
  const records = (c) => {
    const rows = [];
    for (let k = 0; k < c.contacts.length; k += antcd.CONTACT_STRIDE) rows.push(String(Array.from(c.contacts.subarray(k, k + antcd.CONTACT_STRIDE))));
    return rows.sort();
  };
  const [mine, theirs] = [m, fresh].map((x) => antcd.collide(x, I, ball, at, { allContacts: true }));
  assert.ok(mine.colliding && theirs.colliding);
  assert.deepEqual(records(mine), records(theirs));
  assert.ok(antcd.collides(m, I, ball, at));
  m.setVertices(Float32Array.from(flat.positions));
  assert.equal(antcd.selfIntersections(m).pairs.length, 0);
  m.setVertices(Array.from(folded.positions));
  assert.ok(antcd.collides(m, I, ball, at));
  for (const x of [m, fresh, ball]) x.delete();
});

test('setVertices: bad input throws an Error naming it, and the model keeps its vertices', () => {
  const box = antcd.Model.box(0.5, 0.5, 0.5);
  const before = box.mesh().positions;
  const moved = before.map((v) => v + 0.25);
  const n = before.length;
  const cases = [
    [new Float64Array(n - 3), new RegExp(`^Model\\.setVertices: positions has ${n - 3} numbers, the model has ${n / 3} vertices \\(${n}\\)$`)],
    [[...moved, 0, 0, 0], new RegExp(`^Model\\.setVertices: positions has ${n + 3} numbers`)],
    [moved.map((v, k) => (k === 7 ? NaN : v)), /^Model\.setVertices: positions\[7\] = nan is not finite$/i],
    [moved.map((v, k) => (k === 23 ? Infinity : v)), /^Model\.setVertices: positions\[23\] = inf is not finite$/i],
    [new Uint8Array(24), /^Model\.setVertices: positions must be a Float32Array, Float64Array or array of numbers, got a Uint8Array/],
    ['abc', /^Model\.setVertices: positions must be/],
    [null, /^Model\.setVertices: positions must be/],
  ];
  for (const [arg, message] of cases) {
    assert.throws(() => box.setVertices(arg), (e) => e instanceof Error && message.test(e.message), String(message));
    assert.deepEqual(box.mesh().positions, before);
  }
  // Held by a World: refused until it is removed (the World's broad phase keeps its bounds).
  const world = new antcd.World();
  const h = world.add(box, I);
  assert.throws(() => box.setVertices(moved), /^Error: Model\.setVertices: model 'box' is held by a World/);
  assert.deepEqual(box.mesh().positions, before);
  world.remove(h);
  box.setVertices(moved);
  assert.deepEqual(box.mesh().positions, moved);
  world.delete();
  box.delete();
  assert.throws(() => box.setVertices(moved), /^Error: Model\.setVertices: this must be a live antcd Model \(it was deleted\)/);
  assert.throws(() => antcd.selfIntersections(box), /^Error: selfIntersections: model must be a live antcd Model/);
  assert.throws(() => antcd.selfIntersections({}), /^Error: selfIntersections: model must be a live antcd Model/);
});

test('setVertices refuses a triangle that had zero area and has an area now', () => {
  const positions = [0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 2, 0, 0, 3, 0, 0, 4];
  const m = new antcd.Model(positions, [0, 1, 2, 3, 4, 5], { name: 'needle' });
  const moved = positions.slice();
  moved[15] = 1;
  assert.throws(() => m.setVertices(moved), /^Error: Model\.setVertices: needle: refit: triangle 1 had zero area/);
  assert.deepEqual(Array.from(m.mesh().positions), positions);
  m.delete();
});
