// The browser API's arguments read before they are trusted: each is checked like a scene's
// numbers, and refused with its name, its range and what it was.

/** `value` as a short text for a message (1e308 stays 1e308, not 309 digits). */
export function shown(value) {
  if (typeof value === 'number') return Number.isFinite(value) && Math.abs(value) >= 1e6 ? value.toExponential() : String(value);
  if (typeof value === 'string') return JSON.stringify(value.length > 40 ? `${value.slice(0, 40)}…` : value);
  if (value === undefined || value === null) return String(value);
  return typeof value;
}

/** `value` if it is a whole number from `min` to `max`, else an Error naming `name` and the range. */
export function wholeNumber(name, value, min, max) {
  if (Number.isInteger(value) && value >= min && value <= max) return value;
  throw new Error(`${name} must be a whole number from ${min.toLocaleString('en')} to ${max.toLocaleString('en')} (got ${shown(value)})`);
}

/** `value` if it is a whole number of at least `min` (a budget checked elsewhere bounds it), else an Error. */
export function atLeast(name, value, min) {
  if (Number.isInteger(value) && value >= min) return value;
  throw new Error(`${name} must be a whole number of at least ${min} (got ${shown(value)})`);
}

/** `value` if it is a finite number in (`min`, `max`] (`min` itself allowed when `closed`), else an Error. */
export function number(name, value, min, max, { closed = false } = {}) {
  if (typeof value === 'number' && Number.isFinite(value) && (closed ? value >= min : value > min) && value <= max) return value;
  throw new Error(`${name} must be a number ${closed ? 'from' : 'greater than'} ${min} ${closed ? 'to' : 'and at most'} ${max} (got ${shown(value)})`);
}

/** `value` if it is one of `choices`, else an Error listing them. */
export function oneOf(name, value, choices) {
  if (choices.includes(value)) return value;
  throw new Error(`${name} must be one of ${choices.map((c) => `'${c}'`).join(', ')} (got ${shown(value)})`);
}

/** `value` if it is a boolean, else an Error. */
export function boolean(name, value) {
  if (typeof value === 'boolean') return value;
  throw new Error(`${name} must be true or false (got ${shown(value)})`);
}

/**
 * The JSON path of the first number in `value` that JSON cannot hold (NaN, ±Infinity, which
 * `JSON.stringify` would turn into null), and that number; or null when there is none.
 */
export function nonFinite(value, path = '') {
  if (typeof value === 'number') return Number.isFinite(value) ? null : { path, value };
  if (!value || typeof value !== 'object') return null;
  for (const [k, v] of Object.entries(value)) {
    const found = nonFinite(v, Array.isArray(value) ? `${path}[${k}]` : path ? `${path}.${k}` : k);
    if (found) return found;
  }
  return null;
}
