// Headless Debian Chromium through playwright-core (no browser download), for the viewer's tests
// and screenshots. playwright-core comes from the node_modules the CMake build installs from
// viewer/package-lock.json.
import { spawnSync } from 'node:child_process';
import { mkdirSync, rmSync } from 'node:fs';
import { join, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';

export async function launchChromium(nodeModules, executablePath) {
  const { chromium } = await import(pathToFileURL(join(nodeModules, 'playwright-core', 'index.mjs')).href);
  return chromium.launch({
    executablePath,
    headless: true,
    // WebGL comes from SwiftShader (no GPU); Chromium refuses to run as root (CI containers)
    // without --no-sandbox.
    args: ['--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist',
           ...(process.getuid?.() === 0 ? ['--no-sandbox'] : [])],
  });
}

// "--key value" pairs into an object; throws naming the first missing key of `required`.
export function parseArgs(argv, required) {
  const args = {};
  for (let i = 0; i + 1 < argv.length; i += 2) args[argv[i].replace(/^--/, '')] = argv[i + 1];
  for (const key of required) if (!args[key]) throw new Error(`missing --${key}`);
  return args;
}

// The viewer tests' common start: their arguments (--antcd, --node-modules, --chromium,
// --workdir, resolved), an emptied work folder, and `antcd(...argv)` running the CLI there (throws
// with its stderr on a non-zero exit, returns its stdout).
export function viewerTestSetup(argv) {
  const args = parseArgs(argv, ['antcd', 'node-modules', 'chromium', 'workdir']);
  for (const key of ['antcd', 'node-modules', 'workdir']) args[key] = resolve(args[key]);
  const work = args.workdir;
  rmSync(work, { recursive: true, force: true });
  mkdirSync(work, { recursive: true });
  const antcd = (...a) => {
    const r = spawnSync(args.antcd, a, { cwd: work, encoding: 'utf8' });
    if (r.status !== 0) throw new Error(`antcd ${a.join(' ')} exited ${r.status}: ${r.stderr}`);
    return r.stdout;
  };
  return { args, work, antcd };
}

// A 1000x700 page whose console errors, page errors and network requests (anything but file:,
// data: and blob:) are appended to `problems` as one line each.
export async function watchedPage(browser, problems) {
  const page = await browser.newPage({ viewport: { width: 1000, height: 700 } });
  page.on('console', (m) => { if (m.type() === 'error') problems.push(`console: ${m.text()}`); });
  page.on('pageerror', (e) => problems.push(`page error: ${e.message}`));
  page.on('request', (r) => { if (!/^(file|data|blob):/.test(r.url())) problems.push(`network request: ${r.url()}`); });
  return page;
}
