// A scene's flow on the GPU beside the GPU stepper's blobs (where the browser can, the grid lives
// and is stepped on the GPU beside the blobs, read back only on demand): set up from the scene the
// worker runs and its u_g when the gas crosses (`flow-gpu/scene.js`), stepped by the GPU stepper
// step by step from the blobs' heat (`flow-gpu/heat.js`), kept through an edit as the core keeps
// its own (the same box, cells, faces and render objects: new constants; else at rest), and read
// back for `exportFlow()` or when the gas goes back to the worker. Fetched with the first scene
// whose flow the GPU steps (`stepper-handoff.js`); whether it can is `flow-placement.js`'s.

import { HeatDeposit } from '../flow-gpu/heat.js';
import { gpuFlowOfScene } from '../flow-gpu/scene.js';
import { GpuTimer } from '../flow-gpu/timer.js';

const f32 = Math.fround;

/**
 * What of a run scene's flow an edit may keep u_g through: the box, cells, faces and the solid
 * objects' shapes (an object's colour, its model or a non-solid object may change), as the
 * core's edit keeps its own.
 */
function gridOf(run) {
  const f = run.flow;
  const shape = (o) => Object.fromEntries(Object.entries(o).filter(([key]) => key !== 'color' && key !== 'model'));
  const solids = (run.objects ?? []).filter((o) => o.solid).map(shape);
  return JSON.stringify([f.box, f.cells, f.faces, solids]);
}

export class FlowHandoff {
  #gl;
  /** The flow on the GPU (`GpuFlow`), or null. */
  #flow = null;
  #heat = null;
  /** What an edit must keep for u_g to stay (`gridOf`). */
  #grid = null;
  /** What the GPU stepper's steps read (`GpuStepper.apply`'s `flow`). */
  #link = null;
  /** The flow's box [x0, y0, z0, x1, y1, z1] (m). */
  #box = null;

  /** @param {WebGL2RenderingContext} gl the views' context (the GPU stepper's) */
  constructor(gl) {
    this.#gl = gl;
  }

  /** Whether a flow is on the GPU. */
  get active() {
    return this.#flow !== null;
  }

  /**
   * The last flow step's time (ms, the heat's and the flow's passes): the GPU's own, by a timer
   * query, where it gives one; else the page's time to issue them; 0 without a flow.
   */
  get ms() {
    return this.#link?.ms ?? 0;
  }

  /**
   * Takes the flow of the run scene `run` ({flow, wind, objects}, the worker's scene as it runs
   * it) with u_g `faces` ({u, v, w}: each component's faces, m/s), or lets go of it (`run` null).
   */
  start(run, faces = null) {
    this.dispose();
    if (!run) return;
    const { flow, solids, refused } = gpuFlowOfScene(this.#gl, { flow: run.flow, wind: run.wind, render: { objects: run.objects } });
    if (refused) throw new Error(`the GPU cannot step this flow: ${refused}`);
    if (faces) flow.setFaces([faces.u, faces.v, faces.w]);
    this.#flow = flow;
    this.#heat = new HeatDeposit(this.#gl);
    this.#grid = gridOf(run);
    this.#box = run.flow.box;
    // The objects' solid cells, and those of the last step (a repulsor's sphere over them).
    this.#link = { flow, heat: this.#heat, cooling: f32(run.flow.cooling), stir: null, ms: 0, timer: new GpuTimer(this.#gl), fixed: solids, solids };
  }

  /**
   * The flow after an edit to the run scene `run` (null: no flow): kept, u_g and all, with the
   * new constants while the box, cells, faces and objects stay (as the core's edit keeps its
   * own); else started again at rest.
   */
  edit(run) {
    if (!run) {
      this.dispose();
      return;
    }
    if (!this.#flow || gridOf(run) !== this.#grid) {
      this.start(run);
      return;
    }
    const f = run.flow;
    this.#flow.viscosity = f32(f.viscosity);
    this.#flow.buoyancy = f32(f.buoyancy);
    this.#flow.gravity = f.gravity.map(f32);
    this.#link.cooling = f32(f.cooling);
  }

  /** What the GPU stepper's steps read, with the stir `stir` of these steps (or null); null without a flow. */
  link(stir) {
    if (!this.#link) return null;
    this.#link.stir = stir ?? null;
    return this.#link;
  }

  /** u_g on each component's faces ({u, v, w}, m/s), read back; null without a flow. */
  faces() {
    if (!this.#flow) return null;
    const [u, v, w] = this.#flow.faces();
    return { u, v, w };
  }

  /**
   * The flow's grid as `exportFlow()` gives it at the time of `stepper` (the GpuStepper that
   * steps it): {box, cells, time, velocity, temperature} read back, the temperature laid on the
   * cells from the stepper's blobs as they are then.
   */
  export(stepper) {
    const f = this.#flow;
    stepper.depositHeat(this.#link);
    return { box: [...this.#box], cells: [...f.cells], time: stepper.time, velocity: f.cellVelocity(), temperature: f.temperatures() };
  }

  dispose() {
    this.#link?.timer.dispose();
    this.#flow?.dispose();
    this.#heat?.dispose();
    this.#flow = null;
    this.#heat = null;
    this.#grid = null;
    this.#link = null;
  }
}
