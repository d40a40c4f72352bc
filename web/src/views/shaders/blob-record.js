// GLSL: the packed blob record (`frame::packed` in the core), as every GPU view reads it from the
// blob texture (`blob-texture.js`): WORDS_PER_BLOB 32-bit words a blob, two RGBA32UI texels,
// BLOBS_PER_ROW blobs a row.

import { BLOBS_PER_ROW, WORDS_PER_BLOB } from '../../generated/contract.js';

/** `fetchBlob(i, …)`: blob i of the packed frame (centre m, σ m, mass, albedo Ω, source (1 − Ω)Q). */
export const BLOB_GLSL = /* glsl */ `
uniform highp usampler2D blobTex;
void fetchBlob(int i, out vec3 centre, out float sigma, out float mass, out vec3 albedo, out vec3 source) {
  ivec2 p = ivec2((i % ${BLOBS_PER_ROW}) * ${WORDS_PER_BLOB / 4}, i / ${BLOBS_PER_ROW});
  uvec4 a = texelFetch(blobTex, p, 0);
  uvec4 b = texelFetch(blobTex, p + ivec2(1, 0), 0);
  centre = uintBitsToFloat(a.xyz);
  sigma = uintBitsToFloat(a.w);
  mass = uintBitsToFloat(b.x);
  vec2 h0 = unpackHalf2x16(b.y);
  vec2 h1 = unpackHalf2x16(b.z);
  vec2 h2 = unpackHalf2x16(b.w);
  albedo = vec3(h0, h1.x);
  source = vec3(h1.y, h2);
}
`;
