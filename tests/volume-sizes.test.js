// The real-time view's sizes: the march's resolution under its pixel budget (the view's shape
// kept, never above the view), and the brick grid that covers the density grid.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { marchSize } from '../web/src/views/volume/march-upsample.js';
import { BRICK, brickDims } from '../web/src/views/volume/occupancy-pass.js';

test('a view within the march budget is marched at its own size', () => {
  assert.deepEqual(marchSize(640, 360, 2 ** 18), [640, 360]);
  assert.deepEqual(marchSize(512, 512, 2 ** 18), [512, 512]);
  assert.deepEqual(marchSize(1920, 1080, Infinity), [1920, 1080]);
});

test('a larger view is marched at about the budget, in its own shape', () => {
  for (const [w, h, budget] of [[1920, 1080, 2 ** 18], [1920, 1080, 2 ** 17], [1080, 1920, 2 ** 18], [3840, 1000, 2 ** 16]]) {
    const [mw, mh] = marchSize(w, h, budget);
    assert.ok(mw < w && mh < h, `${w}×${h}: ${mw}×${mh}`);
    assert.ok(Math.abs(mw * mh - budget) / budget < 0.01, `${w}×${h}: ${mw * mh} pixels for ${budget}`);
    assert.ok(Math.abs(mw / mh - w / h) / (w / h) < 0.01, `${w}×${h}: shape ${mw}×${mh}`);
  }
  assert.deepEqual(marchSize(1920, 1080, 2 ** 18), [683, 384]);
});

test('the brick grid covers every voxel, each brick BRICK voxels a side', () => {
  for (const dims of [[2, 2, 2], [8, 9, 16], [67, 222, 67], [256, 1, 17]]) {
    const bricks = brickDims(dims);
    dims.forEach((n, a) => {
      assert.ok(bricks[a] * BRICK >= n, `axis ${a} of ${dims}`);
      assert.ok((bricks[a] - 1) * BRICK < n, `axis ${a} of ${dims}: no empty brick layer`);
    });
  }
});
