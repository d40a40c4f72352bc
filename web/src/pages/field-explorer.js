// The field explorer (field.html): generates the small-scale field in the engine worker (with
// progress), animates one slice of it over time, and lets the spectrum be edited.

import GUI from 'lil-gui';
import { Engine } from '../engine/client.js';
import { SliceView } from '../views/slice-view.js';
import { DEFAULT_FIELD, fieldScene, LAWS, maxInertial } from './field-params.js';
import { showMessage, showProgress } from './page-ui.js';

/** Samples per side of the displayed slice. */
const SLICE_RES = 64;
/** Seconds of animation per temporal period of the field (at speed 1). */
const SECONDS_PER_PERIOD = 8;

/** Lattices offered: any even extent from the contract's MIN_EXTENT to MAX_EXTENT works (powers of two are the fastest). */
const LATTICES = {
  '16⁴': [16, 16, 16, 16],
  '24⁴': [24, 24, 24, 24],
  '32⁴': [32, 32, 32, 32],
  '32³ × 64': [32, 32, 32, 64],
  '48³ × 16': [48, 48, 48, 16],
  '64³ × 16': [64, 64, 64, 16],
  '64³ × 32': [64, 64, 64, 32],
  '64⁴': [64, 64, 64, 64],
};

const $ = (selector) => document.querySelector(selector);
const reduceMotion = window.matchMedia?.('(prefers-reduced-motion: reduce)').matches ?? false;

const state = {
  field: structuredClone(DEFAULT_FIELD),
  lattice: '32⁴',
  sliceZ: 0,
  playing: !reduceMotion,
  speed: 1,
  t: 0,
};
const stats = { fieldMs: 0, frameMs: 0, fps: 0, energy: null };
let info = null;
let speedScale = 1;
let generation = Promise.resolve();
let sliceBusy = false;

const engine = new Engine({
  onError: (message) => showMessage(message),
  onRestart: () => { regenerate(); },
});
const view = new SliceView($('#canvas'), { legend: $('#speed-legend') });

function describe(report) {
  const [nx, ny, nz, nt] = info.size;
  const lines = [
    `${nx}×${ny}×${nz}×${nt} field generated in ${info.fieldMs.toFixed(0)} ms`,
    `energy ½⟨|u|²⟩ ${report.energy.toFixed(4)} (law ${report.energy_expected.toFixed(4)})`,
  ];
  if (report.slope !== null) {
    lines.push(`inertial slope ${report.slope.toFixed(3)} (law ${report.slope_expected.toFixed(3)})`);
  }
  lines.push(`divergence ratio ${report.divergence_ratio.toExponential(1)}`);
  $('#status').textContent = lines.join('\n');
}

/**
 * Generates the field for `state.field`: resolves once it is shown, or rejects with the core's
 * refusal of its parameters (the engine checks them; the page writes none of their ranges),
 * which the page shows too.
 */
function generate() {
  const params = structuredClone(state.field);
  const run = generation
    .catch(() => {})
    .then(async () => {
      const loaded = await engine.request('load', { scene: fieldScene(params) }, { onProgress: (p) => showProgress(p.progress, `Generating field: ${p.stage}`) });
      info = { size: loaded.size, fieldMs: loaded.fieldMs };
      stats.fieldMs = info.fieldMs;
      const report = await engine.request('fieldStats');
      stats.energy = report.energy;
      speedScale = 2.5 * report.rms_speed / Math.sqrt(3);
      describe(report);
      await drawSlice();
    });
  generation = run.catch((err) => {
    showProgress(1, 'failed');
    showMessage(err.message);
  });
  return run;
}

/** Generates the field for `state.field`; resolves once it is shown or refused. */
function regenerate() {
  generate().catch(() => {});
  return generation;
}

async function drawSlice() {
  if (!info || sliceBusy) return;
  sliceBusy = true;
  try {
    const slice = await engine.request('slice', {
      z: state.sliceZ, t: state.t, width: SLICE_RES, height: SLICE_RES,
    });
    view.update(slice.data, slice.width, slice.height, speedScale);
    view.render();
  } finally {
    sliceBusy = false;
  }
}

function resize() {
  const canvas = $('#canvas');
  view.resize(canvas.clientWidth, canvas.clientHeight);
  view.render();
}

let last = performance.now();
function frame(now) {
  const dt = Math.min((now - last) / 1000, 0.1);
  last = now;
  if (state.playing && info) {
    state.t = (state.t + (dt * state.speed * info.size[3]) / SECONDS_PER_PERIOD) % info.size[3];
    const start = performance.now();
    drawSlice().then(() => {
      stats.frameMs = performance.now() - start;
    });
    stats.fps = stats.fps * 0.9 + (dt > 0 ? 0.1 / dt : 0);
  }
  requestAnimationFrame(frame);
}

function buildControls() {
  const gui = new GUI({ container: $('#panel'), title: 'Small-scale turbulence', injectStyles: false });
  const spectrum = gui.addFolder('Spectrum (paper §3.2)');
  const s = state.field.spectrum;
  spectrum.add(s, 'law', LAWS).name('law').onFinishChange(regenerate);
  spectrum.add(s, 'epsilon', 0.01, 10, 0.01).name('ε (cascade rate)').onFinishChange(regenerate);
  const kController = spectrum.add(s, 'k_inertial', 0.5, 15, 0.5).name('k inertial').onFinishChange(regenerate);
  spectrum.add(s, 'sigma', 0, 4, 0.05).name('σ (temporal spread)').onFinishChange(regenerate);
  const lattice = gui.addFolder('Lattice');
  lattice.add(state, 'lattice', Object.keys(LATTICES)).name('size').onFinishChange((name) => {
    state.field.size = [...LATTICES[name]];
    const kMax = maxInertial(state.field.size);
    kController.max(kMax);
    if (s.k_inertial > kMax) s.k_inertial = kMax;
    kController.updateDisplay();
    state.sliceZ = Math.min(state.sliceZ, state.field.size[2] - 1);
    zController.max(state.field.size[2] - 1).updateDisplay();
    regenerate();
  });
  lattice.add(state.field, 'seed', 0, 100000, 1).name('seed').onFinishChange(regenerate);
  const viewFolder = gui.addFolder('View');
  const zController = viewFolder.add(state, 'sliceZ', 0, state.field.size[2] - 1, 0.25).name('slice z (lattice)').onChange(() => drawSlice());
  viewFolder.add(state, 'playing').name('play');
  viewFolder.add(state, 'speed', 0, 4, 0.05).name('time speed');
  $('#panel').append($('#status'));
  return gui;
}

buildControls();
new ResizeObserver(resize).observe($('#canvas'));
resize();
const ready = regenerate();
requestAnimationFrame(frame);

/** Scripting handle for tests and the console (the playground has the full browser API of docs/FORMATS.md). */
window.windfield = {
  ready,
  getField: () => structuredClone(state.field),
  setField: (field) => {
    // A refused field leaves the last good one in place, here as in the engine.
    const previous = state.field;
    const asked = structuredClone(field);
    state.field = asked;
    return generate().catch((err) => {
      if (state.field === asked) state.field = previous;
      throw err;
    });
  },
  pause: () => { state.playing = false; },
  play: () => { state.playing = true; },
  stats: () => ({ ...stats, size: info?.size ?? null }),
  fieldStats: (spectrum) => engine.request('fieldStats', { spectrum }),
  sample: (x, y, z, t) => engine.request('sample', { x, y, z, t }),
};
