// The viewer in a real browser: Debian's Chromium, headless, driven by playwright-core (no
// browser download). Generates a small scene, runs exact and maco on it, writes the view with
// `antcd view`, and checks the page against the result files: the data-* contract on several
// frames (opened through #frame=K), stepping, no console errors, a screenshot that is not blank
// and shows the highlight colours; then the same page through `antcd view --serve`.
//
// Usage: node browser_test.mjs --antcd BIN --node-modules DIR --chromium EXE --workdir DIR
import { spawn } from 'node:child_process';
import { readFileSync, writeFileSync } from 'node:fs';
import { join, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';
import assert from 'node:assert/strict';
import { launchChromium, viewerTestSetup, watchedPage } from './chromium.mjs';

const { args, work, antcd } = viewerTestSetup(process.argv.slice(2));

antcd('scene', 'generate', '--out', 'scene', '--objects', '10', '--frames', '24', '--seed', '7');
antcd('run', 'scene/scene.json', '--method', 'exact', '--out', 'exact.json');
antcd('run', 'scene/scene.json', '--method', 'maco', '--seed', '3', '--out', 'maco.json');
antcd('view', 'scene/scene.json', '--result', 'exact.json', '--result', 'maco.json', '--out', 'view.html');

const scene = JSON.parse(readFileSync(join(work, 'scene', 'scene.json'), 'utf8'));
const exact = JSON.parse(readFileSync(join(work, 'exact.json'), 'utf8'));
const maco = JSON.parse(readFileSync(join(work, 'maco.json'), 'utf8'));
const frameOf = (result, k) => result.frames.find((f) => f.frame === k);
const order = new Map(scene.objects.map((o, i) => [o.name, i]));
const sortPairs = (pairs) =>
  pairs.map(([a, b]) => (order.get(a) < order.get(b) ? [a, b] : [b, a]))
    .sort((p, q) => order.get(p[0]) - order.get(q[0]) || order.get(p[1]) - order.get(q[1]));
const key = ([a, b]) => `${a}\u0000${b}`;
function expected(k) {
  const e = sortPairs(frameOf(exact, k).pairs);
  const m = sortPairs(frameOf(maco, k).pairs);
  const inE = new Set(e.map(key));
  const inM = new Set(m.map(key));
  return {
    colliding: sortPairs([...e, ...m.filter((p) => !inE.has(key(p)))]),
    falseAlarms: m.filter((p) => !inE.has(key(p))),
    misses: e.filter((p) => !inM.has(key(p))),
  };
}

const browser = await launchChromium(args['node-modules'], args.chromium);
const problems = [];
try {
  const page = await watchedPage(browser, problems);
  const url = pathToFileURL(join(work, 'view.html')).href;
  const root = page.locator('#antcd-viewer');
  const attrs = () => root.evaluate((e) => ({ ...e.dataset }));

  // Frames with and without collisions, first and last: the first opened by loading the page
  // with #frame=K, the others by changing the fragment (each page load costs seconds under
  // SwiftShader on a busy machine).
  const busiest = exact.frames.reduce((a, f) => (f.pairs.length > a.pairs.length ? f : a)).frame;
  const frames = [...new Set([busiest, 0, 11, scene.frames - 1])];
  for (const [n, k] of frames.entries()) {
    if (n === 0) {
      await page.goto(`${url}#frame=${k}`);
      await page.waitForSelector('#antcd-viewer[data-ready="true"], #antcd-viewer[data-error]', { timeout: 60000 });
    } else {
      await page.evaluate((hash) => { window.location.hash = hash; }, `#frame=${k}`);
      await page.waitForFunction((f) => document.getElementById('antcd-viewer').dataset.frame === String(f), k);
    }
    const d = await attrs();
    assert.equal(d.error, undefined, `page error: ${d.error}`);
    assert.equal(Number(d.objects), scene.objects.length, 'data-objects');
    assert.equal(Number(d.frames), scene.frames, 'data-frames');
    assert.equal(Number(d.frame), k, `data-frame after #frame=${k}`);
    const want = expected(k);
    assert.deepEqual(JSON.parse(d.colliding), want.colliding, `data-colliding, frame ${k}`);
    assert.deepEqual(JSON.parse(d.falseAlarms), want.falseAlarms, `data-false-alarms, frame ${k}`);
    assert.deepEqual(JSON.parse(d.misses), want.misses, `data-misses, frame ${k}`);
    // Exact contacts: at least one per truly colliding pair, at most 16 (the default) per pair.
    const truePairs = frameOf(exact, k).pairs.length;
    assert.ok(Number(d.contacts) >= truePairs && Number(d.contacts) <= 16 * want.colliding.length,
              `data-contacts ${d.contacts} for ${truePairs} colliding pairs, frame ${k}`);
  }
  assert.ok(expected(busiest).colliding.length > 0, 'the test scene has a colliding frame');

  // Stepping: the buttons, the keyboard and the scrubber move the frame, and the pairs follow.
  const start = busiest === scene.frames - 1 ? busiest - 1 : busiest;
  await page.evaluate((hash) => { window.location.hash = hash; }, `#frame=${start}`);
  await page.waitForFunction((k) => document.getElementById('antcd-viewer').dataset.frame === String(k), start);
  await page.click('#antcd-viewer button.step');
  assert.equal(Number((await attrs()).frame), start + 1, 'the step button advances one frame');
  assert.deepEqual(JSON.parse((await attrs()).colliding), expected(start + 1).colliding, 'pairs after stepping');
  await page.keyboard.press('ArrowLeft');
  assert.equal(Number((await attrs()).frame), start, 'ArrowLeft steps back');
  await page.click('#antcd-viewer button.step-back');
  assert.equal(Number((await attrs()).frame), Math.max(0, start - 1), 'the step-back button');
  await page.locator('#antcd-viewer input.scrub').fill(String(scene.frames - 1));
  assert.equal(Number((await attrs()).frame), scene.frames - 1, 'scrubbing to the last frame');
  assert.match(page.url(), new RegExp(`#frame=${scene.frames - 1}$`), 'the fragment follows the frame');
  assert.ok(await page.locator('#antcd-viewer button', { hasText: /VR/ }).count() === 1, 'an Enter VR / VR button');

  // A click on an object (the first hit on a grid over the view) shows its name and pairs.
  let selected;
  for (let y = 0.3; y <= 0.8 && !selected; y += 0.1) {
    for (let x = 0.2; x <= 0.8 && !selected; x += 0.1) {
      await page.mouse.click(1000 * x, 700 * y);
      selected = (await attrs()).selected;
    }
  }
  assert.ok(selected && order.has(selected), `a click selects a scene object (got ${selected})`);
  const info = await page.locator('#antcd-viewer .info').innerText();
  assert.ok(info.includes(selected) && info.includes('colliding in frames'), `the info panel shows ${selected}`);

  // Screenshot of the busiest frame: not blank, and the highlight colour is on screen.
  await page.evaluate((hash) => { window.location.hash = hash; }, `#frame=${busiest}`);
  await page.waitForFunction((k) => document.getElementById('antcd-viewer').dataset.frame === String(k), busiest);
  await page.waitForTimeout(300);
  const png = await page.screenshot({ path: join(work, 'viewer-test.png') });
  const stats = await page.evaluate(async (b64) => {
    const img = new Image();
    img.src = `data:image/png;base64,${b64}`;
    await img.decode();
    const c = document.createElement('canvas');
    c.width = img.width;
    c.height = img.height;
    const ctx = c.getContext('2d');
    ctx.drawImage(img, 0, 0);
    const px = ctx.getImageData(0, 0, c.width, c.height).data;
    let sum = 0;
    let sum2 = 0;
    let highlighted = 0;
    const n = px.length / 4;
    for (let i = 0; i < px.length; i += 4) {
      const [r, g, bl] = [px[i], px[i + 1], px[i + 2]];
      const y = 0.299 * r + 0.587 * g + 0.114 * bl;
      sum += y;
      sum2 += y * y;
      // Reds, oranges or blues of the highlight palette (shaded), not the pastel mesh colours.
      if ((r > 150 && g < 110 && bl < 90) || (r > 200 && g > 110 && g < 190 && bl < 70) || (bl > 180 && r < 90 && g < 150)) ++highlighted;
    }
    const mean = sum / n;
    return { variance: sum2 / n - mean * mean, highlighted, pixels: n };
  }, png.toString('base64'));
  console.log(`screenshot ${join(work, 'viewer-test.png')}: luminance variance ${stats.variance.toFixed(1)}, ` +
              `${stats.highlighted} highlight-coloured pixels of ${stats.pixels}`);
  assert.ok(stats.variance > 100, `screenshot looks blank (luminance variance ${stats.variance})`);
  assert.ok(stats.highlighted > 50, 'the colliding objects are highlighted on screen');

  // The same page served on 127.0.0.1 (blob fetched), then stopped with SIGINT.
  const server = spawn(args.antcd, ['view', 'scene/scene.json', '--result', 'exact.json', '--serve', '--port', '0'],
                       { cwd: work, stdio: ['ignore', 'pipe', 'pipe'] });
  const served = await new Promise((resolve, reject) => {
    let out = '';
    server.stdout.on('data', (chunk) => {
      out += chunk;
      const m = /http:\/\/127\.0\.0\.1:\d+\//.exec(out);
      if (m) resolve(m[0]);
    });
    server.on('exit', (code) => reject(new Error(`antcd view --serve exited ${code}`)));
    setTimeout(() => reject(new Error('antcd view --serve did not start')), 15000);
  });
  const page2 = await browser.newPage();
  page2.on('console', (m) => { if (m.type() === 'error') problems.push(`console (served): ${m.text()}`); });
  page2.on('pageerror', (e) => problems.push(`page error (served): ${e.message}`));
  await page2.goto(`${served}#frame=${busiest}`);
  await page2.waitForSelector('#antcd-viewer[data-ready="true"]', { timeout: 60000 });
  const d2 = await page2.locator('#antcd-viewer').evaluate((e) => ({ ...e.dataset }));
  assert.equal(Number(d2.objects), scene.objects.length, 'served: data-objects');
  assert.deepEqual(JSON.parse(d2.colliding), sortPairs(frameOf(exact, busiest).pairs), 'served: data-colliding');
  const exited = new Promise((resolve) => server.on('exit', (code, signal) => resolve({ code, signal })));
  server.kill('SIGINT');
  assert.deepEqual(await exited, { code: 0, signal: null }, '--serve stops cleanly on SIGINT');

  // A continuous result (antcd run --continuous): the frame's pairs with their first time of
  // impact since the previous frame, in data-first-touch and in the panel.
  antcd('run', 'scene/scene.json', '--continuous', '--out', 'continuous.json');
  antcd('view', 'scene/scene.json', '--result', 'continuous.json', '--out', 'continuous.html');
  const cont = JSON.parse(readFileSync(join(work, 'continuous.json'), 'utf8'));
  const touched = cont.frames.reduce((a, f) => (f.pairs.length > a.pairs.length ? f : a));
  assert.ok(touched.pairs.length > 0, 'the continuous run reports a pair');
  const page3 = await watchedPage(browser, problems);
  await page3.goto(`${pathToFileURL(join(work, 'continuous.html')).href}#frame=${touched.frame}`);
  await page3.waitForSelector('#antcd-viewer[data-ready="true"]', { timeout: 60000 });
  const d3 = await page3.locator('#antcd-viewer').evaluate((e) => ({ ...e.dataset }));
  const wantTouches = touched.pairs
    .map(([a, b], n) => [...sortPairs([[a, b]])[0], touched.toi[n]])
    .sort((p, q) => p[2] - q[2] || order.get(p[0]) - order.get(q[0]) || order.get(p[1]) - order.get(q[1]));
  assert.deepEqual(JSON.parse(d3.firstTouch), wantTouches, `data-first-touch, frame ${touched.frame}`);
  assert.match(await page3.locator('#antcd-viewer').innerText(), /first touch: \S+ – \S+ (at t = [0-9.]+ of the step from frame \d+|at frame 0)/,
               'the panel lists the first touches');

  // A flexible scene (antcd scene generate --flexible): a veneer sheet deforming per frame, with
  // self_collision, one of whose frames folds it onto itself. The page draws the sheet with the
  // scene's vertices of each frame, lists its self pair [sheet, sheet] and draws its triangles.
  antcd('scene', 'generate', '--out', 'flex', '--objects', '12', '--frames', '24', '--seed', '7', '--flexible');
  antcd('run', 'flex/scene.json', '--method', 'exact', '--out', 'flex-exact.json');
  antcd('view', 'flex/scene.json', '--result', 'flex-exact.json', '--out', 'flex.html');
  const flex = JSON.parse(readFileSync(join(work, 'flex', 'scene.json'), 'utf8'));
  const flexExact = JSON.parse(readFileSync(join(work, 'flex-exact.json'), 'utf8'));
  const flexOrder = new Map(flex.objects.map((o, i) => [o.name, i]));
  const flexSort = (pairs) =>
    pairs.map(([a, b]) => (flexOrder.get(a) < flexOrder.get(b) ? [a, b] : [b, a]))
      .sort((p, q) => flexOrder.get(p[0]) - flexOrder.get(q[0]) || flexOrder.get(p[1]) - flexOrder.get(q[1]));
  const sheet = flex.objects.find((o) => o.vertex_frames);
  assert.ok(sheet && sheet.self_collision, 'the flexible scene has a deforming sheet with self_collision');
  // The sheet's side file (include/antcd/scene.hpp): 24-byte header, then float64 x, y, z.
  const avf = readFileSync(join(work, 'flex', sheet.vertex_frames));
  const n = avf.readUInt32LE(12);
  const sceneVertices = (f) => Array.from({ length: 3 * n }, (_, k) => Math.fround(avf.readDoubleLE(24 + 8 * (3 * n * f + k)) * (sheet.scale ?? 1)));
  const folded = flexExact.frames.find((f) => f.pairs.some(([a, b]) => a === b));
  assert.ok(folded, 'the exact run reports a self pair');
  const flat = flexExact.frames.find((f) => !f.pairs.some(([a, b]) => a === b) && f.pairs.length > 0);
  const page4 = await watchedPage(browser, problems);
  await page4.goto(`${pathToFileURL(join(work, 'flex.html')).href}#frame=${folded.frame}`);
  await page4.waitForSelector('#antcd-viewer[data-ready="true"], #antcd-viewer[data-error]', { timeout: 60000 });
  for (const f of [folded, flat]) {
    if (f !== folded) {
      await page4.evaluate((hash) => { window.location.hash = hash; }, `#frame=${f.frame}`);
      await page4.waitForFunction((k) => document.getElementById('antcd-viewer').dataset.frame === String(k), f.frame);
    }
    const d4 = await page4.locator('#antcd-viewer').evaluate((e) => ({ ...e.dataset }));
    assert.equal(d4.error, undefined, `flexible page error: ${d4.error}`);
    assert.deepEqual(JSON.parse(d4.colliding), flexSort(f.pairs), `flexible scene: data-colliding, frame ${f.frame}`);
    const selfWant = (f.self_pairs ?? []).map((sp) => [sp.object, sp.triangles.length]);
    assert.deepEqual(JSON.parse(d4.self), selfWant, `flexible scene: data-self, frame ${f.frame}`);
    const drawn = await page4.evaluate((name) => window.antcdView.drawnVertices(name), sheet.name);
    assert.deepEqual(drawn, sceneVertices(f.frame), `${sheet.name}: drawn vertices of frame ${f.frame} are the scene's`);
    const others = f.pairs.filter(([a, b]) => a !== b).length;
    assert.ok(Number(d4.contacts) >= others, `flexible scene: ${d4.contacts} contacts for ${others} pairs, frame ${f.frame}`);
  }
  assert.notDeepEqual(sceneVertices(folded.frame), sceneVertices(flat.frame), 'the sheet deforms between the two frames');
  await page4.evaluate((hash) => { window.location.hash = hash; }, `#frame=${folded.frame}`);
  await page4.waitForFunction((k) => document.getElementById('antcd-viewer').dataset.frame === String(k), folded.frame);
  assert.match(await page4.locator('#antcd-viewer .counts').innerText(), new RegExp(`self pair: ${sheet.name} touches itself \\(\\d+ triangle pairs?\\)`),
               'the panel lists the self pair');
  console.log(`flexible scene: ${sheet.name} drawn with its vertices of frames ${folded.frame} and ${flat.frame}; ` +
              `self pair with ${folded.self_pairs[0].triangles.length} triangle pairs at frame ${folded.frame}`);
} finally {
  await browser.close();
}
assert.deepEqual(problems, [], 'no console errors, page errors or network requests');
writeFileSync(join(work, 'PASSED'), 'ok\n');
console.log('viewer browser test passed');
