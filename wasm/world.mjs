// The World of the npm package (wasm/src/bind_world.cpp underneath, definitions in
// include/antcd/world.hpp): objects added, moved, deformed and removed, the pair queries, and the
// continuous motion of rigid and deforming objects (sweepMotion, setMotionContinuous). Split from
// index.mjs, which hands in its helpers: the checked allocation, the output block, the argument
// checks and the record readers of sweep() and deformSweep().

const MOTION_KINDS = ['rigidSweep', 'startContact', 'deform'];
const MOTION_HEAD = 10;
const PAIR_STRIDE = 8;

/** The World class, closed over index.mjs's helpers (ctx). */
export function worldApi(ctx) {
  const {
    core, alloc, allocString, check, fail, rethrow, out, outCopy, number, modelOf, optionsOf, writePose, isPose, describe,
    positionsType, withPositions, sweepRecord, deformPair, EMPTY,
  } = ctx;
  const CONTACT_STRIDE = core.contactStride;
  const MOTION_STRIDE = core.motionStride;

  function handleOf(fn, name, v) {
    if (typeof v !== 'number') throw new Error(`${fn}: ${name} must be an object handle (a number), got ${describe(v)}`);
    return v;
  }
  // A motion record at o[at] (bind_world.cpp, write_motion) as a pair of sweepMotion's answer.
  function motionRecord(o, at) {
    const kind = MOTION_KINDS[o[at + 2]];
    return {
      a: o[at], b: o[at + 1], kind, toi: o[at + 3], toleranceDecided: o[at + 4] === 1, point: o.slice(at + 5, at + 8),
      triangles: kind === 'startContact' ? [o[at + 8], o[at + 9]] : null,
      primitive: kind === 'deform' ? deformPair(o, at + MOTION_HEAD) : null,
      sweep: kind === 'rigidSweep' ? sweepRecord(o, at + MOTION_HEAD + PAIR_STRIDE) : null,
    };
  }
  // sweepMotion and setMotionContinuous (method: the core's): the arguments checked, copied into
  // one checked float64 block (n handles, n poses, m handles, m coordinate counts, coordinates).
  function motion(w, fn, method, handles, poses, vertexMotions, opts) {
    if (!(Array.isArray(handles) || (ArrayBuffer.isView(handles) && !(handles instanceof DataView)))) {
      throw new Error(`${fn}: handles must be an array of object handles, got ${describe(handles)}`);
    }
    if (!Array.isArray(poses)) throw new Error(`${fn}: poses must be an array of poses (16 numbers each), got ${describe(poses)}`);
    if (poses.length !== handles.length) throw new Error(`${fn}: ${handles.length} handles but ${poses.length} poses`);
    const motions = vertexMotions ?? [];
    if (!Array.isArray(motions)) {
      throw new Error(`${fn}: vertexMotions must be an array of { handle, positions }, got ${describe(vertexMotions)}`);
    }
    const o = optionsOf(fn, opts);
    const minSeparation = number(fn, 'minSeparation', o.minSeparation, 0);
    const timeTolerance = number(fn, 'timeTolerance', o.timeTolerance, 1e-6);
    const maxIterations = number(fn, 'maxIterations', o.maxIterations, 100000);
    const n = handles.length;
    const m = motions.length;
    for (let k = 0; k < n; ++k) {
      handleOf(fn, `handles[${k}]`, handles[k]);
      if (!isPose(poses[k])) {
        throw new Error(`${fn}: poses[${k}] must be 16 numbers (a column-major 4x4 matrix), got ${describe(poses[k])}`);
      }
    }
    let coords = 0;
    motions.forEach((v, k) => {
      if (v === null || typeof v !== 'object') throw new Error(`${fn}: vertexMotions[${k}] must be { handle, positions }, got ${describe(v)}`);
      handleOf(fn, `vertexMotions[${k}].handle`, v.handle);
      positionsType(fn, `vertexMotions[${k}].positions`, v.positions);
      coords += v.positions.length;
    });
    const p = alloc(fn, 'handles, poses and positions', 8 * (17 * n + 2 * m + coords));
    try {
      const heap = core.HEAPF64;
      let at = p / 8;
      for (let k = 0; k < n; ++k) heap[at + k] = handles[k];
      at += n;
      for (let k = 0; k < n; ++k, at += 16) for (let i = 0; i < 16; ++i) heap[at + i] = poses[k][i];
      motions.forEach((v, k) => {
        heap[at + k] = v.handle;
        heap[at + m + k] = v.positions.length;
      });
      at += 2 * m;
      for (const v of motions) {
        heap.set(v.positions, at);
        at += v.positions.length;
      }
      const count = check(fn, w[method](p, n, m, minSeparation, timeTolerance, maxIterations));
      const all = outCopy(MOTION_STRIDE * count);
      const pairs = [];
      for (let k = 0; k < count; ++k) pairs.push(motionRecord(all, MOTION_STRIDE * k));
      return pairs;
    } finally {
      core.freeBytes(p);
    }
  }

  /** A live set of posed objects; handles are numbers. */
  class World {
    constructor() {
      try {
        this.core = new core.World();
      } catch (e) {
        rethrow('World', e);
      }
    }
    #live(fn) {
      if (this.core === null) throw new Error(`${fn}: the World was deleted`);
      return this.core;
    }
    /**
     * Adds a model at a pose; options: name, group, mask, selfCollision (collideAll and the
     * continuous motion also test the object against itself), rebuildAbove (setVertices rebuilds
     * the object's hierarchy when its refit has grown looser than this; 0: never). Returns the
     * object's handle.
     */
    add(model, pose, options) {
      const fn = 'World.add';
      const w = this.#live(fn);
      const m = modelOf(fn, 'model', model);
      const o = optionsOf(fn, options);
      const group = number(fn, 'group', o.group, 1);
      const mask = number(fn, 'mask', o.mask, 4294967295);
      const rebuildAbove = number(fn, 'rebuildAbove', o.rebuildAbove, 0);
      writePose(0, pose, fn, 'pose');
      const [pName, nameLength] = allocString(fn, 'name', String(o.name ?? ''));
      try {
        const h = w.add(m, pName, nameLength, group, mask, Boolean(o.selfCollision), rebuildAbove);
        if (h < 0) fail(fn);
        return h;
      } finally {
        core.freeBytes(pName);
      }
    }
    remove(handle) {
      const fn = 'World.remove';
      check(fn, this.#live(fn).remove(handleOf(fn, 'handle', handle)));
    }
    setPose(handle, pose) {
      const fn = 'World.setPose';
      const w = this.#live(fn);
      writePose(0, pose, fn, 'pose');
      check(fn, w.setPose(handleOf(fn, 'handle', handle)));
    }
    /**
     * New model-frame positions for a deforming object's vertices (x y z per vertex, its vertex
     * count; the triangles are fixed). The first call copies the object's Model (the Model given
     * to add() is never changed), later ones refit that copy. An Error naming the problem leaves
     * the object unchanged.
     */
    setVertices(handle, positions) {
      const fn = 'World.setVertices';
      const w = this.#live(fn);
      const h = handleOf(fn, 'handle', handle);
      withPositions(fn, 'positions', positions, (p, f32) =>
        check(fn, w.setVertices(h, p, positions.length, f32)));
    }
    get size() { return this.#live('World.size').size(); }
    /**
     * Every colliding pair: { pairs: Float64Array (a, b handles; a === b: a self pair),
     * contactCounts, contacts, selfPairCounts, selfPairs: Uint32Array (i, j triangle pairs) }.
     */
    collideAll(opts) {
      const fn = 'World.collideAll';
      const w = this.#live(fn);
      const o = optionsOf(fn, opts);
      const n = check(fn, w.collideAll(Boolean(o.allContacts), number(fn, 'delta', o.delta, 0),
        Boolean(o.contactNormals), number(fn, 'maxContacts', o.maxContacts, 0)));
      const head = out(4 * n);
      const pairs = new Float64Array(2 * n);
      const contactCounts = new Uint32Array(n);
      const selfPairCounts = new Uint32Array(n);
      let total = 0;
      let self = 0;
      for (let k = 0; k < n; ++k) {
        pairs[2 * k] = head[4 * k];
        pairs[2 * k + 1] = head[4 * k + 1];
        contactCounts[k] = head[4 * k + 2];
        selfPairCounts[k] = head[4 * k + 3];
        total += contactCounts[k];
        self += selfPairCounts[k];
      }
      const first = 4 * n + CONTACT_STRIDE * total;
      const all = out(first + 2 * self);
      return {
        pairs, contactCounts, contacts: total === 0 ? EMPTY : all.slice(4 * n, first), selfPairCounts,
        selfPairs: Uint32Array.from(all.subarray(first)),
      };
    }
    /** Pairs whose meshes are within `d` of each other: Float64Array of (a, b) handles. */
    pairsWithin(d) {
      const w = this.#live('World.pairsWithin');
      const n = check('World.pairsWithin', w.pairsWithin(number('World.pairsWithin', 'distance', d)));
      return outCopy(2 * n);
    }
    /** Nearest hit of the ray origin + s * direction, 0 <= s <= maxDistance, or null. */
    raycast(origin, direction, maxDistance = Infinity) {
      const w = this.#live('World.raycast');
      for (const [name, v] of [['origin', origin], ['direction', direction]]) {
        if (!((Array.isArray(v) || ArrayBuffer.isView(v)) && v.length === 3)) {
          throw new Error(`World.raycast: ${name} must be 3 numbers, got ${describe(v)}`);
        }
      }
      const hit = check('World.raycast', w.raycast(origin[0], origin[1], origin[2], direction[0], direction[1],
        direction[2], number('World.raycast', 'maxDistance', maxDistance)));
      if (hit === 0) return null;
      const o = out(9);
      return { object: o[0], triangle: o[1], distance: o[2], point: o.slice(3, 6), normal: o.slice(6, 9) };
    }
    /**
     * Continuous motion over t in [0, 1] (World::sweep_motion): handles[k] moves to poses[k], each
     * vertexMotions[k] = { handle, positions } deforms to its new model-frame positions (world
     * vertices move linearly); the others stay. Every pair (a === b: a self pair) that comes
     * within minSeparation, sorted by (a, b), with its first time of impact. The World is not
     * changed. options: minSeparation (0), timeTolerance (1e-6), maxIterations (100000).
     */
    sweepMotion(handles, poses, vertexMotions, options) {
      const fn = 'World.sweepMotion';
      return motion(this.#live(fn), fn, 'sweepMotion', handles, poses, vertexMotions, options);
    }
    /** sweepMotion(), then the new poses and positions applied; on an Error nothing changes. */
    setMotionContinuous(handles, poses, vertexMotions, options) {
      const fn = 'World.setMotionContinuous';
      return motion(this.#live(fn), fn, 'setMotionContinuous', handles, poses, vertexMotions, options);
    }
    delete() {
      if (this.core !== null) {
        this.core.delete();
        this.core = null;
      }
    }
  }
  return World;
}
