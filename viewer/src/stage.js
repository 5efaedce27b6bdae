// The three.js side: one mesh per scene object, posed per frame, coloured by its mesh file, with
// the pairs of the current frame highlighted; orbit camera; WebXR (VR) session support.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { VRButton } from 'three/examples/jsm/webxr/VRButton.js';

export const KIND_COLOURS = {
  collide: 0xe0201b, // reported (by both results when there are two)
  false: 0xff9800, // false alarm: the second result only
  miss: 0x1e6bff, // miss: the first result only
};
// First-touch markers of continuous results.
export const TOUCH_COLOUR = 0xd81b9c;
// The intersecting triangles of a self pair (an object touching itself).
export const SELF_COLOUR = 0xffc400;
// An object in several pairs shows the most telling class: a miss, else a true collision.
const KIND_PRIORITY = { miss: 3, collide: 2, false: 1 };

function meshColour(index, count) {
  const colour = new THREE.Color();
  // Spread hues evenly, skipping the highlight hues' neighbourhoods is not needed: highlighted
  // objects also get an emissive glow and a pair line.
  colour.setHSL((index / Math.max(1, count)) * 0.85 + 0.4, 0.25, 0.62);
  return colour;
}

export class Stage {
  constructor(container, model) {
    this.model = model;
    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(window.devicePixelRatio);
    this.renderer.xr.enabled = true;
    container.appendChild(this.renderer.domElement);

    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0xf4f5f7);
    this.world = new THREE.Group(); // moved and scaled as a whole in VR
    this.scene.add(this.world);
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x8090a0, 1.6));
    const sun = new THREE.DirectionalLight(0xffffff, 1.8);
    sun.position.set(1, 2, 1.5);
    this.scene.add(sun);

    const geometries = model.meshes.map((m) => {
      const g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.BufferAttribute(m.positions, 3));
      g.setIndex(new THREE.BufferAttribute(m.indices, 1));
      g.computeVertexNormals();
      g.computeBoundingBox();
      return g;
    });
    this.objects = model.objects.map((o) => {
      const base = meshColour(model.meshes[o.mesh].colour, model.colours);
      // Deforming objects are sheets, seen from both sides.
      const material = new THREE.MeshStandardMaterial({ color: base, roughness: 0.7, metalness: 0.05, flatShading: true, side: o.deforming ? THREE.DoubleSide : THREE.FrontSide });
      // A deforming object draws its own copy of the mesh, its positions replaced every frame.
      let geometry = geometries[o.mesh];
      if (o.deforming) {
        geometry = new THREE.BufferGeometry();
        geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(model.meshes[o.mesh].positions), 3));
        geometry.setIndex(geometries[o.mesh].getIndex());
      }
      const mesh = new THREE.Mesh(geometry, material);
      mesh.matrixAutoUpdate = false;
      mesh.userData = { index: o.index, base };
      this.world.add(mesh);
      return mesh;
    });

    this.pairLines = new THREE.LineSegments(
      new THREE.BufferGeometry(),
      new THREE.LineBasicMaterial({ vertexColors: true, depthTest: false, transparent: true }));
    this.pairLines.renderOrder = 10;
    this.world.add(this.pairLines);
    this.contacts = new THREE.Points(
      new THREE.BufferGeometry(),
      new THREE.PointsMaterial({ color: 0x111111, size: 5, sizeAttenuation: false, depthTest: false }));
    this.contacts.renderOrder = 11;
    this.world.add(this.contacts);
    // Continuous results: where each pair first touched between the previous frame and this one.
    this.touches = new THREE.Points(
      new THREE.BufferGeometry(),
      new THREE.PointsMaterial({ color: TOUCH_COLOUR, size: 11, sizeAttenuation: false, depthTest: false }));
    this.touches.renderOrder = 12;
    this.world.add(this.touches);

    // Self pairs: their intersecting triangles (world frame), drawn over the object.
    this.selfOverlay = new THREE.Mesh(
      new THREE.BufferGeometry(),
      new THREE.MeshBasicMaterial({ color: SELF_COLOUR, side: THREE.DoubleSide, polygonOffset: true, polygonOffsetFactor: -2, polygonOffsetUnits: -4 }));
    this.selfOverlay.renderOrder = 9;
    this.world.add(this.selfOverlay);

    this.camera = new THREE.PerspectiveCamera(45, 1, 0.01, 1000);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.enableDamping = true;
    this.raycaster = new THREE.Raycaster();
    this.selected = -1;
    this.overrides = new Map(); // object index -> THREE.Matrix4 replacing the scene's pose (live page)
    // Deforming objects: object index -> positions (scaled, model frame) replacing the scene's
    // vertices of the frame (live page: the dragged sheet).
    this.vertexOverrides = new Map();
    this.drawnFrame = new Map(); // deforming object index -> the positions last drawn
  }

  // Deforming object `index`'s drawn positions to `positions` (float32 or float64, model frame).
  // `key` (the frame, or the override array) skips the update when those are drawn already.
  setVertices(index, positions, key = positions) {
    const g = this.objects[index].geometry;
    if (this.drawnFrame.get(index) === key) return;
    this.drawnFrame.set(index, key);
    g.attributes.position.array.set(positions);
    g.attributes.position.needsUpdate = true;
    g.computeVertexNormals();
    g.computeBoundingBox();
    g.computeBoundingSphere();
  }

  // Frames the camera on the objects as posed in `frame`.
  fit(frame) {
    this.setPoses(frame);
    const box = new THREE.Box3();
    for (const m of this.objects) box.expandByObject(m);
    const sphere = box.getBoundingSphere(new THREE.Sphere());
    const r = Math.max(sphere.radius, 1e-6);
    this.bounds = { box, sphere };
    this.camera.near = r / 1000;
    this.camera.far = r * 100;
    // Look across the longer horizontal side of the scene, from a little above, far enough for
    // the whole box to fit the view (production lines are long and narrow).
    const half = box.getSize(new THREE.Vector3()).multiplyScalar(0.5);
    const alongX = half.x >= half.z;
    const [wide, deep] = alongX ? [half.x, half.z] : [half.z, half.x];
    const tan = Math.tan(THREE.MathUtils.degToRad(this.camera.fov / 2));
    const distance = Math.max(wide / (tan * this.camera.aspect), Math.max(half.y, deep) / tan) * 1.1 + deep;
    const dir = alongX ? new THREE.Vector3(0.15, 0.55, 1) : new THREE.Vector3(1, 0.55, 0.15);
    this.camera.position.copy(sphere.center).add(dir.normalize().multiplyScalar(Math.max(distance, r * 0.1)));
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(sphere.center);
    this.controls.update();
    const grid = new THREE.GridHelper(r * 3, 30, 0xb0b4ba, 0xd6d9dd);
    grid.position.set(sphere.center.x, box.min.y, sphere.center.z);
    this.world.add(grid);
  }

  setPoses(frame) {
    for (const m of this.objects) {
      const p = this.model.pose(this.model.objects[m.userData.index], frame);
      const own = this.overrides.get(m.userData.index);
      if (own) m.matrix.copy(own);
      else m.matrix.set(p[0], p[1], p[2], p[9], p[3], p[4], p[5], p[10], p[6], p[7], p[8], p[11], 0, 0, 0, 1);
      m.matrixWorldNeedsUpdate = true;
      const o = this.model.objects[m.userData.index];
      if (o.deforming) {
        const own = this.vertexOverrides.get(o.index);
        if (own) this.setVertices(o.index, own);
        else this.setVertices(o.index, this.model.vertices(o, frame), frame);
      }
    }
    this.world.updateMatrixWorld(true);
  }

  // Poses the objects, highlights `pairs` ({i, j, kind}; i === j: a self pair), draws `contacts`
  // (flat xyz), the first-touch points of `touches` ({point: [x, y, z]}) and the intersecting
  // triangles of the self pairs (`selfTriangles`: object index -> triangle pairs a, b, ...).
  show(frame, pairs, contacts, touches = [], selfTriangles = new Map()) {
    this.setPoses(frame);
    const kindOf = new Map();
    for (const p of pairs) {
      for (const k of [p.i, p.j]) {
        if ((KIND_PRIORITY[kindOf.get(k)] ?? 0) < KIND_PRIORITY[p.kind]) kindOf.set(k, p.kind);
      }
    }
    for (const m of this.objects) {
      const kind = kindOf.get(m.userData.index);
      const mat = m.material;
      if (kind) {
        mat.color.set(KIND_COLOURS[kind]);
        mat.emissive.set(KIND_COLOURS[kind]).multiplyScalar(0.35);
      } else {
        mat.color.copy(m.userData.base);
        mat.emissive.set(0x000000);
      }
      if (m.userData.index === this.selected) mat.emissive.set(0x444444);
    }
    const centre = (k) => {
      const m = this.objects[k];
      return m.geometry.boundingBox.getCenter(new THREE.Vector3()).applyMatrix4(m.matrix);
    };
    const points = [];
    const colours = [];
    for (const p of pairs) {
      if (p.i === p.j) continue; // a self pair: its triangles are drawn instead
      const c = new THREE.Color(KIND_COLOURS[p.kind]);
      for (const v of [centre(p.i), centre(p.j)]) {
        points.push(v.x, v.y, v.z);
        colours.push(c.r, c.g, c.b);
      }
    }
    const lines = this.pairLines.geometry;
    lines.setAttribute('position', new THREE.Float32BufferAttribute(points, 3));
    lines.setAttribute('color', new THREE.Float32BufferAttribute(colours, 3));
    lines.computeBoundingSphere();
    this.contacts.geometry.setAttribute('position', new THREE.BufferAttribute(contacts, 3));
    this.contacts.geometry.computeBoundingSphere();
    this.touches.geometry.setAttribute('position', new THREE.Float32BufferAttribute(touches.flatMap((t) => t.point), 3));
    this.touches.geometry.computeBoundingSphere();
    this.#drawSelf(selfTriangles);
  }

  // The triangles of each self pair (both of every pair, each once), in the world frame.
  #drawSelf(selfTriangles) {
    const xyz = [];
    const v = new THREE.Vector3();
    for (const [index, pairs] of selfTriangles) {
      const m = this.objects[index];
      const position = m.geometry.attributes.position;
      const corners = m.geometry.getIndex().array;
      for (const t of new Set(pairs)) {
        for (let c = 0; c < 3; ++c) {
          v.fromBufferAttribute(position, corners[3 * t + c]).applyMatrix4(m.matrix);
          xyz.push(v.x, v.y, v.z);
        }
      }
    }
    this.selfOverlay.geometry.setAttribute('position', new THREE.Float32BufferAttribute(xyz, 3));
    this.selfOverlay.geometry.computeBoundingSphere();
  }

  // The object under a canvas pixel, or -1.
  pick(clientX, clientY) {
    const rect = this.renderer.domElement.getBoundingClientRect();
    const ndc = new THREE.Vector2(((clientX - rect.left) / rect.width) * 2 - 1, -((clientY - rect.top) / rect.height) * 2 + 1);
    this.raycaster.setFromCamera(ndc, this.camera);
    const hit = this.raycaster.intersectObjects(this.objects, false)[0];
    return hit ? hit.object.userData.index : -1;
  }

  resize(width, height) {
    this.renderer.setSize(width, height, false);
    this.camera.aspect = width / Math.max(1, height);
    this.camera.updateProjectionMatrix();
  }

  // The "Enter VR" button (WebXR). In a headset the scene is scaled to about 4 m across and put
  // in front of the viewer, feet on the floor; leaving VR restores the desktop view.
  vrButton() {
    const button = VRButton.createButton(this.renderer);
    this.renderer.xr.addEventListener('sessionstart', () => {
      const { sphere, box } = this.bounds;
      const s = 2 / Math.max(sphere.radius, 1e-6);
      this.world.scale.setScalar(s);
      this.world.position.set(-sphere.center.x * s, -box.min.y * s, -sphere.center.z * s - 2.5);
    });
    this.renderer.xr.addEventListener('sessionend', () => {
      this.world.scale.setScalar(1);
      this.world.position.set(0, 0, 0);
    });
    return button;
  }

  start(onFrame) {
    this.renderer.setAnimationLoop((time) => {
      onFrame(time);
      this.controls.update();
      this.renderer.render(this.scene, this.camera);
    });
  }
}
