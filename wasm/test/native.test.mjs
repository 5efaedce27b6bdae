// The package answers as the native library does: collide (boolean and every contact) and
// distance on generated shapes and on Debian's assimp test models, at poses both sides hold
// exactly. Skipped without ANTCD_CLI (the ctest case wasm_node sets it).
import assert from 'node:assert/strict';
import { existsSync } from 'node:fs';
import { join } from 'node:path';
import { test } from 'node:test';

import { antcd, cli, native, packagedModels, pairKeys, pose, readObj, rng, ROTATIONS, writeObj } from './helpers.mjs';

function fromMesh(name, mesh) {
  let radius = 0;
  for (const x of mesh.positions) radius = Math.max(radius, Math.abs(x));
  return { model: new antcd.Model(mesh.positions, mesh.indices, { name }), file: writeObj(`${name}.obj`, mesh.positions, mesh.indices), radius };
}

// B placed at random translations within the reach of both models, A and B turned by the exact
// rotations.
function compare(a, b, seed, poses) {
  const scale = (a.radius + b.radius) / 2;
  const random = rng(seed);
  let colliding = 0;
  for (let k = 0; k < poses; ++k) {
    const pa = pose([0, 0, 0], ROTATIONS[k % ROTATIONS.length]);
    const t = [0, 1, 2].map(() => (random() - 0.5) * 2.2 * scale);
    const pb = pose(t, ROTATIONS[(k >> 2) % ROTATIONS.length]);
    const all = antcd.collide(a.model, pa.matrix, b.model, pb.matrix, { allContacts: true });
    const ref = native('collide', a.file, pa, b.file, pb, ['--all']);
    assert.equal(all.colliding, ref.colliding, `pose ${k}: verdict`);
    assert.deepEqual(pairKeys(all.contacts), ref.contacts.map((c) => `${c.triangle_a},${c.triangle_b}`).sort(), `pose ${k}: contact pairs`);
    const first = antcd.collide(a.model, pa.matrix, b.model, pb.matrix);
    assert.equal(first.colliding, ref.colliding, `pose ${k}: boolean verdict`);
    assert.equal(first.contacts.length, ref.colliding ? antcd.CONTACT_STRIDE : 0);
    assert.equal(antcd.collides(a.model, pa.matrix, b.model, pb.matrix), ref.colliding, `pose ${k}: collides`);
    const d = antcd.distance(a.model, pa.matrix, b.model, pb.matrix);
    const dref = native('distance', a.file, pa, b.file, pb);
    assert.equal(d.intersecting, dref.intersecting, `pose ${k}: intersecting`);
    assert.ok(Math.abs(d.distance - dref.distance) <= 1e-12 * scale, `pose ${k}: distance ${d.distance} vs ${dref.distance}`);
    if (all.colliding) ++colliding;
  }
  return colliding;
}

test('generated shapes: same verdicts, contact pairs and distances as native', { skip: cli === null && 'ANTCD_CLI not set' }, () => {
  const torus = antcd.Model.torus(1, 0.3, 48, 24);
  const sphere = antcd.Model.sphere(0.6, 40, 20);
  const a = fromMesh('torus', torus.mesh());
  const b = fromMesh('sphere', sphere.mesh());
  const colliding = compare(a, b, 1, 24);
  assert.ok(colliding > 3 && colliding < 21, `${colliding} of 24 poses collide: both outcomes are exercised`);
  for (const m of [torus, sphere, a.model, b.model]) m.delete();
});

test('packaged meshes (assimp test models): same answers as native', { skip: (cli === null || !existsSync(join(packagedModels, 'OBJ', 'spider.obj'))) && 'no CLI or no assimp-testmodels' }, () => {
  const spider = fromMesh('spider', readObj(join(packagedModels, 'OBJ', 'spider.obj')));
  const wuson = fromMesh('wuson', readObj(join(packagedModels, 'OBJ', 'WusonOBJ.obj')));
  assert.ok(spider.model.triangleCount > 1000 && wuson.model.triangleCount > 1000);
  const colliding = compare(spider, wuson, 7, 12);
  assert.ok(colliding > 0 && colliding < 12, `${colliding} of 12 poses collide`);
  spider.model.delete();
  wuson.model.delete();
});
