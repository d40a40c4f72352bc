// GLSL: gas shadows from the core's shadow grid (`frame::shadow_grid`), the exact march's and the
// objects' material's while the exact march is drawn. The grid's columns arrive as a float
// texture BLOBS_PER_ROW texels wide (the exact march's textures' width).

import { BLOBS_PER_ROW } from '../../generated/contract.js';

/** `shadowColumn(l, x)`: ∫ρ from x towards light l, from the shadow grid; needs LIGHTS_GLSL before it. */
export const GRID_SHADOW_GLSL = /* glsl */ `
uniform sampler2D shadowTex;  // shadow columns: light-major, then z, y, x (in .x)
uniform vec3 gridMin, gridMax;
uniform int gridRes;
float fetchShadow(int i) { return texelFetch(shadowTex, ivec2(i % ${BLOBS_PER_ROW}, i / ${BLOBS_PER_ROW}), 0).x; }

// Shadow column ∫ρ towards light l from x, trilinear on the grid of the gas's bounds. Outside
// the grid the column is the one from where the path to the light enters it (no gas lies
// outside), or 0 if it never does.
float gridColumn(int l, vec3 g) {
  ivec3 i0 = min(ivec3(floor(g)), ivec3(gridRes - 2));
  vec3 f = g - vec3(i0);
  int base = l * gridRes * gridRes * gridRes;
  float v[8];
  for (int c = 0; c < 8; c++) {
    ivec3 o = ivec3(c & 1, (c >> 1) & 1, (c >> 2) & 1);
    ivec3 p = i0 + o;
    v[c] = fetchShadow(base + (p.z * gridRes + p.y) * gridRes + p.x);
  }
  float x00 = mix(v[0], v[1], f.x), x10 = mix(v[2], v[3], f.x);
  float x01 = mix(v[4], v[5], f.x), x11 = mix(v[6], v[7], f.x);
  return mix(mix(x00, x10, f.y), mix(x01, x11, f.y), f.z);
}

float shadowColumn(int l, vec3 x) {
  float top = float(gridRes - 1);
  vec3 scale = top / (gridMax - gridMin);
  vec3 g = (x - gridMin) * scale;
  if (all(greaterThanEqual(g, vec3(0.0))) && all(lessThanEqual(g, vec3(top)))) return gridColumn(l, g);
  // Enter the grid's box along the path towards the light (slab test in grid units).
  vec3 d = (lightType[l] == 0 ? lightVec[l] - x : lightVec[l]) * scale;
  float sMax = lightType[l] == 0 ? 1.0 : 1e30;
  vec3 inv = 1.0 / d;
  vec3 t0 = (vec3(0.0) - g) * inv, t1 = (vec3(top) - g) * inv;
  float near = max(max(min(t0.x, t1.x), min(t0.y, t1.y)), max(min(t0.z, t1.z), 0.0));
  float far = min(min(max(t0.x, t1.x), max(t0.y, t1.y)), min(max(t0.z, t1.z), sMax));
  if (near > far) return 0.0;
  return gridColumn(l, clamp(g + d * near, vec3(0.0), vec3(top)));
}
`;
