// A player: one scene running in its own engine worker, drawn into one canvas, with the
// browser API (docs/FORMATS.md). The playground page and every <wind-field> element each own one,
// and use it through its methods only: its view, its engine and its state are its own.

import { Engine } from './engine/client.js';
import { removedError } from './engine/removed.js';
import { FramePace } from './player/frame-pace.js';
import { describeRenderer, LIGHT, lightenedWords, SLOW_FPS, userChoices } from './player/machine.js';
import { budgetWords, memoryBudget } from './player/memory.js';
import { formatsGaveUp, passPrecision } from './views/precision.js';
import { atLeast, boolean, nonFinite, number, oneOf, shown, wholeNumber } from './player/arguments.js';
import { MAX_IMAGE_SIDE } from './generated/contract.js';
import { exportBlob, flipbookRequest, stillRequest, volumeRequest } from './player/exports.js';
import { recordWebM } from './player/recorder.js';
import { ResolutionGovernor, startScale } from './player/resolution.js';
import { EXACT_QUALITY, exactFrameRequest } from './views/exact/exact-frame.js';
import { moved } from './views/guides-layer.js';
import { waitForGpu } from './views/gpu-sync.js';
import { PointerStir } from './views/pointer-stir.js';
import { SceneView } from './views/scene-view.js';
import { VIEWS } from './views/modes.js';
import { GpuStepper, gpuStepperRefuses, gpuStepperUnsupported, MAX_GPU_LATTICE } from './stepper/gpu-stepper.js';
import { SLICE_PLANES, SLICE_SAMPLES } from './views/wind-slice-layer.js';
import { VOLUME_QUALITY } from './views/volume/volume-layer.js';

/** The qualities of the marched views (the exact march's `EXACT_QUALITY`, the volume's `VOLUME_QUALITY`). */
export const QUALITIES = Object.keys(EXACT_QUALITY);
/** The wind slice's planes (`slicePlane`): 'off', 'xy', 'xz', 'yz'. */
export { SLICE_PLANES };
/** A scene that has run this many steps without the engine failing is one to go back to. */
const GOOD_AFTER_STEPS = 120;
/**
 * Most fixed steps taken in one animation frame: by the GPU stepper (each is a pass over every
 * blob on the GPU, drawn with the frame), and by the worker, which steps while the frame is
 * drawn and may catch up a slow frame's worth of simulated time.
 */
const MAX_GPU_STEPS_PER_FRAME = 4;
const MAX_WORKER_STEPS_PER_FRAME = 30;
/** Longest time (s) one frame may account for: a slower frame lets the simulation fall behind. */
const MAX_FRAME_SECONDS = 0.5;
/** The settings a player starts with on a machine that draws the full version. */
/** Why 'auto' steps in the worker on a browser that draws 3-D in software. */
const SOFTWARE_STEPPER = 'this browser draws 3-D in software: the worker steps the gas faster than its GPU passes';
const FULL = Object.freeze({ view: 'raymarch', quality: 'standard', resolution: 'auto', stepper: 'auto', blobCap: null });

/** How long (ms) a lost GPU context may stay lost before the player reports it. */
const CONTEXT_GRACE_MS = 3000;

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

/** What a load or an edit may not do while a video is recorded. */
const recordingRefuses = (what) => new Error(`a recording is under way: ${what} once it has ended`);

/** Whether `scene` must be stepped in the worker: it splits blobs or plays a shape in reverse. */
function sceneKeepsGpuAway(scene) {
  if ((scene.gas?.split_sigma ?? null) !== null) return 'the scene splits blobs (gas.split_sigma)';
  if (scene.shapes?.some((s) => (s.reverse_from ?? null) !== null)) return 'the scene plays a shape in reverse';
  return gpuStepperRefuses(scene);
}

/** Bytes that crossed from the worker for GPU steps `steps` (whole buffers). */
function crossedBytes(steps) {
  return ['births', 'birthSlots', 'freed', 'ranges', 'wind', 'windOffsets', 'solidGrid', 'spheres'].reduce((n, k) => n + steps[k].byteLength, 0);
}

function bytesToDataUrl(bytes) {
  let binary = '';
  for (let i = 0; i < bytes.length; i += 0x8000) binary += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return `data:image/png;base64,${btoa(binary)}`;
}

export class Player {
  /** The 3-D view (three.js) the player draws into its canvas. */
  #view;
  /** The engine worker's handle. */
  #engine;
  /** What the player shows and how: the scene, playing, the view's mode and quality, the speed, visibility. */
  #state;
  /** The current scene as the core normalised it (JSON text): `#state.scene` parsed once from it. */
  #sceneJson = null;
  /** Dragging over the view stirs the gas while it is enabled (`setStirring`). */
  #stirrer;
  /**
   * What steps the gas: the choice (`setStepper`: 'auto', 'cpu' or 'gpu'), what steps it now
   * ('cpu': the worker's core; 'gpu': `stepper/gpu-stepper.js`), why the GPU does not when the
   * choice allows it (or null), the GPU stepper once made, and the field version its lattice is.
   */
  #stepper = { choice: 'auto', active: 'cpu', reason: null, gpu: null, fieldVersion: -1 };
  /** Calls waiting for their turn in `exclusive`: the loop starts no frame while there are any. */
  #waiting = 0;
  /**
   * Where each of `FULL`'s settings comes from: 'full' (the full version's), 'light' (the lighter
   * version's, `player/machine.js`) or 'chosen' (by the page, the user or a script; never lightened).
   */
  #from = { view: 'full', quality: 'full', resolution: 'full', stepper: 'full', blobCap: 'full' };
  /** The machine that draws: {renderer, software} (`describeRenderer`). */
  #machine;
  /** Why the lighter version is shown ('software': WebGL drawn on the CPU; 'slow': measured so), or null. */
  #lighter = null;
  /** The user's own settings this player started with (`player/machine.js`, `userChoices`). */
  #choices = {};
  /** The memory budget of a small device (`player/memory.js`), or null where none applies. */
  #memory = null;
  /** The scene (its JSON text) whose memory cap was last told of, so it is told once. */
  #memoryTold = null;
  /** Calls waiting their turn in `exclusive`, woken at once when the player ends. */
  #sleepers = new Set();
  /** Loads asked for and not yet ended (`#loadTurn`). */
  #loads = 0;
  /** Resolves once the latest load's request has gone to the engine (or it ended without one). */
  #loadSent = Promise.resolve();
  /**
   * Whether a recording has been asked for and not yet ended: steps, loads and edits asked for
   * meanwhile are refused. (`recording`, set once its budget is checked, spans part of it.)
   */
  #recordingAsked = false;

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
    this.hooks = hooks;
    this.#state = {
      scene: null, playing: hooks.playing ?? true, mode: FULL.view, quality: FULL.quality, speed: 1, visible: true,
      pageVisible: document.visibilityState !== 'hidden', blobCap: FULL.blobCap,
    };
    this.stats = {
      blobs: 0, time: 0, fieldMs: 0, stepMs: 0, packMs: 0, frameBytes: 0, frameMs: 0, fps: 0, scale: 1,
      frames: 0, limitedBy: 'paused', sceneBlobCap: null,
    };
    /**
     * Holds the frame rate by scaling the canvas's internal resolution and the real-time
     * view's voxels (`stats().scale`), starting lower on phone-sized screens.
     */
    this.resolution = new ResolutionGovernor({ start: startScale(window.innerWidth, window.innerHeight) });
    /** The frame rate, what limits it, and the pace the resolution follows (`stats().fps`, `limitedBy`). */
    this.pace = new FramePace(this.stats, this.resolution);
    this.busy = false;
    this.lastFrame = null;
    /** The step asked for ahead while playing (a promise of its frame), or null. */
    this.ahead = null;
    /** The showing of that step under way (`#settle`), or null. */
    this.settling = null;
    this.accumulated = 0;
    this.#view = new SceneView(canvas);
    this.#view.volume.profile = Boolean(hooks.profile);
    this.#machine = describeRenderer(this.#view.renderer.getContext());
    this.#memory = memoryBudget(navigator.deviceMemory, this.#view.formats);
    this.#view.volume.memoryBytes = this.#memory?.volumeBytes ?? Infinity;
    const choices = hooks.choices ?? userChoices();
    this.#choices = choices;
    for (const name of Object.keys(FULL)) if (Object.hasOwn(choices, name)) this.#choose(name, choices[name]);
    if (hooks.adapt !== false && !choices.full && this.#machine.software) this.#lighten('software');
    /** Stops stepping and drawing while the page is hidden (another tab, a minimised window). */
    this.onVisibility = () => { this.#state.pageVisible = document.visibilityState !== 'hidden'; };
    document.addEventListener('visibilitychange', this.onVisibility);
    /** Failures of the engine per scene (its normalised JSON text), and the last scene that ran well (its text). */
    this.failures = new Map();
    this.lastGood = null;
    /** Steps taken since the current scene was loaded (it is good after `GOOD_AFTER_STEPS`). */
    this.stepsSinceLoad = 0;
    /** Why the player stopped (the engine keeps failing on its scene), or null. */
    this.halted = null;
    /** Whether a recording is under way (scenes may not change meanwhile). */
    this.recording = false;
    this.#engine = new Engine({
      onError: (m) => hooks.onMessage?.(m),
      onRestart: (reason, how) => this.#recover(reason, how),
    }, { timeoutMs: hooks.requestTimeoutMs });
    /** Whether the view's GPU context is lost (drawing waits for it to come back). */
    this.contextLost = false;
    this.contextTimer = 0;
    this.#view.onContextLost = () => {
      this.contextLost = true;
      // The GPU's state goes with the context: let go of its objects now (deleting them is a
      // no-op while lost), and the worker runs the gas again to where it was (its edits and
      // stirs at the steps they came at) and steps it from now on; a new GPU stepper takes it
      // back after the restore.
      this.#stepper.gpu?.dispose();
      this.#stepper.gpu = null;
      if (this.#stepper.active === 'gpu') {
        this.hooks.onMessage?.('The view lost its GPU context: the worker steps the gas until it is back.');
        this.exclusive(() => this.#restep()).catch((e) => this.hooks.onMessage?.(e.message));
      }
      clearTimeout(this.contextTimer);
      this.contextTimer = setTimeout(() => this.#fault('the view lost its GPU context and the browser did not give it back (too many 3-D views open at once, or the GPU was reset)'), CONTEXT_GRACE_MS);
    };
    this.#view.onContextRestored = () => {
      clearTimeout(this.contextTimer);
      this.contextLost = false;
      if (this.lastFrame) this.#view.setFrame(this.lastFrame);
      this.invalidate();
      // The worker holds the gas since the loss: the GPU takes it back where it can.
      this.exclusive(async () => {
        await this.#engage();
        if (this.#stepper.active === 'gpu') await this.advance(0);
      }).catch((e) => this.hooks.onMessage?.(e.message));
    };
    this.lastTime = performance.now();
    /** When the last frame's work began (rAF ms), and the most frames a second to draw (`setMaxFps`). */
    this.lastStart = -Infinity;
    this.maxFps = Infinity;
    /** Whether something changed the picture since the last frame (the camera moved, …). */
    this.dirty = true;
    this.#view.controls.addEventListener('change', () => { this.dirty = true; });
    /** Dragging stirs the gas instead of orbiting while stirring is on (off at first). */
    this.#stirrer = new PointerStir(this.#view, (position, displacement, radius) => {
      if (this.#state.scene) this.stir(position, displacement, radius).catch(() => {});
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
  #recover(reason, { recycled = false } = {}) {
    const json = this.#sceneJson;
    if (!json) return;
    // Exclusive, so that steps asked for meanwhile wait for the reloaded scene.
    const reload = (text) => this.#loadTurn(text).catch((e) => this.hooks.onMessage?.(e.message));
    if (recycled) {
      // The engine was restarted to give back memory, not because this scene failed.
      this.hooks.onMessage?.(`The engine was restarted to give back memory (${reason}); the scene starts again.`);
      reload(json);
      return;
    }
    const failures = (this.failures.get(json) ?? 0) + 1;
    this.failures.set(json, failures);
    if (failures === 1) {
      reload(json);
    } else if (this.lastGood && this.lastGood !== json) {
      this.hooks.onMessage?.(`This scene stopped the engine twice (${reason}); back to the last scene that ran.`);
      reload(this.lastGood);
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
    if (this.#recordingAsked) throw recordingRefuses('load the scene');
    const text = sceneText(scene);
    return this.#loadTurn(text);
  }

  /**
   * Loads `text` in its turn (`exclusive`). While another load is in the engine (holding the
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
      if (!previous) return await this.exclusive(() => this.#load(text, sent));
      await previous;
      const info = this.#requestLoad(text);
      sent();
      info.catch(() => {});
      return await this.exclusive(async () => this.#adoptLoad(await info));
    } finally {
      sent();
      this.#loads -= 1;
    }
  }

  /** Sends the load of `text` to the engine; resolves with its result. */
  #requestLoad(text) {
    return this.#engine.request('load', { scene: text, blobCap: this.#blobCap() }, {
      onProgress: (p) => this.hooks.onProgress?.(p.progress, `Generating field: ${p.stage}`),
    });
  }

  /**
   * Loads the scene JSON `text`: the engine validates it and hands back the scene normalised
   * (JSON text), which is parsed here once. Resolves with the scene.
   */
  async #load(text, sent = () => {}) {
    if (this.recording) throw recordingRefuses('load the scene');
    await this.#settle();
    const request = this.#requestLoad(text);
    sent();
    return this.#adoptLoad(await request);
  }

  /** Takes a load's result from the engine (`info`) as the running scene; resolves with it. */
  async #adoptLoad(info) {
    if (this.recording) throw recordingRefuses('load the scene');
    this.hooks.onProgress?.(1, 'done');
    this.halted = null;
    this.stepsSinceLoad = 0;
    this.stats.sceneBlobCap = info.blobCap;
    const scene = this.#adopt(info.sceneJson);
    this.#tellMemoryCap();
    this.stats.fieldMs = info.fieldMs;
    this.#view.setCamera(scene.render.camera, scene.render.objects);
    this.#view.setRenderSettings(scene.render);
    this.resize();
    this.accumulated = 0;
    // A new simulation: its centres are in the worker until the GPU takes them.
    this.#stepper.active = 'cpu';
    await this.#engage();
    await this.advance(0);
    await this.hooks.onScene?.(scene);
    return scene;
  }

  /**
   * The blob cap the engine runs the scene under: the chosen or the lighter version's
   * (`setBlobCap`), within the memory budget's; null for none.
   */
  #blobCap() {
    const caps = [this.#state.blobCap, this.#memory?.blobCap].filter((c) => Number.isInteger(c));
    return caps.length > 0 ? Math.min(...caps) : null;
  }

  /** Whether the running scene is held to fewer blobs by the memory budget. */
  #memoryCapped() {
    return this.#memory !== null && this.stats.sceneBlobCap === this.#memory.blobCap;
  }

  /** Tells the page, once a scene, that the memory budget holds the scene to fewer blobs. */
  #tellMemoryCap() {
    if (!this.#memoryCapped() || this.#memoryTold === this.#sceneJson) return;
    this.#memoryTold = this.#sceneJson;
    const notice = this.hooks.onNotice ?? this.hooks.onMessage;
    notice?.(`This device has little memory for 3-D: the scene runs with at most ${this.#memory.blobCap.toLocaleString('en')} blobs `
      + `(fewer, heavier blobs of the same gas), within ${budgetWords(this.#memory)}.`);
  }

  /**
   * What this device gave up against a full one, one phrase each (`stats().gaveUp`): the float
   * formats its GPU lacks (`views/precision.js`), and what the memory budget and the largest
   * texture held back.
   */
  #deviceGaveUp() {
    const formats = this.#view.formats;
    const out = formatsGaveUp(formats);
    const grid = ({ voxels, of }) => `the real-time view's grid of ${voxels.toLocaleString('en')} voxels instead of ${of.toLocaleString('en')}`;
    if (this.#memoryCapped()) out.push(`${budgetWords(this.#memory)}: at most ${this.#memory.blobCap.toLocaleString('en')} blobs`);
    const shrunk = this.#view.volume.grid ? this.#view.volume.shrunk : {};
    if (shrunk.memory) out.push(`${budgetWords(this.#memory)}: ${grid(shrunk.memory)}`);
    if (shrunk.textureSize) out.push(`textures of at most ${formats.maxTextureSize} texels a side: ${grid(shrunk.textureSize)}`);
    return out;
  }

  /** Takes the normalised scene `json` as the current scene; returns it parsed. */
  #adopt(json) {
    const scene = JSON.parse(json);
    this.#state.scene = scene;
    this.#sceneJson = json;
    return scene;
  }

  /**
   * Applies an edited scene to the running simulation: it keeps its blobs and its time
   * (a change of the field's settings is synthesised while the gas goes on); rejects with a
   * clear Error and keeps the scene as it was. Resolves with the scene as the core normalised it.
   */
  async edit(scene) {
    if (this.#recordingAsked) throw recordingRefuses('change the scene');
    const text = sceneText(scene);
    return this.exclusive(() => this.#edit(text));
  }

  /** Applies the scene JSON `text` to the running simulation (see `edit`). */
  async #edit(text) {
    if (this.recording) throw recordingRefuses('change the scene');
    await this.#settle();
    // A scene the GPU cannot step comes back to the worker before the edit (and so does the gas
    // when the stepper's choice changed to the worker).
    const scene = JSON.parse(text);
    if (this.#stepper.active === 'gpu' && (sceneKeepsGpuAway(scene) || this.#stepper.choice === 'cpu')) await this.#toCpu();
    const info = await this.#engine.request('edit', { scene: text, blobCap: this.#blobCap() }, {
      onProgress: (p) => this.hooks.onProgress?.(p.progress, `Generating the new field: ${p.stage}`),
    });
    this.stats.sceneBlobCap = info.blobCap;
    const camera = this.#state.scene?.render.camera;
    const next = this.#adopt(info.sceneJson);
    this.#tellMemoryCap();
    const { render } = next;
    if (info.restarted || !sameCamera(camera, render.camera)) this.#view.setCamera(render.camera, render.objects);
    else this.#view.limits.set(render.camera, render.objects);
    this.#view.setRenderSettings(render);
    if (info.restarted) {
      this.accumulated = 0;
      this.#stepper.active = 'cpu';
    }
    await this.#engage();
    await this.advance(0);
    await this.hooks.onScene?.(next);
    return next;
  }

  /** Restarts the scene at t = 0. */
  reset() {
    return this.exclusive(async () => {
      const t0 = performance.now();
      this.accumulated = 0;
      await this.#show(await this.#engine.request('reset'), 0, t0);
      this.#stepper.active = 'cpu';
      await this.#engage();
      if (this.#stepper.active === 'gpu') await this.advance(0);
    });
  }

  /**
   * Stirs the gas: the pointer moved by `displacement` (m) to `position` (m); the next steps move
   * the gas near it as far, falling off as exp(−distance/`radius`) (m).
   */
  stir(position, displacement, radius) {
    return this.#engine.request('stir', { position, displacement, radius });
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

  async advance(steps) {
    const t0 = performance.now();
    await this.#settle();
    await this.#show(await this.#ask(steps), steps, t0);
  }

  /** Asks for `steps` steps of whoever steps the gas: the worker's frame, or the GPU's steps. */
  #ask(steps) {
    return this.#engine.request(this.#stepper.active === 'gpu' ? 'gpuAdvance' : 'advance', { steps });
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
    const more = left > 0 ? this.#ask(left) : null;
    // Both results count: a worker's frame is the whole state (the last one will do), but steps
    // for the GPU are what changed, and the GPU takes each of them in turn.
    const results = await Promise.all([ahead, more].filter(Boolean));
    this.pace.waitedFor(performance.now() - t0);
    if (this.#state.playing) this.ahead = this.#ask(1);
    for (const earlier of results.slice(0, -1)) if (earlier.gpu) await this.#gpuSteps(earlier);
    await this.#show(results.at(-1), steps, t0);
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

  /**
   * Takes `result` (after `steps` steps: the worker's frame, or steps for the GPU, which it
   * then takes) as the current frame and draws it; `t0` when it was asked for.
   */
  async #show(result, steps, t0) {
    let frame = result;
    if (result.gpu) {
      // Steps the GPU was to take after its copy of the gas was lost: the worker's run again
      // (`#restep`) has them already.
      if (this.#stepper.active !== 'gpu') return;
      await this.#gpuSteps(result);
      if (!this.#stepper.gpu) return;
      frame = { ...this.#gpuFrame(), stepMs: result.stepMs, packMs: 0, crossed: crossedBytes(result) };
    }
    this.lastFrame = frame;
    this.#view.setFrame(frame);
    // A GPU frame holds the blobs the GPU sorted (`count`); `live` is the core's count of them.
    this.stats.blobs = frame.live ?? frame.count;
    this.stats.time = frame.time;
    if (steps > 0) this.stats.stepMs = frame.stepMs;
    this.stepsSinceLoad += steps;
    if (this.stepsSinceLoad >= GOOD_AFTER_STEPS && this.#sceneJson) this.lastGood = this.#sceneJson;
    this.stats.packMs = frame.packMs;
    this.stats.frameBytes = frame.crossed ?? frame.blobs.byteLength + frame.info.byteLength + frame.spheres.byteLength;
    await this.draw();
    this.stats.frameMs = performance.now() - t0;
    this.hooks.onFrame?.(frame);
  }

  /** The blob list of the current state for the current view (docs/FORMATS.md, the blob list); the GPU's centres read back first. */
  async exportBlobs({ width, height } = this.#view.size()) {
    wholeNumber('exportBlobs: width', width, 1, MAX_IMAGE_SIDE);
    wholeNumber('exportBlobs: height', height, 1, MAX_IMAGE_SIDE);
    await this.#syncCentres();
    return this.#engine.request('blobList', { camera: this.#view.cameraSettings(), image: { width, height } });
  }

  async draw(size = this.#view.size()) {
    if (!this.running || !this.lastFrame || !this.#state.scene || this.contextLost) return;
    this.dirty = false;
    this.#view.setRenderSettings(this.#state.scene.render);
    this.#view.guides.update(this.#state.scene);
    const square = this.#view.sliceSquare();
    if (square) {
      const data = await this.#engine.request('windSlice', { ...square, n: SLICE_SAMPLES });
      this.#view.windSlice.update(data, square);
    } else {
      this.#view.windSlice.hide();
    }
    if (this.#state.mode === 'exact') {
      // The exact march draws the core's merged list: the GPU's centres go to the worker first.
      await this.#syncCentres();
      const frame = await this.#engine.request('exactFrame', exactFrameRequest(this.#view.viewBasis(), size.width, size.height, this.#state.quality));
      this.#view.exact.update(frame);
    }
    this.#view.render(this.#state.mode, this.#state.quality);
  }

  /** Sizes the canvas's drawing buffer to its box times the resolution scale. */
  resize() {
    if (!this.running) return;
    const c = this.#view.canvas;
    // Every view follows the pace, the points view too: its float sums cost a fragment per
    // sprite pixel, and a million wide sprites at 1920×1080 took 1.2 s a frame on an H200.
    const scale = this.resolution.scale;
    this.stats.scale = scale;
    this.#view.volumeScale = scale;
    const width = Math.max(Math.round(c.clientWidth * scale), 1);
    const height = Math.max(Math.round(c.clientHeight * scale), 1);
    const now = this.#view.size();
    if (now.width !== width || now.height !== height) this.#view.resize(width, height);
    this.draw().catch(() => {});
  }

  /** Redraws at the next animation frame. */
  invalidate() {
    this.dirty = true;
  }

  /**
   * Counts a frame drawn from `start` to `end` (ms); the resolution may follow the pace. A
   * machine whose view keeps up fewer than `SLOW_FPS` frames a second at the lowest resolution
   * gets the lighter version (unless the page turned adapting off).
   */
  #drawn(start, end) {
    const playing = this.#state.playing;
    if (this.pace.drawn(start, end, { playing })) this.resize();
    const r = this.resolution;
    const slow = this.pace.pace > 0 && this.pace.pace < SLOW_FPS && r.mode === 'auto' && r.scale <= r.min;
    if (slow && playing && this.stats.frames >= 15 && this.hooks.adapt !== false && !this.#lighter && !this.#choices.full) this.#lighten('slow');
  }

  /**
   * Most steps the next frame may take: the GPU stepper's few, or as many as the worker takes in
   * about a frame's time (it steps while the frame is drawn), so that a slow view does not slow
   * the simulated time down when the steps are cheap.
   */
  #stepsPerFrame() {
    if (this.#stepper.active === 'gpu') return MAX_GPU_STEPS_PER_FRAME;
    // A frame's time less its wait for the worker: steps that fit in it are free (the worker
    // steps while the frame is drawn), more would make the worker the one that paces the frames.
    const stepMs = Math.max(this.stats.stepMs, 0.1);
    return Math.max(1, Math.min(MAX_WORKER_STEPS_PER_FRAME, Math.floor((0.8 * Math.max(this.pace.freeMs, 1000 / 60)) / stepMs)));
  }

  loop(now) {
    if (!this.running) return;
    const dt = Math.min((now - this.lastTime) / 1000, MAX_FRAME_SECONDS);
    this.lastTime = now;
    // A call waiting for `exclusive` goes first: frames that take longer than the display's
    // interval would otherwise take the turn each time (it waits on a timer, the loop on the
    // next animation frame, which is already due).
    const shown = this.#state.visible && this.#state.pageVisible;
    const live = this.#state.scene && shown && !this.halted && !this.contextLost;
    // Real time passes for the scene while a frame is in flight or not yet due (a frame cap):
    // the next frame's steps catch up with it, as far as a frame may take.
    if (live && this.#state.playing) this.accumulated += dt * this.#state.speed;
    const due = now - this.lastStart >= 1000 / this.maxFps;
    if (live && !this.busy && !this.#waiting && due) {
      let steps = 0;
      if (this.#state.playing) {
        const h = this.#state.scene.simulation.dt;
        const most = this.#stepsPerFrame();
        steps = Math.min(Math.floor(this.accumulated / h), most);
        this.accumulated -= steps * h;
        // Time the steps could not keep up with is let go, not owed.
        this.accumulated = Math.min(this.accumulated, most * h);
      }
      // Paused with a step in flight: show it.
      const work = steps > 0 ? () => this.#play(steps)
        : this.ahead && !this.#state.playing ? () => this.#settle()
          : this.dirty ? () => this.draw() : null;
      this.pace.tick(now);
      if (work) {
        this.busy = true;
        this.lastStart = now;
        const start = performance.now();
        work()
          .then(() => this.#drawn(start, performance.now()))
          .catch((e) => this.hooks.onMessage?.(e.message))
          .finally(() => { this.busy = false; });
      } else {
        this.pace.idle(now);
      }
    }
    requestAnimationFrame((t) => this.loop(t));
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
  async exclusive(fn) {
    this.#waiting += 1;
    try {
      while (this.busy && this.running) await this.#nap();
    } finally {
      this.#waiting -= 1;
    }
    if (!this.running) throw removedError();
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
  offscreen({ mode, quality = this.#state.quality, standIns = false, width, height }, fn) {
    return this.exclusive(async () => {
      const before = { size: this.#view.size(), mode: this.#state.mode, quality: this.#state.quality, guides: this.#view.showGuides, volumeScale: this.#view.volumeScale };
      Object.assign(this.#state, { mode, quality });
      Object.assign(this.#view, { standIns, showGuides: false, volumeScale: 1 });
      try {
        this.#view.resize(width, height);
        return await fn();
      } finally {
        Object.assign(this.#state, { mode: before.mode, quality: before.quality });
        Object.assign(this.#view, { standIns: false, showGuides: before.guides, volumeScale: before.volumeScale });
        this.#view.resize(before.size.width, before.size.height);
      }
    });
  }

  /** Renders the current view offscreen at `width × height`; a PNG data URL. */
  captureGPU({ mode = 'raymarch', width = 640, height = 480, standIns = false, quality = this.#state.quality } = {}) {
    oneOf('captureGPU: mode', mode, VIEWS);
    oneOf('captureGPU: quality', quality, QUALITIES);
    boolean('captureGPU: standIns', standIns);
    const gl = this.#view.renderer.getContext();
    // A lost context answers null: the image budget alone then.
    const most = Math.min(MAX_IMAGE_SIDE, ...(gl.getParameter(gl.MAX_VIEWPORT_DIMS) ?? []));
    wholeNumber('captureGPU: width', width, 1, most);
    wholeNumber('captureGPU: height', height, 1, most);
    return this.offscreen({ mode, quality, standIns, width, height }, async () => {
      await this.draw({ width, height });
      return this.#view.canvas.toDataURL('image/png');
    });
  }

  /**
   * The real-time view's volumes for the current frame at `quality`, as the GPU holds them and
   * as the core's twin computes them on the same grid (`frame::volume`, `frame::light_volume`): {grid, gpu: {density,
   * source, light}, twin: {density, source, light}} (see `VolumeLayer.read`). For tests.
   */
  inspectVolume({ quality = this.#state.quality } = {}) {
    return this.exclusive(async () => {
      const volume = this.#view.volume;
      if (!volume.prepare(this.#view.renderer, quality)) return null;
      const gpu = volume.read(this.#view.renderer);
      const grid = structuredClone(volume.grid);
      const q = VOLUME_QUALITY[quality] ?? VOLUME_QUALITY.standard;
      await this.#syncCentres();
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
    return this.exclusive(async () => {
      const gpu = this.#stepper.active === 'gpu' ? this.#stepper.gpu : null;
      if (!gpu) return null;
      const { words, info } = gpu.readFrame(this.#state.scene.render.medium.albedo);
      return { ...gpu.readSigmaAndMass(), frame: { words, info } };
    });
  }

  /**
   * The median time (ms) of drawing the current state `frames` times in `mode` at `width ×
   * height`, finished on the GPU: each frame from scratch (the real-time view's volumes rebuilt,
   * as after a step), or with `rebuild: false` the volumes kept (as when orbiting a paused scene
   * or between steps). For benchmarks.
   */
  timeFrames({ mode = 'raymarch', width = 640, height = 360, frames = 5, quality = this.#state.quality, rebuild = true } = {}) {
    return this.offscreen({ mode, quality, width, height }, async () => {
      const times = [];
      for (let i = 0; i <= frames; i++) {
        if (rebuild) this.#view.volume.invalidate();
        const t0 = performance.now();
        await this.draw({ width, height });
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
    return this.exclusive(async () => (this.#stepper.active === 'gpu' ? this.#stepper.gpu.timeStep(repeats) : null));
  }

  /**
   * The median time (ms) of sorting the GPU stepper's gas by σ class and packing it for the
   * views, as after each of its steps (`repeats` times, each pass finished on the GPU): {ms,
   * passes: {keys, counts, gather, bounds, pack}}, or null while the worker steps it. For
   * benchmarks.
   */
  timeGpuSort({ repeats = 5 } = {}) {
    const albedo = () => this.#state.scene.render.medium.albedo;
    return this.exclusive(async () => (this.#stepper.active === 'gpu' ? this.#stepper.gpu.timeSort(repeats, albedo()) : null));
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
    await this.#syncCentres();
    const out = await this.#engine.request('reference', { camera: this.#view.cameraSettings(), width, height }, {
      onProgress: (p) => this.hooks.onProgress?.(p.progress, 'Rendering reference still'),
    });
    this.hooks.onProgress?.(1, 'done');
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
    await this.#syncCentres();
    return exportBlob(this.#engine, 'exportStill', { ...request, camera: this.#view.cameraSettings() }, this.hooks.onProgress);
  }

  async exportFlipbook(options = {}) {
    return exportBlob(this.#engine, 'exportFlipbook', flipbookRequest(options, this.#view.cameraSettings()), this.hooks.onProgress);
  }

  async exportVolume(options = {}) {
    const request = volumeRequest(options);
    await this.#syncCentres();
    return exportBlob(this.#engine, 'exportVolume', request, this.hooks.onProgress);
  }

  /** Cancels the exports in flight (they reject with "cancelled: …"); resolves with how many. */
  cancelExport() {
    return this.#engine.request('cancelExport');
  }

  /**
   * A WebM of `frames` consecutive fixed steps (one step a frame, from the current state),
   * drawn at width × height in `mode`, at `fps` frames per second of video.
   */
  async recordWebM({ frames = 60, width = 640, height = 480, fps = 30, mode = this.#state.mode } = {}) {
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
      // One scene, one size: the scene may not change while the video is made.
      this.recording = true;
      try {
        return await this.offscreen({ mode, width, height }, () => recordWebM({
          canvas: this.#view.canvas,
          frames,
          fps,
          renderFrame: (k) => this.advance(k === 0 ? 0 : 1),
          onProgress: (p) => this.hooks.onProgress?.(p < 1 ? p : 1, 'Recording video'),
        }));
      } finally {
        this.recording = false;
      }
    } finally {
      this.#recordingAsked = false;
    }
  }

  /** Whether the wind guides (and the drag handle, and the wind slice) are drawn. */
  get guides() {
    return this.#view.showGuides;
  }

  setGuides(on) {
    this.#view.showGuides = on;
    this.invalidate();
  }

  /** The wind slice's plane ('off', 'xy', 'xz', 'yz') and its offset along the normal (m). */
  get slicePlane() {
    return this.#view.slicePlane;
  }

  set slicePlane(plane) {
    this.#view.slicePlane = plane;
    this.invalidate();
  }

  get sliceOffset() {
    return this.#view.sliceOffset;
  }

  set sliceOffset(d) {
    this.#view.sliceOffset = d;
    this.invalidate();
  }

  /** The wind slice's colour scale while it is drawn: `{plane, maxSpeed}` (m/s), else null. */
  sliceLegend() {
    const slice = this.#view.windSlice;
    return slice.group.visible ? { plane: this.#view.slicePlane, maxSpeed: slice.maxSpeed } : null;
  }

  /** The real-time view's density volume in voxels `[nx, ny, nz]`, when that view is shown. */
  volumeDims() {
    return this.#state.mode === 'raymarch' ? this.#view.volume.grid?.dims ?? null : null;
  }

  /** Fixes the view's resolution (a scale in (0, 1]) or lets it hold the frame rate ('auto'). */
  setResolution(scale) {
    if (scale !== 'auto' && !(Number.isFinite(Number(scale)) && Number(scale) > 0 && Number(scale) <= 1)) {
      throw new Error(`setResolution: the resolution must be 'auto' or a scale in (0, 1] (got ${scale})`);
    }
    this.#choose('resolution', scale);
  }

  /** The resolution's setting: 'auto' or a fixed scale. */
  get resolutionSetting() {
    return this.resolution.mode === 'auto' ? 'auto' : this.resolution.scale;
  }

  /**
   * Runs the scene with at most `cap` live blobs (the lighter version of a heavier scene,
   * `engine/lighten.js`), or as it is (`null`); the running gas keeps going under the new cap.
   */
  setBlobCap(cap) {
    if (cap !== null && !(Number.isInteger(cap) && cap >= 1)) throw new Error(`setBlobCap: the cap must be a whole number of at least 1, or null (got ${cap})`);
    this.#choose('blobCap', cap);
    return this.#recap();
  }

  /** The blob cap the scene runs under (null: its own `gas.max_blobs`). */
  get blobCap() {
    return this.#state.blobCap;
  }

  /** Sets `name` (one of FULL's settings) to `value` as chosen: the lighter version leaves it alone. */
  #choose(name, value) {
    this.#from[name] = 'chosen';
    this.#apply(name, value);
  }

  /** Applies `value` to the setting `name` (one of FULL's), whoever chose it. */
  #apply(name, value) {
    if (name === 'view') {
      this.#state.mode = value;
      this.resize();
    } else if (name === 'quality') {
      this.#state.quality = value;
      this.invalidate();
    } else if (name === 'resolution') {
      this.resolution.set(value);
      this.resize();
    } else if (name === 'stepper') {
      this.#stepper.choice = value;
    } else if (name === 'blobCap') {
      this.#state.blobCap = value;
    }
  }

  /**
   * Shows the lighter version (`LIGHT`) for every setting nobody chose, because of `reason`
   * ('software' or 'slow'); a scene running already goes on under the lighter settings.
   */
  #lighten(reason) {
    if (this.#lighter) return;
    this.#lighter = reason;
    for (const [name, value] of Object.entries(LIGHT)) {
      if (this.#from[name] === 'full') {
        this.#from[name] = 'light';
        this.#apply(name, value);
      }
    }
    // After the constructor (the page's handle on this player is set by then).
    const lighter = { reason, gaveUp: this.#gaveUp(), renderer: this.#machine.renderer };
    queueMicrotask(() => this.hooks.onLighter?.(lighter));
    if (this.#state.scene) this.#relight().catch((e) => this.hooks.onMessage?.(e.message));
  }

  /**
   * The full version: every setting the lighter version set goes back to the full version's
   * (the user's own choices stay). Resolves once the scene runs so.
   */
  showFull() {
    this.#choices = { ...this.#choices, full: true };
    for (const [name, from] of Object.entries(this.#from)) {
      if (from === 'light') {
        this.#from[name] = 'full';
        this.#apply(name, FULL[name]);
      }
    }
    this.#lighter = null;
    return this.#state.scene ? this.#relight() : Promise.resolve();
  }

  /** After the lighter version came or went: the stepper and the blob cap as they now are. */
  #relight() {
    return this.exclusive(async () => {
      if (this.#sceneJson) await this.#edit(this.#sceneJson);
    });
  }

  /** The running scene under the blob cap as it now is. */
  #recap() {
    return this.#state.scene ? this.exclusive(() => this.#edit(this.#sceneJson)) : Promise.resolve();
  }

  /** What the lighter version gave up, in words (empty when it is not shown). */
  #gaveUp() {
    return this.#lighter ? lightenedWords(Object.keys(this.#from).filter((name) => this.#from[name] === 'light')) : [];
  }

  /** Picks the wind primitive or emitter (`{list, index}`) the drag handle moves, or none. */
  selectHandle(selection) {
    this.#view.guides.select(selection);
    if (selection) this.#view.showGuides = true;
    this.invalidate();
  }

  /**
   * Calls `fn(selection, item)` when the drag handle has moved its item: `item` is a copy of the
   * scene's wind primitive or emitter with its anchor where the handle was let go (m, to the
   * millimetre; a repulsor's whole path moves with it).
   */
  onHandleMoved(fn) {
    this.#view.guides.onMoved = (selection, to) => {
      const item = this.#state.scene?.[selection.list]?.[selection.index];
      if (item) fn(selection, moved(item, to.map((v) => Math.round(v * 1000) / 1000)));
    };
  }

  /** Orbits or zooms for a key pressed on the view (arrows, + and −); true when it did. */
  orbitKey(event) {
    const handled = this.#view.limits.key(event);
    if (handled) this.invalidate();
    return handled;
  }

  /** `n` fixed steps when no frame is in flight. */
  async step(n = 1) {
    // More steps than the run budget allows are refused by the engine, in the budget's words.
    atLeast('steps:', n, 0);
    if (this.#recordingAsked) throw recordingRefuses('take steps');
    return this.exclusive(() => this.advance(n));
  }

  /** The statistics of `stats()`: the engine's, the view's and how the frames go. */
  snapshot() {
    const st = this.#stepper;
    return {
      ...this.stats,
      stepper: st.active,
      ...(st.reason && { stepperReason: st.reason }),
      renderer: this.#machine.renderer,
      software: this.#machine.software,
      lighter: this.#lighter ? { reason: this.#lighter, gaveUp: this.#gaveUp() } : null,
      precision: passPrecision(this.#view.formats),
      memoryBudget: this.#memory && { bytes: this.#memory.bytes, blobCap: this.#memory.blobCap, volumeBytes: this.#memory.volumeBytes },
      gaveUp: this.#deviceGaveUp(),
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
    await this.#syncCentres();
    return this.#engine.request('health');
  }

  /** The small-scale field at lattice coordinates (x, y, z, t). */
  sample(x, y, z, t) {
    return this.#engine.request('sample', { x, y, z, t });
  }

  /**
   * Chooses what steps the gas: 'cpu' (the worker's core, the reference), 'gpu' (the GPU
   * stepper) or 'auto' (the default). 'gpu' and 'auto' step on the GPU where it can, else in the
   * worker, with `stats().stepperReason` saying why. Resolves with what steps it now ('cpu' or
   * 'gpu'); rejects only for another kind.
   */
  async setStepper(kind) {
    if (!['cpu', 'gpu', 'auto'].includes(kind)) throw new Error(`setStepper: the stepper must be 'cpu', 'gpu' or 'auto' (got ${kind})`);
    return this.exclusive(async () => {
      // Where the GPU cannot step the gas, 'gpu' falls back to the worker as 'auto' does, and
      // `stats().stepperReason` says why.
      this.#choose('stepper', kind);
      await this.#engage();
      await this.advance(0);
      return this.#stepper.active;
    });
  }

  /** Why the GPU cannot step the current scene here, or null when it can. */
  #gpuUnavailable() {
    const scene = this.#state.scene;
    const renderer = this.#view.renderer;
    const lattice = scene && scene.field.amplitude > 0 ? scene.field.size.reduce((a, b) => a * b, 1) : 0;
    return (this.contextLost && 'the view has lost its GPU context')
      || gpuStepperUnsupported(renderer)
      || (scene && sceneKeepsGpuAway(scene))
      || (lattice > MAX_GPU_LATTICE && `the field's lattice has over ${MAX_GPU_LATTICE} points`)
      || null;
  }

  /** Puts the gas where the choice of stepper says: on the GPU where it can be, else in the worker. */
  async #engage() {
    const st = this.#stepper;
    st.reason = st.choice === 'cpu' ? null : this.#gpuUnavailable()
      // Drawn in software, the GPU's passes run on the CPU too, many times slower than the
      // worker's core: 'auto' leaves the gas to the worker there ('gpu' still asks for it).
      ?? (st.choice === 'auto' && this.#machine.software ? SOFTWARE_STEPPER : null);
    const wanted = st.choice !== 'cpu' && !st.reason ? 'gpu' : 'cpu';
    if (wanted === st.active || !this.#state.scene) return;
    if (wanted === 'gpu') await this.#toGpu();
    else await this.#toCpu();
  }

  /** Hands the worker's gas to the GPU stepper. */
  async #toGpu() {
    const st = this.#stepper;
    const start = await this.#engine.request('gpuStart');
    const scene = this.#state.scene;
    const births = scene.emitters.reduce((n, e) => n + (e.enabled ? e.rate : 0), 0) * scene.simulation.dt;
    st.gpu ??= new GpuStepper(this.#view.renderer);
    st.gpu.start({ records: start.records, capacity: scene.gas.max_blobs + Math.ceil(4 * births) + 1024, time: start.time });
    st.gpu.setLattice(start.lattice.data, start.lattice.size, start.lattice.potential);
    st.fieldVersion = start.lattice.version;
    st.active = 'gpu';
  }

  /** Brings the gas back from the GPU stepper to the worker, which steps it from now on. */
  async #toCpu() {
    const st = this.#stepper;
    if (st.active !== 'gpu') return;
    // Without its context the GPU's copy is gone: the worker runs the gas again instead.
    if (!st.gpu) {
      await this.#restep();
      return;
    }
    const centres = st.gpu.readCentres();
    st.active = 'cpu';
    await this.#engine.request('takeCentres', { centres, keepOnGpu: false }, { transfer: [centres.buffer] });
  }

  /** Gives the worker the GPU's centres as they are now (for a still, an export, a check). */
  async #syncCentres() {
    if (this.#stepper.active !== 'gpu') return;
    if (!this.#stepper.gpu) {
      await this.#restep();
      return;
    }
    const centres = this.#stepper.gpu.readCentres();
    await this.#engine.request('takeCentres', { centres, keepOnGpu: true }, { transfer: [centres.buffer] });
  }

  /** The GPU takes the steps the worker took (`steps`), on the field the worker now runs on. */
  async #gpuSteps(steps) {
    const st = this.#stepper;
    // Without a GPU stepper (its context lost) the steps are let go: the restore re-steps.
    if (!st.gpu) return;
    if (steps.fieldVersion !== st.fieldVersion) {
      const lattice = await this.#engine.request('gpuLattice');
      st.gpu.setLattice(lattice.data, lattice.size, lattice.potential);
      st.fieldVersion = lattice.version;
    }
    const { simulation, gas } = this.#state.scene;
    st.gpu.apply(steps, { dt: simulation.dt, diffusion: gas.diffusion, alpha: gas.dissipation, rk2: simulation.integrator === 'rk2' });
  }

  /** The views' frame of the GPU stepper's state. */
  #gpuFrame() {
    return this.#stepper.gpu.frame(this.#state.scene.render.medium.albedo);
  }

  /**
   * The GPU's copy of the gas was lost: the worker runs the scene again to where it was (every
   * edit and stir at the step it came at) and steps it from now on; the GPU takes it back when
   * it can (`#engage`).
   */
  async #restep() {
    const t0 = performance.now();
    this.#stepper.active = 'cpu';
    await this.#show(await this.#engine.request('restep', {}, {
      onProgress: (p) => this.hooks.onProgress?.(p.progress, 'Running the scene again'),
    }), 0, t0);
    this.hooks.onProgress?.(1, 'done');
    await this.#engage();
    if (this.#stepper.active === 'gpu') await this.advance(0);
  }

  /** The current scene as the core normalised it, or null before one is loaded. Shared: change a copy (`api().getScene()`). */
  get scene() {
    return this.#state.scene;
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
    return this.exclusive(async () => {});
  }

  /** What the gas is to be stepped by: 'auto', 'gpu' or 'cpu' (`setStepper`). */
  get stepperChoice() {
    return this.#stepper.choice;
  }

  /** The view shown: one of VIEWS. */
  get mode() {
    return this.#state.mode;
  }

  /** Shows the view `mode` (one of VIEWS); throws for any other. */
  setView(mode) {
    if (!VIEWS.includes(mode)) throw new Error(`setView: the view must be one of ${VIEWS.join(', ')} (got ${mode})`);
    this.#choose('view', mode);
  }

  /** The marched views' quality: one of QUALITIES. */
  get quality() {
    return this.#state.quality;
  }

  /** Draws the marched views at `quality` (one of QUALITIES); throws for any other. */
  setQuality(quality) {
    if (!QUALITIES.includes(quality)) throw new Error(`setQuality: the quality must be one of ${QUALITIES.join(', ')} (got ${quality})`);
    this.#choose('quality', quality);
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
    if (!(fps === Infinity || (Number.isFinite(fps) && fps >= 0.1 && fps <= 240))) {
      throw new Error(`setMaxFps: the frame rate must be between 0.1 and 240 frames a second, or Infinity (got ${fps})`);
    }
    this.maxFps = fps;
  }

  /** Whether the view is on screen: a hidden player neither steps nor draws. */
  setVisible(on) {
    this.#state.visible = Boolean(on);
  }

  /** Whether dragging over the view stirs the gas (instead of orbiting). */
  get stirring() {
    return this.#stirrer.enabled;
  }

  setStirring(on) {
    this.#stirrer.enabled = Boolean(on);
  }

  /** The methods of the browser API (docs/FORMATS.md), bound to this player. */
  api(ready) {
    return {
      ready,
      getScene: () => structuredClone(this.#state.scene),
      setScene: (scene) => this.load(scene),
      pause: () => this.pause(),
      setView: (mode) => this.setView(mode),
      play: () => this.setPlaying(true),
      step: (n = 1) => this.step(n),
      stats: () => this.snapshot(),
      editScene: (scene) => this.edit(scene),
      setStepper: (kind) => this.setStepper(kind),
      exportBlobs: (size) => this.exportBlobs(size),
      captureGPU: (options) => this.captureGPU(options),
      renderReference: (options) => this.renderReference(options),
      exportStill: (options) => this.exportStill(options),
      exportFlipbook: (options) => this.exportFlipbook(options),
      exportVolume: (options) => this.exportVolume(options),
      cancelExport: () => this.cancelExport(),
      recordWebM: (options) => this.recordWebM(options),
      inspectVolume: (options) => this.inspectVolume(options),
      inspectStepper: () => this.inspectStepper(),
      timeFrames: (options) => this.timeFrames(options),
      timeGpuSort: (options) => this.timeGpuSort(options),
      timeGpuStep: (options) => this.timeGpuStep(options),
    };
  }

  /**
   * Ends the player: every call in flight or waiting rejects with an AbortError ("the player was
   * removed from the page"), the worker ends, and the GPU's objects and context are let go.
   */
  dispose() {
    if (!this.running) return;
    this.running = false;
    clearTimeout(this.contextTimer);
    document.removeEventListener('visibilitychange', this.onVisibility);
    this.#stirrer.enabled = false;
    this.#engine.terminate(removedError());
    for (const wake of [...this.#sleepers]) wake();
    // The GPU's objects go in a task of their own: the callers hear of the end first (letting
    // go of a context may wait for the GPU to finish what it was drawing).
    setTimeout(() => {
      this.#stepper.gpu?.dispose();
      this.#stepper.gpu = null;
      this.#view.dispose();
    });
  }
}
