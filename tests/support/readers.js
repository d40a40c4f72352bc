// The file formats' own readers, for the tests that hold windfield's exports to them: OpenEXR's
// Python bindings (`OpenEXR` on PyPI) and OpenVDB's (Debian's python3-openvdb, the module
// `pyopenvdb`), run by the project-local Python that `scripts/setup.sh --readers` makes
// (`.venv/`, from Debian's python3 with its system packages, so that it sees pyopenvdb). The
// scripts are in tests/readers/. Missing readers fail the test with what to run; they never
// skip it.
import { execFileSync } from 'node:child_process';
import { existsSync } from 'node:fs';
import { root } from './core.js';

const python = `${root}.venv/bin/python`;
let checked = null;

/** Throws a clear Error unless the readers are installed. */
export function requireReaders() {
  if (checked) return;
  const how = 'run `bash scripts/setup.sh --readers` (npm test does): it installs python3-openvdb with apt and OpenEXR into .venv/';
  if (!existsSync(python)) throw new Error(`the file formats' readers are missing (no ${python}): ${how}`);
  try {
    execFileSync(python, ['-c', 'import OpenEXR, pyopenvdb, numpy'], { stdio: 'pipe' });
  } catch (err) {
    throw new Error(`the file formats' readers cannot be imported (${err.stderr?.toString().trim().split('\n').pop()}): ${how}`);
  }
  checked = true;
}

/** Runs tests/readers/`script` with `args`; its JSON output, parsed. */
export function reader(script, ...args) {
  requireReaders();
  const out = execFileSync(python, [`${root}tests/readers/${script}`, ...args.map(String)], {
    encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'], maxBuffer: 256 << 20,
  });
  return JSON.parse(out);
}
