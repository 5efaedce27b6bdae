// Headless Debian Chromium through playwright-core (no browser download), for the viewer's tests
// and screenshots. playwright-core comes from the node_modules the CMake build installs from
// viewer/package-lock.json.
import { join } from 'node:path';
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
