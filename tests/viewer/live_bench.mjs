// The live page's query time per frame in headless Chromium (a measurement, not a test: it
// asserts nothing about the time): `antcd scene generate` with its defaults (the paper's scene,
// 90 objects, 300 frames) viewed with `antcd view --live`; the page is shown every scene frame in
// turn (showFrame: every moving object re-posed, then collideAll as the page asks it) and the
// WebAssembly time of that animation frame recorded (data-query-ms's number). Prints the median,
// mean, 90th percentile and maximum over the frames. Chromium rounds performance.now() to 0.1 ms
// on a file: page; on a loaded machine single frames are stretched by preemption (the maximum).
//
// Usage: node live_bench.mjs --antcd BIN --node-modules DIR --chromium EXE --workdir DIR
//        [--frames N]   (the first N scene frames; default all)
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';
import { launchChromium, viewerTestSetup, watchedPage } from './chromium.mjs';

const { args, work, antcd } = viewerTestSetup(process.argv.slice(2));

antcd('scene', 'generate', '--out', 'scene');
antcd('view', 'scene/scene.json', '--live', '--out', 'live.html');

const stats = (xs) => {
  const s = [...xs].sort((a, b) => a - b);
  const at = (q) => s[Math.min(s.length - 1, Math.floor(q * s.length))];
  return `median ${at(0.5).toFixed(2)} ms, mean ${(s.reduce((a, b) => a + b, 0) / s.length).toFixed(2)} ms, ` +
    `p90 ${at(0.9).toFixed(2)} ms, max ${s[s.length - 1].toFixed(2)} ms over ${s.length} frames`;
};

const browser = await launchChromium(args['node-modules'], args.chromium);
const problems = [];
try {
  const page = await watchedPage(browser, problems);
  await page.goto(pathToFileURL(join(work, 'live.html')).href);
  await page.waitForSelector('#antcd-viewer[data-ready="true"], #antcd-viewer[data-error]', { timeout: 60000 });
  const viewer = page.locator('#antcd-viewer');
  const objects = await viewer.getAttribute('data-objects');
  const frames = Math.min(Number(args.frames ?? Infinity), Number(await viewer.getAttribute('data-frames')));
  // Each scene frame shown, then two animation frames (the page's loop answers in the first).
  const step = (from, to) => page.evaluate(async ([a, b]) => {
    for (let f = a; f < b; ++f) {
      window.antcdLive.showFrame(f);
      for (let k = 0; k < 2; ++k) await new Promise((done) => requestAnimationFrame(done));
    }
    return window.antcdLive.queryTimes().filter((e) => e.stepped).map((e) => e.ms);
  }, [from, to]);
  await step(0, Math.min(frames, 20)); // warm-up: the engine's tier-up, grown buffers
  const times = await step(0, frames);
  console.log(`live page, default scene (${objects} objects), headless Chromium ${await browser.version()}:`);
  console.log(`  query time per scene frame: ${stats(times)}`);
  if (problems.length) console.log(`  page problems: ${problems.join('; ')}`);
} finally {
  await browser.close();
}
