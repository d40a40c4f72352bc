// The engine's requests over an initialised WASM core: validate and load scenes, synthesise the
// field (with progress), step the simulation and hand out frames, render reference stills.
// The worker (`worker.js`) wires them to messages; tests call them directly.
//
// Each handler takes the request ({ id, type, ...args }) and returns { result, transfer }:
// typed arrays in results are listed in `transfer`, never copied through JSON. A frame is whole
// buffers only, made by the core in one call (`packFrame`, `marchFrame`): the packed blobs
// (`frame::packed` in the core), their description and the moving spheres or the shadow grid;
// nothing per blob is an object or a string.

import { BLOBS_PER_ROW, SHADOW_GRID_HEADER, WORDS_PER_BLOB } from '../generated/contract.js';
import { binBlobs, padRows, TILE } from './tiles.js';

/** Steps taken between two looks at the clock in a long `advance`. */
const STEP_CHUNK = 16;
/** A long `advance` reports its progress this often (ms). */
const PROGRESS_EVERY_MS = 1000;

/** Lets the worker's event loop run (progress posts, newer requests) between synthesis stages. */
const yieldToEvents = () => new Promise((resolve) => setTimeout(resolve));

/**
 * The request handlers over `core` (the WASM module's exports, initialised); `progress(id,
 * value, stage)` reports a request's progress; `memory()` is the core's linear memory (bytes).
 */
export function createHandlers(core, progress, memory = () => 0) {
  /** The current field, its parameters (JSON) and synthesis time. */
  let field = null;
  let fieldKey = '';
  let fieldMs = 0;
  /** The running simulation and its scene. */
  let sim = null;
  let sceneJson = '';

  /**
   * The field parameters (JSON) the newest valid `load` or `edit` wants ('' for none): a
   * synthesis in flight for other parameters gives way to it.
   */
  let wantedKey = '';
  /** The newest valid `load` or `edit` request: an older `load` still waiting gives way to it. */
  let latestLoad = 0;
  /** The synthesis in flight: its parameters and its promise, or null. */
  let synthesis = null;

  const cancelled = () => new Error('cancelled: a newer scene was loaded before this one was ready');
  function cancelledUnlessWanted(key) {
    if (key !== wantedKey) throw cancelled();
  }

  /**
   * Synthesises the field for `key` (its parameters' JSON) unless the current one already
   * matches, reporting progress under request `id`; one synthesis for the same parameters is
   * shared. Yields to the event loop between stages, so requests keep being answered and a
   * newer scene wanting other parameters supersedes it: this one then rejects.
   */
  function ensureField(id, key) {
    if (field && fieldKey === key) return Promise.resolve();
    if (synthesis?.key === key) return synthesis.promise;
    const promise = synthesise(id, key).finally(() => {
      if (synthesis?.promise === promise) synthesis = null;
    });
    synthesis = { key, promise };
    return promise;
  }

  async function synthesise(id, key) {
    // A superseded synthesis frees its memory at its next stage: let it, before allocating.
    await yieldToEvents();
    cancelledUnlessWanted(key);
    const t0 = performance.now();
    const run = new core.FieldSynthesis(key);
    try {
      progress(id, 0, run.stage());
      while (run.step()) {
        progress(id, run.progress() * 0.95, run.stage());
        await yieldToEvents();
        cancelledUnlessWanted(key);
      }
      const next = run.finish();
      field?.free();
      field = next;
      fieldKey = key;
      fieldMs = performance.now() - t0;
    } finally {
      run.free();
    }
  }

  /** The field parameters (JSON) of a normalised scene, '' when it has no small-scale field. */
  const fieldKeyOf = (normal, parsed) => (parsed.field.amplitude > 0 ? core.sceneFieldParams(normal) : '');

  /** A new simulation of the normalised scene, on the current field when it has one. */
  const simulationOf = (normal, key) => (key ? core.SceneSimulation.withField(normal, field) : new core.SceneSimulation(normal));

  /** The JSON text of a scene sent as text (the page's way) or as an object. */
  const sceneText = (scene) => (typeof scene === 'string' ? scene : JSON.stringify(scene));

  async function load(id, scene) {
    const normal = core.validateScene(sceneText(scene));
    const parsed = JSON.parse(normal);
    const key = fieldKeyOf(normal, parsed);
    wantedKey = key;
    latestLoad = id;
    if (key) await ensureField(id, key);
    if (id !== latestLoad) throw cancelled();
    const next = simulationOf(normal, key);
    sim?.free();
    sim = next;
    sceneJson = normal;
    progress(id, 1, 'done');
    return { scene: parsed, fieldMs, size: field ? Array.from(field.size()) : null };
  }

  /**
   * Applies an edited scene to the running simulation, keeping its blobs and time. A change of
   * the field's settings synthesises the new field meanwhile (progress under `id`) and swaps it
   * in when ready; the gas keeps moving on the field in use. A change to `shapes` restarts the
   * scene (on its own field, so it waits for it).
   */
  async function edit(id, scene) {
    if (!sim) return { ...(await load(id, scene)), restarted: true, fieldPending: false };
    const normal = core.validateScene(sceneText(scene));
    const parsed = JSON.parse(normal);
    const key = fieldKeyOf(normal, parsed);
    const ready = !key || (field && fieldKey === key);
    if (!ready && JSON.stringify(parsed.shapes) !== JSON.stringify(JSON.parse(sceneJson).shapes)) {
      return { ...(await load(id, scene)), restarted: true, fieldPending: false };
    }
    wantedKey = key;
    latestLoad = id;
    const restarted = ready && key ? sim.editWithField(normal, field) : sim.edit(normal);
    sceneJson = normal;
    if (!ready) {
      ensureField(id, key).then(() => {
        if (sim && fieldKeyOf(sceneJson, JSON.parse(sceneJson)) === key) sim.setField(field);
        progress(id, 1, 'done');
      }, () => {});
    }
    return { scene: parsed, restarted, fieldPending: !ready, fieldMs };
  }

  function requireSim() {
    if (!sim) throw new Error('no scene loaded yet');
    return sim;
  }

  /**
   * The current state as whole buffers (transferred), from one `packFrame`: `blobs` the packed
   * frame (Uint32Array, WORDS_PER_BLOB words a blob, whole rows), `info` its description
   * (Float32Array, `PackedFrame::info`), `spheres` the visible repulsor spheres (Float32Array,
   * SPHERE_FLOATS each: x y z radius r g b).
   */
  function frame() {
    const s = requireSim();
    const { words: blobs, info, spheres } = s.packFrame();
    const result = { count: info[0], time: s.time(), blobs, info, spheres };
    return { result, transfer: [blobs.buffer, info.buffer, spheres.buffer] };
  }

  /** A blob list (JSON) seen from `camera` at `image`'s size, either kept from the scene if absent. */
  function inView(json, camera, image) {
    const list = JSON.parse(json);
    if (camera) list.camera = camera;
    if (image) list.image = { ...list.image, ...image };
    return list;
  }

  return {
    load: async ({ id, scene }) => ({ result: await load(id, scene) }),
    edit: async ({ id, scene }) => ({ result: await edit(id, scene) }),
    reset: async ({ id }) => {
      // The scene from its start, on its own field (waiting for one being synthesised).
      requireSim();
      const key = fieldKeyOf(sceneJson, JSON.parse(sceneJson));
      if (key) await ensureField(id, key);
      const next = simulationOf(sceneJson, key);
      sim.free();
      sim = next;
      return frame();
    },
    stir: ({ position, velocity, radius }) => {
      // The pointer's wind: from the next step until the next stir (radius 0 stops it).
      requireSim().stir(new Float32Array(position ?? [0, 0, 0]), new Float32Array(velocity ?? [0, 0, 0]), radius);
      return { result: null };
    },
    advance: ({ id, steps }) => {
      const s = requireSim();
      s.checkSteps(steps);
      const t0 = performance.now();
      // A long run reports its progress now and then, so the page knows the engine is alive.
      let reported = t0;
      for (let done = 0; done < steps;) {
        const n = Math.min(steps - done, STEP_CHUNK);
        s.step(n);
        done += n;
        if (done < steps && performance.now() - reported > PROGRESS_EVERY_MS) {
          reported = performance.now();
          progress(id, done / steps, 'stepping');
        }
      }
      const t1 = performance.now();
      const out = frame();
      // Per step, and the frame's packing (once per frame whatever the steps).
      out.result.stepMs = steps > 0 ? (t1 - t0) / steps : 0;
      out.result.packMs = performance.now() - t1;
      return out;
    },
    health: () => {
      // For long runs: the core's memory, the blob count, and blobs whose centre is not finite.
      const s = requireSim();
      const p = s.positions();
      let nonFinite = 0;
      for (let i = 0; i < p.length; i++) if (!Number.isFinite(p[i])) nonFinite += 1;
      return { result: { wasmBytes: memory(), blobs: s.count(), nonFinite } };
    },
    checkSteps: ({ steps }) => ({ result: requireSim().checkSteps(steps) ?? null }),
    blobList: ({ camera, image }) => ({ result: inView(requireSim().blobList(), camera, image) }),
    windSlice: ({ origin, u, v, n }) => {
      const data = requireSim().windSlice(new Float32Array(origin), new Float32Array(u), new Float32Array(v), n, n);
      return { result: data, transfer: [data.buffer] };
    },
    exactFrame: ({ view, width, height, fraction, res }) => {
      // The exact march's input in one round trip: the merged blobs packed, the shadow grid and
      // the screen tiles, each padded to whole texture rows.
      const { words: blobs, info, grid } = requireSim().marchFrame(fraction, res);
      const count = info[0];
      const floats = new Float32Array(blobs.buffer, 0, WORDS_PER_BLOB * count);
      const tiles = binBlobs({ floats, count }, view, width, height, TILE);
      const result = {
        count,
        blobs,
        info,
        grid: grid.slice(0, SHADOW_GRID_HEADER),
        columns: padRows(grid.subarray(SHADOW_GRID_HEADER), BLOBS_PER_ROW),
        heads: padRows(tiles.heads, 4 * BLOBS_PER_ROW),
        list: padRows(tiles.list, BLOBS_PER_ROW),
        tilesX: tiles.tilesX,
      };
      const transfer = ['blobs', 'info', 'grid', 'columns', 'heads', 'list'].map((k) => result[k].buffer);
      return { result, transfer };
    },
    volumeTwin: ({ lo, h, dims, step }) => {
      // The core's twin of the real-time view's volumes for the current blobs (tests compare it
      // with the GPU's).
      const s = requireSim();
      const volume = s.volumeTwin(new Float32Array(lo), h, new Uint32Array(dims));
      const light = s.lightTwin(new Float32Array(lo), h, new Uint32Array(dims), step);
      return { result: { volume, light }, transfer: [volume.buffer, light.buffer] };
    },
    reference: ({ id, list, width, height }) => {
      const render = new core.ReferenceRender(JSON.stringify(list), width, height);
      progress(id, 0, 'rendering');
      const band = Math.max(1, Math.ceil(render.height() / 40));
      while (render.step(band)) progress(id, render.progress(), 'rendering');
      const png = render.png();
      const rgb = render.rgb();
      render.free();
      return { result: { png, rgb, width, height }, transfer: [png.buffer, rgb.buffer] };
    },
    slice: ({ z, t, width, height }) => {
      if (!field) throw new Error('this scene has no small-scale field');
      const data = field.slice_xy(z, t, width, height);
      return { result: { data, width, height }, transfer: [data.buffer] };
    },
    sample: ({ x, y, z, t }) => {
      if (!field) throw new Error('this scene has no small-scale field');
      return { result: Array.from(field.sample(x, y, z, t)) };
    },
    fieldStats: ({ spectrum }) => {
      if (!field) throw new Error('this scene has no small-scale field');
      return { result: JSON.parse(field.stats(spectrum ? JSON.stringify(spectrum) : '')) };
    },
  };
}
