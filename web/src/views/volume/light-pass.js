// The light volume (the real-time view's second pass): for each voxel of a grid of half the
// density grid's resolution, the optical column ∫ρ ds towards each light (up to four, one per
// channel), a midpoint sum through the density volume along the path inside the density grid's
// box and short of a point light, in ⌈length / (step·h)⌉ equal steps — as
// `render::volume::light_columns` in the core. Drawn slice by slice into a 3-D target. The march
// and the objects read S_k = exp(−κ_t · column) from it (Eq. 25).

import * as THREE from 'three';
import { GRID_GLSL } from './glsl.js';
import { LIGHTS_GLSL, MAX_LIGHTS } from '../gas-uniforms.js';
/** Most steps of one column (a 256-voxel diagonal at step 0.5 is 887). */
const MAX_COLUMN_STEPS = 1024;

const vertexShader = /* glsl */ `
void main() { gl_Position = vec4(position.xy, 0.0, 1.0); }
`;

const fragmentShader = /* glsl */ `
precision highp float;
precision highp int;
${GRID_GLSL}
uniform sampler3D densityVolume;
uniform Grid grid;       // the density grid
uniform Grid lightGrid;  // voxels of 2h
uniform float columnStep;
uniform int slice;       // the light grid's slice being drawn
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
  return sum * ds;
}

void main() {
  ivec2 ij = ivec2(gl_FragCoord.xy);
  if (any(greaterThanEqual(ij, lightGrid.dims.xy))) {
    outColumns = vec4(0.0);
    return;
  }
  vec3 x = lightGrid.lo + lightGrid.h * (vec3(ivec3(ij, slice)) + 0.5);
  vec4 c = vec4(0.0);
  for (int l = 0; l < ${MAX_LIGHTS}; l++) {
    if (l >= lightCount) break;
    c[l] = column(x, l);
  }
  outColumns = c;
}
`;

export class LightPass {
  /** @param {object} shared uniforms: the gas uniforms, densityVolume, grid, lightGrid */
  constructor(shared) {
    this.material = new THREE.ShaderMaterial({
      glslVersion: THREE.GLSL3,
      vertexShader,
      fragmentShader,
      uniforms: { ...shared, columnStep: { value: 1 }, slice: { value: 0 } },
      depthTest: false,
      depthWrite: false,
    });
    this.quad = new THREE.Mesh(new THREE.PlaneGeometry(2, 2), this.material);
    this.quad.frustumCulled = false;
    this.scene = new THREE.Scene();
    this.scene.add(this.quad);
    this.camera = new THREE.OrthographicCamera(-1, 1, 1, -1, 0, 1);
  }

  /** Fills the first `slices` layers of `target` (a 3-D target) with columns, steps of `step × h`. */
  render(renderer, target, slices, step) {
    const u = this.material.uniforms;
    u.columnStep.value = step;
    for (let k = 0; k < slices; k++) {
      u.slice.value = k;
      renderer.setRenderTarget(target, k);
      renderer.render(this.scene, this.camera);
    }
  }
}
