// The classroom page and the exports: the spectrum plot's data is what `windfield stats`
// reports for the same field; the Figure 1 demo conserves mass, shows the square at fixed times
// and replays its first seconds; the side-by-side players run three variants; the streamlines
// round a solid sphere are the potential flow's; PNG, WebM and blob-list exports are valid files.
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { expect, test, collectErrors } from './helpers.js';
import { cliPath } from '../tests/support/core.js';
import { reader } from '../tests/support/readers.js';
import { decodePng } from '../tests/support/png.js';

test('classroom: the spectrum plot shows what windfield stats reports', async ({ page }) => {
  const errors = collectErrors(page);
  await page.goto('./classroom.html');
  await page.waitForFunction(() => window.classroom?.ready);
  await page.evaluate(() => window.classroom.ready);
  const { series, report } = await page.evaluate(() => ({ series: window.classroom.series, report: window.classroom.report }));
  const dir = mkdtempSync(join(tmpdir(), 'windfield-classroom-'));
  try {
    execFileSync(cliPath, ['generate', '--size', '32', '--seed', '1', '--out', join(dir, 'f.npy')]);
    const cli = JSON.parse(execFileSync(cliPath, ['stats', '--json', join(dir, 'f.npy')]).toString());
    const inertial = cli.shells.filter((s) => s.energy_expected > 0);
    expect(series.measured.length).toBe(inertial.length);
    expect(series.measured.length).toBeGreaterThan(5);
    inertial.forEach((s, i) => {
      expect(series.measured[i][0]).toBe(s.k);
      expect(Math.abs(series.measured[i][1] / s.energy - 1)).toBeLessThan(1e-4);
      expect(Math.abs(series.target[i][1] / s.energy_expected - 1)).toBeLessThan(1e-9);
      expect(Math.abs(series.spread[i][1] - s.temporal_spread)).toBeLessThan(1e-3 * Math.max(1, s.temporal_spread));
    });
    expect(Math.abs(report.slope - cli.slope)).toBeLessThan(1e-3);
    // The wind taken along: the page's OpenVDB file and 3-D texture are `windfield generate`'s.
    const grids = await page.evaluate(async () => {
      const vdb = await window.classroom.windGrid('vdb');
      const texture = await window.classroom.windGrid('rgb32f');
      return { vdb: [...vdb.bytes], texture: [...texture.bytes], description: texture.description };
    });
    execFileSync(cliPath, ['generate', '--size', '32', '--seed', '1', '--out', join(dir, 'wind.vdb')]);
    execFileSync(cliPath, ['generate', '--size', '32', '--seed', '1', '--out', join(dir, 'wind.rgb32f')]);
    const texture = readFileSync(join(dir, 'wind.rgb32f'));
    const cliTexels = new Float32Array(texture.buffer.slice(texture.byteOffset, texture.byteOffset + texture.length));
    const pageTexels = new Float32Array(new Uint8Array(grids.texture).buffer);
    expect(pageTexels.length).toBe(32 * 32 * 32 * 3);
    const largest = cliTexels.reduce((m, v) => Math.max(m, Math.abs(v)), 0);
    const worst = pageTexels.reduce((m, v, i) => Math.max(m, Math.abs(v - cliTexels[i])), 0);
    expect(worst / largest).toBeLessThan(1e-6);
    // The WASM and native syntheses agree to a float's last bits, not always in them.
    const description = JSON.parse(readFileSync(join(dir, 'wind.rgb32f.json'), 'utf8'));
    expect(Math.abs(grids.description.max_speed / description.max_speed - 1)).toBeLessThan(1e-6);
    expect({ ...grids.description, max_speed: 0 }).toEqual({ ...description, max_speed: 0 });
    // The page's VDB, read by OpenVDB itself beside the command line's.
    writeFileSync(join(dir, 'page.vdb'), Buffer.from(grids.vdb));
    const r = reader('vdb_compare.py', join(dir, 'page.vdb'), join(dir, 'wind.vdb'));
    expect(r.active).toEqual([32 ** 3, 32 ** 3]);
    expect([r.same_box, r.same_transform, r.same_metadata]).toEqual([true, true, true]);
    expect(r.worst).toBeLessThan(1e-6);
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
  expect(errors).toEqual([]);
});

test('classroom: Figure 1 conserves mass; the side-by-side players run three variants', async ({ page }) => {
  const errors = collectErrors(page);
  await page.goto('./classroom.html');
  await page.waitForFunction(() => window.classroom?.ready);
  await page.evaluate(() => window.classroom.ready);
  // The players load as they near the viewport.
  expect(await page.evaluate(() => document.querySelector('#carried').loaded)).toBe(false);
  await page.evaluate(() => document.querySelector('#carried').scrollIntoView());
  await page.evaluate(() => window.classroom.sideBySide);
  const masses = await page.evaluate(() => {
    const d = window.classroom.figure1;
    const before = d.gridMass();
    d.step(0.5);
    return { before, grid: d.gridMass(), blobs: d.blobMass(), t: d.time() };
  });
  expect(masses.t).toBeGreaterThan(0.4);
  expect(Math.abs(masses.grid / masses.before - 1)).toBeLessThan(1e-9);
  expect(Math.abs(masses.blobs / masses.before - 1)).toBeLessThan(1e-9);
  const variants = await page.evaluate(() => ['off', 'on', 'carried'].map((id) => {
    const f = document.getElementById(id).getScene().field;
    return [f.amplitude, f.carried];
  }));
  expect(variants[0][0]).toBe(0);
  expect(variants[1][0]).toBeGreaterThan(0);
  expect(variants[1][1]).toBe(false);
  expect(variants[2][1]).toBe(true);
  expect(errors).toEqual([]);
});

test('classroom: the streamlines round a solid sphere are the potential flow\'s, and both panels draw them', async ({ page }) => {
  const errors = collectErrors(page);
  await page.goto('./classroom.html');
  await page.waitForFunction(() => window.classroom?.ready);
  await page.evaluate(() => window.classroom.ready);
  const sphere = await page.evaluate(() => window.classroom.sphere);
  expect(sphere.core.length).toBe(13);
  // The page's own check of the core's wind: each streamline against the closed form's, and
  // outside the sphere everywhere.
  const potential = ([x, y]) => {
    const r = Math.hypot(x, y);
    const q = 0.5 / r ** 3;
    const ur = x / r;
    return [1 - q * (3 * ur * (x / r) - 1), -q * 3 * ur * (y / r)];
  };
  let gap = 0;
  sphere.core.forEach((line, l) => line.forEach((p, k) => {
    gap = Math.max(gap, Math.hypot(p[0] - sphere.closedForm[l][k][0], p[1] - sphere.closedForm[l][k][1]));
    expect(Math.hypot(...p)).toBeGreaterThanOrEqual(0.99);
  }));
  expect(gap).toBeLessThan(0.05);
  expect(Math.abs(gap - sphere.largestGap)).toBeLessThan(1e-6);
  // The closed form's streamlines follow its wind: each step along the wind's direction.
  for (const line of sphere.closedForm) {
    for (let k = 1; k < line.length; k += 20) {
      const u = potential(line[k - 1]);
      const d = [line[k][0] - line[k - 1][0], line[k][1] - line[k - 1][1]];
      const cos = (u[0] * d[0] + u[1] * d[1]) / (Math.hypot(...u) * Math.hypot(...d));
      expect(cos).toBeGreaterThan(0.99);
    }
  }
  // Both panels are drawn: lines of the chart's colour over the background.
  const drawn = await page.evaluate(() => ['sphere-core', 'sphere-closed'].map((id) => {
    const c = document.getElementById(id);
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let bright = 0;
    for (let i = 0; i < d.length; i += 4) if (d[i] + d[i + 1] + d[i + 2] > 300) bright += 1;
    return bright / (d.length / 4);
  }));
  for (const share of drawn) expect(share).toBeGreaterThan(0.01);
  await expect(page.locator('#sphere-caption')).toContainText('part by at most');
  expect(errors).toEqual([]);
});

test('classroom: Figure 1 shows the square at fixed times, grid and blobs, and its live panels loop', async ({ page }) => {
  const errors = collectErrors(page);
  await page.goto('./classroom.html');
  await page.waitForFunction(() => window.classroom?.snapshots);
  await page.evaluate(() => window.classroom.snapshots);
  // Each snapshot: its density's spread in luminance, and how far it is from the one before.
  const panels = await page.evaluate(() => ['grid', 'blobs'].map((model) => [0, 1, 2, 3, 4].map((k) => {
    const c = document.querySelector(`#fig1-${model}-${k}`);
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    const lum = [];
    for (let i = 0; i < d.length; i += 4) lum.push(0.2126 * d[i] + 0.7152 * d[i + 1] + 0.0722 * d[i + 2]);
    return { label: c.getAttribute('aria-label'), lum };
  })));
  const std = (a) => {
    const m = a.reduce((s, v) => s + v, 0) / a.length;
    return Math.sqrt(a.reduce((s, v) => s + (v - m) ** 2, 0) / a.length);
  };
  const meanDiff = (a, b) => a.reduce((s, v, i) => s + Math.abs(v - b[i]), 0) / a.length;
  for (const [row, model] of [[0, 'grid'], [1, 'blobs']]) {
    expect(panels[row].map((p) => p.label)).toEqual(['0', '0.25', '0.5', '1', '2'].map((t) => `${model} at t = ${t} s`));
    for (let k = 0; k < 5; k++) {
      // Not a uniform haze: the square's remains stand out at every time shown.
      expect(std(panels[row][k].lum), `${model} at snapshot ${k}`).toBeGreaterThan(5);
      // And each snapshot shows a later state than the one before.
      if (k > 0) expect(meanDiff(panels[row][k].lum, panels[row][k - 1].lum), `${model} ${k - 1} → ${k}`).toBeGreaterThan(1);
    }
  }
  // The live panels play the first seconds again and again.
  await expect.poll(() => page.evaluate(() => window.classroom.figure1Loops), { timeout: 60_000 }).toBeGreaterThan(0);
  expect(await page.evaluate(() => window.classroom.figure1.time())).toBeLessThanOrEqual(2 + 1e-9);
  expect(errors).toEqual([]);
});

test('exports: PNG, frame-accurate WebM and the blob list are valid files', async ({ page }) => {
  await page.goto('./');
  await page.waitForFunction(() => window.windfield !== undefined);
  await page.evaluate(() => window.windfield.ready);
  const out = await page.evaluate(async () => {
    const w = window.windfield;
    w.pause();
    await w.step(30);
    const png = await w.captureGPU({ mode: 'points', width: 160, height: 120 });
    const video = await w.recordWebM({ frames: 12, width: 160, height: 120, fps: 30, mode: 'points' });
    const bytes = new Uint8Array(await video.arrayBuffer());
    const list = await w.exportBlobs({ width: 96, height: 72 });
    return { png, video: Array.from(bytes), list: JSON.stringify(list) };
  });
  const png = decodePng(Buffer.from(out.png.split(',')[1], 'base64'));
  expect([png.width, png.height, png.rgb.length]).toEqual([160, 120, 160 * 120 * 3]);
  const video = Buffer.from(out.video);
  expect(video.subarray(0, 4).toString('hex')).toBe('1a45dfa3'); // EBML header
  expect(video.includes(Buffer.from('webm'))).toBe(true);
  expect(video.length).toBeGreaterThan(500);
  const dir = mkdtempSync(join(tmpdir(), 'windfield-export-'));
  try {
    writeFileSync(join(dir, 'blobs.json'), out.list);
    execFileSync(cliPath, ['render', join(dir, 'blobs.json'), '--out', join(dir, 'still.png')]);
    expect(readFileSync(join(dir, 'still.png')).subarray(1, 4).toString()).toBe('PNG');
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});
