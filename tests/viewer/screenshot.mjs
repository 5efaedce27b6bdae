// Saves a PNG of a page written by `antcd view` once the viewer has drawn it (docs/viewer.md).
// Usage: node screenshot.mjs --node-modules DIR --chromium EXE --page VIEW.html --frame K --out PNG
//        [--width 1280 --height 800]
import { resolve } from 'node:path';
import { pathToFileURL } from 'node:url';
import { launchChromium, parseArgs } from './chromium.mjs';

const args = parseArgs(process.argv.slice(2), ['node-modules', 'chromium', 'page', 'frame', 'out']);
const browser = await launchChromium(args['node-modules'], args.chromium);
try {
  const page = await browser.newPage({ viewport: { width: Number(args.width ?? 1280), height: Number(args.height ?? 800) } });
  page.on('console', (m) => { if (m.type() === 'error') console.error(`console: ${m.text()}`); });
  await page.goto(`${pathToFileURL(resolve(args.page)).href}#frame=${args.frame}`);
  await page.waitForSelector('#antcd-viewer[data-ready="true"]', { timeout: 60000 });
  await page.waitForTimeout(500);
  await page.screenshot({ path: args.out });
  const d = await page.locator('#antcd-viewer').evaluate((e) => ({ ...e.dataset }));
  console.log(`${args.out}: frame ${d.frame}, ${JSON.parse(d.colliding).length} pairs highlighted, ` +
              `${JSON.parse(d.falseAlarms).length} false alarms, ${JSON.parse(d.misses).length} misses`);
} finally {
  await browser.close();
}
