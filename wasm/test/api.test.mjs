// The package's API on its own: World (add, setPose, collideAll, pairsWithin, raycast, remove)
// against the pairwise queries, sweeps and penetration depth against closed-form answers, and the
// refusal of bad input with one-line errors naming the problem.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { test } from 'node:test';

import createAntcd from '../index.mjs';
import { antcd, pose, rng, ROTATIONS } from './helpers.mjs';

const I = pose([0, 0, 0]).matrix;
const at = (x, y = 0, z = 0, r = ROTATIONS[0]) => pose([x, y, z], r).matrix;

test('World.collideAll and pairsWithin equal the pairwise queries, objects moved and removed', () => {
  const models = [antcd.Model.box(0.5, 0.4, 0.3, 2), antcd.Model.sphere(0.45, 24, 12), antcd.Model.torus(0.5, 0.15, 32, 12)];
  const world = new antcd.World();
  const random = rng(3);
  const objects = [];
  for (let k = 0; k < 24; ++k) {
    const m = models[k % models.length];
    const p = at(random() * 4, random() * 4, random() * 2, ROTATIONS[k % ROTATIONS.length]);
    objects.push({ m, p, h: world.add(m, p, { name: `o${k}` }) });
  }
  assert.equal(world.size, 24);
  for (let round = 0; round < 3; ++round) {
    if (round === 1) {
      for (const o of objects.filter((_, k) => k % 3 === 0)) {
        o.p = at(random() * 4, random() * 4, random() * 2);
        world.setPose(o.h, o.p);
      }
    }
    if (round === 2) {
      world.remove(objects[5].h);
      assert.throws(() => world.setPose(objects[5].h, I), /World.setPose: .*(removed|not|unknown|stale)/i);
      objects.splice(5, 1);
    }
    const expected = [];
    const within = [];
    for (let i = 0; i < objects.length; ++i) {
      for (let j = i + 1; j < objects.length; ++j) {
        const [a, b] = objects[i].h < objects[j].h ? [objects[i], objects[j]] : [objects[j], objects[i]];
        if (antcd.collide(a.m, a.p, b.m, b.p).colliding) expected.push(`${a.h},${b.h}`);
        if (antcd.distance(a.m, a.p, b.m, b.p).distance <= 0.2) within.push(`${a.h},${b.h}`);
      }
    }
    const got = world.collideAll();
    const pairs = [];
    for (let k = 0; k < got.pairs.length; k += 2) pairs.push(`${got.pairs[k]},${got.pairs[k + 1]}`);
    assert.deepEqual(pairs.sort(), expected.sort(), `round ${round}: colliding pairs`);
    assert.ok(expected.length > 0, 'some pairs collide');
    const w = world.pairsWithin(0.2);
    const wp = [];
    for (let k = 0; k < w.length; k += 2) wp.push(`${w[k]},${w[k + 1]}`);
    assert.deepEqual(wp.sort(), within.sort(), `round ${round}: pairs within 0.2`);
    const all = world.collideAll({ allContacts: true });
    assert.equal(all.contacts.length, antcd.CONTACT_STRIDE * all.contactCounts.reduce((s, n) => s + n, 0));
  }
  world.delete();
  for (const m of models) m.delete();
});

test('World.raycast: nearest face of a box, world frame', () => {
  const box = antcd.Model.box(1, 1, 1);
  const world = new antcd.World();
  const near = world.add(box, at(5, 0, 0));
  world.add(box, at(9, 0, 0));
  const hit = world.raycast([0, 0.25, 0.5], [1, 0, 0]);
  assert.equal(hit.object, near);
  assert.equal(hit.distance, 4);
  assert.deepEqual([...hit.point], [4, 0.25, 0.5]);
  assert.deepEqual([...hit.normal], [-1, 0, 0]);
  assert.equal(world.raycast([0, 0, 0], [0, 1, 0]), null);
  assert.equal(world.raycast([0, 0, 0], [1, 0, 0], 3.5), null);
  world.delete();
  box.delete();
});

test('sweep: time of impact of a box moving onto another, conservative and tight', () => {
  const box = antcd.Model.box(0.5, 0.5, 0.5);
  // A from x = -3 to x = 3 against B at rest at 0: the faces meet at x = -1, t = 2/6.
  const s = antcd.sweep(box, at(-3), at(3), box, I, I, { timeTolerance: 1e-9 });
  assert.ok(s.hit);
  assert.ok(s.toi <= 2 / 6 && s.toi > 2 / 6 - 1e-6, `toi ${s.toi}`);
  const miss = antcd.sweep(box, at(-3, 2), at(3, 2), box, I, I);
  assert.equal(miss.hit, false);
  box.delete();
});

test('penetration: exact depth of two overlapping convex boxes', () => {
  const box = antcd.Model.box(0.5, 0.5, 0.5);
  const p = antcd.penetration(box, at(0.9, 0.2), box, I);
  assert.ok(p.overlapping && p.exact);
  assert.ok(Math.abs(p.lower - 0.1) < 1e-12 && Math.abs(p.upper - 0.1) < 1e-12, `${p.lower} .. ${p.upper}`);
  assert.ok(Math.abs(p.direction[0] - 1) < 1e-12);
  const signed = antcd.distance(box, at(0.9, 0.2), box, I, { signed: true });
  assert.ok(Math.abs(signed.distance + 0.1) < 1e-12);
  box.delete();
});

test('contacts: world-frame points on both surfaces, normals on request', () => {
  const box = antcd.Model.box(0.5, 0.5, 0.5);
  const r = antcd.collide(box, at(0.95), box, I, { allContacts: true, contactNormals: true });
  assert.ok(r.colliding && r.contacts.length >= antcd.CONTACT_STRIDE);
  for (let k = 0; k < r.contacts.length; k += antcd.CONTACT_STRIDE) {
    const x = r.contacts[k + 2];
    assert.ok(x >= 0.45 - 1e-12 && x <= 0.5 + 1e-12, `contact x ${x}`);
    assert.equal(r.contacts[k + 5], 0);
    const n = Math.hypot(r.contacts[k + 6], r.contacts[k + 7], r.contacts[k + 8]);
    assert.ok(Math.abs(n - 1) < 1e-9);
  }
  assert.equal(antcd.collides(box, at(0.95), box, I), true);
  assert.equal(antcd.collides(box, at(1.05), box, I), false);
  assert.equal(antcd.collides(box, at(1.05), box, I, { delta: 0.06 }), true);
  const apart = antcd.collide(box, at(1.05), box, I);
  assert.deepEqual(apart, { colliding: false, contacts: new Float64Array(0) });
  assert.ok(antcd.collide(box, at(1.05), box, I, { delta: 0.06 }).colliding);
  box.delete();
});

test('bad input is refused with an Error naming the problem', () => {
  const box = antcd.Model.box(0.5, 0.5, 0.5);
  const cases = [
    [() => new antcd.Model(new Float32Array(7), [0, 1, 2]), /positions has 7 numbers, not a multiple of 3/],
    [() => new antcd.Model([0, 0, 0, 1, 0, 0, 0, 1, 0], [0, 1, 3]), /indices\[2\] = 3 is not a vertex index in \[0, 3\)/],
    [() => new antcd.Model([0, 0, 0, 1, 0, 0, 0, 1, 0], new Uint32Array([0, 1, 5])), /Model: mesh: triangle 0 references vertex 5/],
    [() => new antcd.Model([0, 0, 0, 1, NaN, 0, 0, 1, 0], [0, 1, 2]), /Model: .*(finite|NaN)/i],
    [() => new antcd.Model([0, 0, 0, 1, 0, 0, 2, 0, 0], [0, 1, 2]), /Model: .*area/i],
    [() => new antcd.Model('abc', [0, 1, 2]), /positions must be a Float32Array/],
    [() => antcd.Model.sphere(-1), /Model.sphere: .*radius/],
    [() => antcd.collide(box, [1, 2, 3], box, I), /collide: poseA must be 16 numbers/],
    [() => antcd.collide(box, I, box, at(0, 0, 0).map((v, k) => (k === 0 ? 2 : v))), /collide: poseB is not a rigid motion/],
    [() => antcd.collide(box, I, box, I.map((v, k) => (k === 13 ? NaN : v))), /collide: poseB is not finite/],
    [() => antcd.collide(box, I, box, I, { delta: -1 }), /collide: .*delta/],
    [() => antcd.collide(box, I, {}, I), /collide: b must be a live antcd Model/],
    [() => antcd.distance(box, I, box, I, { relTolerance: 1 }), /distance: .*rel/i],
    [() => antcd.sweep(box, I, I, box, I, I, { timeTolerance: 0 }), /sweep: .*time/i],
    [() => antcd.penetration(box, I, box, I, { shape: 'round' }), /penetration: shape must be/],
    [() => new antcd.World().setPose(12345, I), /World.setPose: .*/],
    [() => new antcd.World().add(box, I, { group: -1 }), /World.add: group/],
    [() => new antcd.World().pairsWithin(-1), /World.pairsWithin: .*/],
    [() => new antcd.World().raycast([0, 0, 0], [0, 0, 0]), /World.raycast: .*direction/],
  ];
  for (const [f, re] of cases) {
    assert.throws(f, (e) => {
      assert.ok(e instanceof Error);
      assert.match(e.message, re);
      assert.ok(!e.message.includes('\n'), `one line: ${e.message}`);
      return true;
    });
  }
  // A pose that passed its check is not checked again while it repeats (bindings.cpp); a changed
  // one is, a rejected one every time.
  const skew = at(0, 0, 0).map((v, k) => (k === 0 ? 1 + 1e-3 : v));
  assert.equal(antcd.collides(box, I, box, at(0.5)), true);
  assert.equal(antcd.collides(box, I, box, at(0.5)), true);
  assert.throws(() => antcd.collides(box, I, box, skew), /poseB is not a rigid motion/);
  assert.throws(() => antcd.collides(box, I, box, skew), /poseB is not a rigid motion/);
  assert.throws(() => antcd.collides(box, skew, box, I), /poseA is not a rigid motion/);
  assert.equal(antcd.collides(box, I.map((v) => (v === 0 ? -0 : v)), box, at(0.5)), true);
  assert.equal(antcd.collides(box, I, box, at(3)), false);
  const gone = antcd.Model.box(1, 1, 1);
  gone.delete();
  assert.throws(() => antcd.collide(gone, I, box, I), /collide: a must be a live antcd Model \(it was deleted\)/);
  // A model deleted in JS while a World holds it keeps working there.
  const world = new antcd.World();
  const held = antcd.Model.box(0.5, 0.5, 0.5);
  world.add(held, I);
  world.add(box, at(0.9));
  held.delete();
  assert.equal(world.collideAll().pairs.length, 2);
  world.delete();
  box.delete();
});

test('createAntcd uses the bytes given as wasmBinary (as the live page does)', async () => {
  const bytes = readFileSync(new URL('../dist/antcd_core.wasm', import.meta.url));
  const given = await createAntcd({ wasmBinary: bytes });
  const box = given.Model.box(0.5, 0.5, 0.5);
  assert.ok(given.collide(box, I, box, at(0.9)).colliding);
  box.delete();
  await assert.rejects(createAntcd({ wasmBinary: new Uint8Array([0, 97, 115, 109]) }));
});

test('sweep: translations beyond the coordinate range throw, within it the contact is found', () => {
  // Issue 41: a box passing through a box at +-1e155 answered hit false (motion bound inf).
  const box = antcd.Model.box(0.5, 0.5, 0.5);
  for (const s of [1e154, 1e155, 1e300, Number.MAX_VALUE / 2]) {
    assert.throws(() => antcd.sweep(box, at(-s), at(s), box, I, I),
      (e) => e instanceof Error && /^sweep: pose_a0 translation is beyond the continuous queries' coordinate range/.test(e.message),
      String(s));
  }
  assert.throws(() => antcd.sweep(box, I, I, box, I, I, { minSeparation: 1e300 }),
    (e) => e instanceof Error && /^sweep: min_separation is beyond/.test(e.message));
  const r = antcd.sweep(box, at(-1e100), at(1e100), box, I, I);
  assert.ok(r.hit && r.toi <= 0.5);
  box.delete();
});
