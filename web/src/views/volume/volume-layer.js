// The real-time volume view (DESIGN §1, §5 `raymarch`): the frame's blobs splatted on the GPU
// into a density volume, a light volume of shadow columns computed from it, and a ray march of
// the volume with jittered steps, composited over the opaque pass by depth. Its cost per frame
// grows with pixels and with the voxels the gas fills, not with the blob count (only the splat,
// a few fragments a blob, does). The splat draws into a 2-D atlas of slices, which is copied
// slice by slice into 3-D textures for hardware trilinear sampling. The volumes are rebuilt
// only when the frame, the quality or the lights change: orbiting a paused scene re-runs the
// march alone.

import * as THREE from 'three';
import { LIGHTS_GLSL } from '../gas-uniforms.js';
import { waitForGpu } from '../gpu-sync.js';
import { MARCH_PREAMBLE, MarchQuad } from '../march-quad.js';
import { atlasLayout, fitGrid, halved, minVoxelFor } from './grid.js';
import { gridUniform } from './glsl.js';
import { LightPass } from './light-pass.js';
import { MARCH_GLSL, VOLUME_SHADOW_GLSL } from './march-glsl.js';
import { MeshPass } from './mesh-pass.js';
import { SplatPass } from './splat-pass.js';

/**
 * Per quality: the voxel budget of the density grid, the smallest voxel in units of the
 * narrowest blob's σ (finer voxels would resolve nothing more, as no blob is narrower), the
 * march's step and the light columns' step (both in voxels).
 */
export const VOLUME_QUALITY = {
  draft: { budget: 2 ** 18, voxelPerSigma: 1, step: 1, column: 1.5 },
  standard: { budget: 2 ** 20, voxelPerSigma: 1, step: 0.75, column: 1 },
  high: { budget: 2 ** 22, voxelPerSigma: 0.35, step: 0.5, column: 1 },
};

const fragmentShader = /* glsl */ `
${MARCH_PREAMBLE}
${LIGHTS_GLSL}
${VOLUME_SHADOW_GLSL}
${MARCH_GLSL}
uniform bool hasGas;

void main() {
  vec3 rd, behind;
  float sMax;
  viewRay(vUv, rd, sMax, behind);
  vec3 rad = vec3(0.0);
  vec3 T = vec3(1.0);
  if (hasGas) marchVolume(camPos, rd, sMax, rad, T);
  outColor = vec4(encode(rad + T * behind), 1.0);
}
`;

const EMPTY_GRID = { lo: [0, 0, 0], h: 1, dims: [2, 2, 2], size: [2, 2, 2] };

/** Targets grow in steps of this many texels per side, so they are remade only now and then. */
const ATLAS_STEP = 256;
const VOLUME_STEP = 16;

const roundUp = (n, step, max) => Math.min(max, Math.ceil(n / step) * step);

/** True if `target` (of `sizes`) holds `needed` and is not over four times larger. */
function fits(sizes, needed, step, max) {
  const area = (v) => v.reduce((a, b) => a * b, 1);
  return sizes.every((n, a) => n >= needed[a])
    && area(sizes) <= 4 * area(needed.map((n) => roundUp(n, step, max)));
}

const TARGET_OPTIONS = {
  format: THREE.RGBAFormat,
  depthBuffer: false,
  stencilBuffer: false,
  minFilter: THREE.LinearFilter,
  magFilter: THREE.LinearFilter,
  generateMipmaps: false,
};

/** The splat's atlas (`count` float targets) holding `layout`, reusing `target` if it can. */
function atlasTarget(target, layout, type, count, maxSize) {
  const needed = [layout.width, layout.height];
  if (target && target.textures.length === count && target.texture.type === type
      && fits([target.width, target.height], needed, ATLAS_STEP, maxSize)) return target;
  target?.dispose();
  const [w, h] = needed.map((n) => roundUp(n, ATLAS_STEP, maxSize));
  return new THREE.WebGLRenderTarget(w, h, { ...TARGET_OPTIONS, type, count });
}

/** A 3-D float target holding `dims` voxels, reusing `target` if it can. */
function volumeTarget(target, dims, type, max) {
  if (target && target.texture.type === type && fits([target.width, target.height, target.depth], dims, VOLUME_STEP, max)) return target;
  target?.dispose();
  const [w, h, d] = dims.map((n) => roundUp(n, VOLUME_STEP, max));
  const t = new THREE.WebGL3DRenderTarget(w, h, d, { ...TARGET_OPTIONS, type });
  t.texture.wrapR = THREE.ClampToEdgeWrapping;
  return t;
}

const sizeOf = (t) => [t.width, t.height, t.depth];

export class VolumeLayer extends MarchQuad {
  /**
   * @param {object} gas the shared gas uniforms (`gasUniforms()`); this layer fills its
   *   volume entries (lightTex, grid, lightGrid) for the objects' material too
   * @param {import('../blob-texture.js').BlobTexture} blobs
   */
  constructor(gas, blobs) {
    Object.assign(gas, {
      lightVolume: gas.lightVolume ?? { value: null },
      grid: gas.grid ?? { value: { ...EMPTY_GRID } },
      lightGrid: gas.lightGrid ?? { value: { ...EMPTY_GRID } },
    });
    const own = {
      blobTex: { value: null },
      densityVolume: { value: null },
      sourceVolume: { value: null },
      emissive: { value: false },
      stepScale: { value: 0.75 },
      hasGas: { value: false },
    };
    super(fragmentShader, { ...gas, ...own });
    this.gas = gas;
    this.blobs = blobs;
    this.own = own;
    this.atlasUniforms = { atlasCols: { value: 1 }, atlasSize: { value: [1, 1] } };
    this.splat = new SplatPass({ blobTex: own.blobTex, grid: gas.grid, ...this.atlasUniforms });
    this.mesh = new MeshPass({ blobTex: own.blobTex, grid: gas.grid, ...this.atlasUniforms });
    this.light = new LightPass({ ...gas, densityVolume: own.densityVolume });
    /** The splat's atlas and the mesh's two scratch atlases; the 3-D targets: density, emitted source, light columns. */
    this.atlas = null;
    this.scratch = [null, null];
    this.density = null;
    this.source = null;
    this.columns = null;
    this.info = null;
    this.frameSerial = 0;
    this.builtKey = '';
    /** The grid of the last build (m), for tests and the stats readout. */
    this.grid = null;
    /**
     * With `profile` set, each build waits for the GPU after each pass and records the passes'
     * times (ms) in `timings`: slower, for benchmarks only.
     */
    this.profile = false;
    this.timings = null;
  }

  /** A new frame: `info` is `frameInfo` parsed ({count, lo, hi, emissive, classes}). */
  setFrame(info) {
    this.info = info;
    this.frameSerial += 1;
  }

  /** Marks the volumes stale (lights or shadows changed). */
  invalidate() {
    this.builtKey = '';
  }

  #ensureTargets(renderer, grid, layout, emissive) {
    const type = renderer.extensions.has('EXT_float_blend') ? THREE.FloatType : THREE.HalfFloatType;
    const caps = renderer.capabilities;
    const max3d = renderer.getContext().getParameter(renderer.getContext().MAX_3D_TEXTURE_SIZE);
    const count = emissive ? 2 : 1;
    this.atlas = atlasTarget(this.atlas, layout, type, count, caps.maxTextureSize);
    this.scratch = this.scratch.map((t) => atlasTarget(t, layout, type, count, caps.maxTextureSize));
    this.density = volumeTarget(this.density, grid.dims, type, max3d);
    if (emissive) this.source = volumeTarget(this.source, grid.dims, type, max3d);
    this.columns = volumeTarget(this.columns, halved(grid).dims, THREE.FloatType, max3d);
    // Copies land in the 3-D textures before anything is drawn into them: allocate them now.
    for (const t of [this.density, this.source, this.columns]) if (t) renderer.initRenderTarget(t);
  }

  /** A stopwatch of GPU passes when profiling: each call returns ms since the last (0 if not). */
  #clock(renderer) {
    if (!this.profile) return () => 0;
    waitForGpu(renderer);
    let last = performance.now();
    return () => {
      waitForGpu(renderer);
      const now = performance.now();
      const ms = now - last;
      last = now;
      return ms;
    };
  }

  /** Copies the atlas's slices (attachment `i`) into the 3-D target `volume`. */
  #copySlices(renderer, i, volume, grid, cols) {
    const [nx, ny, nz] = grid.dims;
    const box = new THREE.Box2();
    const at = new THREE.Vector3();
    for (let k = 0; k < nz; k++) {
      box.min.set((k % cols) * nx, Math.floor(k / cols) * ny);
      box.max.set(box.min.x + nx, box.min.y + ny);
      renderer.copyTextureToTexture(this.atlas.textures[i], volume.texture, box, at.set(0, 0, k));
    }
  }

  /**
   * Builds the density and light volumes for the current frame at `quality` unless they are
   * already built. Returns false when there is no gas.
   */
  prepare(renderer, quality) {
    const info = this.info;
    const q = VOLUME_QUALITY[quality] ?? VOLUME_QUALITY.standard;
    const key = `${this.frameSerial}|${quality}|${this.gas.hasShadows.value}`;
    if (key === this.builtKey) return this.own.hasGas.value;
    this.builtKey = key;
    const hasGas = Boolean(info && info.count > 0);
    this.own.hasGas.value = hasGas;
    if (!hasGas) {
      this.grid = null;
      return false;
    }
    const maxSize = renderer.capabilities.maxTextureSize;
    const sigmaMax = Math.max(...info.classes.map((c) => c.sigmaMax));
    const minH = Math.max(minVoxelFor(sigmaMax), q.voxelPerSigma * info.sigmaMin);
    let budget = q.budget;
    let grid;
    let layout;
    for (;;) {
      grid = fitGrid(info.lo, info.hi, { budget, minH });
      layout = atlasLayout(grid.dims, maxSize);
      if (layout) break;
      budget /= 2;
    }
    this.grid = grid;
    this.#ensureTargets(renderer, grid, layout, info.emissive);
    this.gas.grid.value = gridUniform(grid, sizeOf(this.density));
    this.gas.lightGrid.value = gridUniform(halved(grid), sizeOf(this.columns));
    this.atlasUniforms.atlasCols.value = layout.cols;
    this.atlasUniforms.atlasSize.value = [this.atlas.width, this.atlas.height];
    this.own.blobTex.value = this.blobs.texture;
    this.own.emissive.value = info.emissive;
    this.own.stepScale.value = q.step;
    const clock = this.#clock(renderer);
    this.splat.render(renderer, this.atlas, info.classes, grid.h);
    const splat = clock();
    this.mesh.render(renderer, info, grid.h, this.atlas, ...this.scratch);
    const mesh = clock();
    this.#copySlices(renderer, 0, this.density, grid, layout.cols);
    if (info.emissive) this.#copySlices(renderer, 1, this.source, grid, layout.cols);
    const copy = clock();
    this.own.densityVolume.value = this.density.texture;
    this.own.sourceVolume.value = (info.emissive ? this.source : this.density).texture;
    if (this.gas.hasShadows.value && this.gas.lightCount.value > 0) {
      this.light.render(renderer, this.columns, halved(grid).dims[2], q.column);
    }
    this.gas.lightVolume.value = this.columns.texture;
    const light = clock();
    if (this.profile) this.timings = { splat, mesh, copy, light };
    renderer.setRenderTarget(null);
    return true;
  }

  /**
   * The volumes of the last build as the GPU holds them (for tests; slow): `density` [ρ, ρΩ]
   * per voxel, `source` [ρ(1 − Ω)Q, 0] per voxel if emissive, `light` the four columns per
   * voxel of the light grid (x fastest, then y, then z, as the core's twin).
   */
  read(renderer) {
    const layers = (target, dims) => {
      const [nx, ny, nz] = dims;
      const out = new Float32Array(4 * nx * ny * nz);
      const slice = new Float32Array(4 * nx * ny);
      for (let k = 0; k < nz; k++) {
        renderer.setRenderTarget(target, k);
        renderer.readRenderTargetPixels(target, 0, 0, nx, ny, slice);
        out.set(slice, 4 * nx * ny * k);
      }
      return out;
    };
    const grid = this.grid;
    const result = {
      density: layers(this.density, grid.dims),
      source: this.info.emissive ? layers(this.source, grid.dims) : null,
      light: layers(this.columns, halved(grid).dims),
    };
    renderer.setRenderTarget(null);
    return result;
  }

  dispose() {
    for (const t of [this.atlas, ...this.scratch, this.density, this.source, this.columns]) t?.dispose();
  }
}
