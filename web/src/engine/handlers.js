// The engine's requests over an initialised WASM core: load and edit scenes (`session.js`: the
// field, the simulation and its scene), step the simulation and hand out frames, render
// reference stills. The worker (`worker.js`) wires them to messages; tests call them directly.
//
// The requests of the core's full module (reference stills, exports, the field's wind grid and
// statistics) wait for it (`full()`); what they need crosses in the formats that exist: the blob
// list and the scene as JSON text, the field as its lattice, handed over once per field
// (`Session.fullField`). Each takes what it reads of the running scene before it waits, so a
// step answered meanwhile does not change what it exports.
//
// Each handler takes the request ({ id, type, ...args }) and returns { result, transfer }:
// typed arrays in results are listed in `transfer`, never copied through JSON. A frame is whole
// buffers only, made by the core in one call (`packFrame`, `marchFrame`): the packed blobs
// (`frame::packed` in the core), their description and the moving spheres or the shadow grid;
// nothing per blob is an object or a string. Scenes cross as JSON text both ways.

import { BLOBS_PER_ROW, MAX_COORD, MAX_STIR_RADIUS, SHADOW_GRID_HEADER, WORDS_PER_BLOB } from '../generated/contract.js';
import { Session } from './session.js';
import { binBlobs, padRows } from './tiles.js';

/** Fastest wind (m/s) a stir gives the gas, however far the pointer moved in one step. */
const MAX_STIR_SPEED = 8;

/** Steps taken between two looks at the clock in a long `advance`. */
const STEP_CHUNK = 16;
/** A long `advance` reports its progress this often (ms). */
const PROGRESS_EVERY_MS = 1000;

/**
 * The current state as whole buffers (transferred), from one `packFrame`: `blobs` the packed
 * frame (Uint32Array, WORDS_PER_BLOB words a blob, whole rows), `info` its description
 * (Float32Array, `frame::packed::PackedFrame::info`), `spheres` the visible repulsor spheres
 * (Float32Array, SPHERE_FLOATS each: x y z radius r g b); `flowMs` the last step's time of the
 * scene's flow, stepped here (ms, 0 without one).
 */
function frame(sim) {
  const { words: blobs, info, spheres } = sim.packFrame();
  const result = { count: info[0], time: sim.time(), blobs, info, spheres, flowMs: sim.flowMs() };
  return { result, transfer: [blobs.buffer, info.buffer, spheres.buffer] };
}

/** Steps `sim` `steps` times, reporting progress under `id` now and then; the frame after. */
function advance(sim, id, steps, progress) {
  sim.checkSteps(steps);
  const t0 = performance.now();
  // A long run reports its progress now and then, so the page knows the engine is alive.
  let reported = t0;
  for (let done = 0; done < steps;) {
    const n = Math.min(steps - done, STEP_CHUNK);
    sim.step(n);
    done += n;
    if (done < steps && performance.now() - reported > PROGRESS_EVERY_MS) {
      reported = performance.now();
      progress(id, done / steps, 'stepping');
    }
  }
  const t1 = performance.now();
  const out = frame(sim);
  // Per step, and the frame's packing (once per frame whatever the steps).
  out.result.stepMs = steps > 0 ? (t1 - t0) / steps : 0;
  out.result.packMs = performance.now() - t1;
  return out;
}

/**
 * The exact march's input in one round trip: the merged blobs packed, the shadow grid and the
 * screen tiles of side `tile`, each padded to whole texture rows.
 */
function exactFrame(sim, { view, width, height, fraction, res, tile }) {
  if (!(Number.isInteger(tile) && tile > 0)) throw new Error(`exactFrame: the tile must be a whole number of pixels (got ${tile})`);
  const { words: blobs, info, grid } = sim.marchFrame(fraction, res);
  const count = info[0];
  const floats = new Float32Array(blobs.buffer, 0, WORDS_PER_BLOB * count);
  const tiles = binBlobs({ floats, count }, view, width, height, tile);
  const result = {
    count,
    blobs,
    info,
    grid: grid.slice(0, SHADOW_GRID_HEADER),
    columns: padRows(grid.subarray(SHADOW_GRID_HEADER), BLOBS_PER_ROW),
    heads: padRows(tiles.heads, 4 * BLOBS_PER_ROW),
    list: padRows(tiles.list, BLOBS_PER_ROW),
    tilesX: tiles.tilesX,
    tile,
  };
  const transfer = ['blobs', 'info', 'grid', 'columns', 'heads', 'list'].map((k) => result[k].buffer);
  return { result, transfer };
}

/** The CPU reference still (PNG bytes) of blob list `list` at `width × height`, progress under `id`. */
function referenceStill(core, list, width, height, id, progress) {
  const render = new core.ReferenceRender(JSON.stringify(list), width, height);
  try {
    progress(id, 0, 'rendering');
    const band = Math.max(1, Math.ceil(render.height() / 40));
    while (render.step(band)) progress(id, render.progress(), 'rendering');
    return render.png();
  } finally {
    render.free();
  }
}

/** Lets the worker's event loop run (progress posts, a cancel) between an export's stages. */
const yieldToEvents = () => new Promise((resolve) => setTimeout(resolve));

/** Rows rendered between two looks at the clock and at a cancel. */
const EXPORT_ROWS = 8;
/** Blobs deposited in a volume between two looks. */
const EXPORT_BLOBS = 2000;

/**
 * Runs the export job `make()` resolves to (`StillExport`, `FlipbookExport` or `VolumeExport` of
 * the core's full module, which may have to be fetched first) stage by stage: `step(n)` until it
 * returns false, reporting progress under `id` and yielding to the event loop between stages so
 * that a `cancelExport` request is heard, also while the module is fetched; a cancelled export
 * throws "cancelled: …" and leaves nothing behind (the job is freed either way).
 */
async function runExport(make, { id, stage, chunk, progress, exports }) {
  const token = { cancelled: false };
  exports.add(token);
  let job = null;
  try {
    job = await make();
    progress(id, 0, stage);
    for (;;) {
      if (token.cancelled) throw new Error(`cancelled: the ${stage.toLowerCase()} was cancelled`);
      if (!job.step(chunk)) break;
      progress(id, job.progress(), stage);
      await yieldToEvents();
    }
    if (token.cancelled) throw new Error(`cancelled: the ${stage.toLowerCase()} was cancelled`);
    progress(id, 1, stage);
  } catch (err) {
    job?.free();
    throw err;
  } finally {
    exports.delete(token);
  }
  return job;
}

/**
 * The request handlers over `core` (the WASM module's exports, initialised); `progress(id,
 * value, stage)` reports a request's progress; `memory()` is the core's linear memory (bytes);
 * `full()` resolves to the core's full module, initialised (none: `core` is the full module).
 */
export function createHandlers(core, progress, memory = () => 0, full = null) {
  const session = new Session(core, progress, full);
  const fullCore = full ?? (async () => core);
  const sim = () => session.requireSim();
  /**
   * The pointer's motion not yet given to the gas: {start and position (m: where that motion
   * began, and the middle of its path), displacement (m), radius (m)}, or null. The next steps
   * consume it (`stirred`), however long they are in coming.
   */
  let stir = null;
  /** The stir the last steps took ({centre, velocity, radius}, as the core's flow splats it), or null. */
  let lastStir = null;
  /** The scene text whose flow the GPU was last told of (`flowOfRun`). */
  let toldRun = null;
  /**
   * What the GPU needs of the running scene's flow, when it changed since it was last told: the
   * flow, the primitives and the render objects of the scene the simulation runs (its lighter
   * version's grid where it runs that), or null (no flow). Undefined: nothing new.
   */
  const flowRunNews = () => {
    const run = session.current?.run ?? null;
    if (run === toldRun) return undefined;
    toldRun = run;
    const scene = run ? JSON.parse(run) : null;
    if (!scene?.flow || scene.flow.enabled === false) return null;
    return { flow: scene.flow, wind: scene.wind, objects: scene.render.objects };
  };
  /**
   * Runs `fn` (which takes `steps` steps) with the pending stir acting on those steps: a wind at
   * the pointer of the pointer's displacement over the steps' duration (so the gas near it moves
   * as far as the pointer did, at any frame rate), falling off as exp(−distance/radius). The stir
   * is used up by them.
   */
  const stirred = (steps, fn) => {
    lastStir = null;
    if (!stir || !(steps > 0)) return fn();
    const s = sim();
    const seconds = steps * session.current.scene.simulation.dt;
    const [dx, dy, dz] = stir.displacement;
    const speed = Math.hypot(dx, dy, dz) / seconds;
    const scale = speed > MAX_STIR_SPEED ? MAX_STIR_SPEED / speed : 1;
    const velocity = new Float32Array([dx, dy, dz].map((d) => (d / seconds) * scale));
    s.stir(new Float32Array(stir.position), velocity, stir.radius);
    session.stirred({ position: [...stir.position], velocity: [...velocity], radius: stir.radius }, steps);
    lastStir = { centre: [...stir.position], velocity: [...velocity], radius: stir.radius };
    stir = null;
    try {
      return fn();
    } finally {
      s.stir(new Float32Array(3), new Float32Array(3), 0);
    }
  };
  /**
   * The lighter version's hold on a scene (`lighten.js`): its blob cap (a whole number ≥ 1, or
   * none) and its flow's grid ('coarse': half the cells along each side; 'full' or none: the scene's).
   */
  const setCap = (blobCap, flowGrid) => {
    if (blobCap !== undefined && blobCap !== null && !(Number.isInteger(blobCap) && blobCap >= 1)) {
      throw new Error(`blobCap must be a whole number of at least 1, or null (got ${blobCap})`);
    }
    if (flowGrid !== undefined && flowGrid !== 'full' && flowGrid !== 'coarse') {
      throw new Error(`flowGrid must be 'full' or 'coarse' (got ${flowGrid})`);
    }
    session.blobCap = blobCap ?? Infinity;
    session.coarseFlow = flowGrid === 'coarse';
  };
  /** The exports in flight (their cancel tokens). */
  const exports = new Set();
  return {
    load: async ({ id, scene, blobCap, flowGrid }) => {
      setCap(blobCap, flowGrid);
      stir = null;
      return { result: await session.load(id, scene) };
    },
    edit: async ({ id, scene, blobCap, flowGrid }) => {
      setCap(blobCap, flowGrid);
      const result = await session.edit(id, scene);
      // The gas stayed on the GPU: so does its flow, as the edit left it (`flowRunNews`).
      if (session.sim?.centresOnGpu()) {
        const flowRun = flowRunNews();
        if (flowRun !== undefined) result.flowRun = flowRun;
      }
      return { result };
    },
    reset: async ({ id }) => {
      stir = null;
      await session.reset(id);
      return frame(sim());
    },
    stir: ({ position, displacement, radius }) => {
      // The pointer moved by `displacement` (m) to `position` with a reach of `radius` (m): the
      // motion adds up until steps use it. The bounds are the core's stir's, in its words.
      const vector = (v, name) => {
        if (!(Array.isArray(v) && v.length === 3 && v.every((c) => Number.isFinite(c) && Math.abs(c) <= MAX_COORD))) {
          throw new Error(`stir: ${name} must be 3 finite numbers of at most ${MAX_COORD}`);
        }
        return v;
      };
      if (!(Number.isFinite(radius) && radius > 0 && radius <= MAX_STIR_RADIUS)) {
        throw new Error(`stir: radius must be between 0 and ${MAX_STIR_RADIUS} m (got ${radius})`);
      }
      sim();
      const d = vector(displacement, 'displacement');
      const end = vector(position, 'position');
      // Where the motion not yet used began: the stir acts at the middle of its path, so a drag
      // made while no step runs (paused, or between slow frames) pushes the gas along its length.
      const start = stir?.start ?? end.map((v, k) => v - d[k]);
      const before = stir?.displacement ?? [0, 0, 0];
      stir = {
        start,
        position: end.map((v, k) => (v + start[k]) / 2),
        displacement: before.map((b, k) => b + d[k]),
        radius,
      };
      return { result: null };
    },
    advance: ({ id, steps }) => stirred(steps, () => {
      const out = advance(sim(), id, steps, progress);
      session.stepped(steps);
      return out;
    }),
    // The GPU stepper (`web/src/stepper/`): the gas's centres go to the GPU and come back on
    // demand; while they are there, each step hands over only the newborns, the emptied slots and
    // the frozen wind (`frame::gpu_steps` in the core).
    gpuStart: () => {
      const s = sim();
      const records = s.handCentresToGpu();
      const lattice = session.lattice();
      // The flow goes with the gas: its scene and its u_g now (the GPU steps it from there).
      toldRun = null;
      const run = flowRunNews();
      const flow = run ? { ...run, faces: s.flowFaces() } : null;
      const faces = flow ? [flow.faces.u.buffer, flow.faces.v.buffer, flow.faces.w.buffer] : [];
      const result = { records, lattice, time: s.time(), flow };
      return { result, transfer: [records.buffer, ...latticeBuffers(lattice), ...faces] };
    },
    gpuLattice: () => {
      const lattice = session.lattice();
      return { result: lattice, transfer: latticeBuffers(lattice) };
    },
    gpuAdvance: ({ steps }) => {
      const s = sim();
      s.checkSteps(steps);
      if (!s.centresOnGpu()) throw new Error('the gas is not on the GPU');
      const t0 = performance.now();
      const out = stirred(steps, () => s.stepForGpu(steps));
      session.stepped(steps);
      const result = { ...out, stepMs: steps > 0 ? (performance.now() - t0) / steps : 0, fieldVersion: session.fieldVersion, gpu: true, stir: lastStir };
      // After an edit, the flow the GPU steps from now (undefined: as it was).
      const flowRun = flowRunNews();
      if (flowRun !== undefined) result.flowRun = flowRun;
      const arrays = ['births', 'birthSlots', 'freed', 'ranges', 'wind', 'windOffsets', 'solidGrid', 'sigmaRange', 'spheres'];
      return { result, transfer: arrays.map((k) => out[k].buffer) };
    },
    takeCentres: ({ centres, keepOnGpu, offsets, flowFaces }) => {
      // The GPU's flow first: a gas stepped here again without the GPU's carried offsets starts
      // them in it.
      if (flowFaces) sim().takeFlow(flowFaces.u, flowFaces.v, flowFaces.w);
      sim().takeCentres(centres, Boolean(keepOnGpu), offsets ?? undefined);
      return { result: null };
    },
    // The scene run again here from its start to where it is, its edits and stirs at the steps
    // they came at (the GPU's copy of the gas was lost): the worker holds the gas from now.
    restep: async ({ id }) => {
      await session.replay(id);
      return advance(sim(), id, 0, progress);
    },
    health: () => {
      // For long runs: the core's memory, the blob count, and blobs whose centre is not finite.
      const s = sim();
      const p = s.positions();
      let nonFinite = 0;
      for (let i = 0; i < p.length; i++) if (!Number.isFinite(p[i])) nonFinite += 1;
      return { result: { wasmBytes: memory(), blobs: s.count(), nonFinite } };
    },
    checkSteps: ({ steps }) => ({ result: sim().checkSteps(steps) ?? null }),
    // The flow's grid now (docs/FORMATS.md, the browser API's `exportFlow`): u_g at the cells'
    // centres (m/s, (nz, ny, nx, 3), x fastest) and the temperature excess (K, (nz, ny, nx)),
    // whole buffers; null for a scene without a flow. The worker's, while it steps the flow (the
    // page reads the GPU's while the GPU does: `player/flow-handoff.js`).
    exportFlow: () => {
      const grid = sim().exportFlow();
      if (!grid) return { result: null };
      const { velocity, temperature } = grid;
      const result = { box: Array.from(grid.box), cells: Array.from(grid.cells), time: grid.time, velocity, temperature };
      return { result, transfer: [velocity.buffer, temperature.buffer] };
    },
    // The blob list for the page (docs/FORMATS.md: `exportBlobs`).
    blobList: ({ camera, image }) => ({ result: session.blobList(camera, image) }),
    // The reference still of the current state from `camera` at `width × height`: the blob list
    // stays in the worker, only the PNG crosses.
    reference: async ({ id, camera, width, height }) => {
      const list = session.blobList(camera, { width, height });
      const png = referenceStill(await fullCore(), list, width, height, id, progress);
      return { result: { png, width, height }, transfer: [png.buffer] };
    },
    // Exports for pipelines (docs/FORMATS.md, exports), from the current state and the
    // view's camera: the same core code and bytes as the command line's `render LIST`,
    // `volume LIST` and `flipbook`. The running scene is only read, never changed.
    exportStill: async ({ id, camera, width, height, format, alpha }) => {
      const list = session.blobList(camera, { width, height });
      if (alpha) list.background = 'transparent';
      const time = sim().time();
      const make = async () => new (await fullCore()).StillExport(JSON.stringify(list), format, time);
      const job = await runExport(make, {
        id, stage: 'Rendering still', chunk: EXPORT_ROWS, progress, exports,
      });
      try {
        const bytes = job.bytes();
        return { result: { bytes, format }, transfer: [bytes.buffer] };
      } finally {
        job.free();
      }
    },
    exportVolume: async ({ id, voxel }) => {
      const list = session.blobList();
      const time = sim().time();
      const make = async () => new (await fullCore()).VolumeExport(JSON.stringify(list), voxel, time);
      const job = await runExport(make, {
        id, stage: 'Building volume', chunk: EXPORT_BLOBS, progress, exports,
      });
      try {
        const bytes = job.finish();
        return { result: { bytes }, transfer: [bytes.buffer] };
      } finally {
        job.free();
      }
    },
    exportFlipbook: async ({ id, request, name }) => {
      // A simulation of its own from t = 0, on the running field when it is the scene's.
      const { json, key } = session.current;
      const text = JSON.stringify(request);
      const own = key && session.field && session.fieldKey === key ? session.fullField() : null;
      const make = async () => {
        const { FlipbookExport } = await fullCore();
        return own ? FlipbookExport.withField(json, text, await own) : new FlipbookExport(json, text);
      };
      const job = await runExport(make, { id, stage: 'Rendering flipbook', chunk: EXPORT_ROWS, progress, exports });
      try {
        const { sheet, description } = job.finish(name);
        return { result: { bytes: sheet, description: JSON.parse(description) }, transfer: [sheet.buffer] };
      } finally {
        job.free();
      }
    },
    // Cancels every export in flight: each rejects with "cancelled: …" at its next stage.
    cancelExport: () => {
      for (const token of exports) token.cancelled = true;
      return { result: exports.size };
    },
    windSlice: ({ origin, u, v, n }) => {
      const data = sim().windSlice(new Float32Array(origin), new Float32Array(u), new Float32Array(v), n, n);
      return { result: data, transfer: [data.buffer] };
    },
    exactFrame: (args) => exactFrame(sim(), args),
    volumeTwin: ({ lo, h, dims, step }) => {
      // The core's twin of the real-time view's volumes for the current blobs (tests compare it
      // with the GPU's).
      const s = sim();
      const volume = s.volumeTwin(new Float32Array(lo), h, new Uint32Array(dims));
      const light = s.lightTwin(new Float32Array(lo), h, new Uint32Array(dims), step);
      return { result: { volume, light }, transfer: [volume.buffer, light.buffer] };
    },
    slice: ({ z, t, width, height }) => {
      const data = session.requireField().slice_xy(z, t, width, height);
      return { result: { data, width, height }, transfer: [data.buffer] };
    },
    sample: ({ x, y, z, t }) => ({ result: Array.from(session.requireField().sample(x, y, z, t)) }),
    // The field as the world's wind at time `t` (s), mapped by the scene's `field` (period,
    // time period, amplitude): an OpenVDB Vec3SGrid or a raw RGB32F texture with its description.
    windGrid: async ({ format, t = 0 }) => {
      const f = session.current?.scene.field;
      const field = await session.fullField();
      const bytes = field.windGrid(new Float64Array(f.period), f.time_period, f.amplitude, t, format);
      const description = format === 'rgb32f'
        ? JSON.parse(field.windGridDescription(new Float64Array(f.period), f.time_period, f.amplitude, t))
        : null;
      return { result: { bytes, description }, transfer: [bytes.buffer] };
    },
    fieldStats: async ({ spectrum }) => ({ result: JSON.parse((await session.fullField()).stats(spectrum ? JSON.stringify(spectrum) : '')) }),
  };
}

/** The buffers of a lattice to transfer: the velocity's and the potential's, where present. */
function latticeBuffers(lattice) {
  return [lattice.data, lattice.potential].filter(Boolean).map((a) => a.buffer);
}
