// Deforming objects of a World from JS (issue 36): World.setVertices (copy of the Model on the
// first call, the Model given to add() unchanged), selfCollision's self pairs in collideAll
// against selfIntersections of a model built from the moved mesh, the deformed object's contacts
// against collide() and the native CLI, and bad input refused with the World unchanged.
import assert from 'node:assert/strict';
import { test } from 'node:test';

import { antcd, cli, native, pairKeys, pose, ROTATIONS, sheet, writeObj } from './helpers.mjs';

const I = pose([0, 0, 0]).matrix;

// A strip whose cross-section (t^2 - 1, t^3 - t), t in [-1.3, 1.25], passes through itself;
// folded = false: the same grid flat in z = 0.
function alpha(folded) {
  return sheet(23, 5, (u, v) => {
    const t = -1.3 + 2.55 * u;
    return folded ? [t * t - 1, v, t * t * t - t] : [t, v, 0];
  });
}

// collideAll's answer with one entry per pair: "a,b" -> { contacts (triangle pair keys), self
// (Uint32Array of triangle pairs) }.
function byPair(r) {
  const pairs = new Map();
  let c = 0;
  let s = 0;
  for (let k = 0; k < r.contactCounts.length; ++k) {
    const contacts = r.contacts.subarray(antcd.CONTACT_STRIDE * c, antcd.CONTACT_STRIDE * (c + r.contactCounts[k]));
    const self = r.selfPairs.subarray(2 * s, 2 * (s + r.selfPairCounts[k]));
    pairs.set(`${r.pairs[2 * k]},${r.pairs[2 * k + 1]}`, { contacts: pairKeys(contacts), self: Array.from(self) });
    c += r.contactCounts[k];
    s += r.selfPairCounts[k];
  }
  assert.equal(c * antcd.CONTACT_STRIDE, r.contacts.length);
  assert.equal(2 * s, r.selfPairs.length);
  return pairs;
}

test('World.setVertices with selfCollision: self pairs as selfIntersections, contacts as collide and native', () => {
  const flat = alpha(false);
  const folded = alpha(true);
  const model = new antcd.Model(flat.positions, flat.indices, { name: 'strip' });
  const fresh = new antcd.Model(folded.positions, folded.indices, { name: 'folded' });
  const ball = antcd.Model.sphere(0.2, 12, 6);
  // The strip turned and moved (self pairs do not depend on the pose); the ball touches the
  // folded strip 0.1 off its surface at t = 1.2 (0.47 from the flat one); a second object shares
  // the strip's Model, far away.
  const P = pose([2, 1, 0.5], ROTATIONS[3]);
  const B = pose([2.4695, 1.521, 1]);
  const world = new antcd.World();
  const h = world.add(model, P.matrix, { name: 'cloth', selfCollision: true });
  const hBall = world.add(ball, B.matrix, { name: 'ball' });
  const hPlain = world.add(model, pose([40, 0, 0]).matrix, { name: 'plain', selfCollision: true });
  assert.equal(world.collideAll({ allContacts: true }).pairs.length, 0, 'flat: nothing collides');

  world.setVertices(h, folded.positions);
  const expected = Array.from(antcd.selfIntersections(fresh).pairs);
  assert.ok(expected.length > 10, `${expected.length / 2} self pairs`);
  const all = byPair(world.collideAll({ allContacts: true }));
  assert.deepEqual([...all.keys()], [`${h},${h}`, `${h},${hBall}`]);
  assert.deepEqual(all.get(`${h},${h}`), { contacts: [], self: expected });
  const direct = antcd.collide(fresh, P.matrix, ball, B.matrix, { allContacts: true });
  assert.ok(direct.colliding);
  assert.deepEqual(all.get(`${h},${hBall}`), { contacts: pairKeys(direct.contacts), self: [] });
  if (cli !== null) {
    const ref = native('collide', writeObj('world-folded.obj', folded.positions, folded.indices), P,
      writeObj('world-ball.obj', ball.mesh().positions, ball.mesh().indices), B, ['--all']);
    assert.deepEqual(all.get(`${h},${hBall}`).contacts, ref.contacts.map((c) => `${c.triangle_a},${c.triangle_b}`).sort());
  }
  // Boolean query: one self pair of them; maxContacts: the first ones.
  const one = byPair(world.collideAll()).get(`${h},${h}`).self;
  assert.equal(one.length, 2);
  assert.ok(expected.some((_, k) => k % 2 === 0 && expected[k] === one[0] && expected[k + 1] === one[1]));
  assert.deepEqual(byPair(world.collideAll({ allContacts: true, maxContacts: 3 })).get(`${h},${h}`).self, expected.slice(0, 6));
  // The Model given to add() is unchanged (the World copied it), and so is the object sharing it.
  assert.deepEqual(model.mesh().positions, flat.positions);
  assert.equal(antcd.selfIntersections(model).intersecting, false);
  // Float32Array and number[] positions; back to flat, folded again.
  world.setVertices(h, Float32Array.from(flat.positions));
  assert.equal(world.collideAll({ allContacts: true }).pairs.length, 0);
  world.setVertices(h, Array.from(folded.positions));
  assert.deepEqual(byPair(world.collideAll({ allContacts: true })), all);
  // A rigid object of the folded Model: its self pair with selfCollision, none without.
  const hRigid = world.add(fresh, pose([0, -40, 0]).matrix, { name: 'rigid fold', selfCollision: true });
  world.add(fresh, pose([0, -80, 0]).matrix, { name: 'unchecked fold' });
  const withRigid = byPair(world.collideAll({ allContacts: true }));
  assert.deepEqual([...withRigid.keys()], [...all.keys(), `${hRigid},${hRigid}`]);
  assert.deepEqual(withRigid.get(`${hRigid},${hRigid}`), { contacts: [], self: expected });
  world.remove(hRigid);
  // The strip's Model is still held by 'plain': Model.setVertices refuses it; once 'plain' is
  // removed it is the JS side's alone again ('cloth' has its own copy), and the World is unmoved.
  assert.throws(() => model.setVertices(folded.positions), /^Error: Model\.setVertices: model 'strip' is held by a World/);
  world.remove(hPlain);
  model.setVertices(folded.positions);
  model.setVertices(flat.positions);
  assert.deepEqual(byPair(world.collideAll({ allContacts: true })), all);
  world.delete();
  for (const m of [model, fresh, ball]) m.delete();
});

test('World.setVertices and World.add: bad input throws an Error naming it, the World unchanged', () => {
  const box = antcd.Model.box(0.5, 0.5, 0.5);
  const needleAt = [0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 2, 0, 0, 3, 0, 0, 4];
  const needle = new antcd.Model(needleAt, [0, 1, 2, 3, 4, 5], { name: 'needle' });
  const world = new antcd.World();
  const h = world.add(box, I, { name: 'cloth', selfCollision: true });
  const hn = world.add(needle, pose([0.2, 0.2, 0]).matrix, { name: 'needle' });
  const gone = world.add(box, pose([9, 0, 0]).matrix);
  world.remove(gone);
  const before = box.mesh().positions;
  const n = before.length;
  const moved = before.map((v) => v * 1.5);
  const answer = () => world.collideAll({ allContacts: true });
  const expected = answer();
  assert.equal(expected.pairs.length, 2, 'box and needle touch');
  const gainsArea = needleAt.slice();
  gainsArea[15] = 1;
  const slot = '\\(slot \\d+, generation \\d+\\)';
  const cases = [
    [() => world.setVertices(h, before.subarray(3)), new RegExp(`^World\\.setVertices: positions of object 'cloth' ${slot}: got ${n / 3 - 1} vertices, the mesh has ${n / 3}$`)],
    [() => world.setVertices(h, before.subarray(1)), new RegExp(`^World\\.setVertices: positions has ${n - 1} numbers, not a multiple of 3$`)],
    [() => world.setVertices(h, moved.map((v, k) => (k === 7 ? NaN : v))), new RegExp(`^World\\.setVertices: positions of object 'cloth' ${slot}: vertex 2 is not finite$`)],
    [() => world.setVertices(h, Float32Array.from(moved, (v, k) => (k === 3 ? Infinity : v))), /^World\.setVertices: positions of object 'cloth' .*: vertex 1 is not finite$/],
    [() => world.setVertices(h, new Uint8Array(n)), /^World\.setVertices: positions must be a Float32Array, Float64Array or array of numbers, got a Uint8Array/],
    [() => world.setVertices(h), /^World\.setVertices: positions must be/],
    [() => world.setVertices('cloth', moved), /^World\.setVertices: handle must be an object handle \(a number\), got string cloth$/],
    [() => world.setVertices(0.5, moved), /^World\.setVertices: handle 0\.5 is not an object handle$/],
    [() => world.setVertices(gone, moved), /^World\.setVertices: handle \(slot 2, generation 0\) is not an object of this world \(removed, or never added\)$/],
    [() => world.setVertices(hn, gainsArea), /^World\.setVertices: positions of object 'needle' .*triangle 1 had zero area when the model was built/],
    [() => world.add(box, I, { rebuildAbove: -1 }), /^World\.add: rebuildAbove of the new object must be >= 0 \(or \+inf\), got -1$/],
    [() => world.add(box, I, { rebuildAbove: 'often' }), /^World\.add: rebuildAbove must be a number, got string often$/],
    [() => world.add(box, I, 'self'), /^World\.add: options must be an object$/],
    [() => world.add(box, [1, 2], { selfCollision: true }), /^World\.add: pose must be 16 numbers/],
  ];
  for (const [call, message] of cases) {
    assert.throws(call, (e) => e instanceof Error && message.test(e.message) && !e.message.includes('\n'), String(message));
    assert.deepEqual(answer(), expected, `unchanged after ${message}`);
  }
  assert.equal(world.size, 2);
  // A rebuildAbove object rebuilds past its bound and answers as before.
  const hr = world.add(box, pose([5, 0, 0]).matrix, { name: 'rebuilt', rebuildAbove: 1.01, selfCollision: true });
  world.setVertices(hr, moved);
  world.setVertices(hr, before);
  assert.deepEqual(answer(), expected);
  world.delete();
  assert.throws(() => world.setVertices(h, moved), /^Error: World\.setVertices: the World was deleted$/);
  box.delete();
  needle.delete();
});
