// WebAssembly memory exhausted (issue 41): with models kept until memory runs out, building one
// more threw nothing and wrote its positions over address 0 (the allocator returned 0), then a
// later call trapped or hung. Now the call throws an Error saying so, and the module keeps
// answering: the queries before and after agree, and once models are deleted it builds again.
// Also World.setVertices and the continuous motion of a deforming object (issues 36, 37).
import assert from 'node:assert/strict';
import { test } from 'node:test';

import createAntcd from '../index.mjs';

const at = (x, y = 0, z = 0) => [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, x, y, z, 1];

test('out of WebAssembly memory: an Error, then the module answers again', { timeout: 240000 }, async () => {
  const antcd = await createAntcd();
  const box = antcd.Model.box(0.5, 0.4, 0.3, 2);
  const ball = antcd.Model.sphere(0.45, 24, 12);
  const query = () => {
    const c = antcd.collide(box, at(0.8, 0.1), ball, at(0, 0, 0.1), { allContacts: true });
    const d = antcd.distance(box, at(1.2), ball, at(0, 0.2));
    return { colliding: c.colliding, contacts: Array.from(c.contacts), distance: d.distance };
  };
  const before = query();
  // 96 MiB of positions per model (4 Mi vertices, one triangle): about twenty fill the 2 GiB.
  const positions = new Float64Array(3 * 4 * 1024 * 1024);
  for (let k = 0; k < positions.length; ++k) positions[k] = k % 7;
  const kept = [];
  let error = null;
  // A World holding the second big model (added while memory is not yet full) as a deforming
  // object: its setVertices and continuous motion need copies of its vertices.
  const held = new antcd.World();
  let big = -1;
  for (let k = 0; k < 64 && error === null; ++k) {
    try {
      kept.push(new antcd.Model(positions, [0, 1, 2], { name: `big ${k}` }));
      if (k === 1) {
        held.add(ball, at(0, 0, 0.1));
        big = held.add(kept[1], at(0.5), { name: 'big', selfCollision: true });
      }
    } catch (e) {
      error = e;
    }
  }
  const worldQuery = () => JSON.stringify([held.collideAll({ allContacts: true }), held.sweepMotion([big], [at(0.6)], [])]);
  const worldBefore = worldQuery();
  assert.ok(error instanceof Error, `no Error after ${kept.length} models: ${error}`);
  // Either the C++ side (the mesh's copy) or the JS side (the positions' buffer) ran out.
  assert.match(error.message, /^Model( big \d+)?: out of WebAssembly memory/);
  assert.ok(kept.length >= 4, `only ${kept.length} models fit`);
  // Less than two such buffers are left now (the last model needed two), so positions twice as
  // large cannot get a buffer: the allocator returns 0, the case that wrote over address 0.
  const twice = new Float64Array(2 * positions.length);
  twice.set(positions);
  assert.throws(() => new antcd.Model(twice, [0, 1, 2], { name: 'twice' }),
    (e) => e instanceof Error && /^Model twice: out of WebAssembly memory \(positions: 201326592 bytes/.test(e.message), 'twice');
  // Still answering, memory still full: the same answers, and the kept models are intact.
  assert.deepEqual(query(), before);
  assert.equal(kept[0].vertexCount, 4 * 1024 * 1024);
  assert.equal(kept[kept.length - 1].name, `big ${kept.length - 1}`);
  // setVertices (a positions buffer, then the C++ copy) and the self queries with memory full:
  // an answer or an out-of-memory Error, and the module answers as before.
  const calls = {
    setVertices: () => kept[0].setVertices(positions),
    selfIntersections: () => antcd.selfIntersections(kept[0]),
    selfProximity: () => antcd.selfProximity(box, 0.01),
    deformSweep: () => antcd.deformSweep(box, box.mesh().positions, box.mesh().positions),
    collisionFreeStep: () => antcd.collisionFreeStep(box, box.mesh().positions, box.mesh().positions, 0.01),
  };
  for (const [name, call] of Object.entries(calls)) {
    try {
      call();
    } catch (e) {
      assert.ok(e instanceof Error && /out of WebAssembly memory/.test(e.message), `${name}: ${e}`);
    }
  }
  // The deforming sweep of a kept model needs two more position buffers of its size (then the
  // C++ copies): the allocation is refused with an Error, nothing written over address 0.
  assert.throws(() => antcd.deformSweep(kept[0], positions, positions),
    (e) => e instanceof Error && /^deformSweep: out of WebAssembly memory/.test(e.message), 'deformSweep');
  assert.deepEqual(query(), before);
  assert.equal(kept[0].vertexCount, 4 * 1024 * 1024);
  // World.setVertices of the big object needs the positions' buffer, their C++ copy and the
  // World's own copy of the Model; a continuous motion deforming it, its buffer and copies: less
  // than two of them are left. An Error each, and the World answers as before.
  const motion = [[], [], [{ handle: big, positions }]];
  for (const [fn, call] of [['setVertices', () => held.setVertices(big, positions)],
    ['sweepMotion', () => held.sweepMotion(...motion)], ['setMotionContinuous', () => held.setMotionContinuous(...motion)]]) {
    assert.throws(call, (e) => e instanceof Error && new RegExp(`^World\\.${fn}: out of WebAssembly memory`).test(e.message), fn);
    assert.equal(worldQuery(), worldBefore, `World.${fn}: the World answers as before`);
  }
  held.delete();
  assert.deepEqual(query(), before);
  // A World can be made (or is refused with an Error), and used.
  let world = null;
  try {
    world = new antcd.World();
  } catch (e) {
    assert.ok(e instanceof Error && /out of WebAssembly memory/.test(e.message), String(e));
  }
  if (world !== null) {
    world.add(box, at(0.8, 0.1));
    world.add(ball, at(0, 0, 0.1));
    assert.equal(world.collideAll().pairs.length, 2);
    world.delete();
  }
  // Room again once the models are deleted: the next one builds.
  for (const m of kept) m.delete();
  const again = new antcd.Model(positions, [0, 1, 2], { name: 'again' });
  assert.equal(again.triangleCount, 1);
  again.delete();
  assert.deepEqual(query(), before);
});
