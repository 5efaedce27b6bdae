// Types of the npm package `antcd` (index.mjs). Frames, units and guarantees are those of the C++
// library (include/antcd/collide.hpp, distance.hpp, sweep.hpp, penetration.hpp, deform_ccd.hpp,
// world.hpp):
// contact points, normals and closest points are in the WORLD frame; distances in mesh units.

/** A column-major 4x4 rigid matrix (three.js Matrix4.elements): rotation (orthonormal within
 * 1e-6, determinant +1), translation in elements 12..14, last row 0 0 0 1. */
export type Pose = ArrayLike<number>;
export type Vec3Like = ArrayLike<number>;

/** Contact records, CONTACT_STRIDE numbers each: triangleA, triangleB, point x y z, distance,
 * normal x y z (from B towards A; zero unless contactNormals), depth. */
export const CONTACT_STRIDE: 10;

export interface CollideOptions {
  /** false (default): stop at the first contact. true: every colliding triangle pair. */
  allContacts?: boolean;
  /** Collision threshold in mesh units (>= 0): surfaces within delta collide. */
  delta?: number;
  /** Fill each contact's normal and depth. */
  contactNormals?: boolean;
  /** With allContacts: stop after this many (0: no limit). */
  maxContacts?: number;
  /** Two closed models also collide when one lies wholly inside the other. */
  volume?: boolean;
}

export interface CollideResult {
  colliding: boolean;
  contacts: Float64Array;
}

export interface DistanceOptions {
  upperBound?: number;
  absTolerance?: number;
  relTolerance?: number;
  /** Signed distance of two closed models (negative: minus the penetration depth). */
  signed?: boolean;
}

export interface DistanceResult {
  distance: number;
  /** A proven lower bound of the true distance. */
  lowerBound: number;
  pointA: Float64Array;
  pointB: Float64Array;
  triangleA: number;
  triangleB: number;
  intersecting: boolean;
  approximate: boolean;
  beyondUpperBound: boolean;
}

export interface SweepOptions {
  minSeparation?: number;
  timeTolerance?: number;
  maxIterations?: number;
}

export interface SweepResult {
  hit: boolean;
  /** Time of impact in [0, 1] (conservative: never after the true first contact). */
  toi: number;
  distance: number;
  motionBound: number;
  iterations: number;
  toleranceDecided: boolean;
  budgetExhausted: boolean;
  /** One contact record (CONTACT_STRIDE numbers) at toi. */
  contact: Float64Array;
}

export interface PenetrationOptions {
  shape?: 'auto' | 'convex' | 'general';
  absTolerance?: number;
  relTolerance?: number;
  maxEvaluations?: number;
}

export interface PenetrationResult {
  overlapping: boolean;
  exact: boolean;
  converged: boolean;
  /** Certified bounds: lower <= depth <= upper. */
  lower: number;
  upper: number;
  direction: Float64Array;
  witness: Float64Array;
  pointA: Float64Array;
  pointB: Float64Array;
  evaluations: number;
}

export interface SelfIntersectionStats {
  nodePairs: number;
  volumeRejects: number;
  trianglePairs: number;
  adjacentPairs: number;
  coneCulled: number;
  coneTests: number;
  coneCacheBytes: number;
}

export interface SelfIntersectionResult {
  intersecting: boolean;
  /** Intersecting triangle pairs, two indices (i < j) per pair, sorted; one pair with firstOnly. */
  pairs: Uint32Array;
  /** Triangles of exactly zero area, ascending: in no pair. */
  degenerateTriangles: Uint32Array;
  stats: SelfIntersectionStats;
}

export interface SelfProximityResult {
  /** The mesh's edges, two vertex indices (lower first) per edge, sorted. */
  edges: Uint32Array;
  /** (vertex, triangle) per pair, sorted. */
  vertexTrianglePairs: Uint32Array;
  vertexTriangleDistances: Float64Array;
  /** The point of each triangle closest to its vertex (3 numbers per pair). */
  vertexTrianglePoints: Float64Array;
  /** (a, b) indices into edges per pair, a < b, sorted. */
  edgeEdgePairs: Uint32Array;
  edgeEdgeDistances: Float64Array;
  edgeEdgePointsA: Float64Array;
  edgeEdgePointsB: Float64Array;
}

export interface DeformSweepOptions {
  /** Contact distance (>= 0, default 0). */
  minSeparation?: number;
  /** Time tolerance (> 0, default 1e-6). */
  timeTolerance?: number;
  /** Every hit primitive pair in pairs (default false: the earliest only, in pair). */
  allPairs?: boolean;
  /** Rigid b only: how far its vertices may stray from the chords followed (0: 1e-3 of its radius). */
  posePathTolerance?: number;
}

export interface DeformPair {
  kind: 'vertexFace' | 'edgeEdge';
  /** vertexFace: [vertex, triangle]; edgeEdge: [a0, a1, b0, b1] (each edge's ends ascending). */
  indices: number[];
  /** Two meshes, vertexFace: the vertex is a's (else the triangle is). */
  vertexInFirst: boolean;
  toi: number;
  toleranceDecided: boolean;
  budgetExhausted: boolean;
}

export interface DeformSweepResult {
  /** A miss is a proof that no pair comes within minSeparation over [0, 1]. */
  hit: boolean;
  /** Never later than the first contact (1 without a hit). */
  toi: number;
  /** The earliest pair's hit came from the tolerance, not from a proof. */
  toleranceDecided: boolean;
  pair: DeformPair | null;
  /** allPairs: every hit pair, sorted by toi, then kind (vertexFace first), then vertexInFirst
   * (true first), then indices; else empty. */
  pairs: DeformPair[];
  nodePairs: number;
  primitiveQueries: number;
  tasks: number;
  scratchBytes: number;
}

export interface WorldAddOptions {
  /** Named in error messages. */
  name?: string;
  group?: number;
  mask?: number;
  /** collideAll and the continuous motion also test the object against itself (self pairs,
   * a === b; groups, masks and delta do not apply to them). */
  selfCollision?: boolean;
  /** setVertices rebuilds the object's hierarchy when its refit grew looser than this (>= 0;
   * 0: never, refit only). */
  rebuildAbove?: number;
}

export interface CollideAllResult {
  /** (a, b) handles per colliding pair, sorted; a === b: a self pair. */
  pairs: Float64Array;
  /** Contact records per pair (0 for a self pair), in contacts in pair order. */
  contactCounts: Uint32Array;
  contacts: Float64Array;
  /** Intersecting triangle pairs per pair (0 for two objects), in selfPairs in pair order. */
  selfPairCounts: Uint32Array;
  /** (i, j) triangle indices per self triangle pair, i < j, sorted per pair (selfIntersections'). */
  selfPairs: Uint32Array;
}

/** New model-frame positions of a deforming object at t = 1 (x y z per vertex, its count). */
export interface VertexMotion {
  handle: number;
  positions: Float32Array | Float64Array | number[];
}

export interface MotionOptions {
  /** Contact distance (>= 0, default 0). */
  minSeparation?: number;
  /** Time tolerance (> 0, default 1e-6). */
  timeTolerance?: number;
  /** Iteration budget of a rigid pair's sweep (>= 1, default 100000). */
  maxIterations?: number;
}

/** A pair of a continuous motion that comes within minSeparation (include/antcd/world.hpp,
 * MotionToi). */
export interface MotionToi {
  /** Handles, a <= b; a === b: a self pair. */
  a: number;
  b: number;
  /** rigidSweep: two rigid objects (sweep); startContact: a pair with a deforming object, or a
   * self pair, already in contact at t = 0 (toi 0); deform: deformSweep found it (primitive). */
  kind: 'rigidSweep' | 'startContact' | 'deform';
  /** Never later than the first contact. */
  toi: number;
  toleranceDecided: boolean;
  /** World point at toi (for display; the certified numbers are toi and the pair). */
  point: Float64Array;
  /** startContact: [triangle of a, triangle of b] (a self pair: i < j); else null. */
  triangles: [number, number] | null;
  /** deform: the primitive pair, a's mesh first; else null. */
  primitive: DeformPair | null;
  /** rigidSweep: sweep()'s answer for the pair; else null. */
  sweep: SweepResult | null;
}

export interface RayHit {
  object: number;
  triangle: number;
  distance: number;
  point: Float64Array;
  normal: Float64Array;
}

export declare class Model {
  /** Throws an Error naming the problem (bad array, index out of range, non-finite coordinate,
   * no triangle of non-zero area). */
  constructor(positions: Float32Array | Float64Array | number[],
              indices: Uint32Array | Uint16Array | Int32Array | number[], options?: { name?: string });
  readonly triangleCount: number;
  readonly vertexCount: number;
  readonly isClosed: boolean;
  readonly name: string;
  /** How much looser setVertices has made the hierarchy since it was built (1: as built). */
  readonly refitGrowth: number;
  mesh(): { positions: Float64Array; indices: Uint32Array };
  /**
   * New vertex positions (3 numbers per vertex, the same count; triangles fixed): refits the
   * hierarchy in O(n). Throws an Error naming the problem, the model unchanged (wrong type or
   * length, non-finite number, a zero-area-at-build triangle gaining an area, a model held by a
   * World: deform the World's object with World.setVertices instead, no WebAssembly memory).
   */
  setVertices(positions: Float32Array | Float64Array | number[]): void;
  /** Frees the model (Worlds holding it keep their own reference). */
  delete(): void;
  static box(hx: number, hy: number, hz: number, subdivisions?: number): Model;
  static sphere(radius: number, slices?: number, stacks?: number): Model;
  static cylinder(radius: number, height: number, slices?: number, stacks?: number): Model;
  static torus(major: number, minor: number, majorSegments?: number, minorSegments?: number): Model;
}

export declare class World {
  constructor();
  /** Returns the object's handle (a number). */
  add(model: Model, pose: Pose, options?: WorldAddOptions): number;
  remove(handle: number): void;
  setPose(handle: number, pose: Pose): void;
  /**
   * New model-frame positions of an object's vertices (its vertex count; triangles fixed): a
   * deforming object. The first call copies the object's Model (the one given to add() is never
   * changed), later ones refit the copy in O(n). Throws an Error naming the problem, the object
   * unchanged (wrong type or count, non-finite number, a zero-area-at-build triangle gaining an
   * area, a removed handle, no WebAssembly memory).
   */
  setVertices(handle: number, positions: Float32Array | Float64Array | number[]): void;
  readonly size: number;
  /** Colliding pairs and self pairs sorted by handle. */
  collideAll(options?: CollideOptions): CollideAllResult;
  /**
   * Continuous motion over t in [0, 1]: handles[k] moves to poses[k] (rigid), vertexMotions[k]'s
   * object deforms (its world vertices move linearly to poses'/its pose applied to the new
   * positions); the others stay. Every pair and self pair that comes within minSeparation,
   * sorted by (a, b). The World is not changed.
   */
  sweepMotion(handles: ArrayLike<number>, poses: Pose[], vertexMotions?: VertexMotion[],
              options?: MotionOptions): MotionToi[];
  /** sweepMotion, then the new poses and positions applied (every argument is checked first). */
  setMotionContinuous(handles: ArrayLike<number>, poses: Pose[], vertexMotions?: VertexMotion[],
                      options?: MotionOptions): MotionToi[];
  /** Pairs whose meshes are within d: (a, b) handles, sorted. */
  pairsWithin(d: number): Float64Array;
  raycast(origin: Vec3Like, direction: Vec3Like, maxDistance?: number): RayHit | null;
  delete(): void;
}

export interface Antcd {
  Model: typeof Model;
  World: typeof World;
  collide(a: Model, poseA: Pose, b: Model, poseB: Pose, options?: CollideOptions): CollideResult;
  /** collide()'s verdict alone: nothing copied out or allocated (for hot loops). */
  collides(a: Model, poseA: Pose, b: Model, poseB: Pose, options?: CollideOptions): boolean;
  distance(a: Model, poseA: Pose, b: Model, poseB: Pose, options?: DistanceOptions): DistanceResult;
  sweep(a: Model, poseA0: Pose, poseA1: Pose, b: Model, poseB0: Pose, poseB1: Pose,
        options?: SweepOptions): SweepResult;
  penetration(a: Model, poseA: Pose, b: Model, poseB: Pose, options?: PenetrationOptions): PenetrationResult;
  /** Triangle pairs of one model that intersect beyond their shared vertices or edge (exact). */
  selfIntersections(model: Model, options?: { firstOnly?: boolean }): SelfIntersectionResult;
  /** Vertex-triangle and edge-edge pairs of one model within delta (>= 0). */
  selfProximity(model: Model, delta: number): SelfProximityResult;
  /**
   * Continuous collision of a deforming mesh a (vertex i from a0 to a1, x y z per vertex): against
   * itself, against a second deforming model b (b0, b1 its positions) or against a rigid b moving
   * between two poses (b0, b1 poses).
   */
  deformSweep(a: Model, a0: Float64Array, a1: Float64Array, options?: DeformSweepOptions): DeformSweepResult;
  deformSweep(a: Model, a0: Float64Array, a1: Float64Array, b: Model, b0: Float64Array, b1: Float64Array,
              options?: DeformSweepOptions): DeformSweepResult;
  deformSweep(a: Model, a0: Float64Array, a1: Float64Array, b: Model, poseB0: Pose, poseB1: Pose,
              options?: DeformSweepOptions): DeformSweepResult;
  /** The collision-free step (IPC): no self pair closer than minSeparation over [0, step]. */
  collisionFreeStep(model: Model, v0: Float64Array, v1: Float64Array, minSeparation: number,
                    options?: { timeTolerance?: number }): number;
  version: string;
  CONTACT_STRIDE: 10;
}

/** Loads the WebAssembly module (options.wasmBinary: the .wasm bytes, else read beside the
 * package's index.mjs). */
export default function createAntcd(options?: { wasmBinary?: ArrayBuffer | Uint8Array }): Promise<Antcd>;
