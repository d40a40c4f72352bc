// A mutation fuzzer over shared links: scene hashes as the playground reads them
// (`decodeScene`, then the core's `validateScene`). Every mutated link must decode to a scene
// the core accepts, or be refused with a message saying why; nothing else may be thrown and
// nothing may hang. WINDFIELD_FUZZ_LINKS sets the count (default 5,000; `npm run fuzz` runs 100,000).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readdirSync, readFileSync } from 'node:fs';
import { loadCore, root } from './support/core.js';
import { decodeScene, encodeScene } from '../web/src/state/url-codec.js';

const core = await loadCore();
const count = Number(process.env.WINDFIELD_FUZZ_LINKS ?? 5_000);

/** xorshift32: a fixed, seeded stream of integers. */
function random(seed) {
  let x = seed >>> 0 || 1;
  return (n) => {
    x ^= x << 13; x >>>= 0;
    x ^= x >>> 17;
    x ^= x << 5; x >>>= 0;
    return x % n;
  };
}

const ALPHABET = 'ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789-_';
const JUNK = ['%', '#', '&', '=', '.', '+', '/', ' ', 'é', '\u0000', 'scene=', '1.', '2.', '=='];
const NUMBERS = [0, -1, 1e308, -1e308, 1e-308, 2 ** 53, 0.5, 1e7, -3, 900000];

/** One JSON-level edit of a scene object (in place). */
function mutateScene(value, pick, depth = 0) {
  if (value && typeof value === 'object' && depth < 8 && pick(3) > 0) {
    const keys = Object.keys(value);
    if (keys.length) {
      const k = keys[pick(keys.length)];
      const edit = pick(8);
      if (edit === 0) delete value[k];
      else if (edit === 1) value[`${k}_unknown`] = 1;
      else value[k] = mutateScene(value[k], pick, depth + 1);
      return value;
    }
  }
  const kinds = [null, true, 'x', [], {}, NUMBERS[pick(NUMBERS.length)], NUMBERS[pick(NUMBERS.length)]];
  return kinds[pick(kinds.length)];
}

/** One text-level edit of a hash. */
function mutateHash(hash, pick) {
  const i = pick(hash.length + 1);
  switch (pick(6)) {
    case 0: return hash.slice(0, i) + ALPHABET[pick(ALPHABET.length)] + hash.slice(i + 1);
    case 1: return hash.slice(0, i) + JUNK[pick(JUNK.length)] + hash.slice(i);
    case 2: return hash.slice(0, i);
    case 3: return hash.slice(0, i) + hash.slice(i + 1 + pick(8));
    case 4: return hash.replace('1.', `${pick(3)}.`);
    default: return hash + hash.slice(pick(hash.length));
  }
}

test('mutated links decode to valid scenes or are refused with a message', async () => {
  const scenes = readdirSync(`${root}public/scenes`).filter((n) => n.endsWith('.json'))
    .map((n) => JSON.parse(readFileSync(`${root}public/scenes/${n}`, 'utf8')));
  const links = await Promise.all(scenes.map((s) => encodeScene(s)));
  const pick = random(20251123);
  const tally = { accepted: 0, refusedLink: 0, refusedScene: 0, empty: 0 };
  for (let n = 0; n < count; n++) {
    let hash;
    if (pick(3) === 0) {
      const scene = mutateScene(structuredClone(scenes[pick(scenes.length)]), pick);
      hash = await encodeScene(scene ?? {});
    } else {
      hash = links[pick(links.length)];
      for (let k = 0; k <= pick(3); k++) hash = mutateHash(hash, pick);
    }
    let scene;
    try {
      scene = await decodeScene(`#${hash}`);
    } catch (err) {
      assert.ok(err instanceof Error && /link/.test(err.message), `decoding ${hash.slice(0, 80)}… threw ${err}`);
      tally.refusedLink += 1;
      continue;
    }
    if (scene === null) {
      tally.empty += 1;
      continue;
    }
    assert.equal(typeof scene, 'object');
    try {
      core.validateScene(JSON.stringify(scene));
      tally.accepted += 1;
    } catch (err) {
      assert.ok(err instanceof Error && err.message.trim().length > 0, `validateScene threw ${err}`);
      tally.refusedScene += 1;
    }
  }
  console.log(`${count} links: ${JSON.stringify(tally)}`);
  assert.ok(tally.accepted > 0 && tally.refusedLink > 0 && tally.refusedScene > 0, JSON.stringify(tally));
});
