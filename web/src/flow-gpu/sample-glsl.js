// GLSL for the blobs' step on the GPU (`stepper/`): the flow's u_g frozen for a step as the core's
// `wind::flow::FrozenFlow` reads it, trilinear on each component's faces inside the box (the
// core's `FaceSampler::at`: the traces' lattices in cells, clamped to the samples), beyond the
// box the value at its nearest point faded to 0 across one cell by a smoothstep in each axis's
// distance. `flowUniforms` gives a GpuFlow's values for the names below.

import { ATLAS_CELLS_GLSL } from './gl.js';

const f32 = Math.fround;

/**
 * `float flowWeight(vec3 x)`: how much of u_g acts at x (m): 1 in the box, 0 a cell or more
 * outside it; `vec3 flowVelocity(vec3 x)`: u_g at x (m/s), unfaded (the box's nearest point).
 */
export const FLOW_SAMPLE_GLSL = /* glsl */ `
uniform highp sampler2D flowU;
uniform highp sampler2D flowV;
uniform highp sampler2D flowW;
uniform ivec4 flowUL;
uniform ivec4 flowVL;
uniform ivec4 flowWL;
uniform vec3 flowOrigin;
uniform float flowInvH;
uniform vec3 flowLo;
uniform vec3 flowHi;
${ATLAS_CELLS_GLSL}
float flowWeight(vec3 x) {
  return fadeBeyond(max(max(flowLo - x, x - flowHi), vec3(0.0)) * flowInvH);
}
float flowComponent(highp sampler2D t, ivec4 L, vec3 o, vec3 q) {
  float c[8];
  vec3 f;
  cornersCells(t, L, o, q, c, f);
  return blend(c, f);
}
vec3 flowVelocity(vec3 x) {
  vec3 q = (clamp(x, flowLo, flowHi) - flowOrigin) * flowInvH;
  return vec3(
    flowComponent(flowU, flowUL, vec3(0.0, 0.5, 0.5), q),
    flowComponent(flowV, flowVL, vec3(0.5, 0.0, 0.5), q),
    flowComponent(flowW, flowWL, vec3(0.5, 0.5, 0.0), q));
}
`;

/**
 * The values of FLOW_SAMPLE_GLSL's uniforms but the three samplers for `flow` (a GpuFlow): the
 * atlases of its current faces, its origin, 1/h and the box's corners (the core's f32
 * arithmetic: hi = lo + n·h).
 */
export function flowUniforms(flow) {
  const [u, v, w] = flow.u.map((p) => p.now.atlas.uniform);
  const lo = flow.origin;
  const hi = lo.map((x, a) => f32(x + f32(flow.cells[a] * flow.h)));
  return { flowUL: u, flowVL: v, flowWL: w, flowOrigin: lo, flowInvH: f32(1 / flow.h), flowLo: lo, flowHi: hi };
}
