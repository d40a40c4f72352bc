// GLSL shared by the real-time view's passes: the packed blob record (`render::frame` in the
// core), erf, and trilinear sampling of a voxel grid held in a 3-D texture.

/** Blobs per row of the blob texture (two RGBA32UI texels each). */
export const BLOBS_PER_ROW = 1024;

/** `fetchBlob(i, …)`: blob i of the packed frame (centre m, σ m, mass, albedo Ω, source (1 − Ω)Q). */
export const BLOB_GLSL = /* glsl */ `
uniform highp usampler2D blobTex;
void fetchBlob(int i, out vec3 centre, out float sigma, out float mass, out vec3 albedo, out vec3 source) {
  ivec2 p = ivec2((i % ${BLOBS_PER_ROW}) * 2, i / ${BLOBS_PER_ROW});
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

/** erf by Abramowitz & Stegun 7.1.26 (|error| < 1.5e-7). */
export const ERF_GLSL = /* glsl */ `
float erf1(float x) {
  float s = sign(x);
  x = abs(x);
  float t = 1.0 / (1.0 + 0.3275911 * x);
  float y = 1.0 - (((((1.061405429 * t - 1.453152027) * t) + 1.421413741) * t - 0.284496736) * t + 0.254829592) * t * exp(-x * x);
  return s * y;
}
`;

/**
 * A voxel grid and its 3-D texture: `sampleVolume(tex, grid, p)` interpolates trilinearly
 * between voxel centres (held beyond the outermost ones, as `VoxelGrid::sample` in the core).
 * The texture may be larger than the grid (`size`), so that it is remade only now and then.
 * `atlasVoxel` and `atlasTexel` address a grid's slices laid out as the tiles of a 2-D atlas.
 */
export const GRID_GLSL = /* glsl */ `
precision highp sampler3D;
struct Grid {
  vec3 lo;      // corner (m)
  float h;      // voxel side (m)
  ivec3 dims;   // voxels per axis
  vec3 size;    // the texture's texels per axis
};
vec4 sampleVolume(sampler3D tex, Grid g, vec3 p) {
  vec3 c = clamp((p - g.lo) / g.h, vec3(0.5), vec3(g.dims) - 0.5);
  return texture(tex, c / g.size);
}
// A grid's slices as tiles of a 2-D atlas, slice k at column k mod cols, row ⌊k / cols⌋: the
// voxel v at atlas texel px (false past the grid), and the texel of voxel v.
bool atlasVoxel(ivec2 px, ivec3 dims, int cols, out ivec3 v) {
  ivec2 tile = px / dims.xy;
  v = ivec3(px - tile * dims.xy, tile.y * cols + tile.x);
  return tile.x < cols && v.z < dims.z;
}
ivec2 atlasTexel(ivec3 v, ivec3 dims, int cols) {
  return ivec2(v.z % cols, v.z / cols) * dims.xy + v.xy;
}
// Distance from x (inside the box) along unit d to the box's boundary.
float exitDistance(vec3 x, vec3 d, vec3 lo, vec3 hi) {
  vec3 far = mix(lo, hi, step(vec3(0.0), d));
  vec3 t = (far - x) / d;
  t = mix(t, vec3(1e30), equal(d, vec3(0.0)));
  return max(min(t.x, min(t.y, t.z)), 0.0);
}
`;

/** The start of a fragment shader drawing into an atlas of a grid's slices: precisions, GRID_GLSL. */
export const ATLAS_PASS_GLSL = /* glsl */ `
precision highp float;
precision highp int;
precision highp sampler2D;
${GRID_GLSL}
`;

/** The uniform value of a `Grid` for a fitted grid held in a texture of `size` texels per axis. */
export function gridUniform(grid, size) {
  return { lo: grid.lo.slice(), h: grid.h, dims: grid.dims.slice(), size: size.slice() };
}
