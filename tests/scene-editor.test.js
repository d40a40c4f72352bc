// The scene editor's new items are valid scenes as they stand, and the drag handle moves an
// item's anchor (a repulsor's whole path) by exactly the drag.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { loadCore, root } from './support/core.js';
import { latticeChoices, LISTS, TEMPLATES } from '../web/src/pages/scene-editor.js';
import { anchorOf, moved } from '../web/src/views/guides-layer.js';

const core = await loadCore();
const base = JSON.parse(readFileSync(`${root}public/scenes/default.json`, 'utf8'));

test('every template, added to a scene, validates', () => {
  for (const [list, kinds] of Object.entries(TEMPLATES)) {
    for (const [kind, item] of Object.entries(kinds)) {
      const scene = structuredClone(base);
      LISTS[list].get(scene).push(structuredClone(item));
      const normal = JSON.parse(core.validateScene(JSON.stringify(scene)));
      const added = LISTS[list].get(normal).at(-1);
      assert.equal(LISTS[list].kind(added), kind, `${list} ${kind}`);
    }
  }
});

test('a bad edit is refused with its path', () => {
  const scene = structuredClone(base);
  scene.emitters.push({ ...TEMPLATES.emitters.sphere, rate: -5 });
  assert.throws(() => core.validateScene(JSON.stringify(scene)), /emitters\[1\]\.rate/);
});

test('moving an anchor moves the item by the drag', () => {
  const vortex = moved(TEMPLATES.wind.vortex, [1, 2, 3]);
  assert.deepEqual(anchorOf(vortex), [1, 2, 3]);
  assert.deepEqual(vortex.axis, TEMPLATES.wind.vortex.axis);
  const emitter = moved(TEMPLATES.emitters.disk, [0.5, 0, -0.5]);
  assert.deepEqual(emitter.center, [0.5, 0, -0.5]);
  const r = TEMPLATES.wind.repulsor;
  const shifted = moved(r, anchorOf(r).map((v, a) => v + [0.5, -0.25, 1][a]));
  shifted.path.forEach(([t, ...p], k) => {
    assert.equal(t, r.path[k][0]);
    p.forEach((v, a) => assert.ok(Math.abs(v - (r.path[k][a + 1] + [0.5, -0.25, 1][a])) < 1e-12));
  });
  assert.deepEqual(r.path[0], [0, -1, 0.6, 0], 'the original is untouched');
});

test('the lattice list offers only extents the core accepts with the scene\'s k_inertial', () => {
  for (const k of [0.5, 2, 4, 7.5, 15]) {
    const offered = latticeChoices(32, k);
    for (const n of offered) {
      const scene = structuredClone(base);
      scene.field.size = [n, n, n, 8];
      scene.field.spectrum.k_inertial = k;
      assert.doesNotThrow(() => core.validateScene(JSON.stringify(scene)), `n = ${n} with k_inertial = ${k}`);
    }
    if (k === 4) assert.ok(!offered.includes(8), 'a lattice of 8 cannot hold k_inertial = 4');
  }
});
