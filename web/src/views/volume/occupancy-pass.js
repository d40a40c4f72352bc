// Where the gas is, brick by brick, for the march to leap over empty space: for each brick of
// BRICK³ voxels of the density grid, the largest density of the voxels a trilinear sample inside
// the brick can reach (the brick and one voxel around it). Drawn in one draw into a 2-D atlas of
// the brick grid's slices. A march that skips bricks whose value is 0 takes exactly the samples
// it would have taken without skipping wherever there is gas, so its image is unchanged.

import { ScreenPass } from '../screen-pass.js';
import { ATLAS_PASS_GLSL } from './glsl.js';

/** Voxels per side of a brick. */
export const BRICK = 8;

/** The brick grid over density grid dimensions `dims`. */
export function brickDims(dims) {
  return dims.map((n) => Math.ceil(n / BRICK));
}

/**
 * GLSL for the march: `emptyBrick(x, lo, hi)` is true where the brick holding x (m) has no gas
 * within reach, and gives that brick's corners (m).
 */
export const BRICK_GLSL = /* glsl */ `
uniform sampler2D occupancy;
uniform ivec3 bricks;
uniform int brickCols;
bool emptyBrick(vec3 x, out vec3 lo, out vec3 hi) {
  float side = grid.h * ${BRICK.toFixed(1)};
  ivec3 b = clamp(ivec3(floor((x - grid.lo) / side)), ivec3(0), bricks - 1);
  lo = grid.lo + side * vec3(b);
  hi = lo + side;
  return texelFetch(occupancy, atlasTexel(b, bricks, brickCols), 0).x <= 0.0;
}
`;

const fragmentShader = /* glsl */ `
${ATLAS_PASS_GLSL}
uniform Grid grid;
uniform int atlasCols;
uniform sampler2D densityAtlas;
uniform ivec3 bricks;
uniform int brickCols;
out vec4 outMax;

void main() {
  ivec3 b;
  outMax = vec4(0.0);
  if (!atlasVoxel(ivec2(gl_FragCoord.xy), bricks, brickCols, b)) return;
  ivec3 lo = max(b * ${BRICK} - 1, ivec3(0));
  ivec3 hi = min(b * ${BRICK} + ${BRICK}, grid.dims - 1);
  float most = 0.0;
  for (int z = lo.z; z <= hi.z; z++) {
    ivec2 corner = atlasTexel(ivec3(0, 0, z), grid.dims, atlasCols);
    for (int y = lo.y; y <= hi.y; y++) {
      for (int x = lo.x; x <= hi.x; x++) most = max(most, texelFetch(densityAtlas, corner + ivec2(x, y), 0).x);
    }
  }
  outMax = vec4(most);
}
`;

export class OccupancyPass extends ScreenPass {
  /** @param {object} shared uniforms: grid, atlasCols */
  constructor(shared) {
    super(fragmentShader, {
      grid: shared.grid, atlasCols: shared.atlasCols, densityAtlas: { value: null }, bricks: { value: [1, 1, 1] }, brickCols: { value: 1 },
    });
  }

  /**
   * Fills `target` (an atlas of the brick grid `bricks`, `cols` slices to a row) from the density
   * atlas `density` (a texture).
   */
  fill(renderer, target, density, bricks, cols) {
    const u = this.material.uniforms;
    u.densityAtlas.value = density;
    u.bricks.value = bricks;
    u.brickCols.value = cols;
    renderer.setRenderTarget(target);
    this.render(renderer);
  }
}
