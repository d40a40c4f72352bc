// The WASM core's door (wasm-core/src/api/, the full module) against what the JavaScript calls: every export
// the engine worker, the classroom page, the benchmarks and the tests use is there, and the
// removed ones (unused getters, and the order-dependent frame getters replaced by whole frames)
// are gone.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { loadCore } from './support/core.js';

const core = await loadCore();

/** Each class the JavaScript constructs, with the methods it calls on it. */
const USED = {
  FieldSynthesis: ['step', 'stage', 'progress', 'finish', 'free'],
  WindField: ['size', 'data', 'sample', 'slice_xy', 'stats', 'free'],
  SceneSimulation: [
    'edit', 'editWithField', 'setField', 'stir', 'step', 'checkSteps', 'time', 'count', 'positions', 'addBlobs',
    'blobList', 'windSlice', 'packFrame', 'marchFrame', 'volumeTwin', 'lightTwin', 'marchList', 'free',
  ],
  ReferenceRender: ['step', 'progress', 'width', 'height', 'rgb', 'png', 'free'],
  StillExport: ['step', 'progress', 'bytes', 'free'],
  FlipbookExport: ['step', 'progress', 'finish', 'free'],
  VolumeExport: ['step', 'progress', 'finish', 'free'],
  Figure1Demo: ['step', 'time', 'n', 'grid', 'blobs', 'gridMass', 'blobMass', 'free'],
};

test('every export the JavaScript uses is there', () => {
  for (const name of ['validateScene', 'sceneFieldParams']) assert.equal(typeof core[name], 'function', name);
  assert.equal(typeof core.WindField.generate, 'function', 'WindField.generate');
  assert.equal(typeof core.SceneSimulation.withField, 'function', 'SceneSimulation.withField');
  assert.equal(typeof core.FlipbookExport.withField, 'function', 'FlipbookExport.withField');
  assert.equal(typeof core.WindField.fromLattice, 'function', 'WindField.fromLattice');
  for (const [cls, methods] of Object.entries(USED)) {
    assert.equal(typeof core[cls], 'function', cls);
    for (const m of methods) assert.equal(typeof core[cls].prototype[m], 'function', `${cls}.${m}`);
  }
});

test('the removed exports are gone', () => {
  const gone = ['sigma', 'mass', 'albedo', 'emission', 'age', 'objects', 'counts', 'frameInfo', 'marchGrid', 'movingSpheres'];
  for (const m of gone) assert.equal(core.SceneSimulation.prototype[m], undefined, `SceneSimulation.${m}`);
});
