// A colour bar: the viridis map from a minimum to a maximum value, with tick values and a title
// naming the quantity and its unit, drawn on a 2-D canvas at the device pixel ratio. With
// `extend`, a pointed end says that values above the maximum take the top colour.

import { VIRIDIS_CSS } from './colormap.js';
import { CHART, fitCanvas, formatTick, linearAxis } from './plot-axes.js';

export class ColourBar {
  /**
   * @param {HTMLCanvasElement} canvas sized by CSS (about 2.8 rem tall)
   * @param {{ title: string, unit?: string, extend?: boolean }} options the quantity, its unit
   *   (left out for a ratio) and whether values above the maximum are clipped to the top colour
   */
  constructor(canvas, { title, unit = '', extend = false }) {
    this.canvas = canvas;
    this.title = title;
    this.unit = unit;
    this.extend = extend;
    this.min = null;
    this.max = null;
    canvas.setAttribute('role', 'img');
    new ResizeObserver(() => this.draw()).observe(canvas);
  }

  /** Shows the map from `min` to `max`; redraws only when they change. */
  set(min, max) {
    if (min === this.min && max === this.max) return;
    this.min = min;
    this.max = max;
    this.draw();
  }

  draw() {
    const { canvas, min, max } = this;
    if (!canvas.clientWidth || min === null) return;
    const { ctx, width: w, height: h } = fitCanvas(canvas);
    const unit = this.unit ? ` (${this.unit})` : '';
    const fontSize = 12;
    ctx.clearRect(0, 0, w, h);
    ctx.font = `${fontSize}px ${CHART.font}`;
    const tip = this.extend ? 9 : 0;
    const x0 = Math.ceil(ctx.measureText(formatTick(min)).width / 2) + 1;
    const x1 = w - Math.max(tip + 2, Math.ceil(ctx.measureText(formatTick(max)).width / 2) + 1);
    const barTop = fontSize + 6;
    const barH = 10;

    ctx.fillStyle = CHART.title;
    ctx.textAlign = 'left';
    ctx.textBaseline = 'top';
    ctx.fillText(`${this.title}${unit}`, x0, 1);

    const gradient = ctx.createLinearGradient(x0, 0, x1, 0);
    VIRIDIS_CSS.forEach((c, i) => gradient.addColorStop(i / (VIRIDIS_CSS.length - 1), c));
    ctx.fillStyle = gradient;
    ctx.fillRect(x0, barTop, x1 - x0, barH);
    if (tip) {
      ctx.fillStyle = VIRIDIS_CSS.at(-1);
      ctx.beginPath();
      ctx.moveTo(x1, barTop);
      ctx.lineTo(x1 + tip, barTop + barH / 2);
      ctx.lineTo(x1, barTop + barH);
      ctx.fill();
    }

    const axis = linearAxis(min, max, { count: Math.max(2, Math.floor((x1 - x0) / 70)), fixed: true });
    const at = (v) => x0 + ((v - min) / (max - min || 1)) * (x1 - x0);
    ctx.strokeStyle = CHART.tick;
    ctx.fillStyle = CHART.tick;
    ctx.textAlign = 'center';
    for (const t of axis.ticks) {
      const X = Math.round(at(t.value)) + 0.5;
      ctx.beginPath();
      ctx.moveTo(X, barTop + barH);
      ctx.lineTo(X, barTop + barH + 4);
      ctx.stroke();
      const label = formatTick(t.value);
      const half = ctx.measureText(label).width / 2;
      ctx.fillText(label, Math.min(Math.max(X, half + 1), w - half - 1), barTop + barH + 5);
    }
    const top = this.extend ? ` and above` : '';
    canvas.setAttribute('aria-label', `Colour scale: ${this.title} from ${formatTick(min)} (dark purple) to ${formatTick(max)}${unit}${top} (yellow)`);
    canvas.dataset.ticks = axis.ticks.map((t) => formatTick(t.value)).join(' ');
  }
}
