// GLSL: gas shadows from the real-time view's light volume (`frame::light_volume` in the core),
// the volume march's and the objects' material's while the volume view is drawn.

import { VOXEL_GRID_GLSL } from './voxel-grid.js';

/**
 * `volumeColumn(l, x, toLight, dist)`: ∫ρ ds from x towards light l; `boxSpan(x, d, sMax)`: the
 * part of a ray inside the density grid's box. Brings the voxel grid's GLSL with it.
 */
export const VOLUME_SHADOW_GLSL = /* glsl */ `
${VOXEL_GRID_GLSL}
uniform sampler3D lightVolume;
uniform Grid grid;
uniform Grid lightGrid;
uniform float columnScale; // the light volume holds ∫ρ ds · columnScale

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
  return sampleVolume(lightVolume, lightGrid, x)[l] / columnScale;
}
`;
