// The gas's heat on the flow's cells, on the GPU (the core's `wind::flow::heat::deposit`): each
// blob j of the GPU stepper's state carries heat h_j = h0_j · exp(−c · age_j) (K·m³; h0 from its
// birth record, c the flow's cooling, 1/s), and the temperature excess averaged over a cell is
// exact, the product over the three axes of (Φ((b − c)/σ) − Φ((a − c)/σ))/h, Φ the standard
// normal distribution and [a, b] the cell's extent along the axis. The Gaussian is cut at four σ
// as in the core (Φ is 0 below −4 and 1 above 4), so a blob reaches the cells that overlap
// [c − 4σ, c + 4σ] and leaves its whole heat on them.
//
// The sum is a scatter: one instance per blob and z slice of its reach draws a rectangle over
// the cells of that slice it reaches (two triangles, any size: no point-size limit), each
// fragment adding its cell's share with additive blending into the R32F temperature atlas
// (EXT_float_blend). An instance past its blob's reach, or of an empty slot or a blob without
// heat, is put outside the view and costs one vertex.

import { linkProgram, passState } from './gl.js';

/** How far a blob's heat reaches, in σ (`heat::REACH`). */
const REACH = 4;

const VERTEX = /* glsl */ `#version 300 es
precision highp float;
precision highp int;
precision highp sampler2D;
uniform sampler2D centres;
uniform sampler2D masses;
uniform int slotsPerRow;
uniform int slices;
uniform float cooling;
uniform vec3 origin;
uniform float h;
uniform ivec3 cells;
uniform ivec4 target;
uniform vec2 size;
flat out vec4 blob;
flat out float heat;
flat out ivec3 lo;
void main() {
  int slot = gl_InstanceID / slices;
  int dz = gl_InstanceID - slot * slices;
  ivec2 p = ivec2(slot % slotsPerRow, slot / slotsPerRow);
  vec4 a = texelFetch(centres, p, 0);
  vec4 b = texelFetch(masses, p, 0);
  float sigma = sqrt(max(a.w, 0.0));
  gl_Position = vec4(2.0, 2.0, 0.0, 1.0);
  blob = vec4(a.xyz, sigma);
  heat = b.w == 0.0 ? 0.0 : b.w * exp(-cooling * b.y);
  if (!(b.x > 0.0) || heat == 0.0 || !(sigma > 0.0)) return;
  // The cells the blob reaches along each axis, [lo, hi) (the core's bounds, f32 as there).
  float reach = ${REACH.toFixed(1)} * sigma;
  ivec3 hi;
  for (int k = 0; k < 3; k++) {
    lo[k] = int(max(floor((a[k] - reach - origin[k]) / h), 0.0));
    hi[k] = min(int(max(ceil((a[k] + reach - origin[k]) / h), 0.0)), cells[k]);
  }
  int z = lo.z + dz;
  if (lo.x >= hi.x || lo.y >= hi.y || z >= hi.z) return;
  // This instance's rectangle of cells in slice z's tile of the atlas.
  ivec2 tile = ivec2(target.x * (z % target.w), target.y * (z / target.w));
  int corner = gl_VertexID;
  bool right = corner == 1 || corner == 2 || corner == 4;
  bool top = corner == 2 || corner == 4 || corner == 5;
  vec2 texel = vec2(tile + ivec2(right ? hi.x : lo.x, top ? hi.y : lo.y));
  gl_Position = vec4(texel / size * 2.0 - 1.0, 0.0, 1.0);
  lo.z = z;
}`;

const FRAGMENT = /* glsl */ `#version 300 es
precision highp float;
precision highp int;
uniform vec3 origin;
uniform float h;
uniform ivec4 target;
flat in vec4 blob;
flat in float heat;
flat in ivec3 lo;
out vec4 added;
// Φ(t), the standard normal distribution, by erf (Abramowitz & Stegun 7.1.26: |error| ≤ 1.5e-7),
// cut at ±REACH as in the core.
float normalCdf(float t) {
  if (t <= -${REACH.toFixed(1)}) return 0.0;
  if (t >= ${REACH.toFixed(1)}) return 1.0;
  float x = abs(t) * 0.70710678;
  float k = 1.0 / (1.0 + 0.3275911 * x);
  float poly = k * (0.254829592 + k * (-0.284496736 + k * (1.421413741 + k * (-1.453152027 + k * 1.061405429))));
  float erfAbs = 1.0 - poly * exp(-x * x);
  return 0.5 * (1.0 + (t < 0.0 ? -erfAbs : erfAbs));
}
// The blob's share of the cell from x0 to x1 along one axis, per metre.
float share(float x0, float x1, float c, float s) {
  return (normalCdf((x1 - c) / s) - normalCdf((x0 - c) / s)) / h;
}
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 cell = p - target.xy * (p / target.xy);
  // The cell's edges as the core places them, origin + h·m.
  vec3 m = vec3(float(cell.x), float(cell.y), float(lo.z));
  vec3 x0 = origin + h * m;
  vec3 x1 = origin + h * (m + 1.0);
  float s = blob.w;
  float w = heat * share(x0.z, x1.z, blob.z, s) * share(x0.y, x1.y, blob.y, s);
  added = vec4(w * share(x0.x, x1.x, blob.x, s), 0.0, 0.0, 0.0);
}`;

export class HeatDeposit {
  constructor(gl) {
    this.gl = gl;
    gl.getExtension('EXT_float_blend');
    const program = linkProgram(gl, VERTEX, FRAGMENT);
    this.program = program;
    this.at = (name) => gl.getUniformLocation(program, name);
  }

  /**
   * Writes T (K) on every cell of `flow` (a GpuFlow, into its temperature lattice) from the
   * blobs of the GPU stepper's state: `centres` and `masses` its raw textures ([centre, σ²] and
   * [mass, age, τ, h0] a slot, `slotsPerRow` slots a row), `slots` slots in use, none wider than
   * `sigmaMax` (m), cooling `cooling` (1/s).
   */
  deposit(flow, { centres, masses, slotsPerRow, slots, sigmaMax, cooling }) {
    const gl = this.gl;
    const target = flow.temperature;
    const atlas = target.atlas;
    passState(gl);
    gl.bindFramebuffer(gl.FRAMEBUFFER, target.framebuffer);
    gl.viewport(0, 0, atlas.width, atlas.height);
    gl.clearColor(0, 0, 0, 0);
    gl.clear(gl.COLOR_BUFFER_BIT);
    const h = flow.h;
    // The most z slices one blob reaches: its cells from ⌊(c − r)/h⌋ to ⌈(c + r)/h⌉, r = 4σ.
    const slices = Math.min(Math.ceil((2 * REACH * sigmaMax) / h) + 2, flow.cells[2]);
    if (!(slots > 0) || !(slices > 0)) return;
    gl.useProgram(this.program);
    gl.activeTexture(gl.TEXTURE0);
    gl.bindTexture(gl.TEXTURE_2D, centres);
    gl.uniform1i(this.at('centres'), 0);
    gl.activeTexture(gl.TEXTURE1);
    gl.bindTexture(gl.TEXTURE_2D, masses);
    gl.uniform1i(this.at('masses'), 1);
    gl.uniform1i(this.at('slotsPerRow'), slotsPerRow);
    gl.uniform1i(this.at('slices'), slices);
    gl.uniform1f(this.at('cooling'), cooling);
    gl.uniform3fv(this.at('origin'), flow.origin);
    gl.uniform1f(this.at('h'), h);
    gl.uniform3iv(this.at('cells'), flow.cells);
    gl.uniform4iv(this.at('target'), atlas.uniform);
    gl.uniform2f(this.at('size'), atlas.width, atlas.height);
    gl.enable(gl.BLEND);
    gl.blendEquation(gl.FUNC_ADD);
    gl.blendFunc(gl.ONE, gl.ONE);
    gl.drawArraysInstanced(gl.TRIANGLES, 0, 6, slots * slices);
    gl.disable(gl.BLEND);
  }

  dispose() {
    this.gl.deleteProgram(this.program);
  }
}
