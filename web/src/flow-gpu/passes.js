// The flow's passes on the GPU, each a per-texel map over one lattice (a velocity component's
// faces, or the cells), the same laws as the core's `wind::flow` step by step:
//
// - CARRIER: u_p + u_g at the cells' centres (the advecting velocity, the core's `Centred`:
//   each component the mean of the cell's two faces, trilinear between the centres).
// - ADVECT_BACK, ADVECT_CORRECT: semi-Lagrangian advection by a midpoint trace back in cells
//   from the face's carrier (its two cells' mean), then MacCormack's correction from a trace
//   forward, clamped to the eight samples the first trace blended (`advect.rs`: Selle et al.
//   2008); a trace from beyond an open face of the box brings u_g faded to 0.
// - DIFFUSE: one explicit substep of ν∇² on one component's faces, with the core's stencil at
//   the box's faces, fixed faces and no-slip or slipping solids (`diffuse.rs`).
// - EDDY_VISCOSITY: Smagorinsky's ν_t = (C_s h)² √(2 S_ij S_ij) per cell, capped at h²/(8 dt),
//   S from u_g's central differences at the cells' centres (CENTRES), one-sided at the box's
//   faces (`subgrid.rs`).
// - EDDY_DIFFUSE: one explicit pass of ν_t's diffusion on one component's free faces, ν_f the
//   mean of its two cells' ν_t, over its free neighbours only (no eddy flux through walls).
// - BUOYANCY: b = −β T g, T averaged onto each face from its two cells (`forces.rs`).
// - SPLAT: a Gaussian force splat within four widths of its centre (`forces.rs`).
// - WIND_ON_FACES: u_p on one component's faces, the scene's own primitives read from a wind
//   table (`SceneFlow::step`, `WindFrame::primitive_wind` at each face).
// - IMPOSE: each fixed face's u_g = v·n − u_p (`boundary.rs`).
// - DIVERGENCE: the Poisson right-hand side b = −h² ∇·u_g of each fluid cell (`project.rs`);
//   with no open face, REDUCE (sums over blocks, down to one texel) and CENTRE_B take out b's
//   mean over the fluid cells, which makes the singular system solvable, as the core does.
// - RELAX: one half sweep (red or black cells) of successive over-relaxation of Σ_f (φ_i − φ_j)
//   = b_i over the free faces f (φ = 0 beyond an open face).
// - GRADIENT: each free face loses ∇φ (`project.rs`).
// - RESIDUAL: b − Aφ per cell (for the solve's check); CENTRES: u_g at the cells' centres;
//   PROBE: u_p + u_g at one point (a stir's push is towards the pointer's velocity from it).
//
// Every pass starts from `s`, the sample of its texel in the target's lattice, and writes 0 past
// the lattice's last slice.

import { PRIMITIVES_GLSL } from '../stepper/wind-glsl.js';

const SAMPLE = /* glsl */ `
  ivec3 s = sampleOf(ivec2(gl_FragCoord.xy), target);
  if (beyond(s, target)) {
    outValue = vec4(0.0);
    return;
  }`;

const OUT = 'layout(location = 0) out vec4 outValue;';

/** The uniforms of lattices `names`: each its texture and its atlas (`name` and `nameL`). */
function lattices(...names) {
  return names.map((n) => `uniform sampler2D ${n};\nuniform ivec4 ${n}L;`).join('\n');
}

/** The carrier at the cells' centres: each component of u_p + u_g the mean of the cell's two faces. */
export const CARRIER = /* glsl */ `
${lattices('px', 'py', 'pz', 'ux', 'uy', 'uz')}
${OUT}
float face(sampler2D p, ivec4 pL, sampler2D u, ivec4 uL, ivec3 m) {
  return fetch1(p, m, pL) + fetch1(u, m, uL);
}
void main() {${SAMPLE}
  outValue = vec4(
    0.5 * (face(px, pxL, ux, uxL, s) + face(px, pxL, ux, uxL, s + ivec3(1, 0, 0))),
    0.5 * (face(py, pyL, uy, uyL, s) + face(py, pyL, uy, uyL, s + ivec3(0, 1, 0))),
    0.5 * (face(pz, pzL, uz, uzL, s) + face(pz, pzL, uz, uzL, s + ivec3(0, 0, 1))),
    0.0);
}`;

const TRACE = /* glsl */ `
// The carrier at the cells' centres (xyz per cell).
${lattices('carrier')}
uniform float dt;
// Where this lattice's samples lie, in cells from the origin, and its component.
uniform vec3 offset;
uniform int axis;
// The carrier at t (cells from the origin): one trilinear blend of its three components
// between the cells' centres, clamped to them (the core's Centred::at_cells).
vec3 carried(vec3 t) {
  ivec3 b;
  vec3 f;
  locate(t.x, carrierL.x, 0.5, b.x, f.x);
  locate(t.y, carrierL.y, 0.5, b.y, f.y);
  locate(t.z, carrierL.z, 0.5, b.z, f.z);
  ivec3 st = ivec3(carrierL.x > 1 ? 1 : 0, carrierL.y > 1 ? 1 : 0, carrierL.z > 1 ? 1 : 0);
  vec3 c[8];
  for (int n = 0; n < 8; n++) {
    ivec3 e = ivec3(n & 1, (n >> 1) & 1, (n >> 2) & 1) * st;
    c[n] = texelFetch(carrier, texelOf(b + e, carrierL), 0).xyz;
  }
  vec3 y0 = mix3(mix3(c[0], c[1], f.x), mix3(c[2], c[3], f.x), f.y);
  vec3 y1 = mix3(mix3(c[4], c[5], f.x), mix3(c[6], c[7], f.x), f.y);
  return mix3(y0, y1, f.z);
}
// The carrier at face s of component axis: the mean of the two cells either side, the one
// cell at the box's faces (the core's Centred::at_face).
vec3 atFace(ivec3 s) {
  int n = carrierL[axis];
  ivec3 c = s;
  c[axis] = min(s[axis], n - 1);
  ivec3 below = c;
  if (s[axis] > 0 && s[axis] < n) below[axis] -= 1;
  return (texelFetch(carrier, texelOf(below, carrierL), 0).xyz + texelFetch(carrier, texelOf(c, carrierL), 0).xyz) * 0.5;
}
// The point the carrier takes to t (cells) over k = dt/h (a midpoint step; a negative k
// traces forward), v0 the carrier at t.
vec3 traceFrom(vec3 t, vec3 v0, float k) {
  vec3 v1 = carried(t - v0 * (0.5 * k));
  return t - v1 * k;
}`;

/** The first trace: the value found where the carrier brought the sample from, and its bounds. */
export const ADVECT_BACK = /* glsl */ `
${TRACE}
${lattices('q')}
// 1 on the axes whose faces are open, 0 on the closed: a trace from beyond an open face brings
// u_g faded to 0 (\`beyond_open_faces\`).
uniform vec3 open;
${OUT}
void main() {${SAMPLE}
  vec3 t = offset + vec3(s);
  float k = dt / h;
  vec3 back = traceFrom(t, atFace(s), k);
  float c[8];
  vec3 f;
  cornersCells(q, qL, offset, back, c, f);
  float lo = c[0];
  float hi = c[0];
  for (int n = 1; n < 8; n++) {
    lo = min(lo, c[n]);
    hi = max(hi, c[n]);
  }
  float w = fadeBeyond(max(max(-back, back - vec3(cells)), vec3(0.0)) * open);
  outValue = vec4(blend(c, f), lo, hi, 0.0) * w;
}`;

/** MacCormack's correction of the first trace, clamped to its bounds. */
export const ADVECT_CORRECT = /* glsl */ `
${TRACE}
${lattices('q')}
// The first trace: (value, lo, hi) per sample.
${lattices('back')}
${OUT}
void main() {${SAMPLE}
  vec3 t = offset + vec3(s);
  float k = dt / h;
  vec3 ahead = traceFrom(t, atFace(s), -k);
  float c[8];
  vec3 f;
  cornersCells(back, backL, offset, ahead, c, f);
  float returned = blend(c, f);
  vec4 first = texelFetch(back, texelOf(s, backL), 0);
  float corrected = first.x + 0.5 * (fetch1(q, s, qL) - returned);
  outValue = vec4(clamp(corrected, first.y, first.z), 0.0, 0.0, 0.0);
}`;

const KINDS = /* glsl */ `
// Each face's [kind, v]: kind 0 free, 1 fixed holding the air (no-slip), 2 fixed slipping.
${lattices('kind')}
vec2 kindOf(ivec3 m) {
  return texelFetch(kind, texelOf(m, kindL), 0).xy;
}`;

/** One explicit substep of ν∇² (r = ν·dt_sub/h²) on component `axis`'s faces. */
export const DIFFUSE = /* glsl */ `
${KINDS}
${lattices('old', 'up')}
uniform int axis;
uniform float r;
${OUT}
// The neighbour m across axis b: u_g there, or what a fixed face stands for.
float neighbour(ivec3 m, int b, ivec3 s, float o) {
  vec2 k = kindOf(m);
  if (k.x == 0.0) return fetch1(old, m, oldL);
  if (b == axis) return k.y - fetch1(up, m, upL);
  if (k.x == 1.0) return 2.0 * k.y - fetch1(up, s, upL) - o - fetch1(up, m, upL);
  return o;
}
void main() {${SAMPLE}
  float o = fetch1(old, s, oldL);
  if (kindOf(s).x != 0.0) {
    outValue = vec4(o, 0.0, 0.0, 0.0);
    return;
  }
  float lap = 0.0;
  for (int b = 0; b < 3; b++) {
    ivec3 e = ivec3(b == 0 ? 1 : 0, b == 1 ? 1 : 0, b == 2 ? 1 : 0);
    float below = s[b] > 0 ? neighbour(s - e, b, s, o) : o;
    float above = s[b] + 1 < target[b] ? neighbour(s + e, b, s, o) : o;
    lap += below + above - 2.0 * o;
  }
  outValue = vec4(o + r * lap, 0.0, 0.0, 0.0);
}`;

/**
 * ν_t (m²/s) per cell: min(scale·√(2 S_ij S_ij), cap), scale = (C_s h)², cap = h²/(8 dt), S the
 * strain rate of u_g at the cells' centres (`centred`), central differences over the cells
 * either side, one-sided at the box's faces, none along an axis of one cell.
 */
export const EDDY_VISCOSITY = /* glsl */ `
${lattices('centred')}
uniform float scale;
uniform float cap;
${OUT}
void main() {${SAMPLE}
  // grad[b] = ∂u/∂x_b.
  vec3 grad[3];
  for (int b = 0; b < 3; b++) {
    ivec3 lo = s;
    ivec3 hi = s;
    lo[b] = max(s[b] - 1, 0);
    hi[b] = min(s[b] + 1, cells[b] - 1);
    grad[b] = vec3(0.0);
    if (hi[b] == lo[b]) continue;
    float span = float(hi[b] - lo[b]) * h;
    grad[b] = (texelFetch(centred, texelOf(hi, centredL), 0).xyz - texelFetch(centred, texelOf(lo, centredL), 0).xyz) / span;
  }
  float ss = 0.0;
  for (int a = 0; a < 3; a++) {
    for (int b = 0; b < 3; b++) {
      float sab = 0.5 * (grad[b][a] + grad[a][b]);
      ss += sab * sab;
    }
  }
  outValue = vec4(min(scale * sqrt(2.0 * ss), cap), 0.0, 0.0, 0.0);
}`;

/**
 * One pass of ν_t's diffusion on component `axis`'s free faces: u += dt·ν_f/h²·Σ(u_n − u)
 * over the free neighbours within the lattice, ν_f the mean of the face's two cells' ν_t
 * (a box face its one cell's); fixed faces as they are.
 */
export const EDDY_DIFFUSE = /* glsl */ `
${KINDS}
${lattices('old', 'nuT')}
uniform int axis;
uniform float dt;
uniform float invH2;
${OUT}
float nuAt(ivec3 s, int m) {
  ivec3 c = s;
  c[axis] = min(m, cells[axis] - 1);
  return fetch1(nuT, c, nuTL);
}
void main() {${SAMPLE}
  float o = fetch1(old, s, oldL);
  int k = s[axis];
  float nu = k == 0 ? nuAt(s, 0) : 0.5 * (nuAt(s, k - 1) + nuAt(s, k));
  if (kindOf(s).x != 0.0 || nu == 0.0) {
    outValue = vec4(o, 0.0, 0.0, 0.0);
    return;
  }
  float sum = 0.0;
  for (int b = 0; b < 3; b++) {
    ivec3 e = ivec3(b == 0 ? 1 : 0, b == 1 ? 1 : 0, b == 2 ? 1 : 0);
    if (s[b] > 0 && kindOf(s - e).x == 0.0) sum += fetch1(old, s - e, oldL) - o;
    if (s[b] + 1 < target[b] && kindOf(s + e).x == 0.0) sum += fetch1(old, s + e, oldL) - o;
  }
  outValue = vec4(o + dt * nu * invH2 * sum, 0.0, 0.0, 0.0);
}`;

/** u −= (dt·β)·T·g on component `axis`'s faces, T on the cells. */
export const BUOYANCY = /* glsl */ `
${lattices('u', 'temperature')}
uniform int axis;
uniform float dtBeta;
uniform float g;
${OUT}
float at(ivec3 s, int m) {
  ivec3 c = s;
  c[axis] = m;
  return fetch1(temperature, c, temperatureL);
}
void main() {${SAMPLE}
  int n = cells[axis];
  int k = s[axis];
  float t = k == 0 ? at(s, 0) : k == n ? at(s, n - 1) : 0.5 * (at(s, k - 1) + at(s, k));
  outValue = vec4(fetch1(u, s, uL) - dtBeta * t * g, 0.0, 0.0, 0.0);
}`;

/** u += (dt·force)·exp(−|x − centre|²/radius²) on the faces within four widths of the centre. */
export const SPLAT = /* glsl */ `
${lattices('u')}
uniform vec3 offset;
uniform vec3 centre;
uniform float radius;
uniform float dtForce;
${OUT}
void main() {${SAMPLE}
  float v = fetch1(u, s, uL);
  float reach = 4.0 * radius;
  vec3 lo = (centre - reach - origin) / h - offset;
  vec3 hi = (centre + reach - origin) / h - offset;
  vec3 p = vec3(s);
  if (all(greaterThanEqual(p, lo)) && all(lessThanEqual(p, hi))) {
    vec3 d = origin + h * (p + offset) - centre;
    float q = d.x * d.x + d.y * d.y + d.z * d.z;
    v += dtForce * exp(-q / (radius * radius));
  }
  outValue = vec4(v, 0.0, 0.0, 0.0);
}`;

/**
 * u_p (m/s) on component `axis`'s faces, each at origin + h·(index + offset): the constant wind
 * and every primitive of the wind table's row 0 that is not a mirror image.
 */
export const WIND_ON_FACES = /* glsl */ `
${PRIMITIVES_GLSL}
uniform vec3 offset;
uniform int axis;
${OUT}
void main() {${SAMPLE}
  vec3 x = origin + h * (vec3(s) + offset);
  outValue = vec4(primitivesWind(0, x)[axis], 0.0, 0.0, 0.0);
}`;

/** Each fixed face's u_g = v − u_p (so u_p + u_g carries v); free faces as they are. */
export const IMPOSE = /* glsl */ `
${KINDS}
${lattices('u', 'up')}
${OUT}
void main() {${SAMPLE}
  vec2 k = kindOf(s);
  outValue = vec4(k.x == 0.0 ? fetch1(u, s, uL) : k.y - fetch1(up, s, upL), 0.0, 0.0, 0.0);
}`;

const ROWS = /* glsl */ `
// Each cell's Poisson row: [free faces, links (bit a: the next cell along a is joined, bit
// 3 + a: the previous one), 0, 0].
${lattices('rows', 'phi')}
// Σ of φ over the cell's fluid neighbours.
float neighbours(ivec3 s, int links) {
  float sum = 0.0;
  for (int a = 0; a < 3; a++) {
    ivec3 e = ivec3(a == 0 ? 1 : 0, a == 1 ? 1 : 0, a == 2 ? 1 : 0);
    if ((links & (1 << a)) != 0) sum += fetch1(phi, s + e, phiL);
    if ((links & (8 << a)) != 0) sum += fetch1(phi, s - e, phiL);
  }
  return sum;
}`;

/** b = −h²·∇·u_g on the fluid cells (0 on the others). */
export const DIVERGENCE = /* glsl */ `
${lattices('ux', 'uy', 'uz', 'rows')}
${OUT}
void main() {${SAMPLE}
  float d = 0.0;
  d += fetch1(ux, s + ivec3(1, 0, 0), uxL) - fetch1(ux, s, uxL);
  d += fetch1(uy, s + ivec3(0, 1, 0), uyL) - fetch1(uy, s, uyL);
  d += fetch1(uz, s + ivec3(0, 0, 1), uzL) - fetch1(uz, s, uzL);
  float diag = texelFetch(rows, texelOf(s, rowsL), 0).x;
  outValue = vec4(diag > 0.0 ? -(h * h) * (d / h) : 0.0, 0.0, 0.0, 0.0);
}`;

/** One half sweep of SOR: the cells of `parity` updated, the others kept. */
export const RELAX = /* glsl */ `
${ROWS}
${lattices('b')}
uniform float omega;
uniform int parity;
${OUT}
void main() {${SAMPLE}
  float p = fetch1(phi, s, phiL);
  if (((s.x + s.y + s.z) & 1) != parity) {
    outValue = vec4(p, 0.0, 0.0, 0.0);
    return;
  }
  vec4 row = texelFetch(rows, texelOf(s, rowsL), 0);
  if (row.x == 0.0) {
    outValue = vec4(0.0);
    return;
  }
  float gs = (fetch1(b, s, bL) + neighbours(s, int(row.y))) / row.x;
  outValue = vec4(p + omega * (gs - p), 0.0, 0.0, 0.0);
}`;

/** b − Aφ and b per cell (0 off the fluid). */
export const RESIDUAL = /* glsl */ `
${ROWS}
${lattices('b')}
${OUT}
void main() {${SAMPLE}
  vec4 row = texelFetch(rows, texelOf(s, rowsL), 0);
  float bs = fetch1(b, s, bL);
  float r = row.x == 0.0 ? 0.0 : bs - (row.x * fetch1(phi, s, phiL) - neighbours(s, int(row.y)));
  outValue = vec4(r, bs, row.x, 0.0);
}`;

/** Component `axis`'s free faces lose ∇φ (φ = 0 beyond an open face). */
export const GRADIENT = /* glsl */ `
${ROWS}
${lattices('u')}
uniform int axis;
// 1 on the axes whose faces are open, 0 on the closed.
uniform vec3 open;
${OUT}
void main() {${SAMPLE}
  float v = fetch1(u, s, uL);
  int n = cells[axis];
  int k = s[axis];
  ivec3 c = s;
  c[axis] = min(k, n - 1);
  float below;
  float above;
  if (k == 0 || k == n) {
    if (!(open[axis] > 0.5 && texelFetch(rows, texelOf(c, rowsL), 0).x > 0.0)) {
      outValue = vec4(v, 0.0, 0.0, 0.0);
      return;
    }
    float p = fetch1(phi, c, phiL);
    below = k == 0 ? 0.0 : p;
    above = k == 0 ? p : 0.0;
  } else {
    ivec3 e = ivec3(axis == 0 ? 1 : 0, axis == 1 ? 1 : 0, axis == 2 ? 1 : 0);
    int links = int(texelFetch(rows, texelOf(c - e, rowsL), 0).y);
    if ((links & (1 << axis)) == 0) {
      outValue = vec4(v, 0.0, 0.0, 0.0);
      return;
    }
    below = fetch1(phi, c - e, phiL);
    above = fetch1(phi, c, phiL);
  }
  outValue = vec4(v - (above - below) * invH, 0.0, 0.0, 0.0);
}`;

/** u_g at the cells' centres: each component the mean of the cell's two faces. */
export const CENTRES = /* glsl */ `
${lattices('ux', 'uy', 'uz')}
${OUT}
void main() {${SAMPLE}
  outValue = vec4(
    0.5 * (fetch1(ux, s, uxL) + fetch1(ux, s + ivec3(1, 0, 0), uxL)),
    0.5 * (fetch1(uy, s, uyL) + fetch1(uy, s + ivec3(0, 1, 0), uyL)),
    0.5 * (fetch1(uz, s, uzL) + fetch1(uz, s + ivec3(0, 0, 1), uzL)),
    0.0);
}`;

/** The wind u_p + u_g at one point (m), each sampled trilinearly on its faces, into one texel. */
export const PROBE = /* glsl */ `
${lattices('ux', 'uy', 'uz', 'px', 'py', 'pz')}
uniform vec3 point;
${OUT}
void main() {
  vec3 p = vec3(
    trilinear(px, pxL, vec3(0.0, 0.5, 0.5), point),
    trilinear(py, pyL, vec3(0.5, 0.0, 0.5), point),
    trilinear(pz, pzL, vec3(0.5, 0.5, 0.0), point));
  vec3 q = vec3(
    trilinear(ux, uxL, vec3(0.0, 0.5, 0.5), point),
    trilinear(uy, uyL, vec3(0.5, 0.0, 0.5), point),
    trilinear(uz, uzL, vec3(0.5, 0.5, 0.0), point));
  outValue = vec4(p + q, 0.0);
}`;

/** The sum of `src`'s first channel over blocks of size.z × size.z texels (size.xy: src's). */
export const REDUCE = /* glsl */ `
uniform sampler2D src;
uniform ivec4 size;
${OUT}
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy) * size.z;
  float sum = 0.0;
  for (int y = 0; y < size.z; y++) {
    for (int x = 0; x < size.z; x++) {
      ivec2 q = p + ivec2(x, y);
      if (q.x < size.x && q.y < size.y) sum += texelFetch(src, q, 0).x;
    }
  }
  outValue = vec4(sum, 0.0, 0.0, 0.0);
}`;

/** b less its mean over the fluid cells (`total`'s texel over `fluid` cells), 0 off them. */
export const CENTRE_B = /* glsl */ `
${lattices('b', 'rows')}
uniform sampler2D total;
uniform float fluid;
${OUT}
void main() {${SAMPLE}
  float diag = texelFetch(rows, texelOf(s, rowsL), 0).x;
  float mean = texelFetch(total, ivec2(0), 0).x / fluid;
  outValue = vec4(diag > 0.0 ? fetch1(b, s, bL) - mean : 0.0, 0.0, 0.0, 0.0);
}`;
