// The engine's Web Worker: owns the WASM core (field, simulation, reference renderer) and
// answers requests from the page.
//
// Protocol (page → worker): { id, type, ...args }.
// Replies (worker → page): { id, ok: true, result } | { id, ok: false, error },
// progress while a request runs: { id, type: 'progress', progress, stage },
// { type: 'fatal', error } if the core cannot start, and { type: 'crashed', error } if it traps
// (a Rust panic or running out of memory leaves the instance unusable: the page restarts us).
// Requests that arrive before the core is ready wait for it, in order. A field synthesis yields
// between its stages, so requests keep being answered meanwhile (on the current scene), and a
// newer valid `load` supersedes one in flight, which then rejects with "cancelled: ...".
// Typed arrays in results are transferred, never copied through JSON.

import init, {
  FieldSynthesis, ReferenceRender, SceneSimulation, sceneFieldParams, shadowGrid, validateScene,
} from '../../pkg/windfield.js';

/** The current field, its parameters (JSON) and synthesis time. */
let field = null;
let fieldKey = '';
let fieldMs = 0;
/** The running simulation and its scene. */
let sim = null;
let sceneJson = '';

const ready = init().catch((err) => {
  self.postMessage({ type: 'fatal', error: `could not start the WASM core: ${err?.message ?? err}` });
  throw err;
});

function progress(id, value, stage) {
  self.postMessage({ id, type: 'progress', progress: value, stage });
}

/** The newest valid `load` request: a synthesis in flight gives way to it. */
let latestLoad = 0;
const yieldToEvents = () => new Promise((resolve) => setTimeout(resolve));

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
  const synthesis = new FieldSynthesis(paramsJson);
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
  const normal = validateScene(JSON.stringify(scene));
  latestLoad = id;
  const parsed = JSON.parse(normal);
  if (parsed.field.amplitude > 0) await ensureField(id, sceneFieldParams(normal));
  supersededUnlessLatest(id);
  const next = parsed.field.amplitude > 0 ? SceneSimulation.withField(normal, field) : new SceneSimulation(normal);
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

/** The blobs of the current state as flat arrays (transferred). */
function frame() {
  const s = requireSim();
  const result = {
    count: s.count(),
    time: s.time(),
    positions: s.positions(),
    sigma: s.sigma(),
    mass: s.mass(),
    albedo: s.albedo(),
    emission: s.emission(),
    age: s.age(),
    counts: JSON.parse(s.counts()),
    objects: JSON.parse(s.objects()),
  };
  const transfer = ['positions', 'sigma', 'mass', 'albedo', 'emission', 'age'].map((k) => result[k].buffer);
  return { result, transfer };
}

/** A blob list (JSON) seen from `camera` at `image`'s size, either kept from the scene if absent. */
function inView(json, camera, image) {
  const list = JSON.parse(json);
  if (camera) list.camera = camera;
  if (image) list.image = { ...list.image, ...image };
  return list;
}

const handlers = {
  load: async ({ id, scene }) => ({ result: await load(id, scene) }),
  reset: () => {
    const next = field && JSON.parse(sceneJson).field.amplitude > 0
      ? SceneSimulation.withField(sceneJson, field)
      : new SceneSimulation(sceneJson);
    sim?.free();
    sim = next;
    return frame();
  },
  advance: ({ steps }) => {
    const t0 = performance.now();
    if (steps > 0) requireSim().step(steps);
    const stepMs = steps > 0 ? (performance.now() - t0) / steps : 0;
    const out = frame();
    out.result.stepMs = stepMs;
    return out;
  },
  blobList: ({ camera, image }) => ({ result: inView(requireSim().blobList(), camera, image) }),
  windSlice: ({ origin, u, v, n }) => {
    const data = requireSim().windSlice(new Float32Array(origin), new Float32Array(u), new Float32Array(v), n, n);
    return { result: data, transfer: [data.buffer] };
  },
  marchList: ({ camera, image, fraction, res }) => {
    // The ray march's input in one round trip: the merged blob list and its shadow grid.
    const json = requireSim().marchList(fraction);
    const list = inView(json, camera, image);
    const grid = list.shadows && list.lights.length ? shadowGrid(json, res) : null;
    return { result: { list, grid }, transfer: grid ? [grid.buffer] : [] };
  },
  reference: ({ id, list, width, height }) => {
    const render = new ReferenceRender(JSON.stringify(list), width, height);
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

self.onmessage = async (event) => {
  const msg = event.data;
  try {
    await ready;
  } catch {
    return;
  }
  const handler = handlers[msg.type];
  try {
    if (!handler) throw new Error(`unknown request "${msg.type}"`);
    const { result, transfer = [] } = await handler(msg);
    self.postMessage({ id: msg.id, ok: true, result }, transfer);
  } catch (err) {
    self.postMessage({ id: msg.id, ok: false, error: err?.message ?? String(err) });
    if (err instanceof WebAssembly.RuntimeError) {
      self.postMessage({ type: 'crashed', error: `the WASM core stopped (${err.message})` });
    }
  }
};
