#!/usr/bin/env node
// Benchmarks: native (the Rust example), WASM (the built core in Node), an FFTW baseline (when
// Debian's libfftw3-dev is installed) and the browser (the built site in chromium), medians of
// several runs. `npm run bench -- --json` prints one JSON object per line; without --json, a
// table. `--no-browser` skips the browser part.
import { execFileSync } from 'node:child_process';
import { existsSync, readFileSync } from 'node:fs';
import { resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { loadCore } from '../tests/support/core.js';
import { benchBrowser, gzipKiB } from './bench-browser.mjs';
import { plumeSpheres } from './plume-spheres.js';

const root = fileURLToPath(new URL('..', import.meta.url));
const json = process.argv.includes('--json');
const results = [];
const emit = (name, value, unit) => {
  const r = { name, value: Math.round(value * 1000) / 1000, unit };
  results.push(r);
  if (json) console.log(JSON.stringify(r));
};

function median(runs, fn) {
  fn();
  const t = [];
  for (let i = 0; i < runs; i++) {
    const s = performance.now();
    fn();
    t.push(performance.now() - s);
  }
  t.sort((a, b) => a - b);
  return t[Math.floor(runs / 2)];
}

const quiet = { cwd: `${root}wasm-core`, stdio: ['ignore', 'pipe', 'inherit'], encoding: 'utf8' };
execFileSync('bash', [`${root}scripts/build-wasm.sh`], { stdio: ['ignore', 'ignore', 'inherit'] });
const native = execFileSync('cargo', ['run', '--quiet', '--release', '--example', 'bench'], quiet);
for (const line of native.split('\n').filter(Boolean)) {
  const r = JSON.parse(line);
  emit(r.name, r.value, r.unit);
}

const core = await loadCore();
/** The paper's field (ε = 1, k_inertial = 4, σ = 1, seed 1) on an n^4 lattice, as JSON. */
const fieldJson = (n) => JSON.stringify({
  size: [n, n, n, n],
  spectrum: { law: 'kolmogorov', epsilon: 1, k_inertial: 4, sigma: 1 },
  seed: 1,
});
emit('field_generate_32x32x32x32_wasm_ms', median(7, () => core.WindField.generate(fieldJson(32)).free()), 'ms');

// One RK2 step of 200,000 blobs in a 32^4 field plus three primitives (as examples/bench.rs).
const sceneJson = readFileSync(`${root}wasm-core/examples/blob-step-scene.json`, 'utf8');
const sim = new core.SceneSimulation(sceneJson);
const n = 200_000;
const positions = new Float32Array(3 * n);
const spread = (i, k) => (((i + 0.5) * k) % 1) * 4 - 2;
for (let i = 0; i < n; i++) {
  positions[3 * i] = spread(i, 0.7548777);
  positions[3 * i + 1] = spread(i, 0.5698403) + 1;
  positions[3 * i + 2] = spread(i, 0.4301597);
}
sim.addBlobs(positions, 0.03, 1);
emit('blob_step_200k_wasm_ms', median(7, () => sim.step(1)), 'ms');
sim.free();
emit('wasm_peak_memory_mib', core.memory.buffer.byteLength / 2 ** 20, 'MiB');

// The worker at 100,000 blobs: the dense plume (tests/fixtures/dense-plume.json) emitting
// 20,000 blobs a second for 5 s up to its cap, then one fixed step and the frame's packing as
// the engine worker does them (web/src/engine/handlers.js: `advance`), median of 31. The same
// quantities as the browser's worker_step_100k_ms (step and pack) and worker_pack_100k_ms.
{
  const plume = JSON.parse(readFileSync(`${root}tests/fixtures/dense-plume.json`, 'utf8'));
  plume.emitters[0].rate = 20_000;
  plume.gas.max_blobs = 100_000;
  const worker = new core.SceneSimulation(JSON.stringify(plume));
  worker.step(Math.round(5 / plume.simulation.dt));
  const step = [];
  const pack = [];
  let count = 0;
  for (let i = 0; i < 32; i++) {
    const t0 = performance.now();
    worker.step(1);
    const t1 = performance.now();
    count = worker.packFrame().info[0];
    const t2 = performance.now();
    if (i > 0) {
      step.push(t1 - t0);
      pack.push(t2 - t1);
    }
  }
  const mid = (t) => t.sort((a, b) => a - b)[t.length >> 1];
  const k = `${Math.round(count / 1000)}k`;
  emit(`worker_step_${k}_wasm_ms`, mid(step) + mid(pack), 'ms');
  emit(`worker_pack_${k}_wasm_ms`, mid(pack), 'ms');
  worker.free();
}

// Solid objects (as examples/bench.rs): one RK2 step among 0, 16 and 256 solid spheres, medians
// of 7 rounds of a step of each in turn (after a warm-up round), two ways: the blob-step
// scene's 100,000 blobs spread through its box in no order among spheres of radius 8 cm (a
// first step puts the blobs seeded inside a sphere out), and the worker's dense plume at
// 100,000 blobs (5 s of emission, the blobs in the order they were born) among spheres of
// radius 1.2 cm through the plume; and the field with its vector potential against the field
// alone.
{
  const spheres = (count) => Array.from({ length: count }, (_, i) => {
    const f = (k) => (((i + 0.5) * k) % 1) * 3.6 - 1.8;
    return { type: 'sphere', center: [f(0.618034), f(0.4142136) + 1, f(0.7320508)], radius: 0.08, color: [0.5, 0.5, 0.5], solid: true };
  });
  const counts = [0, 16, 256];
  /** Medians of 7 interleaved rounds of one step of each of `sims` (freed afterwards). */
  const interleaved = (sims) => {
    sims.forEach((s) => s.step(1));
    const times = sims.map(() => []);
    for (let round = 0; round < 7; round++) {
      sims.forEach((s, k) => {
        const t0 = performance.now();
        s.step(1);
        times[k].push(performance.now() - t0);
      });
    }
    sims.forEach((s) => s.free());
    return times.map((t) => t.sort((a, b) => a - b)[3]);
  };
  const blobStep = interleaved(counts.map((count) => {
    const scene = JSON.parse(sceneJson);
    scene.render = { objects: spheres(count) };
    const s = new core.SceneSimulation(JSON.stringify(scene));
    s.addBlobs(positions.subarray(0, 3 * 100_000), 0.03, 1);
    s.step(1);
    return s;
  }));
  counts.forEach((count, k) => emit(`blob_step_100k_solids_${count}_wasm_ms`, blobStep[k], 'ms'));
  emit('blob_step_256_solids_over_none_wasm', blobStep[2] / blobStep[0], 'ratio');
  const plume = JSON.parse(readFileSync(`${root}tests/fixtures/dense-plume.json`, 'utf8'));
  plume.emitters[0].rate = 20_000;
  plume.gas.max_blobs = 100_000;
  plume.field.boundary_width = 0.02;
  const worker = interleaved(counts.map((count) => {
    plume.render.objects = plumeSpheres(count);
    const s = new core.SceneSimulation(JSON.stringify(plume));
    s.step(Math.round(5 / plume.simulation.dt));
    return s;
  }));
  counts.forEach((count, k) => emit(`worker_step_100k_solids_${count}_wasm_ms`, worker[k], 'ms'));
  emit('worker_step_256_solids_over_none_wasm', worker[2] / worker[0], 'ratio');
  const withPotential = JSON.stringify({ ...JSON.parse(fieldJson(32)), potential: true });
  emit('field_generate_32x32x32x32_with_potential_wasm_ms', median(5, () => {
    const synthesis = new core.FieldSynthesis(withPotential);
    while (synthesis.step());
    synthesis.finish().free();
    synthesis.free();
  }), 'ms');
}

const value = (name) => results.find((r) => r.name === name)?.value;
const nativeMs = value('field_generate_32x32x32x32_native_ms');
const wasmMs = value('field_generate_32x32x32x32_wasm_ms');
if (nativeMs && wasmMs) emit('field_generate_wasm_over_native', wasmMs / nativeMs, 'ratio');

// The flow's step in WebAssembly, the case of examples/bench.rs's flow rows: the module of
// examples/flow-wasm.rs (raw exports, in no page), built as the core is and put through
// wasm-opt -O3 as the core's modules are. The core's bindings come with it: their imports are
// never called by the flow, so each is a stand-in that throws.
{
  execFileSync('cargo', ['build', '--quiet', '--profile', 'wasm', '--target', 'wasm32-unknown-unknown',
    '--no-default-features', '--example', 'flow-wasm'], quiet);
  const raw = resolve(`${root}wasm-core`, process.env.CARGO_TARGET_DIR ?? 'target', 'wasm32-unknown-unknown/wasm/examples/flow_wasm.wasm');
  execFileSync(`${root}node_modules/.bin/wasm-opt`, ['-O3', raw, '-o', `${raw}.opt`], { stdio: ['ignore', 'ignore', 'inherit'] });
  const module = new WebAssembly.Module(readFileSync(`${raw}.opt`));
  const imports = {};
  for (const { module: from, name, kind } of WebAssembly.Module.imports(module)) {
    imports[from] ??= {};
    if (kind === 'function') imports[from][name] = () => { throw new Error(`flow-wasm: ${from}.${name} called`); };
  }
  const flow = new WebAssembly.Instance(module, imports).exports;
  for (const [n, runs, warm] of [[32, 7, 10], [64, 3, 1]]) {
    flow.flow_new(n);
    // V8 first runs a module's baseline code and swaps in the optimised code once compiled:
    // at 32³, the first case, steps before the timed ones keep the baseline out of the figure.
    for (let i = 0; i < warm; i++) flow.flow_step();
    emit(`flow_step_${n}_wasm_ms`, median(runs, () => flow.flow_step()), 'ms');
  }
}

// The largest lattice (2^24 points), and the WASM memory it takes, each in an instance of its
// own (linear memory only grows, so an instance's size is its peak).
let instances = 0;
async function freshCore() {
  const bindings = await import(`${root}web/pkg/windfield_full.js?instance=${++instances}`);
  const exports = bindings.initSync({ module: readFileSync(`${root}web/pkg/windfield_full_bg.wasm`) });
  return { ...bindings, memory: exports.memory };
}
const mib = (c) => c.memory.buffer.byteLength / 2 ** 20;
{
  const c = await freshCore();
  emit('field_generate_64x64x64x64_wasm_ms', median(5, () => c.WindField.generate(fieldJson(64)).free()), 'ms');
}
{
  const c = await freshCore();
  const synthesis = new c.FieldSynthesis(fieldJson(64));
  while (synthesis.step());
  const f = synthesis.finish();
  synthesis.free();
  emit('wasm_field_64_memory_mib', mib(c), 'MiB');
  // The worker keeps the current field while it synthesises the next one.
  const next = c.WindField.generate(JSON.stringify({ ...JSON.parse(fieldJson(64)), seed: 2 }));
  emit('wasm_field_64_replaced_memory_mib', mib(c), 'MiB');
  next.free();
  // The field page's statistics of the field (two half spectra in f64 while they run).
  f.stats('');
  emit('wasm_field_64_stats_memory_mib', mib(c), 'MiB');
  f.free();
}

// FFTW: three complex single-precision 4-D inverse transforms of the same lattices, planned
// with FFTW_MEASURE, in this run (scripts/fftw-baseline.c). Skipped without libfftw3-dev.
if (existsSync('/usr/include/fftw3.h')) {
  const binary = `${root}wasm-core/target/fftw-baseline`;
  try {
    execFileSync('gcc', ['-O2', '-o', binary, `${root}scripts/fftw-baseline.c`, '-lfftw3f', '-lm'], { stdio: ['ignore', 'ignore', 'inherit'] });
    const out = execFileSync(binary, ['32', '64'], { encoding: 'utf8', stdio: ['ignore', 'pipe', 'inherit'] });
    for (const line of out.split('\n').filter(Boolean)) {
      const r = JSON.parse(line);
      emit(r.name, r.value, r.unit);
    }
    for (const n of [32, 64]) {
      const fftw = value(`fftw_inverse_3x_c2c_${n}x${n}x${n}x${n}_ms`);
      const wasm = value(`field_generate_${n}x${n}x${n}x${n}_wasm_ms`);
      const native = value(`field_generate_${n}x${n}x${n}x${n}_native_ms`);
      if (fftw && wasm) emit(`field_over_fftw_${n}`, wasm / fftw, 'ratio');
      if (fftw && native) emit(`field_native_over_fftw_${n}`, native / fftw, 'ratio');
    }
  } catch (err) {
    console.error(`bench: FFTW baseline skipped (${err.message.split('\n')[0]})`);
  }
} else {
  console.error('bench: FFTW baseline skipped (no /usr/include/fftw3.h: apt-get install libfftw3-dev)');
}

// The browser: the built site (`npm run build` first), skipped with --no-browser.
if (!process.argv.includes('--no-browser')) {
  const build = (config) => execFileSync('npx', ['vite', 'build', '--config', config, '--logLevel', 'error'], { cwd: root, stdio: ['ignore', 'ignore', 'inherit'] });
  // The site's sizes, without the standalone element's folder (dist/wind-field/, its own copy
  // of the player and the core).
  build('web/vite.config.js');
  emit('site_js_gzip_kib', gzipKiB(`${root}dist`, /\.js$/, ['wind-field']), 'KiB');
  // The core's first module (what every page's worker starts on), and the full one, fetched on
  // a page's first export, reference still or statistics (and by the classroom).
  emit('site_wasm_gzip_kib', gzipKiB(`${root}dist`, /^windfield_bg-.*\.wasm$/, ['wind-field']), 'KiB');
  emit('site_wasm_full_gzip_kib', gzipKiB(`${root}dist`, /^windfield_full_bg-.*\.wasm$/, ['wind-field']), 'KiB');
  build('web/vite.embed.config.js');
  // The standalone <wind-field>: the loader a page fetches at once; everything a player
  // fetches when it nears the viewport (the loader, the player's chunk, the worker's chunk and
  // the core's first module); and the rest of dist/wind-field/, fetched on first use (the core's
  // full module and its glue on an export, and the chunks the player imports when asked).
  const loader = gzipKiB(`${root}dist`, /^embed\.js$/);
  emit('embed_loader_gzip_kib', loader, 'KiB');
  const first = gzipKiB(`${root}dist/wind-field`, /^(?:(?:player|worker)-.*\.js|windfield_bg-.*\.wasm)$/);
  emit('embed_full_gzip_kib', loader + first, 'KiB');
  emit('embed_lazy_gzip_kib', gzipKiB(`${root}dist/wind-field`, /\.(?:js|wasm)$/) - first, 'KiB');
  for (const r of await benchBrowser()) emit(r.name, r.value, r.unit);
}

if (!json) {
  for (const r of results) console.log(`${r.name.padEnd(44)} ${String(r.value).padStart(10)} ${r.unit}`);
}
