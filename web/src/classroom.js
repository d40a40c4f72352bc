// The classroom page: the field's measured spectrum and temporal spread against the paper's
// laws, a slice of the field, the Figure 1 demo (grid against blobs), and one plume shown with
// turbulence off, on, and carried by the mean wind. `window.classroom` exposes the plotted data
// (`ready`: the plots and Figure 1 drawn; `snapshots`: Figure 1's row filled; `sideBySide`: the
// three players, which load as they near the viewport, running their variants).

import './embed.js';
import init, { Figure1Demo } from '../pkg/windfield.js';
import { Engine } from './engine/client.js';
import { showMessage } from './page-ui.js';
import { SliceView } from './views/slice-view.js';
import { viridis } from './colormap.js';
import { DEFAULT_FIELD } from './field-params.js';

const $ = (s) => document.querySelector(s);
const reduceMotion = window.matchMedia?.('(prefers-reduced-motion: reduce)').matches ?? false;

/** Log-log (or linear) scatter of `points` with the curve `line`, on a 2-D canvas. */
function plot(canvas, { points, line, xLabel, yLabel, log = true }) {
  const ctx = canvas.getContext('2d');
  const { width: w, height: h } = canvas;
  const pad = 44;
  const f = (v) => (log ? Math.log10(v) : v);
  const all = [...points, ...line].filter(([x, y]) => x > 0 && (!log || y > 0));
  const xs = all.map(([x]) => f(x));
  const ys = all.map(([, y]) => f(y));
  const [x0, x1] = [Math.min(...xs), Math.max(...xs)];
  const [y0, y1] = [Math.min(...ys), Math.max(...ys)];
  const px = (x) => pad + ((f(x) - x0) / (x1 - x0 || 1)) * (w - 2 * pad);
  const py = (y) => h - pad - ((f(y) - y0) / (y1 - y0 || 1)) * (h - 2 * pad);
  ctx.fillStyle = '#101418';
  ctx.fillRect(0, 0, w, h);
  ctx.strokeStyle = '#556';
  ctx.strokeRect(pad, pad, w - 2 * pad, h - 2 * pad);
  ctx.fillStyle = '#ccd';
  ctx.font = '13px sans-serif';
  ctx.fillText(xLabel, w / 2 - 20, h - 12);
  ctx.save();
  ctx.translate(14, h / 2 + 30);
  ctx.rotate(-Math.PI / 2);
  ctx.fillText(yLabel, 0, 0);
  ctx.restore();
  ctx.strokeStyle = '#f0a040';
  ctx.lineWidth = 2;
  ctx.beginPath();
  line.filter(([x, y]) => x > 0 && (!log || y > 0)).forEach(([x, y], i) => (i ? ctx.lineTo(px(x), py(y)) : ctx.moveTo(px(x), py(y))));
  ctx.stroke();
  ctx.fillStyle = '#7fc8ff';
  for (const [x, y] of points) {
    if (x <= 0 || (log && y <= 0)) continue;
    ctx.beginPath();
    ctx.arc(px(x), py(y), 3, 0, 2 * Math.PI);
    ctx.fill();
  }
}

/** The plotted series from a `windfield stats` report (the shells inside the inertial range). */
export function spectrumSeries(report) {
  const shells = report.shells.filter((s) => s.energy_expected > 0);
  return {
    measured: shells.map((s) => [s.k, s.energy]),
    target: shells.map((s) => [s.k, s.energy_expected]),
    spread: shells.map((s) => [s.k, s.temporal_spread]),
    spreadTarget: shells.map((s) => [s.k, s.temporal_spread_expected]),
  };
}

const classroom = { report: null, series: null, figure1: null, figure1Loops: 0, ready: null, snapshots: null, sideBySide: null };
window.classroom = classroom;

async function fieldLesson() {
  const engine = new Engine({ onError: (m) => showMessage(m) });
  await engine.request('load', { scene: { version: 1, seed: DEFAULT_FIELD.seed, field: { size: DEFAULT_FIELD.size, spectrum: DEFAULT_FIELD.spectrum } } });
  const report = await engine.request('fieldStats');
  classroom.report = report;
  classroom.series = spectrumSeries(report);
  const s = classroom.series;
  plot($('#spectrum'), { points: s.measured, line: s.target, xLabel: 'k', yLabel: 'E(k)' });
  plot($('#spread'), { points: s.spread, line: s.spreadTarget, xLabel: 'k', yLabel: 'spread', log: false });
  $('#spectrum-caption').textContent = `Shell energy E(k), log-log: fitted slope ${report.slope.toFixed(3)} (Kolmogorov −5/3 ≈ −1.667); energy ${(report.energy_ratio * 100).toFixed(1)} % of the target.`;
  const view = new SliceView($('#slice'));
  let t = 0;
  const draw = async () => {
    const slice = await engine.request('slice', { z: 0, t, width: 64, height: 64 });
    view.update(slice.data, slice.width, slice.height, (2.5 * report.rms_speed) / Math.sqrt(3));
    view.render();
  };
  await draw();
  if (!reduceMotion) {
    const tick = async () => {
      t = (t + 0.05) % 32;
      await draw().catch(() => {});
      requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  }
}

/** Draws an n×n density (row 0 at the bottom) into a canvas with the viridis map. */
function paint(canvas, data, n, scale) {
  const ctx = canvas.getContext('2d');
  const image = ctx.createImageData(n, n);
  for (let j = 0; j < n; j++) {
    for (let i = 0; i < n; i++) {
      const o = 4 * ((n - 1 - j) * n + i);
      viridis(data[j * n + i] / scale, image.data, o);
      image.data[o + 3] = 255;
    }
  }
  const off = new OffscreenCanvas(n, n);
  off.getContext('2d').putImageData(image, 0, 0);
  ctx.imageSmoothingEnabled = false;
  ctx.drawImage(off, 0, 0, canvas.width, canvas.height);
}

/** Figure 1's snapshot times (s): the row of panels, as in the paper's figure. */
export const FIGURE1_TIMES = [0, 0.25, 0.5, 1, 2];
/** The live panels play the first `FIGURE1_TIMES.at(-1)` seconds, hold this long (s), and restart. */
const FIGURE1_HOLD = 1;
/** Simulated seconds per animation frame of the live panels. */
const FIGURE1_STEP = 1 / 30;

/**
 * Figure 1: the live grid and blob panels play the square's first seconds and restart, so its
 * evolution stays in view; on the way they fill a row of snapshots at fixed times for each
 * model. With reduced motion the panels are not animated: the demo runs in the background and
 * the panels show the latest snapshot, once.
 */
async function figure1Lesson() {
  await init();
  let demo = new Figure1Demo('{}');
  classroom.figure1 = demo;
  classroom.figure1Loops = 0;
  const end = FIGURE1_TIMES.at(-1);
  let next = 0;
  let held = 0;
  let snapshotsDone;
  classroom.snapshots = new Promise((resolve) => { snapshotsDone = resolve; });
  const live = () => {
    const n = demo.n();
    paint($('#grid'), demo.grid(), n, 1);
    paint($('#blobs'), demo.blobs(), n, 1);
    $('#grid-caption').textContent = `Grid, t = ${demo.time().toFixed(2)} s, mass ${demo.gridMass().toFixed(5)}`;
    $('#blobs-caption').textContent = `Blobs, t = ${demo.time().toFixed(2)} s, mass ${demo.blobMass().toFixed(5)}`;
  };
  /** Paints the snapshots the demo has reached (the same on every pass: the demo is deterministic). */
  const snapshot = () => {
    while (next < FIGURE1_TIMES.length && demo.time() >= FIGURE1_TIMES[next] - 1e-9) {
      const n = demo.n();
      paint($(`#fig1-grid-${next}`), demo.grid(), n, 1);
      paint($(`#fig1-blobs-${next}`), demo.blobs(), n, 1);
      next += 1;
      if (reduceMotion) live();
      if (next === FIGURE1_TIMES.length) snapshotsDone();
    }
  };
  /** Steps to the next snapshot time, at most one frame's step. */
  const advance = () => {
    const target = next < FIGURE1_TIMES.length ? FIGURE1_TIMES[next] : Infinity;
    demo.step(Math.min(FIGURE1_STEP, target - demo.time()));
  };
  let ticking = false;
  const schedule = () => {
    if (ticking) return;
    ticking = true;
    requestAnimationFrame(tick);
  };
  const restart = () => {
    demo.free();
    demo = new Figure1Demo('{}');
    classroom.figure1 = demo;
    next = 0;
    held = 0;
    snapshot();
    live();
    schedule();
  };
  $('#fig1-reset').addEventListener('click', () => {
    classroom.figure1Loops += 1;
    restart();
  });
  function tick() {
    ticking = false;
    if (demo.time() < end - 1e-9) {
      advance();
      snapshot();
      if (!reduceMotion) live();
    } else if (!reduceMotion && ++held > FIGURE1_HOLD * 60) {
      classroom.figure1Loops += 1;
      restart();
    }
    if (!reduceMotion || next < FIGURE1_TIMES.length) schedule();
  }
  snapshot();
  live();
  schedule();
}

/**
 * Section 3's players load as they near the viewport; each then gets its variant of the scene.
 * Resolves when all three run their variants.
 */
async function sideBySide() {
  const players = ['off', 'on', 'carried'].map((id) => $(`#${id}`));
  return Promise.all(players.map(async (p) => {
    await p.ready;
    const base = p.getScene();
    const variants = {
      off: { ...base, field: { ...base.field, amplitude: 0 } },
      on: base,
      carried: { ...base, field: { ...base.field, carried_by_wind: true } },
    };
    if (p.id !== 'on') await p.setScene(variants[p.id]);
  }));
}

const fail = (e) => {
  showMessage(e.message);
  throw e;
};
classroom.ready = Promise.all([fieldLesson(), figure1Lesson()]).catch(fail);
classroom.sideBySide = sideBySide().catch(fail);
