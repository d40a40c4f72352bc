// The real-time view's own GLSL preamble for its atlas passes, and the uniform value of a grid.
// The chunks it shares with other views (the blob record, erf, the voxel grid, its atlas
// addressing) are in `../shaders/`.

import { VOXEL_GRID_GLSL } from '../shaders/voxel-grid.js';

/** The start of a fragment shader drawing into an atlas of a grid's slices: precisions, the voxel grid. */
export const ATLAS_PASS_GLSL = /* glsl */ `
precision highp float;
precision highp int;
precision highp sampler2D;
${VOXEL_GRID_GLSL}
`;

/** The uniform value of a `Grid` for a fitted grid held in a texture of `size` texels per axis. */
export function gridUniform(grid, size) {
  return { lo: grid.lo.slice(), h: grid.h, dims: grid.dims.slice(), size: size.slice() };
}
