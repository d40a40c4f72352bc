// GLSL: the lights and the medium every gas-aware shader shares (paper Appendix B: the
// extinction κ_t of Eqs. 23 and 28, the phase function p of Eq. 25), over the uniforms of
// `views/gas-uniforms.js`: at most VIEW_LIGHTS lights, κ_t, the phase function, and the output
// encoding.

import { VIEW_LIGHTS } from '../../generated/contract.js';

/** Declarations and helpers: lights, κ_t, the phase function, the output encoding. */
export const LIGHTS_GLSL = /* glsl */ `
uniform int lightCount;
uniform int lightType[${VIEW_LIGHTS}];  // 0 point, 1 directional
uniform vec3 lightVec[${VIEW_LIGHTS}];  // position, or unit vector towards the light
uniform vec3 lightColor[${VIEW_LIGHTS}];
uniform vec3 extinction;               // κ_t per channel
uniform bool hasShadows;
uniform int phaseType;                 // 0 isotropic, 1 Henyey-Greenstein
uniform float phaseG;
uniform bool srgb;

// p(cos θ), cos θ = D·l (docs/FORMATS.md: isotropic p ≡ 1).
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
