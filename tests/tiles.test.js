// Screen tiles: every pixel whose ray meets a blob's truncated sphere finds the blob in its
// tile's list (checked by brute force), lists run front to back, blobs behind are dropped.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { TRUNCATION } from '../web/src/generated/contract.js';
import { binBlobs } from '../web/src/engine/tiles.js';
import { tileFor } from '../web/src/views/exact/exact-frame.js';

const view = {
  position: [0.2, 1, 4],
  forward: [0, 0, -1],
  right: [1, 0, 0],
  up: [0, 1, 0],
  tanHalf: Math.tan((40 * Math.PI) / 360),
};

function blobs(n) {
  const positions = new Float32Array(3 * n);
  const sigma = new Float32Array(n);
  for (let i = 0; i < n; i++) {
    const f = (k) => (((i + 0.5) * k) % 1) * 3 - 1.5;
    positions.set([f(0.7548777), f(0.5698403) + 1, f(0.4301597) * 2], 3 * i);
    sigma[i] = 0.02 + 0.08 * ((i * 7) % 11) / 11;
  }
  positions.set([0, 1, 5], 0); // behind the camera
  // Packed as the core packs a frame: centre and σ in the first four of eight words.
  const floats = new Float32Array(8 * n);
  for (let i = 0; i < n; i++) {
    floats.set(positions.subarray(3 * i, 3 * i + 3), 8 * i);
    floats[8 * i + 3] = sigma[i];
  }
  return { positions, sigma, floats, count: n };
}

/** Every blob a ray of the `w × h` image meets is in its pixel's tile, listed front to back. */
function checkTiles(b, w, h, tile) {
  const t = binBlobs(b, view, w, h, tile);
  assert.equal(t.tilesX, Math.ceil(w / tile));
  assert.equal(t.tilesY, Math.ceil(h / tile));
  for (let py = 0; py < h; py += 3) {
    for (let px = 0; px < w; px += 3) {
      const x = ((px + 0.5) / w * 2 - 1) * view.tanHalf * (w / h);
      const y = ((py + 0.5) / h * 2 - 1) * view.tanHalf;
      const len = Math.hypot(x, y, 1);
      const d = [x / len, y / len, -1 / len];
      const k = Math.floor(py / tile) * t.tilesX + Math.floor(px / tile);
      const [start, count] = [t.heads[4 * k], t.heads[4 * k + 1]];
      const members = new Set(Array.from(t.list.subarray(start, start + count)));
      for (let i = 0; i < b.count; i++) {
        const oc = [0, 1, 2].map((c) => b.positions[3 * i + c] - view.position[c]);
        const s = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2];
        const r2 = oc[0] ** 2 + oc[1] ** 2 + oc[2] ** 2 - s * s;
        const R = TRUNCATION * b.sigma[i];
        if (r2 < R * R && s + Math.sqrt(R * R - r2) > 0) assert.ok(members.has(i), `pixel ${px},${py} misses blob ${i}`);
      }
      let last = -Infinity;
      for (const i of members) {
        const z = view.position[2] - b.positions[3 * i + 2];
        assert.ok(z >= last - 1e-6);
        last = z;
      }
    }
  }
  assert.ok(!Array.from(t.list).includes(0), 'the blob behind the camera is dropped');
}

test('every blob a pixel ray meets is in that pixel tile, front to back, at each tile side the march picks', () => {
  const b = blobs(300);
  checkTiles(b, 96, 64, 16);
  for (const [w, h] of [[40, 30], [96, 64], [160, 120], [320, 240]]) checkTiles(b, w, h, tileFor(w, h));
});

test('a smaller image gets smaller tiles, whose pixels visit fewer blobs', () => {
  const b = blobs(2000);
  const visits = (w, h, tile) => {
    const t = binBlobs(b, view, w, h, tile);
    let sum = 0;
    for (let py = 0; py < h; py++) {
      for (let px = 0; px < w; px++) sum += t.heads[4 * (Math.floor(py / tile) * t.tilesX + Math.floor(px / tile)) + 1];
    }
    return sum / (w * h);
  };
  assert.equal(tileFor(1920, 1080), 16);
  assert.ok(tileFor(40, 30) < tileFor(160, 120) && tileFor(160, 120) < tileFor(320, 240));
  const [small, fixed] = [visits(40, 30, tileFor(40, 30)), visits(40, 30, 16)];
  assert.ok(small < fixed / 3, `a pixel of 40 × 30 visits ${small.toFixed(0)} blobs with its tiles, ${fixed.toFixed(0)} with 16-pixel ones`);
});

test('tiles hold far fewer blobs than the scene as blobs spread out', () => {
  const t = binBlobs(blobs(2000), view, 320, 240, 16);
  const counts = [];
  for (let k = 0; k < t.tilesX * t.tilesY; k++) counts.push(t.heads[4 * k + 1]);
  const mean = counts.reduce((a, b) => a + b, 0) / counts.length;
  assert.ok(mean < 2000 / 4, `mean per tile ${mean}`);
});
