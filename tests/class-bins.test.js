// The GPU stepper's σ bins (web/src/stepper/class-bins.js): the window of classes and the steps
// each class is cut into, and the description of the sorted blobs the views draw from — each
// blob within its range's σ bounds and class, and a range cut at a width going to the passes
// that need it. The bin of a blob is computed here as the pass's GLSL computes it.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { BIN_GLSL, binClasses, binLayout, BINS, OVERFLOW_BIN } from '../web/src/stepper/class-bins.js';
import { frameDescription } from '../web/src/views/scene-view.js';
import { classOf, classSigma, cutClasses } from '../web/src/views/volume/grid.js';
import { CLASS_BIAS, INFO_HEADER, INFO_PER_CLASS } from '../web/src/generated/contract.js';

const square = new Float32Array(1);
const squareBits = new Uint32Array(square.buffer);

/** The bin of a blob of σ (m, single precision) as BIN_GLSL's `binOf` finds it. */
function binOf(sigma, { first, classes, subBits }) {
  square[0] = Math.fround(sigma) * Math.fround(sigma);
  const bits = squareBits[0];
  const k = Math.min(Math.max(((bits >>> 23) & 255) - 127 + CLASS_BIAS, 0), 63) - first;
  if (k < 0 || k >= classes) return OVERFLOW_BIN;
  return (k << subBits) + ((bits & 0x7fffff) >>> (23 - subBits));
}

/** σ (single precision) spread evenly in log σ over [lo, hi] (m), `n` of them, in no order. */
function sigmas(lo, hi, n) {
  return Array.from({ length: n }, (_, i) => Math.fround(lo * (hi / lo) ** (((i * 0.6180339887) % 1))));
}

/** The frame description of `sigma` sorted into its bins, as the GPU stepper gives it, and the sorted σ. */
function sortedFrame(sigma) {
  const lo = Math.min(...sigma);
  const hi = Math.max(...sigma);
  const layout = binLayout(lo, hi);
  const bins = sigma.map((s) => binOf(s, layout));
  const counts = new Float32Array(BINS);
  for (const b of bins) counts[b] += 1;
  const entries = binClasses(layout, counts, 1.0001 * hi);
  const info = new Float32Array(INFO_HEADER + INFO_PER_CLASS * entries.length);
  info[0] = sigma.length;
  info[8] = lo;
  info[9] = entries.length;
  entries.forEach((e, i) => info.set(e, INFO_HEADER + INFO_PER_CLASS * i));
  // A stable counting sort by bin, as the passes sort the slots.
  const order = sigma.map((_, i) => i).sort((a, b) => bins[a] - bins[b] || a - b);
  return { layout, frame: frameDescription(info), sorted: order.map((i) => sigma[i]) };
}

test('the window of classes: each class cut into as many steps as the bins leave room for, a wider range into fifteen classes', () => {
  const span = (lo, hi) => binLayout(lo, hi);
  // σ within one class (σ² within a factor 2): eight steps; two classes, four; three, four;
  // five, two; eight, one; twenty, fifteen classes of one step.
  const one = classSigma(40);
  assert.deepEqual(span(one * 1.01, one * 1.3), { first: 40, classes: 1, subBits: 3 });
  assert.deepEqual(span(one * 1.01, one * 1.9), { first: 40, classes: 2, subBits: 2 });
  assert.equal(span(one * 1.01, one * 2.2).subBits, 2);
  assert.equal(span(one * 1.01, one * 4.5).subBits, 1);
  assert.deepEqual(span(one * 1.01, one * 12), { first: 40, classes: 8, subBits: 0 });
  assert.deepEqual(span(one * 1.01, one * 1000), { first: 40, classes: 15, subBits: 0 });
  // The window reaches a little past the core's range (the GPU rounds σ apart from it).
  assert.equal(span(one, 1.3 * one).first, 39);
  // No blobs: no bins.
  assert.equal(span(0, 0).classes, 0);
  assert.match(BIN_GLSL, /int binOf\(vec4 centre, float mass\)/);
});

test('the sorted blobs\' description: each blob in a range of its class and within the range\'s σ bounds, ranges in order', () => {
  for (const [lo, hi] of [[0.01, 0.013], [0.004, 0.05], [0.002, 0.4], [1e-4, 3]]) {
    const sigma = sigmas(lo, hi, 4000);
    const { layout, frame, sorted } = sortedFrame(sigma);
    assert.equal(frame.count, sigma.length);
    let next = 0;
    for (const c of frame.classes) {
      assert.equal(c.offset, next);
      next += c.count;
      for (const s of sorted.slice(c.offset, c.offset + c.count)) {
        if (c.mixed) {
          // Only blobs past the window are left unsorted.
          assert.ok(classOf(s) >= layout.first + layout.classes, `σ ${s} unsorted`);
          continue;
        }
        assert.equal(classOf(s), c.index, `σ ${s} in class ${c.index}`);
        assert.ok(s >= c.sigmaLow * (1 - 1e-7) && s <= c.sigmaMax, `σ ${s} outside [${c.sigmaLow}, ${c.sigmaMax}] of class ${c.index}`);
      }
    }
    assert.equal(next, sigma.length);
    // Steps of a class follow one another: each starts where the one before ends.
    const steps = frame.classes.filter((c, i) => i > 0 && !c.mixed && frame.classes[i - 1].index === c.index);
    if (layout.subBits > 0) assert.ok(steps.length > 0, `[${lo}, ${hi}] cut into steps`);
    // The widest range reaches no further than the widest blob (a little past it).
    const widest = frame.classes.filter((c) => !c.mixed).at(-1);
    assert.ok(widest.sigmaMax <= 1.0001 * hi * (1 + 1e-7));
    assert.equal(frame.classes.some((c) => c.mixed), classOf(hi) >= layout.first + OVERFLOW_BIN);
  }
});

test('the sorted blobs cut at a width: every narrower blob in a narrow range, every other in a wide one, only a straddling step in both', () => {
  const sigma = sigmas(0.004, 0.05, 4000);
  const { frame, sorted } = sortedFrame(sigma);
  const inside = (parts, i) => parts.some((c) => i >= c.offset && i < c.offset + c.count);
  for (const limit of [0.003, 0.0049, 0.008, 0.01, 0.0123, 0.03, 0.06]) {
    const { narrow, wide } = cutClasses(frame.classes, null, limit);
    let both = 0;
    sorted.forEach((s, i) => {
      if (s < limit) assert.ok(inside(narrow, i), `σ ${s} below ${limit} splatted`);
      else assert.ok(inside(wide, i), `σ ${s} at least ${limit} through the mesh`);
      if (inside(narrow, i) && inside(wide, i)) both += 1;
    });
    // At most the one step that holds the limit goes to both.
    const steps = frame.classes.filter((c) => c.sigmaLow < limit * (1 + 1e-5) && c.sigmaMax >= limit * (1 - 1e-5));
    assert.ok(steps.length <= 1, `${steps.length} steps straddle ${limit}`);
    assert.equal(both, steps.reduce((n, c) => n + c.count, 0));
  }
});
