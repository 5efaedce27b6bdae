#!/usr/bin/env bash
# The npm package as a user gets it: `npm pack` in wasm/ (after the build put dist/ there), the
# tarball installed into an empty project (offline: the package has no dependencies), imported by
# name, and one query answered.
# Usage: pack_test.sh WORKDIR
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
work="$1"
rm -rf "$work"
mkdir -p "$work/project"
tarball="$(cd "$here" && npm pack --silent --pack-destination "$work")"
cd "$work/project"
printf '{ "name": "antcd-pack-test", "version": "1.0.0", "private": true, "type": "module" }\n' > package.json
npm install --offline --no-audit --no-fund --loglevel=error "$work/$tarball"
cat > check.mjs <<'JS'
import createAntcd from 'antcd';
const antcd = await createAntcd();
const box = antcd.Model.box(0.5, 0.5, 0.5);
const at = (x) => [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, x, 0, 0, 1];
const touching = antcd.collide(box, at(0), box, at(0.9)).colliding;
const apart = antcd.collide(box, at(0), box, at(1.1)).colliding;
if (!touching || apart) throw new Error(`wrong verdicts from the installed package: ${touching}, ${apart}`);
// deform.mjs is in the tarball too: a vertex of the box moving out through the opposite face.
const p0 = box.mesh().positions;
const p1 = p0.slice();
p1[0] += 2;
if (!antcd.deformSweep(box, p0, p1).hit) throw new Error('deformSweep from the installed package missed');
console.log(`installed ${process.argv[2]}: antcd ${antcd.version} answers`);
JS
node check.mjs "$tarball"
