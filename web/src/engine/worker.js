// The engine's Web Worker: owns the WASM core and answers requests from the page.
//
// Protocol (page → worker): { id, type, ...args }.
// Replies (worker → page): { id, ok: true, result } | { id, ok: false, error },
// progress while a request runs: { id, type: 'progress', progress, stage },
// and { type: 'fatal', error } if the core cannot start.
// Requests that arrive before the core is ready wait for it, in order.
// Typed arrays in results are transferred, never copied through JSON.

import init, { FieldSynthesis } from '../../pkg/windfield.js';

const STAGES = [
  'filtering white noise', 'x transform (u₁, u₂)', 'y transform (u₁, u₂)', 'z transform (u₁, u₂)',
  't transform (u₁, u₂)', 'x transform (u₃)', 'y transform (u₃)', 'z transform (u₃)',
  't transform (u₃)', 'interleaving',
];

let field = null;
let fieldInfo = null;

const ready = init().catch((err) => {
  self.postMessage({ type: 'fatal', error: `could not start the WASM core: ${err?.message ?? err}` });
  throw err;
});

function generate(id, params) {
  const t0 = performance.now();
  const synthesis = new FieldSynthesis(JSON.stringify(params));
  let stage = 0;
  self.postMessage({ id, type: 'progress', progress: 0, stage: STAGES[0] });
  while (synthesis.step()) {
    stage += 1;
    self.postMessage({ id, type: 'progress', progress: synthesis.progress(), stage: STAGES[stage] });
  }
  const next = synthesis.finish();
  synthesis.free();
  field?.free();
  field = next;
  const fieldMs = performance.now() - t0;
  fieldInfo = { size: Array.from(field.size()), fieldMs, params };
  self.postMessage({ id, type: 'progress', progress: 1, stage: 'done' });
  return { result: fieldInfo };
}

function requireField() {
  if (!field) throw new Error('no field generated yet');
  return field;
}

const handlers = {
  generate: ({ id, params }) => generate(id, params),
  slice: ({ z, t, width, height }) => {
    const data = requireField().slice_xy(z, t, width, height);
    return { result: { data, width, height }, transfer: [data.buffer] };
  },
  sample: ({ x, y, z, t }) => ({ result: Array.from(requireField().sample(x, y, z, t)) }),
  data: () => {
    const data = requireField().data();
    return { result: { data, size: fieldInfo.size }, transfer: [data.buffer] };
  },
  stats: ({ spectrum }) => ({
    result: JSON.parse(requireField().stats(spectrum ? JSON.stringify(spectrum) : '')),
  }),
  info: () => ({ result: fieldInfo }),
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
    const { result, transfer = [] } = handler(msg);
    self.postMessage({ id: msg.id, ok: true, result }, transfer);
  } catch (err) {
    self.postMessage({ id: msg.id, ok: false, error: err?.message ?? String(err) });
  }
};
