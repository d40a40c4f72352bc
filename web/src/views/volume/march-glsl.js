// GLSL of the real-time view's ray march through the density volume with jittered steps,
// leaping over empty bricks. It follows the light volume's chunk (`../shaders/volume-shadow.js`:
// the voxel grid, `volumeColumn`), which the objects' material reads too, and the objects'
// shadows (`../shaders/occluders.js`: `lightBlocked`, row 1 + l for light l).

import { NEAR_COLUMN_STEPS, NEAR_COLUMN_VOXELS, VIEW_LIGHTS } from '../../generated/contract.js';
import { BRICK_GLSL } from './occupancy-pass.js';

const MAX_MARCH_STEPS = 1024;

/**
 * The march: the single-scattering model of paper Appendix B (Eqs. 22–28, as the CPU reference
 * `render/renderer.rs` marches it) on the voxel density: each step's transparency τ_i =
 * exp(−κ_t ρ ds) (Eq. 28 on the voxels), its source C = Ω L (+ the emitted source, Eq. 24), L
 * the lights through the phase function and their shadow transmittance S_k (Eq. 25), each
 * sample lit through `shadowColumn` (the near part of the column summed, the rest read), and
 * front-to-back compositing (Eqs. 26–27). Samples
 * sit at s0 + (k + j)·ds; where a brick holds no gas the march goes on at the first such sample
 * past the brick, so it takes the same samples wherever there is gas as a march without leaps.
 */
export const MARCH_GLSL = /* glsl */ `
${BRICK_GLSL}
uniform sampler3D densityVolume;
uniform sampler3D sourceVolume;
uniform bool emissive;
uniform float stepScale;
uniform float densityScale; // the density volume holds ρ · densityScale

// The column ∫ρ ds from x towards light l (unit d, dist away): the first NEAR_COLUMN_VOXELS
// voxels summed here through the density volume, the rest read from the light volume where
// the near part ends (frame::light_volume::march_column in the core). Read at x itself, the light volume's
// columns, stored 2h apart, would lend dense gas's lit skin the column of its inside.
float shadowColumn(int l, vec3 x, vec3 d, float dist) {
  float reach = min(${NEAR_COLUMN_VOXELS.toFixed(1)} * grid.h, dist);
  float ds = reach / ${NEAR_COLUMN_STEPS.toFixed(1)};
  float sum = 0.0;
  for (int k = 0; k < ${NEAR_COLUMN_STEPS}; k++) {
    sum += sampleVolume(densityVolume, grid, x + d * ((float(k) + 0.5) * ds)).x;
  }
  float far = reach < dist ? volumeColumn(l, x + d * reach, d, dist - reach) : 0.0;
  return sum * ds / densityScale + far;
}

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
    // 1 − τ_i (Eq. 28), the voxel's density over the step.
    vec3 absorbed = 1.0 - exp(-extinction * (d.x / densityScale * ds));
    vec3 albedo = d.yzw / d.x;
    vec3 L = vec3(0.0);
    for (int l = 0; l < ${VIEW_LIGHTS}; l++) {
      if (l >= lightCount) break;
      float dist;
      vec3 toLight = towardsLight(l, x, dist);
      if (hasShadows && lightBlocked(1 + l, x, toLight, dist)) continue;
      vec3 S = hasShadows ? exp(-extinction * shadowColumn(l, x, toLight, dist)) : vec3(1.0);
      L += phase(dot(rd, toLight)) * S * lightColor[l]; // Eq. 25
    }
    vec3 C = albedo * L; // Eq. 24
    if (emissive) C += sampleVolume(sourceVolume, grid, x).rgb / d.x;
    rad += T * absorbed * C; // Eq. 27
    T *= 1.0 - absorbed;
    if (max(T.r, max(T.g, T.b)) < 1e-4) break;
  }
}
`;
