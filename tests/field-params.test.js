// The page's field-parameter checks follow the core's rules and paths.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { DEFAULT_FIELD, maxInertial, validateField, withSize } from '../web/src/pages/field-params.js';

test('the default field is the paper statistics on 32^4 and valid', () => {
  assert.deepEqual(validateField(DEFAULT_FIELD), []);
  assert.deepEqual(DEFAULT_FIELD.spectrum, { law: 'kolmogorov', epsilon: 1, k_inertial: 4, sigma: 1 });
});

test('each bad parameter is named', () => {
  const cases = [
    [withSize(DEFAULT_FIELD, [32, 33, 32, 32]), 'field.size[1]'],
    [withSize(DEFAULT_FIELD, [2, 32, 32, 32]), 'field.size[0]'],
    [withSize(DEFAULT_FIELD, [32, 32, 32, 258]), 'field.size[3]'],
    [withSize(DEFAULT_FIELD, [32, 32, 5, 32]), 'field.size[2]'],
    [withSize(DEFAULT_FIELD, 128), 'field.size: nx*ny*nz*nt'],
    [{ ...DEFAULT_FIELD, spectrum: { ...DEFAULT_FIELD.spectrum, law: 'x' } }, 'field.spectrum.law'],
    [{ ...DEFAULT_FIELD, spectrum: { ...DEFAULT_FIELD.spectrum, epsilon: 0 } }, 'field.spectrum.epsilon'],
    [{ ...DEFAULT_FIELD, spectrum: { ...DEFAULT_FIELD.spectrum, k_inertial: 0 } }, 'field.spectrum.k_inertial'],
    [{ ...DEFAULT_FIELD, spectrum: { ...DEFAULT_FIELD.spectrum, sigma: -1 } }, 'field.spectrum.sigma'],
    [{ ...DEFAULT_FIELD, seed: 1.5 }, 'seed'],
  ];
  for (const [field, path] of cases) {
    const errors = validateField(field);
    assert.equal(errors.length, 1, JSON.stringify(errors));
    assert.ok(errors[0].startsWith(path), errors[0]);
  }
});

test('any even extent from 4 to 256 is a lattice, with the core\'s message otherwise', () => {
  for (const size of [[24, 48, 48, 16], [6, 10, 4, 8], [256, 256, 16, 16], [64, 64, 64, 64]]) {
    assert.deepEqual(validateField({ ...withSize(DEFAULT_FIELD, size), spectrum: { ...DEFAULT_FIELD.spectrum, k_inertial: 1 } }), []);
  }
  assert.deepEqual(validateField(withSize(DEFAULT_FIELD, [32, 33, 32, 32])),
    ['field.size[1]: must be an even number between 4 and 256 (got 33 for ny)']);
});

test('the explorer\'s k_inertial goes up to the largest |k| among the lattice\'s modes; any lattice takes the paper\'s 4', () => {
  // Components up to n/2 − 1 on each axis (the Nyquist planes are zero): (31, 7, 15).
  assert.equal(maxInertial([64, 16, 32, 4]), Math.hypot(31, 7, 15));
  for (const n of [4, 6, 8, 16]) assert.deepEqual(validateField(withSize(DEFAULT_FIELD, n)), [], `${n}`);
  for (const k of [0, -1, 257, NaN]) {
    assert.deepEqual(validateField({ ...DEFAULT_FIELD, spectrum: { ...DEFAULT_FIELD.spectrum, k_inertial: k } }),
      ['field.spectrum.k_inertial: must be a finite number greater than 0 and at most 256']);
  }
});
