// The URL hash codec: exact round trips, compact links, clear errors for damaged ones.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { decodeScene, encodeScene, HASH_KEY } from '../web/src/state/url-codec.js';
import { root } from './support/core.js';

const scene = JSON.parse(readFileSync(`${root}tests/fixtures/plume.json`, 'utf8'));

test('round trip is exact, including awkward numbers and text', async () => {
  const odd = { ...scene, seed: 2 ** 53, note: 'ε = 1, σ → 0 — "quotes" \\ \u{1F32C}', field: { ...scene.field, amplitude: 0.1 + 0.2 } };
  for (const s of [scene, odd, { version: 1 }]) {
    const hash = await encodeScene(s);
    assert.ok(hash.startsWith(`${HASH_KEY}=1.`));
    assert.match(hash, /^scene=1\.[A-Za-z0-9_-]+$/);
    assert.deepEqual(await decodeScene(`#${hash}`), s);
    assert.deepEqual(await decodeScene(hash), s);
  }
});

test('a link may carry the scene as plain JSON, percent-encoded or not', async () => {
  const odd = { ...scene, note: 'a + b & c = "d" #1 100%' };
  assert.deepEqual(await decodeScene(`#scene=${encodeURIComponent(JSON.stringify(odd))}`), odd);
  assert.deepEqual(await decodeScene('#scene={"version":1,"seed":7}'), { version: 1, seed: 7 });
  assert.deepEqual(await decodeScene('scene=%20%7B%22version%22%3A1%7D'), { version: 1 });
  await assert.rejects(decodeScene('#scene={"version":1,'), /not valid JSON/);
  await assert.rejects(decodeScene(`#scene=${encodeURIComponent('{"a":"' + 'x'.repeat(2 << 20) + '"}')}`), /longer than 1 MiB/);
});

test('links are compact', async () => {
  const hash = await encodeScene(scene);
  assert.ok(hash.length < JSON.stringify(scene).length, `${hash.length} chars`);
});

test('no scene in the hash is null; damaged links throw readable errors', async () => {
  assert.equal(await decodeScene(''), null);
  assert.equal(await decodeScene('#other=1'), null);
  await assert.rejects(decodeScene('#scene=garbage'), /damaged/);
  await assert.rejects(decodeScene('#scene=1.!!!'), /damaged/);
  await assert.rejects(decodeScene('#scene=1.AAAA'), /damaged/);
  await assert.rejects(decodeScene('#scene=9.abc'), /codec version 9/);
  const good = await encodeScene(scene);
  await assert.rejects(decodeScene(`#${good.slice(0, -6)}`), /damaged/);
  const notObject = await encodeScene([1, 2]);
  await assert.rejects(decodeScene(notObject), /scene object/);
});

test('messages name what is wrong in a reader\'s words, never a browser\'s internals', async () => {
  for (const hash of ['#scene=garbage', '#scene=1.!!!', '#scene=1.AAAAA', '#scene=1.AAAA']) {
    const err = await decodeScene(hash).then(() => null, (e) => e);
    assert.equal(err?.message, 'the link is damaged or cut short', hash);
  }
});

test('a link that inflates past 4 MiB is refused before it is read further', async () => {
  // 1.5 GB of spaces would deflate to about 1.5 MB; 16 MiB deflates to about 16 KB.
  const bomb = `{"version": 1, "note": "${' '.repeat(16 << 20)}"}`;
  const hash = await encodeScene(JSON.parse(bomb));
  assert.ok(hash.length < 100_000, `${hash.length} chars`);
  await assert.rejects(decodeScene(hash), /larger than 4 MiB/);
  await assert.rejects(decodeScene(`#scene=1.${'A'.repeat((1 << 20) + 100)}`), /longer than 1 MiB/);
});
