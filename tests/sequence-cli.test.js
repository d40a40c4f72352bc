// `windfield render --frames` (docs/FORMATS.md, the command line): shards run as separate processes write exactly the
// unsharded run's bytes; complete frames are skipped unless --force; a killed run leaves no half
// frame and a rerun finishes it; bad ranges, patterns and shards are refused before anything is
// written; runs over the step budget are refused naming simulation.dt and the time.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFile, execFileSync, spawn } from 'node:child_process';
import { existsSync, mkdtempSync, openSync, readdirSync, readFileSync, rmSync, statSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { promisify } from 'node:util';
import { cli, cliPath, root } from './support/core.js';
import { decodePng } from './support/png.js';

const dir = mkdtempSync(join(tmpdir(), 'windfield-seq-'));
process.on('exit', () => rmSync(dir, { recursive: true, force: true }));
const scene = `${root}public/scenes/default.json`;
const run = promisify(execFile);
const frames = (out, ...extra) => ['render', scene, '--frames', '0..12', '--fps', '24', '--width', '80', '--height', '60', '--out', out, ...extra];

/** Name → bytes of every file in `d` but the sequence's manifest. */
function files(d) {
  return Object.fromEntries(readdirSync(d).filter((n) => !n.endsWith('.windfield.json')).sort()
    .map((n) => [n, readFileSync(join(d, n))]));
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

test('shards in parallel write exactly the unsharded frames', async () => {
  const whole = join(dir, 'whole');
  const sharded = join(dir, 'sharded');
  cli(frames(`${whole}/f%03d.png`));
  await Promise.all([0, 1, 2].map((i) => run(cliPath, frames(`${sharded}/f%03d.png`, '--shard', `${i}/3`))));
  const a = files(whole);
  const b = files(sharded);
  assert.deepEqual(Object.keys(a), Array.from({ length: 12 }, (_, k) => `f${String(k).padStart(3, '0')}.png`));
  // Beside the frames, the manifest the shards share: what makes their bytes.
  const manifest = JSON.parse(readFileSync(join(sharded, 'f%03d.png.windfield.json'), 'utf8'));
  assert.deepEqual([manifest.fps, manifest.width, manifest.height], [24, 80, 60]);
  assert.ok(readFileSync(join(whole, 'f%03d.png.windfield.json')).equals(readFileSync(join(sharded, 'f%03d.png.windfield.json'))));
  assert.deepEqual(Object.keys(b), Object.keys(a));
  for (const name of Object.keys(a)) assert.ok(a[name].equals(b[name]), `${name} differs`);
  // Frames are the scene at successive times: the gas moves between the first and the last.
  assert.notDeepEqual(decodePng(a['f000.png']).rgb, decodePng(a['f011.png']).rgb);
});

test('complete frames are skipped unless --force', () => {
  const out = join(dir, 'again');
  cli(frames(`${out}/f%03d.png`));
  const before = Object.fromEntries(readdirSync(out).map((n) => [n, statSync(join(out, n)).mtimeMs]));
  // A damaged frame (cut short) is not complete: only it is rendered again.
  const cut = join(out, 'f005.png');
  writeFileSync(cut, readFileSync(cut).subarray(0, 100));
  // Nor is one of full length whose closing IEND chunk is lost (its last 12 bytes zeroed).
  const tail = join(out, 'f007.png');
  const lost = readFileSync(tail);
  lost.fill(0, lost.length - 12);
  writeFileSync(tail, lost);
  const second = execFileSync(cliPath, frames(`${out}/f%03d.png`), { encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] });
  assert.equal(second, '');
  for (const [name, mtime] of Object.entries(before)) {
    if (name !== 'f005.png' && name !== 'f007.png') assert.equal(statSync(join(out, name)).mtimeMs, mtime, `${name} was rendered again`);
  }
  assert.equal(decodePng(readFileSync(cut)).width, 80);
  assert.equal(readFileSync(tail).subarray(-8, -4).toString('latin1'), 'IEND', 'the frame without its IEND was rendered again');
  const forced = join(dir, 'forced-log');
  execFileSync(cliPath, [...frames(`${out}/f%03d.png`), '--force'], { stdio: ['ignore', 'ignore', openSync(forced, 'w')] });
  assert.match(readFileSync(forced, 'utf8'), /frame 11 /);
});

test('a killed run leaves only whole frames, and a rerun finishes exactly', async () => {
  const args = (out) => ['render', `${root}public/scenes/psychedelic-steam.json`, '--frames', '0..16', '--fps', '4',
    '--width', '120', '--height', '90', '--out', `${out}/f%02d.png`];
  const killed = join(dir, 'killed');
  const child = spawn(cliPath, args(killed), { stdio: 'ignore' });
  // The run's end, whether it exited or could not start: the wait below stops there too.
  const ended = new Promise((r) => {
    child.on('exit', (code, signal) => r(signal ?? `exit status ${code}`));
    child.on('error', (err) => r(err.message));
  });
  let end = null;
  ended.then((why) => { end = why; });
  // Kill it once a few frames are written, mid-run.
  while (end === null && (!existsSync(killed) || readdirSync(killed).filter((n) => n.endsWith('.png')).length < 3)) {
    await new Promise((r) => setTimeout(r, 20));
  }
  assert.equal(end, null, 'the run ended before it wrote three frames');
  child.kill('SIGKILL');
  await ended;
  const written = readdirSync(killed).filter((n) => n.endsWith('.png'));
  assert.ok(written.length < 16, 'the run was stopped before its end');
  for (const name of written) {
    const png = decodePng(readFileSync(join(killed, name)));
    assert.deepEqual([png.width, png.height], [120, 90], `${name} is whole`);
  }
  cli(args(killed));
  const reference = join(dir, 'unkilled');
  cli(args(reference));
  const a = files(reference);
  const b = Object.fromEntries(Object.entries(files(killed)).filter(([n]) => n.endsWith('.png')));
  assert.deepEqual(Object.keys(b), Object.keys(a));
  for (const name of Object.keys(a)) assert.ok(a[name].equals(b[name]), `${name} differs`);
});

test('bad ranges, patterns, shards and rates: a clear error and nothing written', () => {
  const out = join(dir, 'never');
  const cases = [
    [['--frames', '5..2'], /--frames: .*empty/],
    [['--frames', 'a..b'], /--frames: /],
    [['--frames', '0..4', '--fps', '0'], /--fps: /],
    [['--frames', '0..4'], /--fps: required/],
    [['--frames', '0..4', '--fps', '24', '--shard', '3/3'], /--shard: /],
    [['--frames', '0..4', '--fps', '24', '--shard', 'x'], /--shard: /],
  ];
  for (const [extra, message] of cases) {
    assert.match(refused(['render', scene, '--out', `${out}/f%03d.png`, ...extra]), message);
  }
  assert.match(refused(['render', scene, '--frames', '0..4', '--fps', '24', '--out', `${out}/f.png`]), /--out: .*%0Nd/);
  assert.match(refused(['render', scene, '--frames', '0..4', '--fps', '24', '--out', `${out}/f%03d-%03d.png`]), /--out: /);
  assert.match(refused(['render', `${root}wasm-core/tests/golden/colours.json`, '--frames', '0..4', '--fps', '24', '--out', `${out}/f%03d.png`]), /needs a scene/);
  assert.equal(existsSync(out), false);
});

test('runs over a million steps are refused before they start, naming simulation.dt and the time', () => {
  const tiny = join(dir, 'tiny-dt.json');
  const s = JSON.parse(readFileSync(scene, 'utf8'));
  s.simulation = { ...s.simulation, dt: 1e-9 };
  delete s.render.time;
  writeFileSync(tiny, JSON.stringify(s));
  const out = join(dir, 'budget');
  for (const [args, seconds] of [
    [['simulate', tiny, '--seconds', '2', '--out', `${out}/blobs.json`], /2 s/],
    [['render', tiny, '--seconds', '2', '--out', `${out}/still.png`], /2 s/],
    [['render', tiny, '--frames', '0..48', '--fps', '24', '--out', `${out}/f%03d.png`], /1\.958\d* s/],
    // A still without --seconds is at render.time, 3 s when the scene names none.
    [['render', tiny, '--out', `${out}/still.png`], /3 s/],
  ]) {
    const message = refused(args);
    assert.match(message, /simulation\.dt/);
    assert.match(message, /1000000/);
    assert.match(message, new RegExp(`${seconds.source} of simulated time`));
  }
  // A scene's own render.time is a run like any other: checked as the scene is read.
  writeFileSync(tiny, JSON.stringify({ ...s, render: { ...s.render, time: 5 } }));
  assert.match(refused(['simulate', tiny, '--seconds', '0', '--out', `${out}/blobs.json`]), /simulation\.dt: 5 s of simulated time/);
  assert.equal(existsSync(out), false);
});
