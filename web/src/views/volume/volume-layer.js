// The real-time volume view (docs/ARCHITECTURE.md; the `raymarch` view of docs/FORMATS.md): the frame's blobs splatted on the GPU
// into a density volume, a light volume of shadow columns computed from it, and a ray march of
// the volume with jittered steps that leap over empty bricks, composited over the opaque pass by
// depth. Its cost per frame grows with pixels and with the voxels the gas fills, not with the
// blob count (only the splat, a few fragments a blob, does). The splat and the light pass draw
// into 2-D atlases of slices, copied several slices a draw into 3-D textures for hardware
// trilinear sampling. A view larger than the quality's march budget is marched at a lower
// resolution and upsampled by depth. The volumes are rebuilt only when the frame, the quality
// or the lights change: orbiting a paused scene re-runs the march alone.
// Precision (`../precision.js`): the atlases and volumes hold 32-bit floats where the GPU blends
// and filters them, else 16-bit ones. Either way they hold optical depths, not densities: a
// density volume voxel holds κ̄ρh (the optical depth across the voxel, κ̄ the largest of the
// medium's extinctions), a light column κ̄∫ρds, numbers of order 10⁻⁴ to 10² for any visible gas,
// well inside a half float's range (6·10⁻⁵ to 65,504 at full precision), whatever the scene's
// units of mass and length.
// A lost WebGL context: while it is lost nothing is built or read, and the layer lets go of its
// raw WebGL copier and of three.js's objects for its targets and passes; once it is restored
// the next `prepare` makes them again and rebuilds the volumes from the frame it holds.

import * as THREE from 'three';
import { DIRECT_LIMIT } from '../../generated/contract.js';
import { waitForGpu } from '../gpu-sync.js';
import { MarchQuad } from '../march-quad.js';
import { sharingUniforms } from '../screen-pass.js';
import { releaseGeometries } from '../context-loss.js';
import { LIGHTS_GLSL } from '../shaders/lights.js';
import { MARCH_PREAMBLE } from '../shaders/march-preamble.js';
import { OCCLUDERS_GLSL } from '../shaders/occluders.js';
import { VOLUME_SHADOW_GLSL } from '../shaders/volume-shadow.js';
import { gpuFormats, passPrecision, texelType } from '../precision.js';
import { atlasLayout, cutClasses, fitGrid, halved, minVoxelFor } from './grid.js';
import { gridUniform } from './glsl.js';
import { LightPass } from './light-pass.js';
import { MARCH_GLSL } from './march-glsl.js';
import { marchSize, MarchUpsample, SPLIT_OUTPUTS_GLSL } from './march-upsample.js';
import { MESH_ATTACHMENTS, MeshPass } from './mesh-pass.js';
import { brickDims, OccupancyPass } from './occupancy-pass.js';
import { SliceCopy } from './slice-copy.js';
import { SPLAT_LAYERS, SplatPass } from './splat-pass.js';

/**
 * Per quality: the voxel budget of the density grid, the smallest voxel in units of the
 * narrowest blob's σ (finer voxels would resolve nothing more, as no blob is narrower), the
 * march's step and the light columns' step (both in voxels), and the most pixels the march
 * draws (a larger view is marched at a lower resolution: `march-upsample.js`).
 */
export const VOLUME_QUALITY = {
  draft: { budget: 2 ** 18, voxelPerSigma: 1, step: 1, column: 1.5, marchPixels: 2 ** 17 },
  standard: { budget: 2 ** 20, voxelPerSigma: 1, step: 0.75, column: 1, marchPixels: 2 ** 18 },
  high: { budget: 2 ** 22, voxelPerSigma: 0.35, step: 0.5, column: 1, marchPixels: Infinity },
};

const fragmentShader = /* glsl */ `
${MARCH_PREAMBLE}
${LIGHTS_GLSL}
${VOLUME_SHADOW_GLSL}
${OCCLUDERS_GLSL}
${MARCH_GLSL}
uniform bool hasGas;
#ifdef SPLIT
${SPLIT_OUTPUTS_GLSL}
#endif

void main() {
  vec3 rd, behind;
  float sMax;
  viewRay(vUv, rd, sMax, behind);
  vec3 rad = vec3(0.0);
  vec3 T = vec3(1.0);
  if (hasGas) marchVolume(camPos, rd, sMax, rad, T);
#ifdef SPLIT
  writeSplit(rad, T);
#else
  outColor = vec4(encode(rad + T * behind), 1.0);
#endif
}
`;

const EMPTY_GRID = { lo: [0, 0, 0], h: 1, dims: [2, 2, 2], size: [2, 2, 2] };

/** Targets grow in steps of this many texels per side, so they are remade only now and then. */
const ATLAS_STEP = 256;
const VOLUME_STEP = 16;

const roundUp = (n, step, max) => Math.min(max, Math.ceil(n / step) * step);

/**
 * True if `target` (of `sizes`) holds `needed` and is at most `slack` times larger than it
 * rounded up: 4, so that a target is kept while the gas grows and shrinks, or 1 under a memory
 * budget, which counts the targets at their rounded sizes.
 */
function fits(sizes, needed, step, max, slack) {
  const area = (v) => v.reduce((a, b) => a * b, 1);
  return sizes.every((n, a) => n >= needed[a])
    && area(sizes) <= slack * area(needed.map((n) => roundUp(n, step, max)));
}

/** The volumes' options: filtered (trilinear samples between voxel centres). */
const TARGET_OPTIONS = {
  format: THREE.RGBAFormat,
  depthBuffer: false,
  stencilBuffer: false,
  minFilter: THREE.LinearFilter,
  magFilter: THREE.LinearFilter,
  generateMipmaps: false,
};

/**
 * An atlas (`count` float targets) holding `layout`, reusing `target` if it can. Atlases are
 * read texel by texel (texelFetch), never filtered, so they need no filterable format.
 */
function atlasTarget(target, layout, type, count, maxSize, slack) {
  const needed = [layout.width, layout.height];
  if (target && target.textures.length === count && target.texture.type === type
      && fits([target.width, target.height], needed, ATLAS_STEP, maxSize, slack)) return target;
  target?.dispose();
  const [w, h] = needed.map((n) => roundUp(n, ATLAS_STEP, maxSize));
  return new THREE.WebGLRenderTarget(w, h, {
    ...TARGET_OPTIONS, type, count, minFilter: THREE.NearestFilter, magFilter: THREE.NearestFilter,
  });
}

/** A 3-D float target holding `dims` voxels, reusing `target` if it can. */
function volumeTarget(target, dims, type, max, slack) {
  if (target && target.texture.type === type && fits([target.width, target.height, target.depth], dims, VOLUME_STEP, max, slack)) return target;
  target?.dispose();
  const [w, h, d] = dims.map((n) => roundUp(n, VOLUME_STEP, max));
  const t = new THREE.WebGL3DRenderTarget(w, h, d, { ...TARGET_OPTIONS, type });
  t.texture.wrapR = THREE.ClampToEdgeWrapping;
  return t;
}

const sizeOf = (t) => [t.width, t.height, t.depth];

/**
 * Bytes a voxel of the density grid takes in the targets, for texels of `texelBytes` (16 for
 * 32-bit floats, 8 for 16-bit): the splat's atlas, the mesh's four attachments and its
 * scratch, the density volume (each but the mesh's twice for emissive gas: the source), and
 * an eighth of a voxel each for the light atlas and the light volume.
 */
function volumeBytesPerVoxel(texelBytes, emissive) {
  return texelBytes * (4 + 3 * (emissive ? 2 : 1) + 2 / 8);
}

export class VolumeLayer extends MarchQuad {
  /** Set between the context's loss and its restoration. */
  #lost = false;

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
      // The units of the stored volumes: a density voxel holds ρ · densityScale, a light
      // column ∫ρ ds · columnScale (κ̄h and κ̄: optical depths).
      densityScale: gas.densityScale ?? { value: 1 },
      columnScale: gas.columnScale ?? { value: 1 },
    });
    const own = {
      blobTex: { value: null },
      densityVolume: { value: null },
      sourceVolume: { value: null },
      emissive: { value: false },
      stepScale: { value: 0.75 },
      hasGas: { value: false },
      occupancy: { value: null },
      bricks: { value: [1, 1, 1] },
      brickCols: { value: 1 },
    };
    super(fragmentShader, { ...gas, ...own });
    /** The same march writing radiance and transmittance apart, for a lower resolution. */
    this.splitMaterial = sharingUniforms(this.material);
    this.splitMaterial.defines = { SPLIT: 1 };
    this.fullMaterial = this.material;
    this.upsample = new MarchUpsample(this.material.uniforms);
    this.marchPixels = Infinity;
    this.gas = gas;
    this.blobs = blobs;
    this.own = own;
    this.atlasUniforms = { atlasCols: { value: 1 }, atlasSize: { value: [1, 1] } };
    this.splat = new SplatPass({ blobTex: own.blobTex, grid: gas.grid, densityScale: gas.densityScale, ...this.atlasUniforms });
    this.mesh = new MeshPass({ blobTex: own.blobTex, grid: gas.grid, densityScale: gas.densityScale, ...this.atlasUniforms });
    this.light = new LightPass({ ...gas, densityVolume: own.densityVolume });
    this.occupancyPass = new OccupancyPass({ grid: gas.grid, ...this.atlasUniforms });
    /** Made on the first build (it needs the context). */
    this.copier = null;
    /**
     * The splat's atlas, the mesh's atlas and its scratch atlas, the light pass's atlas, the bricks'
     * atlas; the 3-D targets: density, emitted source, light columns.
     */
    this.atlas = null;
    this.scratch = [null, null];
    this.lightAtlas = null;
    this.bricks = null;
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
    /** The precision of the last build's passes (`passPrecision`), for the stats. */
    this.precision = null;
    /**
     * What the last build gave up to fit, each `{voxels, of}` (the grid's voxels, and those it
     * would have had) or null: `memory` (a voxel budget held within `memoryBytes`) and
     * `textureSize` (fewer voxels until the atlases fit the largest texture).
     */
    this.shrunk = { memory: null, textureSize: null };
    /** Most bytes the targets may take (the player's memory budget: `player/memory.js`). */
    this.memoryBytes = Infinity;
    /** The GPU's float formats (`gpuFormats`), set by the view (else asked for at the first build). */
    this.formats = null;
  }

  /** True while the renderer's context is lost: nothing can be built or read. */
  #isLost(renderer) {
    return this.#lost || renderer.getContext().isContextLost();
  }

  /**
   * The context is lost: build and read nothing until it is restored. The slice copier's raw
   * WebGL objects die with the context (a new copier is made on the next build); the targets
   * and the passes' geometries are disposed now, while that deletes nothing (`context-loss.js`).
   */
  contextLost() {
    this.#lost = true;
    this.copier?.dispose();
    this.copier = null;
    for (const t of [this.atlas, ...this.scratch, this.lightAtlas, this.bricks, this.density, this.source, this.columns]) t?.dispose();
    this.upsample.target?.dispose();
    releaseGeometries(this.scene, this.splat.scene, this.splat.layers.scene, this.mesh.depositScene, this.mesh.blur.scene, this.light.scene, this.occupancyPass.scene, this.upsample.scene);
  }

  /**
   * The context is back (three.js has made its own state anew): the volumes are rebuilt, their
   * targets set up again and a new slice copier made, on the next `prepare`.
   */
  contextRestored() {
    this.#lost = false;
    this.invalidate();
  }

  /** A new frame: `info` is its description (`frameDescription` in `scene-view.js`: {count, lo, hi, emissive, σ classes}). */
  setFrame(info) {
    this.info = info;
    this.frameSerial += 1;
  }

  /** Marks the volumes stale (lights or shadows changed). */
  invalidate() {
    this.builtKey = '';
  }

  /**
   * The targets for `grid` (`layouts` its atlases) within the largest textures of `formats`
   * (`gpuFormats`), in `precision` (`passPrecision`): the density atlases and volumes, added by
   * blending and filtered, and the light columns, only filtered.
   */
  #ensureTargets(renderer, formats, precision, grid, layouts, emissive) {
    this.precision = precision;
    const type = texelType(this.precision.density);
    const lightType = texelType(this.precision.light);
    const { maxTextureSize: maxSize, max3dTextureSize: max3d } = formats;
    const count = emissive ? 2 : 1;
    const slack = Number.isFinite(this.memoryBytes) ? 1 : 4;
    const atlas = (t, layout, kind, n) => atlasTarget(t, layout, kind, n, maxSize, slack);
    this.atlas = atlas(this.atlas, layouts.density, type, count);
    // The mesh's atlas (the splat's layers before it) holds two classes in progress, its scratch one.
    this.scratch = this.scratch.map((t, i) => atlas(t, layouts.density, type, i === 0 ? Math.max(MESH_ATTACHMENTS, SPLAT_LAYERS) : count));
    this.lightAtlas = atlas(this.lightAtlas, layouts.light, lightType, 1);
    this.bricks = atlas(this.bricks, layouts.bricks, type, 1);
    this.density = volumeTarget(this.density, grid.dims, type, max3d, slack);
    if (emissive) this.source = volumeTarget(this.source, grid.dims, type, max3d, slack);
    this.columns = volumeTarget(this.columns, halved(grid).dims, lightType, max3d, slack);
    // Copies land in the 3-D textures before anything is drawn into them: allocate them now.
    for (const t of [this.density, this.source, this.columns]) if (t) renderer.initRenderTarget(t);
    this.copier ??= new SliceCopy(renderer);
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

  /**
   * Builds the density and light volumes for the current frame at `quality` unless they are
   * already built. Returns false when there is no gas. `scale` (0–1], the view's resolution
   * scale, scales the voxels' count by scale³ (their side by 1/scale), as it scales the pixels'
   * side: the voxels keep their size in pixels and the whole view's cost follows the scale.
   * Returns false, building nothing, while the context is lost.
   */
  prepare(renderer, quality, scale = 1) {
    if (this.#isLost(renderer)) return false;
    const info = this.info;
    const q = VOLUME_QUALITY[quality] ?? VOLUME_QUALITY.standard;
    const extinction = this.gas.extinction.value;
    const key = `${this.frameSerial}|${quality}|${scale}|${this.gas.hasShadows.value}|${extinction.toArray()}|${this.memoryBytes}`;
    if (key === this.builtKey) return this.own.hasGas.value;
    this.builtKey = key;
    const hasGas = Boolean(info && info.count > 0);
    this.own.hasGas.value = hasGas;
    if (!hasGas) {
      this.grid = null;
      // No gas, no gas shadows on the objects (not an earlier frame's light volume).
      this.gas.lightVolume.value = null;
      return false;
    }
    const formats = this.formats ?? gpuFormats(renderer);
    const maxSize = formats.maxTextureSize;
    const sigmaMax = Math.max(...info.classes.map((c) => c.sigmaMax));
    const minH = Math.max(minVoxelFor(sigmaMax), q.voxelPerSigma * info.sigmaMin);
    const precision = passPrecision(formats);
    const wanted = q.budget * scale ** 3;
    const most = Math.floor(this.memoryBytes / volumeBytesPerVoxel(precision.density === 'float32' ? 16 : 8, info.emissive));
    let budget = Math.min(wanted, most);
    // The voxels the quality would give, those the memory budget lets it have, those it gets.
    const voxels = (g) => g.dims[0] * g.dims[1] * g.dims[2];
    const full = voxels(fitGrid(info.lo, info.hi, { budget: wanted, minH }));
    const allowed = budget < wanted ? voxels(fitGrid(info.lo, info.hi, { budget, minH })) : full;
    let grid;
    let layouts;
    for (;;) {
      grid = fitGrid(info.lo, info.hi, { budget, minH });
      layouts = {
        density: atlasLayout(grid.dims, maxSize),
        light: atlasLayout(halved(grid).dims, maxSize),
        bricks: atlasLayout(brickDims(grid.dims), maxSize),
      };
      if (layouts.density && layouts.light && layouts.bricks) break;
      // Slices that cannot be tiled within the largest texture: fewer, larger voxels.
      budget /= 2;
    }
    this.shrunk = {
      memory: allowed < full ? { voxels: allowed, of: full } : null,
      textureSize: voxels(grid) < allowed ? { voxels: voxels(grid), of: allowed } : null,
    };
    const layout = layouts.density;
    const lightGrid = halved(grid);
    this.grid = grid;
    this.#ensureTargets(renderer, formats, precision, grid, layouts, info.emissive);
    // Stored optical depths (see the head of this file): κ̄h per unit density, κ̄ per unit column.
    const unit = Math.max(extinction.x, extinction.y, extinction.z);
    const perDensity = Number.isFinite(unit) && unit > 0 ? unit : 1;
    this.gas.densityScale.value = perDensity * grid.h;
    this.gas.columnScale.value = perDensity;
    this.gas.grid.value = gridUniform(grid, sizeOf(this.density));
    this.gas.lightGrid.value = gridUniform(lightGrid, sizeOf(this.columns));
    this.atlasUniforms.atlasCols.value = layout.cols;
    // Draw over the layouts only: a target kept from a larger grid is bigger than its layout.
    const draw = (target, l) => target.viewport.set(0, 0, l.width, l.height);
    for (const t of [this.atlas, ...this.scratch]) draw(t, layout);
    draw(this.lightAtlas, layouts.light);
    draw(this.bricks, layouts.bricks);
    this.atlasUniforms.atlasSize.value = [layout.width, layout.height];
    this.own.blobTex.value = this.blobs.texture;
    this.own.emissive.value = info.emissive;
    this.own.stepScale.value = q.step;
    this.marchPixels = q.marchPixels;
    const clock = this.#clock(renderer);
    // Each pass draws the part of each σ class that it may need: blobs narrower than
    // DIRECT_LIMIT voxels are splatted, the others go through the mesh.
    const cut = cutClasses(info.classes, this.blobs.words, DIRECT_LIMIT * grid.h);
    this.splat.render(renderer, this.atlas, cut.narrow, grid.h, { emissive: info.emissive, layers: this.scratch[0] });
    const splat = clock();
    const { deposit, blur } = this.mesh.render(renderer, { ...info, classes: cut.wide }, grid.h, this.atlas, ...this.scratch, clock);
    this.copier.copy(this.atlas.textures[0], this.density.texture, grid.dims, layout.cols);
    if (info.emissive) this.copier.copy(this.atlas.textures[1], this.source.texture, grid.dims, layout.cols);
    const copy = clock();
    const bricks = brickDims(grid.dims);
    this.occupancyPass.fill(renderer, this.bricks, this.atlas.textures[0], bricks, layouts.bricks.cols);
    this.own.occupancy.value = this.bricks.texture;
    this.own.bricks.value = bricks;
    this.own.brickCols.value = layouts.bricks.cols;
    const occupancy = clock();
    this.own.densityVolume.value = this.density.texture;
    this.own.sourceVolume.value = (info.emissive ? this.source : this.density).texture;
    if (this.gas.hasShadows.value && this.gas.lightCount.value > 0) {
      this.light.fill(renderer, this.lightAtlas, layouts.light.cols, q.column);
      this.copier.copy(this.lightAtlas.texture, this.columns.texture, lightGrid.dims, layouts.light.cols);
    }
    this.gas.lightVolume.value = this.columns.texture;
    const light = clock();
    if (this.profile) this.timings = { splat, deposit, blur, copy, occupancy, light };
    renderer.setRenderTarget(null);
    return true;
  }

  /**
   * The volumes of the last build as the GPU holds them, in densities (for tests; slow): `density` [ρ, ρΩ]
   * per voxel, `source` [ρ(1 − Ω)Q, 0] per voxel if emissive, `light` the four columns per
   * voxel of the light grid (x fastest, then y, then z, as the core's twin). Null while the
   * context is lost or before a build with gas.
   */
  read(renderer) {
    if (this.#isLost(renderer) || !this.grid || !this.density) return null;
    // Each slice in, and back from the stored optical depths (`unit` of each) to densities and columns.
    const layers = (target, dims, unit) => {
      const [nx, ny, nz] = dims;
      const out = new Float32Array(4 * nx * ny * nz);
      const half = target.texture.type === THREE.HalfFloatType;
      const slice = half ? new Uint16Array(4 * nx * ny) : new Float32Array(4 * nx * ny);
      for (let k = 0; k < nz; k++) {
        renderer.setRenderTarget(target, k);
        renderer.readRenderTargetPixels(target, 0, 0, nx, ny, slice);
        slice.forEach((v, i) => { out[4 * nx * ny * k + i] = (half ? THREE.DataUtils.fromHalfFloat(v) : v) / unit; });
      }
      return out;
    };
    const grid = this.grid;
    const { densityScale, columnScale } = this.gas;
    const result = {
      density: layers(this.density, grid.dims, densityScale.value),
      source: this.info.emissive ? layers(this.source, grid.dims, densityScale.value) : null,
      light: layers(this.columns, halved(grid).dims, columnScale.value),
    };
    renderer.setRenderTarget(null);
    return result;
  }

  /**
   * Draws the march into the renderer's current target: straight, or where the view has more
   * pixels than the quality's budget, at a lower resolution upsampled over the opaque pass.
   */
  render(renderer) {
    const resolution = this.material.uniforms.resolution.value;
    const [width, height] = [resolution.x, resolution.y];
    const [w, h] = marchSize(width, height, this.marchPixels);
    if (w === width && h === height) {
      this.quad.material = this.fullMaterial;
      super.render(renderer);
      return;
    }
    const output = renderer.getRenderTarget();
    this.quad.material = this.splitMaterial;
    resolution.set(w, h);
    renderer.setRenderTarget(this.upsample.targetFor(w, h));
    super.render(renderer);
    resolution.set(width, height);
    renderer.setRenderTarget(output);
    this.upsample.composite(renderer);
  }

  dispose() {
    for (const t of [this.atlas, ...this.scratch, this.lightAtlas, this.bricks, this.density, this.source, this.columns]) t?.dispose();
    this.copier?.dispose();
    this.upsample.dispose();
  }
}
