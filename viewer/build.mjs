// Bundles src/main.js with three.js into one self-contained script for `antcd view`.
// Usage: node build.mjs [OUTFILE]   (default dist/antcd-viewer.js)
// The CMake build copies this file next to the node_modules it installs (in the build tree, so
// that esbuild resolves from there) and sets ANTCD_VIEWER_SRC to this folder in the sources.
import { build } from 'esbuild';
import { readFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = process.env.ANTCD_VIEWER_SRC ?? dirname(fileURLToPath(import.meta.url));
const modules = join(dirname(fileURLToPath(import.meta.url)), 'node_modules');
const outfile = process.argv[2] ?? join(here, 'dist', 'antcd-viewer.js');
await build({
  entryPoints: [join(here, 'src', 'main.js')],
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
