// Shared by the node tests: the package, the native CLI as the reference (ANTCD_CLI, set by the
// ctest case wasm_node), mesh files written so that both sides read the very same doubles, and
// rigid poses whose matrices both sides compute exactly.
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';

import createAntcd from '../index.mjs';

export const antcd = await createAntcd();
export const cli = process.env.ANTCD_CLI ?? null;
export const workdir = mkdtempSync(join(tmpdir(), 'antcd-wasm-test-'));
export const packagedModels = process.env.ANTCD_ASSIMP_MODELS ?? '/usr/share/assimp/models';

// Rotations whose matrices are exact in floating point, given as the unit quaternion the CLI
// takes (w, x, y, z) and the column-major 3x3 both sides then hold: identity, half turns about x
// and z, and the cyclic permutation (a third of a turn about (1, 1, 1)).
export const ROTATIONS = [
  { q: [1, 0, 0, 0], m: [1, 0, 0, 0, 1, 0, 0, 0, 1] },
  { q: [0, 1, 0, 0], m: [1, 0, 0, 0, -1, 0, 0, 0, -1] },
  { q: [0, 0, 0, 1], m: [-1, 0, 0, 0, -1, 0, 0, 0, 1] },
  { q: [0.5, 0.5, 0.5, 0.5], m: [0, 1, 0, 0, 0, 1, 1, 0, 0] },
];

/** A pose: { matrix (16, column-major), cli ("tx,ty,tz,qw,qx,qy,qz") }. */
export function pose(t, rotation = ROTATIONS[0]) {
  const r = rotation.m;
  const matrix = [r[0], r[1], r[2], 0, r[3], r[4], r[5], 0, r[6], r[7], r[8], 0, t[0], t[1], t[2], 1];
  return { matrix, cli: [...t, ...rotation.q].map(String).join(',') };
}

/** Writes positions/indices as OBJ with the shortest round-trip text of every coordinate. */
export function writeObj(name, positions, indices) {
  const lines = [];
  for (let k = 0; k < positions.length; k += 3) lines.push(`v ${positions[k]} ${positions[k + 1]} ${positions[k + 2]}`);
  for (let k = 0; k < indices.length; k += 3) lines.push(`f ${indices[k] + 1} ${indices[k + 1] + 1} ${indices[k + 2] + 1}`);
  const path = join(workdir, name);
  writeFileSync(path, lines.join('\n') + '\n');
  return path;
}

/** Triangulated OBJ reader (v and f lines; polygons fanned; negative indices resolved). */
export function readObj(path) {
  const positions = [];
  const indices = [];
  for (const line of readFileSync(path, 'latin1').split(/\r?\n/)) {
    const t = line.trim().split(/\s+/);
    if (t[0] === 'v') {
      positions.push(Number(t[1]), Number(t[2]), Number(t[3]));
    } else if (t[0] === 'f') {
      const nv = positions.length / 3;
      const v = t.slice(1).map((s) => {
        const i = parseInt(s.split('/')[0], 10);
        return i < 0 ? nv + i : i - 1;
      });
      for (let k = 1; k + 1 < v.length; ++k) indices.push(v[0], v[k], v[k + 1]);
    }
  }
  return { positions: new Float64Array(positions), indices: new Uint32Array(indices) };
}

/** The native answer: `antcd <command> A B --pose-a .. --pose-b .. --json ...extra`. */
export function native(command, fileA, poseA, fileB, poseB, extra = []) {
  const out = execFileSync(cli, [command, fileA, fileB, '--pose-a', poseA.cli, '--pose-b', poseB.cli, '--json', ...extra],
    { encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] });
  return JSON.parse(out);
}

/** Sorted "a,b" triangle pairs of a contact array (CONTACT_STRIDE records). */
export function pairKeys(contacts) {
  const keys = [];
  for (let k = 0; k < contacts.length; k += antcd.CONTACT_STRIDE) keys.push(`${contacts[k]},${contacts[k + 1]}`);
  return keys.sort();
}

/** A deterministic generator (mulberry32) for poses. */
export function rng(seed) {
  let s = seed >>> 0;
  return () => {
    s = (s + 0x6d2b79f5) >>> 0;
    let t = s;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

/** A grid sheet of nx x ny vertices at place(u, v) (u, v in [0, 1]), two triangles per cell. */
export function sheet(nx, ny, place) {
  const positions = new Float64Array(3 * nx * ny);
  const indices = [];
  for (let i = 0; i < nx; ++i) {
    for (let j = 0; j < ny; ++j) positions.set(place(i / (nx - 1), j / (ny - 1)), 3 * (i * ny + j));
  }
  for (let i = 0; i + 1 < nx; ++i) {
    for (let j = 0; j + 1 < ny; ++j) {
      const a = i * ny + j;
      const b = (i + 1) * ny + j;
      indices.push(a, b, b + 1, a, b + 1, a + 1);
    }
  }
  return { positions, indices: new Uint32Array(indices) };
}

/** A rigid pose matrix (column-major): a turn by `angle` about z, then translation t. */
export function turnZ(angle, t = [0, 0, 0]) {
  const c = Math.cos(angle);
  const s = Math.sin(angle);
  return [c, s, 0, 0, -s, c, 0, 0, 0, 0, 1, 0, t[0], t[1], t[2], 1];
}

/** positions (x y z per vertex) mapped by a column-major rigid matrix. */
export function posed(matrix, positions) {
  const out = new Float64Array(positions.length);
  for (let k = 0; k < positions.length; k += 3) {
    for (let r = 0; r < 3; ++r) {
      out[k + r] = matrix[r] * positions[k] + matrix[4 + r] * positions[k + 1] + matrix[8 + r] * positions[k + 2] + matrix[12 + r];
    }
  }
  return out;
}
