// What both GPU marches share: a full-screen quad, the uniforms of the camera's rays, and the
// opaque pass (colour and depth) the gas is composited over. Their shaders start with
// `shaders/march-preamble.js`, which reads these uniforms.

import * as THREE from 'three';
import { ScreenPass } from './screen-pass.js';

export class MarchQuad extends ScreenPass {
  /** @param {string} fragmentShader GLSL 3 (from `MARCH_PREAMBLE` on) @param {object} uniforms its own */
  constructor(fragmentShader, uniforms) {
    super(fragmentShader, {
      ...uniforms,
      opaqueColor: { value: null }, opaqueDepth: { value: null }, hasOpaque: { value: false },
      resolution: { value: new THREE.Vector2(1, 1) },
      camPos: { value: new THREE.Vector3() }, camForward: { value: new THREE.Vector3() },
      camRight: { value: new THREE.Vector3() }, camUp: { value: new THREE.Vector3() },
      tanHalf: { value: 1 }, camNear: { value: 0.01 }, camFar: { value: 100 },
      background: { value: new THREE.Vector3() },
    });
  }

  /** Camera basis (`SceneView.viewBasis()`), image size and background. */
  setView(view, width, height, background) {
    const u = this.material.uniforms;
    u.resolution.value.set(width, height);
    u.camPos.value.fromArray(view.position);
    u.camForward.value.fromArray(view.forward);
    u.camRight.value.fromArray(view.right);
    u.camUp.value.fromArray(view.up);
    u.tanHalf.value = view.tanHalf;
    u.background.value.fromArray(background);
  }

  /** Binds the opaque pass (colour and depth targets) and its camera's clip planes. */
  setOpaque(target, near, far) {
    const u = this.material.uniforms;
    u.hasOpaque.value = Boolean(target);
    u.opaqueColor.value = target?.texture ?? null;
    u.opaqueDepth.value = target?.depthTexture ?? null;
    u.camNear.value = near;
    u.camFar.value = far;
  }
}
