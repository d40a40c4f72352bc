// The light volume (the real-time view's second pass): for each voxel of a grid of half the
// density grid's resolution, the optical column ∫ρ ds towards each light (up to four, one per
// channel), a midpoint sum through the density volume along the path inside the density grid's
// box and short of a point light, in ⌈length / (step·h)⌉ equal steps — as
// `frame::light_volume::light_columns` in the core. Drawn in one draw into a 2-D atlas of the light
// grid's slices (then copied into a 3-D texture, `slice-copy.js`). The march and the objects
// read S_k = exp(−κ_t · column) from it (Eq. 25). It reads densities stored times densityScale
// and stores columns times columnScale (optical depths, `volume-layer.js`), at most 65,504 (a
// half float's largest: a column that deep lets no light through).

import { ScreenPass } from '../screen-pass.js';
import { VIEW_LIGHTS } from '../../generated/contract.js';
import { LIGHTS_GLSL } from '../shaders/lights.js';
import { ATLAS_PASS_GLSL } from './glsl.js';
/** Most steps of one column (a 256-voxel diagonal at step 0.5 is 887). */
const MAX_COLUMN_STEPS = 1024;

const fragmentShader = /* glsl */ `
${ATLAS_PASS_GLSL}
uniform sampler3D densityVolume;
uniform Grid grid;       // the density grid
uniform Grid lightGrid;  // voxels of 2h
uniform float columnStep;
uniform float densityScale;
uniform float columnScale;
uniform int lightCols;   // light grid slice k is the atlas tile at column k mod lightCols, row ⌊k / lightCols⌋
${LIGHTS_GLSL}
out vec4 outColumns;

float column(vec3 x, int l) {
  float toLight;
  vec3 d = towardsLight(l, x, toLight);
  vec3 hi = grid.lo + grid.h * vec3(grid.dims);
  float len = min(exitDistance(x, d, grid.lo, hi), toLight);
  if (len <= 0.0) return 0.0;
  float n = max(ceil(len / (columnStep * grid.h)), 1.0);
  float ds = len / n;
  float sum = 0.0;
  for (int k = 0; k < ${MAX_COLUMN_STEPS}; k++) {
    if (float(k) >= n) break;
    sum += sampleVolume(densityVolume, grid, x + d * ((float(k) + 0.5) * ds)).x;
  }
  return sum * ds / densityScale;
}

void main() {
  ivec3 v;
  if (!atlasVoxel(ivec2(gl_FragCoord.xy), lightGrid.dims, lightCols, v)) {
    outColumns = vec4(0.0);
    return;
  }
  vec3 x = lightGrid.lo + lightGrid.h * (vec3(v) + 0.5);
  vec4 c = vec4(0.0);
  for (int l = 0; l < ${VIEW_LIGHTS}; l++) {
    if (l >= lightCount) break;
    c[l] = column(x, l);
  }
  outColumns = min(c * columnScale, vec4(65504.0));
}
`;

export class LightPass extends ScreenPass {
  /** @param {object} shared uniforms: the gas uniforms (with densityScale, columnScale, grid, lightGrid), densityVolume */
  constructor(shared) {
    super(fragmentShader, { ...shared, columnStep: { value: 1 }, lightCols: { value: 1 } });
  }

  /**
   * Fills `target` (a 2-D atlas of the light grid's slices, `cols` to a row) with columns, in
   * steps of `step × h`.
   */
  fill(renderer, target, cols, step) {
    const u = this.material.uniforms;
    u.columnStep.value = step;
    u.lightCols.value = cols;
    renderer.setRenderTarget(target);
    this.render(renderer);
  }
}
