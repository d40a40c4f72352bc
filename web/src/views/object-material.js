// The opaque objects' material: Lambert shading shadowed by the gas and by the other objects, as
// the rendering model (docs/FORMATS.md) defines it — colour ⊙ Σ_k max(0, n·l_k) S_k L_k. S_k is
// zero where an object lies between the surface and light k (an exact ray test against every
// object, `shaders/occluders.js`), else the gas's transmittance from whichever gas view is
// drawn: the exact march's shadow grid or the real-time view's light volume (the shared gas
// uniforms say which; none in the points view), so objects and gas always see the same frame.

import * as THREE from 'three';
import { VIEW_LIGHTS } from '../generated/contract.js';
import { GRID_SHADOW_GLSL } from './shaders/grid-shadow.js';
import { LIGHTS_GLSL } from './shaders/lights.js';
import { OCCLUDERS_GLSL } from './shaders/occluders.js';
import { VOLUME_SHADOW_GLSL } from './shaders/volume-shadow.js';

const vertexShader = /* glsl */ `
out vec3 vWorld;
out vec3 vNormal;
void main() {
  vec4 w = modelMatrix * vec4(position, 1.0);
  vWorld = w.xyz;
  vNormal = normalize(transpose(inverse(mat3(modelMatrix))) * normal);
  gl_Position = projectionMatrix * viewMatrix * w;
}
`;

const fragmentShader = /* glsl */ `
precision highp float;
precision highp int;
precision highp sampler2D;
in vec3 vWorld;
in vec3 vNormal;
uniform vec3 baseColor;
uniform int shadowSource;  // 0 none, 1 shadow grid, 2 light volume
out vec4 fragColor;
${LIGHTS_GLSL}
${GRID_SHADOW_GLSL}
${VOLUME_SHADOW_GLSL}
${OCCLUDERS_GLSL}
void main() {
  vec3 n = normalize(vNormal) * (gl_FrontFacing ? 1.0 : -1.0);
  vec3 x = vWorld + n * 1e-4;
  vec3 lit = vec3(0.0);
  for (int l = 0; l < ${VIEW_LIGHTS}; l++) {
    if (l >= lightCount) break;
    float dist;
    vec3 toLight = towardsLight(l, x, dist);
    float c = max(dot(n, toLight), 0.0);
    if (c == 0.0) continue;
    if (hasShadows && lightBlocked(0, x, toLight, dist)) continue;
    float column = 0.0;
    if (hasShadows && shadowSource == 1) column = shadowColumn(l, x);
    if (hasShadows && shadowSource == 2) column = volumeColumn(l, x, toLight, dist);
    lit += c * exp(-extinction * column) * lightColor[l];
  }
  // Linear into the marches' opaque target; the canvas's encoding when drawn directly.
  fragColor = linearToOutputTexel(vec4(baseColor * lit, 1.0));
}
`;

/** A material of linear colour `color` whose lights and gas shadows come from `gas`. */
export function shadowedLambert(color, gas) {
  const uniforms = { ...gas, baseColor: { value: new THREE.Vector3().fromArray(color) } };
  return new THREE.ShaderMaterial({ glslVersion: THREE.GLSL3, vertexShader, fragmentShader, uniforms, side: THREE.DoubleSide });
}
