// GLSL: a grid's slices laid out as the tiles of a 2-D atlas (slice k at column k mod cols, row
// ⌊k / cols⌋; `atlasLayout` in `views/volume/grid.js` lays them out).

/** `atlasVoxel(px, dims, cols, v)`: the voxel at atlas texel px (false past the grid); `atlasTexel(v, dims, cols)`: the texel of voxel v. */
export const ATLAS_GLSL = /* glsl */ `
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
`;
