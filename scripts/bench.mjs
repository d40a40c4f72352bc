#!/usr/bin/env node
// Benchmarks: native (the Rust example), WASM (the built core in Node) and the browser (the
// built site in chromium), medians of several runs. `npm run bench -- --json` prints one JSON
// object per line; without --json, a table. `--no-browser` skips the browser part.
import { execFileSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { loadCore } from '../tests/support/core.js';
import { benchBrowser, gzipKiB } from './bench-browser.mjs';

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
const field = JSON.stringify({
  size: [32, 32, 32, 32],
  spectrum: { law: 'kolmogorov', epsilon: 1, k_inertial: 4, sigma: 1 },
  seed: 1,
});
emit('field_generate_32x32x32x32_wasm_ms', median(7, () => core.WindField.generate(field).free()), 'ms');

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

const nativeMs = results.find((r) => r.name === 'field_generate_32x32x32x32_native_ms')?.value;
const wasmMs = results.find((r) => r.name === 'field_generate_32x32x32x32_wasm_ms')?.value;
if (nativeMs && wasmMs) emit('field_generate_wasm_over_native', wasmMs / nativeMs, 'ratio');

// The browser: the built site (`npm run build` first), skipped with --no-browser.
if (!process.argv.includes('--no-browser')) {
  const build = (config) => execFileSync('npx', ['vite', 'build', '--config', config, '--logLevel', 'error'], { cwd: root, stdio: ['ignore', 'ignore', 'inherit'] });
  // The site's sizes before the embed build adds its standalone module to dist/.
  build('web/vite.config.js');
  emit('site_js_gzip_kib', gzipKiB(`${root}dist`, /\.js$/), 'KiB');
  emit('site_wasm_gzip_kib', gzipKiB(`${root}dist`, /\.wasm$/), 'KiB');
  build('web/vite.embed.config.js');
  // The standalone <wind-field>: the loader a page fetches at once, and everything a player
  // fetches when it nears the viewport (the player's code and the worker with the core).
  const loader = gzipKiB(`${root}dist`, /^embed\.js$/);
  emit('embed_loader_gzip_kib', loader, 'KiB');
  emit('embed_full_gzip_kib', loader + gzipKiB(`${root}dist/wind-field`, /\.js$/), 'KiB');
  for (const r of await benchBrowser()) emit(r.name, r.value, r.unit);
}

if (!json) {
  for (const r of results) console.log(`${r.name.padEnd(44)} ${String(r.value).padStart(10)} ${r.unit}`);
}
