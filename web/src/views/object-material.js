// The opaque objects' material: Lambert shading shadowed by the gas, as DESIGN §4 defines it —
// colour ⊙ Σ_k max(0, n·l_k) S_k L_k, with S_k from the same shadow grid the ray march uses
// (its uniforms are shared, so both always see the same frame).

import * as THREE from 'three';
import { SHADOW_GLSL } from './raymarch-layer.js';

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
out vec4 fragColor;
${SHADOW_GLSL}
void main() {
  vec3 n = normalize(vNormal) * (gl_FrontFacing ? 1.0 : -1.0);
  vec3 x = vWorld + n * 1e-4;
  vec3 lit = vec3(0.0);
  for (int l = 0; l < 4; l++) {
    if (l >= lightCount) break;
    vec3 toLight = lightType[l] == 0 ? normalize(lightVec[l] - x) : lightVec[l];
    float c = max(dot(n, toLight), 0.0);
    if (c > 0.0) lit += c * exp(-kappa * shadowColumn(l, x)) * lightColor[l];
  }
  // Linear into the ray march's target; the canvas's encoding when drawn directly.
  fragColor = linearToOutputTexel(vec4(baseColor * lit, 1.0));
}
`;

/**
 * A material of linear colour `color` whose lights and gas shadows come from `shared` (the ray
 * march's uniforms).
 */
export function shadowedLambert(color, shared) {
  const uniforms = { baseColor: { value: new THREE.Vector3().fromArray(color) } };
  for (const name of ['shadowTex', 'gridMin', 'gridMax', 'gridRes', 'hasShadows', 'lightCount', 'lightType', 'lightVec', 'lightColor', 'kappa']) {
    uniforms[name] = shared[name];
  }
  return new THREE.ShaderMaterial({ glslVersion: THREE.GLSL3, vertexShader, fragmentShader, uniforms, side: THREE.DoubleSide });
}
