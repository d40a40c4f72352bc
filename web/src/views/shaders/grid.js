// GLSL: a voxel grid and its 3-D texture (`frame::volume::VoxelGrid` in the core).

/**
 * `struct Grid` and `sampleVolume(tex, grid, p)`: trilinear between voxel centres, held beyond
 * the outermost ones (as `VoxelGrid::sample`). The texture may be larger than the grid (`size`),
 * so that it is remade only now and then.
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
`;
