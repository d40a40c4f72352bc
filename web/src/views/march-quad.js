// What both GPU marches share: a full-screen quad, the camera's rays, and the opaque pass
// (colour and depth) the gas is composited over.

import * as THREE from 'three';

/**
 * The start of a march's fragment shader: precisions, the quad's `vUv` in, `outColor` out, and
 * `viewRay(uv, rd, sMax, behind)`: the pixel's ray, where the opaque pass ends it, what lies there.
 */
export const MARCH_PREAMBLE = /* glsl */ `
precision highp float;
precision highp int;
precision highp sampler2D;
in vec2 vUv;
out vec4 outColor;
uniform sampler2D opaqueColor;
uniform sampler2D opaqueDepth;
uniform bool hasOpaque;
uniform vec2 resolution;
uniform vec3 camPos, camForward, camRight, camUp;
uniform float tanHalf, camNear, camFar;
uniform vec3 background;

void viewRay(vec2 uv, out vec3 rd, out float sMax, out vec3 behind) {
  vec2 ndc = gl_FragCoord.xy / resolution * 2.0 - 1.0;
  float aspect = resolution.x / resolution.y;
  rd = normalize(camForward + camRight * ndc.x * tanHalf * aspect + camUp * ndc.y * tanHalf);
  behind = background;
  sMax = 1e30;
  if (hasOpaque) {
    float d = texture(opaqueDepth, uv).x;
    if (d < 1.0) {
      float zN = d * 2.0 - 1.0;
      float viewZ = 2.0 * camNear * camFar / (camFar + camNear - zN * (camFar - camNear));
      sMax = viewZ / dot(rd, camForward);
      behind = texture(opaqueColor, uv).rgb;
    }
  }
}
`;

const vertexShader = /* glsl */ `
out vec2 vUv;
void main() { vUv = uv; gl_Position = vec4(position.xy, 0.0, 1.0); }
`;

export class MarchQuad {
  /** @param {string} fragmentShader GLSL 3 (from MARCH_PREAMBLE on) @param {object} uniforms its own */
  constructor(fragmentShader, uniforms) {
    this.material = new THREE.ShaderMaterial({
      glslVersion: THREE.GLSL3,
      vertexShader,
      fragmentShader,
      depthTest: false,
      depthWrite: false,
      uniforms: {
        ...uniforms,
        opaqueColor: { value: null }, opaqueDepth: { value: null }, hasOpaque: { value: false },
        resolution: { value: new THREE.Vector2(1, 1) },
        camPos: { value: new THREE.Vector3() }, camForward: { value: new THREE.Vector3() },
        camRight: { value: new THREE.Vector3() }, camUp: { value: new THREE.Vector3() },
        tanHalf: { value: 1 }, camNear: { value: 0.01 }, camFar: { value: 100 },
        background: { value: new THREE.Vector3() },
      },
    });
    const quad = new THREE.Mesh(new THREE.PlaneGeometry(2, 2), this.material);
    quad.frustumCulled = false;
    this.scene = new THREE.Scene();
    this.scene.add(quad);
    this.ortho = new THREE.OrthographicCamera(-1, 1, 1, -1, 0, 1);
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

  render(renderer) {
    renderer.render(this.scene, this.ortho);
  }
}
