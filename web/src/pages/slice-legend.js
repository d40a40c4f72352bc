// The wind slice's legend: the colour bar of its speed scale (viridis, 0 to the slice's fastest
// wind) with its ends in m/s.

import { viridis } from '../charts/colormap.js';

/** Paints the colour bar into `legend`'s canvas and labels its top speed `maxSpeed` (m/s). */
export function drawSliceLegend(legend, maxSpeed) {
  const bar = legend.querySelector('.legend-bar');
  const context = bar.getContext('2d');
  const image = context.createImageData(bar.width, 1);
  for (let i = 0; i < bar.width; i++) {
    viridis(i / (bar.width - 1), image.data, 4 * i);
    image.data[4 * i + 3] = 255;
  }
  for (let y = 0; y < bar.height; y++) context.putImageData(image, 0, y);
  legend.querySelector('.legend-max').textContent = `${maxSpeed.toPrecision(2)} m/s`;
  legend.setAttribute('aria-label', `Wind slice colours: speed from 0 (dark blue) to ${maxSpeed.toPrecision(2)} m/s (yellow)`);
}
