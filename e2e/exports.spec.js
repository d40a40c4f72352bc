// Exports for pipelines in the browser (docs/FORMATS.md, exports): `exportStill` and
// `exportVolume` give the command line's bytes for the same state (the blob list `exportBlobs`
// hands out, rendered or voxelised by `windfield render` and `windfield volume`), a flipbook's
// sheet carries its description, bad arguments are refused with their name and range, and a
// cancelled export leaves the running scene as it was.
import { test, expect } from '@playwright/test';
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { cliPath } from '../tests/support/core.js';
import { encodeScene } from '../web/src/state/url-codec.js';

const smallPlume = JSON.parse(readFileSync(new URL('../tests/fixtures/small-plume.json', import.meta.url), 'utf8'));

async function open(page) {
  await page.goto(`./?view=points#${await encodeScene(smallPlume)}`);
  await page.waitForFunction(() => window.windfield !== undefined);
  await page.evaluate(() => window.windfield.ready);
}

/** Bytes of a Blob made in the page, as base64 (a Blob does not cross to the test). */
const blobBytes = (b64) => Buffer.from(b64, 'base64');

test('exportStill and exportVolume give the command line\'s bytes for the same state', async ({ page }) => {
  await open(page);
  const out = await page.evaluate(async () => {
    const w = window.windfield;
    await w.pause();
    await w.setStepper('cpu');
    await w.step(90);
    const b64 = async (blob) => {
      const bytes = new Uint8Array(await blob.arrayBuffer());
      let s = '';
      for (let i = 0; i < bytes.length; i += 0x8000) s += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
      return btoa(s);
    };
    const size = { width: 64, height: 48 };
    const still = await w.exportStill({ ...size, format: 'png', alpha: true });
    const opaque = await w.exportStill({ ...size, format: 'png' });
    const exr = await w.exportStill({ ...size, format: 'exr', alpha: true });
    const vdb = await w.exportVolume({ voxel: 0.02 });
    return {
      list: await w.exportBlobs(size),
      time: w.stats().time,
      types: [still.type, exr.type, vdb.type],
      still: await b64(still),
      opaque: await b64(opaque),
      exr: await b64(exr),
      vdb: await b64(vdb),
    };
  });
  expect(out.types).toEqual(['image/png', 'image/x-exr', 'application/x-vdb']);
  const dir = mkdtempSync(join(tmpdir(), 'windfield-e2e-exports-'));
  try {
    const list = join(dir, 'list.json');
    writeFileSync(list, JSON.stringify(out.list));
    const cli = (...args) => execFileSync(cliPath, args, { stdio: 'pipe' });
    const time = String(out.time);
    cli('render', list, '--alpha', '--out', join(dir, 'still.png'));
    cli('render', list, '--out', join(dir, 'opaque.png'));
    cli('render', list, '--alpha', '--time', time, '--out', join(dir, 'still.exr'));
    cli('volume', list, '--voxel', '0.02', '--time', time, '--out', join(dir, 'gas.vdb'));
    const same = (name, bytes) => expect(readFileSync(join(dir, name)).equals(blobBytes(bytes)), `${name}: the browser's bytes differ from the CLI's`).toBe(true);
    same('still.png', out.still);
    same('opaque.png', out.opaque);
    same('still.exr', out.exr);
    same('gas.vdb', out.vdb);
    expect(blobBytes(out.still).subarray(1, 4).toString()).toBe('PNG');
    expect(blobBytes(out.vdb).readUInt32LE(0)).toBe(0x56444220);
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});

test('export arguments are refused with their name and range; a flipbook carries its description', async ({ page }) => {
  await open(page);
  const result = await page.evaluate(async () => {
    const w = window.windfield;
    await w.pause();
    // Gas to measure: an empty scene's volume is empty, and accepted at any voxel.
    await w.step(20);
    const t0 = w.stats().time;
    const refusal = (p) => p.then(() => 'accepted', (e) => e.message);
    return {
      t0,
      width: await refusal(w.exportStill({ width: 0 })),
      format: await refusal(w.exportStill({ format: 'tiff' })),
      alpha: await refusal(w.exportStill({ alpha: 'yes' })),
      voxel: await refusal(w.exportVolume({ voxel: -1 })),
      budget: await refusal(w.exportVolume({ voxel: 1e-5 })),
      grid: await refusal(w.exportFlipbook({ frames: [0, 10], grid: [3, 3], tile: [16, 16] })),
      sheet: await refusal(w.exportFlipbook({ frames: [0, 4], grid: [4, 1], tile: [8192, 8] })),
      fps: await refusal(w.exportFlipbook({ frames: [0, 4], fps: 0 })),
      frames: await refusal(w.exportFlipbook({ frames: [5, 5] })),
      blobs: w.stats().blobs,
      book: await w.exportFlipbook({ frames: [6, 10], fps: 12, grid: [2, 2], tile: [24, 18] }).then((b) => ({ type: b.type, size: b.size, description: b.description })),
      time: w.stats().time,
    };
  });
  expect(result.width).toMatch(/^exportStill: width must be a whole number from 1 to 8192/);
  expect(result.format).toMatch(/^exportStill: format must be 'png' or 'exr'/);
  expect(result.alpha).toMatch(/^exportStill: alpha must be true or false/);
  expect(result.voxel).toMatch(/^exportVolume: voxel must be a side in metres/);
  expect(result.blobs).toBeGreaterThan(0);
  expect(result.budget).toMatch(/^voxel: .*2\^28/);
  expect(result.grid).toMatch(/^grid: 3×3 = 9 tiles cannot hold the 10 frames/);
  expect(result.sheet).toMatch(/^grid, tile: the sheet would be 32768×8 pixels, more than 16384 a side/);
  expect(result.fps).toMatch(/^exportFlipbook: fps must be a number greater than 0/);
  expect(result.frames).toMatch(/^exportFlipbook: frames must be \[A, B\] with A < B/);
  expect(result.book.type).toBe('image/png');
  expect(result.book.description).toMatchObject({ columns: 2, rows: 2, fps: 12, tile_width: 24, tile_height: 18, frame_count: 4, frames: [6, 10] });
  expect(result.book.description.frame_times).toHaveLength(4);
  // The flipbook ran a simulation of its own: the running scene did not move.
  expect(result.time).toBe(result.t0);
});

test('a cancelled export rejects and leaves the running scene untouched', async ({ page }) => {
  await open(page);
  const result = await page.evaluate(async () => {
    const w = window.windfield;
    await w.pause();
    await w.setStepper('cpu');
    await w.step(30);
    const before = { stats: w.stats(), list: await w.exportBlobs({ width: 32, height: 24 }) };
    const book = w.exportFlipbook({ frames: [0, 40], fps: 24, grid: [8, 5], tile: [128, 96] }).then(() => 'finished', (e) => e.message);
    await new Promise((r) => setTimeout(r, 300));
    const cancelled = await w.cancelExport();
    const outcome = await book;
    const after = { stats: w.stats(), list: await w.exportBlobs({ width: 32, height: 24 }) };
    await w.step(1);
    return { cancelled, outcome, before, after, next: w.stats().time };
  });
  expect(result.cancelled).toBe(1);
  expect(result.outcome).toMatch(/^cancelled: /);
  expect(result.after.stats.time).toBe(result.before.stats.time);
  expect(result.after.list).toEqual(result.before.list);
  expect(result.next).toBeGreaterThan(result.before.stats.time);
});
