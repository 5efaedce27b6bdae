// Deforming objects on the live page (viewer/src/live.js): each is its own WebAssembly Model,
// outside the World (a World refuses setVertices on the Models it holds), given every animation
// frame the scene's vertices of the frame with the user's bends applied.
//
// A bend (a mouse drag on the sheet) pulls the grabbed point and the sheet around it: vertex v
// (model frame) moves by offset * w(|v - anchor| / radius), w(s) = (1 - s^2)^3 for s < 1, else 0:
// 1 at the grabbed point, falling smoothly (zero slope at both ends) to 0 at `radius`, beyond
// which the sheet keeps its shape. A closed form of the scene's vertices and the drag, nothing
// integrated over time, so it cannot blow up however far or fast the sheet is dragged; bends are
// applied in order, each to the vertices the ones before it made. No stretching limit: a long
// drag stretches the sheet (and may fold it onto itself: its self-contacts light up).
// Pure functions of numbers (no three.js), so a node test can recompute them.

/** The bend radius, as a fraction of the sheet's longest extent at rest. */
export const BEND_RADIUS = 0.4;

/** Weight of a vertex at distance r from the anchor (radius R): (1 - (r/R)^2)^3 inside, else 0. */
export function bendWeight(r, radius) {
  const s = r / radius;
  if (!(s < 1)) return 0;
  const t = 1 - s * s;
  return t * t * t;
}

/**
 * Applies one bend { anchor: [x, y, z], offset: [x, y, z], radius } (model frame) to `positions`
 * (x, y, z per vertex) in place.
 */
export function applyBend(positions, { anchor, offset, radius }) {
  for (let k = 0; k < positions.length; k += 3) {
    const w = bendWeight(Math.hypot(positions[k] - anchor[0], positions[k + 1] - anchor[1], positions[k + 2] - anchor[2]), radius);
    if (w === 0) continue;
    positions[k] += offset[0] * w;
    positions[k + 1] += offset[1] * w;
    positions[k + 2] += offset[2] * w;
  }
  return positions;
}

/** The longest side of the box around `positions` (x, y, z per vertex). */
export function longestExtent(positions) {
  const lo = [Infinity, Infinity, Infinity];
  const hi = [-Infinity, -Infinity, -Infinity];
  for (let k = 0; k < positions.length; k += 3) {
    for (let c = 0; c < 3; ++c) {
      lo[c] = Math.min(lo[c], positions[k + c]);
      hi[c] = Math.max(hi[c], positions[k + c]);
    }
  }
  return Math.max(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
}

/**
 * One deforming object of the page: `view` the page's ViewModel, `object` its entry, `antcd` the
 * WebAssembly module. update(frame) gives the Model the frame's vertices with the bends (only
 * when they changed) and, for a self_collision object, asks selfIntersections.
 */
export class Sheet {
  constructor(antcd, view, object) {
    this.antcd = antcd;
    this.view = view;
    this.object = object;
    this.index = object.index;
    const mesh = view.meshes[object.mesh];
    this.model = new antcd.Model(mesh.positions64, mesh.indices, { name: object.name });
    this.radius = BEND_RADIUS * longestExtent(mesh.positions64);
    this.bends = [];
    this.version = 0; // bumped by every change of a bend
    this.built = { frame: -1, version: -1 };
    this.vertices = null; // Float64Array: the Model's current positions (a new array per change)
    this.selfPairs = null; // Uint32Array (a, b per pair) of the current vertices; null: not tested
  }

  /** A new bend at `anchor` (model frame), not displaced yet; returns it for the drag to move. */
  addBend(anchor) {
    const bend = { anchor: [...anchor], offset: [0, 0, 0], radius: this.radius };
    this.bends.push(bend);
    ++this.version;
    return bend;
  }

  /** The drag moved `bend` to `offset` (model frame). */
  moveBend(bend, offset) {
    bend.offset = [...offset];
    ++this.version;
  }

  /** The Model to `frame`'s vertices and the bends; returns true when they changed. */
  update(frame) {
    if (this.built.frame === frame && this.built.version === this.version) return false;
    const v = Float64Array.from(this.view.vertices64(this.object, frame));
    for (const b of this.bends) applyBend(v, b);
    this.model.setVertices(v);
    this.vertices = v;
    this.built = { frame, version: this.version };
    this.selfPairs = this.object.self_collision ? this.antcd.selfIntersections(this.model).pairs : null;
    return true;
  }
}
