// Exports for pipelines (docs/FORMATS.md, exports), held to the formats' own readers: an EXR
// still read by OpenEXR's Python bindings is the `linear` PNG's radiance in half floats, with
// its camera and time in the header; flipbook tiles are the stills of their frames byte for
// byte; a VDB volume read by OpenVDB's Python bindings is the blob list's density at the voxel
// centres (evaluated independently in Python) with the same mass; the wind grid read by OpenVDB
// is the field's lattice scaled to the world; refusals name the setting and write nothing.
// The readers run in the project-local Python of `scripts/setup.sh --readers`
// (tests/support/readers.js); without them these tests fail, saying what to run.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync, spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, readdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { PNG } from 'pngjs';
import { cli, cliPath, root } from './support/core.js';
import { readNpy } from './support/npy.js';
import { reader, requireReaders } from './support/readers.js';

const dir = mkdtempSync(join(tmpdir(), 'windfield-pipeline-'));
process.on('exit', () => rmSync(dir, { recursive: true, force: true }));
const plume = `${root}tests/fixtures/small-plume.json`;

/** A copy of the small plume with `render` changes, written to `dir`. */
function sceneWith(name, render) {
  const scene = JSON.parse(readFileSync(plume, 'utf8'));
  Object.assign(scene.render.image, render.image ?? {});
  if (render.background) scene.render.background = render.background;
  const path = join(dir, `${name}.json`);
  writeFileSync(path, JSON.stringify(scene));
  return path;
}

/** Runs the CLI expecting input to be refused: its stderr. */
function refused(args) {
  try {
    execFileSync(cliPath, args, { stdio: 'pipe' });
  } catch (err) {
    assert.equal(err.status, 2, `exit status for ${args.join(' ')}`);
    return err.stderr.toString();
  }
  assert.fail(`${args.join(' ')} was accepted`);
}

const png = (path) => PNG.sync.read(readFileSync(path));

test('the readers are installed (scripts/setup.sh --readers)', () => {
  requireReaders();
});

test('an EXR still is the linear render\'s radiance in half floats, with camera and time', () => {
  const scene = sceneWith('linear', { image: { encoding: 'linear', width: 48, height: 36 } });
  const still = (out, ...extra) => cli(['render', scene, '--seconds', '1.5', '--out', join(dir, out), ...extra]);
  still('linear.png');
  still('linear.exr');
  still('alpha.png', '--alpha');
  still('alpha.exr', '--alpha');
  const exr = reader('exr_pixels.py', join(dir, 'linear.exr'));
  assert.equal(exr.pixel_type, 'float16');
  assert.deepEqual([exr.width, exr.height], [48, 36]);
  const ref = png(join(dir, 'linear.png'));
  assert.equal(ref.data.length, 48 * 36 * 4);
  let worst = 0;
  for (let p = 0; p < 48 * 36; p++) {
    assert.equal(exr.rgba[4 * p + 3], 1, 'an opaque still has alpha 1');
    for (let c = 0; c < 3; c++) {
      const v = exr.rgba[4 * p + c];
      // The PNG is round(255·clamp(v)) of the f32 radiance; the EXR holds it in half floats
      // (relative error ≤ 2^-11).
      const err = Math.abs(255 * Math.min(Math.max(v, 0), 1) - ref.data[4 * p + c]);
      assert.ok(err <= 0.5 + 255 * v * 2 ** -11 + 1e-6, `pixel ${p} channel ${c}: EXR ${v}, PNG ${ref.data[4 * p + c]}`);
      worst = Math.max(worst, err);
    }
  }
  assert.ok(worst > 0, 'the image is not empty');
  // The header: the scene's time and its camera.
  const h = exr.header;
  assert.ok(Math.abs(h.windfieldTime - 90 * 0.016666) < 1e-5, `windfieldTime ${h.windfieldTime}`);
  assert.equal(h.fieldOfViewVertical, 40);
  assert.ok(h.software.startsWith('windfield'));
  const camera = JSON.parse(readFileSync(plume, 'utf8')).render.camera;
  const apply = (m, p) => [0, 1, 2, 3].map((c) => p[0] * m[0][c] + p[1] * m[1][c] + p[2] * m[2][c] + m[3][c]);
  assert.ok(apply(h.worldToCamera, camera.position).slice(0, 3).every((v) => Math.abs(v) < 1e-5));
  const ndc = apply(h.worldToNDC, camera.target);
  assert.ok(Math.abs(ndc[0] / ndc[3] - 0.5) < 1e-5 && Math.abs(ndc[1] / ndc[3] - 0.5) < 1e-5, `${ndc}`);

  // With alpha: premultiplied in the EXR, straight in the PNG (alpha is linear in both).
  const a = reader('exr_pixels.py', join(dir, 'alpha.exr'));
  const ap = png(join(dir, 'alpha.png'));
  let translucent = 0;
  for (let p = 0; p < 48 * 36; p++) {
    const alpha = a.rgba[4 * p + 3];
    assert.ok(Math.abs(255 * alpha - ap.data[4 * p + 3]) <= 0.5 + 255 * alpha * 2 ** -11 + 1e-6, `alpha at ${p}`);
    if (alpha > 0.05 && alpha < 0.95) translucent += 1;
    if (alpha < 0.02) continue;
    for (let c = 0; c < 3; c++) {
      const straight = a.rgba[4 * p + c] / alpha;
      if (straight > 1) continue;
      // Straight colour in the linear PNG; its rounding, and the half floats of both values.
      const err = Math.abs(255 * straight - ap.data[4 * p + c]);
      assert.ok(err <= 0.5 + 255 * straight * 2 ** -10 + 1e-6, `pixel ${p} channel ${c}: ${straight} vs ${ap.data[4 * p + c]}`);
    }
  }
  assert.ok(translucent > 20, `${translucent} translucent pixels`);
});

test('each tile of a flipbook is the still of its frame, byte for byte', () => {
  const scene = sceneWith('book-scene', {});
  const sheet = join(dir, 'book.png');
  cli(['flipbook', scene, '--frames', '20..25', '--fps', '15', '--grid', '3×2', '--tile', '40x30', '--out', sheet]);
  const description = JSON.parse(readFileSync(join(dir, 'book.json'), 'utf8'));
  assert.equal(readFileSync(join(dir, 'book.png.json'), 'utf8'), readFileSync(join(dir, 'book.json'), 'utf8'));
  assert.deepEqual(
    [description.columns, description.rows, description.fps, description.tile_width, description.tile_height, description.frame_count],
    [3, 2, 15, 40, 30, 5],
  );
  assert.equal(description.frame_times.length, 5);
  assert.equal(description.image, 'book.png');
  assert.equal(description.alpha, 'straight');
  const s = png(sheet);
  assert.deepEqual([s.width, s.height], [120, 60]);
  for (let k = 0; k < 6; k++) {
    const [x0, y0] = [40 * (k % 3), 30 * Math.floor(k / 3)];
    const tile = Buffer.alloc(40 * 30 * 4);
    for (let y = 0; y < 30; y++) s.data.copy(tile, 160 * y, 4 * ((y0 + y) * 120 + x0), 4 * ((y0 + y) * 120 + x0 + 40));
    if (k === 5) {
      assert.ok(tile.every((b) => b === 0), 'the tile past the last frame is transparent');
      continue;
    }
    const still = join(dir, `frame${k}.png`);
    cli(['render', scene, '--seconds', String((20 + k) / 15), '--alpha', '--width', '40', '--height', '30', '--out', still]);
    assert.ok(png(still).data.equals(tile), `tile ${k} is not the still of frame ${20 + k}`);
  }
  // A grid that cannot hold the frames is refused, and nothing is written.
  const err = refused(['flipbook', scene, '--frames', '0..7', '--fps', '15', '--grid', '3x2', '--tile', '40x30', '--out', join(dir, 'small.png')]);
  assert.match(err, /windfield: error: --grid: 3×2 = 6 tiles cannot hold the 7 frames/);
  assert.match(refused(['flipbook', scene, '--frames', '0..4', '--fps', '15', '--grid', '3x2', '--tile', '8192x8192', '--out', join(dir, 'huge.png')]), /more than 16384 a side/);
  assert.ok(!existsSync(join(dir, 'small.png')) && !existsSync(join(dir, 'huge.png')));
});

test('a VDB volume is the blob list\'s density at the voxel centres, read by OpenVDB', () => {
  const list = join(dir, 'plume-list.json');
  cli(['simulate', plume, '--seconds', '2.5', '--out', list]);
  const h = 0.015;
  const vdb = join(dir, 'plume.vdb');
  cli(['volume', list, '--voxel', String(h), '--out', vdb]);
  const r = reader('vdb_density.py', vdb, list, h);
  assert.equal(r.class, 'fog volume');
  assert.equal(r.type, 'float');
  assert.deepEqual(r.grids, ['density'], 'no emission grid without emitting blobs');
  assert.ok(r.voxel_size.every((v) => Math.abs(v - h) < 1e-12), `voxel size ${r.voxel_size}`);
  assert.deepEqual(r.index_to_world_123.map((v) => Math.round(v / h * 1e6) / 1e6), [1, 2, 3], 'voxel (i, j, k) at (i, j, k)·H');
  assert.ok(r.active > 1000, `${r.active} active voxels`);
  assert.ok(r.worst < 1e-4, `the voxels differ from the density by ${r.worst} of the peak`);
  // Voxels below 1e-6 of the peak are inactive (up to the voxels' own rounding, `worst`).
  assert.ok(r.smallest_active >= 1e-6 - r.worst, `an active voxel below 1e-6 of the peak: ${r.smallest_active}`);
  assert.ok(r.inactive_below <= 1e-6 + r.worst, `an inactive voxel holds ${r.inactive_below} of the peak`);
  assert.ok(Math.abs(r.mass_grid / r.mass_blobs - 1) < 1e-3, `mass ${r.mass_grid} vs ${r.mass_blobs}`);
  assert.equal(r.metadata.file_voxel_count, r.active);
  assert.equal(r.creator.split(' ')[0], 'windfield');
  // The scene simulated by `volume` itself gives the same voxels as its blob list.
  const direct = join(dir, 'direct.vdb');
  cli(['volume', plume, '--seconds', '2.5', '--voxel', String(h), '--out', direct]);
  const d = reader('vdb_density.py', direct, list, h);
  assert.deepEqual([d.active, d.worst, d.mass_grid], [r.active, r.worst, r.mass_grid]);
  assert.ok(Math.abs(d.metadata.windfield_time - 150 * 0.016666) < 1e-9);
  // Blobs that emit add an emission grid.
  const glowing = JSON.parse(readFileSync(list, 'utf8'));
  glowing.blobs[0].emission = [2, 1, 0.5];
  glowing.blobs[0].albedo = [0.2, 0.2, 0.2];
  writeFileSync(join(dir, 'glow.json'), JSON.stringify(glowing));
  cli(['volume', join(dir, 'glow.json'), '--voxel', String(h), '--out', join(dir, 'glow.vdb')]);
  assert.deepEqual(reader('vdb_density.py', join(dir, 'glow.vdb'), join(dir, 'glow.json'), h).grids, ['density', 'emission']);
  // Over the voxel budget: refused before any work, naming --voxel.
  assert.match(refused(['volume', list, '--voxel', '0.0001', '--out', join(dir, 'fine.vdb')]), /--voxel: .*2\^28.*use voxels of at least/);
  assert.ok(!existsSync(join(dir, 'fine.vdb')));
});

test('volume sequences shard like render sequences and OpenVDB reads every frame', () => {
  const out = join(dir, 'vol');
  const args = (...extra) => ['volume', plume, '--frames', '3..7', '--fps', '4', '--voxel', '0.02', '--out', `${out}/gas.%04d.vdb`, ...extra];
  cli(args('--shard', '0/2'));
  cli(args('--shard', '1/2'));
  const names = readdirSync(out).sort();
  assert.deepEqual(names, ['gas.%04d.vdb.windfield.json', 'gas.0003.vdb', 'gas.0004.vdb', 'gas.0005.vdb', 'gas.0006.vdb']);
  const manifest = JSON.parse(readFileSync(join(out, names[0]), 'utf8'));
  assert.equal(manifest.voxel, 0.02);
  assert.equal(manifest.width, undefined);
  const before = readFileSync(join(out, 'gas.0005.vdb'));
  const whole = join(dir, 'whole.vdb');
  cli(['volume', plume, '--seconds', String(5 / 4), '--voxel', '0.02', '--out', whole]);
  assert.ok(before.equals(readFileSync(whole)), 'frame 5 is the volume at 5/4 s');
  // Complete frames are skipped; another voxel size under the same pattern is refused.
  const again = spawnSync(cliPath, args(), { encoding: 'utf8' });
  assert.equal(again.status, 0);
  assert.match(again.stderr, /nothing to write: all 4 frames .* are complete/);
  assert.match(refused(['volume', plume, '--frames', '3..7', '--fps', '4', '--voxel', '0.03', '--out', `${out}/gas.%04d.vdb`]), /another run/);
  const list = join(dir, 'list5.json');
  cli(['simulate', plume, '--seconds', String(5 / 4), '--out', list]);
  const r = reader('vdb_density.py', join(out, 'gas.0005.vdb'), list, 0.02);
  assert.ok(r.worst < 1e-4 && r.metadata.windfield_time > 1.2, JSON.stringify(r.metadata));
});

test('the wind grid of `generate` is the field\'s lattice in world units, read by OpenVDB', () => {
  const npy = join(dir, 'field.npy');
  const common = ['--size', '16,12,10,8', '--seed', '7', '--k-inertial', '2'];
  cli(['generate', ...common, '--out', npy]);
  const mapping = ['--time', '1.3', '--period', '2,3,4', '--time-period', '5', '--amplitude', '2'];
  cli(['generate', ...common, '--out', join(dir, 'field.vdb'), ...mapping]);
  cli(['generate', ...common, '--out', join(dir, 'field.rgb32f'), ...mapping]);
  const r = reader('vdb_wind.py', join(dir, 'field.vdb'), npy, 1.3, '2,3,4', 5, 2);
  assert.equal(r.name, 'wind');
  assert.equal(r.type, 'vec3s');
  assert.equal(r.active, 16 * 12 * 10);
  assert.equal(r.vector_type, 'contravariant relative');
  assert.ok(r.voxel_size.every((v, a) => Math.abs(v - r.cell[a]) < 1e-12), `${r.voxel_size} vs ${r.cell}`);
  assert.deepEqual(r.world_of_321, [3 * 2 / 16, 2 * 3 / 12, 1 * 4 / 10]);
  assert.ok(r.worst < 1e-6, `the grid differs from the lattice by ${r.worst} of its largest speed`);
  // The raw texture holds the same numbers, x fastest, and its description the layout.
  const raw = readFileSync(join(dir, 'field.rgb32f'));
  const texels = new Float32Array(raw.buffer.slice(raw.byteOffset, raw.byteOffset + raw.length));
  const description = JSON.parse(readFileSync(join(dir, 'field.rgb32f.json'), 'utf8'));
  assert.deepEqual(description.size, [16, 12, 10]);
  assert.deepEqual(description.box, { min: [-1 / 16, -1.5 / 12, -2 / 10], max: [2 - 1 / 16, 3 - 1.5 / 12, 4 - 2 / 10] });
  assert.deepEqual(description.units, { position: 'm', value: 'm/s' });
  assert.equal(description.time, 1.3);
  assert.equal(texels.length, 16 * 12 * 10 * 3);
  const { data } = readNpy(npy);
  const q = 1.3 * 8 / 5;
  const [t0, f] = [Math.floor(q), q - Math.floor(q)];
  let worst = 0;
  let scale = 0;
  for (let n = 0; n < 16 * 12 * 10; n++) {
    for (let c = 0; c < 3; c++) {
      const lattice = (1 - f) * data[3 * (t0 * 1920 + n) + c] + f * data[3 * ((t0 + 1) * 1920 + n) + c];
      const want = 2 * [2, 3, 4][c] / 5 * lattice;
      worst = Math.max(worst, Math.abs(texels[3 * n + c] - want));
      scale = Math.max(scale, Math.abs(want));
    }
  }
  assert.ok(worst < 1e-6 * scale, `texture differs by ${worst} (largest ${scale})`);
  // The world mapping applies to grids only; a .npy stays in lattice units.
  assert.match(refused(['generate', '--size', '8', '--time', '1', '--out', join(dir, 'x.npy')]), /--time: applies to a wind grid/);
});

test('`windfield flow` as OpenVDB is the same grid as its .npy, velocity and temperature at the cell centres', () => {
  const scene = `${root}tests/fixtures/hot-flow.json`;
  cli(['flow', scene, '--seconds', '0.5', '--out', join(dir, 'flow.npy')]);
  cli(['flow', scene, '--seconds', '0.5', '--out', join(dir, 'flow.vdb')]);
  const r = reader('vdb_flow.py', join(dir, 'flow.vdb'), join(dir, 'flow.npy'));
  assert.deepEqual(r.types, ['vec3s', 'float']);
  assert.equal(r.active[0], r.active[1]);
  assert.ok(r.hottest > 0, 'the emitter heats the grid');
  assert.equal(r.worst, 0, 'the two files hold the same float32 values');
});

test('`windfield wind --box` as OpenVDB is the same wind as its .npy, at the cell centres', () => {
  const scene = `${root}public/scenes/steam-mug.json`;
  const box = ['--box', '-0.5,0,-0.5,0.5,1.2,0.5', '--n', '6,8,5'];
  cli(['wind', scene, '--seconds', '1.5', ...box, '--out', join(dir, 'wind-box.npy')]);
  cli(['wind', scene, '--seconds', '1.5', ...box, '--out', join(dir, 'wind-box.vdb')]);
  const r = reader('vdb_box.py', join(dir, 'wind-box.vdb'), join(dir, 'wind-box.npy'));
  assert.equal(r.name, 'wind');
  assert.equal(r.type, 'vec3s');
  assert.equal(r.active, 6 * 8 * 5);
  assert.equal(r.time, 1.5);
  const cell = [1 / 6, 1.2 / 8, 1 / 5];
  r.voxel_size.forEach((v, a) => assert.ok(Math.abs(v - cell[a]) < 1e-12, `voxel size ${r.voxel_size}`));
  [-0.5, 0, -0.5].forEach((lo, a) => assert.ok(Math.abs(r.world_of_000[a] - (lo + cell[a] / 2)) < 1e-12, `${r.world_of_000}`));
  [3, 2, 1].forEach((i, a) => assert.ok(Math.abs(r.world_of_321[a] - ([-0.5, 0, -0.5][a] + (i + 0.5) * cell[a])) < 1e-12));
  assert.ok(r.largest > 0.05, `the mug's wind is not still (${r.largest} m/s)`);
  assert.equal(r.worst, 0, 'the two files hold the same float32 values');
});
