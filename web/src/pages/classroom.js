// The classroom page: the field's measured spectrum and temporal spread against the paper's
// laws, a slice of the field, the Figure 1 demo (grid against blobs), one plume shown with
// turbulence off, on, and carried by the large scales, and the wind's streamlines round a solid
// sphere beside the closed form, and one scene under the kinematic and the physical large
// scales side by side. `window.classroom` exposes the plotted data (`ready`: the plots, Figure 1
// and the sphere drawn; `axes`: each chart's tick values as drawn; `snapshots`: Figure 1's row
// filled; `sphere`: the sphere's streamlines; `sideBySide`: the three players, which load as
// they near the viewport, running their variants; `largeScales`: the two players of the large
// scales, loaded as they near the viewport).

import '../embed.js';
import init, { Figure1Demo, sphereFlow } from '../../pkg/windfield_full.js';
import { viridis } from '../charts/colormap.js';
import { ColourBar } from '../charts/colour-bar.js';
import { CHART, drawChart, linearAxis, logAxis } from '../charts/plot-axes.js';
import { Engine } from '../engine/client.js';
import { SliceView } from '../views/slice-view.js';
import { DEFAULT_FIELD, fieldScene } from './field-params.js';
import { showMessage } from './page-ui.js';

const $ = (s) => document.querySelector(s);
const reduceMotion = window.matchMedia?.('(prefers-reduced-motion: reduce)').matches ?? false;

/** The plotted series from a `windfield stats` report (the shells inside the inertial range). */
function spectrumSeries(report) {
  const shells = report.shells.filter((s) => s.energy_expected > 0);
  return {
    measured: shells.map((s) => [s.k, s.energy]),
    target: shells.map((s) => [s.k, s.energy_expected]),
    spread: shells.map((s) => [s.k, s.temporal_spread]),
    spreadTarget: shells.map((s) => [s.k, s.temporal_spread_expected]),
  };
}

const classroom = { report: null, series: null, axes: {}, figure1: null, figure1Loops: 0, ready: null, snapshots: null, sphere: null, sideBySide: null };
window.classroom = classroom;

/**
 * Draws the chart `spec` (see `drawChart`) into the canvas `#id`, again whenever the canvas is
 * resized; records the tick values drawn in `classroom.axes[id]` and the canvas's data-x-ticks
 * and data-y-ticks.
 */
function chart(id, spec) {
  const canvas = $(`#${id}`);
  const draw = () => {
    if (!canvas.clientWidth) return;
    const labels = drawChart(canvas, spec);
    classroom.axes[id] = { x: labels.xLabels, y: labels.yLabels, xTitle: spec.x.title, yTitle: spec.y.title };
    canvas.dataset.xTicks = labels.xLabels.join(' ');
    canvas.dataset.yTicks = labels.yLabels.join(' ');
  };
  draw();
  new ResizeObserver(draw).observe(canvas);
}

/**
 * The field's export buttons: the wind at t = 0, mapped to the world as a scene's field with the
 * defaults maps it, as OpenVDB (`wind.vdb`) or as a raw RGB32F 3-D texture with its JSON
 * description (`wind.rgb32f`, `wind.rgb32f.json`): the bytes `windfield generate` writes.
 * `classroom.windGrid(format)` gives them to a test.
 */
function takeTheWind(engine) {
  classroom.windGrid = (format) => engine.request('windGrid', { format });
  const save = (name, parts) => {
    const a = document.createElement('a');
    a.href = URL.createObjectURL(new Blob(parts));
    a.download = name;
    a.click();
    setTimeout(() => URL.revokeObjectURL(a.href), 10_000);
  };
  $('#wind-vdb').addEventListener('click', async () => {
    save('wind.vdb', [(await classroom.windGrid('vdb')).bytes]);
  });
  $('#wind-texture').addEventListener('click', async () => {
    const { bytes, description } = await classroom.windGrid('rgb32f');
    save('wind.rgb32f', [bytes]);
    save('wind.rgb32f.json', [`${JSON.stringify(description, null, 2)}\n`]);
  });
}

async function fieldLesson() {
  const engine = new Engine({ onError: (m) => showMessage(m) });
  await engine.request('load', { scene: fieldScene(DEFAULT_FIELD) });
  const report = await engine.request('fieldStats');
  classroom.report = report;
  takeTheWind(engine);
  classroom.series = spectrumSeries(report);
  const s = classroom.series;
  const ys = (...lists) => lists.flat().map(([, y]) => y);
  const ks = s.measured.map(([k]) => k);
  const kAxis = (log) => ({
    ...(log ? logAxis(Math.min(...ks), Math.max(...ks)) : linearAxis(0, Math.max(...ks))),
    title: 'wave number k (cycles per period)',
  });
  const energies = ys(s.measured, s.target).filter((e) => e > 0);
  const spreads = ys(s.spread, s.spreadTarget);
  chart('spectrum', {
    x: kAxis(true),
    y: { ...logAxis(Math.min(...energies), Math.max(...energies)), title: 'E(k) (lattice units)' },
    series: [
      { points: s.target, style: 'line', colour: CHART.line, label: 'law (slope −5/3)' },
      { points: s.measured, style: 'dots', colour: CHART.dots, label: 'measured shells' },
    ],
  });
  chart('spread', {
    x: kAxis(false),
    y: { ...linearAxis(0, Math.max(...spreads)), title: 'RMS ω (cycles per period)' },
    series: [
      { points: s.spreadTarget, style: 'line', colour: CHART.line, label: 'law kσ (clipped)' },
      { points: s.spread, style: 'dots', colour: CHART.dots, label: 'measured shells' },
    ],
    key: 'bottom-right',
  });
  $('#spectrum-caption').textContent = `Shell energy E(k), log-log: fitted slope ${report.slope.toFixed(3)} (Kolmogorov −5/3 ≈ −1.667); energy ${(report.energy_ratio * 100).toFixed(1)} % of the target.`;
  const slice = $('#slice');
  const view = new SliceView(slice, { legend: $('#slice-scale') });
  new ResizeObserver(() => {
    view.resize(slice.clientWidth, slice.clientHeight);
    view.render();
  }).observe(slice);
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
const FIGURE1_TIMES = [0, 0.25, 0.5, 1, 2];
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
  new ColourBar($('#density-legend'), { title: 'density ρ / ρ₀, ρ₀ the square\'s initial density' }).set(0, 1);
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
    // Nothing to step where the demo is at or past the target already (a step from elsewhere).
    demo.step(Math.max(0, Math.min(FIGURE1_STEP, target - demo.time())));
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

/** Streamlines and the sphere's outline per panel: the core's wind, and the closed form. */
const SPHERE_LINES = 13;
const SPHERE_POINTS = 240;

/** `flat` (x, y pairs, `points` a line) as polylines of [x, y]. */
function polylines(flat, points) {
  const lines = [];
  for (let i = 0; i < flat.length; i += 2 * points) {
    lines.push(Array.from({ length: points }, (_, k) => [flat[i + 2 * k], flat[i + 2 * k + 1]]));
  }
  return lines;
}

/**
 * The wind round a solid sphere: streamlines of the core's wind (computed by the core,
 * `sphereFlow`) beside those of the potential flow around a sphere.
 */
async function sphereLesson() {
  await init();
  const flow = sphereFlow(SPHERE_LINES, SPHERE_POINTS);
  const outline = Array.from({ length: 121 }, (_, k) => [Math.cos((k * Math.PI) / 60), Math.sin((k * Math.PI) / 60)]);
  classroom.sphere = {
    core: polylines(flow.core, flow.points),
    closedForm: polylines(flow.closedForm, flow.points),
    largestGap: flow.largestGap,
  };
  const axes = {
    x: { ...linearAxis(-3.5, 3.5, { fixed: true }), title: 'x / a (along the wind)' },
    y: { ...linearAxis(-2.5, 2.5, { fixed: true }), title: 'y / a' },
  };
  const panel = (id, lines, label) => chart(id, {
    ...axes,
    series: [
      { lines, style: 'line', colour: CHART.line, label },
      { points: outline, style: 'line', colour: CHART.dots, label: 'solid sphere, radius a' },
    ],
  });
  panel('sphere-core', classroom.sphere.core, 'the core\'s wind');
  panel('sphere-closed', classroom.sphere.closedForm, 'potential flow');
  // A gap below the caption's four decimals is written with a power of ten (3.2 × 10⁻⁶), not as 0.0000.
  const superscript = (digits) => [...digits].map((d) => '⁰¹²³⁴⁵⁶⁷⁸⁹'[d]).join('');
  const gap = flow.largestGap === 0 ? '0'
    : flow.largestGap >= 1e-4 ? flow.largestGap.toFixed(4)
      : flow.largestGap.toExponential(1).replace(/e-(\d+)$/, (_, exp) => ` × 10⁻${superscript(exp)}`);
  $('#sphere-caption').textContent = `Streamlines traced by the fourth-order Runge–Kutta rule through each wind; the two sets part by at most ${gap} a.`;
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
      carried: { ...base, field: { ...base.field, carried: true } },
    };
    if (p.id !== 'on') await p.setScene(variants[p.id]);
  }));
}

/**
 * Section 5's two players (`public/classroom/ceiling-kinematic.json` and
 * `ceiling-physical.json`: the same scene without and with a flow) load as they near the
 * viewport. Resolves when both are ready.
 */
async function largeScales() {
  await Promise.all(['kinematic', 'physical'].map((id) => $(`#${id}`).ready));
}

const fail = (e) => {
  showMessage(e.message);
  throw e;
};
classroom.ready = Promise.all([fieldLesson(), figure1Lesson(), sphereLesson()]).catch(fail);
classroom.sideBySide = sideBySide().catch(fail);
classroom.largeScales = largeScales().catch(fail);
