// The npm package: the TypeScript declarations compile in a consumer's file (and reject what
// they should); `npm pack` ships the element's entries, their types and every file the
// bundler entry imports; a bundler (Vite) builds a page that imports the package by name, with
// the player's code split off to load on demand.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, readdirSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join, relative, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = fileURLToPath(new URL('..', import.meta.url));
const pkg = JSON.parse(readFileSync(join(root, 'package.json'), 'utf8'));
const built = existsSync(join(root, 'web/pkg/windfield_bg.wasm'));

test('the declarations type a consumer of the element and of window.windfield', () => {
  const tsc = join(root, 'node_modules/typescript/bin/tsc');
  try {
    execFileSync(process.execPath, [tsc, '-p', join(root, 'tests/types/tsconfig.json')], { encoding: 'utf8' });
  } catch (e) {
    assert.fail(`tsc found errors:\n${e.stdout}${e.stderr}`);
  }
});

test('the declared view names are the ones the player and the element accept', async () => {
  const { VIEWS } = await import('../web/src/views/modes.js');
  const types = readFileSync(join(root, 'types/index.d.ts'), 'utf8');
  const union = types.match(/export type WindFieldView = ([^;]+);/);
  assert.ok(union, 'types/index.d.ts declares WindFieldView');
  assert.deepEqual(union[1].split('|').map((s) => s.trim().replace(/'/g, '')), VIEWS);
});

/** The relative files a module imports (statically, dynamically, or as `new URL(…, import.meta.url)`). */
function imports(file) {
  const text = readFileSync(file, 'utf8');
  const found = new Set();
  const patterns = [
    /\bfrom\s+['"](\.{1,2}\/[^'"]+)['"]/g,
    /\bimport\s*\(\s*['"](\.{1,2}\/[^'"]+)['"]\s*\)/g,
    /^\s*import\s+['"](\.{1,2}\/[^'"]+)['"]/gm,
    /new URL\(\s*['"]([^'"]+\.(?:js|wasm))['"]\s*,\s*import\.meta\.url\s*\)/g,
  ];
  for (const re of patterns) for (const m of text.matchAll(re)) found.add(resolve(dirname(file), m[1]));
  return [...found];
}

/** Every file reachable from `entry` through relative imports. */
function importGraph(entry) {
  const seen = new Set();
  const visit = (file) => {
    if (seen.has(file)) return;
    seen.add(file);
    if (file.endsWith('.js')) for (const f of imports(file)) visit(f);
  };
  visit(entry);
  return [...seen].map((f) => relative(root, f));
}

test('npm pack ships the element (source for bundlers, standalone module), its types and scenes', () => {
  const out = execFileSync('npm', ['pack', '--dry-run', '--json', '--ignore-scripts'], { cwd: root, encoding: 'utf8', stdio: ['ignore', 'pipe', 'ignore'] });
  const files = new Set(JSON.parse(out)[0].files.map((f) => f.path));
  assert.equal(pkg.private, true);
  assert.equal(pkg.types, './types/index.d.ts');
  assert.equal(pkg.exports['.'].default, './web/src/embed.js');
  assert.equal(pkg.exports['.'].types, './types/index.d.ts');
  assert.equal(pkg.exports['./embed.js'].default, './dist/embed.js');
  for (const path of ['package.json', 'types/index.d.ts', 'web/src/embed.js', 'public/scenes/default.json', 'public/presets.json']) {
    assert.ok(files.has(path), `${path} is packed`);
  }
  // Everything the bundler entry imports is in the package (the generated core once built).
  for (const path of importGraph(join(root, 'web/src/embed.js'))) {
    if (path.startsWith('web/pkg/') && !built) continue;
    assert.ok(files.has(path), `${path} (imported by the element) is packed`);
  }
  // The standalone build, when there is one: the loader and every chunk beside it.
  if (existsSync(join(root, 'dist/embed.js'))) {
    assert.ok(files.has('dist/embed.js'));
    for (const name of readdirSync(join(root, 'dist/wind-field'))) assert.ok(files.has(`dist/wind-field/${name}`), name);
  }
  // Nothing but what a consumer needs.
  for (const path of files) assert.doesNotMatch(path, /^(tests|e2e|scripts|wasm-core|docs)\//);
});

test('a bundler builds a page that imports the package; the player code loads on demand', { skip: !built && 'the WASM core is not built' }, async () => {
  const { build } = await import('vite');
  // The consumer sits inside the package so that `windfield` resolves to it by name (as it
  // would from node_modules), through its `exports`.
  const dir = mkdtempSync(join(root, 'tests/.consumer-'));
  const out = mkdtempSync(join(tmpdir(), 'windfield-consumer-'));
  try {
    writeFileSync(join(dir, 'index.html'), '<!doctype html><script type="module" src="./main.js"></script><wind-field preset="default"></wind-field>');
    writeFileSync(join(dir, 'main.js'), "import { WindFieldElement } from 'windfield';\nconsole.log(customElements.get('wind-field') === WindFieldElement);\n");
    await build({ root: dir, configFile: false, logLevel: 'silent', base: './', build: { outDir: out, target: 'es2022' }, worker: { format: 'es' } });
    const assets = readdirSync(join(out, 'assets'));
    const entry = assets.find((f) => /^index-.*\.js$/.test(f));
    const player = assets.find((f) => /^player-.*\.js$/.test(f));
    assert.ok(entry && player, `entry and player chunks in ${assets.join(', ')}`);
    assert.ok(assets.some((f) => /^worker-.*\.js$/.test(f)), 'the engine worker');
    assert.ok(assets.some((f) => /\.wasm$/.test(f)), 'the WASM core');
    // The page's own script is the small loader; three.js lives in the lazily imported chunk.
    const entryCode = readFileSync(join(out, 'assets', entry), 'utf8');
    assert.match(entryCode, new RegExp(`import\\(["'][^"']*${player.replace(/[.]/g, '\\.')}`));
    assert.ok(entryCode.length < 40_000, `entry is ${entryCode.length} bytes`);
    assert.ok(readFileSync(join(out, 'assets', player), 'utf8').includes('WebGLRenderer'));
  } finally {
    rmSync(dir, { recursive: true, force: true });
    rmSync(out, { recursive: true, force: true });
  }
});
