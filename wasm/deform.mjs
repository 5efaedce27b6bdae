// The deforming sweeps of the npm package (deformSweep, collisionFreeStep; wasm/src/bind_deform.cpp
// underneath, definitions in include/antcd/deform_ccd.hpp): every vertex of a mesh moves linearly
// from positions0 to positions1 over t in [0, 1]. Split from index.mjs, which hands in its
// helpers: the checked allocation, the output block, the argument checks.

/** The two functions and the pair record's reader, closed over index.mjs's helpers (ctx). */
export function deformApi(ctx) {
  const { core, alloc, check, out, outCopy, number, modelOf, optionsOf, writePose, isPose, describe, Model } = ctx;
  // Float64Array positions copied into checked WebAssembly allocations: [[address, length], ...]
  // (free every address, also on an error: freeAll).
  function positionsIn(fn, arrays) {
    const blocks = [];
    try {
      for (const [name, v] of arrays) {
        if (!(v instanceof Float64Array)) {
          throw new Error(`${fn}: ${name} must be a Float64Array (x y z per vertex), got ${describe(v)}`);
        }
        const p = alloc(fn, name, v.length * 8);
        blocks.push([p, v.length]);
        core.HEAPF64.set(v, p / 8);
      }
    } catch (e) {
      freeAll(blocks);
      throw e;
    }
    return blocks;
  }
  function freeAll(blocks) {
    for (const [p] of blocks) core.freeBytes(p);
  }
  function nonNegative(fn, name, v, dflt) {
    const x = number(fn, name, v, dflt);
    if (!(x >= 0) || !Number.isFinite(x)) throw new Error(`${fn}: ${name} must be a finite number >= 0, got ${describe(v)}`);
    return x;
  }
  function positive(fn, name, v, dflt) {
    const x = number(fn, name, v, dflt);
    if (!(x > 0) || !Number.isFinite(x)) throw new Error(`${fn}: ${name} must be a finite number > 0, got ${describe(v)}`);
    return x;
  }
  const PAIR_KINDS = ['vertexFace', 'edgeEdge'];
  const DEFORM_HEAD = 7;
  const PAIR_STRIDE = 8;
  function deformPair(o, at) {
    const kind = PAIR_KINDS[o[at]];
    return {
      kind, vertexInFirst: o[at + 1] === 1,
      indices: kind === 'vertexFace' ? [o[at + 2], o[at + 3]] : [o[at + 2], o[at + 3], o[at + 4], o[at + 5]],
      toi: o[at + 6], toleranceDecided: (o[at + 7] & 1) !== 0, budgetExhausted: (o[at + 7] & 2) !== 0,
    };
  }

  /**
   * Continuous collision of a deforming mesh (vertex i of a moves linearly from a0 to a1, x y z per
   * vertex, Float64Array): deformSweep(a, a0, a1, options) against itself; deformSweep(a, a0, a1,
   * b, b0, b1, options) against a second deforming model b (b0, b1: Float64Array positions) or a
   * rigid one moving between two poses (b0, b1: 16 numbers each, column-major; 16 is never three
   * times a vertex count). options: minSeparation (0), timeTolerance (1e-6), allPairs (false),
   * posePathTolerance (0). { hit, toi, toleranceDecided, pair, pairs, nodePairs, primitiveQueries,
   * tasks, scratchBytes }.
   */
  function deformSweep(a, a0, a1, ...rest) {
    const fn = 'deformSweep';
    const ia = modelOf(fn, 'a', a);
    const other = rest[0] instanceof Model;
    if (rest.length > 4) throw new Error(`${fn}: at most 7 arguments (a, a0, a1, b, b0, b1, options), got ${3 + rest.length}`);
    if (!other && rest.length > 1) throw new Error(`${fn}: the 4th argument must be a Model (b) or the options, got ${describe(rest[0])}`);
    const [b, b0, b1, opts] = other ? rest : [undefined, undefined, undefined, rest[0]];
    const o = optionsOf(fn, opts);
    const minSeparation = nonNegative(fn, 'minSeparation', o.minSeparation, 0);
    const timeTolerance = positive(fn, 'timeTolerance', o.timeTolerance, 1e-6);
    const posePathTolerance = nonNegative(fn, 'posePathTolerance', o.posePathTolerance, 0);
    let mode = 0;
    let ib = -1;
    const arrays = [['a0', a0], ['a1', a1]];
    if (other) {
      ib = modelOf(fn, 'b', b);
      if (isPose(b0) !== isPose(b1)) {
        throw new Error(`${fn}: b0 and b1 must both be poses (16 numbers) or both positions (Float64Array), got ${describe(b0)} and ${describe(b1)}`);
      }
      if (isPose(b0)) {
        mode = 2;
        writePose(0, b0, fn, 'poseB0');
        writePose(1, b1, fn, 'poseB1');
      } else {
        mode = 1;
        arrays.push(['b0', b0], ['b1', b1]);
      }
    }
    const blocks = positionsIn(fn, arrays);
    try {
      const [pa0, pa1, pb0 = [0, 0], pb1 = [0, 0]] = blocks;
      check(fn, core.deformSweep(mode, ia, pa0[0], pa0[1], pa1[0], pa1[1], ib, pb0[0], pb0[1], pb1[0], pb1[1],
        minSeparation, timeTolerance, Boolean(o.allPairs), posePathTolerance));
    } finally {
      freeAll(blocks);
    }
    const head = out(DEFORM_HEAD);
    const k = head[6];
    const all = outCopy(DEFORM_HEAD + PAIR_STRIDE * (1 + k));
    const hit = (all[0] & 1) !== 0;
    const pairs = [];
    for (let i = 0; i < k; ++i) pairs.push(deformPair(all, DEFORM_HEAD + PAIR_STRIDE * (1 + i)));
    return {
      hit, toi: all[1], toleranceDecided: (all[0] & 2) !== 0, pair: hit ? deformPair(all, DEFORM_HEAD) : null, pairs,
      nodePairs: all[2], primitiveQueries: all[3], tasks: all[4], scratchBytes: all[5],
    };
  }

  /**
   * The collision-free step in IPC's terms: the largest s in [0, 1] (never larger than the true one,
   * within timeTolerance of it) such that over [0, s] no self pair of model, moving from v0 to v1,
   * comes closer than minSeparation. 1 when none does.
   */
  function collisionFreeStep(model, v0, v1, minSeparation, opts) {
    const fn = 'collisionFreeStep';
    const id = modelOf(fn, 'model', model);
    if (minSeparation === undefined) throw new Error(`${fn}: minSeparation is required (a finite number >= 0)`);
    const sep = nonNegative(fn, 'minSeparation', minSeparation, 0);
    const o = optionsOf(fn, opts);
    const timeTolerance = positive(fn, 'timeTolerance', o.timeTolerance, 1e-6);
    const blocks = positionsIn(fn, [['v0', v0], ['v1', v1]]);
    try {
      check(fn, core.collisionFreeStep(id, blocks[0][0], blocks[0][1], blocks[1][0], blocks[1][1], sep, timeTolerance));
    } finally {
      freeAll(blocks);
    }
    return out(1)[0];
  }

  return { deformSweep, collisionFreeStep, deformPair };
}
