// The classroom page: the field's measured spectrum and temporal spread against the paper's
// laws, a slice of the field, the Figure 1 demo (grid against blobs), and one plume shown with
// turbulence off, on, and carried by the mean wind. `window.classroom` exposes the plotted data.

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

const classroom = { report: null, series: null, figure1: null, ready: null };
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

async function figure1Lesson() {
  await init();
  let demo = new Figure1Demo('{}');
  classroom.figure1 = demo;
  const frame = () => {
    const n = demo.n();
    paint($('#grid'), demo.grid(), n, 1);
    paint($('#blobs'), demo.blobs(), n, 1);
    $('#grid-caption').textContent = `Grid, t = ${demo.time().toFixed(2)} s, mass ${demo.gridMass().toFixed(5)}`;
    $('#blobs-caption').textContent = `Blobs, t = ${demo.time().toFixed(2)} s, mass ${demo.blobMass().toFixed(5)}`;
  };
  $('#fig1-reset').addEventListener('click', () => {
    demo.free();
    demo = new Figure1Demo('{}');
    classroom.figure1 = demo;
    frame();
  });
  frame();
  if (!reduceMotion) {
    const tick = () => {
      if (demo.time() < 12) {
        demo.step(1 / 30);
        frame();
      }
      requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  }
}

async function sideBySide() {
  const players = ['off', 'on', 'carried'].map((id) => $(`#${id}`));
  await Promise.all(players.map((p) => p.ready));
  const base = players[0].getScene();
  const variants = {
    off: { ...base, field: { ...base.field, amplitude: 0 } },
    on: base,
    carried: { ...base, field: { ...base.field, carried_by_wind: true } },
  };
  await Promise.all(players.map((p) => p.setScene(variants[p.id])));
}

classroom.ready = Promise.all([fieldLesson(), figure1Lesson(), sideBySide()]).catch((e) => {
  showMessage(e.message);
  throw e;
});
