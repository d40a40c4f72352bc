// Charts on a 2-D canvas: linear and logarithmic (decade) axes with tick values, axis titles
// with units, dots and lines, and a key; drawn at the device pixel ratio, for the dark theme.

/** The theme's colours for charts. */
export const CHART = {
  background: '#101418',
  frame: '#5b6673',
  grid: '#222b34',
  gridMajor: '#33404c',
  tick: '#c5ced6',
  title: '#e6e9ec',
  dots: '#7fc8ff',
  line: '#f0a040',
  font: 'system-ui, -apple-system, "Segoe UI", sans-serif',
};

/**
 * Sizes `canvas`'s backing store to its CSS box times the device pixel ratio; returns the 2-D
 * context, scaled to draw in CSS pixels, and the box's size.
 */
export function fitCanvas(canvas) {
  const ratio = window.devicePixelRatio || 1;
  const width = canvas.clientWidth || canvas.width;
  const height = canvas.clientHeight || canvas.height;
  const bw = Math.max(1, Math.round(width * ratio));
  const bh = Math.max(1, Math.round(height * ratio));
  if (canvas.width !== bw || canvas.height !== bh) {
    canvas.width = bw;
    canvas.height = bh;
  }
  const ctx = canvas.getContext('2d');
  ctx.setTransform(bw / width, 0, 0, bh / height, 0, 0);
  return { ctx, width, height };
}

const SUPERSCRIPT = { '-': '⁻', 0: '⁰', 1: '¹', 2: '²', 3: '³', 4: '⁴', 5: '⁵', 6: '⁶', 7: '⁷', 8: '⁸', 9: '⁹' };

/** A tick value as people write it: plain decimals from 0.001 to 99999, else m×10ⁿ. */
export function formatTick(v) {
  if (v === 0) return '0';
  const a = Math.abs(v);
  if (a >= 1e-3 && a < 1e5) return String(Number(v.toPrecision(3))).replace('-', '−');
  const n = Math.floor(Math.log10(a) + 1e-9);
  const m = Number((v / 10 ** n).toPrecision(2));
  const power = `10${String(n).split('').map((c) => SUPERSCRIPT[c]).join('')}`;
  return m === 1 ? power : `${String(m).replace('-', '−')}×${power}`;
}

/** The step of about `count` ticks over a span: 1, 2 or 5 times a power of ten. */
function niceStep(span, count) {
  const raw = span / Math.max(count, 1);
  const p = 10 ** Math.floor(Math.log10(raw));
  const m = raw / p;
  return (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10) * p;
}

/**
 * A linear axis over [lo, hi]: the range widened to whole steps (unless `fixed`) and its ticks,
 * about `count` of them.
 */
export function linearAxis(lo, hi, { count = 5, fixed = false } = {}) {
  if (!(hi > lo)) [lo, hi] = [lo - 1, hi + 1];
  const step = niceStep(hi - lo, count);
  const from = fixed ? lo : Math.floor(lo / step + 1e-9) * step;
  const to = fixed ? hi : Math.ceil(hi / step - 1e-9) * step;
  const ticks = [];
  for (let v = Math.ceil(from / step - 1e-9) * step; v <= to + step * 1e-9; v += step) {
    ticks.push({ value: Math.abs(v) < step * 1e-9 ? 0 : Number(v.toPrecision(12)), major: true, label: true });
  }
  return { lo: from, hi: to, log: false, ticks };
}

/** Which labels of a decade go first when they would collide: 1, then 2 and 5, then 3, then the rest. */
const RANK = [0, 0, 1, 2, 3, 1, 3, 3, 3, 3];

/**
 * A logarithmic axis over [lo, hi] (both > 0), widened by `margin` (a factor) at each end:
 * major ticks at the decades, minor ones at 2–9 times them. Labels go on the decades and on
 * 2 and 5 times them; on a span under about a decade and a half, on every minor tick too
 * (the chart drops those that would collide).
 */
export function logAxis(lo, hi, { margin = 1.12 } = {}) {
  if (!(hi > lo)) [lo, hi] = [lo / 2, hi * 2];
  const from = lo / margin;
  const to = hi * margin;
  const dense = Math.log10(to / from) < 1.5;
  const ticks = [];
  for (let n = Math.floor(Math.log10(from)); n <= Math.ceil(Math.log10(to)); n++) {
    for (let m = 1; m <= 9; m++) {
      const value = Number((m * 10 ** n).toPrecision(6));
      if (value < from || value > to) continue;
      ticks.push({ value, major: m === 1, label: m === 1 || m === 2 || m === 5 || dense, rank: RANK[m] });
    }
  }
  return { lo: from, hi: to, log: true, ticks };
}

/** Position along an axis, 0 at `lo` and 1 at `hi`. */
function fraction(axis, v) {
  return axis.log ? Math.log10(v / axis.lo) / Math.log10(axis.hi / axis.lo) : (v - axis.lo) / (axis.hi - axis.lo);
}

/** The labelled ticks, highest rank first, without any that would overlap one already kept. */
function spacedLabels(ticks, place, size, gap) {
  const kept = [];
  const order = ticks.filter((t) => t.label).sort((a, b) => (a.rank ?? 0) - (b.rank ?? 0));
  for (const t of order) {
    const at = place(t.value);
    const half = size(t) / 2 + gap / 2;
    if (kept.every((k) => Math.abs(k.at - at) >= half + k.half)) kept.push({ tick: t, at, half });
  }
  return kept.map((k) => k.tick);
}

/**
 * Draws a chart into `canvas`: `x` and `y` are axes (from `linearAxis` or `logAxis`) with a
 * `title` (name and unit); `series` is a list of `{ points: [[x, y], …], style: 'dots' | 'line',
 * colour, label }` (a line series may give `lines`, several polylines of one colour and one row
 * of the key, instead of `points`); `key` is where the series' key goes: 'top-right' or
 * 'bottom-right'.
 */
export function drawChart(canvas, { x, y, series, key = 'top-right' }) {
  const { ctx, width: w, height: h } = fitCanvas(canvas);
  const small = w < 360;
  const fontSize = small ? 11 : 12;
  const font = `${fontSize}px ${CHART.font}`;
  ctx.font = font;
  const yLabels = y.ticks.filter((t) => t.label).map((t) => ctx.measureText(formatTick(t.value)).width);
  const left = Math.ceil(fontSize + 12 + Math.max(0, ...yLabels) + 6);
  const right = 14;
  const top = 12;
  const bottom = fontSize * 2 + 22;
  const plotW = w - left - right;
  const plotH = h - top - bottom;
  const px = (v) => left + fraction(x, v) * plotW;
  const py = (v) => top + (1 - fraction(y, v)) * plotH;
  const inside = ([a, b]) => a >= x.lo && a <= x.hi && b >= y.lo && b <= y.hi && (!x.log || a > 0) && (!y.log || b > 0);

  ctx.fillStyle = CHART.background;
  ctx.fillRect(0, 0, w, h);

  // Grid lines at every tick, brighter at the majors; ticks outside the frame.
  ctx.lineWidth = 1;
  const segment = (colour, x0, y0, x1, y1) => {
    ctx.strokeStyle = colour;
    ctx.beginPath();
    ctx.moveTo(x0, y0);
    ctx.lineTo(x1, y1);
    ctx.stroke();
  };
  const gridColour = (axis, t) => (t.major && axis.log ? CHART.gridMajor : CHART.grid);
  for (const t of x.ticks) {
    const X = Math.round(px(t.value)) + 0.5;
    segment(gridColour(x, t), X, top, X, top + plotH);
    segment(CHART.frame, X, top + plotH, X, top + plotH + (t.major || t.label ? 5 : 3));
  }
  for (const t of y.ticks) {
    const Y = Math.round(py(t.value)) + 0.5;
    segment(gridColour(y, t), left, Y, left + plotW, Y);
    segment(CHART.frame, left, Y, left - (t.major || t.label ? 5 : 3), Y);
  }
  ctx.strokeStyle = CHART.frame;
  ctx.strokeRect(left + 0.5, top + 0.5, plotW - 1, plotH - 1);

  // Tick values.
  ctx.fillStyle = CHART.tick;
  ctx.textAlign = 'center';
  ctx.textBaseline = 'top';
  const xKept = spacedLabels(x.ticks, px, (t) => ctx.measureText(formatTick(t.value)).width, 8);
  for (const t of xKept) ctx.fillText(formatTick(t.value), px(t.value), top + plotH + 7);
  ctx.textAlign = 'right';
  ctx.textBaseline = 'middle';
  const yKept = spacedLabels(y.ticks, py, () => fontSize, 8);
  for (const t of yKept) ctx.fillText(formatTick(t.value), left - 7, py(t.value));

  // Axis titles.
  ctx.fillStyle = CHART.title;
  ctx.textAlign = 'center';
  ctx.textBaseline = 'bottom';
  ctx.fillText(x.title, left + plotW / 2, h - 4);
  ctx.save();
  ctx.translate(4, top + plotH / 2);
  ctx.rotate(-Math.PI / 2);
  ctx.textBaseline = 'top';
  ctx.fillText(y.title, 0, 0);
  ctx.restore();

  // The series, clipped to the frame.
  ctx.save();
  ctx.beginPath();
  ctx.rect(left, top, plotW, plotH);
  ctx.clip();
  for (const s of series) {
    const shown = (points) => points.filter(([a, b]) => (!x.log || a > 0) && (!y.log || b > 0));
    const pts = shown(s.points ?? []);
    ctx.fillStyle = s.colour;
    ctx.strokeStyle = s.colour;
    if (s.style === 'line') {
      ctx.lineWidth = 2;
      for (const line of s.lines ? s.lines.map(shown) : [pts]) {
        ctx.beginPath();
        line.forEach(([a, b], i) => (i ? ctx.lineTo(px(a), py(b)) : ctx.moveTo(px(a), py(b))));
        ctx.stroke();
      }
    } else {
      for (const p of pts.filter(inside)) {
        ctx.beginPath();
        ctx.arc(px(p[0]), py(p[1]), 3, 0, 2 * Math.PI);
        ctx.fill();
      }
    }
  }
  ctx.restore();

  // The key: one row per series, a sample of its mark and its label.
  ctx.font = font;
  const rowH = fontSize + 6;
  const keyW = Math.max(...series.map((s) => ctx.measureText(s.label).width)) + 30;
  const kx = left + plotW - keyW - 6;
  const ky = key === 'top-right' ? top + 6 : top + plotH - 6 - rowH * series.length - 4;
  ctx.fillStyle = 'rgba(16, 20, 24, 0.85)';
  ctx.fillRect(kx, ky, keyW, rowH * series.length + 4);
  series.forEach((s, i) => {
    const cy = ky + 2 + rowH * i + rowH / 2;
    ctx.fillStyle = s.colour;
    ctx.strokeStyle = s.colour;
    if (s.style === 'line') {
      ctx.lineWidth = 2;
      ctx.beginPath();
      ctx.moveTo(kx + 6, cy);
      ctx.lineTo(kx + 22, cy);
      ctx.stroke();
    } else {
      ctx.beginPath();
      ctx.arc(kx + 14, cy, 3, 0, 2 * Math.PI);
      ctx.fill();
    }
    ctx.fillStyle = CHART.title;
    ctx.textAlign = 'left';
    ctx.textBaseline = 'middle';
    ctx.fillText(s.label, kx + 27, cy);
  });
  const inOrder = (kept) => kept.map((t) => t.value).sort((a, b) => a - b).map(formatTick);
  return { xLabels: inOrder(xKept), yLabels: inOrder(yKept) };
}
