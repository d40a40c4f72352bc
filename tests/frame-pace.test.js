// The status line's frames a second (`player/frame-pace.js`), driven with frames at chosen times:
// a capped rate shows as itself however long each frame's step and drawing take, a steady rate
// as itself, a stopped one falls to zero, and any rate agrees with the frames counted over the
// window.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { FramePace } from '../web/src/player/frame-pace.js';

/**
 * Frames begun at `starts` (ms), frame i drawn in `draw(i)` ms, one after the other; the rate
 * read every 10 ms up to `until` (ms): [now, fps] pairs.
 */
function readings(starts, draw, until) {
  const stats = { fps: 0, frames: 0, limitedBy: null };
  const pace = new FramePace(stats, { target: 60, observe: () => false });
  const frames = starts.map((start, i) => ({ start, end: start + draw(i) }));
  frames.forEach((f, i) => assert.ok(i === 0 || f.start >= frames[i - 1].end, 'frames one after the other'));
  const out = [];
  let k = 0;
  for (let now = 0; now <= until; now += 10) {
    for (; k < frames.length && frames[k].end <= now; k++) pace.drawn(frames[k].start, frames[k].end, { playing: true });
    pace.tick(now);
    out.push([now, stats.fps]);
  }
  return out;
}

/** A frame begun every `interval` ms (plus `jitter(i)`) from `first` up to `until`. */
function cadence(first, interval, until, jitter = () => 0) {
  const starts = [first];
  while (starts.at(-1) + interval < until) starts.push(starts.at(-1) + interval + jitter(starts.length));
  return starts;
}

test('frames capped at 0.2 a second show as 0.2, whatever each one takes to draw', () => {
  // The cap spaces the frames' beginnings 5 s apart (a little more, as animation frames come);
  // the first frame of each pair waits 1.5 s for its steps, the second draws at once.
  const starts = cadence(1000, 5000, 60_000, (i) => (i * 7) % 40);
  const rates = readings(starts, (i) => (i % 2 ? 10 : 1500), 60_000).filter(([now]) => now >= 7000);
  const [low, high] = [Math.min(...rates.map(([, r]) => r)), Math.max(...rates.map(([, r]) => r))];
  assert.ok(low > 0.195 && high < 0.205, `0.2 fps read as ${low.toFixed(3)} to ${high.toFixed(3)}`);
});

test('a steady 60 frames a second shows as 60, and stopped, the rate falls to zero in the window', () => {
  const starts = cadence(0, 1000 / 60, 10_000);
  const last = starts.at(-1);
  const rates = readings(starts, () => 5, 16_000);
  const at = (t) => rates.find(([now]) => now >= t)[1];
  for (const t of [1000, 4000, 9000]) assert.ok(Math.abs(at(t) - 60) < 0.5, `${at(t)} at ${t} ms`);
  const after = rates.filter(([now]) => now > last + 10).map(([, r]) => r);
  after.forEach((r, i) => assert.ok(i === 0 || r <= after[i - 1] + 1e-9, 'falls, never rises'));
  assert.ok(at(last + 2500) > 20 && at(last + 2500) < 40, `${at(last + 2500)} halfway`);
  assert.equal(at(last + 5100), 0);
});

test('an uneven rate agrees with the frames counted over the last five seconds', () => {
  // About 20 frames a second, each interval 30 to 70 ms.
  const starts = cadence(0, 30, 30_000, (i) => (i * 37) % 41);
  const rates = readings(starts, () => 20, 30_000);
  for (const t of [8000, 15_000, 29_000]) {
    const counted = starts.filter((s) => s > t - 5000 && s + 20 <= t).length / 5;
    const shown = rates.find(([now]) => now >= t)[1];
    assert.ok(Math.abs(shown - counted) < 0.05 * counted, `${shown} shown, ${counted} counted at ${t} ms`);
  }
});
