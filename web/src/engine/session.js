// The engine's scene over an initialised WASM core: the current field (synthesised in stages
// with progress, shared by scenes of the same field parameters), the running simulation and its
// scene. The request handlers (`handlers.js`) call it; it knows nothing of messages.
//
// A scene arrives as JSON text and is turned from and to JSON once per load: the core validates
// it and returns it normalised (JSON text), the session parses that once (it needs the field's
// amplitude and the shapes) and hands the normalised text on for the page to parse once. Nothing
// re-reads it afterwards: `reset`, edits and a finished synthesis use what was kept.
//
// A field synthesis yields to the event loop between its stages, so requests keep being
// answered meanwhile (on the current scene), and a newer valid `load` or `edit` wanting other
// field parameters supersedes it: the older one then rejects with "cancelled: ...".

import { coarsenFlow, lightenScene, overCap } from './lighten.js';

/** Lets the worker's event loop run (progress posts, newer requests) between synthesis stages. */
const yieldToEvents = () => new Promise((resolve) => setTimeout(resolve));

/**
 * How the first module's refusal of a scene that serde could not read begins (the core's
 * `scene::read::PATH_UNREAD`): it does not track the JSON path, so the full module is asked for it.
 */
const PATH_UNREAD = 'scene (path unread): ';

/**
 * The error of a load or synthesis that a newer one superseded (`superseded`: no refusal of its
 * input; what its synthesis took is freed, for the newer one to reuse).
 */
const cancelled = () => Object.assign(new Error('cancelled: a newer scene was loaded before this one was ready'), { superseded: true });

/** `scene` if it is JSON text (the engine's protocol), else a clear Error. */
function sceneText(scene) {
  if (typeof scene !== 'string') throw new Error('the scene must be sent as JSON text');
  return scene;
}

/** Whether two values parsed from JSON are equal (deep). */
function sameData(a, b) {
  if (a === b) return true;
  if (typeof a !== 'object' || typeof b !== 'object' || a === null || b === null) return false;
  if (Array.isArray(a) !== Array.isArray(b)) return false;
  const keys = Object.keys(a);
  if (keys.length !== Object.keys(b).length) return false;
  return keys.every((k) => Object.hasOwn(b, k) && sameData(a[k], b[k]));
}

export class Session {
  /** The current field, its parameters (JSON, the key of its synthesis) and synthesis time (ms). */
  field = null;
  fieldKey = '';
  fieldMs = 0;
  /** The running simulation, or null before the first load. */
  sim = null;
  /**
   * The field the simulation runs on (a `WindField`, or null), and a count of its changes: the
   * GPU stepper holds a copy of its lattice and asks again when the count moves.
   */
  simField = null;
  fieldVersion = 0;
  /**
   * Its scene: the core's normalised JSON text, that parsed, its field parameters ('' for none),
   * and the JSON text the simulation runs (the lighter version's under a blob cap or on a
   * coarser flow, `lighten.js`).
   */
  current = null;
  /** Most live blobs the simulation may run (`Infinity`: the scene's own `gas.max_blobs`). */
  blobCap = Infinity;
  /** Whether a scene's flow runs on the coarser grid (`coarserCells`, the lighter version's). */
  coarseFlow = false;
  /** Steps the simulation has taken since it started (its load, a restart). */
  steps = 0;
  /**
   * How the running simulation began and what changed it since, so that it can be run again to
   * where it is, exactly (`replay`: the GPU's copy of the gas was lost): the start {run, key},
   * the JSON text and the field's key it started on; then, in order, each at the step it came
   * at, `edit` {run, key (the field it took, or null: the one in use)}, `field` {key} (a new
   * field swapped in) and `stir` {position, velocity, radius, steps} (the pointer's wind over
   * that many steps).
   */
  #start0 = null;
  #history = [];
  /**
   * The field parameters the newest valid `load` or `edit` wants ('' for none): a synthesis in
   * flight for other parameters gives way to it.
   */
  #wantedKey = '';
  /** The newest valid `load` or `edit` request: an older `load` still waiting gives way to it. */
  #latestLoad = 0;
  /** The synthesis in flight: its parameters and its promise, or null. */
  #synthesis = null;
  /** The full module's copy of the current field: {of (the field), promise (of the copy)}, or null. */
  #fullField = null;

  /**
   * @param {object} core the WASM module's exports, initialised
   * @param {(id: number, value: number, stage: string) => void} progress reports a request's progress
   * @param {(() => Promise<object>) | null} full resolves to the core's full module, initialised
   *   (null: `core` is the full module)
   */
  constructor(core, progress, full = null) {
    this.core = core;
    this.progress = progress;
    this.full = full;
  }

  /** The running simulation, or a clear Error before a scene is loaded. */
  requireSim() {
    if (!this.sim) throw new Error('no scene loaded yet');
    return this.sim;
  }

  /** The current field, or a clear Error when the scene has none. */
  requireField() {
    if (!this.field) throw new Error('this scene has no small-scale field');
    return this.field;
  }

  /**
   * The current field as the core's full module holds it (a `WindField` of that module): its
   * lattice and ψ, read now, copied over once per field (`WindField.fromLattice`), never
   * synthesised again. The field itself where `core` is the full module.
   */
  fullField() {
    const field = this.requireField();
    if (!this.full) return Promise.resolve(field);
    if (this.#fullField?.of !== field) {
      this.#dropFullField();
      const key = this.fieldKey;
      const data = field.data();
      const potential = field.potential();
      const promise = this.full().then((full) => full.WindField.fromLattice(key, data, potential));
      const entry = { of: field, promise };
      this.#fullField = entry;
      promise.catch(() => {
        if (this.#fullField === entry) this.#fullField = null;
      });
    }
    return this.#fullField.promise;
  }

  /** Frees the full module's copy of a field that is no longer current. */
  #dropFullField() {
    const entry = this.#fullField;
    this.#fullField = null;
    entry?.promise.then((copy) => copy.free(), () => {});
  }

  /**
   * `text` validated and normalised by the core: {json, scene, key, run}, `run` the JSON text the
   * simulation runs (the scene's own, or its lighter version under the blob cap and with its
   * flow on the coarser grid).
   */
  #read(text) {
    const json = this.core.validateScene(sceneText(text));
    const scene = JSON.parse(json);
    const key = scene.field.amplitude > 0 ? this.core.sceneFieldParams(json) : '';
    const capped = lightenScene(scene, this.blobCap);
    const lighter = this.coarseFlow ? coarsenFlow(capped) : capped;
    const run = lighter === scene ? json : this.core.validateScene(JSON.stringify(lighter));
    return { json, scene, key, run };
  }

  /** Whether the simulation runs a lighter version of its scene (fewer blobs, a coarser flow). */
  get lightened() {
    return Boolean(this.current && this.current.run !== this.current.json);
  }

  /** Notes the field the simulation runs on now. */
  #runsOn(field) {
    if (field !== this.simField) {
      this.simField = field;
      this.fieldVersion += 1;
    }
  }

  /** A new simulation of `next` (from `#read`), on the current field when it has one. */
  #simulationOf({ run, key }) {
    return key ? this.core.SceneSimulation.withField(run, this.field) : new this.core.SceneSimulation(run);
  }

  /**
   * Synthesises the field for `key` unless the current one already matches, reporting progress
   * under request `id`; one synthesis for the same parameters is shared.
   */
  ensureField(id, key) {
    if (this.field && this.fieldKey === key) return Promise.resolve();
    if (this.#synthesis?.key === key) return this.#synthesis.promise;
    const promise = this.#synthesise(id, key).finally(() => {
      if (this.#synthesis?.promise === promise) this.#synthesis = null;
    });
    this.#synthesis = { key, promise };
    return promise;
  }

  async #synthesise(id, key) {
    const wanted = () => {
      if (key !== this.#wantedKey) throw cancelled();
    };
    // A superseded synthesis frees its memory at its next stage: let it, before allocating.
    await yieldToEvents();
    wanted();
    const t0 = performance.now();
    const run = new this.core.FieldSynthesis(key);
    try {
      this.progress(id, 0, run.stage());
      while (run.step()) {
        this.progress(id, run.progress() * 0.95, run.stage());
        await yieldToEvents();
        wanted();
      }
      const next = run.finish();
      this.#dropFullField();
      this.field?.free();
      this.field = next;
      this.fieldKey = key;
      this.fieldMs = performance.now() - t0;
    } finally {
      run.free();
    }
  }

  /**
   * Loads the scene `text` (JSON) from its start, on its field (synthesised under request `id`
   * when it is not the current one). Resolves with {sceneJson (normalised), fieldMs, size}.
   */
  load(id, text) {
    let next;
    try {
      next = this.#read(text);
    } catch (err) {
      return this.#refuse(err, text);
    }
    return this.#start(id, next);
  }

  /**
   * Rejects with `err`, a refusal of the scene `text`, at its JSON path: the first module reads
   * scenes without tracking the path (its refusals name {@link PATH_UNREAD}), so the full module
   * reads a scene the first one refused that way again, for the message that names the path.
   * Without the full module, the first one's message stands, its marker dropped.
   */
  async #refuse(err, text) {
    if (!this.full || !err?.message?.startsWith(PATH_UNREAD)) throw err;
    const unread = new Error(`scene: ${err.message.slice(PATH_UNREAD.length)}`);
    const full = await this.full().catch(() => null);
    if (!full) throw unread;
    full.validateScene(sceneText(text));
    throw unread;
  }

  async #start(id, next) {
    this.#wantedKey = next.key;
    this.#latestLoad = id;
    if (next.key) await this.ensureField(id, next.key);
    if (id !== this.#latestLoad) throw cancelled();
    const sim = this.#simulationOf(next);
    this.sim?.free();
    this.sim = sim;
    this.current = next;
    this.#runsOn(next.key ? this.field : null);
    this.#began(next);
    this.progress(id, 1, 'done');
    return { sceneJson: next.json, fieldMs: this.fieldMs, size: this.field ? Array.from(this.field.size()) : null, ...this.#cap(next) };
  }

  /**
   * Applies the edited scene `text` to the running simulation, keeping its blobs and time. A
   * change of the field's settings synthesises the new field meanwhile (progress under `id`)
   * and swaps it in when ready; the gas keeps moving on the field in use. A change to `shapes`
   * with it restarts the scene (on its own field, so it waits for it). Resolves with
   * {sceneJson, restarted, fieldPending, fieldMs}.
   */
  async edit(id, text) {
    let next;
    try {
      next = this.#read(text);
    } catch (err) {
      return this.#refuse(err, text);
    }
    if (!this.sim) return { ...(await this.#start(id, next)), restarted: true, fieldPending: false };
    const ready = !next.key || (this.field && this.fieldKey === next.key);
    if (!ready && !sameData(next.scene.shapes, this.current.scene.shapes)) {
      return { ...(await this.#start(id, next)), restarted: true, fieldPending: false };
    }
    this.#wantedKey = next.key;
    this.#latestLoad = id;
    const withField = ready && next.key;
    const restarted = withField ? this.sim.editWithField(next.run, this.field) : this.sim.edit(next.run);
    this.current = next;
    if (restarted) this.#began({ run: next.run, key: withField ? next.key : this.#keyInUse() });
    else this.#history.push({ kind: 'edit', step: this.steps, run: next.run, key: withField ? next.key : null });
    if (!next.key) this.#runsOn(null);
    else if (ready) this.#runsOn(this.field);
    if (!ready) {
      this.ensureField(id, next.key).then(() => {
        if (this.sim && this.current.key === next.key) {
          this.sim.setField(this.field);
          this.#runsOn(this.field);
          this.#history.push({ kind: 'field', step: this.steps, key: next.key });
        }
        this.progress(id, 1, 'done');
      }, () => {});
    }
    return { sceneJson: next.json, restarted, fieldPending: !ready, fieldMs: this.fieldMs, ...this.#cap(next) };
  }

  /**
   * What the simulation of `next` runs under: {blobCap (its max_blobs, or null for the scene's
   * own), flowCells (its flow's cells where they are not the scene's, else null)}.
   */
  #cap(next) {
    if (next.run === next.json) return { blobCap: null, flowCells: null };
    const run = JSON.parse(next.run);
    const cells = run.flow?.cells ?? null;
    const coarser = cells && cells.some((n, i) => n !== next.scene.flow.cells[i]);
    return { blobCap: overCap(next.scene, this.blobCap) ? run.gas.max_blobs : null, flowCells: coarser ? cells : null };
  }

  /** Restarts the current scene at t = 0, on its own field (waiting for one being synthesised). */
  async reset(id) {
    this.requireSim();
    const scene = this.current;
    if (scene.key) await this.ensureField(id, scene.key);
    const sim = this.#simulationOf(scene);
    this.sim.free();
    this.sim = sim;
    this.#runsOn(scene.key ? this.field : null);
    this.#began(scene);
  }

  /** The simulation (re)started from `start` ({run, key}) at step 0: its history begins. */
  #began({ run, key }) {
    this.steps = 0;
    this.#start0 = { run, key };
    this.#history = [];
  }

  /** The key of the field the simulation runs on now ('' for none). */
  #keyInUse() {
    return this.simField ? this.fieldKey : '';
  }

  /** The simulation took `n` steps. */
  stepped(n) {
    this.steps += n;
  }

  /** The pointer's wind `stir` ({position, velocity, radius}) acts on the next `steps` steps. */
  stirred(stir, steps) {
    this.#history.push({ kind: 'stir', step: this.steps, steps, ...stir });
  }

  /**
   * Runs the simulation again from its start to the step it is at, with every edit, field and
   * stir at the step it came at: the same state, bit for bit, as stepping it here all along
   * (after the GPU stepped it and lost it). Fields no longer held are synthesised again (under
   * request `id`, with progress); the running simulation is replaced by the replayed one.
   */
  async replay(id) {
    this.requireSim();
    const target = this.steps;
    const made = new Map();
    const fieldOf = async (key) => {
      if (!key) return null;
      if (key === this.fieldKey && this.field) return this.field;
      if (!made.has(key)) {
        const run = new this.core.FieldSynthesis(key);
        try {
          while (run.step()) await yieldToEvents();
          made.set(key, run.finish());
        } finally {
          run.free();
        }
      }
      return made.get(key);
    };
    try {
      const start = this.#start0;
      const first = await fieldOf(start.key);
      const sim = first ? this.core.SceneSimulation.withField(start.run, first) : new this.core.SceneSimulation(start.run);
      let at = 0;
      const stepTo = async (step) => {
        while (at < step) {
          const n = Math.min(step - at, 64);
          sim.step(n);
          at += n;
          this.progress(id, at / Math.max(target, 1), 'replaying the steps');
          await yieldToEvents();
        }
      };
      try {
        for (const e of this.#history) {
          await stepTo(e.step);
          if (e.kind === 'edit') {
            const field = await fieldOf(e.key);
            if (field) sim.editWithField(e.run, field);
            else sim.edit(e.run);
          } else if (e.kind === 'field') {
            sim.setField(await fieldOf(e.key));
          } else if (e.kind === 'stir') {
            sim.stir(new Float32Array(e.position), new Float32Array(e.velocity), e.radius);
            await stepTo(e.step + e.steps);
            sim.stir(new Float32Array(3), new Float32Array(3), 0);
          }
        }
        await stepTo(target);
      } catch (err) {
        sim.free();
        throw err;
      }
      this.sim.free();
      this.sim = sim;
    } finally {
      for (const field of made.values()) if (field !== this.field) field.free();
    }
  }

  /**
   * The lattice of the field the simulation runs on, for the GPU stepper: {data (xyz per point,
   * `[t][z][y][x]`), size, potential (ψ laid out as data, or null), version}, or no data for a
   * scene without one.
   */
  lattice() {
    const f = this.simField;
    const potential = f ? f.potential() : null;
    return {
      data: f ? f.data() : null,
      size: f ? Array.from(f.size()) : null,
      // The field's vector potential (scenes with solid objects), else empty.
      potential: potential?.length ? potential : null,
      version: this.fieldVersion,
    };
  }

  /**
   * The blob list (docs/FORMATS.md) of the current state seen from `camera` at `image`'s size, either
   * kept from the scene if absent.
   */
  blobList(camera, image) {
    const list = JSON.parse(this.requireSim().blobList());
    if (camera) list.camera = camera;
    if (image) list.image = { ...list.image, ...image };
    return list;
  }
}
