// The npm package `antcd`: the exact collision library compiled to WebAssembly, as an ES module.
// index.d.ts states the API; README.md (repository root, "WebAssembly") shows one example.
//
//   import createAntcd from 'antcd';
//   const antcd = await createAntcd();
//   const a = new antcd.Model(positions, indices);          // Float32Array/Float64Array, indices
//   const r = antcd.collide(a, poseA, b, poseB, { allContacts: true });
//   a.delete();
//
// Poses are column-major 4x4 rigid matrices (three.js Matrix4.elements; 16 numbers). Bad input
// throws a JS Error whose message names the argument and the problem. Queries copy their poses into
// a fixed block of WebAssembly memory and read their answers from a reused one: no WebAssembly
// allocation per query once the buffers have grown; collides() (the verdict alone) allocates
// nothing in JS either. Every WebAssembly allocation is checked: when memory runs out the call
// throws an Error saying "out of WebAssembly memory" and the module keeps answering (delete()
// models and Worlds to make room).
import { deformApi } from './deform.mjs';
import { worldApi } from './world.mjs';
import factory from './dist/antcd_core.cjs';

const isNode = typeof process !== 'undefined' && process.versions != null && process.versions.node != null;

async function wasmBytes(options) {
  if (options.wasmBinary) return options.wasmBinary;
  const url = new URL('./dist/antcd_core.wasm', import.meta.url);
  if (isNode && url.protocol === 'file:') {
    const fs = await import('node:fs/promises');
    return fs.readFile(url);
  }
  const response = await fetch(url);
  if (!response.ok) throw new Error(`antcd: cannot load ${url}: HTTP ${response.status}`);
  return new Uint8Array(await response.arrayBuffer());
}

/** Contact records: triangleA, triangleB, point x y z, distance, normal x y z, depth. */
export const CONTACT_STRIDE = 10;
const SWEEP_STRIDE = 5 + CONTACT_STRIDE;
const EMPTY = new Float64Array(0);
const NO_OPTIONS = Object.freeze({});

function isPose(p) {
  return (Array.isArray(p) || ArrayBuffer.isView(p)) && p.length === 16;
}

/**
 * Loads the WebAssembly module. options.wasmBinary: the .wasm bytes (otherwise read beside this
 * file: the file system under node, fetch in a browser).
 */
export default async function createAntcd(options = {}) {
  const core = await factory({ wasmBinary: await wasmBytes(options) });
  const poseBase = core.poseBlock() / 8;
  const utf8 = new TextDecoder();
  const toUtf8 = new TextEncoder();

  // The NUL-terminated UTF-8 string at address p of WebAssembly memory.
  function cString(p) {
    const heap = core.HEAPU8;
    let end = p;
    while (heap[end] !== 0) ++end;
    return utf8.decode(heap.subarray(p, end));
  }
  function fail(fn) {
    throw new Error(cString(core._antcd_last_error()) || `${fn} failed`);
  }
  function outOfMemory(fn, what, bytes) {
    return new Error(`${fn}: out of WebAssembly memory (${what}: ${bytes} bytes; delete() the models and Worlds no longer needed)`);
  }
  // n bytes of WebAssembly memory (free with core.freeBytes), or an Error when none are left.
  function alloc(fn, what, n) {
    const p = core.allocBytes(Math.max(n, 8));
    if (p === 0) throw outOfMemory(fn, what, n);
    return p;
  }
  // A string's UTF-8 bytes copied into WebAssembly memory: [address, length] (free the address).
  function allocString(fn, what, text) {
    const bytes = toUtf8.encode(text);
    const p = alloc(fn, what, bytes.length);
    core.HEAPU8.set(bytes, p);
    return [p, bytes.length];
  }
  // A C++ exception that escaped the bindings (only Embind's own allocations can throw one: a
  // World's construction) as an Error.
  function rethrow(fn, e) {
    if (e instanceof Error) throw e;
    throw new Error(`${fn}: out of WebAssembly memory (delete() the models and Worlds no longer needed)`);
  }
  function check(fn, rc) {
    if (rc < 0) fail(fn);
    return rc;
  }
  function writePose(slot, pose, fn, name) {
    if (!isPose(pose)) {
      throw new Error(`${fn}: ${name} must be 16 numbers (a column-major 4x4 matrix), got ${describe(pose)}`);
    }
    const heap = core.HEAPF64;
    const base = poseBase + 16 * slot;
    for (let k = 0; k < 16; ++k) heap[base + k] = pose[k];
  }
  function out(n) {
    return new Float64Array(core.HEAPF64.buffer, core._antcd_out_block(), n);
  }
  // A copy of the first n numbers of the output block (one allocation: no view in between).
  function outCopy(n) {
    if (n === 0) return EMPTY;
    const base = core._antcd_out_block() / 8;
    return core.HEAPF64.slice(base, base + n);
  }
  function number(fn, name, v, dflt) {
    if (v === undefined) return dflt;
    if (typeof v !== 'number' || Number.isNaN(v)) throw new Error(`${fn}: ${name} must be a number, got ${describe(v)}`);
    return v;
  }
  function modelOf(fn, name, m) {
    if (!(m instanceof Model) || m.id === null) {
      throw new Error(`${fn}: ${name} must be a live antcd Model${m instanceof Model ? ' (it was deleted)' : ''}`);
    }
    return m.id;
  }
  function optionsOf(fn, opts) {
    if (opts !== undefined && (opts === null || typeof opts !== 'object')) throw new Error(`${fn}: options must be an object`);
    return opts ?? NO_OPTIONS;
  }
  // Bits of the collision flags argument: every contact, contact normals, volume (solids).
  function collisionFlags(o) {
    return (o.allContacts ? 1 : 0) | (o.contactNormals ? 2 : 0) | (o.volume ? 4 : 0);
  }
  // Whether positions (x y z per vertex: Float32Array, Float64Array or numbers) are float32; an
  // Error naming `name` for another type or a length not a multiple of 3.
  function positionsType(fn, name, positions) {
    const f32 = positions instanceof Float32Array;
    if (!(f32 || positions instanceof Float64Array || Array.isArray(positions))) {
      throw new Error(`${fn}: ${name} must be a Float32Array, Float64Array or array of numbers, got ${describe(positions)}`);
    }
    if (positions.length % 3 !== 0) throw new Error(`${fn}: ${name} has ${positions.length} numbers, not a multiple of 3`);
    return f32;
  }
  // body(pointer, f32) with the positions copied into WebAssembly memory (checked as
  // positionsType does, freed afterwards); returns body's answer.
  function withPositions(fn, name, positions, body) {
    const f32 = positionsType(fn, name, positions);
    const p = alloc(fn, name, positions.length * (f32 ? 4 : 8));
    try {
      if (f32) core.HEAPF32.set(positions, p / 4);
      else core.HEAPF64.set(positions, p / 8);
      return body(p, f32);
    } finally {
      core.freeBytes(p);
    }
  }
  function info(model) {
    check('Model', core.modelInfo(modelOf('Model', 'this', model)));
    return out(5);
  }

  /**
   * A triangle mesh with its bounding-volume hierarchy (built once). Its triangles are fixed; its
   * vertex positions change only through setVertices (a deforming mesh).
   */
  class Model {
    /**
     * positions: x y z per vertex (Float32Array, Float64Array or numbers); indices: three vertex
     * indices per triangle (Uint32Array, Uint16Array, Int32Array or numbers). options.name names
     * the model in error messages.
     */
    constructor(positions, indices, options = {}) {
      this.id = null;
      if (positions === SHAPE) {
        this.id = indices;
        return;
      }
      const name = options.name ?? 'mesh';
      const f32 = positions instanceof Float32Array;
      if (!(f32 || positions instanceof Float64Array || Array.isArray(positions))) {
        throw new Error(`Model ${name}: positions must be a Float32Array, Float64Array or array of numbers, got ${describe(positions)}`);
      }
      if (positions.length % 3 !== 0) throw new Error(`Model ${name}: positions has ${positions.length} numbers, not a multiple of 3`);
      if (!(ArrayBuffer.isView(indices) || Array.isArray(indices))) {
        throw new Error(`Model ${name}: indices must be an integer typed array or array of numbers, got ${describe(indices)}`);
      }
      if (indices.length % 3 !== 0) throw new Error(`Model ${name}: indices has ${indices.length} numbers, not a multiple of 3`);
      const nv = positions.length / 3;
      let ix = indices;
      if (!(indices instanceof Uint32Array) && !(indices instanceof Uint16Array)) {
        ix = new Uint32Array(indices.length);
        for (let k = 0; k < indices.length; ++k) {
          const v = indices[k];
          if (!Number.isInteger(v) || v < 0 || v >= nv) {
            throw new Error(`Model ${name}: indices[${k}] = ${v} is not a vertex index in [0, ${nv})`);
          }
          ix[k] = v;
        }
      }
      const posBytes = positions.length * (f32 ? 4 : 8);
      let pPos = 0;
      let pIdx = 0;
      let pName = 0;
      try {
        pPos = alloc(`Model ${name}`, 'positions', posBytes);
        pIdx = alloc(`Model ${name}`, 'indices', indices.length * 4);
        let nameLength = 0;
        [pName, nameLength] = allocString(`Model ${name}`, 'name', String(name));
        if (f32) core.HEAPF32.set(positions, pPos / 4);
        else core.HEAPF64.set(positions, pPos / 8);
        core.HEAPU32.set(ix, pIdx / 4);
        this.id = check('Model', core.modelCreate(pPos, positions.length, f32, pIdx, indices.length, pName, nameLength));
      } finally {
        for (const p of [pPos, pIdx, pName]) if (p !== 0) core.freeBytes(p);
      }
    }
    get triangleCount() { return info(this)[0]; }
    get vertexCount() { return info(this)[1]; }
    /** Closed and consistently oriented (bounds a solid): volume queries and penetration apply. */
    get isClosed() { return info(this)[2] === 1; }
    get name() { return cString(core._antcd_model_name(modelOf('Model', 'this', this))); }
    /** How much looser setVertices has made the hierarchy since it was built (1: as built). */
    get refitGrowth() { return info(this)[4]; }
    /**
     * New positions for the vertices (x y z per vertex, as many vertices as the model has; the
     * triangles are fixed): refits the hierarchy in O(n), every query then answers as on a model
     * built from the moved mesh. Throws an Error naming the problem, the model unchanged: a wrong
     * type or length, a non-finite number, a triangle of zero area at build time that has an area
     * now, a model held by a World (deform the World's object with World.setVertices, or remove
     * it from the World first), or no WebAssembly memory.
     */
    setVertices(positions) {
      const fn = 'Model.setVertices';
      const id = modelOf(fn, 'this', this);
      positionsType(fn, 'positions', positions);
      const nv = info(this)[1];
      if (positions.length !== 3 * nv) {
        throw new Error(`${fn}: positions has ${positions.length} numbers, the model has ${nv} vertices (${3 * nv})`);
      }
      withPositions(fn, 'positions', positions, (p, f32) =>
        check(fn, core.modelSetVertices(id, p, positions.length, f32)));
    }
    /** { positions: Float64Array, indices: Uint32Array } of the model's mesh. */
    mesh() {
      check('Model.mesh', core.modelMesh(modelOf('Model', 'this', this)));
      const head = out(2);
      const nv = head[0];
      const nt = head[1];
      const all = out(2 + 3 * nv + 3 * nt);
      return { positions: all.slice(2, 2 + 3 * nv), indices: Uint32Array.from(all.subarray(2 + 3 * nv)) };
    }
    /** Frees the WebAssembly memory (a World still holding the model keeps its own reference). */
    delete() {
      if (this.id !== null) {
        core.modelRelease(this.id);
        this.id = null;
      }
    }
    static box(hx, hy, hz, subdivisions = 1) { return shape('box', hx, hy, hz, subdivisions, 0); }
    static sphere(radius, slices = 32, stacks = 16) { return shape('sphere', radius, 0, 0, slices, stacks); }
    static cylinder(radius, height, slices = 32, stacks = 1) { return shape('cylinder', radius, height, 0, slices, stacks); }
    static torus(major, minor, majorSegments = 48, minorSegments = 24) {
      return shape('torus', major, minor, 0, majorSegments, minorSegments);
    }
  }
  const SHAPE = Symbol('shape');
  const SHAPE_CODES = { box: 0, sphere: 1, cylinder: 2, torus: 3 };
  function shape(kind, a, b, c, n1, n2) {
    const fn = `Model.${kind}`;
    for (const [k, v] of [['size', a], ['size', b], ['size', c]]) number(fn, k, v);
    for (const v of [n1, n2]) {
      if (!Number.isInteger(v) || v < 0 || v > 1e6) throw new Error(`${fn}: segment count ${describe(v)} is not an integer in [0, 1e6]`);
    }
    return new Model(SHAPE, check(fn, core.modelShape(SHAPE_CODES[kind], a, b, c, n1, n2)));
  }

  /** Exact collision of two posed models: { colliding, contacts } (contacts: CONTACT_STRIDE per contact, world frame). */
  function collide(a, poseA, b, poseB, opts) {
    const ca = modelOf('collide', 'a', a);
    const cb = modelOf('collide', 'b', b);
    writePose(0, poseA, 'collide', 'poseA');
    writePose(1, poseB, 'collide', 'poseB');
    const o = optionsOf('collide', opts);
    const rc = check('collide', core._antcd_collide(ca, cb, collisionFlags(o), number('collide', 'delta', o.delta, 0),
      number('collide', 'maxContacts', o.maxContacts, 0)));
    return { colliding: rc > 0, contacts: rc > 1 ? outCopy(CONTACT_STRIDE * (rc - 1)) : EMPTY };
  }

  /**
   * The verdict of collide() alone, for hot loops: no contact is copied out, nothing is allocated
   * (options as collide's; allContacts makes no difference to the verdict).
   */
  function collides(a, poseA, b, poseB, opts) {
    const ca = modelOf('collides', 'a', a);
    const cb = modelOf('collides', 'b', b);
    writePose(0, poseA, 'collides', 'poseA');
    writePose(1, poseB, 'collides', 'poseB');
    const o = optionsOf('collides', opts);
    return check('collides', core._antcd_collide(ca, cb, collisionFlags(o) & ~1, number('collides', 'delta', o.delta, 0), 0)) > 0;
  }

  /** Minimum distance between the surfaces (signed for two closed models with options.signed). */
  function distance(a, poseA, b, poseB, opts = {}) {
    const ca = modelOf('distance', 'a', a);
    const cb = modelOf('distance', 'b', b);
    writePose(0, poseA, 'distance', 'poseA');
    writePose(1, poseB, 'distance', 'poseB');
    check('distance', core._antcd_distance(ca, cb, number('distance', 'upperBound', opts.upperBound, Infinity),
      number('distance', 'absTolerance', opts.absTolerance, 0), number('distance', 'relTolerance', opts.relTolerance, 0),
      opts.signed ? 1 : 0));
    const o = out(11);
    return {
      distance: o[0], lowerBound: o[1], pointA: o.slice(2, 5), pointB: o.slice(5, 8),
      triangleA: o[8], triangleB: o[9], intersecting: (o[10] & 1) !== 0, approximate: (o[10] & 2) !== 0,
      beyondUpperBound: (o[10] & 4) !== 0,
    };
  }

  /** Continuous collision: A from poseA0 to poseA1, B from poseB0 to poseB1 over t in [0, 1]. */
  function sweep(a, poseA0, poseA1, b, poseB0, poseB1, opts = {}) {
    const ca = modelOf('sweep', 'a', a);
    const cb = modelOf('sweep', 'b', b);
    writePose(0, poseA0, 'sweep', 'poseA0');
    writePose(1, poseA1, 'sweep', 'poseA1');
    writePose(2, poseB0, 'sweep', 'poseB0');
    writePose(3, poseB1, 'sweep', 'poseB1');
    check('sweep', core.sweep(ca, cb, number('sweep', 'minSeparation', opts.minSeparation, 0),
      number('sweep', 'timeTolerance', opts.timeTolerance, 1e-6), number('sweep', 'maxIterations', opts.maxIterations, 100000)));
    return sweepRecord(out(SWEEP_STRIDE), 0);
  }
  // The sweep record at o[at] (bindings.cpp, write_sweep) as sweep()'s answer.
  function sweepRecord(o, at) {
    const flags = o[at + 4];
    return {
      hit: (flags & 1) !== 0, toi: o[at], distance: o[at + 1], motionBound: o[at + 2], iterations: o[at + 3],
      toleranceDecided: (flags & 2) !== 0, budgetExhausted: (flags & 4) !== 0,
      contact: o.slice(at + 5, at + SWEEP_STRIDE),
    };
  }

  const SHAPES = { auto: 0, convex: 1, general: 2 };
  /** Penetration depth bounds of two closed models (lower <= depth <= upper). */
  function penetration(a, poseA, b, poseB, opts = {}) {
    const ca = modelOf('penetration', 'a', a);
    const cb = modelOf('penetration', 'b', b);
    const shapeCode = SHAPES[opts.shape ?? 'auto'];
    if (shapeCode === undefined) throw new Error(`penetration: shape must be 'auto', 'convex' or 'general', got ${describe(opts.shape)}`);
    writePose(0, poseA, 'penetration', 'poseA');
    writePose(1, poseB, 'penetration', 'poseB');
    check('penetration', core.penetration(ca, cb, shapeCode, number('penetration', 'absTolerance', opts.absTolerance, 0),
      number('penetration', 'relTolerance', opts.relTolerance, 0.01),
      number('penetration', 'maxEvaluations', opts.maxEvaluations, 64)));
    const o = out(16);
    return {
      overlapping: (o[15] & 1) !== 0, exact: (o[15] & 2) !== 0, converged: (o[15] & 4) !== 0,
      lower: o[0], upper: o[1], direction: o.slice(2, 5), witness: o.slice(5, 8), pointA: o.slice(8, 11),
      pointB: o.slice(11, 14), evaluations: o[14],
    };
  }

  const SELF_STATS = ['nodePairs', 'volumeRejects', 'trianglePairs', 'adjacentPairs', 'coneCulled', 'coneTests',
    'coneCacheBytes'];
  /**
   * Triangle pairs of one model that intersect beyond their shared vertices or edge (exact):
   * { intersecting, pairs: Uint32Array (i, j per pair, i < j, sorted), degenerateTriangles, stats }.
   * options.firstOnly: stop at the first pair found.
   */
  function selfIntersections(model, opts) {
    const fn = 'selfIntersections';
    const id = modelOf(fn, 'model', model);
    const o = optionsOf(fn, opts);
    check(fn, core.selfIntersections(id, Boolean(o.firstOnly)));
    const head = out(10);
    const k = head[1];
    const d = head[2];
    const stats = {};
    SELF_STATS.forEach((name, c) => { stats[name] = head[3 + c]; });
    const all = out(10 + 2 * k + d);
    return {
      intersecting: head[0] === 1, pairs: Uint32Array.from(all.subarray(10, 10 + 2 * k)),
      degenerateTriangles: Uint32Array.from(all.subarray(10 + 2 * k)), stats,
    };
  }

  /**
   * Vertex-triangle pairs (the vertex not a corner of the triangle) and edge-edge pairs (no common
   * vertex) of one model within delta, with closest points and distances (model frame).
   */
  function selfProximity(model, delta) {
    const fn = 'selfProximity';
    const id = modelOf(fn, 'model', model);
    if (typeof delta !== 'number') throw new Error(`${fn}: delta must be a number, got ${describe(delta)}`);
    check(fn, core.selfProximity(id, delta));
    const head = out(3);
    const [e, nvt, nee] = [head[0], head[1], head[2]];
    const all = out(3 + 2 * e + 9 * (nvt + nee));
    const edges = Uint32Array.from(all.subarray(3, 3 + 2 * e));
    const group = (first, n, pointsA) => {
      const pairs = new Uint32Array(2 * n);
      const distances = new Float64Array(n);
      const a = pointsA ? new Float64Array(3 * n) : null;
      const b = new Float64Array(3 * n);
      for (let k = 0; k < n; ++k) {
        const r = first + 9 * k;
        pairs[2 * k] = all[r];
        pairs[2 * k + 1] = all[r + 1];
        distances[k] = all[r + 2];
        if (a) a.set(all.subarray(r + 3, r + 6), 3 * k);
        b.set(all.subarray(r + 6, r + 9), 3 * k);
      }
      return { pairs, distances, a, b };
    };
    const vt = group(3 + 2 * e, nvt, false);
    const ee = group(3 + 2 * e + 9 * nvt, nee, true);
    return {
      edges, vertexTrianglePairs: vt.pairs, vertexTriangleDistances: vt.distances, vertexTrianglePoints: vt.b,
      edgeEdgePairs: ee.pairs, edgeEdgeDistances: ee.distances, edgeEdgePointsA: ee.a, edgeEdgePointsB: ee.b,
    };
  }

  const { deformSweep, collisionFreeStep, deformPair } = deformApi({
    core, alloc, check, out, outCopy, number, modelOf, optionsOf, writePose, isPose, describe, Model,
  });

  const World = worldApi({
    core, alloc, allocString, check, fail, rethrow, out, outCopy, number, modelOf, optionsOf, writePose, isPose, describe,
    positionsType, withPositions, sweepRecord, deformPair, EMPTY,
  });

  return {
    Model, World, collide, collides, distance, sweep, penetration, selfIntersections, selfProximity,
    deformSweep, collisionFreeStep,
    version: core.version(), CONTACT_STRIDE,
  };
}

function describe(v) {
  if (v === null) return 'null';
  if (Array.isArray(v)) return `an array of length ${v.length}`;
  if (ArrayBuffer.isView(v)) return `a ${v.constructor.name} of length ${v.length}`;
  if (typeof v === 'object') return 'an object';
  return `${typeof v} ${String(v).slice(0, 40)}`;
}
