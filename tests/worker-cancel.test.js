// The engine worker in Node: a newer `load` supersedes a field synthesis in flight, which
// rejects with "cancelled"; the newer scene is the one that ends up loaded. Deterministic: the
// second load is sent from inside the first one's progress report, at a chosen stage.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';

// What a browser gives a module worker: `self`, and `fetch` for the core's .wasm file.
const posted = [];
let onPost = () => {};
globalThis.self = {
  postMessage(msg) {
    posted.push(msg);
    onPost(msg);
  },
};
globalThis.fetch = async (url) => new Response(readFileSync(fileURLToPath(url)), {
  headers: { 'Content-Type': 'application/wasm' },
});
await import('../web/src/engine/worker.js');

/** Sends a request; resolves with the worker's reply (ok or not). */
function request(id, type, args = {}) {
  return new Promise((resolve) => {
    const previous = onPost;
    onPost = (msg) => {
      previous(msg);
      if (msg.id === id && msg.type !== 'progress') resolve(msg);
    };
    self.onmessage({ data: { id, type, ...args } });
  });
}

const scene = (size, seed) => JSON.stringify({ version: 1, seed, field: { size, spectrum: { k_inertial: 2 } } });

test('a newer load cancels a synthesis in flight, and the newer scene is loaded', async () => {
  const first = scene([16, 16, 16, 16], 1);
  const second = scene([12, 12, 12, 8], 2);
  let secondReply = null;
  let stagesRun = 0;
  const previous = onPost;
  onPost = (msg) => {
    previous(msg);
    // Mid-synthesis: after the first's third stage, the second load arrives.
    if (msg.id === 1 && msg.type === 'progress' && msg.progress > 0 && ++stagesRun === 3) {
      secondReply = request(2, 'load', { scene: second });
    }
  };
  const firstReply = await request(1, 'load', { scene: first });
  assert.equal(firstReply.ok, false);
  assert.match(firstReply.error, /^cancelled: a newer scene was loaded/);
  assert.equal(stagesRun, 3, 'the first synthesis stopped at the stage after the newer load came');
  const reply = await secondReply;
  assert.equal(reply.ok, true, reply.error);
  assert.deepEqual(reply.result.size, [12, 12, 12, 8]);
  assert.equal(JSON.parse(reply.result.sceneJson).seed, 2);
  const stats = await request(3, 'fieldStats');
  assert.deepEqual(stats.result.size, [12, 12, 12, 8]);
});

test('an invalid newer scene does not cancel a valid load in flight', async () => {
  let badReply = null;
  let sent = false;
  const previous = onPost;
  onPost = (msg) => {
    previous(msg);
    if (msg.id === 10 && msg.type === 'progress' && msg.progress > 0 && !sent) {
      sent = true;
      badReply = request(11, 'load', { scene: scene([16, 15, 16, 16], 3) });
    }
  };
  const reply = await request(10, 'load', { scene: scene([8, 8, 8, 8], 4) });
  assert.equal(reply.ok, true, reply.error);
  assert.deepEqual(reply.result.size, [8, 8, 8, 8]);
  const bad = await badReply;
  assert.equal(bad.ok, false);
  assert.match(bad.error, /field\.size\[1\]: must be an even number between 4 and 256 \(got 15 for ny\)/);
});

test('progress reports name the synthesis stages and only grow', async () => {
  const start = posted.length;
  const reply = await request(20, 'load', { scene: scene([10, 6, 8, 6], 5) });
  assert.equal(reply.ok, true, reply.error);
  const reports = posted.slice(start).filter((m) => m.id === 20 && m.type === 'progress');
  const values = reports.map((m) => m.progress);
  assert.deepEqual(values, [...values].sort((a, b) => a - b));
  assert.ok(reports.some((m) => /t transform/.test(m.stage)), JSON.stringify(reports.map((m) => m.stage)));
  assert.ok(reports.some((m) => /x transforms/.test(m.stage)));
  assert.equal(values.at(-1), 1);
});
