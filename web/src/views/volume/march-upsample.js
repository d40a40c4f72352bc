// The march at a lower resolution than the view, brought up to the view's: the march writes the
// gas's radiance and transmittance (and the depth its ray stopped at) per low-resolution pixel,
// and this pass composites them over the full-resolution opaque pass, rad + T · behind, with
// each of the four nearest low-resolution pixels weighted bilinearly and by how near its depth
// is to the pixel's own (a joint bilateral upsampling), so gas does not bleed across the edges
// of objects. The volume the march reads is coarser than the view (about a hundred voxels
// across the gas at `standard`): at two view pixels a march pixel the gas loses little.

import * as THREE from 'three';
import { ScreenPass } from '../screen-pass.js';
import { LIGHTS_GLSL } from '../shaders/lights.js';
import { MARCH_PREAMBLE } from '../shaders/march-preamble.js';

/**
 * `stoppedAt(d)`: the view depth (m) of depth-buffer value d, the far plane where nothing was
 * drawn, and at most 60 km, so that it fits the march's target in half floats too (the far
 * plane lies a million metres out, past the ground planes' edges).
 */
const STOPPED_AT_GLSL = /* glsl */ `
float stoppedAt(float d) {
  return min(d < 1.0 ? viewDepth(d) : camFar, 6.0e4);
}
`;

/** The march's own outputs in its split form (after MARCH_PREAMBLE's outColor, location 0). */
export const SPLIT_OUTPUTS_GLSL = /* glsl */ `
layout(location = 1) out vec4 outTransmittance;
${STOPPED_AT_GLSL}
// Radiance (rgb) and transmittance (rgb) of the gas, and the view depth (m) where the ray stopped,
// at most MAX_DEPTH.
void writeSplit(vec3 rad, vec3 T) {
  float d;
  behindAt(vUv, d);
  outColor = vec4(rad, 1.0);
  outTransmittance = vec4(T, stoppedAt(d));
}
`;

const fragmentShader = /* glsl */ `
${MARCH_PREAMBLE}
${LIGHTS_GLSL}
uniform sampler2D marchRadiance;
uniform sampler2D marchTransmittance;
${STOPPED_AT_GLSL}

void main() {
  float d;
  vec3 behind = behindAt(vUv, d);
  float z = stoppedAt(d);
  ivec2 size = textureSize(marchRadiance, 0);
  vec2 p = vUv * vec2(size) - 0.5;
  ivec2 p0 = ivec2(floor(p));
  vec2 f = p - floor(p);
  vec3 rad = vec3(0.0);
  vec3 T = vec3(0.0);
  float total = 0.0;
  for (int i = 0; i < 4; i++) {
    ivec2 o = ivec2(i & 1, i >> 1);
    ivec2 q = clamp(p0 + o, ivec2(0), size - 1);
    vec2 b = mix(1.0 - f, f, vec2(o));
    vec4 t = texelFetch(marchTransmittance, q, 0);
    float w = b.x * b.y * (1e-4 + exp(-8.0 * abs(t.a - z) / z));
    rad += w * texelFetch(marchRadiance, q, 0).rgb;
    T += w * t.rgb;
    total += w;
  }
  outColor = vec4(encode((rad + T * behind) / total), 1.0);
}
`;

export class MarchUpsample extends ScreenPass {
  /** @param {object} uniforms the march's (opaque pass, camera, background) and the gas's */
  constructor(uniforms) {
    super(fragmentShader, { ...uniforms, marchRadiance: { value: null }, marchTransmittance: { value: null } });
    this.target = null;
  }

  /** The march's target at `width × height`: radiance, transmittance and depth (remade on resize). */
  targetFor(width, height) {
    if (this.target?.width !== width || this.target?.height !== height) {
      this.target?.dispose();
      this.target = new THREE.WebGLRenderTarget(width, height, {
        type: THREE.HalfFloatType,
        count: 2,
        depthBuffer: false,
        minFilter: THREE.NearestFilter,
        magFilter: THREE.NearestFilter,
      });
    }
    return this.target;
  }

  /** Composites the march's target over the opaque pass into the renderer's current target. */
  composite(renderer) {
    const u = this.material.uniforms;
    u.marchRadiance.value = this.target.textures[0];
    u.marchTransmittance.value = this.target.textures[1];
    this.render(renderer);
  }

  dispose() {
    this.target?.dispose();
    super.dispose();
  }
}

/** The march's resolution for a view of `width × height` drawing at most `pixels` pixels. */
export function marchSize(width, height, pixels) {
  const scale = Math.min(1, Math.sqrt(pixels / (width * height)));
  return scale >= 1 ? [width, height] : [Math.max(1, Math.round(width * scale)), Math.max(1, Math.round(height * scale))];
}
