// The resolution governor: below its frame-rate target the scale falls at once, above it it
// rises slowly and settles short of where it last fell from; a fixed scale stays fixed.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { ResolutionGovernor, SMALL_SCREEN_SCALE, startScale } from '../web/src/player/resolution.js';

/** Feeds `fps(scale)` every 100 ms for `seconds`; returns the scales taken. */
function run(governor, fps, seconds, start = 0) {
  const scales = [];
  for (let t = start; t < start + seconds * 1000; t += 100) {
    governor.observe(t, fps(governor.scale));
    scales.push(governor.scale);
  }
  return scales;
}

test('a slow view lowers its resolution until it holds the target', () => {
  const g = new ResolutionGovernor({ target: 60 });
  // A view whose cost is its pixels: 120 fps at a quarter of them, 7.5 fps at full size.
  const fps = (s) => 7.5 / (s * s);
  const scales = run(g, fps, 20);
  const last = scales.at(-1);
  assert.ok(last < 0.45 && last >= 0.25, `settled at ${last}`);
  assert.ok(fps(last) >= 0.85 * 60, `holds ${fps(last).toFixed(0)} fps at scale ${last}`);
  // Settled: no change over the last five seconds.
  assert.equal(new Set(scales.slice(-50)).size, 1);
  // It only fell in steps of 0.8 and never went below the least scale.
  assert.ok(scales.every((s) => s >= 0.25));
});

test('a fast view keeps full resolution; a fixed scale is kept whatever the rate', () => {
  const g = new ResolutionGovernor({ target: 60 });
  assert.deepEqual(new Set(run(g, () => 60, 10)), new Set([1]));
  g.set(0.5);
  assert.deepEqual(new Set(run(g, () => 5, 10, 10_000)), new Set([0.5]));
  g.set('auto');
  assert.equal(g.scale, 1);
  run(g, () => 10, 2, 20_000);
  assert.ok(g.scale < 1);
});

test('phone-sized screens start at a lower resolution, in either orientation', () => {
  assert.equal(startScale(390, 844), SMALL_SCREEN_SCALE);
  assert.equal(startScale(844, 390), SMALL_SCREEN_SCALE);
  assert.equal(startScale(1100, 720), 1);
  const g = new ResolutionGovernor({ target: 60, start: startScale(390, 844) });
  assert.equal(g.scale, SMALL_SCREEN_SCALE);
  // It still rises when the frame rate allows, and 'auto' goes back to the start.
  run(g, () => 60, 10);
  assert.ok(g.scale > SMALL_SCREEN_SCALE);
  g.set(0.25);
  g.set('auto');
  assert.equal(g.scale, SMALL_SCREEN_SCALE);
});
