// A player: one scene running in its own engine worker, drawn into one canvas, with the
// browser API (docs/FORMATS.md). The playground page and every <wind-field> element each own one,
// and use it through its methods only: its view, its engine and its state are its own.
//
// The Player keeps the scene (loads in their turn, edits, restarts) and the frame loop (the
// steps a frame takes, the step asked for ahead, drawing); the modules beside it hold its other
// jobs: `recovery.js` (the engine's failures, a lost GPU context), `stepper-handoff.js` (the
// gas between the worker and the GPU stepper), `captures.js` (stills, exports, the WebM, the
// looks inside for tests and benchmarks), `view-settings.js` (the view, quality, resolution and
// what is drawn over the gas), `lighter.js` (the lighter version, and where each setting came
// from), `memory.js` (a small device's budget) and `api.js` (the browser API's table).

import { Engine } from '../engine/client.js';
import { removedError } from '../engine/removed.js';
import { exactFrameRequest } from '../views/exact/exact-frame.js';
import { PointerStir } from '../views/pointer-stir.js';
import { passPrecision } from '../views/precision.js';
import { SceneView } from '../views/scene-view.js';
import { SLICE_SAMPLES } from '../views/wind-slice-layer.js';
import { browserApi } from './api.js';
import { atLeast, nonFinite, shown } from './arguments.js';
import { Captures } from './captures.js';
import { hasFlow } from './flow-placement.js';
import { FramePace } from './frame-pace.js';
import { LighterVersion } from './lighter.js';
import { describeRenderer, userChoices } from './machine.js';
import { MemoryLimit } from './memory.js';
import { Recovery } from './recovery.js';
import { StepperHandoff } from './stepper-handoff.js';
import { checkQuality, checkResolution, checkView, ViewSettings } from './view-settings.js';

export { QUALITIES, SLICE_PLANES } from './view-settings.js';

/**
 * Most fixed steps taken in one animation frame: by the GPU stepper (each is a pass over every
 * blob on the GPU, drawn with the frame), and by the worker, which steps while the frame is
 * drawn and may catch up a slow frame's worth of simulated time.
 */
const MAX_GPU_STEPS_PER_FRAME = 4;
const MAX_WORKER_STEPS_PER_FRAME = 30;
/** Longest time (s) one frame may account for: a slower frame lets the simulation fall behind. */
const MAX_FRAME_SECONDS = 0.5;

/** A scene as the JSON text the worker takes; a clear Error for what cannot be a scene. */
function sceneText(scene) {
  if (!scene || typeof scene !== 'object' || Array.isArray(scene)) throw new Error('a scene must be an object (a parsed scene JSON)');
  // JSON would write these as null, and the core would then name the wrong fault.
  const bad = nonFinite(scene);
  if (bad) throw new Error(`${bad.path}: must be a finite number (got ${shown(bad.value)})`);
  try {
    return JSON.stringify(scene);
  } catch (err) {
    throw new Error(`the scene cannot be read as JSON (${err instanceof RangeError ? 'it is nested too deeply' : err.message})`);
  }
}

/** Whether two cameras (the blob list's form, docs/FORMATS.md) are the same. */
function sameCamera(a, b) {
  if (!a || !b || a.fov_y_deg !== b.fov_y_deg) return false;
  return ['position', 'target', 'up'].every((k) => a[k].every((v, i) => v === b[k][i]));
}

export class Player {
  /** The page's hooks (see the constructor). */
  #hooks;
  /** The 3-D view (three.js) the player draws into its canvas. */
  #view;
  /** The engine worker's handle. */
  #engine;
  /** What the player shows: the scene, playing, the speed, the blob cap, visibility (its own and the page's). */
  #state;
  /** The current scene as the core normalised it (JSON text): `#state.scene` parsed once from it. */
  #sceneJson = null;
  /** The statistics of `stats()` kept here and by the frame pace. */
  #stats;
  /** The frame rate, what limits it, and the pace the resolution follows (`stats().fps`, `limitedBy`). */
  #pace;
  /** The view, quality, resolution and frame cap, and what is drawn over the gas. */
  #settings;
  /** The lighter version, and where each setting came from. */
  #lighter;
  /** Who steps the gas (the worker or the GPU) and the gas handed between them. */
  #handoff;
  /** The engine's failures and the GPU context's loss. */
  #recovery;
  /** Stills, exports, the WebM, and the looks inside for tests and benchmarks. */
  #captures;
  /** The memory budget of a small device (`memory.js`). */
  #memory;
  /** The machine that draws: {renderer, software} (`describeRenderer`). */
  #machine;
  /** Dragging over the view stirs the gas while it is enabled (`setStirring`). */
  #stirrer;
  /** Calls waiting for their turn in `#exclusive`: the loop starts no frame while there are any. */
  #waiting = 0;
  /** Calls waiting their turn in `#exclusive`, woken at once when the player ends. */
  #sleepers = new Set();
  /** Loads asked for and not yet ended (`#loadTurn`). */
  #loads = 0;
  /** Resolves once the latest load's request has gone to the engine (or it ended without one). */
  #loadSent = Promise.resolve();
  /** Whether a frame (or a call in its turn) is in flight. */
  #busy = false;
  /** The frame shown last (the worker's or the GPU's), or null. */
  #lastFrame = null;
  /** The step asked for ahead while playing (a promise of its frame), or null. */
  #ahead = null;
  /** The showing of that step under way (`#settle`), or null. */
  #settling = null;
  /** Simulated time (s) owed to the scene, taken by the next frames' steps. */
  #accumulated = 0;
  /** When the last animation frame came (rAF ms), and when the last frame's work began. */
  #lastTime;
  #lastStart = -Infinity;
  /** Whether something changed the picture since the last frame (the camera moved, …). */
  #dirty = true;
  /** Whether the player runs (until `dispose`). */
  #running = false;
  /** Stops stepping and drawing while the page is hidden (another tab, a minimised window). */
  #onVisibility;

  /**
   * @param {HTMLCanvasElement} canvas
   * @param {{onProgress?: (p: number, stage: string) => void, onMessage?: (text: string) => void,
   *          onFrame?: (frame: object) => void, onScene?: (scene: object) => void,
   *          onFault?: (message: string) => void, onNotice?: (text: string) => void, requestTimeoutMs?: number,
   *          playing?: boolean, profile?: boolean, adapt?: boolean, choices?: object,
   *          onLighter?: (lighter: {reason: string, gaveUp: string[], renderer: string}) => void}} hooks
   *   (`onFault`: the player cannot go on as it is, e.g. its GPU context was lost for good or its
   *   scene stops the engine; `onNotice`: news that is no fault, e.g. a small device's memory
   *   budget holds the scene to fewer blobs (else `onMessage` hears it); `profile`: time the volume view's passes on the GPU, reported by
   *   `stats().passes`; slower, for benchmarks; `adapt` (true unless false): a machine that draws
   *   in software, or is measured slow, gets the lighter version, and `onLighter` hears of it;
   *   `choices`: the user's own settings, standing over the lighter version (by default this
   *   session's, `userChoices()`))
   */
  constructor(canvas, hooks = {}) {
    this.#hooks = hooks;
    this.#state = {
      scene: null, playing: hooks.playing ?? true, speed: 1, visible: true,
      pageVisible: document.visibilityState !== 'hidden', blobCap: null, flowGrid: 'full',
    };
    this.#stats = {
      blobs: 0, time: 0, fieldMs: 0, stepMs: 0, packMs: 0, frameBytes: 0, frameMs: 0, fps: 0, scale: 1,
      frames: 0, limitedBy: 'paused', sceneBlobCap: null, flowMs: 0,
    };
    this.#view = new SceneView(canvas);
    this.#settings = new ViewSettings(this.#view, { resize: () => this.resize(), invalidate: () => this.#invalidate() });
    this.#pace = new FramePace(this.#stats, this.#settings.resolution);
    this.#view.volume.profile = Boolean(hooks.profile);
    this.#machine = describeRenderer(this.#view.renderer.getContext());
    this.#memory = new MemoryLimit(navigator.deviceMemory, this.#view.formats);
    this.#view.volume.memoryBytes = this.#memory.volumeBytes();
    this.#recovery = new Recovery(hooks, {
      reload: (text) => this.#loadTurn(text),
      sceneJson: () => this.#sceneJson,
    });
    this.#engine = new Engine({
      onError: (m) => hooks.onMessage?.(m),
      onRestart: (reason, how) => this.#recovery.engineRestarted(reason, how),
    }, { timeoutMs: hooks.requestTimeoutMs });
    this.#handoff = new StepperHandoff({
      engine: this.#engine,
      renderer: this.#view.renderer,
      software: this.#machine.software,
      scene: () => this.#state.scene,
      contextLost: () => this.#recovery.contextLost,
      restep: () => this.#restep(),
      flowBytes: this.#memory.flowBytes,
    });
    this.#captures = new Captures({
      engine: this.#engine,
      view: this.#view,
      settings: this.#settings,
      handoff: this.#handoff,
      scene: () => this.#state.scene,
      exclusive: (fn) => this.#exclusive(fn),
      draw: (size) => this.#draw(size),
      advance: (steps) => this.#advance(steps),
      onProgress: (p, stage) => this.#hooks.onProgress?.(p, stage),
    });
    this.#lighter = new LighterVersion({
      machine: this.#machine,
      choices: hooks.choices ?? userChoices(),
      adapt: hooks.adapt !== false,
      apply: (name, value) => this.#apply(name, value),
      onLighter: (lighter) => this.#hooks.onLighter?.(lighter),
      rerun: () => this.#rerun(),
      onMessage: (text) => this.#hooks.onMessage?.(text),
    });
    this.#onVisibility = () => { this.#state.pageVisible = document.visibilityState !== 'hidden'; };
    document.addEventListener('visibilitychange', this.#onVisibility);
    this.#recovery.watchContext(this.#view, {
      lost: () => {
        // The GPU's state goes with the context: let go of its objects now, and the worker
        // runs the gas again to where it was (its edits and stirs at the steps they came at)
        // and steps it from now on; a new GPU stepper takes it back after the restore.
        if (this.#handoff.contextLost()) {
          this.#hooks.onMessage?.('The view lost its GPU context: the worker steps the gas until it is back.');
          this.#exclusive(() => this.#restep()).catch((e) => this.#hooks.onMessage?.(e.message));
        }
      },
      restored: () => {
        if (this.#lastFrame) this.#view.setFrame(this.#lastFrame);
        this.#invalidate();
        // The worker holds the gas since the loss: the GPU takes it back where it can.
        this.#exclusive(async () => {
          await this.#handoff.engage();
          if (this.#handoff.active === 'gpu') await this.#advance(0);
        }).catch((e) => this.#hooks.onMessage?.(e.message));
      },
    });
    this.#lastTime = performance.now();
    this.#view.controls.addEventListener('change', () => { this.#dirty = true; });
    /** Dragging stirs the gas instead of orbiting while stirring is on (off at first). */
    this.#stirrer = new PointerStir(this.#view, (position, displacement, radius) => {
      if (this.#state.scene) this.#stir(position, displacement, radius).catch(() => {});
    });
    this.#running = true;
    this.resize();
    requestAnimationFrame((t) => this.#loop(t));
  }

  // The scene: loads in their turn, edits, restarts.

  /** Loads `scene` (validated by the core); rejects with a clear Error and keeps the old one. */
  async load(scene) {
    this.#captures.refuseIfAsked('load the scene');
    const text = sceneText(scene);
    return this.#loadTurn(text);
  }

  /**
   * Loads `text` in its turn (`#exclusive`). While another load is in the engine (holding the
   * turn, so no frame is in flight), this one is sent at once, after that one's request: the
   * engine then cancels the older (`cancelled: a newer scene was loaded…`, its field synthesis
   * stopped at its next stage), and this one takes its result in its turn.
   */
  async #loadTurn(text) {
    const previous = this.#loads > 0 ? this.#loadSent : null;
    let sent;
    this.#loadSent = new Promise((resolve) => { sent = resolve; });
    this.#loads += 1;
    try {
      if (!previous) return await this.#exclusive(() => this.#load(text, sent));
      await previous;
      const info = this.#requestLoad(text);
      sent();
      info.catch(() => {});
      return await this.#exclusive(async () => this.#adoptLoad(await info));
    } finally {
      sent();
      this.#loads -= 1;
    }
  }

  /** Sends the load of `text` to the engine; resolves with its result. */
  #requestLoad(text) {
    return this.#engine.request('load', { scene: text, ...this.#holds() }, {
      onProgress: (p) => this.#hooks.onProgress?.(p.progress, `Generating field: ${p.stage}`),
    });
  }

  /**
   * Loads the scene JSON `text`: the engine validates it and hands back the scene normalised
   * (JSON text), which is parsed here once. Resolves with the scene.
   */
  async #load(text, sent = () => {}) {
    this.#captures.refuseIfRecording('load the scene');
    await this.#settle();
    const request = this.#requestLoad(text);
    sent();
    return this.#adoptLoad(await request);
  }

  /**
   * What the engine holds a scene to: the blob cap (the memory budget's or the lighter
   * version's) and the flow's grid (the lighter version's coarser one, or the scene's own).
   */
  #holds() {
    return { blobCap: this.#memory.blobCap(this.#state.blobCap), flowGrid: this.#state.flowGrid };
  }

  /** Takes a load's result from the engine (`info`) as the running scene; resolves with it. */
  async #adoptLoad(info) {
    this.#captures.refuseIfRecording('load the scene');
    this.#hooks.onProgress?.(1, 'done');
    this.#recovery.loaded();
    this.#stats.sceneBlobCap = info.blobCap;
    const scene = this.#adopt(info.sceneJson);
    this.#lighter.flowRuns(info.flowCells, scene.flow?.cells);
    this.#tellMemoryCap();
    this.#stats.fieldMs = info.fieldMs;
    this.#view.setCamera(scene.render.camera, scene.render.objects);
    this.#view.setRenderSettings(scene.render);
    this.resize();
    this.#accumulated = 0;
    // A new simulation: its centres are in the worker until the GPU takes them.
    this.#handoff.heldByWorker();
    await this.#handoff.engage();
    await this.#advance(0);
    await this.#hooks.onScene?.(scene);
    return scene;
  }

  /** Tells the page, once a scene, that the memory budget holds the scene to fewer blobs. */
  #tellMemoryCap() {
    const text = this.#memory.notice(this.#sceneJson, this.#stats.sceneBlobCap);
    if (text) (this.#hooks.onNotice ?? this.#hooks.onMessage)?.(text);
  }

  /** Takes the normalised scene `json` as the current scene; returns it parsed. */
  #adopt(json) {
    const scene = JSON.parse(json);
    this.#state.scene = scene;
    this.#sceneJson = json;
    // A scene with a flow shares the view's half of a memory budget with the flow's textures.
    this.#view.volume.memoryBytes = this.#memory.volumeBytes(hasFlow(scene));
    return scene;
  }

  /**
   * Applies an edited scene to the running simulation: it keeps its blobs and its time
   * (a change of the field's settings is synthesised while the gas goes on); rejects with a
   * clear Error and keeps the scene as it was. Resolves with the scene as the core normalised it.
   */
  async edit(scene) {
    this.#captures.refuseIfAsked('change the scene');
    const text = sceneText(scene);
    return this.#exclusive(() => this.#edit(text));
  }

  /** Applies the scene JSON `text` to the running simulation (see `edit`). */
  async #edit(text) {
    this.#captures.refuseIfRecording('change the scene');
    await this.#settle();
    // A scene the GPU cannot step comes back to the worker before the edit (and so does the gas
    // when the stepper's choice changed to the worker).
    await this.#handoff.leaveFor(JSON.parse(text));
    const info = await this.#engine.request('edit', { scene: text, ...this.#holds() }, {
      onProgress: (p) => this.#hooks.onProgress?.(p.progress, `Generating the new field: ${p.stage}`),
    });
    this.#stats.sceneBlobCap = info.blobCap;
    if (info.flowRun !== undefined) await this.#handoff.edited(info.flowRun);
    const camera = this.#state.scene?.render.camera;
    const next = this.#adopt(info.sceneJson);
    this.#lighter.flowRuns(info.flowCells, next.flow?.cells);
    this.#tellMemoryCap();
    const { render } = next;
    if (info.restarted || !sameCamera(camera, render.camera)) this.#view.setCamera(render.camera, render.objects);
    else this.#view.limits.set(render.camera, render.objects);
    this.#view.setRenderSettings(render);
    if (info.restarted) {
      this.#accumulated = 0;
      this.#handoff.heldByWorker();
    }
    await this.#handoff.engage();
    await this.#advance(0);
    await this.#hooks.onScene?.(next);
    return next;
  }

  /** The running scene again under the settings as they now are (its stepper, its blob cap, its flow's grid). */
  #rerun() {
    return this.#state.scene ? this.#exclusive(async () => {
      if (this.#sceneJson) await this.#edit(this.#sceneJson);
    }) : Promise.resolve();
  }

  /** Restarts the scene at t = 0. */
  reset() {
    return this.#exclusive(async () => {
      const t0 = performance.now();
      this.#accumulated = 0;
      await this.#show(await this.#engine.request('reset'), 0, t0);
      this.#handoff.heldByWorker();
      await this.#handoff.engage();
      if (this.#handoff.active === 'gpu') await this.#advance(0);
    });
  }

  /**
   * The GPU's copy of the gas was lost: the worker runs the scene again to where it was (every
   * edit and stir at the step it came at) and steps it from now on; the GPU takes it back when
   * it can (`StepperHandoff.engage`).
   */
  async #restep() {
    const t0 = performance.now();
    this.#handoff.heldByWorker();
    await this.#show(await this.#engine.request('restep', {}, {
      onProgress: (p) => this.#hooks.onProgress?.(p.progress, 'Running the scene again'),
    }), 0, t0);
    this.#hooks.onProgress?.(1, 'done');
    await this.#handoff.engage();
    if (this.#handoff.active === 'gpu') await this.#advance(0);
  }

  /** Loads the scene JSON at `url` (its text goes to the engine as it is). */
  async loadUrl(url) {
    const response = await fetch(url);
    if (!response.ok) throw new Error(`could not load ${url} (${response.status})`);
    const text = await response.text();
    try {
      return await this.#loadTurn(text);
    } catch (err) {
      if (/not valid JSON/.test(err.message)) throw new Error(`${url} is not a scene (JSON expected)`);
      throw err;
    }
  }

  /** The current scene as the core normalised it, or null before one is loaded. Shared: change a copy (`api().getScene()`). */
  get scene() {
    return this.#state.scene;
  }

  // The frame loop: the steps each frame takes, the step asked for ahead, drawing.

  /** `n` fixed steps when no frame is in flight. */
  async step(n = 1) {
    // More steps than the run budget allows are refused by the engine, in the budget's words.
    atLeast('steps:', n, 0);
    this.#captures.refuseIfAsked('take steps');
    return this.#exclusive(() => this.#advance(n));
  }

  /** Takes `steps` steps and shows their frame, the step asked for ahead shown first. */
  async #advance(steps) {
    const t0 = performance.now();
    await this.#settle();
    await this.#show(await this.#ask(steps), steps, t0);
  }

  /** Asks for `steps` steps of whoever steps the gas: the worker's frame, or the GPU's steps. */
  #ask(steps) {
    return this.#engine.request(this.#handoff.active === 'gpu' ? 'gpuAdvance' : 'advance', { steps });
  }

  /**
   * While playing: the frame `steps` ahead, then the next step asked for at once, so the worker
   * steps while this frame is drawn (the worker runs one step ahead of the picture, as a frame
   * in flight; `#settle` shows it before anything else reads or changes the state).
   */
  async #play(steps) {
    const t0 = performance.now();
    // Both requests go out now, in order, before anything else can ask the worker for more.
    const ahead = this.#ahead;
    this.#ahead = null;
    const left = ahead ? steps - 1 : steps;
    const more = left > 0 ? this.#ask(left) : null;
    // Both results count: a worker's frame is the whole state (the last one will do), but steps
    // for the GPU are what changed, and the GPU takes each of them in turn.
    const results = await Promise.all([ahead, more].filter(Boolean));
    this.#pace.waitedFor(performance.now() - t0);
    if (this.#state.playing) this.#ahead = this.#ask(1);
    for (const earlier of results.slice(0, -1)) if (earlier.gpu) await this.#handoff.takeSteps(earlier);
    await this.#show(results.at(-1), steps, t0);
  }

  /**
   * Shows the step asked for ahead, if any, so the picture is the worker's state again. Callers
   * meanwhile wait for the same showing, and go on in the order they called.
   */
  #settle() {
    if (this.#ahead) {
      const ahead = this.#ahead;
      this.#ahead = null;
      this.#settling = ahead.then((frame) => this.#show(frame, 1, performance.now()))
        .finally(() => { this.#settling = null; });
    }
    return this.#settling ?? Promise.resolve();
  }

  /**
   * Takes `result` (after `steps` steps: the worker's frame, or steps for the GPU, which it
   * then takes) as the current frame and draws it; `t0` when it was asked for.
   */
  async #show(result, steps, t0) {
    const frame = await this.#handoff.frameOf(result);
    if (!frame) return;
    this.#lastFrame = frame;
    this.#view.setFrame(frame);
    // A GPU frame holds the blobs the GPU sorted (`count`); `live` is the core's count of them.
    this.#stats.blobs = frame.live ?? frame.count;
    this.#stats.time = frame.time;
    if (steps > 0) this.#stats.stepMs = frame.stepMs;
    this.#recovery.stepped(steps);
    this.#stats.packMs = frame.packMs;
    // The worker's frame times the flow's last step; the GPU's comes from a scene without one.
    this.#stats.flowMs = frame.flowMs ?? 0;
    this.#stats.frameBytes = frame.crossed ?? frame.blobs.byteLength + frame.info.byteLength + frame.spheres.byteLength;
    await this.#draw();
    this.#stats.frameMs = performance.now() - t0;
    this.#hooks.onFrame?.(frame);
  }

  /** Draws the current frame at `size` (the view's drawing size unless given). */
  async #draw(size = this.#view.size()) {
    if (!this.#running || !this.#lastFrame || !this.#state.scene || this.#recovery.contextLost) return;
    this.#dirty = false;
    this.#view.setRenderSettings(this.#state.scene.render);
    this.#view.guides.update(this.#state.scene);
    const square = this.#view.sliceSquare();
    if (square) {
      const data = await this.#engine.request('windSlice', { ...square, n: SLICE_SAMPLES });
      this.#view.windSlice.update(data, square);
    } else {
      this.#view.windSlice.hide();
    }
    const settings = this.#settings;
    if (settings.mode === 'exact') {
      // The exact march draws the core's merged list: the GPU's centres go to the worker first.
      await this.#handoff.syncCentres();
      const frame = await this.#engine.request('exactFrame', exactFrameRequest(this.#view.viewBasis(), size.width, size.height, settings.quality));
      this.#view.exact.update(frame);
    }
    this.#view.render(settings.mode, settings.quality);
  }

  /** Sizes the canvas's drawing buffer to its box times the resolution scale. */
  resize() {
    if (!this.#running) return;
    const c = this.#view.canvas;
    // Every view follows the pace, the points view too: its float sums cost a fragment per
    // sprite pixel, and a million wide sprites at 1920×1080 took 1.2 s a frame on an H200.
    const scale = this.#settings.resolution.scale;
    this.#stats.scale = scale;
    this.#view.volumeScale = scale;
    const width = Math.max(Math.round(c.clientWidth * scale), 1);
    const height = Math.max(Math.round(c.clientHeight * scale), 1);
    const now = this.#view.size();
    if (now.width !== width || now.height !== height) this.#view.resize(width, height);
    this.#draw().catch(() => {});
  }

  /** Redraws at the next animation frame. */
  #invalidate() {
    this.#dirty = true;
  }

  /**
   * Counts a frame drawn from `start` to `end` (ms); the resolution may follow the pace, and a
   * machine whose view keeps up too few frames a second gets the lighter version (`lighter.js`).
   */
  #drawn(start, end) {
    const playing = this.#state.playing;
    if (this.#pace.drawn(start, end, { playing })) this.resize();
    this.#lighter.measured(this.#pace.pace, this.#settings.resolution, this.#stats.frames, playing);
  }

  /**
   * Most steps the next frame may take: the GPU stepper's few, or as many as the worker takes in
   * about a frame's time (it steps while the frame is drawn), so that a slow view does not slow
   * the simulated time down when the steps are cheap.
   */
  #stepsPerFrame() {
    if (this.#handoff.active === 'gpu') return MAX_GPU_STEPS_PER_FRAME;
    // A frame's time less its wait for the worker: steps that fit in it are free (the worker
    // steps while the frame is drawn), more would make the worker the one that paces the frames.
    const stepMs = Math.max(this.#stats.stepMs, 0.1);
    return Math.max(1, Math.min(MAX_WORKER_STEPS_PER_FRAME, Math.floor((0.8 * Math.max(this.#pace.freeMs, 1000 / 60)) / stepMs)));
  }

  #loop(now) {
    if (!this.#running) return;
    const dt = Math.min((now - this.#lastTime) / 1000, MAX_FRAME_SECONDS);
    this.#lastTime = now;
    // A call waiting for `#exclusive` goes first: frames that take longer than the display's
    // interval would otherwise take the turn each time (it waits on a timer, the loop on the
    // next animation frame, which is already due).
    const onScreen = this.#state.visible && this.#state.pageVisible;
    const live = this.#state.scene && onScreen && !this.#recovery.halted && !this.#recovery.contextLost;
    // Real time passes for the scene while a frame is in flight or not yet due (a frame cap):
    // the next frame's steps catch up with it, as far as a frame may take.
    if (live && this.#state.playing) this.#accumulated += dt * this.#state.speed;
    const due = now - this.#lastStart >= 1000 / this.#settings.maxFps;
    if (live && !this.#busy && !this.#waiting && due) {
      let steps = 0;
      if (this.#state.playing) {
        const h = this.#state.scene.simulation.dt;
        const most = this.#stepsPerFrame();
        steps = Math.min(Math.floor(this.#accumulated / h), most);
        this.#accumulated -= steps * h;
        // Time the steps could not keep up with is let go, not owed.
        this.#accumulated = Math.min(this.#accumulated, most * h);
      }
      // Paused with a step in flight: show it.
      const work = steps > 0 ? () => this.#play(steps)
        : this.#ahead && !this.#state.playing ? () => this.#settle()
          : this.#dirty ? () => this.#draw() : null;
      this.#pace.tick(now);
      if (work) {
        this.#busy = true;
        this.#lastStart = now;
        const start = performance.now();
        work()
          .then(() => this.#drawn(start, performance.now()))
          .catch((e) => this.#hooks.onMessage?.(e.message))
          .finally(() => { this.#busy = false; });
      } else {
        this.#pace.idle(now);
      }
    }
    requestAnimationFrame((t) => this.#loop(t));
  }

  /** A wait of 5 ms, cut short when the player ends (`dispose`). */
  #nap() {
    return new Promise((resolve) => {
      const wake = () => {
        clearTimeout(timer);
        this.#sleepers.delete(wake);
        resolve();
      };
      const timer = setTimeout(wake, 5);
      this.#sleepers.add(wake);
    });
  }

  /** Runs `fn` when no frame is in flight, the step asked for ahead shown first. */
  async #exclusive(fn) {
    this.#waiting += 1;
    try {
      while (this.#busy && this.#running) await this.#nap();
    } finally {
      this.#waiting -= 1;
    }
    if (!this.#running) throw removedError();
    this.#busy = true;
    try {
      await this.#settle();
      return await fn();
    } finally {
      this.#busy = false;
    }
  }

  /** Whether the scene plays (steps in real time); `setPlaying` changes it. */
  get playing() {
    return this.#state.playing;
  }

  setPlaying(on) {
    this.#state.playing = Boolean(on);
  }

  /** Stops playing; resolves once the steps already in flight are shown, so `stats()` holds still. */
  pause() {
    this.setPlaying(false);
    return this.#exclusive(async () => {});
  }

  /** Simulated seconds per second while playing. */
  get speed() {
    return this.#state.speed;
  }

  /** Plays at `speed` simulated seconds per second (0 or more); throws for anything else. */
  setSpeed(speed) {
    if (!(Number.isFinite(speed) && speed >= 0)) throw new Error(`setSpeed: the speed must be a number of 0 or more (got ${speed})`);
    this.#state.speed = speed;
  }

  /**
   * Draws at most `fps` frames a second (a number in [0.1, 240], or Infinity: as the display
   * allows); the simulated time keeps up as far as the steps allow. To save power, or to see how
   * the player does on a slow machine.
   */
  setMaxFps(fps) {
    this.#settings.setMaxFps(fps);
  }

  /** Whether the view is on screen: a hidden player neither steps nor draws. */
  setVisible(on) {
    this.#state.visible = Boolean(on);
  }

  // The settings (`view-settings.js`, `lighter.js`) and the stepper's choice.

  /** Sets `name` (one of the lighter version's settings) to `value` as it is, whoever chose it. */
  #apply(name, value) {
    if (name === 'stepper') this.#handoff.choice = value;
    else if (name === 'blobCap') this.#state.blobCap = value;
    else if (name === 'flow') this.#state.flowGrid = value;
    else this.#settings.apply(name, value);
  }

  /** The view shown: one of VIEWS. */
  get mode() {
    return this.#settings.mode;
  }

  /** Shows the view `mode` (one of VIEWS); throws for any other. */
  setView(mode) {
    this.#lighter.choose('view', checkView('setView', mode));
  }

  /** The marched views' quality: one of QUALITIES. */
  get quality() {
    return this.#settings.quality;
  }

  /** Draws the marched views at `quality` (one of QUALITIES); throws for any other. */
  setQuality(quality) {
    this.#lighter.choose('quality', checkQuality('setQuality', quality));
  }

  /** Fixes the view's resolution (a scale in (0, 1]) or lets it hold the frame rate ('auto'). */
  setResolution(scale) {
    this.#lighter.choose('resolution', checkResolution(scale));
  }

  /** The resolution's setting: 'auto' or a fixed scale. */
  get resolutionSetting() {
    return this.#settings.resolutionSetting;
  }

  /**
   * Runs the scene with at most `cap` live blobs (the lighter version of a heavier scene,
   * `engine/lighten.js`), or as it is (`null`); the running gas keeps going under the new cap.
   */
  setBlobCap(cap) {
    if (cap !== null && !(Number.isInteger(cap) && cap >= 1)) throw new Error(`setBlobCap: the cap must be a whole number of at least 1, or null (got ${cap})`);
    this.#lighter.choose('blobCap', cap);
    return this.#rerun();
  }

  /** The blob cap the scene runs under (null: its own `gas.max_blobs`). */
  get blobCap() {
    return this.#state.blobCap;
  }

  /** What the gas is to be stepped by: 'auto', 'gpu' or 'cpu' (`setStepper`). */
  get stepperChoice() {
    return this.#handoff.choice;
  }

  /**
   * Chooses what steps the gas: 'cpu' (the worker's core, the reference), 'gpu' (the GPU
   * stepper) or 'auto' (the default). 'gpu' and 'auto' step on the GPU where it can, else in the
   * worker, with `stats().stepperReason` saying why. Resolves with what steps it now ('cpu' or
   * 'gpu'); rejects only for another kind.
   */
  async setStepper(kind) {
    if (!['cpu', 'gpu', 'auto'].includes(kind)) throw new Error(`setStepper: the stepper must be 'cpu', 'gpu' or 'auto' (got ${kind})`);
    return this.#exclusive(async () => {
      // Where the GPU cannot step the gas, 'gpu' falls back to the worker as 'auto' does, and
      // `stats().stepperReason` says why.
      this.#lighter.choose('stepper', kind);
      await this.#handoff.engage();
      await this.#advance(0);
      return this.#handoff.active;
    });
  }

  /**
   * The full version: every setting the lighter version set goes back to the full version's
   * (the user's own choices stay). Resolves once the scene runs so.
   */
  showFull() {
    return this.#lighter.showFull();
  }

  /** Whether the wind guides (and the drag handle, and the wind slice) are drawn. */
  get guides() {
    return this.#settings.guides;
  }

  setGuides(on) {
    this.#settings.guides = on;
  }

  /** The wind slice's plane ('off', 'xy', 'xz', 'yz') and its offset along the normal (m). */
  get slicePlane() {
    return this.#settings.slicePlane;
  }

  set slicePlane(plane) {
    this.#settings.slicePlane = plane;
  }

  get sliceOffset() {
    return this.#settings.sliceOffset;
  }

  set sliceOffset(d) {
    this.#settings.sliceOffset = d;
  }

  /** The wind slice's colour scale while it is drawn: `{plane, maxSpeed}` (m/s), else null. */
  sliceLegend() {
    return this.#settings.sliceLegend();
  }

  /** The real-time view's density volume in voxels `[nx, ny, nz]`, when that view is shown. */
  volumeDims() {
    return this.#settings.volumeDims();
  }

  /** Picks the wind primitive or emitter (`{list, index}`) the drag handle moves, or none. */
  selectHandle(selection) {
    this.#settings.selectHandle(selection);
  }

  /**
   * Calls `fn(selection, item)` when the drag handle has moved its item: `item` is a copy of the
   * scene's wind primitive or emitter with its anchor where the handle was let go (m, to the
   * millimetre; a repulsor's whole path moves with it).
   */
  onHandleMoved(fn) {
    this.#settings.onHandleMoved(() => this.#state.scene, fn);
  }

  /** Orbits or zooms for a key pressed on the view (arrows, + and −); true when it did. */
  orbitKey(event) {
    return this.#settings.orbitKey(event);
  }

  /** Whether dragging over the view stirs the gas (instead of orbiting). */
  get stirring() {
    return this.#stirrer.enabled;
  }

  setStirring(on) {
    this.#stirrer.enabled = Boolean(on);
  }

  // The engine's own answers.

  /**
   * Stirs the gas: the pointer moved by `displacement` (m) to `position` (m); the next steps move
   * the gas near it as far, falling off as exp(−distance/`radius`) (m).
   */
  #stir(position, displacement, radius) {
    return this.#engine.request('stir', { position, displacement, radius });
  }

  /** The statistics of `stats()`: the engine's, the view's and how the frames go. */
  snapshot() {
    const handoff = this.#handoff;
    return {
      ...this.#stats,
      stepper: handoff.active,
      ...(handoff.reason && { stepperReason: handoff.reason }),
      flowStepper: handoff.flowStepper,
      renderer: this.#machine.renderer,
      software: this.#machine.software,
      lighter: this.#lighter.snapshot(),
      precision: passPrecision(this.#view.formats),
      memoryBudget: this.#memory.snapshot(),
      gaveUp: this.#memory.gaveUp(this.#view, this.#stats.sceneBlobCap),
      ...(this.#view.volume.timings && { passes: { ...this.#view.volume.timings } }),
    };
  }

  /** The field's statistics against `spectrum` (its own when absent), measured in the worker. */
  async fieldStats(spectrum) {
    if (spectrum !== undefined && (spectrum === null || typeof spectrum !== 'object' || Array.isArray(spectrum))) {
      throw new Error(`fieldStats: the spectrum must be an object like a scene's field.spectrum (got ${shown(spectrum)})`);
    }
    const bad = spectrum && nonFinite(spectrum, 'spectrum');
    if (bad) throw new Error(`fieldStats: ${bad.path} must be a finite number (got ${shown(bad.value)})`);
    return this.#engine.request('fieldStats', { spectrum });
  }

  /** The engine's health: its memory, the blob count and blobs whose centre is not finite. */
  async health() {
    await this.#handoff.syncCentres();
    return this.#engine.request('health');
  }

  /** The small-scale field at lattice coordinates (x, y, z, t). */
  sample(x, y, z, t) {
    return this.#engine.request('sample', { x, y, z, t });
  }

  // Captures, exports and looks inside (`captures.js`).

  /** The blob list of the current state for the current view (docs/FORMATS.md, the blob list). */
  exportBlobs(size) {
    return this.#captures.exportBlobs(size);
  }

  /** Renders the current view offscreen (`{mode, width, height, standIns, quality}`); a PNG data URL. */
  captureGPU(options) {
    return this.#captures.captureGPU(options);
  }

  /** The WASM reference still of the current view (`{width, height}`); a PNG data URL. */
  renderReference(options) {
    return this.#captures.renderReference(options);
  }

  /** The WASM reference still of the current view (`{width, height}`): the PNG's bytes. */
  referencePng(options) {
    return this.#captures.referencePng(options);
  }

  /** Exports for pipelines (docs/FORMATS.md, exports): a still, a flipbook, a volume; each a Promise of a Blob. */
  exportStill(options) {
    return this.#captures.exportStill(options);
  }

  exportFlipbook(options) {
    return this.#captures.exportFlipbook(options);
  }

  exportVolume(options) {
    return this.#captures.exportVolume(options);
  }

  /** The flow's grid now ({box, cells, time, velocity, temperature}), or null without a flow. */
  exportFlow() {
    return this.#captures.exportFlow();
  }

  /** Cancels the exports in flight (they reject with "cancelled: …"); resolves with how many. */
  cancelExport() {
    return this.#captures.cancelExport();
  }

  /** A WebM of `frames` consecutive fixed steps (`{frames, width, height, fps, mode}`). */
  recordWebM(options) {
    return this.#captures.recordWebM(options);
  }

  /** The real-time view's volumes, as the GPU holds them and as the core's twin computes them. For tests. */
  inspectVolume(options) {
    return this.#captures.inspectVolume(options);
  }

  /** The GPU stepper's blobs and its frame of them; null while the worker steps the gas. For tests. */
  inspectStepper() {
    return this.#captures.inspectStepper();
  }

  /** The median time (ms) of drawing the current state offscreen. For benchmarks. */
  timeFrames(options) {
    return this.#captures.timeFrames(options);
  }

  /** The median time (ms) of one GPU step, or null while the worker steps the gas. For benchmarks. */
  timeGpuStep(options) {
    return this.#captures.timeGpuStep(options);
  }

  /** The median time (ms) of the GPU stepper's sort and pack, or null while the worker steps the gas. For benchmarks. */
  timeGpuSort(options) {
    return this.#captures.timeGpuSort(options);
  }

  /** The methods of the browser API (docs/FORMATS.md), bound to this player. */
  api(ready) {
    return browserApi(this, ready);
  }

  /**
   * Ends the player: every call in flight or waiting rejects with an AbortError ("the player was
   * removed from the page"), the worker ends, and the GPU's objects and context are let go.
   */
  dispose() {
    if (!this.#running) return;
    this.#running = false;
    this.#recovery.dispose();
    document.removeEventListener('visibilitychange', this.#onVisibility);
    this.#stirrer.enabled = false;
    this.#engine.terminate(removedError());
    for (const wake of [...this.#sleepers]) wake();
    // The GPU's objects go in a task of their own: the callers hear of the end first (letting
    // go of a context may wait for the GPU to finish what it was drawing).
    setTimeout(() => {
      this.#handoff.dispose();
      this.#view.dispose();
    });
  }
}
