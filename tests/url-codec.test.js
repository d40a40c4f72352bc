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
