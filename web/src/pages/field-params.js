// Field parameters as the core takes them (docs/FORMATS.md: the field and the scene format): lattice size, spectrum, seed.
// Pure functions, shared by the field explorer, the classroom and the unit tests. The core
// checks the parameters (the engine refuses a field's scene in the core's words): the page
// writes none of their ranges, and takes their defaults from the core (the contract).

import { DEFAULT_EPSILON, DEFAULT_EXTENT, DEFAULT_K_INERTIAL, DEFAULT_SEED, DEFAULT_SIGMA } from '../generated/contract.js';

/** The core's defaults for a field: the paper's statistics (§6). */
export const DEFAULT_FIELD = Object.freeze({
  size: [DEFAULT_EXTENT, DEFAULT_EXTENT, DEFAULT_EXTENT, DEFAULT_EXTENT],
  spectrum: { law: 'kolmogorov', epsilon: DEFAULT_EPSILON, k_inertial: DEFAULT_K_INERTIAL, sigma: DEFAULT_SIGMA },
  seed: DEFAULT_SEED,
});

/** The spectrum laws (`field.spectrum.law`). */
export const LAWS = ['kolmogorov', 'paper-literal'];

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
