// Loads the built WASM core (web/pkg) and the native CLI for tests and benchmarks.
import { readFileSync, existsSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { execFileSync } from 'node:child_process';

export const root = fileURLToPath(new URL('../../', import.meta.url));
export const cliPath = `${root}wasm-core/target/release/windfield`;
const pkg = `${root}web/pkg/`;

/**
 * Initialises the WASM core (built by `npm run build:wasm`): the full module (every binding),
 * or with `player` the first module a player fetches (web/pkg/windfield.js). Returns its JS
 * bindings plus `memory`, the instance's linear memory.
 */
export async function loadCore({ player = false } = {}) {
  const name = player ? 'windfield' : 'windfield_full';
  if (!existsSync(`${pkg}${name}_bg.wasm`)) {
    throw new Error('web/pkg is missing: run `npm run build:wasm` first');
  }
  const core = await import(`${pkg}${name}.js`);
  const exports = core.initSync({ module: readFileSync(`${pkg}${name}_bg.wasm`) });
  return { ...core, memory: exports.memory };
}

/** Runs the native CLI (built by `cargo build --release`); returns stdout. */
export function cli(args) {
  if (!existsSync(cliPath)) throw new Error('native CLI missing: run `cargo build --release` in wasm-core/');
  return execFileSync(cliPath, args, { encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] });
}
