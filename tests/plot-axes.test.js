// The charts' axes: decade ticks on log axes, whole 1-2-5 steps on linear ones, tick values
// written as people write them.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { formatTick, linearAxis, logAxis } from '../web/src/charts/plot-axes.js';

test('a log axis has major ticks at the decades and labels 1, 2 and 5 times them', () => {
  const axis = logAxis(0.0012, 3.4);
  assert.ok(axis.lo < 0.0012 && axis.hi > 3.4);
  assert.deepEqual(axis.ticks.filter((t) => t.major).map((t) => t.value), [0.01, 0.1, 1]);
  assert.deepEqual(axis.ticks.filter((t) => t.label).map((t) => t.value), [0.002, 0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1, 2]);
  assert.ok(axis.ticks.every((t) => t.value >= axis.lo && t.value <= axis.hi));
});

test('a log axis spanning less than a decade and a half offers every minor tick as a label', () => {
  const axis = logAxis(4, 27);
  assert.deepEqual(axis.ticks.filter((t) => t.label).map((t) => t.value), [4, 5, 6, 7, 8, 9, 10, 20, 30]);
});

test('a linear axis widens to whole steps of 1, 2 or 5 times a power of ten', () => {
  assert.deepEqual(linearAxis(0, 8.7).ticks.map((t) => t.value), [0, 2, 4, 6, 8, 10]);
  assert.deepEqual(linearAxis(0, 1.56, { count: 4, fixed: true }).ticks.map((t) => t.value), [0, 0.5, 1, 1.5]);
  assert.deepEqual(linearAxis(0.1, 0.3).ticks.map((t) => t.value), [0.1, 0.15, 0.2, 0.25, 0.3]);
});

test('tick values read as decimals, or as powers of ten when very small or large', () => {
  assert.equal(formatTick(0), '0');
  assert.equal(formatTick(0.006), '0.006');
  assert.equal(formatTick(20), '20');
  assert.equal(formatTick(-1.5), '−1.5');
  assert.equal(formatTick(1e-5), '10⁻⁵');
  assert.equal(formatTick(2e-5), '2×10⁻⁵');
  assert.equal(formatTick(1e6), '10⁶');
});
