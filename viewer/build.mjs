// Bundles src/main.js with three.js into one self-contained script for `antcd view`.
// Usage: node build.mjs [OUTFILE] [--live]   (default dist/antcd-viewer.js)
// --live: the live page's bundle instead (src/live.js for `antcd view --live`), with the
// WebAssembly build of antcd inside (wasm/index.mjs, wasm/dist/: built first by the wasm/ build),
// its .wasm inlined as bytes.
// The CMake build copies this file next to the node_modules it installs (in the build tree, so
// that esbuild resolves from there) and sets ANTCD_VIEWER_SRC to this folder in the sources.
import { build } from 'esbuild';
import { readFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = process.env.ANTCD_VIEWER_SRC ?? dirname(fileURLToPath(import.meta.url));
const modules = join(dirname(fileURLToPath(import.meta.url)), 'node_modules');
const live = process.argv.includes('--live');
const outfile = process.argv.slice(2).find((a) => a !== '--live') ?? join(here, 'dist', live ? 'antcd-live.js' : 'antcd-viewer.js');
await build({
  entryPoints: [join(here, 'src', live ? 'live.js' : 'main.js')],
  // The Emscripten glue's node-only branches (never taken in a browser) and the package's node
  // file loading (the page passes the inlined bytes instead).
  external: ['fs', 'path', 'crypto', 'node:*'],
  loader: { '.wasm': 'binary' },
  logOverride: { 'empty-import-meta': 'silent' },
  bundle: true,
  format: 'iife',
  minify: true,
  // Browsers with WebGL 2 and the syntax three.js itself uses.
  target: ['chrome111', 'firefox115', 'safari16.4'],
  nodePaths: [modules],
  legalComments: 'eof',
  outfile,
  logLevel: 'warning',
});
// The bundle is inlined in a <script> element: it must not contain a closing tag.
if (/<\/script/i.test(readFileSync(outfile, 'utf8'))) {
  console.error(`error: ${outfile} contains "</script" and cannot be inlined`);
  process.exit(1);
}
