// What both GPU marches share: a full-screen quad, the camera's rays, and the opaque pass
// (colour and depth) the gas is composited over.

import * as THREE from 'three';
import { ScreenPass } from './screen-pass.js';

/**
 * The start of a march's fragment shader: precisions, the quad's `vUv` in, `outColor` out,
 * `behindAt(uv, depth)`: what the opaque pass left at uv and its depth (1 where it drew nothing),
 * and `viewRay(uv, rd, sMax, behind)`: the pixel's ray, where the opaque pass ends it, what lies there.
 */
export const MARCH_PREAMBLE = /* glsl */ `
precision highp float;
precision highp int;
precision highp sampler2D;
in vec2 vUv;
layout(location = 0) out vec4 outColor;
uniform sampler2D opaqueColor;
uniform sampler2D opaqueDepth;
uniform bool hasOpaque;
uniform vec2 resolution;
uniform vec3 camPos, camForward, camRight, camUp;
uniform float tanHalf, camNear, camFar;
uniform vec3 background;

vec3 behindAt(vec2 uv, out float depth) {
  depth = hasOpaque ? texture(opaqueDepth, uv).x : 1.0;
  return depth < 1.0 ? texture(opaqueColor, uv).rgb : background;
}

// Distance (m) along the view axis of an opaque-pass depth d < 1.
float viewDepth(float d) {
  float zN = d * 2.0 - 1.0;
  return 2.0 * camNear * camFar / (camFar + camNear - zN * (camFar - camNear));
}

void viewRay(vec2 uv, out vec3 rd, out float sMax, out vec3 behind) {
  vec2 ndc = gl_FragCoord.xy / resolution * 2.0 - 1.0;
  float aspect = resolution.x / resolution.y;
  rd = normalize(camForward + camRight * ndc.x * tanHalf * aspect + camUp * ndc.y * tanHalf);
  float d;
  behind = behindAt(uv, d);
  sMax = d < 1.0 ? viewDepth(d) / dot(rd, camForward) : 1e30;
}
`;

export class MarchQuad extends ScreenPass {
  /** @param {string} fragmentShader GLSL 3 (from MARCH_PREAMBLE on) @param {object} uniforms its own */
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
