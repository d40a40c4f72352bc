// GLSL: the wind u = u_l + u_s (paper Eq. 3) frozen at one time, read from a wind table the core
// writes (`gas::wind_table`; layout in the generated contract) and the small-scale field's raw
// lattice: quadrilinear and periodic in (x, y, z, t) on the lattice (§3; the world mapping of
// docs/FORMATS.md: lattice point q = (x − offset)·cells per metre, velocity times the scale),
// then each large-scale primitive (uniform, source or sink, vortex, repulsor, each with its
// exponential decay). With SOLIDS defined, the wind goes round the table's solid objects as the
// core's `WindFrame::parts` makes it (the field's vector potential from a second lattice,
// doublets, mirror images, the ramped curl by differences, projections) and a point that ended
// inside a solid is put back outside, each blob visiting only the solids its cell of the core's grid
// lists (and the planes); with CARRIED, the small scales are sampled at each blob's
// carried coordinates (two phases, cross-faded). `tests/gpu_steps.rs` in the core holds this
// same arithmetic, written out in Rust, to the core's own wind.

import {
  CYLINDER_SOLID_KIND, CYLINDER_ZONE_INNER, CYLINDER_ZONE_OUTER, EDGE_STEPS, PLANE_SOLID_KIND, REPULSOR_KIND,
  SOLID_GRID_HEADER, SOURCE_KIND, SPHERE_SOLID_KIND, SPHERE_ZONE_INNER, SPHERE_ZONE_OUTER, VORTEX_KIND, WIND_TABLE_HEADER, WIND_TABLE_PRIMITIVE,
  WIND_TABLE_SOLID,
} from '../generated/contract.js';

/** Texels (RGBA32F) of a wind table's header, and per primitive. */
export const HEADER_TEXELS = WIND_TABLE_HEADER / 4;
export const PRIMITIVE_TEXELS = WIND_TABLE_PRIMITIVE / 4;
export const SOLID_TEXELS = WIND_TABLE_SOLID / 4;

/** Texels (RGBA32F) of the solids' grid's header (`gas::solid_grid`). */
const SOLID_GRID_TEXELS = SOLID_GRID_HEADER / 4;

const f = (v) => (Number.isInteger(v) ? v.toFixed(1) : String(v));

/**
 * `vec3 primitiveWind(int row, int j, vec3 x)`: primitive j's wind (m/s) at `x` (m), its decay
 * with it, from row `row` of `windTable` (`tableTexel(row, i)` its texel i), and
 * `vec3 primitivesWind(int row, vec3 x)`: u_p, the scene's own primitives' (the constant wind
 * and every primitive that is not a mirror image: `WindFrame::primitive_wind`).
 */
export const PRIMITIVES_GLSL = /* glsl */ `
uniform highp sampler2D windTable;

vec4 tableTexel(int row, int i) { return texelFetch(windTable, ivec2(i, row), 0); }

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

vec3 primitivesWind(int row, vec3 x) {
  vec4 constant = tableTexel(row, 4);
  vec3 u = constant.xyz;
  int n = int(constant.w);
  for (int j = 0; j < n; j++) {
    if (tableTexel(row, ${HEADER_TEXELS} + ${PRIMITIVE_TEXELS} * j + 1).w < -0.5) u += primitiveWind(row, j, x);
  }
  return u;
}
`;

/**
 * `vec3 wind(int row, vec3 x)`: the wind (m/s) at `x` (m) from row `row` of `windTable` (row 0
 * the step's start, row 1 its middle). `lattice` holds the field's points (xyz, then 0), point
 * ((t·nz + z)·ny + y)·nx + x at texel (index mod `latticeWidth`, index / `latticeWidth`).
 */
export const WIND_GLSL = /* glsl */ `${PRIMITIVES_GLSL}
uniform highp sampler2D lattice;
uniform ivec4 latticeSize;
uniform int latticeWidth;

vec3 latticePoint(highp sampler2D tex, ivec3 c, int t) {
  ivec3 n = latticeSize.xyz;
  // The periodic wrap (GLSL's % is undefined for negative operands).
  ivec3 w = clamp(c - n * ivec3(floor(vec3(c) / vec3(n))), ivec3(0), n - 1);
  int index = ((t * n.z + w.z) * n.y + w.y) * n.x + w.x;
  return texelFetch(tex, ivec2(index % latticeWidth, index / latticeWidth), 0).xyz;
}

/** The lattice tex at world point x, times scale per component: trilinear in the blend of the two bracketing time slices. */
vec3 latticeSample(highp sampler2D tex, int row, vec3 x, vec3 scale) {
  vec4 slices = tableTexel(row, 0);
  vec3 q = (x - tableTexel(row, 1).xyz) * tableTexel(row, 2).xyz;
  vec3 fl = floor(q);
  vec3 f = q - fl;
  ivec3 c = ivec3(fl);
  int t0 = int(slices.y);
  int t1 = int(slices.z);
  vec3 e[4];
  for (int k = 0; k < 4; k++) {
    ivec3 o = ivec3(0, k & 1, k >> 1);
    vec3 a0 = latticePoint(tex, c + o, t0);
    vec3 a1 = latticePoint(tex, c + o + ivec3(1, 0, 0), t0);
    vec3 corner0 = (a0 + (latticePoint(tex, c + o, t1) - a0) * slices.w) * scale;
    vec3 corner1 = (a1 + (latticePoint(tex, c + o + ivec3(1, 0, 0), t1) - a1) * slices.w) * scale;
    e[k] = corner0 + (corner1 - corner0) * f.x;
  }
  vec3 lo = e[0] + (e[1] - e[0]) * f.y;
  vec3 hi = e[2] + (e[3] - e[2]) * f.y;
  return lo + (hi - lo) * f.z;
}

vec3 smallScale(int row, vec3 x) { return latticeSample(lattice, row, x, tableTexel(row, 3).xyz); }

vec3 wind(int row, vec3 x) {
  vec4 constant = tableTexel(row, 4);
  vec3 u = constant.xyz;
  if (tableTexel(row, 0).x > 0.5) u += smallScale(row, x);
#ifdef FLOW
  u += flowVelocity(x) * flowWeight(x);
#endif
  int n = int(constant.w);
  for (int j = 0; j < n; j++) u += primitiveWind(row, j, x);
  return u;
}
`;

/**
 * `void windParts(int row, vec3 x, vec3 oa, vec3 ob, out vec3 large, out vec3 small)`: the wind
 * at `x` in its large-scale and small-scale parts, with the carried offsets `oa`, `ob` of the
 * two phases (used with CARRIED); `windPartsAndClearance`, the same and how far x surely lies
 * from every solid; and `vec3 pushOut(int row, vec3 x)` (with SOLIDS): x put back just outside
 * a solid it lies in. The core's `WindFrame::parts`, `parts_and_clearance` and
 * `Solids::push_out`, line by line. With SOLIDS, `potentialLattice` holds the field's vector
 * potential as `lattice` its velocity, and `solidGrid` the core's grid over the solids (`gas::solid_grid`, `SolidGrid::write_gpu`:
 * a header, a texel per cell with its lists' bounds, the members four to a texel, the planes first),
 * texel i at (i mod `solidGridWidth`, i / `solidGridWidth`): a blob visits the solids its cell lists,
 * as the core's `Solids::around` has it, so a step costs about the same among 16 solids or 256.
 */
export const WIND_PARTS_GLSL = /* glsl */ `
uniform highp sampler2D potentialLattice;

vec3 blendedSample(highp sampler2D tex, int row, vec3 x, vec3 scale, vec3 oa, vec3 ob) {
#ifdef CARRIED
  vec4 w = tableTexel(row, 7);
  vec3 shift = 0.5 * vec3(latticeSize.xyz) / tableTexel(row, 2).xyz;
  vec3 u = vec3(0.0);
  if (w.x != 0.0) u += latticeSample(tex, row, x + oa, scale) * w.x;
  if (w.y != 0.0) u += latticeSample(tex, row, x + ob + shift, scale) * w.y;
  return u;
#else
  return latticeSample(tex, row, x, scale);
#endif
}

/**
 * latticeSample at the six points y of a stencil about c, the same arithmetic with the lattice
 * cell holding c fetched once (a point outside it samples on its own). The corners and the
 * interpolation are written out again rather than shared with latticeSample through small
 * functions: that split made every step half again as slow in SwiftShader.
 */
void stencilSample(highp sampler2D tex, int row, vec3 y[6], vec3 c, vec3 scale, out vec3 s[6]) {
  vec4 slices = tableTexel(row, 0);
  vec3 origin = tableTexel(row, 1).xyz;
  vec3 inv = tableTexel(row, 2).xyz;
  ivec3 cell = ivec3(floor((c - origin) * inv));
  int t0 = int(slices.y);
  int t1 = int(slices.z);
  vec3 lo[4];
  vec3 hi[4];
  for (int k = 0; k < 4; k++) {
    ivec3 o = ivec3(0, k & 1, k >> 1);
    vec3 a0 = latticePoint(tex, cell + o, t0);
    vec3 a1 = latticePoint(tex, cell + o + ivec3(1, 0, 0), t0);
    lo[k] = (a0 + (latticePoint(tex, cell + o, t1) - a0) * slices.w) * scale;
    hi[k] = (a1 + (latticePoint(tex, cell + o + ivec3(1, 0, 0), t1) - a1) * slices.w) * scale;
  }
  for (int p = 0; p < 6; p++) {
    vec3 q = (y[p] - origin) * inv;
    vec3 fl = floor(q);
    if (ivec3(fl) != cell) {
      s[p] = latticeSample(tex, row, y[p], scale);
      continue;
    }
    vec3 f = q - fl;
    vec3 e[4];
    for (int k = 0; k < 4; k++) e[k] = lo[k] + (hi[k] - lo[k]) * f.x;
    vec3 l = e[0] + (e[1] - e[0]) * f.y;
    vec3 h = e[2] + (e[3] - e[2]) * f.y;
    s[p] = l + (h - l) * f.z;
  }
}

/** blendedSample at the six points of a stencil about c. */
void blendedStencil(highp sampler2D tex, int row, vec3 points[6], vec3 c, vec3 scale, vec3 oa, vec3 ob, out vec3 s[6]) {
#ifdef CARRIED
  vec4 w = tableTexel(row, 7);
  vec3 shift = 0.5 * vec3(latticeSize.xyz) / tableTexel(row, 2).xyz;
  vec3 y[6];
  vec3 part[6];
  for (int k = 0; k < 6; k++) s[k] = vec3(0.0);
  if (w.x != 0.0) {
    for (int k = 0; k < 6; k++) y[k] = points[k] + oa;
    stencilSample(tex, row, y, c + oa, scale, part);
    for (int k = 0; k < 6; k++) s[k] += part[k] * w.x;
  }
  if (w.y != 0.0) {
    for (int k = 0; k < 6; k++) y[k] = points[k] + ob + shift;
    stencilSample(tex, row, y, c + ob + shift, scale, part);
    for (int k = 0; k < 6; k++) s[k] += part[k] * w.y;
  }
#else
  stencilSample(tex, row, points, c, scale, s);
#endif
}

vec3 smallAt(int row, vec3 x, vec3 oa, vec3 ob) {
  if (tableTexel(row, 0).x < 0.5) return vec3(0.0);
  return blendedSample(lattice, row, x, tableTexel(row, 3).xyz, oa, ob);
}

#ifdef SOLIDS
uniform highp sampler2D solidGrid;
uniform int solidGridWidth;

vec4 gridTexel(int i) { return texelFetch(solidGrid, ivec2(i % solidGridWidth, i / solidGridWidth), 0); }

/** Entry k of the grid's members: the planes (0 to planeCount() − 1), then the cells' lists. */
int gridMember(int k) {
  vec4 t = gridTexel(${SOLID_GRID_TEXELS} + int(gridTexel(0).w) + (k >> 2));
  return int(t[k & 3]);
}

int planeCount() { return int(gridTexel(1).w); }

/**
 * The lists of the grid cell holding x, as bounds into the members: the solids whose layer may
 * hold a point of it (x to y), the spheres (y to z) and the other solids (z to w) whose wind may
 * reach one. Empty outside the grid. The core's \`SolidGrid::cell\` and \`lists\`.
 */
ivec4 cellLists(vec3 x) {
  vec4 head = gridTexel(0);
  vec3 dims = gridTexel(2).xyz;
  vec3 q = (x - head.xyz) * gridTexel(1).xyz;
  if (head.w == 0.0 || !(all(greaterThanEqual(q, vec3(0.0))) && all(lessThan(q, dims)))) return ivec4(0);
  ivec3 c = ivec3(q);
  ivec3 n = ivec3(dims);
  return ivec4(gridTexel(${SOLID_GRID_TEXELS} + (c.z * n.y + c.y) * n.x + c.x));
}

/**
 * The solid the i-th visit of a search at a point of \`cell\` tests: the cell's layers list,
 * then the planes (the core's order); i below \`cell.y − cell.x + planeCount()\`.
 */
int layerOrPlane(ivec4 cell, int i) {
  int layers = cell.y - cell.x;
  return gridMember(i < layers ? cell.x + i : i - layers);
}

int solidAt(int row, int j) {
  return ${HEADER_TEXELS} + ${PRIMITIVE_TEXELS} * int(tableTexel(row, 4).w) + ${SOLID_TEXELS} * j;
}


float rampOf(float s) {
  s = clamp(s, -1.0, 1.0);
  float s2 = s * s;
  return s * (15.0 + s2 * (-10.0 + 3.0 * s2)) * 0.125;
}

vec2 taperOf(float s) {
  if (s <= 0.0) return vec2(1.0, 0.0);
  if (s >= 1.0) return vec2(0.0);
  float s2 = s * s;
  return vec2(1.0 - s2 * s * (10.0 + s * (-15.0 + 6.0 * s)), -30.0 * s2 * (1.0 - s) * (1.0 - s));
}

vec3 perpendicularTo(vec3 a) {
  vec3 other = abs(a.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
  return normalize(cross(a, other));
}

/** Solid j's signed distance (xyz: its outward normal there; w: the distance), its rims rounded by \`edge\` (m). */
vec4 solidDistance(int row, int j, vec3 x, float edge) {
  int at = solidAt(row, j);
  float kind = tableTexel(row, at).x;
  vec4 a = tableTexel(row, at + 1);
  vec4 b = tableTexel(row, at + 2);
  if (kind == ${f(SPHERE_SOLID_KIND)}) {
    vec3 r = x - a.xyz;
    float len = length(r);
    return vec4(len > 1e-12 ? r / len : vec3(0.0, 1.0, 0.0), len - a.w);
  }
  if (kind == ${f(PLANE_SOLID_KIND)}) return vec4(b.xyz, dot(x - a.xyz, b.xyz));
  vec3 r = x - a.xyz;
  float s = dot(r, b.xyz);
  vec3 radial = r - b.xyz * s;
  float rho = length(radial);
  vec3 outward = rho > 1e-12 ? radial / rho : perpendicularTo(b.xyz);
  float height = b.w;
  float radius = a.w;
  if (edge <= 0.0) {
    float dr = rho - radius;
    vec3 cap = s > 0.5 * height ? b.xyz : -b.xyz;
    float ds = s > 0.5 * height ? s - height : -s;
    if (dr > 0.0 && ds > 0.0) {
      float d = sqrt(dr * dr + ds * ds);
      return vec4((outward * dr + cap * ds) / d, d);
    }
    if (dr > 0.0) return vec4(outward, dr);
    if (ds > 0.0) return vec4(cap, ds);
    return dr > ds ? vec4(outward, dr) : vec4(cap, ds);
  }
  float half_ = 0.5 * height;
  vec3 cap = s > half_ ? b.xyz : -b.xyz;
  float e = min(min(edge, radius), half_);
  float qx = rho - (radius - e);
  float qy = abs(s - half_) - (half_ - e);
  if (qx > 0.0 && qy > 0.0) {
    float q = sqrt(qx * qx + qy * qy);
    return vec4((outward * qx + cap * qy) / q, q - e);
  }
  return qx > qy ? vec4(outward, qx - e) : vec4(cap, qy - e);
}

float solidEdge(int row, int j) {
  vec4 s0 = tableTexel(row, solidAt(row, j));
  return s0.x == ${f(CYLINDER_SOLID_KIND)} ? ${f(EDGE_STEPS)} * s0.y : 0.0;
}

/** A solid's doublet at x: its vector potential (out psi) and wind (out u). */
void doubletAt(int row, int j, vec3 x, out vec3 psi, out vec3 u) {
  int at = solidAt(row, j);
  vec4 s0 = tableTexel(row, at);
  vec4 a = tableTexel(row, at + 1);
  vec4 b = tableTexel(row, at + 2);
  vec3 d = tableTexel(row, at + 3).xyz;
  psi = vec3(0.0);
  u = vec3(0.0);
  if (s0.z == 1.0) {
    float radius = a.w;
    vec3 r = x - a.xyz;
    float rho = length(r);
    float span = ${f(SPHERE_ZONE_OUTER - SPHERE_ZONE_INNER)} * radius;
    vec2 w = taperOf((rho - ${f(SPHERE_ZONE_INNER)} * radius) / span);
    if (w.x == 0.0) return;
    vec3 p;
    vec3 v;
    if (rho >= radius) {
      vec3 n = r / rho;
      float q = radius / rho;
      float q3 = 0.5 * q * q * q;
      p = cross(d, r) * (-q3);
      v = (n * (3.0 * dot(d, n)) - d) * (-q3);
    } else {
      p = cross(d, r) * -0.5;
      v = -d;
    }
    if (w.y == 0.0) {
      psi = p * w.x;
      u = v * w.x;
      return;
    }
    vec3 grad = r * (w.y / (span * rho));
    psi = p * w.x;
    u = v * w.x + cross(grad, p);
  } else if (s0.z == 2.0) {
    vec3 axis = b.xyz;
    float radius = a.w;
    float height = b.w;
    vec3 r = x - a.xyz;
    float s = dot(r, axis);
    float beyond = s > height ? s - height : -s;
    float wAxial = taperOf(beyond / radius).x;
    if (wAxial == 0.0) return;
    vec3 rv = r - axis * s;
    float rho = length(rv);
    float span = ${f(CYLINDER_ZONE_OUTER - CYLINDER_ZONE_INNER)} * radius;
    vec2 wr = taperOf((rho - ${f(CYLINDER_ZONE_INNER)} * radius) / span);
    if (wr.x == 0.0) return;
    float r2 = radius * radius;
    float md = dot(d, rv);
    float stream;
    vec3 grad;
    if (rho >= radius) {
      float inv2 = 1.0 / (rho * rho);
      stream = -r2 * md * inv2;
      grad = (d - rv * (2.0 * md * inv2)) * (-r2 * inv2);
    } else {
      float q = rho * rho / r2;
      float p = 1.0 + q * (3.0 + q * (-5.0 + 2.0 * q));
      float dp = 3.0 + q * (-10.0 + 6.0 * q);
      stream = -md * p;
      grad = -(d * p + rv * (md * dp * 2.0 / r2));
    }
    vec3 g = grad * wr.x;
    if (wr.y != 0.0) g += rv * (stream * wr.y / (span * rho));
    psi = axis * (stream * wr.x * wAxial);
    u = cross(g, axis) * wAxial;
  }
}

vec3 projected(vec3 u, vec3 n, float alpha, bool keepOutflow) {
  float un = dot(u, n);
  if (keepOutflow) un = min(un, 0.0);
  return u - n * ((1.0 - alpha) * un);
}

int imageOf(int row, int j) { return int(tableTexel(row, ${HEADER_TEXELS} + ${PRIMITIVE_TEXELS} * j + 1).w); }

bool hasImageIn(int row, int j, int plane) {
  int at = ${HEADER_TEXELS} + ${PRIMITIVE_TEXELS} * j;
  int first = int(tableTexel(row, at + 2).w);
  int count = int(tableTexel(row, at + 3).w);
  for (int k = 0; k < count; k++) {
    if (imageOf(row, first + k) == plane) return true;
  }
  return false;
}

/** Whether primitive j is a vortex without decay (turned by the ramped curl of its potential). */
bool hasPotential(int row, int j) {
  vec4 head = tableTexel(row, ${HEADER_TEXELS} + ${PRIMITIVE_TEXELS} * j);
  return head.x == ${f(VORTEX_KIND)} && head.y == 0.0;
}

vec3 vortexPotential(int row, int j, vec3 y, vec3 gauge) {
  int at = ${HEADER_TEXELS} + ${PRIMITIVE_TEXELS} * j;
  vec4 head = tableTexel(row, at);
  vec3 p = tableTexel(row, at + 2).xyz;
  vec3 axis = tableTexel(row, at + 3).xyz;
  vec3 c = cross(axis, y - p);
  vec3 c0 = cross(axis, gauge - p);
  return axis * (-0.5 * head.z * log((dot(c, c) + head.w) / (dot(c0, c0) + head.w)));
}

/** The point a vortex's potential vanishes at near solid n: a plane's foot of it, else the solid's centre. */
vec3 gaugeOf(int row, int n, int j) {
  int at = solidAt(row, n);
  vec4 s0 = tableTexel(row, at);
  vec4 a = tableTexel(row, at + 1);
  vec4 b = tableTexel(row, at + 2);
  if (s0.x == ${f(PLANE_SOLID_KIND)}) {
    vec3 q = tableTexel(row, ${HEADER_TEXELS} + ${PRIMITIVE_TEXELS} * j + 2).xyz;
    return q - b.xyz * dot(q - a.xyz, b.xyz);
  }
  if (s0.x == ${f(CYLINDER_SOLID_KIND)}) return a.xyz + b.xyz * (0.5 * b.w);
  return a.xyz;
}

/** Whether primitive j passes exactly near solid n (it and its mirror image in that plane). */
bool exactNear(int row, int n, int j) {
  if (tableTexel(row, solidAt(row, n)).x != ${f(PLANE_SOLID_KIND)}) return false;
  int image = imageOf(row, j);
  return image == n || (image < 0 && hasImageIn(row, j, n));
}

/**
 * Whether solid j's doublet may be other than zero at a point of the stencil about c with steps
 * h (m): a sphere's ends ${f(SPHERE_ZONE_OUTER)} radii out, and every point lies within h of c.
 */
bool reachesStencil(int row, int j, vec3 c, float h) {
  int at = solidAt(row, j);
  if (tableTexel(row, at).z != 1.0) return true;
  vec4 a = tableTexel(row, at + 1);
  return length(c - a.xyz) <= ${f(SPHERE_ZONE_OUTER)} * a.w + 1.01 * h;
}

/**
 * The large-scale potential turned by the ramped curl near solid n, at the stencil's six points
 * y: the doublets of the solids whose wind \`lists\` (a cell's) says may reach, but n's, and the
 * vortices. Each solid's row of the table is read once for the six points; each point's sum
 * keeps the core's order.
 */
void rampedPotentials(int row, int n, ivec4 lists, vec3 c, float h, vec3 y[6], out vec3 psi[6]) {
  for (int k = 0; k < 6; k++) psi[k] = vec3(0.0);
  for (int m = lists.y; m < lists.w; m++) {
    int j = gridMember(m);
    if (j == n || !reachesStencil(row, j, c, h)) continue;
    for (int k = 0; k < 6; k++) {
      vec3 p;
      vec3 u;
      doubletAt(row, j, y[k], p, u);
      psi[k] += p;
    }
  }
  int count = int(tableTexel(row, 4).w);
  for (int j = 0; j < count; j++) {
    if (exactNear(row, n, j) || !hasPotential(row, j)) continue;
    vec3 gauge = gaugeOf(row, n, j);
    for (int k = 0; k < 6; k++) psi[k] += vortexPotential(row, j, y[k], gauge);
  }
}

vec3 rampedCurl(vec3 a[6], vec3 points[6]) {
  vec3 span = vec3(points[0].x - points[1].x, points[2].y - points[3].y, points[4].z - points[5].z);
  vec3 inv = 1.0 / span;
  vec3 dx = (a[0] - a[1]) * inv.x;
  vec3 dy = (a[2] - a[3]) * inv.y;
  vec3 dz = (a[4] - a[5]) * inv.z;
  return vec3(dy.z - dz.y, dz.x - dx.z, dx.y - dy.x);
}

void nearSolid(int row, int n, vec4 near_, vec3 x, ivec4 cell, vec3 oa, vec3 ob, out vec3 large, out vec3 small) {
  int at = solidAt(row, n);
  vec4 s0 = tableTexel(row, at);
  vec4 sb = tableTexel(row, at + 2);
  float width = tableTexel(row, 5).y;
  vec3 nrm = near_.xyz;
  float alpha = rampOf(near_.w / width);
  bool plane = s0.x == ${f(PLANE_SOLID_KIND)};
  vec3 u0 = tableTexel(row, 4).xyz;
  if (s0.x == ${f(SPHERE_SOLID_KIND)}) {
    large = u0;
  } else if (s0.x == ${f(CYLINDER_SOLID_KIND)}) {
    vec3 along = sb.xyz * dot(u0, sb.xyz);
    large = (u0 - along) + projected(along, nrm, alpha, false);
  } else {
    large = projected(u0, nrm, alpha, true);
  }
  if (s0.z > 0.0) {
    vec3 p;
    vec3 u;
    doubletAt(row, n, x, p, u);
    large += u;
  }
  // Deeper inside than a step, the ramped curl is the one a step deep, about c, with the lists there.
  float h = s0.y;
  vec3 c = near_.w < -h ? x + nrm * (-h - near_.w) : x;
  ivec4 lists = near_.w < -h ? cellLists(c) : cell;
  bool others = false;
  for (int k = lists.y; k < lists.w; k++) others = others || gridMember(k) != n;
  bool vortices = false;
  int count = int(tableTexel(row, 4).w);
  for (int j = 0; j < count; j++) {
    if (exactNear(row, n, j)) large += primitiveWind(row, j, x);
    else if (hasPotential(row, j)) vortices = true;
    else large += projected(primitiveWind(row, j, x), nrm, alpha, plane);
  }
  bool hasField = tableTexel(row, 0).x > 0.5;
  bool hasPsi = tableTexel(row, 5).z > 0.5;
  if (!(others || vortices || hasPsi)) {
    small = hasField ? projected(smallAt(row, x, oa, ob), nrm, alpha, false) : vec3(0.0);
    return;
  }
  float edge = solidEdge(row, n);
  vec3 points[6];
  float alphas[6];
  vec3 normals[6];
  for (int k = 0; k < 6; k++) {
    vec3 e = vec3(k / 2 == 0 ? 1.0 : 0.0, k / 2 == 1 ? 1.0 : 0.0, k / 2 == 2 ? 1.0 : 0.0);
    points[k] = c + e * ((k % 2 == 0 ? 1.0 : -1.0) * h);
    vec4 dn = solidDistance(row, n, points[k], edge);
    alphas[k] = rampOf(dn.w / width);
    normals[k] = dn.xyz;
  }
  vec3 a[6];
  if (others || vortices) {
    vec3 psi[6];
    rampedPotentials(row, n, lists, c, h, points, psi);
    for (int k = 0; k < 6; k++) a[k] = psi[k] * alphas[k] + normals[k] * ((1.0 - alphas[k]) * dot(normals[k], psi[k]));
    large += rampedCurl(a, points);
  }
  if (hasPsi) {
    vec3 psi[6];
    blendedStencil(potentialLattice, row, points, c, tableTexel(row, 6).xyz, oa, ob, psi);
    for (int k = 0; k < 6; k++) a[k] = psi[k] * alphas[k] + normals[k] * ((1.0 - alphas[k]) * dot(normals[k], psi[k]));
    small = rampedCurl(a, points);
  } else {
    // The field's potential is still being synthesised: project meanwhile (about c).
    small = hasField ? projected(smallAt(row, c, oa, ob), nrm, alpha, false) : vec3(0.0);
  }
}

/** Whether x lies inside a solid (one of its cell's, or a plane); its signed distance and normal in \`dn\` when it does. */
bool insideSolid(int row, vec3 x, out vec4 dn) {
  ivec4 cell = cellLists(x);
  int visits = cell.y - cell.x + planeCount();
  for (int i = 0; i < visits; i++) {
    dn = solidDistance(row, layerOrPlane(cell, i), x, 0.0);
    if (dn.w < 0.0) return true;
  }
  return false;
}

vec3 pushOut(int row, vec3 x) {
  float gap = 1e-4 * tableTexel(row, 5).y;
  vec3 start = x;
  vec3 normal = vec3(0.0, 1.0, 0.0);
  vec4 dn;
  for (int round_ = 0; round_ < 4; round_++) {
    if (!insideSolid(row, x, dn)) return x;
    vec3 ax = abs(x);
    float g = gap + 4.0 * 1.1920929e-7 * max(ax.x, max(ax.y, ax.z));
    x += dn.xyz * (g - dn.w);
    normal = dn.xyz;
  }
  if (!insideSolid(row, x, dn)) return x;
  // Overlapping solids sent it back and forth: the shortest of seven ways out of them all.
  vec3 ways[7] = vec3[7](normal, vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0),
    vec3(0, 0, 1), vec3(0, 0, -1));
  for (float t = max(gap, 1e-4); t < 1e3; t *= 1.25) {
    for (int w = 0; w < 7; w++) {
      vec3 y = start + ways[w] * t;
      if (!insideSolid(row, y, dn)) return y;
    }
  }
  return x;
}
#endif

#ifdef SOLIDS
/**
 * How far x surely lies from every solid (m), from the rounded distance \`nearest\` of the
 * nearest solid within the layer (the layer's width when none): the core's \`Solids::clearance\`.
 */
float clearanceOf(int row, float nearest, vec3 x) {
  float d = min(nearest, tableTexel(row, 5).y);
  vec3 ax = abs(x);
  return (d - tableTexel(row, 6).w) * 0.999 - 1e-6 * (1.0 + max(ax.x, max(ax.y, ax.z)));
}
#endif

/**
 * The wind's parts at x by the solids' closed forms (no flow), and how far x surely lies from
 * every solid (\`clear\`, m; with SOLIDS).
 */
void closedFormParts(int row, vec3 x, vec3 oa, vec3 ob, out vec3 large, out vec3 small, out float clear) {
#ifdef SOLIDS
  float width = tableTexel(row, 5).y;
  ivec4 cell = cellLists(x);
  int visits = cell.y - cell.x + planeCount();
  int nearest = -1;
  vec4 best = vec4(0.0);
  for (int i = 0; i < visits; i++) {
    int j = layerOrPlane(cell, i);
    vec4 dn = solidDistance(row, j, x, solidEdge(row, j));
    if (dn.w < width && (nearest < 0 || dn.w < best.w)) {
      nearest = j;
      best = dn;
    }
  }
  if (nearest >= 0) {
    clear = clearanceOf(row, best.w, x);
    nearSolid(row, nearest, best, x, cell, oa, ob, large, small);
    return;
  }
  clear = clearanceOf(row, width, x);
  large = tableTexel(row, 4).xyz;
  for (int k = cell.y; k < cell.w; k++) {
    vec3 p;
    vec3 u;
    doubletAt(row, gridMember(k), x, p, u);
    large += u;
  }
#else
  clear = 0.0;
  large = tableTexel(row, 4).xyz;
#endif
  int count = int(tableTexel(row, 4).w);
  for (int j = 0; j < count; j++) large += primitiveWind(row, j, x);
  small = smallAt(row, x, oa, ob);
}

/** The wind's parts at x, and how far x surely lies from every solid (\`clear\`, m; with SOLIDS). */
void windPartsAndClearance(int row, vec3 x, vec3 oa, vec3 ob, out vec3 large, out vec3 small, out float clear) {
  closedFormParts(row, x, oa, ob, large, small, clear);
#ifdef FLOW
  // Within the flow's box u_p + u_g replaces the solids' closed forms for the large scales;
  // across its fade layer the two blend (u_p: the scene's primitives, no mirror images).
  float w = flowWeight(x);
  if (w > 0.0) {
    vec3 solved = tableTexel(row, 4).xyz;
    int count = int(tableTexel(row, 4).w);
    for (int j = 0; j < count; j++) {
      if (tableTexel(row, ${HEADER_TEXELS} + ${PRIMITIVE_TEXELS} * j + 1).w < 0.0) solved += primitiveWind(row, j, x);
    }
    solved += flowVelocity(x);
    large += (solved - large) * w;
  }
#endif
}

void windParts(int row, vec3 x, vec3 oa, vec3 ob, out vec3 large, out vec3 small) {
  float clear;
  windPartsAndClearance(row, x, oa, ob, large, small, clear);
}
`;
