#!/usr/bin/env node
// The real-time view's frame of one plume (tests/fixtures/dense-plume.json, 5 s of emission at
// each count) stepped by the worker and by the GPU stepper, alternately, over the built site
// (dist/) in Debian's chromium with SwiftShader: each round draws the worker's frame, hands the
// gas to the GPU for a step, times its sorting by σ class (and each pass of it), draws the
// GPU's frame, and hands the gas back. Each frame is timed twice: the wall clock (the median of
// `timeFrames`), and the CPU time of chromium's GPU process over the frames drawn (SwiftShader's
// work, which other processes on a shared machine slow in wall time but do not add to).
// Prints one JSON object a round.
//
//   node scripts/bench-gpu-frames.mjs [--counts 100000,1000000] [--rounds 3] [--frames 3]
import { readFileSync, readdirSync } from 'node:fs';
import { root, withSite } from './site.mjs';

const arg = (name, fallback) => {
  const i = process.argv.indexOf(`--${name}`);
  return i > 0 ? process.argv[i + 1] : fallback;
};
const counts = arg('counts', '100000,1000000').split(',').map(Number);
const rounds = Number(arg('rounds', 3));
const frames = Number(arg('frames', 3));

/** The ids of chromium's GPU processes started by this script. */
function gpuProcesses() {
  const all = [];
  for (const name of readdirSync('/proc')) {
    if (!/^\d+$/.test(name)) continue;
    try {
      const stat = readFileSync(`/proc/${name}/stat`, 'utf8');
      const parent = Number(stat.slice(stat.lastIndexOf(')') + 2).split(' ')[1]);
      all.push({ pid: Number(name), parent, gpu: readFileSync(`/proc/${name}/cmdline`, 'utf8').includes('--type=gpu-process') });
    } catch {
      // gone meanwhile
    }
  }
  const ours = new Set([process.pid]);
  for (let grew = true; grew;) {
    grew = false;
    for (const p of all) {
      if (!ours.has(p.pid) && ours.has(p.parent)) {
        ours.add(p.pid);
        grew = true;
      }
    }
  }
  return all.filter((p) => p.gpu && ours.has(p.pid)).map((p) => p.pid);
}

/** CPU seconds (user and system) the processes `pids` have used. */
function cpuSeconds(pids) {
  let total = 0;
  for (const pid of pids) {
    try {
      const stat = readFileSync(`/proc/${pid}/stat`, 'utf8');
      const fields = stat.slice(stat.lastIndexOf(')') + 2).split(' ');
      total += (Number(fields[11]) + Number(fields[12])) / 100;
    } catch {
      // gone meanwhile
    }
  }
  return total;
}

const plume = JSON.parse(readFileSync(`${root}tests/fixtures/dense-plume.json`, 'utf8'));
await withSite('', async (page) => {
  await page.evaluate(() => window.windfield.ready);
  const pids = gpuProcesses();
  // Waits for the GPU (one pixel of the canvas read back), so that a measure starts idle.
  const settle = () => page.evaluate(() => {
    const gl = document.querySelector('#canvas').getContext('webgl2');
    const bound = gl.getParameter(gl.FRAMEBUFFER_BINDING);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
    gl.bindFramebuffer(gl.FRAMEBUFFER, bound);
  });
  const timed = async (fn, options) => {
    await settle();
    const before = cpuSeconds(pids);
    const value = await page.evaluate(fn, options);
    return { value, cpuMs: 1000 * (cpuSeconds(pids) - before) };
  };
  const view = { mode: 'raymarch', width: 640, height: 360, frames, quality: 'standard' };
  const round1 = (x) => Math.round(x);
  for (const n of counts) {
    await page.evaluate(async ({ scene, n }) => {
      const w = window.windfield;
      await w.pause();
      await w.setStepper('cpu');
      w.setView('points');
      scene.emitters[0].rate = n / 5;
      scene.gas.max_blobs = n;
      await w.setScene(scene);
      await w.step(Math.round(5 / scene.simulation.dt));
    }, { scene: structuredClone(plume), n });
    for (let r = 0; r < rounds; r++) {
      const worker = await timed((o) => window.windfield.timeFrames(o), view);
      const stepper = await page.evaluate(async () => {
        const got = await window.windfield.setStepper('gpu');
        await window.windfield.step(1);
        return got;
      });
      // (A build from before the GPU sorted its gas has no timeGpuSort.)
      const sort = await page.evaluate(() => window.windfield.timeGpuSort?.({ repeats: 3 }) ?? null);
      const gpu = await timed((o) => window.windfield.timeFrames(o), view);
      await page.evaluate(() => window.windfield.setStepper('cpu'));
      // timeFrames draws frames + 1 frames (the first untimed): CPU time per frame drawn.
      const perFrame = (t) => t.cpuMs / (frames + 1);
      console.log(JSON.stringify({
        blobs: n,
        stepper,
        worker_frame_ms: round1(worker.value),
        gpu_frame_ms: round1(gpu.value),
        worker_frame_cpu_ms: round1(perFrame(worker)),
        gpu_frame_cpu_ms: round1(perFrame(gpu)),
        gpu_over_worker_cpu: Math.round(1000 * (gpu.cpuMs / worker.cpuMs)) / 1000,
        gpu_sort_ms: sort && round1(sort.ms),
        gpu_sort_passes_ms: sort && Object.fromEntries(Object.entries(sort.passes).map(([k, v]) => [k, round1(v)])),
      }));
    }
  }
});
