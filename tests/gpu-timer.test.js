// The GPU timer of the flow's passes (web/src/flow-gpu/timer.js) on a stand-in context whose
// queries answer at once: each stretch's result becomes `ms` when the next stretch begins, the
// first stretch's (its programs compiled in it) is let go, and one over a disjoint period too.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { GpuTimer } from '../web/src/flow-gpu/timer.js';

/** A WebGL2 stand-in with EXT_disjoint_timer_query_webgl2 whose stretches take `times` ns in turn. */
function standIn(times, disjointAt = -1) {
  const ext = { TIME_ELAPSED_EXT: 1, GPU_DISJOINT_EXT: 2 };
  let next = 0;
  let polls = 0;
  return {
    QUERY_RESULT_AVAILABLE: 3,
    QUERY_RESULT: 4,
    getExtension: (name) => (name === 'EXT_disjoint_timer_query_webgl2' ? ext : null),
    createQuery: () => ({ ns: times[next++] }),
    beginQuery() {},
    endQuery() {},
    deleteQuery() {},
    getParameter: (p) => (p === ext.GPU_DISJOINT_EXT ? polls++ === disjointAt : null),
    getQueryParameter: (q, p) => (p === 3 ? true : q.ns),
  };
}

test('the first stretch, which compiles the passes, is let go; later ones become ms', () => {
  const timer = new GpuTimer(standIn([6.4e9, 5e5, 7e5]));
  const seen = [];
  for (let i = 0; i < 3; i++) {
    timer.begin();
    timer.end();
    seen.push(timer.ms);
  }
  timer.poll();
  seen.push(timer.ms);
  assert.deepEqual(seen, [null, null, 0.5, 0.7]);
});

test('a stretch over a disjoint period is let go', () => {
  const timer = new GpuTimer(standIn([1e6, 2e6, 3e6], 2));
  for (let i = 0; i < 3; i++) {
    timer.begin();
    timer.end();
  }
  timer.poll();
  // Stretch 1 let go (the first), stretch 2 read, stretch 3 over the disjoint period.
  assert.equal(timer.ms, 2);
});

test('without the extension ms stays null', () => {
  const gl = { ...standIn([1e6]), getExtension: () => null };
  const timer = new GpuTimer(gl);
  timer.begin();
  timer.end();
  timer.poll();
  assert.equal(timer.ms, null);
});
