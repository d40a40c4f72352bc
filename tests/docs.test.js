// The docs say what the code does: the embedding guide lists exactly the presets there are, and
// names every attribute the element observes and every method its API has.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';

const root = new URL('../', import.meta.url);
const read = (path) => readFileSync(new URL(path, root), 'utf8');

test('the embedding guide lists exactly the presets in public/presets.json', () => {
  const guide = read('web/embed.html');
  const row = guide.match(/<tr><td><code>preset<\/code><\/td><td>([^]*?)<\/td><\/tr>/);
  assert.ok(row, 'the guide has a row for the preset attribute');
  const listed = [...row[1].split('(')[0].matchAll(/<code>([a-z0-9-]+)<\/code>/g)].map((m) => m[1]).filter((n) => n !== 'scenes/');
  const presets = JSON.parse(read('public/presets.json')).presets.map((p) => p.name);
  assert.deepEqual([...listed].sort(), [...presets].sort());
});

test('the embedding guide names every attribute the element observes and every method of its API', () => {
  const guide = read('web/embed.html');
  const element = read('web/src/embed.js');
  const observed = JSON.parse(element.match(/observedAttributes\(\) \{\s*return (\[[^\]]*\])/)[1].replace(/'/g, '"'));
  for (const name of observed) assert.match(guide, new RegExp(`<tr><td><code>${name}</code></td>`), `attribute ${name}`);
  const api = read('web/src/element/api.js');
  const methods = [...api.matchAll(/^ {2}(?:async )?([a-zA-Z]+)\(/gm)].map((m) => m[1]);
  assert.ok(methods.length >= 8);
  for (const name of methods) assert.match(guide, new RegExp(`<code>${name}\\(`), `method ${name}`);
});

test('the guide states the poster time every preset has', () => {
  const guide = read('web/embed.html');
  const presets = JSON.parse(read('public/presets.json')).presets.map((p) => p.name);
  const times = presets.map((name) => JSON.parse(read(`public/scenes/${name}.json`)).render?.time ?? 3);
  const [lo, hi] = [Math.min(...times), Math.max(...times)];
  assert.match(guide, new RegExp(`from ${lo} s to ${hi} s among the presets`));
});
