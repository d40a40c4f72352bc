// The real-time view's frame on a real GPU, for scripts/gpu-bench/run.sh: loaded into a copy of
// the playground, it drives window.windfield and reports through the console (one
// `GPUBENCH {json}` line per figure), so it needs no driver program beside the browser. Query:
// frames, counts, qualities; `profile` adds the volume passes' times (each waits for the GPU);
// `steppers=cpu,gpu` emits and times the gas with each stepper in turn (the worker's step and
// pack, or the GPU's step and sort) and draws what that stepper holds; `liveView=points` plays
// in the points view instead of the real-time view. `twin` checks the GPU stepper against the
// core on this GPU as e2e/gpu-stepper.spec.js does in software, and only that.
// Each real-time figure twice: volumes rebuilt every frame (as while the scene plays), and kept
// (`rebuild: false`, the march alone, as while orbiting a paused scene). `live=S` then plays each
// plume for S seconds in the playground's own view, filling the window, and reports the frame
// rate it holds and the resolution scale it chose (the page's `quality` query sets its quality).
// `views=0` leaves the frames out. `solids=16,64,256` then steps the plume of each count among
// that many solid spheres (as `npm run bench`), with each stepper (each figure says which stepper
// stepped), and `widths` the layers' widths (m, 0.02 by default) it steps them with. `flow=32,64`
// times the flow's GPU step at those cells a side (flow.js here), and only that. `presets=candle`
// plays each named preset (its flow stepped where its gas is) for `live` seconds (10 by
// default) with each stepper, filling the window, and reports the frame rate it holds, who
// stepped the flow and its step's time.
import { centreStatistics, distances, everyKind, totalMass, withSolids } from './gas-twin.js';
import { plumeSpheres } from './plume-spheres.js';
import { flowBench } from './flow-bench.js';

const log = (o) => console.log(`GPUBENCH ${JSON.stringify(o)}`);
const query = new URLSearchParams(location.search);
const frames = Number(query.get('frames') || 10);
// With `presets` and no `counts`, only the presets.
const counts = (query.get('counts') || (query.has('presets') ? '' : '10000,100000')).split(',').filter(Boolean).map(Number);
const qualities = (query.get('qualities') || 'standard,high').split(',');
// Without `steppers` the page keeps its own choice ('auto': the GPU where it can).
const steppers = (query.get('steppers') || 'auto').split(',');

/** The WebGL2 renderer's name, unmasked where the browser allows. */
function renderer() {
  const gl = document.createElement('canvas').getContext('webgl2');
  if (!gl) return 'no WebGL2';
  const info = gl.getExtension('WEBGL_debug_renderer_info');
  return gl.getParameter(info ? info.UNMASKED_RENDERER_WEBGL : gl.RENDERER);
}

/** One plume, 5 s of emission, at `n` blobs (as scripts/bench-browser.mjs). */
async function plumeOf(w, plume, n) {
  const scene = structuredClone(plume);
  w.pause();
  scene.emitters[0].rate = n / 5;
  scene.gas.max_blobs = n;
  await w.setScene(scene);
  await w.step(Math.round(5 / scene.simulation.dt));
  return w.stats().blobs;
}

async function main() {
  log({ renderer: renderer() });
  if (query.has('flow')) {
    await flowBench(log, query.get('flow').split(',').map(Number));
    return;
  }
  while (!window.windfield) await new Promise((r) => setTimeout(r, 100));
  const w = window.windfield;
  await w.ready;
  if (query.has('twin')) {
    await twin(w);
    return;
  }
  const plume = await (await fetch('./dense-plume.json')).json();
  for (const n of counts) {
    for (const stepper of steppers) {
      await w.setStepper(stepper);
      const blobs = await plumeOf(w, plume, n);
      const step = await stepTimes(w);
      log({ blobs, ...step });
      const frame = async (mode, width, height, quality, rebuild = true) => {
        const ms = await w.timeFrames({ mode, width, height, frames, quality, rebuild });
        // With `profile` in the query, the volumes' passes of the last frame (ms each).
        const passes = mode === 'raymarch' && rebuild ? w.stats().passes : undefined;
        log({ blobs, stepper: step.stepper, mode, quality, width, height, rebuild, ms, fps: 1000 / ms, passes });
      };
      // `views=0` times the steps alone.
      if (query.get('views') === '0') continue;
      for (const quality of qualities) {
        await frame('raymarch', 1920, 1080, quality);
        await frame('raymarch', 1920, 1080, quality, false);
      }
      await frame('raymarch', 640, 360, 'standard');
      await frame('points', 1920, 1080);
    }
  }
  // `widths=0.02,0.002`: the layer's width (`field.boundary_width`, m) of each solids scene.
  const widths = (query.get('widths') || '0.02').split(',').map(Number);
  for (const count of (query.get('solids') || '').split(',').filter(Boolean).map(Number)) {
    for (const width of widths) {
      const among = structuredClone(plume);
      among.field.boundary_width = width;
      among.render.objects = plumeSpheres(count);
      for (const n of counts) {
        for (const stepper of steppers) {
          await w.setStepper(stepper);
          const blobs = await plumeOf(w, among, n);
          log({ blobs, solids: count, width, ...(await stepTimes(w)) });
        }
      }
    }
  }
  for (const name of (query.get('presets') || '').split(',').filter(Boolean)) {
    const preset = await (await fetch(`./scenes/${name}.json`)).json();
    fillWindow();
    for (const stepper of steppers) {
      await w.setStepper(stepper);
      w.pause();
      await w.setScene(preset);
      await w.step(Math.round(3 / preset.simulation.dt));
      await playFor(w, Number(query.get('live') || 10), { preset: name, blobs: w.stats().blobs });
    }
  }
  const seconds = Number(query.get('live') || 0);
  if (seconds > 0 && !query.has('presets')) {
    fillWindow();
    for (const n of counts) {
      for (const stepper of steppers) {
        await w.setStepper(stepper);
        await live(w, plume, n, seconds);
      }
    }
  }
}

const blobsOf = async (w) => (await w.exportBlobs({ width: 32, height: 24 })).blobs;

/**
 * The GPU stepper against the core on this GPU (e2e/gpu-stepper.spec.js asks the same in
 * software, from the same scenes and measures, tests/support/gas-twin.js): one step from the
 * same state, blob by blob, in the scene of every kind and in it with solids and carried eddies
 * (the farthest blob from the core's, m; the test asks < 1e-5 m), and a turbulent plume stepped
 * 240 times on each (count, mass, centroid and spread; the test asks mass within 1e-4, centroid
 * within 2 % of the spread, spread within 2 %).
 */
async function twin(w) {
  w.pause();
  for (const [name, scene] of [['every kind', everyKind], ['every kind with solids', withSolids]]) {
    await w.setStepper('cpu');
    await w.setScene(scene);
    await w.step(30);
    const stepper = await w.setStepper('gpu');
    await w.step(1);
    const gpu = await blobsOf(w);
    await w.setStepper('cpu');
    await w.setScene(scene);
    await w.step(31);
    const cpu = await blobsOf(w);
    const apart = distances(gpu, cpu);
    log({ twin: name, stepper, blobs: [gpu.length, cpu.length], farthestM: Math.max(...apart), beyond1e5: apart.filter((d) => d >= 1e-5).length });
  }
  const plume = await (await fetch('./small-plume.json')).json();
  const run = async (kind) => {
    await w.setStepper(kind);
    await w.setScene(plume);
    await w.step(240);
    return { stepper: w.stats().stepper, blobs: await blobsOf(w) };
  };
  const [g, c] = [await run('gpu'), await run('cpu')];
  const [sg, sc] = [centreStatistics(g.blobs), centreStatistics(c.blobs)];
  log({
    twin: 'small-plume, 240 steps',
    steppers: [g.stepper, c.stepper],
    blobs: [g.blobs.length, c.blobs.length],
    massApart: Math.abs(totalMass(g.blobs) - totalMass(c.blobs)) / totalMass(c.blobs),
    centroidApartOfSpread: sg.map((s, a) => Math.abs(s.mean - sc[a].mean) / sc[a].spread),
    spreadApart: sg.map((s, a) => Math.abs(s.spread - sc[a].spread) / sc[a].spread),
  });
}

/**
 * One step of the gas as it stands, with the stepper now active: the worker's step and pack
 * (median of five single steps, as the worker reports them), or the GPU's step and its sort by
 * σ class for the views (`timeGpuStep`, `timeGpuSort`: each pass finished on the GPU).
 */
async function stepTimes(w) {
  const stepper = w.stats().stepper;
  if (stepper === 'gpu') {
    const stepMs = await w.timeGpuStep({ repeats: 5 });
    const sortMs = (await w.timeGpuSort({ repeats: 5 })).ms;
    return { stepper, stepMs, sortMs, ms: stepMs + sortMs };
  }
  const step = [];
  const pack = [];
  for (let i = 0; i < 5; i++) {
    await w.step(1);
    step.push(w.stats().stepMs);
    pack.push(w.stats().packMs);
  }
  const mid = (t) => t.sort((a, b) => a - b)[2];
  return { stepper, stepMs: mid(step), packMs: mid(pack), ms: mid(step) + mid(pack), reason: w.stats().stepperReason };
}

/**
 * The playground playing the plume of `n` blobs for `seconds`, one step a display frame (dt =
 * 1/60 s, so every frame rebuilds the volumes): its last 5 s of frame rate and step time.
 */
/** The playground's view over the whole window. */
function fillWindow() {
  document.head.insertAdjacentHTML('beforeend', '<style>#view { position: fixed !important; inset: 0; z-index: 9; border-radius: 0; }</style>');
}

async function live(w, plume, n, seconds) {
  const blobs = await plumeOf(w, { ...plume, simulation: { ...plume.simulation, dt: 1 / 60 } }, n);
  await playFor(w, seconds, { blobs });
}

/** Plays the scene in the view for `seconds` and reports the rate it held, with `about`. */
async function playFor(w, seconds, about) {
  const view = query.get('liveView') || 'raymarch';
  w.setView(view);
  w.play();
  const samples = [];
  for (let t = 0; t < seconds; t++) {
    await new Promise((r) => setTimeout(r, 1000));
    samples.push(w.stats());
  }
  w.pause();
  w.setView('raymarch');
  const last = samples.slice(-5);
  const canvas = document.querySelector('#canvas');
  log({
    live: true,
    view,
    ...about,
    quality: query.get('quality') || 'standard',
    stepper: w.stats().stepper,
    flowStepper: w.stats().flowStepper,
    flowMs: last.reduce((a, s) => a + s.flowMs, 0) / last.length,
    box: [canvas.clientWidth, canvas.clientHeight],
    canvas: [canvas.width, canvas.height],
    fps: last.reduce((a, s) => a + s.fps, 0) / last.length,
    stepMs: last.reduce((a, s) => a + s.stepMs, 0) / last.length,
    scale: last.at(-1).scale,
    scales: samples.map((s) => s.scale),
  });
}

main().then(() => log({ done: true }), (e) => log({ error: String(e?.stack || e) }));
