// The GPU stepper: the gas's centres advected on the GPU (paper §4, Eq. 14) through the wind the
// core freezes for each step, while the core in the worker keeps the rest of the gas (births,
// σ, mass, removal, the cap: `gas::slots`). Per step only the newborns, the emptied slots and the
// frozen wind cross to the GPU; the views draw the state where it is (a recording too), sorted
// by σ class on the GPU as the worker's frames are (`binning.js`) and packed; the centres come
// back only on demand (`readCentres`: a reference still, a blob export, the exact view, or
// stepping in the worker again).
//
// WebGL2 with float render targets (EXT_color_buffer_float) and three draw buffers is enough:
// every pass is a per-texel map (four with carried turbulence, which every WebGL2 has), and
// none blends. The state must be 32-bit: a centre a metre from the origin moves by about a
// millimetre a step, which is one step of a half float there (2⁻¹⁰ m), so in half floats the
// gas would move in jumps or not at all; a GPU with only half-float targets (many phones) has
// the worker step the gas. At the WebGL2 phones' 4096 texels a side every texture fits any
// scene (the state 1024 slots a row: the most live blobs and four steps' most births fill 1,369
// rows, 2,054 once grown by half; the lattice 4096 points a row: 2²² points in 1,024 rows; the
// solids' grid 4096 texels a row, at most 192 rows). Where these are missing the worker steps the
// gas, and for scenes whose wind table would be wider than a texture row (hundreds of
// primitives with their mirror images).

import * as THREE from 'three';
import { BLOB_FLOATS, BLOBS_PER_ROW, INFO_HEADER, INFO_PER_CLASS, WORDS_PER_BLOB } from '../generated/contract.js';
import { Binning } from './binning.js';
import { binClasses, binLayout } from './class-bins.js';
import { flowUniforms } from '../flow-gpu/sample-glsl.js';
import { repulsorSolids, sameSolids } from '../flow-gpu/boundary.js';
import { BoundsPass, NewbornPass, PackPass, ScreenPass, StepPass, WritePass } from './passes.js';
import { StepperState } from './state.js';
import { HEADER_TEXELS, PRIMITIVE_TEXELS, SOLID_TEXELS } from './wind-glsl.js';

/** Where a wind table holds its constant wind (xyz, m/s): the header's fifth texel (`wind::wind_table`). */
const CONSTANT_WIND = 4 * 4;
/** Widest lattice texture row (texels); a lattice fills rows of this many points. */
const LATTICE_WIDTH = 4096;
/** Most lattice points the GPU takes (64 MiB as RGBA32F); larger fields are stepped in the worker. */
export const MAX_GPU_LATTICE = 1 << 22;

/**
 * Why the GPU cannot step the gas with `renderer`, or null when it can: WebGL2, float render
 * targets, three draw buffers, and textures wide enough for the state and the lattice.
 */
export function gpuStepperUnsupported(renderer) {
  if (!renderer.capabilities.isWebGL2) return 'this browser has no WebGL2';
  const gl = renderer.getContext();
  if (!renderer.extensions.has('EXT_color_buffer_float')) return 'this GPU cannot render to float textures (no EXT_color_buffer_float)';
  if (gl.getParameter(gl.MAX_DRAW_BUFFERS) < 3) return 'this GPU draws to fewer than three targets at once';
  if (gl.getParameter(gl.MAX_TEXTURE_SIZE) < LATTICE_WIDTH) return `this GPU's textures are narrower than ${LATTICE_WIDTH}`;
  return null;
}

/**
 * Why the GPU stepper cannot step `scene`, or null when it can: its wind table (a texture row:
 * the header, each primitive and, at most, a mirror image of it in each solid plane, each solid)
 * must fit in LATTICE_WIDTH texels. Any number of solids fits otherwise: each blob visits only
 * those its cell of the core's grid lists.
 */
export function gpuStepperRefuses(scene) {
  const solids = (scene.render?.objects ?? []).filter((o) => o.solid);
  const planes = solids.filter((o) => o.type === 'plane').length;
  const winds = (scene.wind ?? []).length;
  const texels = HEADER_TEXELS + PRIMITIVE_TEXELS * winds * (1 + planes) + SOLID_TEXELS * solids.length;
  if (texels > LATTICE_WIDTH) {
    return `the scene's wind table (${winds} primitives, their mirror images in ${planes} solid planes, ${solids.length} solids) is wider than the GPU stepper's ${LATTICE_WIDTH} texels`;
  }
  return null;
}

/** Copies every attachment of one state into a larger one (the first rows of it). */
class CopyPass extends ScreenPass {
  constructor(count) {
    const outputs = Array.from({ length: count }, (_, k) => `layout(location = ${k}) out vec4 o${k};`).join('\n');
    const inputs = Array.from({ length: count }, (_, k) => `uniform highp sampler2D i${k};`).join('\n');
    const copies = Array.from({ length: count }, (_, k) => `o${k} = p.y < rows ? texelFetch(i${k}, p, 0) : vec4(0.0);`).join('\n  ');
    const uniforms = { rows: { value: 0 } };
    for (let k = 0; k < count; k++) uniforms[`i${k}`] = { value: null };
    super(`${inputs}\nuniform int rows;\n${outputs}\nvoid main() {\n  ivec2 p = ivec2(gl_FragCoord.xy);\n  ${copies}\n}`, uniforms);
    this.count = count;
  }

  copy(renderer, from, to) {
    const u = this.material.uniforms;
    u.rows.value = from.height;
    for (let k = 0; k < this.count; k++) u[`i${k}`].value = from.textures[k];
    this.draw(renderer, to);
  }
}

export class GpuStepper {
  /** @param {THREE.WebGLRenderer} renderer the views' renderer: the state is in its context */
  constructor(renderer) {
    this.renderer = renderer;
    this.stepPass = new StepPass();
    this.writePass = new WritePass();
    this.newbornPass = new NewbornPass(this.stepPass);
    this.packPass = new PackPass();
    this.boundsPass = new BoundsPass();
    this.binning = new Binning();
    this.copyMoving = new CopyPass(2);
    this.copyCarried = new CopyPass(4);
    this.copyFixed = new CopyPass(3);
    this.state = null;
    this.lattice = null;
    this.windTable = null;
    this.solidGrid = null;
    /** One past the highest slot in use; what the views draw. */
    this.highWater = 0;
    this.count = 0;
    this.sigmaRange = [0, 0];
    this.emissive = false;
    this.spheres = new Float32Array(0);
    this.time = 0;
    /** Changes of the state, and the change last sorted and described (`frame`). */
    this.version = 0;
    this.sorted = null;
  }

  /** The flow lattices' three.js textures (`#external`). */
  #externals = new Map();

  /**
   * Takes the gas over: `records` (BLOB_FLOATS per slot, slot order, as the core's
   * `handCentresToGpu` gives them), room for `capacity` slots, at simulated time `time` (s).
   */
  start({ records, capacity, time = 0, carried = false }) {
    const slots = records.length / BLOB_FLOATS;
    this.state?.dispose();
    this.state = new StepperState(Math.max(capacity, slots, 1), carried);
    // Kept until the first steps say whether the wind carries its small scales: a state that
    // must carry offsets is then written again from them, offsets and all.
    this.startRecords = carried ? null : records;
    const renderer = this.renderer;
    for (const target of [...this.state.moving, this.state.fixed]) {
      renderer.setRenderTarget(target);
      renderer.setClearColor(0x000000, 0);
      renderer.clear(true, false, false);
    }
    const all = Uint32Array.from({ length: slots }, (_, i) => i);
    this.writePass.write(renderer, this.state, this.state.now, records, all, new Uint32Array(0));
    renderer.setRenderTarget(null);
    this.highWater = slots;
    this.time = time;
    [this.count, ...this.sigmaRange] = extentOfRecords(records);
    this.version += 1;
  }

  /**
   * The small-scale field's lattice (`data`: xyz per point, `[t][z][y][x]`, lattice units) of
   * `size` `[nx, ny, nz, nt]`, or none (a scene without one).
   */
  setLattice(data, size, potential = null) {
    this.lattice?.dispose();
    this.potential?.dispose();
    this.lattice = null;
    this.potential = null;
    this.latticeSize = size;
    if (!data) return;
    this.lattice = latticeTexture(data);
    // The field's vector potential (scenes with solid objects), laid out as the velocity.
    if (potential?.length) this.potential = latticeTexture(potential);
  }

  /**
   * Room for at least `slots` slots, with carried offsets when `carried`, keeping the state (a
   * state that gains offsets starts them at zero: the coordinates just reset).
   */
  #ensureCapacity(slots, carried) {
    const old = this.state;
    if (slots <= old.capacity && (old.carried || !carried)) return;
    const grown = new StepperState(Math.max(slots, old.capacity < slots ? Math.ceil(1.5 * old.capacity) : old.capacity), carried || old.carried);
    if (grown.carried) {
      for (const target of grown.moving) {
        this.renderer.setRenderTarget(target);
        this.renderer.setClearColor(0x000000, 0);
        this.renderer.clear(true, false, false);
      }
    }
    (old.carried ? this.copyCarried : this.copyMoving).copy(this.renderer, old.now, grown.now);
    this.copyFixed.copy(this.renderer, old.fixed, grown.fixed);
    old.dispose();
    this.state = grown;
  }

  /** The solids' grid (`gas::solid_grid`, `SolidGrid::write_gpu`) as an RGBA32F texture, LATTICE_WIDTH texels a row. */
  #setSolidGrid(grid) {
    this.solidGrid?.dispose();
    this.solidGrid = rowsTexture(grid.length / 4, (texels) => texels.set(grid));
  }

  /** The wind table texture holding tables `a` (row 0) and `b` (row 1). */
  #setWind(a, b) {
    const width = Math.max(a.length / 4, b.length / 4, HEADER_TEXELS + PRIMITIVE_TEXELS);
    if (!this.windTable || this.windTable.image.width < width) {
      this.windTable?.dispose();
      const w = Math.ceil(width / 64) * 64;
      this.windTable = new THREE.DataTexture(new Float32Array(8 * w), w, 2, THREE.RGBAFormat, THREE.FloatType);
    }
    const data = this.windTable.image.data;
    data.fill(0);
    data.set(a, 0);
    data.set(b, 4 * this.windTable.image.width);
    this.windTable.needsUpdate = true;
  }

  /** A three.js texture of the flow lattice `lattice`'s own WebGL texture (made once each). */
  #external(lattice) {
    let t = this.#externals.get(lattice);
    if (!t) {
      t = new THREE.ExternalTexture(lattice.texture);
      this.#externals.set(lattice, t);
    }
    return t;
  }

  /** The raw WebGL texture of attachment `k` of render target `target`. */
  #raw(target, k) {
    return this.renderer.properties.get(target.textures[k]).__webglTexture;
  }

  /**
   * The flow's part of one step from the state now (`wind::flow::SceneFlow::step` on the GPU):
   * u_p from the step's first wind table `table` (its constant where the primitives are all
   * uniform winds without a decay, else each face's from the table's primitives) and the solid
   * cells with the table's repulsors' spheres (`repulsorSolids`), the gas's heat deposited on
   * the cells (the blobs of the first `slots` slots, none wider than `sigmaMax`, m), the stir
   * `stir` if any, then the flow's step of `dt` (s); the step pass is then given the flow's new
   * u_g.
   */
  #stepFlow(link, table, dt, slots, sigmaMax) {
    const { flow } = link;
    if (table[CONSTANT_WIND + 3] > 0) {
      // Primitives beyond the constant wind: u_p on the faces from this table.
      flow.setWindTable(table);
      link.up = null;
    } else {
      const up = Array.from(table.subarray(CONSTANT_WIND, CONSTANT_WIND + 3));
      if (!link.up || link.up.some((v, a) => v !== up[a])) {
        flow.setUniformWind(up);
        link.up = up;
      }
    }
    if (link.fixed) {
      // A repulsor's sphere is solid cells where it is now (the objects' alone once none is).
      const solids = repulsorSolids(link.fixed, flow, table) ?? link.fixed;
      if (solids !== link.solids && !sameSolids(solids, link.solids)) flow.setSolids(solids);
      link.solids = solids;
    }
    const t0 = performance.now();
    link.timer?.begin();
    this.#depositHeat(link, slots, sigmaMax);
    flow.step(dt, flow.temperature, link.stir ? [flow.splatOf(link.stir)] : []);
    link.timer?.end();
    // The GPU's own time of the last flow step it finished where it can say, else the page's
    // time to issue this one's passes.
    link.ms = link.timer?.ms ?? performance.now() - t0;
    this.renderer.resetState();
    const u = this.stepPass.material.uniforms;
    const [fu, fv, fw] = flow.u.map((p) => this.#external(p.now));
    u.flowU.value = fu;
    u.flowV.value = fv;
    u.flowW.value = fw;
    for (const [name, value] of Object.entries(flowUniforms(flow))) u[name].value = value;
  }

  /**
   * T (K) on the cells of the flow of `link` (as #stepFlow's) from the blobs as they are now:
   * `exportFlow()`'s temperature at the state's time (a step lays T before it moves the blobs
   * and writes the newborns).
   */
  depositHeat(link) {
    this.#depositHeat(link, Math.min(this.state.capacity, this.highWater), this.sigmaRange[1]);
    this.renderer.resetState();
  }

  /**
   * T on the cells of `link`'s flow from the blobs in the current state's first `slots` slots,
   * none wider than `sigmaMax` (m).
   */
  #depositHeat(link, slots, sigmaMax) {
    link.heat.deposit(link.flow, {
      centres: this.#raw(this.state.now, 0),
      masses: this.#raw(this.state.now, 1),
      slotsPerRow: BLOBS_PER_ROW,
      slots,
      sigmaMax,
      cooling: link.cooling,
    });
  }

  /**
   * Takes the steps the core took (`steps`: its `stepForGpu` result) with time step `dt` (s),
   * diffusion κ (m²/s), dissipation α (1/s) and the RK2 midpoint rule or Euler; with `flow`
   * (`{flow: GpuFlow, heat: HeatDeposit, cooling (1/s), stir}`, the scene's flow on the GPU)
   * each step first steps the flow from the blobs' heat, and the blobs move through u_g too.
   */
  apply(steps, { dt, diffusion, alpha, rk2, flow = null }) {
    const renderer = this.renderer;
    const n = steps.ranges.length / 4;
    // The tables say whether the wind goes round solids and carries its small scales
    // (`gas::wind_table`: header floats 20 and 23).
    const solids = n > 0 && steps.wind[20] > 0;
    const carried = n > 0 && steps.wind[23] > 0;
    if (carried && !this.state.carried && this.startRecords) {
      this.start({ records: this.startRecords, capacity: this.state.capacity, time: this.time, carried: true });
    }
    if (n > 0) this.startRecords = null;
    // The solids' grid comes with the first steps of a scene (and after an edit that builds it anew).
    if (steps.solidGrid?.length) this.#setSolidGrid(steps.solidGrid);
    this.#ensureCapacity(steps.highWater, carried);
    this.stepPass.configure({ solids, carried, flow: Boolean(flow) });
    // Every σ during these steps is below this (σ² grows by κ·dt a step; the end's widest may
    // have died within them).
    const sigmaMax = Math.sqrt(Math.max(this.sigmaRange[1], steps.sigmaRange[1]) ** 2 + n * diffusion * dt);
    // Every slot in use during them (empty ones cost one vertex an instance).
    const slots = Math.min(this.state.capacity, Math.max(this.highWater, steps.highWater));
    const u = this.stepPass.material.uniforms;
    u.dt.value = dt;
    u.diffusion.value = diffusion;
    u.alpha.value = alpha;
    u.rk2.value = rk2;
    u.lattice.value = this.lattice;
    u.potentialLattice.value = this.potential ?? this.lattice;
    u.solidGrid.value = this.solidGrid;
    u.solidGridWidth.value = LATTICE_WIDTH;
    const [nx, ny, nz, nt] = this.latticeSize ?? [1, 1, 1, 1];
    u.latticeSize.value.set(nx, ny, nz, nt);
    u.latticeWidth.value = LATTICE_WIDTH;
    const table = (k) => steps.wind.subarray(steps.windOffsets[k], steps.windOffsets[k + 1] ?? steps.wind.length);
    for (let k = 0; k < n; k++) {
      if (flow) this.#stepFlow(flow, table(2 * k), dt, slots, sigmaMax);
      this.#setWind(table(2 * k), table(2 * k + 1));
      u.windTable.value = this.windTable;
      u.centres.value = this.state.now.textures[0];
      u.masses.value = this.state.now.textures[1];
      u.ownVelocities.value = this.state.fixed.textures[0];
      u.offsetsA.value = this.state.carried ? this.state.now.textures[2] : null;
      u.offsetsB.value = this.state.carried ? this.state.now.textures[3] : null;
      this.stepPass.draw(renderer, this.state.next);
      const [firstBirth, births, firstFreed, freed] = steps.ranges.subarray(4 * k, 4 * k + 4);
      this.writePass.write(
        renderer,
        this.state,
        this.state.next,
        steps.births.subarray(BLOB_FLOATS * firstBirth, BLOB_FLOATS * (firstBirth + births)),
        steps.birthSlots.subarray(firstBirth, firstBirth + births),
        steps.freed.subarray(firstFreed, firstFreed + freed),
        flow ? this.newbornPass : null,
      );
      this.state.swap();
    }
    renderer.setRenderTarget(null);
    this.highWater = steps.highWater;
    this.count = steps.count;
    this.sigmaRange = Array.from(steps.sigmaRange);
    this.emissive = steps.emissive;
    this.spheres = steps.spheres;
    this.time = steps.time;
    this.version += 1;
  }

  /**
   * The views' frame of the current state, on the GPU: the blobs sorted by σ class and packed
   * (`binning.js`; `frame::packed`), the frame's description (`frame::packed` info: the classes
   * from the bins' counts, the bounds by reduction) and the moving spheres. The state is sorted
   * once a change (a start, the steps of `apply`), and only then do the bins' counts and the
   * bounds come back: a few floats, read once the GPU has done the steps, which drawing the frame
   * waits for anyway.
   */
  frame(mediumAlbedo) {
    const renderer = this.renderer;
    if (this.sorted?.version !== this.version) this.sorted = this.#sort();
    const { order, count, info } = this.sorted;
    const texture = this.packPass.pack(renderer, this.state, order, count, mediumAlbedo);
    renderer.setRenderTarget(null);
    return { texture, count, live: this.count, info, spheres: this.spheres, time: this.time };
  }

  /**
   * Sorts the state into its bins and describes the sorted frame: {version, order, count,
   * info}. `clock` may time the passes (`Binning.sort`).
   */
  #sort(clock = () => {}) {
    const renderer = this.renderer;
    const [sigmaMin, sigmaMax] = this.sigmaRange;
    const layout = binLayout(sigmaMin, sigmaMax);
    const { order, counts } = this.binning.sort(renderer, this.state, this.highWater, layout, clock);
    this.boundsPass.update(renderer, this.state);
    clock('bounds');
    renderer.setRenderTarget(null);
    // σ on the GPU may round a little above the core's: the widest class reaches past it.
    const classes = binClasses(layout, counts, 1.0001 * sigmaMax);
    const count = counts.reduce((a, b) => a + b, 0);
    const info = new Float32Array(INFO_HEADER + INFO_PER_CLASS * classes.length);
    info[0] = count;
    const b = this.boundsPass.bounds;
    if (b) info.set(b, 1);
    info[7] = this.emissive ? 1 : 0;
    info[8] = sigmaMin;
    info[9] = classes.length;
    classes.forEach((c, i) => info.set(c, INFO_HEADER + INFO_PER_CLASS * i));
    return { version: this.version, order, count, info };
  }

  /**
   * The median time (ms) of one step pass over every slot in use, run `repeats` times on the
   * current state with the last step's wind and finished on the GPU; the state is left as it
   * was (the results go to the spare buffer, never swapped in). For benchmarks.
   */
  timeStep(repeats = 5) {
    const renderer = this.renderer;
    // The last row in use, read back: the pass has finished every slot before it.
    const row = Math.max(Math.ceil(this.highWater / BLOBS_PER_ROW) - 1, 0);
    const texels = new Float32Array(4 * BLOBS_PER_ROW);
    const times = [];
    const u = this.stepPass.material.uniforms;
    u.centres.value = this.state.now.textures[0];
    u.masses.value = this.state.now.textures[1];
    u.ownVelocities.value = this.state.fixed.textures[0];
    u.offsetsA.value = this.state.carried ? this.state.now.textures[2] : null;
    u.offsetsB.value = this.state.carried ? this.state.now.textures[3] : null;
    for (let i = 0; i <= repeats; i++) {
      const t0 = performance.now();
      this.stepPass.draw(renderer, this.state.next);
      renderer.readRenderTargetPixels(this.state.next, 0, row, BLOBS_PER_ROW, 1, texels);
      if (i > 0) times.push(performance.now() - t0);
    }
    renderer.setRenderTarget(null);
    return times.sort((a, b) => a - b)[Math.floor(times.length / 2)];
  }

  /**
   * The median time (ms) of sorting the current state into its bins and packing it for the
   * views (`frame` after a step), run `repeats` times, each pass finished on the GPU before the
   * next: {ms, passes: the median of each pass (the bins' keys; their counts, running sums and
   * totals read back; the gathering of the order; the bounds; the packing, with the medium's
   * albedo `mediumAlbedo`)}. For benchmarks.
   */
  timeSort(repeats, mediumAlbedo) {
    const runs = [];
    for (let i = 0; i <= repeats; i++) {
      const times = {};
      const t0 = performance.now();
      let last = t0;
      const clock = (name) => {
        this.#wait();
        const now = performance.now();
        times[name] = now - last;
        last = now;
      };
      this.sorted = this.#sort(clock);
      this.packPass.pack(this.renderer, this.state, this.sorted.order, this.sorted.count, mediumAlbedo);
      clock('pack');
      times.ms = last - t0;
      if (i > 0) runs.push(times);
    }
    this.renderer.setRenderTarget(null);
    const median = (name) => runs.map((r) => r[name]).sort((a, b) => a - b)[Math.floor(runs.length / 2)];
    const passes = Object.fromEntries(Object.keys(runs[0]).filter((k) => k !== 'ms').map((k) => [k, median(k)]));
    return { ms: median('ms'), passes };
  }

  /** Waits until the GPU has done everything asked of it (reads one texel of the state back). */
  #wait() {
    this.renderer.readRenderTargetPixels(this.state.now, 0, 0, 1, 1, new Float32Array(4));
  }

  /** Attachment `k` of the moving state, every slot in use (RGBA per slot), read back (a stall). */
  #read(k) {
    const rows = Math.ceil(this.highWater / BLOBS_PER_ROW);
    const texels = new Float32Array(4 * BLOBS_PER_ROW * Math.max(rows, 1));
    if (rows > 0) this.renderer.readRenderTargetPixels(this.state.now, 0, 0, BLOBS_PER_ROW, rows, texels, undefined, k);
    return texels.subarray(0, 4 * this.highWater);
  }

  /** The centres (xyz per slot, m) as they are now, read back from the GPU (a stall). */
  readCentres() {
    const texels = this.#read(0);
    const out = new Float32Array(3 * this.highWater);
    for (let i = 0; i < this.highWater; i++) out.set(texels.subarray(4 * i, 4 * i + 3), 3 * i);
    return out;
  }

  /**
   * σ (m), mass and centre (xyz, m) of every slot holding a blob, in slot order, and the slots'
   * numbers, read back (for tests).
   */
  readSigmaAndMass() {
    const a = this.#read(0);
    const b = this.#read(1);
    const sigma = [];
    const mass = [];
    const centre = [];
    const slot = [];
    for (let i = 0; i < this.highWater; i++) {
      if (!(b[4 * i] > 0)) continue;
      sigma.push(Math.sqrt(a[4 * i + 3]));
      mass.push(b[4 * i]);
      centre.push(...a.subarray(4 * i, 4 * i + 3));
      slot.push(i);
    }
    return { sigma: Float32Array.from(sigma), mass: Float32Array.from(mass), centre: Float32Array.from(centre), slot };
  }

  /**
   * The views' frame of the current state as they read it: its packed words (WORDS_PER_BLOB a
   * blob, sorted) and its description, read back (for tests).
   */
  readFrame(mediumAlbedo) {
    const { count, info } = this.frame(mediumAlbedo);
    const rows = Math.ceil(count / BLOBS_PER_ROW);
    const words = new Uint32Array(WORDS_PER_BLOB * BLOBS_PER_ROW * rows);
    if (rows > 0) {
      const gl = this.renderer.getContext();
      this.renderer.setRenderTarget(this.packPass.target);
      gl.readPixels(0, 0, (WORDS_PER_BLOB / 4) * BLOBS_PER_ROW, rows, gl.RGBA_INTEGER, gl.UNSIGNED_INT, words);
      this.renderer.setRenderTarget(null);
    }
    return { words: words.subarray(0, WORDS_PER_BLOB * count), info };
  }

  /** The carried offsets of every slot in use (phase a xyz, phase b xyz per slot), read back (for tests). */
  readCarried() {
    if (!this.state.carried) return null;
    const a = this.#read(2);
    const b = this.#read(3);
    const out = new Float32Array(6 * this.highWater);
    for (let i = 0; i < this.highWater; i++) {
      out.set(a.subarray(4 * i, 4 * i + 3), 6 * i);
      out.set(b.subarray(4 * i, 4 * i + 3), 6 * i + 3);
    }
    return out;
  }

  dispose() {
    this.state?.dispose();
    this.lattice?.dispose();
    this.potential?.dispose();
    this.windTable?.dispose();
    this.solidGrid?.dispose();
    for (const t of this.#externals.values()) t.dispose();
    for (const p of [this.stepPass, this.newbornPass, this.writePass, this.packPass, this.boundsPass, this.binning, this.copyMoving, this.copyCarried, this.copyFixed]) p.dispose();
  }
}

/** An RGBA32F texture of `count` texels, LATTICE_WIDTH a row, written by `fill` (given the texels' floats, zeros past the last). */
function rowsTexture(count, fill) {
  const rows = Math.ceil(count / LATTICE_WIDTH);
  const texels = new Float32Array(4 * LATTICE_WIDTH * rows);
  fill(texels);
  const texture = new THREE.DataTexture(texels, LATTICE_WIDTH, rows, THREE.RGBAFormat, THREE.FloatType);
  texture.needsUpdate = true;
  return texture;
}

/** A lattice (xyz per point) as an RGBA32F texture, LATTICE_WIDTH points a row. */
function latticeTexture(data) {
  const points = data.length / 3;
  return rowsTexture(points, (texels) => {
    for (let i = 0; i < points; i++) texels.set(data.subarray(3 * i, 3 * i + 3), 4 * i);
  });
}

/** The blobs of records (those with mass), and their narrowest and widest σ (m; 0 without blobs). */
function extentOfRecords(records) {
  let count = 0;
  let lo = Infinity;
  let hi = 0;
  for (let i = 0; i < records.length; i += BLOB_FLOATS) {
    if (!(records[i + 4] > 0)) continue;
    const sigma = Math.fround(Math.sqrt(Math.max(records[i + 3], 0)));
    count += 1;
    lo = Math.min(lo, sigma);
    hi = Math.max(hi, sigma);
  }
  return count > 0 ? [count, lo, hi] : [0, 0, 0];
}
