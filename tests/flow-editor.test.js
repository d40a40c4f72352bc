// The playground's flow editor: a flow added round any preset's emitters, and every refit of its
// cells, is a flow the core accepts (cubes within 1 %, 8 to 256 cells an axis).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { loadCore, root } from './support/core.js';
import { defaultFlow, fitFlowBox, flowFaces, flowLongest, FLOW_CELLS } from '../web/src/pages/scene-editor.js';
import { closedAxes } from '../web/src/flow-gpu/boundary.js';

const core = await loadCore();
const presets = JSON.parse(readFileSync(`${root}public/presets.json`, 'utf8')).presets.map(({ name }) => name);
const load = (name) => JSON.parse(readFileSync(`${root}public/scenes/${name}.json`, 'utf8'));
const validate = (scene) => JSON.parse(core.validateScene(JSON.stringify(scene)));

test('a flow added round each preset\'s emitters validates and holds its emitters', () => {
  for (const name of presets) {
    // As the playground holds it: normalised by the core.
    const scene = validate(load(name));
    delete scene.flow;
    scene.flow = defaultFlow(scene);
    const flow = validate(scene).flow;
    assert.ok(flow.enabled, name);
    for (const e of scene.emitters) {
      for (let a = 0; a < 3; a += 1) {
        assert.ok(e.center[a] > flow.box[a] && e.center[a] < flow.box[a + 3], `${name}: emitter inside the box along ${'xyz'[a]}`);
      }
    }
  }
});

test('every offered cell count refits the box to cubes the core accepts', () => {
  const scene = load('default');
  for (const bounds of [[-0.4, 0, -0.4, 0.4, 1.6, 0.4], [-1.5, 0, -0.6, 1.5, 1.2, 0.6], [0, 0, 0, 3, 0.05, 0.7]]) {
    for (const n of FLOW_CELLS) {
      const fitted = fitFlowBox(bounds, n);
      const h = fitted.cells.map((c, a) => (fitted.box[a + 3] - fitted.box[a]) / c);
      for (const x of h) assert.ok(Math.abs(x - h[0]) <= 1e-3 * h[0], `cubes: ${h}`);
      assert.equal(flowLongest(fitted), n);
      scene.flow = { ...fitted };
      assert.doesNotThrow(() => validate(scene), `${bounds} at ${n} cells`);
    }
  }
});

test('the faces across each axis, as the panel writes them, are the faces the core reads', () => {
  const scene = load('cylinder-wake');
  for (let bits = 0; bits < 8; bits += 1) {
    const across = Object.fromEntries(['x', 'y', 'z'].map((a, i) => [a, bits & (1 << i) ? 'closed' : 'open']));
    scene.flow.faces = flowFaces(across);
    const read = validate(scene).flow.faces;
    assert.deepEqual(closedAxes(read), [0, 1, 2].map((i) => Boolean(bits & (1 << i))), JSON.stringify(read));
    if (bits === 0 || bits === 7) assert.equal(typeof read, 'string');
  }
});
