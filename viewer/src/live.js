// antcd live page (`antcd view SCENE --live`): the scene plays; the user picks an object with the
// mouse (or squeezes a WebXR controller pointing at it) and moves it; every animation frame the
// WebAssembly build of antcd (wasm/, inlined in this bundle) poses its World and answers which
// pairs collide, and the page lights them up with their contact points.
//
// Page contract, on #antcd-viewer (besides data-objects, data-frames, data-ready, data-error):
//   data-live "true"; data-frame the scene frame shown; data-colliding JSON [[nameA, nameB], ...]
//   of the colliding pairs, names in scene order, sorted; data-query-ms the WebAssembly time of
//   the last frame (poses + collideAll), data-query-mean-ms its mean over the last 60 frames;
//   data-dragged the moved object's name. window.antcdLive: state() (frame, pairs, the moved
//   objects' poses as 16 doubles, with rotation_wxyz when a controller turned them), pause(),
//   play(), showFrame(f), poseOf(name), pickPoint(name) (a canvas point on the object, client
//   pixels), screenOf(name), queryTimes() (per animation frame since the last call), and the
//   WebXR controllers without a headset: controllerPose(c, matrix), controllerEvent(c,
//   'squeezestart' | 'squeezeend'), aimAt(name) (a controller matrix pointing at the object).
// Poses and meshes are the scene's float64 values (poses64, positions64 of the payload), so the
// answers are those of the native library at the same poses.
// Deforming objects (flexible sheets, the payload's vertex_frames64): each is its own Model outside
// the World (sheets.js), given the frame's vertices every frame; a mouse drag on one bends it
// (sheets.js: the grabbed point pulled, the sheet deformed smoothly around it; a controller's
// squeeze still moves it rigidly). It is tested against every other object with collides /
// collide, and a self_collision object against itself with selfIntersections (rigid ones once:
// their self-intersections do not depend on the pose). A self pair is [name, name] in
// data-colliding (sorted with the others), its intersecting triangles drawn over the object;
// data-self JSON [[name, trianglePairs], ...] counts them. window.antcdLive also has
// verticesOf(name) (a deforming object's current vertices, model frame, x y z per vertex, or
// null), bendsOf(name) (its bends: { anchor, offset, radius }, model frame) and state() adds
// selfTriangles [[name, [a, b, ...]], ...].
import * as THREE from 'three';

import createAntcd from '../../wasm/index.mjs';
import wasmBinary from '../../wasm/dist/antcd_core.wasm';
import { loadView } from './data.js';
import { ControllerGrabs } from './grab.js';
import { Sheet } from './sheets.js';
import { Stage } from './stage.js';

const FPS = 12;
// Contact points drawn per colliding pair: 4 keep the query near the boolean one (the traversal
// stops there), 16 cost about 2.5x as much on the paper scene (wasm/bench/scene.mjs).
const CONTACTS_PER_PAIR = 4;

// Row-major rotation + translation (12 numbers) to a column-major 4x4 (three.js order).
function columnMajor(p, out) {
  out[0] = p[0]; out[1] = p[3]; out[2] = p[6]; out[3] = 0;
  out[4] = p[1]; out[5] = p[4]; out[6] = p[7]; out[7] = 0;
  out[8] = p[2]; out[9] = p[5]; out[10] = p[8]; out[11] = 0;
  out[12] = p[9]; out[13] = p[10]; out[14] = p[11]; out[15] = 1;
  return out;
}

function posesAt(object, frame) {
  const n = object.poses64.length / 12;
  const k = n === 1 ? 0 : frame;
  return object.poses64.subarray(12 * k, 12 * k + 12);
}

function panelElement(root) {
  const el = document.createElement('div');
  el.className = 'antcd-live-panel';
  el.style.cssText = 'position:absolute;left:8px;top:8px;padding:6px 10px;background:rgba(255,255,255,.88);'
    + 'font:13px system-ui,sans-serif;border-radius:4px;pointer-events:none;white-space:pre';
  root.append(el);
  return el;
}

async function main() {
  const root = document.getElementById('antcd-viewer');
  root.style.cssText = 'position:fixed;inset:0;overflow:hidden';
  let model;
  try {
    model = await loadView(document);
    if (!model.live) throw new Error('this page has no live data (antcd view --live writes it)');
  } catch (error) {
    root.dataset.error = String(error.message ?? error);
    root.textContent = `antcd view --live: ${root.dataset.error}`;
    throw error;
  }
  root.dataset.live = 'true';
  root.dataset.objects = String(model.objects.length);
  root.dataset.frames = String(model.frames);

  const antcd = await createAntcd({ wasmBinary });
  const models = model.meshes.map((m, k) => new antcd.Model(m.positions64, m.indices, { name: m.file ?? `mesh ${k}` }));
  const world = new antcd.World();
  const scratch = new Float64Array(16);
  // Deforming objects stay out of the World: index -> Sheet (null for a rigid object).
  const sheetOf = model.objects.map((o) => (o.deforming ? new Sheet(antcd, model, o) : null));
  const sheets = sheetOf.filter((s) => s);
  const handles = model.objects.map((o, i) => (sheetOf[i] ? null : world.add(models[o.mesh], columnMajor(posesAt(o, 0), scratch), { name: o.name })));
  const indexOf = new Map(handles.map((h, i) => [h, i]).filter(([h]) => h !== null));
  const moving = model.objects.map((o) => o.poses64.length > 12);
  // Rigid self_collision objects: their self-intersections, once per mesh (pose-independent).
  const rigidSelf = new Map();
  for (const o of model.objects) {
    if (!o.self_collision || o.deforming || rigidSelf.has(o.mesh)) continue;
    rigidSelf.set(o.mesh, antcd.selfIntersections(models[o.mesh]).pairs);
  }

  const stage = new Stage(root, model);
  stage.renderer.domElement.style.cssText = 'display:block;width:100%;height:100%';
  root.append(stage.vrButton());
  const panel = panelElement(root);

  let frame = 0;
  let playing = true;
  let lastStep = 0;
  const moved = new Map(); // object index -> Float64Array(16): the user's pose, scene frame
  const rotations = new Map(); // object index -> [w, x, y, z] its moved rotation came from
  const times = [];
  const timeLog = []; // { ms, stepped } per animation frame, for queryTimes()
  let pairs = [];
  let selfTriangles = new Map(); // object index -> its self pair's triangle pairs (a, b, ...)

  const resize = () => stage.resize(root.clientWidth, root.clientHeight);
  window.addEventListener('resize', resize);
  resize();
  stage.fit(0);

  // The World's answer for the current frame and moves: poses of the objects that move (the
  // scene's, or the user's), then every colliding pair.
  let posedFrame = -1;
  const query = () => {
    const stepped = posedFrame !== frame;
    const t0 = performance.now();
    for (let i = 0; i < handles.length; ++i) {
      if (handles[i] === null) continue;
      const own = moved.get(i);
      if (own) world.setPose(handles[i], own);
      else if (moving[i] && posedFrame !== frame) world.setPose(handles[i], columnMajor(posesAt(model.objects[i], frame), scratch));
    }
    posedFrame = frame;
    const r = world.collideAll({ allContacts: true, maxContacts: CONTACTS_PER_PAIR });
    const found = sheets.length ? sheetPairs() : { pairs: [], points: [] };
    const ms = performance.now() - t0;
    times.push(ms);
    if (times.length > 60) times.shift();
    timeLog.push({ ms, stepped });
    if (timeLog.length > 10000) timeLog.shift();
    pairs = [];
    for (let k = 0; k < r.pairs.length; k += 2) {
      const i = indexOf.get(r.pairs[k]);
      const j = indexOf.get(r.pairs[k + 1]);
      pairs.push(i < j ? { i, j, kind: 'collide' } : { i: j, j: i, kind: 'collide' });
    }
    pairs.push(...found.pairs);
    selfTriangles = new Map();
    for (const o of model.objects) {
      const own = o.self_collision ? (sheetOf[o.index]?.selfPairs ?? rigidSelf.get(o.mesh)) : null;
      if (!own?.length) continue;
      pairs.push({ i: o.index, j: o.index, kind: 'collide' });
      selfTriangles.set(o.index, own);
    }
    pairs.sort((a, b) => a.i - b.i || a.j - b.j);
    const points = new Float32Array((r.contacts.length / antcd.CONTACT_STRIDE) * 3 + found.points.length);
    for (let k = 0, n = 0; k < r.contacts.length; k += antcd.CONTACT_STRIDE, n += 3) {
      points[n] = r.contacts[k + 2];
      points[n + 1] = r.contacts[k + 3];
      points[n + 2] = r.contacts[k + 4];
    }
    points.set(found.points, points.length - found.points.length);
    const mean = times.reduce((s, t) => s + t, 0) / times.length;
    root.dataset.frame = String(frame);
    root.dataset.colliding = JSON.stringify(pairs.map((p) => [model.objects[p.i].name, model.objects[p.j].name]));
    root.dataset.self = JSON.stringify([...selfTriangles].map(([i, t]) => [model.objects[i].name, t.length / 2]));
    root.dataset.queryMs = ms.toFixed(3);
    root.dataset.queryMeanMs = mean.toFixed(3);
    panel.textContent = `frame ${frame + 1}/${model.frames}${playing ? '' : ' (paused: space plays)'}\n`
      + `${model.objects.length} objects, ${pairs.length} colliding pair${pairs.length === 1 ? '' : 's'}\n`
      + `antcd (WebAssembly) query: ${ms.toFixed(2)} ms this frame, ${mean.toFixed(2)} ms mean\n`
      + `drag an object to move it${sheets.length ? ', a sheet to bend it' : ''} (VR: squeeze)`;
    for (const [i, m] of moved) stage.overrides.set(i, new THREE.Matrix4().fromArray(m));
    for (const sheet of sheets) stage.vertexOverrides.set(sheet.index, sheet.vertices);
    stage.show(frame, pairs, points, [], selfTriangles);
  };

  // The deforming objects to the frame's vertices and bends, then each against every other object
  // (each pair once) at the current poses: the pairs ({i, j, kind}) and contact points (flat xyz).
  function sheetPairs() {
    for (const sheet of sheets) sheet.update(frame);
    const poses = model.objects.map((o, i) => poseOf(i));
    const out = { pairs: [], points: [] };
    const options = { allContacts: true, maxContacts: CONTACTS_PER_PAIR };
    for (const sheet of sheets) {
      const a = sheet.index;
      for (let b = 0; b < model.objects.length; ++b) {
        if (b === a || (sheetOf[b] && b < a)) continue;
        const other = sheetOf[b]?.model ?? models[model.objects[b].mesh];
        if (!antcd.collides(sheet.model, poses[a], other, poses[b])) continue;
        const c = antcd.collide(sheet.model, poses[a], other, poses[b], options);
        out.pairs.push({ i: Math.min(a, b), j: Math.max(a, b), kind: 'collide' });
        for (let k = 0; k < c.contacts.length; k += antcd.CONTACT_STRIDE) out.points.push(c.contacts[k + 2], c.contacts[k + 3], c.contacts[k + 4]);
      }
    }
    return out;
  }

  // Picking with the World's own ray cast, in the scene's frame (stage.world is scaled in VR).
  // Deforming objects are not in the World: three.js's ray cast on their drawn meshes (the
  // current vertices, float32), the nearer hit wins.
  const toScene = new THREE.Matrix4();
  const sheetRay = new THREE.Raycaster();
  const pickRay = (origin, direction) => {
    toScene.copy(stage.world.matrixWorld).invert();
    const o = origin.clone().applyMatrix4(toScene);
    const d = direction.clone().transformDirection(toScene);
    const hit = world.size ? world.raycast([o.x, o.y, o.z], [d.x, d.y, d.z]) : null;
    let best = hit ? { index: indexOf.get(hit.object), point: new THREE.Vector3(...hit.point), distance: hit.distance } : null;
    if (sheets.length) {
      sheetRay.set(origin, direction.clone().normalize());
      const h = sheetRay.intersectObjects(sheets.map((s) => stage.objects[s.index]), false)[0];
      if (h) {
        const point = h.point.clone().applyMatrix4(toScene);
        const distance = point.distanceTo(o);
        if (!best || distance < best.distance) best = { index: h.object.userData.index, point, distance };
      }
    }
    return best;
  };
  const poseOf = (i) => moved.get(i) ?? columnMajor(posesAt(model.objects[i], frame), new Float64Array(16));

  // Mouse: drag in the plane through the picked point facing the camera; only the translation
  // changes (the rotation keeps the scene's exact values).
  let drag = null;
  const canvas = stage.renderer.domElement;
  const ndc = (e) => {
    const rect = canvas.getBoundingClientRect();
    return new THREE.Vector2(((e.clientX - rect.left) / rect.width) * 2 - 1, -((e.clientY - rect.top) / rect.height) * 2 + 1);
  };
  // Capture: before OrbitControls' own listener, which then sees itself disabled.
  canvas.addEventListener('pointerdown', (e) => {
    stage.raycaster.setFromCamera(ndc(e), stage.camera);
    const hit = pickRay(stage.raycaster.ray.origin, stage.raycaster.ray.direction);
    if (!hit) return;
    const normal = stage.camera.getWorldDirection(new THREE.Vector3());
    const pose = Float64Array.from(poseOf(hit.index));
    stage.controls.enabled = false;
    stage.selected = hit.index;
    root.dataset.dragged = model.objects[hit.index].name;
    canvas.setPointerCapture(e.pointerId);
    const sheet = sheetOf[hit.index];
    if (sheet) {
      // A sheet bends: a new bend anchored at the picked point (model frame), pulled by the drag.
      const m = new THREE.Matrix4().fromArray(pose);
      const anchor = hit.point.clone().applyMatrix4(m.clone().invert());
      drag = { index: hit.index, plane: new THREE.Plane().setFromNormalAndCoplanarPoint(normal, hit.point), start: hit.point, sheet,
               bend: sheet.addBend(anchor.toArray()), toModel: new THREE.Matrix3().setFromMatrix4(m).transpose() };
      return;
    }
    drag = { index: hit.index, plane: new THREE.Plane().setFromNormalAndCoplanarPoint(normal, hit.point), start: hit.point, t0: [pose[12], pose[13], pose[14]], pose };
    moved.set(hit.index, pose);
  }, { capture: true });
  canvas.addEventListener('pointermove', (e) => {
    if (!drag) return;
    stage.raycaster.setFromCamera(ndc(e), stage.camera);
    const p = stage.raycaster.ray.intersectPlane(drag.plane, new THREE.Vector3());
    if (!p) return;
    if (drag.sheet) {
      drag.sheet.moveBend(drag.bend, p.clone().sub(drag.start).applyMatrix3(drag.toModel).toArray());
      return;
    }
    drag.pose[12] = drag.t0[0] + (p.x - drag.start.x);
    drag.pose[13] = drag.t0[1] + (p.y - drag.start.y);
    drag.pose[14] = drag.t0[2] + (p.z - drag.start.z);
  });
  const endDrag = () => {
    drag = null;
    stage.controls.enabled = true;
  };
  canvas.addEventListener('pointerup', endDrag);
  canvas.addEventListener('pointercancel', endDrag);

  // WebXR: squeeze grabs the object the controller points at; it then follows the controller
  // rigidly (rotation too) until the squeeze ends (grab.js).
  const controllers = [0, 1].map((c) => {
    const controller = stage.renderer.xr.getController(c);
    stage.scene.add(controller);
    return controller;
  });
  const grabs = new ControllerGrabs(pickRay, poseOf, (i, pose, wxyz) => {
    moved.set(i, pose);
    rotations.set(i, wxyz);
  });
  for (const controller of controllers) {
    controller.addEventListener('squeezestart', () => {
      const i = grabs.start(controller, controller.matrixWorld, stage.world.matrixWorld);
      if (i === null) return;
      stage.selected = i;
      root.dataset.dragged = model.objects[i].name;
    });
    controller.addEventListener('squeezeend', () => grabs.end(controller));
  }
  const followControllers = () => grabs.follow((c) => c.matrixWorld, stage.world.matrixWorld);

  const setPlaying = (on) => {
    playing = on;
  };
  window.addEventListener('keydown', (e) => {
    if (e.key === ' ') {
      e.preventDefault();
      setPlaying(!playing);
    }
  });
  window.antcdLive = {
    pause: () => setPlaying(false),
    play: () => setPlaying(true),
    // Pauses on scene frame f (answered at the next animation frame).
    showFrame: (f) => {
      setPlaying(false);
      frame = Math.min(Math.max(0, Math.floor(f)), model.frames - 1);
    },
    state: () => ({
      frame,
      pairs: JSON.parse(root.dataset.colliding ?? '[]'),
      moved: [...moved].map(([i, m]) => ({ name: model.objects[i].name, pose: Array.from(m), rotation_wxyz: rotations.get(i) })),
      queryMs: Number(root.dataset.queryMs),
      selfTriangles: [...selfTriangles].map(([i, t]) => [model.objects[i].name, Array.from(t)]),
    }),
    verticesOf: (name) => {
      const sheet = sheetOf[model.objects.findIndex((o) => o.name === name)];
      return sheet ? Array.from(sheet.vertices) : null;
    },
    bendsOf: (name) => structuredClone(sheetOf[model.objects.findIndex((o) => o.name === name)]?.bends ?? null),
    // A canvas point (client pixels) whose pick ray hits object `name` first, or null.
    pickPoint: (name) => {
      const i = model.objects.findIndex((o) => o.name === name);
      if (i < 0) return null;
      const rect = canvas.getBoundingClientRect();
      const mesh = model.meshes[model.objects[i].mesh];
      const m = new THREE.Matrix4().fromArray(poseOf(i));
      const v = new THREE.Vector3();
      const n = mesh.positions64.length / 3;
      // A sheet: its current vertices (on its surface); else points between a vertex and the
      // object's centre, spread over the mesh.
      const at = sheetOf[i]?.vertices ?? mesh.positions64;
      const inward = sheetOf[i] ? 1 : 0.6;
      for (let k = 0; k < 200; ++k) {
        const a = Math.floor((k * 7919) % n);
        v.set(at[3 * a], at[3 * a + 1], at[3 * a + 2]).multiplyScalar(inward).applyMatrix4(m);
        const p = v.clone().project(stage.camera);
        if (Math.abs(p.x) > 0.95 || Math.abs(p.y) > 0.95) continue;
        const x = rect.left + ((p.x + 1) / 2) * rect.width;
        const y = rect.top + ((1 - p.y) / 2) * rect.height;
        stage.raycaster.setFromCamera(new THREE.Vector2(p.x, p.y), stage.camera);
        const hit = pickRay(stage.raycaster.ray.origin, stage.raycaster.ray.direction);
        if (hit && hit.index === i) return { x, y };
      }
      return null;
    },
    // The query time of every animation frame since the last call ({ ms, stepped: the scene
    // advanced, so its moving objects were posed }), for the frame-time benchmark.
    queryTimes: () => timeLog.splice(0),
    // Object `name`'s current pose (16 numbers, column-major, scene frame).
    poseOf: (name) => Array.from(poseOf(model.objects.findIndex((o) => o.name === name))),
    // WebXR without a headset: controller c's placement (16 numbers, column-major, in the three.js
    // world) and its events ('squeezestart', 'squeezeend'), dispatched as WebXR's would be.
    controllerPose: (c, elements) => {
      const k = controllers[c];
      k.matrixAutoUpdate = false;
      k.matrix.fromArray(elements);
      k.updateMatrixWorld(true);
    },
    controllerEvent: (c, type) => controllers[c].dispatchEvent({ type }),
    // A controller placement (three.js world) whose ray hits object `name` first, or null.
    aimAt: (name) => {
      const i = model.objects.findIndex((o) => o.name === name);
      if (i < 0) return null;
      const mesh = model.meshes[model.objects[i].mesh];
      const m = new THREE.Matrix4().fromArray(poseOf(i));
      const centre = new THREE.Vector3().setFromMatrixPosition(m);
      const n = mesh.positions64.length / 3;
      let radius = 0;
      for (let k = 0; k < n; ++k) radius = Math.max(radius, Math.hypot(mesh.positions64[3 * k], mesh.positions64[3 * k + 1], mesh.positions64[3 * k + 2]));
      const v = new THREE.Vector3();
      for (let k = 0; k < 200; ++k) {
        const a = Math.floor((k * 7919) % n);
        v.set(mesh.positions64[3 * a], mesh.positions64[3 * a + 1], mesh.positions64[3 * a + 2]).applyMatrix4(m);
        const out = v.clone().sub(centre);
        if (out.lengthSq() === 0) continue;
        out.normalize();
        for (const reach of [0.5, 1, 2]) {
          const eye = v.clone().addScaledVector(out, reach * radius).applyMatrix4(stage.world.matrixWorld);
          const target = v.clone().applyMatrix4(stage.world.matrixWorld);
          const up = Math.abs(out.y) > 0.9 ? new THREE.Vector3(1, 0, 0) : new THREE.Vector3(0, 1, 0);
          const aim = new THREE.Matrix4().lookAt(eye, target, up).setPosition(eye);
          const hit = pickRay(eye, new THREE.Vector3(0, 0, -1).transformDirection(aim));
          if (hit && hit.index === i) return aim.elements.slice();
        }
      }
      return null;
    },
    screenOf: (name) => {
      const i = model.objects.findIndex((o) => o.name === name);
      const rect = canvas.getBoundingClientRect();
      const m = poseOf(i);
      const p = new THREE.Vector3(m[12], m[13], m[14]).project(stage.camera);
      return { x: rect.left + ((p.x + 1) / 2) * rect.width, y: rect.top + ((1 - p.y) / 2) * rect.height };
    },
  };

  stage.start((time) => {
    if (playing && time - lastStep >= 1000 / FPS) {
      lastStep = time;
      frame = (frame + 1) % model.frames;
    }
    followControllers();
    query();
    if (root.dataset.ready !== 'true') requestAnimationFrame(() => { root.dataset.ready = 'true'; });
  });
}

main().catch((error) => console.error('antcd view --live:', error));
