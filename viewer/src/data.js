// Reads the page's "antcd-view/1" description and its binary blob (see apps/antcd/view_page.hpp)
// and answers per-frame questions about the results: which pairs collide, where two results differ.

function decodeBase64(text) {
  const binary = atob(text.replace(/\s+/g, ''));
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; ++i) bytes[i] = binary.charCodeAt(i);
  return bytes.buffer;
}

async function readBlob(element) {
  if (element.dataset.src) {
    const response = await fetch(element.dataset.src);
    if (!response.ok) throw new Error(`${element.dataset.src}: HTTP ${response.status}`);
    return response.arrayBuffer();
  }
  return decodeBase64(element.textContent);
}

export async function loadView(doc) {
  const data = JSON.parse(doc.getElementById('antcd-view-data').textContent);
  if (data.format !== 'antcd-view/1') throw new Error(`unknown view format ${data.format}`);
  if (new Uint8Array(new Uint32Array([1]).buffer)[0] !== 1) {
    throw new Error('big-endian platform: the view blob is little-endian');
  }
  const buffer = await readBlob(doc.getElementById('antcd-view-blob'));
  if (buffer.byteLength !== data.blob_bytes) {
    throw new Error(`view blob has ${buffer.byteLength} bytes, expected ${data.blob_bytes}`);
  }
  const f32 = ([offset, count]) => new Float32Array(buffer, offset, count);
  const u32 = ([offset, count]) => new Uint32Array(buffer, offset, count);
  // float64 arrays (live pages) may start on a 4-byte boundary only: copied out.
  const f64 = (ref) => (ref ? new Float64Array(buffer.slice(ref[0], ref[0] + 8 * ref[1])) : null);
  const meshes = data.meshes.map((m) => ({ ...m, positions: f32(m.positions), indices: u32(m.indices), positions64: f64(m.positions64) }));
  // Deforming objects: every frame's vertices (frames x vertices x 3, scale applied, model frame);
  // live pages carry them as float64 only and the drawn float32 copy is rounded here.
  const objects = data.objects.map((o, index) => {
    const vertexFrames64 = f64(o.vertex_frames64);
    const vertexFrames = o.vertex_frames ? f32(o.vertex_frames) : vertexFrames64 && Float32Array.from(vertexFrames64);
    return { ...o, index, poses: f32(o.poses), poses64: f64(o.poses64), vertexFrames, vertexFrames64, deforming: vertexFrames !== null };
  });
  const results = data.results.map((r) => new Result(r, u32));
  const contacts = new Map((data.contacts?.frames ?? []).map((frame, k) => [frame, f32(data.contacts.points[k])]));
  return new ViewModel(data, meshes, objects, results, contacts);
}

const pairKey = (i, j) => i * 0x100000 + j;

class Result {
  constructor(r, u32) {
    Object.assign(this, r);
    this.row = new Map(r.frames.map((frame, k) => [frame, k]));
    this.keys = r.pairs.map((pairs) => new Set(pairs.map(([i, j]) => pairKey(i, j))));
    // Per frame: object index -> its self pair's intersecting triangle pairs (a, b, a, b, ...).
    this.self = (r.self_triangles ?? []).map((list) => new Map(list.map(([object, ref]) => [object, u32(ref)])));
  }
  selfTrianglesAt(frame) { const k = this.row.get(frame); return (k === undefined ? null : this.self[k]) ?? new Map(); }
  covers(frame) { return this.row.has(frame); }
  pairsAt(frame) { const k = this.row.get(frame); return k === undefined ? null : this.pairs[k]; }
  timeAt(frame) { const k = this.row.get(frame); return k === undefined ? null : this.time_ms[k]; }
  candidatesAt(frame) { const k = this.row.get(frame); return k === undefined ? null : this.candidates[k]; }
  has(frame, i, j) { const k = this.row.get(frame); return k !== undefined && this.keys[k].has(pairKey(i, j)); }
  // Continuous results: the pairs of a frame with their first time of impact over the step from
  // the previous frame (0: previous frame, 1: this one) and the contact point there.
  touchesAt(frame) {
    const k = this.row.get(frame);
    if (k === undefined || !this.toi) return [];
    return this.pairs[k].map(([i, j], n) => ({ i, j, toi: this.toi[k][n], point: this.touch_points[k][n] }));
  }
}

// Pair classes of a frame: 'collide' (reported, and with two results reported by both), 'false'
// (reported by the second result only: a false alarm against the first), 'miss' (first only).
export class ViewModel {
  constructor(data, meshes, objects, results, contacts) {
    this.frames = data.frames;
    this.live = data.live === true;
    this.contacts = contacts; // frame -> flat xyz of exact contact points (world frame)
    this.scene = data.scene;
    this.colours = data.colours;
    this.meshes = meshes;
    this.objects = objects;
    this.results = results;
    this.totals = this.#countDifferences();
  }

  pose(object, frame) {
    const n = object.poses.length / 12;
    const k = n === 1 ? 0 : frame;
    return object.poses.subarray(k * 12, k * 12 + 12);
  }

  // A deforming object's vertices of `frame` (scaled, model frame), or null for a rigid one.
  vertices(object, frame) {
    if (!object.deforming) return null;
    const n = this.meshes[object.mesh].vertices * 3;
    return object.vertexFrames.subarray(frame * n, frame * n + n);
  }

  vertices64(object, frame) {
    if (!object.vertexFrames64) return null;
    const n = this.meshes[object.mesh].vertices * 3;
    return object.vertexFrames64.subarray(frame * n, frame * n + n);
  }

  // Self pairs' triangle pairs of the frame: object index -> Uint32Array (a, b per pair), from
  // the first result that has the object's self pair there.
  selfTriangles(frame) {
    const out = new Map();
    for (const r of this.results) {
      for (const [object, pairs] of r.selfTrianglesAt(frame)) if (!out.has(object)) out.set(object, pairs);
    }
    return out;
  }

  contactsAt(frame) {
    return this.contacts.get(frame) ?? new Float32Array(0);
  }

  // First touches of the frame (continuous results; with two, the first result's for a pair both
  // report), sorted by (toi, i, j).
  firstTouches(frame) {
    const seen = new Set();
    const out = [];
    for (const r of this.results) {
      for (const t of r.touchesAt(frame)) {
        if (seen.has(pairKey(t.i, t.j))) continue;
        seen.add(pairKey(t.i, t.j));
        out.push(t);
      }
    }
    return out.sort((a, b) => a.toi - b.toi || a.i - b.i || a.j - b.j);
  }

  compared(frame) {
    return this.results.length === 2 && this.results[0].covers(frame) && this.results[1].covers(frame);
  }

  classify(frame) {
    const out = [];
    if (this.compared(frame)) {
      const [ref, other] = this.results;
      for (const [i, j] of ref.pairsAt(frame)) out.push({ i, j, kind: other.has(frame, i, j) ? 'collide' : 'miss' });
      for (const [i, j] of other.pairsAt(frame)) if (!ref.has(frame, i, j)) out.push({ i, j, kind: 'false' });
    } else {
      const seen = new Set();
      for (const r of this.results) {
        for (const [i, j] of r.pairsAt(frame) ?? []) {
          if (seen.has(pairKey(i, j))) continue;
          seen.add(pairKey(i, j));
          out.push({ i, j, kind: 'collide' });
        }
      }
    }
    out.sort((a, b) => a.i - b.i || a.j - b.j);
    return out;
  }

  #countDifferences() {
    const totals = { compared: 0, falseAlarms: 0, misses: 0 };
    if (this.results.length !== 2) return totals;
    for (const frame of this.results[0].frames) {
      if (!this.compared(frame)) continue;
      totals.compared += 1;
      for (const p of this.classify(frame)) {
        if (p.kind === 'false') totals.falseAlarms += 1;
        if (p.kind === 'miss') totals.misses += 1;
      }
    }
    return totals;
  }

  // Frames in which `index` is in a reported pair, per result.
  collidingFrames(index) {
    return this.results.map((r) =>
      r.frames.filter((frame, k) => r.pairs[k].some(([i, j]) => i === index || j === index)));
  }
}

// "3-7, 12, 20-21" from sorted frame numbers.
export function frameRanges(frames) {
  const parts = [];
  for (let k = 0; k < frames.length; ) {
    let e = k;
    while (e + 1 < frames.length && frames[e + 1] === frames[e] + 1) ++e;
    parts.push(e === k ? `${frames[k]}` : `${frames[k]}-${frames[e]}`);
    k = e + 1;
  }
  return parts.join(', ');
}
