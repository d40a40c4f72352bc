// GLSL: the wind u = u_l + u_s (paper Eq. 3) frozen at one time, read from a wind table the core
// writes (`gas::wind::WindFrame::write_gpu_table`; layout in the generated contract) and the
// small-scale field's raw lattice: quadrilinear and periodic in (x, y, z, t) on the lattice
// (§3; the world mapping of docs/FORMATS.md: lattice point q = (x − offset)·cells per metre, velocity times
// the scale), then each large-scale primitive (uniform, source or sink, vortex, repulsor, each
// with its exponential decay). `tests/gpu_steps.rs` in the core holds this same arithmetic,
// written out in Rust, to the core's own wind.

import { REPULSOR_KIND, SOURCE_KIND, VORTEX_KIND, WIND_TABLE_HEADER, WIND_TABLE_PRIMITIVE } from '../generated/contract.js';

/** Texels (RGBA32F) of a wind table's header, and per primitive. */
export const HEADER_TEXELS = WIND_TABLE_HEADER / 4;
export const PRIMITIVE_TEXELS = WIND_TABLE_PRIMITIVE / 4;

/**
 * `vec3 wind(int row, vec3 x)`: the wind (m/s) at `x` (m) from row `row` of `windTable` (row 0
 * the step's start, row 1 its middle). `lattice` holds the field's points (xyz, then 0), point
 * ((t·nz + z)·ny + y)·nx + x at texel (index mod `latticeWidth`, index / `latticeWidth`).
 */
export const WIND_GLSL = /* glsl */ `
uniform highp sampler2D windTable;
uniform highp sampler2D lattice;
uniform ivec4 latticeSize;
uniform int latticeWidth;

vec4 tableTexel(int row, int i) { return texelFetch(windTable, ivec2(i, row), 0); }

vec3 latticePoint(ivec3 c, int t) {
  ivec3 n = latticeSize.xyz;
  // The periodic wrap (GLSL's % is undefined for negative operands).
  ivec3 w = clamp(c - n * ivec3(floor(vec3(c) / vec3(n))), ivec3(0), n - 1);
  int index = ((t * n.z + w.z) * n.y + w.y) * n.x + w.x;
  return texelFetch(lattice, ivec2(index % latticeWidth, index / latticeWidth), 0).xyz;
}

vec3 smallScale(int row, vec3 x) {
  vec4 slices = tableTexel(row, 0);
  vec3 q = (x - tableTexel(row, 1).xyz) * tableTexel(row, 2).xyz;
  vec3 scale = tableTexel(row, 3).xyz;
  vec3 fl = floor(q);
  vec3 f = q - fl;
  ivec3 c = ivec3(fl);
  int t0 = int(slices.y);
  int t1 = int(slices.z);
  vec3 e[4];
  for (int k = 0; k < 4; k++) {
    ivec3 o = ivec3(0, k & 1, k >> 1);
    vec3 a0 = latticePoint(c + o, t0);
    vec3 a1 = latticePoint(c + o + ivec3(1, 0, 0), t0);
    vec3 corner0 = (a0 + (latticePoint(c + o, t1) - a0) * slices.w) * scale;
    vec3 corner1 = (a1 + (latticePoint(c + o + ivec3(1, 0, 0), t1) - a1) * slices.w) * scale;
    e[k] = corner0 + (corner1 - corner0) * f.x;
  }
  vec3 lo = e[0] + (e[1] - e[0]) * f.y;
  vec3 hi = e[2] + (e[3] - e[2]) * f.y;
  return lo + (hi - lo) * f.z;
}

vec3 primitiveWind(int row, int j, vec3 x) {
  int at = ${HEADER_TEXELS} + ${PRIMITIVE_TEXELS} * j;
  vec4 head = tableTexel(row, at);
  vec3 origin = tableTexel(row, at + 1).xyz;
  vec3 p = tableTexel(row, at + 2).xyz;
  vec3 q = tableTexel(row, at + 3).xyz;
  float kind = head.x;
  float a = head.z;
  float b = head.w;
  vec3 r = x - p;
  vec3 u;
  if (kind == ${SOURCE_KIND.toFixed(1)}) {
    float d2 = dot(r, r) + b;
    u = r * (a / (d2 * sqrt(d2)));
  } else if (kind == ${VORTEX_KIND.toFixed(1)}) {
    vec3 c = cross(q, r);
    u = c * (a / (dot(c, c) + b));
  } else if (kind == ${REPULSOR_KIND.toFixed(1)}) {
    float d = length(r);
    vec3 n = d > 1e-6 ? r / d : vec3(0.0, 1.0, 0.0);
    if (d < a) {
      u = q + n * b;
    } else {
      float s = a / d;
      u = (n * (3.0 * dot(q, n)) - q) * (0.5 * s * s * s) + n * (b * s * s);
    }
  } else {
    u = p;
  }
  return head.y > 0.0 ? u * exp(-length(x - origin) * head.y) : u;
}

vec3 wind(int row, vec3 x) {
  vec4 constant = tableTexel(row, 4);
  vec3 u = constant.xyz;
  if (tableTexel(row, 0).x > 0.5) u += smallScale(row, x);
  int n = int(constant.w);
  for (int j = 0; j < n; j++) u += primitiveWind(row, j, x);
  return u;
}
`;
