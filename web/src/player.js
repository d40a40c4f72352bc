// A player: one scene running in its own engine worker, drawn into one canvas, with the
// scripting API of DESIGN §5. The playground page and every <wind-field> element each own one.

import { Engine } from './engine/client.js';
import { recordWebM } from './recorder.js';
import { ResolutionGovernor, startScale } from './resolution.js';
import { waitForGpu } from './views/gpu-sync.js';
import { PointerStir } from './views/pointer-stir.js';
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
/** A scene that has run this many steps without the engine failing is one to go back to. */
const GOOD_AFTER_STEPS = 120;
/** Most fixed steps taken in one animation frame. */
const MAX_STEPS_PER_FRAME = 4;
/** A frame that waited longer than this (ms) for the worker's step was paced by the worker. */
const WORKER_WAIT_MS = 2;

/** How long (ms) a lost GPU context may stay lost before the player reports it. */
const CONTEXT_GRACE_MS = 3000;

/** A scene as the JSON text the worker takes; a clear Error for what cannot be a scene. */
function sceneText(scene) {
  if (!scene || typeof scene !== 'object' || Array.isArray(scene)) throw new Error('a scene must be an object (a parsed scene JSON)');
  try {
    return JSON.stringify(scene);
  } catch (err) {
    throw new Error(`the scene cannot be read as JSON (${err instanceof RangeError ? 'it is nested too deeply' : err.message})`);
  }
}

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
   *          onFault?: (message: string) => void, requestTimeoutMs?: number,
   *          playing?: boolean, profile?: boolean}} hooks (`onFault`: the player cannot go on
   *   as it is, e.g. its GPU context was lost for good or its scene stops the engine; `profile`:
   *   time the volume view's passes on the GPU, reported by `stats().passes`; slower, for
   *   benchmarks)
   */
  constructor(canvas, hooks = {}) {
    this.hooks = hooks;
    this.state = { scene: null, playing: hooks.playing ?? true, mode: 'raymarch', quality: 'standard', speed: 1, visible: true };
    this.stats = {
      blobs: 0, time: 0, fieldMs: 0, stepMs: 0, packMs: 0, frameBytes: 0, frameMs: 0, fps: 0, scale: 1,
      frames: 0, limitedBy: 'paused',
    };
    /** When the last frames were drawn (ms), the newest last: `stats().fps` counts them. */
    this.drawTimes = [];
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
    /** How long the last frame waited for the worker (ms), and the share of recent frames spent so. */
    this.waited = 0;
    this.waitShare = 0;
    this.accumulated = 0;
    this.view = new SceneView(canvas);
    this.view.volume.profile = Boolean(hooks.profile);
    /** Failures of the engine per scene (its JSON text), and the last scene that ran well. */
    this.failures = new Map();
    this.lastGood = null;
    /** Steps taken since the current scene was loaded (it is good after `GOOD_AFTER_STEPS`). */
    this.stepsSinceLoad = 0;
    /** Why the player stopped (the engine keeps failing on its scene), or null. */
    this.halted = null;
    /** Whether a recording is under way (scenes may not change meanwhile). */
    this.recording = false;
    this.engine = new Engine({
      onError: (m) => hooks.onMessage?.(m),
      onRestart: (reason) => this.#recover(reason),
    }, { timeoutMs: hooks.requestTimeoutMs });
    /** Whether the view's GPU context is lost (drawing waits for it to come back). */
    this.contextLost = false;
    this.contextTimer = 0;
    this.view.onContextLost = () => {
      this.contextLost = true;
      clearTimeout(this.contextTimer);
      this.contextTimer = setTimeout(() => this.#fault('the view lost its GPU context and the browser did not give it back (too many 3-D views open at once, or the GPU was reset)'), CONTEXT_GRACE_MS);
    };
    this.view.onContextRestored = () => {
      clearTimeout(this.contextTimer);
      this.contextLost = false;
      if (this.lastFrame) this.view.setFrame(this.lastFrame);
      this.invalidate();
    };
    this.lastTime = performance.now();
    this.lastDrawn = 0;
    /** Whether something changed the picture since the last frame (the camera moved, …). */
    this.dirty = true;
    this.view.controls.addEventListener('change', () => { this.dirty = true; });
    /** Dragging stirs the gas instead of orbiting while `stirring.enabled` (off at first). */
    this.stirring = new PointerStir(this.view, (position, velocity, radius) => {
      if (this.state.scene) this.stir(position, velocity, radius).catch(() => {});
    });
    this.running = true;
    this.resize();
    requestAnimationFrame((t) => this.loop(t));
  }

  /**
   * After the engine failed (and was restarted): reloads the scene that ran, unless it has made
   * the engine fail before, in which case it goes back to the last scene that ran well, or stops
   * with a message; a scene never sends the engine into a loop of restarts.
   */
  #recover(reason) {
    const scene = this.state.scene;
    if (!scene) return;
    const key = JSON.stringify(scene);
    const failures = (this.failures.get(key) ?? 0) + 1;
    this.failures.set(key, failures);
    // Exclusive, so that steps asked for meanwhile wait for the reloaded scene.
    const reload = (next) => this.exclusive(() => this.load(next)).catch((e) => this.hooks.onMessage?.(e.message));
    if (failures === 1) {
      reload(scene);
    } else if (this.lastGood && this.lastGood !== key) {
      this.hooks.onMessage?.(`This scene stopped the engine twice (${reason}); back to the last scene that ran.`);
      reload(JSON.parse(this.lastGood));
    } else {
      this.#fault(`this scene stopped the engine twice (${reason}); load another scene`);
      this.halted = reason;
    }
  }

  /** Reports that the player cannot go on as it is. */
  #fault(message) {
    this.hooks.onFault?.(message);
    if (!this.hooks.onFault) this.hooks.onMessage?.(message);
  }

  /** Loads `scene` (validated by the core); rejects with a clear Error and keeps the old one. */
  async load(scene) {
    if (this.recording) throw new Error('a recording is under way: load the scene once it has ended');
    const text = sceneText(scene);
    await this.#settle();
    const info = await this.engine.request('load', { scene: text }, {
      onProgress: (p) => this.hooks.onProgress?.(p.progress, `Generating field: ${p.stage}`),
    });
    this.hooks.onProgress?.(1, 'done');
    this.halted = null;
    this.stepsSinceLoad = 0;
    this.state.scene = info.scene;
    this.stats.fieldMs = info.fieldMs;
    this.view.setCamera(info.scene.render.camera, info.scene.render.objects);
    this.view.setRenderSettings(info.scene.render);
    this.resize();
    this.accumulated = 0;
    await this.advance(0);
    await this.hooks.onScene?.(info.scene);
    return info.scene;
  }

  /**
   * Applies an edited scene to the running simulation: it keeps its blobs and its time
   * (a change of the field's settings is synthesised while the gas goes on); rejects with a
   * clear Error and keeps the scene as it was. Resolves with the scene as the core normalised it.
   */
  async edit(scene) {
    if (this.recording) throw new Error('a recording is under way: change the scene once it has ended');
    const text = sceneText(scene);
    await this.#settle();
    const info = await this.engine.request('edit', { scene: text }, {
      onProgress: (p) => this.hooks.onProgress?.(p.progress, `Generating the new field: ${p.stage}`),
    });
    const camera = JSON.stringify(this.state.scene?.render.camera);
    this.state.scene = info.scene;
    if (info.restarted || camera !== JSON.stringify(info.scene.render.camera)) this.view.setCamera(info.scene.render.camera, info.scene.render.objects);
    else this.view.limits.set(info.scene.render.camera, info.scene.render.objects);
    this.view.setRenderSettings(info.scene.render);
    if (info.restarted) this.accumulated = 0;
    await this.advance(0);
    await this.hooks.onScene?.(info.scene);
    return info.scene;
  }

  /** Restarts the scene at t = 0. */
  reset() {
    return this.exclusive(async () => {
      const t0 = performance.now();
      this.accumulated = 0;
      await this.#show(await this.engine.request('reset'), 0, t0);
    });
  }

  /**
   * Stirs the gas from the next step on: a wind of `velocity` (m/s) at `position` (m) that falls
   * off as exp(−distance/`radius`), until the next call; `radius` 0 stops it.
   */
  stir(position, velocity, radius) {
    return this.engine.request('stir', { position, velocity, radius });
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
    this.stepsSinceLoad += steps;
    if (this.stepsSinceLoad >= GOOD_AFTER_STEPS && this.state.scene) this.lastGood = JSON.stringify(this.state.scene);
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
    if (!this.lastFrame || !this.state.scene || this.contextLost) return;
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
   * Counts a frame drawn from `start` to `end` (ms). `stats().fps` is the number of frames drawn
   * in the last second (the last two while the rate is low), so it says what the screen shows;
   * `stats().limitedBy` what holds the rate down: `worker` (frames spend most of their time
   * waiting for the step), `view` (drawing takes the time), `display` (the frames keep up with the display) or `paused`.
   * The resolution follows the pace of frames the view itself paced: drawn back to back, not
   * after an idle animation frame (a scene stepping slower than the display) nor after waiting
   * for the worker.
   */
  #drawn(start, end) {
    const times = this.drawTimes;
    times.push(end);
    while (times.length > 2 && times[0] < end - 2000) times.shift();
    this.stats.frames += 1;
    this.#countRate(end);
    const busy = start - this.lastDrawn < 100;
    const seconds = (busy ? end - this.lastDrawn : end - start) / 1000;
    // The share of the frame spent waiting for the worker's step (smoothed).
    if (seconds > 0) this.waitShare = 0.8 * this.waitShare + 0.2 * Math.min(this.waited / (1000 * seconds), 1);
    const paced = this.idleAt > this.lastDrawn || this.waited > WORKER_WAIT_MS;
    this.waited = 0;
    this.lastDrawn = end;
    this.stats.limitedBy = !this.state.playing ? 'paused'
      : this.waitShare > 0.5 ? 'worker'
        : this.stats.fps < 0.9 * this.resolution.target ? 'view' : 'display';
    if (!(seconds > 0) || paced) return;
    this.pace = this.pace > 0 && busy ? 0.8 * this.pace + 0.2 / seconds : 1 / seconds;
    if (this.state.mode !== 'points' && this.resolution.observe(end, this.pace)) this.resize();
  }

  /** Frames drawn per second at `now` (ms): those of the last second, or of two when few. */
  #countRate(now) {
    const times = this.drawTimes;
    const inLast = (ms) => times.filter((t) => t > now - ms).length;
    const recent = inLast(1000);
    this.stats.fps = recent >= 10 ? recent : inLast(2000) / 2;
  }

  loop(now) {
    if (!this.running) return;
    const dt = Math.min((now - this.lastTime) / 1000, 0.1);
    this.lastTime = now;
    if (this.state.scene && !this.busy && this.state.visible && !this.halted) {
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
      // Frames stop counting while nothing is drawn.
      if (now - (this.drawTimes.at(-1) ?? -Infinity) > 2000 && this.stats.fps > 0) this.#countRate(now);
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
    if (this.recording) throw new Error('a recording is under way already');
    // One scene, one size: the scene may not change while the video is made.
    this.recording = true;
    try {
      return await this.offscreen({ mode, width, height }, () => recordWebM({
        canvas: this.view.canvas,
        frames,
        fps,
        renderFrame: (k) => this.advance(k === 0 ? 0 : 1),
        onProgress: (p) => this.hooks.onProgress?.(p < 1 ? p : 1, 'Recording video'),
      }));
    } finally {
      this.recording = false;
    }
  }

  /** Whether the wind guides (and the drag handle, and the wind slice) are drawn. */
  get guides() {
    return this.view.showGuides;
  }

  setGuides(on) {
    this.view.showGuides = on;
    this.invalidate();
  }

  /** The wind slice's plane ('off', 'xy', 'xz', 'yz') and its offset along the normal (m). */
  get slicePlane() {
    return this.view.slicePlane;
  }

  set slicePlane(plane) {
    this.view.slicePlane = plane;
    this.invalidate();
  }

  get sliceOffset() {
    return this.view.sliceOffset;
  }

  set sliceOffset(d) {
    this.view.sliceOffset = d;
    this.invalidate();
  }

  /** The wind slice's colour scale while it is drawn: `{plane, maxSpeed}` (m/s), else null. */
  sliceLegend() {
    const slice = this.view.windSlice;
    return slice.group.visible ? { plane: this.view.slicePlane, maxSpeed: slice.maxSpeed } : null;
  }

  /** The real-time view's density volume in voxels `[nx, ny, nz]`, when that view is shown. */
  volumeDims() {
    return this.state.mode === 'raymarch' ? this.view.volume.grid?.dims ?? null : null;
  }

  /** Fixes the view's resolution (a scale in (0, 1]) or lets it hold the frame rate ('auto'). */
  setResolution(scale) {
    this.resolution.set(scale);
    this.resize();
  }

  /** Picks the wind primitive or emitter (`{list, index}`) the drag handle moves, or none. */
  selectHandle(selection) {
    this.view.guides.select(selection);
    if (selection) this.view.showGuides = true;
    this.invalidate();
  }

  /** Calls `fn(selection, to)` when the drag handle has moved its item to `to` (m). */
  onHandleMoved(fn) {
    this.view.guides.onMoved = fn;
  }

  /** Orbits or zooms for a key pressed on the view (arrows, + and −); true when it did. */
  orbitKey(event) {
    const handled = this.view.limits.key(event);
    if (handled) this.invalidate();
    return handled;
  }

  /** `n` fixed steps when no frame is in flight. */
  step(n = 1) {
    return this.exclusive(() => this.advance(n));
  }

  /** The statistics of `stats()`: the engine's, the view's and how the frames go. */
  snapshot() {
    return { ...this.stats, stepper: 'cpu', ...(this.view.volume.timings && { passes: { ...this.view.volume.timings } }) };
  }

  /** The field's statistics against `spectrum` (its own when absent), measured in the worker. */
  fieldStats(spectrum) {
    return this.engine.request('fieldStats', { spectrum });
  }

  /** The engine's health: its memory, the blob count and blobs whose centre is not finite. */
  health() {
    return this.engine.request('health');
  }

  /** The small-scale field at lattice coordinates (x, y, z, t). */
  sample(x, y, z, t) {
    return this.engine.request('sample', { x, y, z, t });
  }

  /**
   * Chooses what steps the gas: 'cpu' (the worker's core), 'gpu' or 'auto' (the GPU where it
   * can). Stepping on the GPU is not available in this build: 'gpu' rejects, 'auto' takes the
   * worker.
   */
  async setStepper(kind) {
    if (!['cpu', 'gpu', 'auto'].includes(kind)) throw new Error(`setStepper: the stepper must be 'cpu', 'gpu' or 'auto' (got ${kind})`);
    if (kind === 'gpu') throw new Error('setStepper: stepping on the GPU is not available here; the worker steps the gas');
    return this.snapshot().stepper;
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
      step: (n = 1) => this.step(n),
      stats: () => this.snapshot(),
      editScene: (scene) => this.edit(scene),
      setStepper: (kind) => this.setStepper(kind),
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
