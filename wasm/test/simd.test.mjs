// The package's build compiles the core's SSE2 paths to WebAssembly SIMD128 (-msimd128 -msse2,
// wasm/CMakeLists.txt): its code holds the instructions Emscripten's <emmintrin.h> makes of
// _mm_cvtpd_ps (f32x4.demote_f64x2_zero: the float face-axes node test of src/bvh/face_test.hpp
// and the World tree's float boxes) and of _mm_movemask_ps (i32x4.bitmask), which neither the
// scalar paths nor the autovectoriser emit: a build with -DANTCD_WASM_SSE2=OFF has none of them.
// That the answers stay the native library's is checked by the other tests (native.test.mjs,
// api.test.mjs, ...) against the native CLI.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import test from 'node:test';

function codeSection(bytes) {
  let p = 8; // magic and version
  const leb = () => {
    let r = 0;
    let shift = 0;
    let b;
    do {
      b = bytes[p++];
      r |= (b & 0x7f) << shift;
      shift += 7;
    } while (b & 0x80);
    return r >>> 0;
  };
  while (p < bytes.length) {
    const id = bytes[p++];
    const size = leb();
    if (id === 10) return bytes.subarray(p, p + size);
    p += size;
  }
  return null;
}

// Occurrences of a SIMD instruction (prefix 0xfd, then its LEB128 opcode) in the code section.
function count(code, opcode) {
  let n = 0;
  for (let k = 0; k + opcode.length < code.length; ++k) {
    if (code[k] === 0xfd && opcode.every((b, j) => code[k + 1 + j] === b)) ++n;
  }
  return n;
}

test('the package is built with the SSE2 paths in SIMD128', () => {
  const code = codeSection(readFileSync(new URL('../dist/antcd_core.wasm', import.meta.url)));
  assert.ok(code, 'dist/antcd_core.wasm has a code section');
  assert.ok(count(code, [0x5e]) > 0, 'f32x4.demote_f64x2_zero (_mm_cvtpd_ps) is missing: built without -msse2?');
  assert.ok(count(code, [0xa4, 0x01]) > 0, 'i32x4.bitmask (_mm_movemask_ps) is missing: built without -msse2?');
});
