// The flow's guide: the box's edges, and a faint pane on each closed face, lying on that face.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import * as THREE from 'three';
import { flowGuide } from '../web/src/views/guides-layer.js';

/** The world-space bounds of a guide's child. */
function boundsOf(object) {
  object.updateWorldMatrix(true, false);
  return new THREE.Box3().setFromObject(object);
}

test('a flow closed across y alone shows its edges and two panes, its floor and its lid', () => {
  const box = [-0.45, 0, -0.6, 2.25, 0.3, 0.6];
  const guide = flowGuide({ box, faces: { x: 'open', y: 'closed', z: 'open' } });
  const panes = guide.children.filter((c) => c.isMesh);
  assert.equal(guide.children.filter((c) => c.isLineSegments).length, 1);
  assert.equal(panes.length, 2);
  const near = (a, b) => assert.ok(Math.abs(a - b) < 1e-6, `${a} against ${b}`);
  const ys = [];
  for (const pane of panes) {
    const b = boundsOf(pane);
    near(b.min.x, box[0]);
    near(b.max.x, box[3]);
    near(b.min.z, box[2]);
    near(b.max.z, box[5]);
    near(b.min.y, b.max.y);
    ys.push(b.min.y);
  }
  ys.sort((a, b) => a - b);
  near(ys[0], box[1]);
  near(ys[1], box[4]);
});

test('closed across every axis: six panes, each on its face; open: none', () => {
  const box = [0, 0, 0, 1, 2, 3];
  const closed = flowGuide({ box, faces: 'closed' }).children.filter((c) => c.isMesh);
  assert.equal(closed.length, 6);
  for (const pane of closed) {
    const b = boundsOf(pane);
    const flat = [0, 1, 2].filter((a) => Math.abs(b.max.getComponent(a) - b.min.getComponent(a)) < 1e-6);
    assert.equal(flat.length, 1);
    const a = flat[0];
    assert.ok([box[a], box[a + 3]].some((v) => Math.abs(v - b.min.getComponent(a)) < 1e-6));
    for (const o of [0, 1, 2].filter((c) => c !== a)) {
      assert.ok(Math.abs(b.min.getComponent(o) - box[o]) < 1e-6 && Math.abs(b.max.getComponent(o) - box[o + 3]) < 1e-6);
    }
  }
  assert.equal(flowGuide({ box }).children.filter((c) => c.isMesh).length, 0);
});
