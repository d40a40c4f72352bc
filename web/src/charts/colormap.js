// Perceptually uniform colour map (viridis, sampled at nine stops) for scalar fields.

const STOPS = [
  [0.267, 0.005, 0.329], [0.283, 0.141, 0.458], [0.254, 0.265, 0.530],
  [0.207, 0.372, 0.553], [0.164, 0.471, 0.558], [0.128, 0.567, 0.551],
  [0.135, 0.659, 0.518], [0.267, 0.749, 0.441], [0.478, 0.821, 0.318],
  [0.741, 0.873, 0.150], [0.993, 0.906, 0.144],
];

/** Writes the colour of `v` in [0, 1] (clamped) as bytes into `out` at `offset`. */
export function viridis(v, out, offset) {
  const x = Math.min(Math.max(v, 0), 1) * (STOPS.length - 1);
  const i = Math.min(Math.floor(x), STOPS.length - 2);
  const f = x - i;
  const a = STOPS[i];
  const b = STOPS[i + 1];
  for (let c = 0; c < 3; c++) out[offset + c] = Math.round(255 * (a[c] + f * (b[c] - a[c])));
}

/** The map's stops as CSS colours, evenly spaced over [0, 1]: a canvas gradient through them is the map. */
export const VIRIDIS_CSS = STOPS.map((s) => `rgb(${s.map((c) => Math.round(255 * c)).join(', ')})`);
