// GLSL of the real-time view's ray march: the light volume read at any point (objects included),
// and the march through the density volume with jittered steps, leaping over empty bricks.

import { GRID_GLSL } from './glsl.js';
import { BRICK_GLSL } from './occupancy-pass.js';
import { MAX_LIGHTS } from '../gas-uniforms.js';

/** Gas shadows from the light volume: `volumeColumn(l, x)`, ∫ρ ds from x towards light l. */
export const VOLUME_SHADOW_GLSL = /* glsl */ `
${GRID_GLSL}
uniform sampler3D lightVolume;
uniform Grid grid;
uniform Grid lightGrid;

// The part [near, far] of the ray x + s·d, 0 ≤ s ≤ sMax, inside the density grid's box (slab
// test); near > far if it misses.
vec2 boxSpan(vec3 x, vec3 d, float sMax) {
  vec3 inv = 1.0 / d;
  vec3 a = (grid.lo - x) * inv;
  vec3 b = (grid.lo + grid.h * vec3(grid.dims) - x) * inv;
  vec3 tMin = min(a, b);
  vec3 tMax = max(a, b);
  return vec2(max(max(tMin.x, tMin.y), max(tMin.z, 0.0)), min(min(tMax.x, tMax.y), min(tMax.z, sMax)));
}

// Inside the density grid's box, the light volume at x; outside, where the path to the light
// enters the box (no gas lies outside), or 0 if it never does.
float volumeColumn(int l, vec3 x, vec3 toLight, float toLightDistance) {
  vec3 hi = grid.lo + grid.h * vec3(grid.dims);
  if (any(lessThan(x, grid.lo)) || any(greaterThan(x, hi))) {
    vec2 span = boxSpan(x, toLight, toLightDistance);
    if (span.x > span.y) return 0.0;
    x += toLight * span.x;
  }
  return sampleVolume(lightVolume, lightGrid, x)[l];
}
`;

export const MAX_MARCH_STEPS = 1024;

/**
 * The march: front-to-back compositing of the voxel density (DESIGN §4 on the volume). Samples
 * sit at s0 + (k + j)·ds; where a brick holds no gas the march goes on at the first such sample
 * past the brick, so it takes the same samples wherever there is gas as a march without leaps.
 */
export const MARCH_GLSL = /* glsl */ `
${BRICK_GLSL}
uniform sampler3D densityVolume;
uniform sampler3D sourceVolume;
uniform bool emissive;
uniform float stepScale;

// Interleaved gradient noise: a fixed jitter per pixel in [0, 1).
float jitter(vec2 px) {
  return fract(52.9829189 * fract(dot(px, vec2(0.06711056, 0.00583715))));
}

// Composites the gas along camPos + s·rd for s in [0, sMax) onto (rad, T).
void marchVolume(vec3 camPos, vec3 rd, float sMax, inout vec3 rad, inout vec3 T) {
  vec2 span = boxSpan(camPos, rd, sMax);
  float s0 = span.x;
  float s1 = span.y;
  if (s1 <= s0) return;
  float ds = stepScale * grid.h;
  float j = jitter(gl_FragCoord.xy);
  float k = 0.0;
  for (int n = 0; n < ${MAX_MARCH_STEPS}; n++, k += 1.0) {
    float s = s0 + (k + j) * ds;
    if (s >= s1) break;
    vec3 x = camPos + rd * s;
    vec3 lo, hi;
    if (emptyBrick(x, lo, hi)) {
      float past = s + exitDistance(x, rd, lo, hi);
      k = max(k, ceil((past - s0) / ds - j) - 1.0);
      continue;
    }
    vec4 d = sampleVolume(densityVolume, grid, x);
    if (d.x <= 0.0) continue;
    vec3 absorbed = 1.0 - exp(-kappa * (d.x * ds));
    vec3 albedo = d.yzw / d.x;
    vec3 L = vec3(0.0);
    for (int l = 0; l < ${MAX_LIGHTS}; l++) {
      if (l >= lightCount) break;
      float dist;
      vec3 toLight = towardsLight(l, x, dist);
      vec3 S = hasShadows ? exp(-kappa * volumeColumn(l, x, toLight, dist)) : vec3(1.0);
      L += phase(dot(rd, toLight)) * S * lightColor[l];
    }
    vec3 C = albedo * L;
    if (emissive) C += sampleVolume(sourceVolume, grid, x).rgb / d.x;
    rad += T * absorbed * C;
    T *= 1.0 - absorbed;
    if (max(T.r, max(T.g, T.b)) < 1e-4) break;
  }
}
`;
