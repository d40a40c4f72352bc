// Browser benchmarks over the built site (dist/) in Debian's chromium with SwiftShader:
// navigation to first frame; the worker's step, packing and frame size at 100,000 and 1,000,000
// blobs against one GPU step of the same gas and its sorting by σ class; the real-time view's
// frame at 10,000, 100,000 and 1,000,000 blobs of one plume (640×360) against the points view's,
// and at 1,000,000 the frame of the GPU-stepped gas against the worker's; then the lighter
// version a visitor gets in software (`benchLighter`) and the pace the page keeps in real time,
// whose behaviour the end-to-end tests check on Playwright's clock (`benchPace`). SwiftShader
// runs shaders on the CPU: compare the ratios, not the times. Prints {name, value, unit} objects.
import { readdirSync, readFileSync, statSync } from 'node:fs';
import { gzipSync } from 'node:zlib';
import { plumeSpheres } from './plume-spheres.js';
import { root, withSite } from './site.mjs';
import { encodeScene } from '../web/src/state/url-codec.js';

/**
 * Gzipped size (KiB) of the files under `dir` whose names match `pattern`, less the folders
 * named in `skip` (the standalone element's, `wind-field/`, which an earlier embed build leaves
 * in dist/ beside the site's own copy of the core).
 */
export function gzipKiB(dir, pattern, skip = []) {
  let total = 0;
  for (const name of readdirSync(dir)) {
    const path = `${dir}/${name}`;
    if (statSync(path).isDirectory()) {
      if (!skip.includes(name)) total += gzipKiB(path, pattern, skip) * 1024;
    } else if (pattern.test(name)) total += gzipSync(readFileSync(path), { level: 9 }).length;
  }
  return total / 1024;
}

/**
 * In the page: the preset `name` 3 s in, its worker step and flow times (ms, medians of seven
 * steps) and, once the GPU stepper takes it, one step there with the flow read back (ms, the
 * median of five); `stepper` says who took it.
 */
async function flowPresetSteps(name) {
  const w = window.windfield;
  const scene = await (await fetch(`./scenes/${name}.json`)).json();
  await w.pause();
  await w.setStepper('cpu');
  await w.setScene(scene);
  await w.step(Math.round(3 / scene.simulation.dt));
  w.setView('points');
  const steps = [];
  const flows = [];
  for (let i = 0; i < 7; i++) {
    await new Promise((r) => setTimeout(r, 500));
    await w.step(1);
    steps.push(w.stats().stepMs);
    flows.push(w.stats().flowMs);
  }
  const stepper = await w.setStepper('gpu');
  await w.step(1);
  await w.exportFlow();
  const gpu = [];
  for (let i = 0; i < 5; i++) {
    const t0 = performance.now();
    await w.step(1);
    await w.exportFlow();
    gpu.push(performance.now() - t0);
  }
  await w.setStepper('cpu');
  w.setView('raymarch');
  const mid = (t) => t.sort((a, b) => a - b)[Math.floor(t.length / 2)];
  return { step: mid(steps), flow: mid(flows), stepper, gpu: mid(gpu) };
}

/** Runs the benchmarks against the built site; returns the results. */
export async function benchBrowser() {
  const results = [];
  const emit = (name, value, unit) => results.push({ name, value: Math.round(value * 1000) / 1000, unit });

  await withSite('', async (page) => {
    const firstFrame = await page.evaluate(async () => {
      await window.windfield.ready;
      return performance.now();
    });
    emit('first_frame_ms', firstFrame, 'ms');

    // One plume, 5 s of emission, at `count` blobs: the same volume whatever the count.
    const plume = JSON.parse(readFileSync(`${root}tests/fixtures/dense-plume.json`, 'utf8'));
    const plumeOf = (count, scene = plume) => page.evaluate(async ({ scene, n }) => {
      const w = window.windfield;
      await w.pause();
      scene.emitters[0].rate = n / 5;
      scene.gas.max_blobs = n;
      await w.setScene(scene);
      await w.step(Math.round(5 / scene.simulation.dt));
      return w.stats().blobs;
    }, { scene: structuredClone(scene), n: count });

    // The worker steps unless a benchmark below hands the gas to the GPU.
    await page.evaluate(() => window.windfield.setStepper('cpu'));

    // The worker alone: SwiftShader draws on the same two cores, so the page shows points and
    // rests between steps, and no frame is being drawn while the worker steps.
    const workerStep = () => page.evaluate(async () => {
      const w = window.windfield;
      const step = [];
      const pack = [];
      w.setView('points');
      for (let i = 0; i < 7; i++) {
        await new Promise((r) => setTimeout(r, 1000));
        await w.step(1);
        step.push(w.stats().stepMs);
        pack.push(w.stats().packMs);
      }
      w.setView('raymarch');
      const mid = (t) => t.sort((a, b) => a - b)[3];
      return { step: mid(step), pack: mid(pack), bytes: w.stats().frameBytes };
    });
    // One GPU step of the same gas (the state handed over, one step taken, then timed passes),
    // and the sorting of its slots by σ class for the views that follows each step. With `view`,
    // also the real-time view's frame of the state as the GPU holds it (sorted on the GPU).
    const gpuStep = ({ view = false } = {}) => page.evaluate(async (withView) => {
      const w = window.windfield;
      w.setView('points');
      const stepper = await w.setStepper('gpu');
      await w.step(1);
      const ms = stepper === 'gpu' ? await w.timeGpuStep({ repeats: 5 }) : null;
      const sort = stepper === 'gpu' ? (await w.timeGpuSort({ repeats: 5 })).ms : null;
      const frame = stepper === 'gpu' && withView
        ? await w.timeFrames({ mode: 'raymarch', width: 640, height: 360, frames: 5, quality: 'standard' }) : null;
      await w.setStepper('cpu');
      w.setView('raymarch');
      return { ms, sort, frame };
    }, view);
    const frame = (mode) => page.evaluate((m) => window.windfield.timeFrames({ mode: m, width: 640, height: 360, frames: 5, quality: 'standard' }), mode);

    const n100 = await plumeOf(100_000);
    const worker = await workerStep();
    const k = `${Math.round(n100 / 1000)}k`;
    emit(`worker_step_${k}_ms`, worker.step + worker.pack, 'ms');
    emit(`worker_pack_${k}_ms`, worker.pack, 'ms');
    emit(`frame_bytes_${k}`, worker.bytes, 'bytes');
    const gpu100 = await gpuStep();
    if (gpu100.ms !== null) {
      emit('gpu_step_100k_ms', gpu100.ms, 'ms');
      emit('gpu_sort_100k_ms', gpu100.sort, 'ms');
    }

    // The same plume among 16 and 256 solid spheres of radius 1.2 cm (as examples/bench.rs):
    // the worker's step and the GPU's (each blob visits the solids its cell of the core's grid
    // lists), and their ratios to the step without solids.
    const solidSteps = {};
    for (const count of [16, 256]) {
      const among = structuredClone(plume);
      among.field.boundary_width = 0.02;
      among.render.objects = plumeSpheres(count);
      const blobs = await plumeOf(100_000, among);
      const k = `${Math.round(blobs / 1000)}k`;
      const w = await workerStep();
      emit(`worker_step_${k}_solids_${count}_ms`, w.step + w.pack, 'ms');
      const g = await gpuStep();
      if (g.ms !== null) emit(`gpu_step_${k}_solids_${count}_ms`, g.ms, 'ms');
      solidSteps[count] = { worker: w.step + w.pack, gpu: g.ms };
    }
    emit('worker_step_256_solids_over_none', solidSteps[256].worker / (worker.step + worker.pack), 'ratio');
    if (gpu100.ms !== null && solidSteps[256].gpu !== null) {
      emit('gpu_step_256_solids_over_none', solidSteps[256].gpu / gpu100.ms, 'ratio');
    }
    // The flow presets, 3 s in: the worker's step with its flow's part (medians of seven steps),
    // and the step on the GPU beside the blobs, flow and all (medians of five, each finished by
    // reading the flow back: in SwiftShader how it scales, not what a GPU does).
    for (const name of ['candle', 'ceiling-smoke', 'cylinder-wake']) {
      const out = await page.evaluate(flowPresetSteps, name);
      const key = name.replace('-', '_');
      emit(`flow_${key}_worker_step_ms`, out.step, 'ms');
      emit(`flow_${key}_worker_flow_ms`, out.flow, 'ms');
      if (out.stepper === 'gpu') emit(`flow_${key}_gpu_step_and_readback_ms`, out.gpu, 'ms');
    }
    await plumeOf(100_000);

    const view = {};
    const points = {};
    view[100] = await frame('raymarch');
    points[100] = await frame('points');
    await plumeOf(10_000);
    view[10] = await frame('raymarch');
    emit('view_frame_640x360_10k_ms', view[10], 'ms');
    emit('view_frame_640x360_100k_ms', view[100], 'ms');
    emit('view_100k_over_10k', view[100] / view[10], 'ratio');
    emit('points_frame_640x360_100k_ms', points[100], 'ms');
    emit('view_over_points_100k', view[100] / points[100], 'ratio');

    // A million blobs: the same plume, ten times as dense.
    const n1m = await plumeOf(1_000_000);
    const worker1m = await workerStep();
    emit('blobs_1m', n1m, 'blobs');
    emit('worker_step_1m_wasm_ms', worker1m.step + worker1m.pack, 'ms');
    const gpu1m = await gpuStep({ view: true });
    if (gpu1m.ms !== null) {
      emit('gpu_step_1m_ms', gpu1m.ms, 'ms');
      emit('gpu_sort_1m_ms', gpu1m.sort, 'ms');
      emit('worker_over_gpu_step_1m', (worker1m.step + worker1m.pack) / gpu1m.ms, 'ratio');
      emit('view_frame_640x360_1m_gpu_stepped_ms', gpu1m.frame, 'ms');
    }
    view[1000] = await frame('raymarch');
    if (gpu1m.ms !== null) emit('view_frame_640x360_1m_gpu_stepped_over_worker', gpu1m.frame / view[1000], 'ratio');
    points[1000] = await frame('points');
    emit('view_frame_640x360_1m_ms', view[1000], 'ms');
    emit('view_frame_640x360_1m_over_100k', view[1000] / view[100], 'ratio');
    emit('points_frame_640x360_1m_ms', points[1000], 'ms');
    emit('points_frame_640x360_1m_over_100k', points[1000] / points[100], 'ratio');
  });
  for (const r of await benchLighter()) results.push(r);
  for (const r of await benchPace()) results.push(r);
  return results;
}

/**
 * The lighter version SwiftShader gets (`web/src/player/machine.js`), as a visitor meets it in
 * the playground (1100 × 720): per preset, the frames drawn a second and the simulated seconds
 * a second over the 5 s after its first 10 s; the time from a click on its card in the picker to
 * the first frame with gas; and the delay from a pointer event to its handler while the default
 * scene plays (median of 20). Prints {name, value, unit} objects.
 */
export async function benchLighter() {
  const results = [];
  const emit = (name, value, unit) => results.push({ name, value: Math.round(value * 1000) / 1000, unit });
  const { presets } = JSON.parse(readFileSync(`${root}public/presets.json`, 'utf8'));
  await withSite('', async (page, open) => {
    await page.evaluate(() => window.windfield.ready);
    await page.evaluate(() => {
      window.pointerDelays = [];
      document.querySelector('#canvas').addEventListener('pointermove', (e) => window.pointerDelays.push(performance.now() - e.timeStamp));
    });
    const box = await page.locator('#canvas').boundingBox();
    for (let k = 0; k < 20; k++) {
      await page.mouse.move(box.x + 100 + 10 * k, box.y + box.height / 2);
      await page.waitForTimeout(100);
    }
    const delays = (await page.evaluate(() => window.pointerDelays)).sort((x, y) => x - y);
    emit('light_pointer_delay_median_ms', delays[Math.floor(delays.length / 2)], 'ms');
    emit('light_pointer_delay_most_ms', delays.at(-1), 'ms');
    let slowest = 0;
    for (const { name } of presets) {
      const { seed } = JSON.parse(readFileSync(`${root}public/scenes/${name}.json`, 'utf8'));
      const before = await page.evaluate(() => window.windfield.stats().frames);
      const t0 = Date.now();
      await page.locator(`#picker [data-preset="${name}"]`).click();
      // The first frame with the new scene's own gas (its seed: not the scene before's).
      await page.waitForFunction(({ frames, preset, seed }) => {
        const s = window.windfield.stats();
        return new URLSearchParams(location.search).get('preset') === (preset === 'default' ? null : preset)
          && window.windfield.getScene()?.seed === seed && s.frames > frames && s.blobs > 0;
      }, { frames: before, preset: name, seed }, { timeout: 120_000, polling: 50 });
      const ms = Date.now() - t0;
      slowest = Math.max(slowest, ms);
      emit(`light_click_to_gas_${name}_ms`, ms, 'ms');
    }
    emit('preset_first_gas_ms_max', slowest, 'ms');
    for (const { name } of presets) {
      await open(`?preset=${name}`);
      await page.evaluate(() => window.windfield.ready);
      await page.waitForTimeout(10_000);
      const a = await page.evaluate(() => ({ ...window.windfield.stats(), now: performance.now() }));
      await page.waitForTimeout(5000);
      const b = await page.evaluate(() => ({ ...window.windfield.stats(), now: performance.now() }));
      const seconds = (b.now - a.now) / 1000;
      emit(`light_fps_${name}`, (b.frames - a.frames) / seconds, 'frames/s');
      emit(`light_simulated_${name}`, (b.time - a.time) / seconds, 's/s');
    }
  }, { lighter: true });
  return results;
}

/** A second tab in `page`'s browser that keeps one core busy (a heavy page beside the playground). */
async function busyTab(page) {
  const busy = await page.context().browser().newPage();
  await busy.setContent(`<script>
    (function spin() {
      const end = performance.now() + 45;
      while (performance.now() < end) Math.sqrt(Math.random());
      setTimeout(spin, 5);
    })();
  </script>`);
  return busy;
}

/**
 * The pace the page keeps in real time, at the playground's size in the end-to-end tests (900 ×
 * 580), whose behaviour those tests check on Playwright's clock: the lighter version beside a
 * busy second tab (frames and simulated seconds a second over the 3 s that end 10 s after the
 * load began); the status line at a cap of 0.2 frames a second (11 s after the load); in the
 * full version, the status line's frames a second over the frames counted in its 5 s; the time
 * from a player's removal to the last of its pending calls rejected; and the page's timers at a
 * 1 × 1 window (the most a 100 ms timeout came late, of 10). Prints {name, value, unit} objects.
 */
export async function benchPace() {
  const results = [];
  const emit = (name, value, unit) => results.push({ name, value: Math.round(value * 1000) / 1000, unit });
  const size = { width: 900, height: 580 };
  await withSite('', async (page, open) => {
    await page.setViewportSize(size);
    const busy = await busyTab(page);
    const loadedAt = Date.now();
    await open('');
    await page.evaluate(() => window.windfield.ready);
    await page.waitForTimeout(Math.max(0, loadedAt + 7000 - Date.now()));
    const a = await page.evaluate(() => ({ ...window.windfield.stats(), now: performance.now() }));
    await page.waitForTimeout(3000);
    const b = await page.evaluate(() => ({ ...window.windfield.stats(), now: performance.now() }));
    await busy.close();
    const seconds = (b.now - a.now) / 1000;
    emit('lighter_fps_busy_tab', (b.frames - a.frames) / seconds, 'frames/s');
    emit('lighter_simulated_per_second_busy_tab', (b.time - a.time) / seconds, 's/s');
    await open('?fps=0.2');
    await page.evaluate(() => window.windfield.ready);
    await page.waitForTimeout(11_000);
    emit('status_fps_at_cap_0_2', await page.evaluate(() => window.windfield.stats().fps), 'frames/s');
  }, { lighter: true });
  await withSite('?view=points', async (page, open) => {
    await page.setViewportSize(size);
    await page.evaluate(() => window.windfield.ready);
    const agree = await page.evaluate(async () => {
      const w = window.windfield;
      w.play();
      await new Promise((r) => setTimeout(r, 1000));
      const a = w.stats();
      const t0 = performance.now();
      await new Promise((r) => setTimeout(r, 5000));
      const b = w.stats();
      return { counted: (b.frames - a.frames) / ((performance.now() - t0) / 1000), reported: b.fps };
    });
    emit('status_fps_over_counted', agree.reported / agree.counted, 'ratio');

    const smallPlume = readFileSync(`${root}tests/fixtures/small-plume.json`, 'utf8');
    await page.route('**/tiny.json', (route) => route.fulfill({ contentType: 'application/json', body: smallPlume }));
    await page.route('**/mounts.html', (route) => route.fulfill({
      contentType: 'text/html',
      body: '<!doctype html><html lang="en"><meta charset="utf-8"><title>mounts</title><script type="module" src="./embed.js"></script><body></body></html>',
    }));
    await page.goto(new URL('mounts.html', page.url()).href);
    await page.waitForFunction(() => customElements.get('wind-field') !== undefined);
    const abortMs = await page.evaluate(async () => {
      const el = document.createElement('wind-field');
      for (const [k, v] of Object.entries({ loading: 'eager', view: 'points', src: './tiny.json', 'poster-time': '0' })) el.setAttribute(k, v);
      document.body.append(el);
      await el.ready;
      el.pause();
      const calls = [el.step(300_000), el.setScene(el.getScene()), el.editScene(el.getScene()), el.setStepper('cpu')];
      await new Promise((r) => setTimeout(r, 50));
      const removed = performance.now();
      el.remove();
      const settled = await Promise.all(calls.map((p) => p.then(() => performance.now(), () => performance.now())));
      return Math.max(...settled) - removed;
    });
    emit('removed_player_abort_ms', abortMs, 'ms');

    await open(`?view=raymarch#${await encodeScene(JSON.parse(smallPlume))}`);
    await page.evaluate(() => window.windfield.ready);
    await page.setViewportSize({ width: 1, height: 1 });
    const lags = await page.evaluate(async () => {
      const out = [];
      for (let i = 0; i < 10; i++) {
        const t0 = performance.now();
        await new Promise((r) => setTimeout(r, 100));
        out.push(performance.now() - t0 - 100);
      }
      return out;
    });
    emit('tiny_window_timer_lag_ms_max', Math.max(...lags), 'ms');
  });
  return results;
}
