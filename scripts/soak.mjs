#!/usr/bin/env node
// The soak: plays the playground (the built site in chromium) at its scene's max_blobs in each
// view in turn — points, the real-time view, the exact march — for `--minutes` in all (default
// 30), sampling the page's JS heap (after a collection, so a sample is what is kept, not what
// awaits the collector), the engine's WASM memory, the frame time and the blobs
// whose centres are not finite. Prints a JSON line a sample and a summary; exits 1 unless
// memory stays flat (each view's largest sample in its second half within 10 % of its first
// half's), no centre is ever NaN, and the page logs no error.
//   npm run soak -- --minutes 30 [--blobs N]
import { readFileSync } from 'node:fs';
import { root, withSite } from './site.mjs';
import { VIEWS } from '../web/src/views/modes.js';

const arg = (name, fallback) => {
  const i = process.argv.indexOf(`--${name}`);
  return i >= 0 ? Number(process.argv[i + 1]) : fallback;
};
const minutes = arg('minutes', 30);
const blobs = arg('blobs', 100_000);
const SAMPLE_MS = 10_000;

const scene = JSON.parse(readFileSync(`${root}tests/fixtures/dense-plume.json`, 'utf8'));
scene.gas.max_blobs = blobs;
scene.emitters[0].rate = blobs / 5;

const errors = [];
const report = await withSite('?view=points', async (page) => {
  const cdp = await page.context().newCDPSession(page);
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', (e) => errors.push(e.message));
  await page.evaluate(async (s) => {
    const w = window.windfield;
    await w.ready;
    w.pause();
    await w.setScene(s);
    // Up to max_blobs before the clock starts: the soak runs at the cap.
    await w.step(Math.round(5.5 / s.simulation.dt));
  }, scene);
  const views = {};
  for (const view of VIEWS) {
    const samples = [];
    const end = Date.now() + (minutes * 60_000) / VIEWS.length;
    await page.evaluate((v) => {
      window.windfield.setView(v);
      window.windfield.play();
    }, view);
    while (Date.now() < end) {
      await new Promise((r) => setTimeout(r, Math.min(SAMPLE_MS, Math.max(end - Date.now(), 0))));
      await cdp.send('HeapProfiler.collectGarbage');
      const { usedSize } = await cdp.send('Runtime.getHeapUsage');
      const s = await page.evaluate(async () => {
        const w = window.windfield;
        const health = await w.health();
        const st = w.stats();
        return { ...health, frameMs: st.frameMs, fps: st.fps, scale: st.scale, time: st.time };
      });
      s.heapBytes = usedSize;
      samples.push(s);
      console.log(JSON.stringify({ view, ...s }));
    }
    await page.evaluate(() => window.windfield.pause());
    views[view] = samples;
  }
  return views;
});

/** Memory is flat: the second half's largest sample within 10 % of the first half's. */
const flat = (values) => {
  const half = Math.floor(values.length / 2);
  if (half < 1) return true;
  return Math.max(...values.slice(half)) <= 1.1 * Math.max(...values.slice(0, half));
};
const summary = {};
let ok = errors.length === 0;
for (const [view, samples] of Object.entries(report)) {
  const heap = samples.map((s) => s.heapBytes);
  const wasm = samples.map((s) => s.wasmBytes);
  const frames = samples.map((s) => s.frameMs).sort((a, b) => a - b);
  const nonFinite = samples.reduce((n, s) => n + s.nonFinite, 0);
  const v = {
    samples: samples.length,
    blobs: samples.at(-1)?.blobs,
    simulatedSeconds: samples.length ? samples.at(-1).time - samples[0].time : 0,
    heapMiB: [Math.min(...heap), Math.max(...heap)].map((b) => +(b / 2 ** 20).toFixed(1)),
    wasmMiB: [Math.min(...wasm), Math.max(...wasm)].map((b) => +(b / 2 ** 20).toFixed(1)),
    medianFrameMs: frames[Math.floor(frames.length / 2)],
    heapFlat: flat(heap),
    wasmFlat: flat(wasm),
    nonFinite,
  };
  ok &&= v.heapFlat && v.wasmFlat && nonFinite === 0;
  summary[view] = v;
}
console.log(JSON.stringify({ minutes, blobs, errors, views: summary, ok }));
process.exit(ok ? 0 : 1);
