// A player: one scene running in its own engine worker, drawn into one canvas, with the
// scripting API of DESIGN §5. The playground page and every <wind-field> element each own one.

import { Engine } from './engine/client.js';
import { recordWebM } from './recorder.js';
import { ResolutionGovernor, startScale } from './resolution.js';
import { waitForGpu } from './views/gpu-sync.js';
import { SceneView } from './views/scene-view.js';
import { SLICE_SAMPLES } from './views/wind-slice-layer.js';
import { VOLUME_QUALITY } from './views/volume/volume-layer.js';

/**
 * The exact march at each quality: shadow-grid points per axis, and the cell side (in σ) within
 * which blobs are merged by moments for it (`render::lod` in the core). The real-time view's
 * qualities are `VOLUME_QUALITY`.
 */
export const QUALITY = {
  draft: { shadowGrid: 16, merge: 1 },
  standard: { shadowGrid: 32, merge: 0.5 },
  high: { shadowGrid: 64, merge: 0.25 },
};
/** The views (DESIGN §5's capture modes). */
export const MODES = ['points', 'raymarch', 'exact'];
/** Most fixed steps taken in one animation frame. */
const MAX_STEPS_PER_FRAME = 4;
/** A frame that waited longer than this (ms) for the worker's step was paced by the worker. */
const WORKER_WAIT_MS = 2;

function bytesToDataUrl(bytes) {
  let binary = '';
  for (let i = 0; i < bytes.length; i += 0x8000) binary += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return `data:image/png;base64,${btoa(binary)}`;
}

export class Player {
  /**
   * @param {HTMLCanvasElement} canvas
   * @param {{onProgress?: (p: number, stage: string) => void, onMessage?: (text: string) => void,
   *          onFrame?: (frame: object) => void, onScene?: (scene: object) => void,
   *          playing?: boolean, profile?: boolean}} hooks (`profile`: time the volume view's
   *   passes on the GPU, reported by `stats().passes`; slower, for benchmarks)
   */
  constructor(canvas, hooks = {}) {
    this.hooks = hooks;
    this.state = { scene: null, playing: hooks.playing ?? true, mode: 'raymarch', quality: 'standard', speed: 1, visible: true };
    this.stats = { blobs: 0, time: 0, fieldMs: 0, stepMs: 0, packMs: 0, frameBytes: 0, frameMs: 0, fps: 0, scale: 1 };
    /**
     * Holds the frame rate by scaling the canvas's internal resolution and the real-time
     * view's voxels (`stats().scale`), starting lower on phone-sized screens.
     */
    this.resolution = new ResolutionGovernor({ start: startScale(window.innerWidth, window.innerHeight) });
    this.busy = false;
    this.lastFrame = null;
    /** The step asked for ahead while playing (a promise of its frame), or null. */
    this.ahead = null;
    /** The showing of that step under way (`#settle`), or null. */
    this.settling = null;
    /** When the loop last found nothing to do (rAF ms). */
    this.idleAt = -Infinity;
    /** Frames per second the view keeps up, from frames drawn back to back (the governor's input). */
    this.pace = 0;
    /** How long the last frame waited for the worker (ms). */
    this.waited = 0;
    this.accumulated = 0;
    this.view = new SceneView(canvas);
    this.view.volume.profile = Boolean(hooks.profile);
    this.engine = new Engine({
      onError: (m) => hooks.onMessage?.(m),
      onRestart: () => {
        // Exclusive, so that steps asked for meanwhile wait for the reloaded scene.
        if (this.state.scene) this.exclusive(() => this.load(this.state.scene)).catch((e) => hooks.onMessage?.(e.message));
      },
    });
    this.lastTime = performance.now();
    this.lastDrawn = 0;
    /** Whether something changed the picture since the last frame (the camera moved, …). */
    this.dirty = true;
    this.view.controls.addEventListener('change', () => { this.dirty = true; });
    this.running = true;
    this.resize();
    requestAnimationFrame((t) => this.loop(t));
  }

  /** Loads `scene` (validated by the core); rejects with a clear Error and keeps the old one. */
  async load(scene) {
    await this.#settle();
    const info = await this.engine.request('load', { scene }, {
      onProgress: (p) => this.hooks.onProgress?.(p.progress, `Generating field: ${p.stage}`),
    });
    this.hooks.onProgress?.(1, 'done');
    this.state.scene = info.scene;
    this.stats.fieldMs = info.fieldMs;
    this.view.setCamera(info.scene.render.camera);
    this.view.setRenderSettings(info.scene.render);
    this.resize();
    this.accumulated = 0;
    await this.advance(0);
    await this.hooks.onScene?.(info.scene);
    return info.scene;
  }

  /** Loads the scene JSON at `url`. */
  async loadUrl(url) {
    const response = await fetch(url);
    if (!response.ok) throw new Error(`could not load ${url} (${response.status})`);
    let scene;
    try {
      scene = await response.json();
    } catch {
      throw new Error(`${url} is not a scene (JSON expected)`);
    }
    return this.load(scene);
  }

  async advance(steps) {
    const t0 = performance.now();
    await this.#settle();
    await this.#show(await this.engine.request('advance', { steps }), steps, t0);
  }

  /**
   * While playing: the frame `steps` ahead, then the next step asked for at once, so the worker
   * steps while this frame is drawn (the worker runs one step ahead of the picture, as a frame
   * in flight; `#settle` shows it before anything else reads or changes the state).
   */
  async #play(steps) {
    const t0 = performance.now();
    // Both requests go out now, in order, before anything else can ask the worker for more.
    const ahead = this.ahead;
    this.ahead = null;
    const left = ahead ? steps - 1 : steps;
    const more = left > 0 ? this.engine.request('advance', { steps: left }) : null;
    let frame = ahead ? await ahead : null;
    if (more) frame = await more;
    this.waited = performance.now() - t0;
    if (this.state.playing) this.ahead = this.engine.request('advance', { steps: 1 });
    await this.#show(frame, steps, t0);
  }

  /**
   * Shows the step asked for ahead, if any, so the picture is the worker's state again. Callers
   * meanwhile wait for the same showing, and go on in the order they called.
   */
  #settle() {
    if (this.ahead) {
      const ahead = this.ahead;
      this.ahead = null;
      this.settling = ahead.then((frame) => this.#show(frame, 1, performance.now()))
        .finally(() => { this.settling = null; });
    }
    return this.settling ?? Promise.resolve();
  }

  /** Takes `frame` (after `steps` steps) as the current one and draws it; `t0` when it was asked for. */
  async #show(frame, steps, t0) {
    this.lastFrame = frame;
    this.view.setFrame(frame);
    this.stats.blobs = frame.count;
    this.stats.time = frame.time;
    if (steps > 0) this.stats.stepMs = frame.stepMs;
    this.stats.packMs = frame.packMs;
    this.stats.frameBytes = frame.blobs.byteLength + frame.info.byteLength + frame.spheres.byteLength;
    await this.draw();
    this.stats.frameMs = performance.now() - t0;
    this.hooks.onFrame?.(frame);
  }

  /** The blob list of the current state for the current view (DESIGN §4). */
  exportBlobs({ width, height } = this.view.size()) {
    return this.engine.request('blobList', { camera: this.view.cameraSettings(), image: { width, height } });
  }

  async draw(size = this.view.size()) {
    if (!this.lastFrame || !this.state.scene) return;
    this.dirty = false;
    this.view.setRenderSettings(this.state.scene.render);
    this.view.guides.update(this.state.scene);
    const square = this.view.sliceSquare();
    if (square) {
      const data = await this.engine.request('windSlice', { ...square, n: SLICE_SAMPLES });
      this.view.windSlice.update(data, square);
    } else {
      this.view.windSlice.hide();
    }
    if (this.state.mode === 'exact') {
      const quality = QUALITY[this.state.quality] ?? QUALITY.standard;
      const frame = await this.engine.request('exactFrame', {
        view: this.view.viewBasis(), width: size.width, height: size.height, fraction: quality.merge, res: quality.shadowGrid,
      });
      this.view.exact.update(frame);
    }
    this.view.render(this.state.mode, this.state.quality);
  }

  /** Sizes the canvas's drawing buffer to its box times the resolution scale. */
  resize() {
    const c = this.view.canvas;
    const scale = this.state.mode === 'points' ? 1 : this.resolution.scale;
    this.stats.scale = scale;
    this.view.volumeScale = scale;
    const width = Math.max(Math.round(c.clientWidth * scale), 1);
    const height = Math.max(Math.round(c.clientHeight * scale), 1);
    const now = this.view.size();
    if (now.width !== width || now.height !== height) this.view.resize(width, height);
    this.draw().catch(() => {});
  }

  /** Redraws at the next animation frame. */
  invalidate() {
    this.dirty = true;
  }

  /**
   * Counts a frame drawn from `start` to `end` (ms) into the frame rate and lets the resolution
   * follow it: a frame begun right after the last one counts from that one's end (the loop's
   * pace); the first after an idle spell counts its own duration.
   */
  #drawn(start, end) {
    const busy = start - this.lastDrawn < 100;
    const seconds = (busy ? end - this.lastDrawn : end - start) / 1000;
    // A frame after an animation frame with nothing to do (a scene stepping slower than the
    // display), or one that waited for the worker's step, is paced by the scene or the worker,
    // not by the view: it does not move the resolution.
    const paced = this.idleAt > this.lastDrawn || this.waited > WORKER_WAIT_MS;
    this.waited = 0;
    this.lastDrawn = end;
    if (!(seconds > 0)) return;
    this.stats.fps = this.stats.fps > 0 && busy ? 0.8 * this.stats.fps + 0.2 / seconds : 1 / seconds;
    if (paced) return;
    this.pace = this.pace > 0 && busy ? 0.8 * this.pace + 0.2 / seconds : 1 / seconds;
    if (this.state.mode !== 'points' && this.resolution.observe(end, this.pace)) this.resize();
  }

  loop(now) {
    if (!this.running) return;
    const dt = Math.min((now - this.lastTime) / 1000, 0.1);
    this.lastTime = now;
    if (this.state.scene && !this.busy && this.state.visible) {
      let steps = 0;
      if (this.state.playing) {
        this.accumulated += dt * this.state.speed;
        const h = this.state.scene.simulation.dt;
        steps = Math.min(Math.floor(this.accumulated / h), MAX_STEPS_PER_FRAME);
        this.accumulated -= steps * h;
      }
      // Paused with a step in flight: show it.
      const work = steps > 0 ? () => this.#play(steps)
        : this.ahead && !this.state.playing ? () => this.#settle()
          : this.dirty ? () => this.draw() : null;
      if (work) {
        this.busy = true;
        const start = performance.now();
        work()
          .then(() => this.#drawn(start, performance.now()))
          .catch((e) => this.hooks.onMessage?.(e.message))
          .finally(() => { this.busy = false; });
      } else {
        this.idleAt = now;
      }
    }
    requestAnimationFrame((t) => this.loop(t));
  }

  /** Runs `fn` when no frame is in flight, the step asked for ahead shown first. */
  async exclusive(fn) {
    while (this.busy) await new Promise((r) => setTimeout(r, 5));
    this.busy = true;
    try {
      await this.#settle();
      return await fn();
    } finally {
      this.busy = false;
    }
  }

  /**
   * Runs `fn` (exclusively) with the view at `width × height`, drawn in `mode` at `quality`,
   * with `standIns` and without guides; puts the view back as it was afterwards.
   */
  offscreen({ mode, quality = this.state.quality, standIns = false, width, height }, fn) {
    return this.exclusive(async () => {
      const before = { size: this.view.size(), mode: this.state.mode, quality: this.state.quality, guides: this.view.showGuides, volumeScale: this.view.volumeScale };
      Object.assign(this.state, { mode, quality });
      Object.assign(this.view, { standIns, showGuides: false, volumeScale: 1 });
      try {
        this.view.resize(width, height);
        return await fn();
      } finally {
        Object.assign(this.state, { mode: before.mode, quality: before.quality });
        Object.assign(this.view, { standIns: false, showGuides: before.guides, volumeScale: before.volumeScale });
        this.view.resize(before.size.width, before.size.height);
      }
    });
  }

  /** Renders the current view offscreen at `width × height`; a PNG data URL. */
  captureGPU({ mode = 'raymarch', width = 640, height = 480, standIns = false, quality = this.state.quality } = {}) {
    return this.offscreen({ mode, quality, standIns, width, height }, async () => {
      await this.draw({ width, height });
      return this.view.canvas.toDataURL('image/png');
    });
  }

  /**
   * The real-time view's volumes for the current frame at `quality`, as the GPU holds them and
   * as the core's twin computes them on the same grid (`render::volume`): {grid, gpu: {density,
   * source, light}, twin: {density, source, light}} (see `VolumeLayer.read`). For tests.
   */
  inspectVolume({ quality = this.state.quality } = {}) {
    return this.exclusive(async () => {
      const volume = this.view.volume;
      if (!volume.prepare(this.view.renderer, quality)) return null;
      const gpu = volume.read(this.view.renderer);
      const grid = structuredClone(volume.grid);
      const q = VOLUME_QUALITY[quality] ?? VOLUME_QUALITY.standard;
      const twin = await this.engine.request('volumeTwin', { lo: grid.lo, h: grid.h, dims: grid.dims, step: q.column });
      const voxels = grid.dims[0] * grid.dims[1] * grid.dims[2];
      return {
        grid,
        gpu,
        twin: { density: twin.volume.subarray(0, 4 * voxels), source: twin.volume.subarray(4 * voxels), light: twin.light },
      };
    });
  }

  /**
   * The median time (ms) of drawing the current state `frames` times in `mode` at `width ×
   * height`, finished on the GPU: each frame from scratch (the real-time view's volumes rebuilt,
   * as after a step), or with `rebuild: false` the volumes kept (as when orbiting a paused scene
   * or between steps). For benchmarks.
   */
  timeFrames({ mode = 'raymarch', width = 640, height = 360, frames = 5, quality = this.state.quality, rebuild = true } = {}) {
    return this.offscreen({ mode, quality, width, height }, async () => {
      const times = [];
      for (let i = 0; i <= frames; i++) {
        if (rebuild) this.view.volume.invalidate();
        const t0 = performance.now();
        await this.draw({ width, height });
        waitForGpu(this.view.renderer);
        if (i > 0) times.push(performance.now() - t0);
      }
      return times.sort((a, b) => a - b)[Math.floor(times.length / 2)];
    });
  }

  /** The WASM reference still of the current view at `width × height`; a PNG data URL. */
  async renderReference({ width = 320, height = 240 } = {}) {
    const list = await this.exportBlobs({ width, height });
    const out = await this.engine.request('reference', { list, width, height }, {
      onProgress: (p) => this.hooks.onProgress?.(p.progress, 'Rendering reference still'),
    });
    this.hooks.onProgress?.(1, 'done');
    return bytesToDataUrl(out.png);
  }

  /**
   * A WebM of `frames` consecutive fixed steps (one step a frame, from the current state),
   * drawn at width × height in `mode`, at `fps` frames per second of video.
   */
  async recordWebM({ frames = 60, width = 640, height = 480, fps = 30, mode = this.state.mode } = {}) {
    // One step a frame: the budget of DESIGN §7 holds before anything is recorded.
    await this.engine.request('checkSteps', { steps: frames });
    return this.offscreen({ mode, width, height }, () => recordWebM({
      canvas: this.view.canvas,
      frames,
      fps,
      renderFrame: (k) => this.advance(k === 0 ? 0 : 1),
      onProgress: (p) => this.hooks.onProgress?.(p < 1 ? p : 1, 'Recording video'),
    }));
  }

  /** DESIGN §5's methods, bound to this player. */
  api(ready) {
    return {
      ready,
      getScene: () => structuredClone(this.state.scene),
      setScene: (scene) => this.load(scene),
      pause: () => { this.state.playing = false; },
      setView: (mode) => {
        if (!MODES.includes(mode)) throw new Error(`setView: the view must be one of ${MODES.join(', ')} (got ${mode})`);
        this.state.mode = mode;
        this.resize();
      },
      play: () => { this.state.playing = true; },
      step: (n = 1) => this.exclusive(() => this.advance(n)),
      stats: () => ({ ...this.stats, ...(this.view.volume.timings && { passes: { ...this.view.volume.timings } }) }),
      exportBlobs: (size) => this.exportBlobs(size),
      captureGPU: (options) => this.captureGPU(options),
      renderReference: (options) => this.renderReference(options),
      recordWebM: (options) => this.recordWebM(options),
      inspectVolume: (options) => this.inspectVolume(options),
      timeFrames: (options) => this.timeFrames(options),
    };
  }

  dispose() {
    this.running = false;
    this.engine.terminate();
    this.view.renderer.dispose();
  }
}
