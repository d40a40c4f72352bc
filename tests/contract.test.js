// The contract between the core and the page (web/src/generated/contract.js, written by the
// core's `windfield contract`): every constant a number, the file exactly what the core writes
// now (when the native CLI is built; wasm-core/tests/contract.rs checks it in any case), and the
// engine and the views reading its numbers from it rather than from copies of their own.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { existsSync, readFileSync } from 'node:fs';
import { readdirSync } from 'node:fs';
import { join, relative } from 'node:path';
import * as contract from '../web/src/generated/contract.js';
import * as tiles from '../web/src/engine/tiles.js';
import { cli, cliPath, root } from './support/core.js';

/** Every JavaScript file under `dir`, but the generated ones. */
function sources(dir) {
  return readdirSync(dir, { withFileTypes: true }).flatMap((e) => {
    const path = join(dir, e.name);
    if (e.isDirectory()) return e.name === 'generated' ? [] : sources(path);
    return e.name.endsWith('.js') ? [path] : [];
  });
}

test('every shared constant is a finite number, none negative', () => {
  const names = Object.keys(contract);
  assert.ok(names.length >= 10, names.join());
  // Sizes and limits are positive; a kind (an enumeration's value, `*_KIND`) may be 0.
  for (const name of names) {
    const ok = Number.isFinite(contract[name]) && (contract[name] > 0 || (name.endsWith('_KIND') && contract[name] === 0));
    assert.ok(ok, `${name} = ${contract[name]}`);
  }
  assert.equal(contract.WORDS_PER_BLOB, 8);
  assert.equal(contract.BLOBS_PER_ROW, 1024);
});

test('the shipped contract is what the core writes now', (t) => {
  if (!existsSync(cliPath)) {
    t.skip('native CLI not built (cargo build --release); wasm-core/tests/contract.rs checks the file');
    return;
  }
  const shipped = readFileSync(`${root}web/src/generated/contract.js`, 'utf8');
  assert.equal(shipped, cli(['contract']), 'stale: regenerate with `windfield contract > web/src/generated/contract.js`');
});

test('the engine takes its shared numbers from the contract', () => {
  // One home: the engine does not hand the contract's numbers on as its own.
  for (const name of Object.keys(contract)) assert.equal(tiles[name], undefined, `engine/tiles.js re-exports ${name}`);
  const engine = ['handlers.js', 'tiles.js'].map((f) => readFileSync(`${root}web/src/engine/${f}`, 'utf8')).join('\n');
  for (const copy of [/\b8 \* (i|count)\b/, /=\s*1024\b/, /=\s*4\.5\b/, /slice\(0, 8\)/]) {
    assert.doesNotMatch(engine, copy, 'a hand-written copy of a contract constant');
  }
});

test('no page, view or engine module defines a contract constant of its own', () => {
  const names = Object.keys(contract).join('|');
  const own = new RegExp(`\\b(const|let|var)\\s+(${names})\\s*=`);
  for (const file of sources(join(root, 'web/src'))) {
    const text = readFileSync(file, 'utf8');
    assert.doesNotMatch(text, own, `${relative(root, file)} defines its own copy of a contract constant`);
  }
});
