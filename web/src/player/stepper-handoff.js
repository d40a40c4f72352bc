// Who steps a player's gas, and the gas handed between them: the engine worker's core (the
// reference, 'cpu') or the GPU stepper (`stepper/gpu-stepper.js`, 'gpu'), as the choice
// (`setStepper`: 'auto', 'cpu' or 'gpu') allows and the scene and the machine permit. The gas
// crosses as its blobs' centres: to the GPU with the worker's records and the field's lattice,
// back to the worker as the GPU's centres (for good, or for a still, an export, a check).

import { GpuStepper, gpuStepperRefuses, gpuStepperUnsupported, MAX_GPU_LATTICE } from '../stepper/gpu-stepper.js';
import { flowKeepsGpuAway, hasFlow } from './flow-placement.js';

/** Why 'auto' steps in the worker on a browser that draws 3-D in software. */
const SOFTWARE_STEPPER = 'this browser draws 3-D in software: the worker steps the gas faster than its GPU passes';

/**
 * Why `scene` must be stepped in the worker (it splits blobs, plays a shape in reverse, has a
 * flow the GPU of `gl` cannot step or whose textures pass the `flowBytes` a memory budget gives
 * it, …), or null. A flow the GPU can step goes with the gas: the GPU steps it beside the
 * blobs, from their heat (`flow-handoff.js`).
 */
function sceneKeepsGpuAway(scene, gl, flowBytes) {
  const flow = flowKeepsGpuAway(scene, gl, flowBytes);
  if (flow) return `the scene's flow stays in the worker: ${flow}`;
  if ((scene.gas?.split_sigma ?? null) !== null) return 'the scene splits blobs (gas.split_sigma)';
  if (scene.shapes?.some((s) => (s.reverse_from ?? null) !== null)) return 'the scene plays a shape in reverse';
  return gpuStepperRefuses(scene);
}

/** Bytes that crossed from the worker for GPU steps `steps` (whole buffers). */
function crossedBytes(steps) {
  return ['births', 'birthSlots', 'freed', 'ranges', 'wind', 'windOffsets', 'solidGrid', 'spheres'].reduce((n, k) => n + steps[k].byteLength, 0);
}

export class StepperHandoff {
  #engine;
  #renderer;
  /** Whether the machine draws 3-D in software (`machine.js`). */
  #software;
  /** The running scene (as the core normalised it), or null. */
  #scene;
  /** Whether the view's GPU context is lost. */
  #contextLost;
  /** Runs the scene again in the worker to where it was (the GPU's copy of the gas is gone). */
  #restep;
  /** The choice: 'auto', 'cpu' or 'gpu' (`setStepper`). */
  #choice = 'auto';
  /** What steps the gas now: 'cpu' (the worker's core) or 'gpu'. */
  #active = 'cpu';
  /** Why the GPU does not step the gas when the choice allows it, or null. */
  #reason = null;
  /** The GPU stepper once made (null again once its context is lost). */
  #gpu = null;
  /** The field version its lattice is. */
  #fieldVersion = -1;
  /**
   * The scene's flow on the GPU while the GPU steps the gas (`flow-handoff.js`, fetched with the
   * first scene whose flow the GPU steps), once made.
   */
  #flow = null;
  /** Most bytes of a flow's textures on the GPU (`MemoryLimit.flowBytes`). */
  #flowBytes;

  /**
   * @param {{engine: import('../engine/client.js').Engine, renderer: object, software: boolean,
   *   scene: () => object | null, contextLost: () => boolean, restep: () => Promise<void>,
   *   flowBytes?: number}} parts
   */
  constructor({ engine, renderer, software, scene, contextLost, restep, flowBytes = Infinity }) {
    this.#engine = engine;
    this.#renderer = renderer;
    this.#software = software;
    this.#scene = scene;
    this.#contextLost = contextLost;
    this.#restep = restep;
    this.#flowBytes = flowBytes;
  }

  /** The choice of stepper: 'auto', 'gpu' or 'cpu'; taken at the next `engage`. */
  get choice() {
    return this.#choice;
  }

  set choice(kind) {
    this.#choice = kind;
  }

  /** What steps the gas now: 'cpu' or 'gpu'. */
  get active() {
    return this.#active;
  }

  /** Why the worker steps the gas where the choice allows the GPU (`stats().stepperReason`), or null. */
  get reason() {
    return this.#reason;
  }

  /**
   * What steps the scene's flow (`stats().flowStepper`): 'gpu' beside the GPU's blobs, 'cpu'
   * (the worker's core), or null without a flow.
   */
  get flowStepper() {
    if (this.#active === 'gpu' && this.#flow?.active) return 'gpu';
    return hasFlow(this.#scene()) ? 'cpu' : null;
  }

  /** The GPU's last flow step (ms on the page) while it steps the flow, else null. */
  get gpuFlowMs() {
    return this.flowStepper === 'gpu' ? this.#flow.ms : null;
  }

  /** The flow's grid read back from the GPU while it steps the flow (`exportFlow()`), else null. */
  gpuFlowGrid() {
    return this.flowStepper === 'gpu' ? this.#flow.export(this.#gpu) : null;
  }

  /** The GPU stepper while it steps the gas, else null. */
  get onGpu() {
    return this.#active === 'gpu' ? this.#gpu : null;
  }

  /** The gas is in the worker now (a new simulation, or one run again): the GPU takes it at `engage`. */
  heldByWorker() {
    this.#active = 'cpu';
  }

  /** Why the GPU cannot step the current scene here, or null when it can. */
  #gpuUnavailable() {
    const scene = this.#scene();
    const lattice = scene && scene.field.amplitude > 0 ? scene.field.size.reduce((a, b) => a * b, 1) : 0;
    return (this.#contextLost() && 'the view has lost its GPU context')
      || gpuStepperUnsupported(this.#renderer)
      || (scene && sceneKeepsGpuAway(scene, this.#renderer.getContext(), this.#flowBytes))
      || (lattice > MAX_GPU_LATTICE && `the field's lattice has over ${MAX_GPU_LATTICE} points`)
      || null;
  }

  /** Puts the gas where the choice of stepper says: on the GPU where it can be, else in the worker. */
  async engage() {
    this.#reason = this.#choice === 'cpu' ? null : this.#gpuUnavailable()
      // Drawn in software, the GPU's passes run on the CPU too, many times slower than the
      // worker's core: 'auto' leaves the gas to the worker there ('gpu' still asks for it).
      ?? (this.#choice === 'auto' && this.#software ? SOFTWARE_STEPPER : null);
    const wanted = this.#choice !== 'cpu' && !this.#reason ? 'gpu' : 'cpu';
    if (wanted === this.#active || !this.#scene()) return;
    if (wanted === 'gpu') await this.#toGpu();
    else await this.#toCpu();
  }

  /** Brings the gas back to the worker before an edit to `scene` where the GPU may not step it. */
  async leaveFor(scene) {
    if (this.#active === 'gpu' && (sceneKeepsGpuAway(scene, this.#renderer.getContext(), this.#flowBytes) || this.#choice === 'cpu')) await this.#toCpu();
  }

  /**
   * An edit the gas stayed on the GPU through: its flow as the worker now runs it (`run`: the
   * run scene's flow, primitives and objects; null without a flow), kept, restarted or gone.
   */
  async edited(run) {
    if (this.#active !== 'gpu') return;
    if (run) await this.#flowHandoff();
    if (!this.#flow) return;
    this.#flow.edit(run);
    this.#renderer.resetState();
  }

  /** The flow's hand-off to the GPU, its code fetched and the hand-off made on first use. */
  async #flowHandoff() {
    if (!this.#flow) {
      const { FlowHandoff } = await import('./flow-handoff.js');
      this.#flow ??= new FlowHandoff(this.#renderer.getContext());
    }
    return this.#flow;
  }

  /** Hands the worker's gas to the GPU stepper. */
  async #toGpu() {
    const start = await this.#engine.request('gpuStart');
    if (start.flow) await this.#flowHandoff();
    const scene = this.#scene();
    const births = scene.emitters.reduce((n, e) => n + (e.enabled ? e.rate : 0), 0) * scene.simulation.dt;
    this.#gpu ??= new GpuStepper(this.#renderer);
    this.#gpu.start({ records: start.records, capacity: scene.gas.max_blobs + Math.ceil(4 * births) + 1024, time: start.time });
    this.#gpu.setLattice(start.lattice.data, start.lattice.size, start.lattice.potential);
    this.#fieldVersion = start.lattice.version;
    this.#flow?.start(start.flow, start.flow?.faces);
    this.#renderer.resetState();
    this.#active = 'gpu';
  }

  /** Brings the gas back from the GPU stepper to the worker, which steps it from now on. */
  async #toCpu() {
    if (this.#active !== 'gpu') return;
    // Without its context the GPU's copy is gone: the worker runs the gas again instead.
    if (!this.#gpu) {
      await this.#restep();
      return;
    }
    const centres = this.#gpu.readCentres();
    // The carried offsets and the flow go back with the gas, as the GPU left them.
    const offsets = this.#gpu.readCarried();
    const flowFaces = this.#flow?.faces() ?? null;
    this.#flow?.dispose();
    this.#renderer.resetState();
    this.#active = 'cpu';
    const buffers = [centres, ...(offsets ? [offsets] : []), ...(flowFaces ? [flowFaces.u, flowFaces.v, flowFaces.w] : [])].map((a) => a.buffer);
    await this.#engine.request('takeCentres', { centres, keepOnGpu: false, offsets, flowFaces }, { transfer: buffers });
  }

  /** Gives the worker the GPU's centres as they are now (for a still, an export, a check). */
  async syncCentres() {
    if (this.#active !== 'gpu') return;
    if (!this.#gpu) {
      await this.#restep();
      return;
    }
    const centres = this.#gpu.readCentres();
    await this.#engine.request('takeCentres', { centres, keepOnGpu: true }, { transfer: [centres.buffer] });
  }

  /** The GPU takes the steps the worker took (`steps`), on the field the worker now runs on. */
  async takeSteps(steps) {
    // Without a GPU stepper (its context lost) the steps are let go: the restore re-steps.
    if (!this.#gpu) return;
    if (steps.fieldVersion !== this.#fieldVersion) {
      const lattice = await this.#engine.request('gpuLattice');
      this.#gpu.setLattice(lattice.data, lattice.size, lattice.potential);
      this.#fieldVersion = lattice.version;
    }
    // After an edit, the flow the worker now runs (kept, restarted or gone).
    if (steps.flowRun !== undefined) {
      if (steps.flowRun) await this.#flowHandoff();
      this.#flow?.edit(steps.flowRun);
      this.#renderer.resetState();
    }
    const { simulation, gas } = this.#scene();
    const flow = this.#flow?.link(steps.stir) ?? null;
    this.#gpu.apply(steps, { dt: simulation.dt, diffusion: gas.diffusion, alpha: gas.dissipation, rk2: simulation.integrator === 'rk2', flow });
  }

  /**
   * The views' frame of a step's `result`: the worker's frame as it is, or the GPU's after it
   * took the steps; null where the GPU's copy of the gas was lost (the worker's run again,
   * `#restep`, has the steps already).
   */
  async frameOf(result) {
    if (!result.gpu) return result;
    if (this.#active !== 'gpu') return null;
    await this.takeSteps(result);
    if (!this.#gpu) return null;
    const flowMs = this.gpuFlowMs ?? 0;
    return { ...this.#gpu.frame(this.#scene().render.medium.albedo), stepMs: result.stepMs + flowMs, flowMs, packMs: 0, crossed: crossedBytes(result) };
  }

  /**
   * The GPU's state went with its context: lets go of the GPU stepper (deleting its objects is
   * a no-op while lost). Returns whether it held the gas (the worker must then run it again).
   */
  contextLost() {
    this.dispose();
    return this.#active === 'gpu';
  }

  /** Lets go of the GPU stepper's objects. */
  dispose() {
    this.#flow?.dispose();
    this.#flow = null;
    this.#gpu?.dispose();
    this.#gpu = null;
  }
}
