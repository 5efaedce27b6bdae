// Grabbing objects on the live page (viewer/src/live.js) with WebXR controllers, as functions of
// the controller's matrixWorld and the scene's placement in the three.js world (stage.world's
// matrixWorld: scaled and moved in a headset), so that a test drives it without a headset.
//
// squeeze start: the object the controller's ray (its -Z axis from its origin) hits first is
//   grabbed, keeping its pose relative to the controller;
// every frame while squeezed: the object follows the controller rigidly (rotation too);
// squeeze end: the object stays where it was let go.
// Poses are column-major 4x4 rigid matrices in the scene's frame; a followed pose is made rigid
// again as the native scene loader makes a quaternion pose (rigidPose), so that a scene file
// holding its rotation_wxyz gives the native library the very same matrix.
import * as THREE from 'three';

/**
 * The rigid pose (Float64Array(16), column-major) of translation `t` and rotation quaternion `q`
 * (w, x, y, z; any length), as the native scene loader builds it: the quaternion divided by its
 * norm sqrt(w^2 + x^2 + y^2 + z^2), then Eigen's quaternion-to-matrix formula, which three.js's
 * Matrix4.compose computes with the same operations.
 */
export function rigidPose(t, [w, x, y, z]) {
  const n = Math.sqrt(w * w + x * x + y * y + z * z);
  const q = new THREE.Quaternion(x / n, y / n, z / n, w / n);
  const m = new THREE.Matrix4().compose(new THREE.Vector3(t[0], t[1], t[2]), q, new THREE.Vector3(1, 1, 1));
  return Float64Array.from(m.elements);
}

export class ControllerGrabs {
  /**
   * pick(origin, direction): the first object hit by a ray given in the three.js world
   * (the controller's frame's parent), { index } or null. poseOf(index): its current pose. onMove(index, pose, rotationWxyz): a
   * grabbed object's new pose (scene frame) and the quaternion it was made from.
   */
  constructor(pick, poseOf, onMove) {
    this.pick = pick;
    this.poseOf = poseOf;
    this.onMove = onMove;
    this.grabs = new Map(); // controller -> { index, offset: controller-to-object in the scene's frame }
    this.toScene = new THREE.Matrix4();
    this.hand = new THREE.Matrix4();
    this.position = new THREE.Vector3();
    this.rotation = new THREE.Quaternion();
    this.scale = new THREE.Vector3();
  }

  // The controller's placement in the scene's frame.
  #hand(controllerWorld, sceneWorld) {
    this.toScene.copy(sceneWorld).invert();
    return this.hand.multiplyMatrices(this.toScene, controllerWorld);
  }

  /** Squeeze start: grabs what the controller points at; returns its index or null. */
  start(controller, controllerWorld, sceneWorld) {
    const origin = new THREE.Vector3().setFromMatrixPosition(controllerWorld);
    const direction = new THREE.Vector3(0, 0, -1).transformDirection(controllerWorld);
    const hit = this.pick(origin, direction);
    if (!hit) return null;
    const offset = this.#hand(controllerWorld, sceneWorld).clone().invert()
      .multiply(new THREE.Matrix4().fromArray(this.poseOf(hit.index)));
    this.grabs.set(controller, { index: hit.index, offset });
    return hit.index;
  }

  /** Squeeze end: releases the controller's object. */
  end(controller) {
    this.grabs.delete(controller);
  }

  /** Every frame: each grabbed object to its controller's placement (worldOf(controller)). */
  follow(worldOf, sceneWorld) {
    for (const [controller, g] of this.grabs) {
      const m = this.#hand(worldOf(controller), sceneWorld).clone().multiply(g.offset);
      // Rigid again (the scaled frames leave rounding): translation and unit quaternion.
      m.decompose(this.position, this.rotation, this.scale);
      const q = this.rotation;
      const wxyz = [q.w, q.x, q.y, q.z];
      this.onMove(g.index, rigidPose(this.position.toArray(), wxyz), wxyz);
    }
  }
}
