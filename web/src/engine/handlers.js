// The engine's requests over an initialised WASM core: validate and load scenes, synthesise the
// field (with progress), step the simulation and hand out frames, render reference stills.
// The worker (`worker.js`) wires them to messages; tests call them directly.
//
// Each handler takes the request ({ id, type, ...args }) and returns { result, transfer }:
// typed arrays in results are listed in `transfer`, never copied through JSON. A frame is whole
// buffers only: the packed blobs (`render::frame` in the core), their description and the
// moving spheres; nothing per blob is an object or a string.

import { binBlobs, padRows, TEX_WIDTH, TILE } from './tiles.js';

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

  /** The newest valid `load` request: a synthesis in flight gives way to it. */
  let latestLoad = 0;

  function supersededUnlessLatest(id) {
    if (id !== latestLoad) throw new Error('cancelled: a newer scene was loaded before this one was ready');
  }

  /**
   * Synthesises the field for `paramsJson` unless the current one already matches. Yields to
   * the event loop between stages, so a newer `load` supersedes it: this one then rejects.
   */
  async function ensureField(id, paramsJson) {
    if (field && fieldKey === paramsJson) return;
    // A superseded synthesis frees its memory at its next stage: let it, before allocating.
    await yieldToEvents();
    supersededUnlessLatest(id);
    const t0 = performance.now();
    const synthesis = new core.FieldSynthesis(paramsJson);
    try {
      progress(id, 0, synthesis.stage());
      while (synthesis.step()) {
        progress(id, synthesis.progress() * 0.95, synthesis.stage());
        await yieldToEvents();
        supersededUnlessLatest(id);
      }
      const next = synthesis.finish();
      field?.free();
      field = next;
      fieldKey = paramsJson;
      fieldMs = performance.now() - t0;
    } finally {
      synthesis.free();
    }
  }

  async function load(id, scene) {
    const normal = core.validateScene(JSON.stringify(scene));
    latestLoad = id;
    const parsed = JSON.parse(normal);
    if (parsed.field.amplitude > 0) await ensureField(id, core.sceneFieldParams(normal));
    supersededUnlessLatest(id);
    const next = parsed.field.amplitude > 0 ? core.SceneSimulation.withField(normal, field) : new core.SceneSimulation(normal);
    sim?.free();
    sim = next;
    sceneJson = normal;
    progress(id, 1, 'done');
    return { scene: parsed, fieldMs, size: field ? Array.from(field.size()) : null };
  }

  function requireSim() {
    if (!sim) throw new Error('no scene loaded yet');
    return sim;
  }

  /**
   * The current state as whole buffers (transferred): `blobs` the packed frame (Uint32Array, eight
   * words a blob, whole rows), `info` its description (Float32Array, `frameInfo`), `spheres` the
   * visible repulsor spheres (Float32Array, x y z radius r g b each).
   */
  function frame() {
    const s = requireSim();
    const blobs = s.packFrame();
    const info = s.frameInfo();
    const spheres = s.movingSpheres();
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
    reset: () => {
      const next = field && JSON.parse(sceneJson).field.amplitude > 0
        ? core.SceneSimulation.withField(sceneJson, field)
        : new core.SceneSimulation(sceneJson);
      sim?.free();
      sim = next;
      return frame();
    },
    advance: ({ steps }) => {
      requireSim().checkSteps(steps);
      const t0 = performance.now();
      if (steps > 0) requireSim().step(steps);
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
      const s = requireSim();
      const blobs = s.marchFrame(fraction, res);
      const info = s.frameInfo();
      const grid = s.marchGrid();
      const count = info[0];
      const tiles = binBlobs({ floats: new Float32Array(blobs.buffer, 0, 8 * count), count }, view, width, height, TILE);
      const result = {
        count,
        blobs,
        info,
        grid: grid.slice(0, 8),
        columns: padRows(grid.subarray(8), TEX_WIDTH),
        heads: padRows(tiles.heads, 4 * TEX_WIDTH),
        list: padRows(tiles.list, TEX_WIDTH),
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
