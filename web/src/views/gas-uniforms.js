// Uniforms every gas-aware shader shares (the exact march, the real-time view, the objects'
// material): the lights, the medium's extinction and phase function, and where gas shadows come
// from. One object of {value} holders, owned by the view; each material spreads it into its own
// uniforms, so all of them always see the same frame.

import * as THREE from 'three';

export const MAX_LIGHTS = 4;

/** Declarations and helpers: lights, κ_t, the phase function, the output encoding. */
export const LIGHTS_GLSL = /* glsl */ `
uniform int lightCount;
uniform int lightType[${MAX_LIGHTS}];  // 0 point, 1 directional
uniform vec3 lightVec[${MAX_LIGHTS}];  // position, or unit vector towards the light
uniform vec3 lightColor[${MAX_LIGHTS}];
uniform vec3 kappa;                    // extinction κ_t per channel
uniform bool hasShadows;
uniform int phaseType;                 // 0 isotropic, 1 Henyey-Greenstein
uniform float phaseG;
uniform bool srgb;

// p(cos θ), cos θ = D·l (DESIGN §4: isotropic p ≡ 1).
float phase(float c) {
  if (phaseType == 0) return 1.0;
  float g = phaseG;
  return (1.0 - g * g) / pow(1.0 + g * g - 2.0 * g * c, 1.5);
}

// Unit vector from x towards light l and the distance to it (1e30 if directional).
vec3 towardsLight(int l, vec3 x, out float dist) {
  if (lightType[l] == 0) {
    vec3 r = lightVec[l] - x;
    dist = length(r);
    return r / max(dist, 1e-9);
  }
  dist = 1e30;
  return lightVec[l];
}

vec3 encode(vec3 v) {
  v = clamp(v, 0.0, 1.0);
  if (!srgb) return v;
  return mix(12.92 * v, 1.055 * pow(v, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), v));
}
`;

/** Fresh holders for the shared uniforms. */
export function gasUniforms() {
  return {
    lightCount: { value: 0 },
    lightType: { value: new Array(MAX_LIGHTS).fill(0) },
    lightVec: { value: Array.from({ length: MAX_LIGHTS }, () => new THREE.Vector3()) },
    lightColor: { value: Array.from({ length: MAX_LIGHTS }, () => new THREE.Vector3()) },
    kappa: { value: new THREE.Vector3(1, 1, 1) },
    hasShadows: { value: false },
    phaseType: { value: 0 },
    phaseG: { value: 0 },
    srgb: { value: true },
    // Where gas shadows come from: 0 none, 1 the exact march's shadow grid, 2 the light volume.
    shadowSource: { value: 0 },
  };
}

/** Sets the lights (at most MAX_LIGHTS) and the medium (extinction, phase) of DESIGN §4. */
export function setLights(u, lights, medium) {
  const k = Array.isArray(medium.extinction) ? medium.extinction : [medium.extinction, medium.extinction, medium.extinction];
  u.kappa.value.fromArray(k);
  const used = lights.slice(0, MAX_LIGHTS);
  u.lightCount.value = used.length;
  used.forEach((l, i) => {
    u.lightType.value[i] = l.type === 'point' ? 0 : 1;
    if (l.type === 'point') u.lightVec.value[i].fromArray(l.position);
    else u.lightVec.value[i].fromArray(l.direction).normalize().negate();
    u.lightColor.value[i].fromArray(l.color);
  });
  u.phaseType.value = medium.phase?.type === 'henyey-greenstein' ? 1 : 0;
  u.phaseG.value = medium.phase?.g ?? 0;
}
