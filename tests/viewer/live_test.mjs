// The live page (`antcd view SCENE --live`) in Debian's headless Chromium: the paper's scene (90
// objects) with the WebAssembly World answering every animation frame. Pauses the motion, drags an
// object onto another with the mouse, then grabs a third with a WebXR controller's squeeze (no
// headset: the page's hooks place controller 0 and dispatch its events as three.js's WebXR
// manager does), moves and turns the controller and lets go; checks that the grabbed object
// followed the controller rigidly and stayed after the squeeze, and the highlighted pairs against
// the native library at the same poses after each move (a one-frame copy of the scene with the
// moved objects' new poses, run with `antcd run --method exact`); no console errors, no network
// request, a query time per frame reported (printed, with the mean over the frames seen).
//
// Usage: node live_test.mjs --antcd BIN --node-modules DIR --chromium EXE --workdir DIR
//        [--screenshot PNG]   (also saves the page after the drag, for the README)
import { readFileSync, writeFileSync } from 'node:fs';
import { join, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';
import assert from 'node:assert/strict';
import { launchChromium, viewerTestSetup, watchedPage } from './chromium.mjs';

const { args, work, antcd } = viewerTestSetup(process.argv.slice(2));
const THREE = await import(pathToFileURL(join(args['node-modules'], 'three', 'build', 'three.module.js')).href);

antcd('scene', 'generate', '--out', 'scene', '--objects', '90', '--frames', '40', '--seed', '11');
antcd('view', 'scene/scene.json', '--live', '--out', 'live.html');
const scene = JSON.parse(readFileSync(join(work, 'scene', 'scene.json'), 'utf8'));
const order = new Map(scene.objects.map((o, i) => [o.name, i]));
const sortPairs = (pairs) =>
  pairs.map(([a, b]) => (order.get(a) < order.get(b) ? [a, b] : [b, a]))
    .sort((p, q) => order.get(p[0]) - order.get(q[0]) || order.get(p[1]) - order.get(q[1]));

// The native answer at the page's poses: the scene at `frame`, the moved objects at their poses:
// the new translation, and the rotation either the scene's (a mouse drag keeps it) or the
// quaternion the page made a controller-turned pose from (grab.js: the native loader's formula).
function nativePairs(frame, moved) {
  const objects = scene.objects.map((o) => {
    const p = structuredClone(o.poses.length === 1 ? o.poses[0] : o.poses[frame]);
    const m = moved.find((x) => x.name === o.name);
    if (m) p.translation = [m.pose[12], m.pose[13], m.pose[14]];
    if (m?.rotation_wxyz) p.rotation_wxyz = m.rotation_wxyz;
    return { ...o, poses: [p] };
  });
  writeFileSync(join(work, 'scene', 'moved.json'), JSON.stringify({ ...scene, frames: 1, objects }));
  antcd('run', 'scene/moved.json', '--method', 'exact', '--out', 'native.json');
  return sortPairs(JSON.parse(readFileSync(join(work, 'native.json'), 'utf8')).frames[0].pairs);
}

const browser = await launchChromium(args['node-modules'], args.chromium);
const problems = [];
try {
  const page = await watchedPage(browser, problems);
  await page.goto(pathToFileURL(join(work, 'live.html')).href);
  await page.waitForSelector('#antcd-viewer[data-ready="true"], #antcd-viewer[data-error]', { timeout: 60000 })
    .catch((e) => { throw new Error(`page not ready: ${e.message}; ${problems.join('; ')}`); });
  const attrs = () => page.locator('#antcd-viewer').evaluate((e) => ({ ...e.dataset }));
  // Waits for n animation frames: the page's loop (controllers followed, World posed and asked)
  // has run at least n - 1 times since the call, however slow the machine.
  const frames = (n) => page.evaluate(async (k) => {
    for (let i = 0; i < k; ++i) await new Promise((done) => requestAnimationFrame(done));
  }, n);
  let d = await attrs();
  assert.equal(d.error, undefined, `page error: ${d.error}`);
  assert.equal(d.live, 'true');
  assert.equal(Number(d.objects), 90);

  // The scene plays: the frame advances and every frame is answered.
  await page.waitForFunction(() => Number(document.getElementById('antcd-viewer').dataset.frame) >= 2, null, { timeout: 30000 });
  await page.evaluate(() => window.antcdLive.pause());
  await frames(3);
  const before = await page.evaluate(() => window.antcdLive.state());
  assert.deepEqual(sortPairs(before.pairs), nativePairs(before.frame, []), `frame ${before.frame}: pairs before the drag`);

  // Drag an object whose pick point is on screen onto the centre of another one.
  const names = scene.objects.map((o) => o.name);
  let dragged = null;
  for (const [k, name] of names.entries()) {
    if (k % 7 !== 3) continue;
    const from = await page.evaluate((n) => window.antcdLive.pickPoint(n), name);
    if (!from) continue;
    const target = names[(k + 1) % names.length];
    const to = await page.evaluate((n) => window.antcdLive.screenOf(n), target);
    if (Math.hypot(to.x - from.x, to.y - from.y) < 20 || to.x < 0 || to.y < 0 || to.x > 1000 || to.y > 700) continue;
    dragged = { name, target, from, to };
    break;
  }
  assert.ok(dragged, 'an object to drag is on screen');
  await page.mouse.move(dragged.from.x, dragged.from.y);
  await page.mouse.down();
  for (let s = 1; s <= 10; ++s) {
    await page.mouse.move(dragged.from.x + ((dragged.to.x - dragged.from.x) * s) / 10, dragged.from.y + ((dragged.to.y - dragged.from.y) * s) / 10);
  }
  await page.mouse.up();
  await frames(3);
  const after = await page.evaluate(() => window.antcdLive.state());
  d = await attrs();
  assert.equal(d.dragged, dragged.name, 'the pressed object is the dragged one');
  assert.equal(after.frame, before.frame, 'paused');
  assert.equal(after.moved.length, 1);
  const m = after.moved[0];
  const original = scene.objects[order.get(m.name)];
  const p0 = original.poses.length === 1 ? original.poses[0] : original.poses[after.frame];
  assert.notDeepEqual([m.pose[12], m.pose[13], m.pose[14]], p0.translation, 'the object moved');
  const expected = nativePairs(after.frame, after.moved);
  assert.deepEqual(sortPairs(after.pairs), expected, 'highlighted pairs after the drag equal the native answer');
  assert.ok(expected.some(([a, b]) => a === m.name || b === m.name), `${m.name} dragged onto ${dragged.target} collides`);
  assert.ok(Number(d.queryMs) >= 0 && Number.isFinite(Number(d.queryMeanMs)), `query time reported: ${d.queryMs}`);
  console.log(`live page: 90 objects, ${expected.length} colliding pairs after dragging ${m.name}; ` +
              `WebAssembly query ${d.queryMs} ms last frame, ${d.queryMeanMs} ms mean (headless Chromium)`);
  if (args.screenshot) await page.screenshot({ path: resolve(args.screenshot) });

  // WebXR squeeze: controller 0 pointed at an object (not the dragged one) grabs it.
  const live = (f, ...a) => page.evaluate(([g, x]) => window.antcdLive[g](...x), [f, a]);
  let grab = null;
  for (const [k, name] of names.entries()) {
    if (k % 5 !== 1 || name === m.name) continue;
    const aim = await live('aimAt', name);
    const target = names[(k + 2) % names.length];
    if (aim && target !== m.name) {
      grab = { name, target, aim };
      break;
    }
  }
  assert.ok(grab, 'an object a controller can point at');
  const matrix = (a) => new THREE.Matrix4().fromArray(a);
  const grabbedPose = matrix(await live('poseOf', grab.name));
  const m0 = matrix(grab.aim);
  await live('controllerPose', 0, grab.aim);
  await live('controllerEvent', 0, 'squeezestart');
  assert.equal((await attrs()).dragged, grab.name, 'squeeze grabs the object the controller points at');
  // Move the controller in steps by D: a 40 degree turn about the object's centre, then the
  // object's centre onto the target's. The object must end at D grabbedPose (the scene is not scaled
  // outside a headset: three.js world = scene frame).
  const c0 = new THREE.Vector3().setFromMatrixPosition(grabbedPose);
  const c1 = new THREE.Vector3().setFromMatrixPosition(matrix(await live('poseOf', grab.target)));
  const motion = (s) => new THREE.Matrix4().makeTranslation(c0.clone().lerp(c1, s))
    .multiply(new THREE.Matrix4().makeRotationAxis(new THREE.Vector3(0.3, 1, 0.2).normalize(), (s * 40 * Math.PI) / 180))
    .multiply(new THREE.Matrix4().makeTranslation(c0.clone().negate()));
  for (let s = 1; s <= 5; ++s) {
    await live('controllerPose', 0, motion(s / 5).multiply(m0).elements);
    await frames(1);
  }
  await frames(3);
  const held = await page.evaluate(() => window.antcdLive.state());
  const g = held.moved.find((x) => x.name === grab.name);
  assert.ok(g && g.rotation_wxyz, 'the grabbed object moved with the controller');
  const want = motion(1).multiply(grabbedPose).elements;
  const error = Math.max(...g.pose.map((v, k) => Math.abs(v - want[k])));
  assert.ok(error < 1e-9 * (1 + c0.length() + c1.length()), `rigid follow: pose off by ${error}`);
  const heldExpected = nativePairs(held.frame, held.moved);
  assert.deepEqual(sortPairs(held.pairs), heldExpected, 'highlighted pairs while grabbed equal the native answer');
  assert.ok(heldExpected.some(([a, b]) => a === grab.name || b === grab.name), `${grab.name} moved onto ${grab.target} collides`);
  // Squeeze end: the object stays where it was let go while the controller moves on.
  await live('controllerEvent', 0, 'squeezeend');
  await live('controllerPose', 0, new THREE.Matrix4().makeTranslation(1, 2, 3).multiply(motion(1)).multiply(m0).elements);
  await frames(3);
  const released = await page.evaluate(() => window.antcdLive.state());
  assert.deepEqual(released.moved.find((x) => x.name === grab.name).pose, g.pose, 'released where it was let go');
  assert.deepEqual(sortPairs(released.pairs), heldExpected, 'highlighted pairs after the release');
  console.log(`live page: WebXR squeeze grabbed ${grab.name}, moved it onto ${grab.target} (rigid within ${error.toExponential(1)}), ` +
              `${heldExpected.length} colliding pairs as native`);

  // A flexible scene: the sheet (its own Model, outside the World) shows the scene's vertices of
  // the frame; its self pair is [sheet, sheet]; a mouse drag bends it (viewer/src/sheets.js,
  // recomputed here) and the pairs at the bent vertices equal the native answer (a one-frame
  // scene whose side file holds the page's vertices).
  antcd('scene', 'generate', '--out', 'flex', '--objects', '12', '--frames', '24', '--seed', '7', '--flexible');
  antcd('view', 'flex/scene.json', '--live', '--out', 'flex-live.html');
  antcd('run', 'flex/scene.json', '--method', 'exact', '--out', 'flex-exact.json');
  const flex = JSON.parse(readFileSync(join(work, 'flex', 'scene.json'), 'utf8'));
  const flexOrder = new Map(flex.objects.map((o, i) => [o.name, i]));
  const flexSort = (pairs) => pairs.map(([a, b]) => (flexOrder.get(a) <= flexOrder.get(b) ? [a, b] : [b, a]))
    .sort((p, q) => flexOrder.get(p[0]) - flexOrder.get(q[0]) || flexOrder.get(p[1]) - flexOrder.get(q[1]));
  const sheet = flex.objects.find((o) => o.vertex_frames);
  assert.equal(sheet.scale ?? 1, 1, 'the generated sheet is not scaled');
  const avf = readFileSync(join(work, 'flex', sheet.vertex_frames));
  const nv = avf.readUInt32LE(12);
  const sceneVertices = (f) => Array.from({ length: 3 * nv }, (_, k) => avf.readDoubleLE(24 + 8 * (3 * nv * f + k)));
  const folded = JSON.parse(readFileSync(join(work, 'flex-exact.json'), 'utf8')).frames.find((f) => f.pairs.some(([a, b]) => a === b));
  assert.ok(folded, 'the flexible scene folds its sheet onto itself in some frame');
  const nativeFlex = (frame, vertices) => {
    const bytes = Buffer.alloc(24 + 8 * vertices.length);
    avf.copy(bytes, 0, 0, 16);
    bytes.writeBigUInt64LE(1n, 16);
    vertices.forEach((v, k) => bytes.writeDoubleLE(v, 24 + 8 * k));
    writeFileSync(join(work, 'flex', 'frames', 'page.avf'), bytes);
    const objects = flex.objects.map((o) => ({ ...o, poses: [o.poses.length === 1 ? o.poses[0] : o.poses[frame]],
                                               ...(o === sheet ? { vertex_frames: 'frames/page.avf' } : {}) }));
    writeFileSync(join(work, 'flex', 'page.json'), JSON.stringify({ ...flex, frames: 1, objects }));
    antcd('run', 'flex/page.json', '--method', 'exact', '--out', 'flex-native.json');
    const f = JSON.parse(readFileSync(join(work, 'flex-native.json'), 'utf8')).frames[0];
    return { pairs: flexSort(f.pairs), self: (f.self_pairs ?? []).map((sp) => [sp.object, sp.triangles.flat()]) };
  };
  const fpage = await watchedPage(browser, problems);
  await fpage.goto(pathToFileURL(join(work, 'flex-live.html')).href);
  await fpage.waitForSelector('#antcd-viewer[data-ready="true"], #antcd-viewer[data-error]', { timeout: 60000 });
  const fl = (f, ...a) => fpage.evaluate(([g, x]) => window.antcdLive[g](...x), [f, a]);
  const fframes = (n) => fpage.evaluate(async (k) => { for (let i = 0; i < k; ++i) await new Promise((done) => requestAnimationFrame(done)); }, n);
  await fl('showFrame', folded.frame);
  await fframes(3);
  const rest = await fl('state');
  assert.deepEqual(await fl('verticesOf', sheet.name), sceneVertices(folded.frame), 'the sheet has the scene\'s vertices of the frame');
  const restNative = nativeFlex(folded.frame, sceneVertices(folded.frame));
  assert.deepEqual(flexSort(rest.pairs), restNative.pairs, `flexible frame ${folded.frame}: pairs as native`);
  assert.ok(rest.pairs.some(([a, b]) => a === sheet.name && b === sheet.name), 'the self pair is in data-colliding');
  assert.deepEqual(rest.selfTriangles, restNative.self, 'self triangle pairs as native');
  const from = await fl('pickPoint', sheet.name);
  assert.ok(from, 'a point of the sheet is on screen');
  await fpage.mouse.move(from.x, from.y);
  await fpage.mouse.down();
  for (let s = 1; s <= 8; ++s) await fpage.mouse.move(from.x + 5 * s, from.y - 12 * s);
  await fpage.mouse.up();
  await fframes(3);
  const bentState = await fl('state');
  const bent = await fl('verticesOf', sheet.name);
  const bends = await fl('bendsOf', sheet.name);
  assert.equal((await fpage.locator('#antcd-viewer').evaluate((e) => e.dataset.dragged)), sheet.name, 'the sheet is the dragged object');
  assert.equal(bends.length, 1, 'one bend');
  assert.ok(Math.hypot(...bends[0].offset) > 0, 'the drag pulled the sheet');
  const { applyBend } = await import(pathToFileURL(resolve(import.meta.dirname, '..', '..', 'viewer', 'src', 'sheets.js')).href);
  assert.deepEqual(bent, Array.from(applyBend(Float64Array.from(sceneVertices(folded.frame)), bends[0])), 'the bent vertices are the bend of the scene\'s');
  assert.notDeepEqual(bent, sceneVertices(folded.frame), 'dragging changed the vertices');
  const bentNative = nativeFlex(folded.frame, bent);
  assert.deepEqual(flexSort(bentState.pairs), bentNative.pairs, 'pairs of the bent sheet as native');
  assert.deepEqual(bentState.selfTriangles, bentNative.self, 'self triangle pairs of the bent sheet as native');
  console.log(`live page, flexible: ${sheet.name} bent by ${Math.hypot(...bends[0].offset).toFixed(3)}; ` +
              `${rest.pairs.length} pairs before, ${bentState.pairs.length} after, as native`);
  assert.deepEqual(problems, []);
} finally {
  await browser.close();
}
