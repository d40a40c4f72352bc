// GLSL: the start of a march's fragment shader (the exact march, the real-time view's march and
// its upsampling), over the uniforms `views/march-quad.js` gives its quad.

/**
 * Precisions, the quad's `vUv` in, `outColor` out, `behindAt(uv, depth)`: what the opaque pass
 * left at uv and its depth (1 where it drew nothing), `viewDepth(d)`, and
 * `viewRay(uv, rd, sMax, behind)`: the pixel's ray, where the opaque pass ends it, what lies there.
 */
export const MARCH_PREAMBLE = /* glsl */ `
precision highp float;
precision highp int;
precision highp sampler2D;
in vec2 vUv;
layout(location = 0) out vec4 outColor;
uniform sampler2D opaqueColor;
uniform sampler2D opaqueDepth;
uniform bool hasOpaque;
uniform vec2 resolution;
uniform vec3 camPos, camForward, camRight, camUp;
uniform float tanHalf, camNear, camFar;
uniform vec3 background;

vec3 behindAt(vec2 uv, out float depth) {
  depth = hasOpaque ? texture(opaqueDepth, uv).x : 1.0;
  return depth < 1.0 ? texture(opaqueColor, uv).rgb : background;
}

// Distance (m) along the view axis of an opaque-pass depth d < 1.
float viewDepth(float d) {
  float zN = d * 2.0 - 1.0;
  return 2.0 * camNear * camFar / (camFar + camNear - zN * (camFar - camNear));
}

void viewRay(vec2 uv, out vec3 rd, out float sMax, out vec3 behind) {
  vec2 ndc = gl_FragCoord.xy / resolution * 2.0 - 1.0;
  float aspect = resolution.x / resolution.y;
  rd = normalize(camForward + camRight * ndc.x * tanHalf * aspect + camUp * ndc.y * tanHalf);
  float d;
  behind = behindAt(uv, d);
  sMax = d < 1.0 ? viewDepth(d) / dot(rd, camForward) : 1e30;
}
`;
