// What a player makes of its scene besides the picture on screen: the GPU's picture offscreen
// (`captureGPU`), the WASM reference still, the blob list, the exports for pipelines (a still,
// a flipbook, a volume: `exports.js` checks their arguments, the worker makes the files) and
// the WebM (`recorder.js`), and the looks inside and timings that tests and benchmarks ask
// for. Each reads the running scene and leaves it as it was; a recording holds it still.

import { MAX_IMAGE_SIDE } from '../generated/contract.js';
import { VIEWS } from '../views/modes.js';
import { waitForGpu } from '../views/gpu-sync.js';
import { VOLUME_QUALITY } from '../views/volume/volume-layer.js';
import { atLeast, boolean, number, oneOf, wholeNumber } from './arguments.js';
import { exportBlob, flipbookRequest, stillRequest, volumeRequest } from './exports.js';
import { QUALITIES } from './view-settings.js';

/** What a load or an edit may not do while a video is recorded. */
const recordingRefuses = (what) => new Error(`a recording is under way: ${what} once it has ended`);

function bytesToDataUrl(bytes) {
  let binary = '';
  for (let i = 0; i < bytes.length; i += 0x8000) binary += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return `data:image/png;base64,${btoa(binary)}`;
}

export class Captures {
  #engine;
  #view;
  /** The view settings (`view-settings.js`): the mode and quality drawn. */
  #settings;
  /** The stepper hand-off (`stepper-handoff.js`): the GPU's centres go to the worker before the worker reads them. */
  #handoff;
  /** The running scene, or null. */
  #scene;
  /** Runs a call in its turn (no frame in flight), draws the current frame at a size, takes steps. */
  #exclusive;
  #draw;
  #advance;
  /** Hears how far a long capture has come (`onProgress`). */
  #onProgress;
  /**
   * Whether a recording has been asked for and not yet ended: steps, loads and edits asked for
   * meanwhile are refused. (`#recording`, set once its budget is checked, spans part of it.)
   */
  #recordingAsked = false;
  /** Whether a recording is under way (scenes may not change meanwhile). */
  #recording = false;

  /**
   * @param {{engine: object, view: object, settings: import('./view-settings.js').ViewSettings,
   *   handoff: import('./stepper-handoff.js').StepperHandoff, scene: () => object | null,
   *   exclusive: (fn: () => Promise<unknown>) => Promise<unknown>, draw: (size: object) => Promise<void>,
   *   advance: (steps: number) => Promise<void>, onProgress: (p: number, stage: string) => void}} parts
   */
  constructor({ engine, view, settings, handoff, scene, exclusive, draw, advance, onProgress }) {
    this.#engine = engine;
    this.#view = view;
    this.#settings = settings;
    this.#handoff = handoff;
    this.#scene = scene;
    this.#exclusive = exclusive;
    this.#draw = draw;
    this.#advance = advance;
    this.#onProgress = onProgress;
  }

  /** Refuses `what` (a load, an edit, steps) once a recording has been asked for and until it ends. */
  refuseIfAsked(what) {
    if (this.#recordingAsked) throw recordingRefuses(what);
  }

  /** Refuses `what` while the recording's frames are being made. */
  refuseIfRecording(what) {
    if (this.#recording) throw recordingRefuses(what);
  }

  /**
   * Runs `fn` (exclusively) with the view at `width × height`, drawn in `mode` at `quality`,
   * with `standIns` and without guides; puts the view back as it was afterwards.
   */
  #offscreen({ mode, quality = this.#settings.quality, standIns = false, width, height }, fn) {
    return this.#exclusive(async () => {
      const view = this.#view;
      const before = { size: view.size(), guides: view.showGuides, volumeScale: view.volumeScale };
      const shown = this.#settings.drawAs({ mode, quality });
      Object.assign(view, { standIns, showGuides: false, volumeScale: 1 });
      try {
        view.resize(width, height);
        return await fn();
      } finally {
        this.#settings.drawAs(shown);
        Object.assign(view, { standIns: false, showGuides: before.guides, volumeScale: before.volumeScale });
        view.resize(before.size.width, before.size.height);
      }
    });
  }

  /** The blob list of the current state for the current view (docs/FORMATS.md, the blob list); the GPU's centres read back first. */
  async exportBlobs({ width, height } = this.#view.size()) {
    wholeNumber('exportBlobs: width', width, 1, MAX_IMAGE_SIDE);
    wholeNumber('exportBlobs: height', height, 1, MAX_IMAGE_SIDE);
    await this.#handoff.syncCentres();
    return this.#engine.request('blobList', { camera: this.#view.cameraSettings(), image: { width, height } });
  }

  /** Renders the current view offscreen at `width × height`; a PNG data URL. */
  captureGPU({ mode = 'raymarch', width = 640, height = 480, standIns = false, quality = this.#settings.quality } = {}) {
    oneOf('captureGPU: mode', mode, VIEWS);
    oneOf('captureGPU: quality', quality, QUALITIES);
    boolean('captureGPU: standIns', standIns);
    const gl = this.#view.renderer.getContext();
    // A lost context answers null: the image budget alone then.
    const most = Math.min(MAX_IMAGE_SIDE, ...(gl.getParameter(gl.MAX_VIEWPORT_DIMS) ?? []));
    wholeNumber('captureGPU: width', width, 1, most);
    wholeNumber('captureGPU: height', height, 1, most);
    return this.#offscreen({ mode, quality, standIns, width, height }, async () => {
      await this.#draw({ width, height });
      return this.#view.canvas.toDataURL('image/png');
    });
  }

  /**
   * The real-time view's volumes for the current frame at `quality`, as the GPU holds them and
   * as the core's twin computes them on the same grid (`frame::volume`, `frame::light_volume`):
   * {grid, gpu: {density, source, light}, twin: {density, source, light}} (see
   * `VolumeLayer.read`). For tests.
   */
  inspectVolume({ quality = this.#settings.quality } = {}) {
    return this.#exclusive(async () => {
      const volume = this.#view.volume;
      if (!volume.prepare(this.#view.renderer, quality)) return null;
      const gpu = volume.read(this.#view.renderer);
      const grid = structuredClone(volume.grid);
      const q = VOLUME_QUALITY[quality] ?? VOLUME_QUALITY.standard;
      await this.#handoff.syncCentres();
      const twin = await this.#engine.request('volumeTwin', { lo: grid.lo, h: grid.h, dims: grid.dims, step: q.column });
      const voxels = grid.dims[0] * grid.dims[1] * grid.dims[2];
      return {
        grid,
        gpu,
        twin: { density: twin.volume.subarray(0, 4 * voxels), source: twin.volume.subarray(4 * voxels), light: twin.light },
      };
    });
  }

  /**
   * The GPU stepper's own σ (m), mass and centre of every blob it holds and the slot holding it
   * (slot order), and the views' frame of them as the GPU sorted and packed it (`frame`: its
   * words and description); null while the worker steps the gas. For tests: the core's blobs are
   * in `exportBlobs`.
   */
  inspectStepper() {
    return this.#exclusive(async () => {
      const gpu = this.#handoff.onGpu;
      if (!gpu) return null;
      const { words, info } = gpu.readFrame(this.#scene().render.medium.albedo);
      return { ...gpu.readSigmaAndMass(), frame: { words, info } };
    });
  }

  /**
   * The median time (ms) of drawing the current state `frames` times in `mode` at `width ×
   * height`, finished on the GPU: each frame from scratch (the real-time view's volumes rebuilt,
   * as after a step), or with `rebuild: false` the volumes kept (as when orbiting a paused scene
   * or between steps). For benchmarks.
   */
  timeFrames({ mode = 'raymarch', width = 640, height = 360, frames = 5, quality = this.#settings.quality, rebuild = true } = {}) {
    return this.#offscreen({ mode, quality, width, height }, async () => {
      const times = [];
      for (let i = 0; i <= frames; i++) {
        if (rebuild) this.#view.volume.invalidate();
        const t0 = performance.now();
        await this.#draw({ width, height });
        waitForGpu(this.#view.renderer);
        if (i > 0) times.push(performance.now() - t0);
      }
      return times.sort((a, b) => a - b)[Math.floor(times.length / 2)];
    });
  }

  /**
   * The median time (ms) of one GPU step of the current gas (`repeats` passes, finished on the
   * GPU; the gas is not moved), or null while the worker steps it. For benchmarks.
   */
  timeGpuStep({ repeats = 5 } = {}) {
    return this.#exclusive(async () => this.#handoff.onGpu?.timeStep(repeats) ?? null);
  }

  /**
   * The median time (ms) of sorting the GPU stepper's gas by σ class and packing it for the
   * views, as after each of its steps (`repeats` times, each pass finished on the GPU): {ms,
   * passes: {keys, counts, gather, bounds, pack}}, or null while the worker steps it. For
   * benchmarks.
   */
  timeGpuSort({ repeats = 5 } = {}) {
    return this.#exclusive(async () => this.#handoff.onGpu?.timeSort(repeats, this.#scene().render.medium.albedo) ?? null);
  }

  /**
   * The WASM reference still of the current view at `width × height`; a PNG data URL. The
   * engine renders the blob list of its current state from this camera: only the PNG crosses.
   */
  async renderReference({ width = 320, height = 240 } = {}) {
    return bytesToDataUrl(await this.referencePng({ width, height }));
  }

  /** The WASM reference still of the current view at `width × height` (see `renderReference`): the PNG's bytes. */
  async referencePng({ width = 320, height = 240 } = {}) {
    wholeNumber('renderReference: width', width, 1, MAX_IMAGE_SIDE);
    wholeNumber('renderReference: height', height, 1, MAX_IMAGE_SIDE);
    await this.#handoff.syncCentres();
    const out = await this.#engine.request('reference', { camera: this.#view.cameraSettings(), width, height }, {
      onProgress: (p) => this.#onProgress(p.progress, 'Rendering reference still'),
    });
    this.#onProgress(1, 'done');
    return out.png;
  }

  /**
   * Exports for pipelines (docs/FORMATS.md, exports), made in the worker by the command line's
   * code: a still (PNG or EXR, optionally over a transparent background) and a volume (OpenVDB)
   * of the current state, a flipbook of the scene from t = 0, each seen from the view's camera;
   * each a Promise of a Blob. The running scene is only read; `cancelExport()` stops them.
   */
  async exportStill(options = {}) {
    const request = stillRequest(options, this.#view.size());
    await this.#handoff.syncCentres();
    return exportBlob(this.#engine, 'exportStill', { ...request, camera: this.#view.cameraSettings() }, this.#onProgress);
  }

  async exportFlipbook(options = {}) {
    return exportBlob(this.#engine, 'exportFlipbook', flipbookRequest(options, this.#view.cameraSettings()), this.#onProgress);
  }

  async exportVolume(options = {}) {
    const request = volumeRequest(options);
    await this.#handoff.syncCentres();
    return exportBlob(this.#engine, 'exportVolume', request, this.#onProgress);
  }

  /**
   * The flow's grid now (docs/FORMATS.md, the browser API): `{box, cells, time, velocity,
   * temperature}`, u_g at the cells' centres (m/s, Float32Array (nz, ny, nx, 3), x fastest) and
   * the temperature excess (K, Float32Array (nz, ny, nx)), whole buffers from wherever the flow
   * is stepped (read back from the GPU while it steps the flow, else from the worker); null for
   * a scene without one.
   */
  exportFlow() {
    return this.#exclusive(async () => this.#handoff.gpuFlowGrid() ?? this.#engine.request('exportFlow'));
  }

  /** Cancels the exports in flight (they reject with "cancelled: …"); resolves with how many. */
  cancelExport() {
    return this.#engine.request('cancelExport');
  }

  /**
   * A WebM of `frames` consecutive fixed steps (one step a frame, from the current state),
   * drawn at width × height in `mode`, at `fps` frames per second of video.
   */
  async recordWebM({ frames = 60, width = 640, height = 480, fps = 30, mode = this.#settings.mode } = {}) {
    // More frames than the run budget allows are refused below, in the budget's words.
    atLeast('recordWebM: frames', frames, 1);
    wholeNumber('recordWebM: width', width, 2, 4096);
    wholeNumber('recordWebM: height', height, 2, 4096);
    number('recordWebM: fps', fps, 0, 240);
    oneOf('recordWebM: mode', mode, VIEWS);
    if (this.#recordingAsked) throw new Error('a recording is under way already');
    // Steps asked for from now on are refused, however long the budget's check below takes; a
    // load asked for before it still lands first (the engine answers in order).
    this.#recordingAsked = true;
    try {
      // One step a frame: the run budget (docs/FORMATS.md, the command line) holds before anything is recorded.
      await this.#engine.request('checkSteps', { steps: frames });
      // The encoder and the muxer are fetched with the first recording (webm-muxer is not part
      // of the player's first load).
      const { recordWebM: record } = await import('./recorder.js');
      // One scene, one size: the scene may not change while the video is made.
      this.#recording = true;
      try {
        return await this.#offscreen({ mode, width, height }, () => record({
          canvas: this.#view.canvas,
          frames,
          fps,
          renderFrame: (k) => this.#advance(k === 0 ? 0 : 1),
          onProgress: (p) => this.#onProgress(p < 1 ? p : 1, 'Recording video'),
        }));
      } finally {
        this.#recording = false;
      }
    } finally {
      this.#recordingAsked = false;
    }
  }
}
