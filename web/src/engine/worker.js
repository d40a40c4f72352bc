// The engine's Web Worker: owns the WASM core (field, simulation, reference renderer) and
// answers requests from the page.
//
// Protocol (page → worker): { id, type, ...args }.
// Replies (worker → page): { id, ok: true, result } | { id, ok: false, error },
// progress while a request runs: { id, type: 'progress', progress, stage },
// { type: 'fatal', error } if the core cannot start, { type: 'crashed', error } if it traps
// (a Rust panic or running out of memory leaves the instance unusable: the page restarts us),
// and a refusal that grew the core's memory past REFUSAL_GROWTH says so (`recycle`: the page
// then restarts us to give the memory back).
// Requests that arrive before the core is ready wait for it, in order. A field synthesis yields
// between its stages, so requests keep being answered meanwhile (on the current scene), and a
// newer valid `load` supersedes one in flight, which then rejects with "cancelled: ...".
// The requests themselves are `handlers.js`; typed arrays in results are transferred.
//
// The worker starts on the core's first module (web/pkg/windfield.js: the field, the scene and
// its simulation, the frames). The full module (windfield_full.js: the exports, the reference
// renderer, the field's statistics and wind grid) is fetched the first time a request needs it,
// and only then; a failure to fetch it refuses that request and leaves the player running.

import init, * as core from '../../pkg/windfield.js';
import { createHandlers } from './handlers.js';

let memory = null;
/**
 * A refused request that grew the core's memory by more than this (bytes) has the worker
 * restarted: WebAssembly memory is never given back, and a hostile scene's parse may have taken
 * a lot of it before the refusal.
 */
const REFUSAL_GROWTH = 64 * 1024 * 1024;
const memoryBytes = () => memory?.buffer.byteLength ?? 0;
const ready = init().then((wasm) => { memory = wasm.memory; }, (err) => {
  self.postMessage({ type: 'fatal', error: `could not start the WASM core: ${err?.message ?? err}` });
  throw err;
});

/** The full module, initialised: fetched on the first request that needs it, then kept. */
let full = null;
const fullCore = () => {
  full ??= import('../../pkg/windfield_full.js').then(async (module) => {
    await module.default();
    return module;
  }).catch((err) => {
    full = null;
    throw new Error(`could not start the WASM core's full module: ${err?.message ?? err}`);
  });
  return full;
};

const handlers = createHandlers(core, (id, value, stage) => {
  self.postMessage({ id, type: 'progress', progress: value, stage });
}, memoryBytes, fullCore);

self.onmessage = async (event) => {
  const msg = event.data;
  // Every request is answered; one that cannot be read at all (no id) cannot be, and the page's
  // time limit catches it.
  if (!msg || typeof msg !== 'object' || !Number.isSafeInteger(msg.id)) return;
  try {
    await ready;
  } catch {
    return;
  }
  const handler = Object.hasOwn(handlers, msg.type) ? handlers[msg.type] : null;
  const before = memoryBytes();
  try {
    if (!handler) throw new Error(`unknown request "${String(msg.type)}"`);
    const { result, transfer = [] } = await handler(msg);
    self.postMessage({ id: msg.id, ok: true, result }, transfer);
  } catch (err) {
    // A load a newer one superseded refused nothing: the newer one reuses what it took, and a
    // restart now would drop the newer one with it.
    const grown = err?.superseded ? 0 : memoryBytes() - before;
    const recycle = grown > REFUSAL_GROWTH ? `a refused request took ${Math.round(grown / 2 ** 20)} MiB of the engine's memory` : undefined;
    self.postMessage({ id: msg.id, ok: false, error: err?.message ?? String(err), ...(recycle && { recycle }) });
    if (err instanceof WebAssembly.RuntimeError) {
      self.postMessage({ type: 'crashed', error: `the WASM core stopped (${err.message})` });
    }
  }
};
