// Field parameters as the core takes them (docs/FORMATS.md: the field and the scene format): lattice size, spectrum, seed.
// Pure functions, shared by the field explorer, the classroom and the unit tests. The lattice's
// limits are the core's (the contract's).

import { MAX_EXTENT, MAX_POINTS, MIN_EXTENT } from '../generated/contract.js';

/** The paper's statistics (§6): ε = 1, k_inertial = 4, σ = 1, on a 32⁴ lattice. */
export const DEFAULT_FIELD = Object.freeze({
  size: [32, 32, 32, 32],
  spectrum: { law: 'kolmogorov', epsilon: 1, k_inertial: 4, sigma: 1 },
  seed: 1,
});

export const LAWS = ['kolmogorov', 'paper-literal'];
// Extents per axis: even numbers from MIN_EXTENT to MAX_EXTENT (powers of two are the fastest);
// at most MAX_POINTS lattice points in all (2^24, 64⁴: a 192 MiB field).
const AXES = ['nx', 'ny', 'nz', 'nt'];

const isExtent = (n) => Number.isInteger(n) && n % 2 === 0 && n >= MIN_EXTENT && n <= MAX_EXTENT;

/**
 * Checks field parameters with the core's rules and paths; returns a list of
 * `path: message` strings (empty when valid).
 */
export function validateField(field) {
  const errors = [];
  const size = field?.size;
  if (!Array.isArray(size) || size.length !== 4) {
    errors.push('field.size: must be [nx, ny, nz, nt]');
  } else {
    size.forEach((n, i) => {
      if (!isExtent(n)) {
        errors.push(`field.size[${i}]: must be an even number between ${MIN_EXTENT} and ${MAX_EXTENT} (got ${n} for ${AXES[i]})`);
      }
    });
    if (errors.length === 0 && size.reduce((a, b) => a * b, 1) > MAX_POINTS) {
      errors.push(`field.size: nx*ny*nz*nt must be at most ${MAX_POINTS} lattice points`);
    }
  }
  if (errors.length) return errors; // the spectrum's range depends on a valid lattice
  const s = field?.spectrum ?? {};
  if (!LAWS.includes(s.law)) errors.push('field.spectrum.law: must be "kolmogorov" or "paper-literal"');
  if (!(Number.isFinite(s.epsilon) && s.epsilon > 0 && s.epsilon <= 1e6)) {
    errors.push('field.spectrum.epsilon: must be greater than 0 and at most 1000000');
  }
  if (!(Number.isFinite(s.k_inertial) && s.k_inertial > 0 && s.k_inertial <= 256)) {
    errors.push('field.spectrum.k_inertial: must be a finite number greater than 0 and at most 256');
  }
  if (!(Number.isFinite(s.sigma) && s.sigma >= 0 && s.sigma <= 100)) {
    errors.push('field.spectrum.sigma: must be between 0 and 100');
  }
  if (!(Number.isInteger(field?.seed) && field.seed >= 0 && field.seed <= 2 ** 53)) {
    errors.push('seed: must be an integer between 0 and 2^53');
  }
  return errors;
}

/**
 * The scene (JSON text, as the engine takes it) of the field `field` alone: no wind, no gas.
 */
export function fieldScene(field) {
  return JSON.stringify({ version: 1, seed: field.seed, field: { size: field.size, spectrum: field.spectrum } });
}

/** A deep copy of `field` with the lattice given as one extent or four. */
export function withSize(field, size) {
  const s = Array.isArray(size) ? size : [size, size, size, size];
  return { ...field, size: [...s], spectrum: { ...field.spectrum } };
}

/**
 * Largest k_inertial that leaves modes with energy on the lattice (the explorer's slider goes no
 * further): the largest |k| among its modes, √(Σ (n/2 − 1)²) over x, y and z (the Nyquist planes
 * are zero). Above it the field is calm.
 */
export function maxInertial(size) {
  return Math.hypot(size[0] / 2 - 1, size[1] / 2 - 1, size[2] / 2 - 1);
}
