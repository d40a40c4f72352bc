// The field explorer's parameters: the default is the paper's statistics, and a bad parameter of
// the explorer's field scene is refused by the core (which the explorer's engine runs) with its
// path and range; the page writes none of the ranges itself.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { MAX_EXTENT, MIN_EXTENT } from '../web/src/generated/contract.js';
import { DEFAULT_FIELD, fieldScene, maxInertial, withSize } from '../web/src/pages/field-params.js';
import { loadCore } from './support/core.js';

const core = await loadCore();

/** The core's refusal of the explorer's scene of `field` (its message), or null when it takes it. */
function refusal(field) {
  try {
    core.validateScene(fieldScene(field));
    return null;
  } catch (err) {
    return err.message;
  }
}

test('the default field is the paper statistics on 32^4 and valid', () => {
  assert.equal(refusal(DEFAULT_FIELD), null);
  assert.deepEqual(DEFAULT_FIELD.spectrum, { law: 'kolmogorov', epsilon: 1, k_inertial: 4, sigma: 1 });
});

test('each bad parameter is named', () => {
  const cases = [
    [withSize(DEFAULT_FIELD, [32, 33, 32, 32]), 'field.size[1]'],
    [withSize(DEFAULT_FIELD, [2, 32, 32, 32]), 'field.size[0]'],
    [withSize(DEFAULT_FIELD, [32, 32, 32, 258]), 'field.size[3]'],
    [withSize(DEFAULT_FIELD, [32, 32, 5, 32]), 'field.size[2]'],
    [withSize(DEFAULT_FIELD, 128), 'field.size: nx*ny*nz*nt'],
    // 2^32 points, which a count in WebAssembly's 32-bit usize would wrap to 0.
    [withSize(DEFAULT_FIELD, 256), 'field.size: nx*ny*nz*nt'],
    [{ ...DEFAULT_FIELD, spectrum: { ...DEFAULT_FIELD.spectrum, law: 'x' } }, 'field.spectrum.law'],
    [{ ...DEFAULT_FIELD, spectrum: { ...DEFAULT_FIELD.spectrum, epsilon: 0 } }, 'field.spectrum.epsilon'],
    [{ ...DEFAULT_FIELD, spectrum: { ...DEFAULT_FIELD.spectrum, k_inertial: 0 } }, 'field.spectrum.k_inertial'],
    [{ ...DEFAULT_FIELD, spectrum: { ...DEFAULT_FIELD.spectrum, sigma: -1 } }, 'field.spectrum.sigma'],
    [{ ...DEFAULT_FIELD, seed: 1.5 }, 'seed'],
  ];
  for (const [field, path] of cases) {
    const message = refusal(field);
    assert.ok(message?.startsWith(`${path}`), `${JSON.stringify(field)}: ${message}`);
  }
});

test('any even extent from MIN_EXTENT to MAX_EXTENT is a lattice, with the core\'s message otherwise', () => {
  for (const size of [[24, 48, 48, 16], [6, 10, 4, 8], [256, 256, 16, 16], [64, 64, 64, 64]]) {
    assert.equal(refusal({ ...withSize(DEFAULT_FIELD, size), spectrum: { ...DEFAULT_FIELD.spectrum, k_inertial: 1 } }), null);
  }
  assert.equal(refusal(withSize(DEFAULT_FIELD, [32, 33, 32, 32])),
    `field.size[1]: must be an even number between ${MIN_EXTENT} and ${MAX_EXTENT} (got 33 for ny)`);
});

test('the explorer\'s k_inertial goes up to the largest |k| among the lattice\'s modes; any lattice takes the paper\'s 4', () => {
  // Components up to n/2 − 1 on each axis (the Nyquist planes are zero): (31, 7, 15).
  assert.equal(maxInertial([64, 16, 32, 4]), Math.hypot(31, 7, 15));
  for (const n of [4, 6, 8, 16]) assert.equal(refusal(withSize(DEFAULT_FIELD, n)), null, `${n}`);
  for (const k of [0, -1, 257]) {
    assert.match(refusal({ ...DEFAULT_FIELD, spectrum: { ...DEFAULT_FIELD.spectrum, k_inertial: k } }),
      /^field\.spectrum\.k_inertial: must be a finite number greater than 0 and at most 256 \(got /);
  }
});
