// The contract between the core and the page (web/src/generated/contract.js, written by the
// core's `windfield contract`): every constant a number, the file exactly what the core writes
// now (when the native CLI is built; wasm-core/tests/contract.rs checks it in any case), and the
// engine reading its numbers from it rather than from copies of its own.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { existsSync, readFileSync } from 'node:fs';
import * as contract from '../web/src/generated/contract.js';
import { TEX_WIDTH, TRUNCATION } from '../web/src/engine/tiles.js';
import { cli, cliPath, root } from './support/core.js';

test('every shared constant is a finite positive number', () => {
  const names = Object.keys(contract);
  assert.ok(names.length >= 10, names.join());
  for (const name of names) assert.ok(Number.isFinite(contract[name]) && contract[name] > 0, `${name} = ${contract[name]}`);
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
  assert.equal(TRUNCATION, contract.TRUNCATION);
  assert.equal(TEX_WIDTH, contract.BLOBS_PER_ROW);
  const engine = ['handlers.js', 'tiles.js'].map((f) => readFileSync(`${root}web/src/engine/${f}`, 'utf8')).join('\n');
  for (const copy of [/\b8 \* (i|count)\b/, /=\s*1024\b/, /=\s*4\.5\b/, /slice\(0, 8\)/]) {
    assert.doesNotMatch(engine, copy, 'a hand-written copy of a contract constant');
  }
});
