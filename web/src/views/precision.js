// What the GPU can store, blend and filter, and the precision each GPU pass takes from it.
// Many phones' WebGL2 renders to no 32-bit float colour buffer (EXT_color_buffer_float missing:
// only EXT_color_buffer_half_float), blends none (EXT_float_blend missing), or filters none
// (OES_texture_float_linear missing); then a pass stores 16-bit floats (11 significant bits,
// largest 65,504) instead. Every pass works in either; its values are kept in units that suit
// half floats whatever the GPU (`volume-layer.js`: optical depths), so on a full GPU it draws
// the same image to the float's last bits. docs/ARCHITECTURE.md says what each pass needs and why.

import * as THREE from 'three';

/**
 * The GPU's float formats through `renderer` (three.js asks for the extensions once):
 * `float32Targets` (renders to RGBA32F), `float32Blend` (adds into it), `float32Filter`
 * (filters it linearly), `halfTargets` (renders to RGBA16F, which blends and filters wherever
 * it renders), the largest 2-D and 3-D texture sides, and which extensions are missing.
 */
export function gpuFormats(renderer) {
  const has = (name) => renderer.extensions.has(name);
  const gl = renderer.getContext();
  const float32Targets = has('EXT_color_buffer_float');
  const formats = {
    float32Targets,
    float32Blend: float32Targets && has('EXT_float_blend'),
    float32Filter: has('OES_texture_float_linear'),
    halfTargets: float32Targets || has('EXT_color_buffer_half_float'),
    maxTextureSize: renderer.capabilities.maxTextureSize,
    max3dTextureSize: gl.getParameter(gl.MAX_3D_TEXTURE_SIZE) ?? 256,
  };
  formats.missing = ['EXT_color_buffer_float', 'EXT_float_blend', 'OES_texture_float_linear'].filter((n) => !has(n));
  return formats;
}

/**
 * The precision ('float32' or 'float16') of each pass that stores floats, on a GPU of `formats`:
 * - `density`: the real-time view's splat and particle mesh, which add blobs into an atlas by
 *   blending, and the density and source volumes copied from it and filtered by the march:
 *   32-bit where the GPU blends and filters 32-bit floats.
 * - `light`: the light columns, written once a voxel (no blending) and filtered by the march
 *   and the objects: 32-bit where the GPU renders to and filters 32-bit floats.
 * - `points`: the points view's sums of the sprites' optical depths, blended: 32-bit where
 *   the GPU blends 32-bit floats (read texel for texel, never filtered).
 */
export function passPrecision(formats) {
  const of = (full) => (full ? 'float32' : 'float16');
  return {
    density: of(formats.float32Blend && formats.float32Filter),
    light: of(formats.float32Targets && formats.float32Filter),
    points: of(formats.float32Blend),
  };
}

/** The three.js texel type of a precision. */
export function texelType(precision) {
  return precision === 'float32' ? THREE.FloatType : THREE.HalfFloatType;
}

/**
 * What a GPU of `formats` gives up against a full one, one phrase each: which extension is
 * missing and what is done instead (empty on a full GPU).
 */
export function formatsGaveUp(formats) {
  const out = [];
  const precision = passPrecision(formats);
  const halves = [];
  if (precision.density === 'float16') halves.push('the real-time view\'s density volume');
  if (precision.light === 'float16') halves.push('its light columns');
  if (precision.points === 'float16') halves.push('the points view\'s sums');
  if (halves.length > 0) {
    const missing = formats.missing.join(', ');
    out.push(`no ${missing}: ${listed(halves)} in 16-bit floats`);
  }
  if (!formats.float32Targets) out.push('no EXT_color_buffer_float: the worker steps the gas');
  if (!formats.halfTargets) out.push('no EXT_color_buffer_half_float either: the real-time and points views cannot draw the gas');
  return out;
}

/** 'a', 'a and b', 'a, b and c'. */
function listed(items) {
  return items.length < 2 ? items.join('') : `${items.slice(0, -1).join(', ')} and ${items.at(-1)}`;
}
