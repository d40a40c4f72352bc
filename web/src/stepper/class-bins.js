// The bins the GPU stepper sorts its blobs into before the views draw them, as the core sorts a
// worker's frame into σ classes (`frame::packed`): class k holds σ in [σ_k, σ_{k+1}),
// σ_k = √2^(k − CLASS_BIAS) m. The GPU counts into BINS bins at once, so the bins cover a window
// of the gas's classes (from the core's σ range), each class cut into 2^subBits steps of σ² by
// the top bits of its mantissa, as finely as the window leaves room for (the worker's frames have
// SUBCLASS_BITS): a pass then draws only the steps of a class it may need. The last bin holds any
// blob outside the window, unsorted (a class that never fills: the window is the core's range).
// Pure functions: `binning.js` runs the passes, these say what the bins mean.

import { CLASS_BIAS, SUBCLASS_BITS } from '../generated/contract.js';
import { classOf } from '../views/volume/grid.js';

/** Bins counted at once: four RGBA texels. */
export const BINS = 16;
/** The bin of blobs outside the window of classes. */
export const OVERFLOW_BIN = BINS - 1;
/** The last σ class (open above), as class 0 is open below (`frame::packed::SIGMA_CLASSES`). */
const LAST_CLASS = 63;
/** The GPU's σ may round a little apart from the core's: the window reaches this far past its range. */
const MARGIN = 1e-4;

/**
 * The bins for a gas of σ (m) in [sigmaMin, sigmaMax] (the core's range): `first`, the first
 * class of the window; `classes`, how many; `subBits`, the bits of σ²'s mantissa that cut each
 * class (`classes << subBits` bins of the first OVERFLOW_BIN).
 */
export function binLayout(sigmaMin, sigmaMax) {
  if (!(sigmaMax > 0)) return { first: 0, classes: 0, subBits: 0 };
  const first = classOf(Math.max(sigmaMin, 0) * (1 - MARGIN));
  const span = classOf(sigmaMax * (1 + MARGIN)) - first + 1;
  let subBits = 0;
  while (subBits < SUBCLASS_BITS && span << (subBits + 1) <= OVERFLOW_BIN) subBits += 1;
  return { first, classes: Math.min(span, OVERFLOW_BIN), subBits };
}

/**
 * The σ classes of the sorted blobs as a frame's description has them (`frame::packed` info:
 * `[index, offset, count, σ_max]` each, narrowest first), from the blobs counted in each bin
 * (`counts`, BINS numbers) of `layout`. A class cut into steps comes as one entry a step, in
 * order; an entry's σ_max is its step's upper bound (the widest one's no more than `reach`, m,
 * the widest σ there is), so the next entry of the class starts at it (`frameDescription`). The
 * overflow bin is a mixed entry (index −1) up to `reach`.
 */
export function binClasses(layout, counts, reach) {
  const steps = 1 << layout.subBits;
  const used = layout.classes * steps;
  let widest = -1;
  for (let j = 0; j < used; j++) if (counts[j] > 0) widest = j;
  const entries = [];
  let offset = 0;
  for (let j = 0; j < used; j++) {
    if (!(counts[j] > 0)) continue;
    const k = layout.first + Math.floor(j / steps);
    const step = j % steps;
    // σ² of class k runs from 2^(k − CLASS_BIAS); its step j from (1 + j / steps) of that.
    const square = 2 ** (k - CLASS_BIAS);
    const bottom = Math.sqrt(square * (1 + step / steps));
    const top = k === LAST_CLASS ? Infinity : Math.sqrt(square * (1 + (step + 1) / steps));
    const sigmaMax = j === widest && reach >= bottom ? Math.min(top, reach) : top;
    entries.push([k, offset, counts[j], sigmaMax]);
    offset += counts[j];
  }
  if (counts[OVERFLOW_BIN] > 0) entries.push([-1, offset, counts[OVERFLOW_BIN], reach]);
  return entries;
}

/**
 * GLSL: `int binOf(vec4 centre, float mass)`, the bin of a slot from its moving state (centre
 * xyz and σ² in `centre`): σ as the packed frame has it, sqrt(σ²), and its class from σ·σ as
 * every view computes it; −1 for an empty slot (no mass or no width, left out as the core's
 * packing leaves them out). Uniforms `firstClass`, `windowClasses` and `subBits` (`binLayout`).
 */
export const BIN_GLSL = /* glsl */ `
uniform int firstClass;
uniform int windowClasses;
uniform int subBits;
int binOf(vec4 centre, float mass) {
  float sigma = sqrt(max(centre.w, 0.0));
  if (!(mass > 0.0) || !(sigma > 0.0)) return -1;
  uint bits = floatBitsToUint(sigma * sigma);
  int k = clamp(int((bits >> 23) & 255u) - 127 + ${CLASS_BIAS}, 0, ${LAST_CLASS}) - firstClass;
  if (k < 0 || k >= windowClasses) return ${OVERFLOW_BIN};
  return (k << subBits) + int((bits & 0x7fffffu) >> (23 - subBits));
}
`;
