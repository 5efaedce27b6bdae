// Continuous motion of a World with deforming objects from JS (issue 37): World.sweepMotion
// against dense sub-stepping (collides() and selfIntersections() / selfProximity() on models
// built from the interpolated vertices at 300 times: no missed pair, toi never after the first
// step in contact and within a step of it), each pair's answer against sweep() / deformSweep()
// of the same motion, setMotionContinuous applying it, and bad input refused with the World
// unchanged.
import assert from 'node:assert/strict';
import { test } from 'node:test';

import { antcd, posed, sheet, turnZ } from './helpers.mjs';

const STEPS = 300;
const lerp = (a, b, t) => a.map((x, k) => (1 - t) * x + t * b[k]);

// The scene: each object { name, model, indices, rest (model-frame vertices at t = 0), end
// (at t = 1, deforming objects), angle0/1 and t0/t1 (a turn about z and a translation at both
// ends), self }.
function scene() {
  const cloth = sheet(11, 11, (u, v) => [2 * u - 1, 2 * v - 1, 1]);
  const sag = cloth.positions.map((x, k) => {
    if (k % 3 !== 2) return x;
    const [px, py] = [cloth.positions[k - 2], cloth.positions[k - 1]];
    return x - 1.2 * (1 - (px * px + py * py) / 2);
  });
  // The strip of deform.test.mjs: flat, then bent through itself (t^2 - 1, t^3 - t).
  const flat = sheet(15, 4, (u, v) => [-1.3 + 2.55 * u, v, 0]);
  const fold = flat.positions.map((x, k) => {
    const t = flat.positions[k - (k % 3)];
    return [t * t - 1, flat.positions[k - (k % 3) + 1], t * t * t - t][k % 3];
  });
  const quad = sheet(2, 2, (u, v) => [2 * u - 1, 2 * v - 1, 0]);
  const far = sheet(5, 5, (u, v) => [u, v, 0]);
  const box = antcd.Model.box(0.3, 0.3, 0.3);
  const boxMesh = box.mesh();
  const objects = [
    // Sags onto the box below, which turns by 60 degrees: a deforming-rigid pair (Deform), at
    // about t = 0.583; its own self pair never comes.
    { name: 'cloth', mesh: cloth, end: sag, self: true },
    { name: 'box', mesh: boxMesh, model: box, angle1: Math.PI / 3 },
    // Folds through itself while moving and turning: a self pair (Deform).
    { name: 'fold', mesh: flat, end: fold, self: true, t0: [10, 0, 0], t1: [10, 0.5, 0], angle0: 0.4, angle1: 0.7 },
    // Two rigid boxes, one turning a quarter turn onto the other: RigidSweep.
    { name: 'boxA', mesh: boxMesh, model: box, t0: [0, 5, 0], t1: [0, 7, 0], angle1: Math.PI / 2 },
    { name: 'boxB', mesh: boxMesh, model: box, t0: [0, 6.5, 0] },
    // A quad through a box at t = 0 (crossing edges, no vertex inside): StartContact.
    { name: 'quad', mesh: quad, end: quad.positions.map((x, k) => x + (k % 3 === 2 ? 0.05 : 0)), t0: [20, 0, 0] },
    { name: 'boxC', mesh: boxMesh, model: box, t0: [20, 0, 0] },
    // Deforms far from everything: no pair.
    { name: 'far', mesh: far, end: far.positions.map((x, k) => x * 1.5 + (k % 3 === 2 ? 0.3 : 0)), t0: [-20, 0, 0], self: true },
  ];
  for (const o of objects) {
    o.model ??= new antcd.Model(o.mesh.positions, o.mesh.indices, { name: o.name });
    o.t0 ??= [0, 0, 0];
    o.angle0 ??= 0;
    o.moves = o.angle1 !== undefined || o.t1 !== undefined || o.end !== undefined;
    o.t1 ??= o.t0;
    o.angle1 ??= o.angle0;
    o.pose0 = turnZ(o.angle0, o.t0);
    o.pose1 = turnZ(o.angle1, o.t1);
    if (o.end) {
      o.world0 = posed(o.pose0, o.mesh.positions);
      o.world1 = posed(o.pose1, o.end);
    }
  }
  return { objects, box };
}

function build(objects, minSeparation) {
  const world = new antcd.World();
  for (const o of objects) o.handle = world.add(o.model, o.pose0, { name: o.name, selfCollision: Boolean(o.self) });
  const moving = objects.filter((o) => o.moves);
  const args = [moving.map((o) => o.handle), moving.map((o) => o.pose1),
    objects.filter((o) => o.end).map((o) => ({ handle: o.handle, positions: o.end })), { minSeparation }];
  return { world, args };
}

// The first step (as a time) at which each pair is in contact (within minSeparation), by
// collides() / selfIntersections() / selfProximity() on models of the interpolated state.
function firstContacts(objects, minSeparation) {
  const first = new Map();
  for (let s = 0; s <= STEPS; ++s) {
    const t = s / STEPS;
    const state = objects.map((o) => {
      if (!o.end) {
        const pose = turnZ(o.angle0 + (o.angle1 - o.angle0) * t, lerp(o.t0, o.t1, t));
        return { model: o.model, pose, own: false };
      }
      const model = new antcd.Model(lerp(o.world0, o.world1, t), o.mesh.indices);
      return { model, pose: turnZ(0), own: true };
    });
    for (let i = 0; i < objects.length; ++i) {
      const key = (j) => `${objects[i].handle},${objects[j].handle}`;
      if (objects[i].self && !first.has(key(i))) {
        const m = state[i].model;
        const close = minSeparation > 0 ? antcd.selfProximity(m, minSeparation) : null;
        const near = close !== null && close.vertexTrianglePairs.length + close.edgeEdgePairs.length > 0;
        if (near || antcd.selfIntersections(m, { firstOnly: true }).intersecting) first.set(key(i), t);
      }
      for (let j = i + 1; j < objects.length; ++j) {
        if (first.has(key(j))) continue;
        if (antcd.collides(state[i].model, state[i].pose, state[j].model, state[j].pose, { delta: minSeparation })) first.set(key(j), t);
      }
    }
    for (const x of state) if (x.own) x.model.delete();
  }
  return first;
}

for (const minSeparation of [0, 0.05]) {
  test(`World.sweepMotion against dense sub-stepping, minSeparation ${minSeparation}`, () => {
    const { objects, box } = scene();
    const { world, args } = build(objects, minSeparation);
    const by = Object.fromEntries(objects.map((o) => [o.name, o]));
    const before = world.collideAll({ allContacts: true });
    const pairs = world.sweepMotion(...args);
    assert.deepEqual(world.sweepMotion(...args), pairs, 'a const query: the same answer again');
    assert.deepEqual(world.collideAll({ allContacts: true }), before, 'the World unchanged');
    const got = new Map(pairs.map((p) => [`${p.a},${p.b}`, p]));
    const first = firstContacts(objects, minSeparation);
    const names = (key) => key.split(',').map((h) => objects.find((o) => String(o.handle) === h).name).join('-');
    assert.deepEqual([...got.keys()].map(names), ['cloth-box', 'fold-fold', 'boxA-boxB', 'quad-boxC']);
    assert.deepEqual([...got.keys()].sort(), [...first.keys()].sort(), 'the pairs the sub-steps find in contact');
    for (const [key, t] of first) {
      const p = got.get(key);
      assert.ok(p.toi <= t, `${names(key)}: toi ${p.toi} after the first step in contact ${t}`);
      // Within a step of it too, unless a primitive pair ran out of its budget (a conservative
      // stop: the fold's near-parallel edges with minSeparation 0.05 stop at 0.125, 0.327 here).
      if (!p.primitive?.budgetExhausted) {
        assert.ok(p.toi >= t - 1 / STEPS - 0.01, `${names(key)}: toi ${p.toi} well before the first step in contact ${t}`);
      }
      assert.ok(p.a <= p.b && p.point.length === 3);
    }
    const pk = (x, y) => got.get(`${by[x].handle},${by[y].handle}`);
    // cloth-box: deformSweep of the cloth's world vertices against the box's two poses.
    const cb = pk('cloth', 'box');
    const ds = antcd.deformSweep(by.cloth.model, by.cloth.world0, by.cloth.world1, box, by.box.pose0, by.box.pose1, { minSeparation });
    assert.deepEqual([cb.kind, cb.toi, cb.toleranceDecided, cb.primitive, cb.triangles, cb.sweep], ['deform', ds.toi, ds.toleranceDecided, ds.pair, null, null]);
    assert.ok(cb.toi > 0.5 && cb.toi < 0.6, `cloth-box toi ${cb.toi}`);
    if (cb.primitive.kind === 'vertexFace' && cb.primitive.vertexInFirst) {
      const v = cb.primitive.indices[0];
      const at = lerp(by.cloth.world0.subarray(3 * v, 3 * v + 3), by.cloth.world1.subarray(3 * v, 3 * v + 3), cb.toi);
      at.forEach((x, k) => assert.ok(Math.abs(x - cb.point[k]) < 1e-12, `point ${cb.point} vs ${at}`));
    }
    // fold's self pair: deformSweep of its world vertices.
    const ff = pk('fold', 'fold');
    const fs = antcd.deformSweep(by.fold.model, by.fold.world0, by.fold.world1, { minSeparation });
    assert.deepEqual([ff.kind, ff.toi, ff.primitive], ['deform', fs.toi, fs.pair]);
    // boxA-boxB: exactly sweep()'s answer.
    const ab = pk('boxA', 'boxB');
    const sw = antcd.sweep(box, by.boxA.pose0, by.boxA.pose1, box, by.boxB.pose0, by.boxB.pose0, { minSeparation });
    assert.deepEqual([ab.kind, ab.toi, ab.sweep, ab.primitive, ab.triangles], ['rigidSweep', sw.toi, sw, null, null]);
    assert.deepEqual(Array.from(ab.point), Array.from(sw.contact.subarray(2, 5)));
    // quad-boxC: in contact at t = 0, a crossing triangle pair.
    const qb = pk('quad', 'boxC');
    assert.deepEqual([qb.kind, qb.toi, qb.toleranceDecided, qb.primitive, qb.sweep], ['startContact', 0, false, null, null]);
    const c = antcd.collide(by.quad.model, by.quad.pose0, box, by.boxC.pose0, { allContacts: true, delta: minSeparation });
    const crossing = [];
    for (let k = 0; k < c.contacts.length; k += antcd.CONTACT_STRIDE) crossing.push(`${c.contacts[k]},${c.contacts[k + 1]}`);
    assert.ok(crossing.includes(qb.triangles.join(',')), `${qb.triangles} in ${crossing}`);

    // setMotionContinuous: the same answer, then the World holds the end state.
    assert.deepEqual(world.setMotionContinuous(...args), pairs);
    const now = world.collideAll();
    const inContact = [];
    for (let k = 0; k < now.pairs.length; k += 2) inContact.push(names(`${now.pairs[k]},${now.pairs[k + 1]}`));
    const atEnd = [];
    for (const [i, o] of objects.entries()) {
      const m = o.end ? new antcd.Model(o.end, o.mesh.indices) : o.model;
      if (o.self && antcd.selfIntersections(m).intersecting) atEnd.push(`${o.name}-${o.name}`);
      for (const q of objects.slice(i + 1)) {
        const mq = q.end ? new antcd.Model(q.end, q.mesh.indices) : q.model;
        if (antcd.collides(m, o.pose1, mq, q.pose1)) atEnd.push(`${o.name}-${q.name}`);
        if (q.end) mq.delete();
      }
      if (o.end) m.delete();
    }
    assert.deepEqual(inContact, atEnd);
    assert.ok(atEnd.includes('cloth-box') && atEnd.includes('fold-fold'), String(atEnd));
    // No motion now: every pair in contact has toi 0.
    const still = world.sweepMotion([], [], []);
    for (const name of atEnd) assert.equal(still.find((p) => names(`${p.a},${p.b}`) === name)?.toi, 0, name);
    world.delete();
    for (const o of objects) if (o.model !== box) o.model.delete();
    box.delete();
  });
}

test('World.sweepMotion and setMotionContinuous: bad input throws an Error naming it, the World unchanged', () => {
  const { objects, box } = scene();
  const { world, args } = build(objects, 0);
  const [cloth, boxH] = [objects[0].handle, objects[1].handle];
  const end = objects[0].end;
  const gone = world.add(box, turnZ(0, [50, 0, 0]));
  world.remove(gone);
  const expected = world.sweepMotion(...args);
  const state = world.collideAll({ allContacts: true });
  const I = turnZ(0);
  const nan = end.slice();
  nan[10] = NaN;
  const huge = end.slice();
  huge[4] = 1e151;
  const cases = [
    [['cloth', [], []], /handles must be an array of object handles, got string cloth$/],
    [[[cloth], [], []], /: 1 handles but 0 poses$/],
    [[[cloth], new Float64Array(16), []], /: poses must be an array of poses \(16 numbers each\)/],
    [[[cloth], [[1, 2]], []], /: poses\[0\] must be 16 numbers \(a column-major 4x4 matrix\), got an array of length 2$/],
    [[[cloth], [I.map((x, k) => (k === 0 ? 2 : x))], []], /: poses\[0\] is not a rigid motion/],
    [[[cloth], [turnZ(0, [1e200, 0, 0])], []], /: poses\[0\] translation is beyond/],
    [[['a'], [I], []], /: handles\[0\] must be an object handle \(a number\), got string a$/],
    [[[0.5], [I], []], /: handles\[0\] 0\.5 is not an object handle$/],
    [[[gone], [I], []], /: handles\[0\] \(slot \d+, generation 0\) is not an object of this world \(removed, or never added\)$/],
    [[[cloth, boxH, cloth], [I, I, I], []], /: handles\[2\] repeats handles\[0\]/],
    [[[], [], 'end'], /: vertexMotions must be an array of \{ handle, positions \}, got string end$/],
    [[[], [], [null]], /: vertexMotions\[0\] must be \{ handle, positions \}, got null$/],
    [[[], [], [{ positions: end }]], /: vertexMotions\[0\]\.handle must be an object handle \(a number\), got undefined/],
    [[[], [], [{ handle: cloth, positions: new Int32Array(end.length) }]], /: vertexMotions\[0\]\.positions must be a Float32Array, Float64Array or array of numbers, got a Int32Array/],
    [[[], [], [{ handle: cloth, positions: end.subarray(2) }]], /: vertexMotions\[0\]\.positions has \d+ numbers, not a multiple of 3$/],
    [[[], [], [{ handle: cloth, positions: end.subarray(3) }]], /: vertexMotions\[0\]\.positions of object 'cloth' \(slot 0, generation 0\): got 120 vertices, the mesh has 121$/],
    [[[], [], [{ handle: cloth, positions: nan }]], /: vertexMotions\[0\]\.positions of object 'cloth' .*: vertex 3 is not finite$/],
    [[[], [], [{ handle: cloth, positions: huge }]], /: vertexMotions\[0\]\.positions of object 'cloth' .*: vertex 1's world position at t = 1 exceeds/],
    [[[], [], [{ handle: cloth, positions: end }, { handle: cloth, positions: end }]], /: vertexMotions\[1\]\.handle repeats vertexMotions\[0\]\.handle/],
    [[[], [], [], { minSeparation: -1 }], /: minSeparation must be finite and >= 0, got -1$/],
    [[[], [], [], { minSeparation: 'near' }], /: minSeparation must be a number, got string near$/],
    [[[], [], [], { timeTolerance: 0 }], /: timeTolerance must be /],
    [[[], [], [], { maxIterations: 0 }], /: maxIterations 0 is not an integer in \[1, 2\^32\)$/],
    [[[], [], [], 'fast'], /: options must be an object$/],
  ];
  for (const fn of ['sweepMotion', 'setMotionContinuous']) {
    for (const [call, message] of cases) {
      assert.throws(() => world[fn](...call), (e) => e instanceof Error && e.message.startsWith(`World.${fn}: `) &&
        message.test(e.message) && !e.message.includes('\n'), `${fn} ${message}`);
    }
    assert.deepEqual(world.collideAll({ allContacts: true }), state, `${fn}: the World unchanged`);
    assert.deepEqual(world.sweepMotion(...args), expected, `${fn}: the same motion, the same answer`);
  }
  // Typed arrays of handles and Float32Array / number[] positions are accepted.
  const f32 = world.sweepMotion(Float64Array.from(args[0]), args[1], args[2].map((m) => ({ handle: m.handle, positions: Float32Array.from(m.positions) })));
  assert.equal(f32.length, expected.length);
  assert.deepEqual(world.sweepMotion(args[0], args[1], args[2].map((m) => ({ handle: m.handle, positions: Array.from(m.positions) }))), expected);
  world.delete();
  assert.throws(() => world.sweepMotion([], [], []), /^Error: World\.sweepMotion: the World was deleted$/);
  for (const o of objects) if (o.model !== box) o.model.delete();
  box.delete();
});
