// The playground's wind slice: the core's `windSlice` samples u = u_l + u_s (Eq. 3) where the
// slice's square says, and the square lies where the view asks.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { loadCore, root } from './support/core.js';
import { sliceGeometry } from '../web/src/views/wind-slice-layer.js';

const core = await loadCore();
const base = JSON.parse(readFileSync(`${root}public/scenes/default.json`, 'utf8'));

/** Uniform wind plus a source (no turbulence): u = U + s/(4π) · r / (|r|² + a²)^{3/2}. */
function closedForm(x, U, p, s, a) {
  const r = x.map((c, i) => c - p[i]);
  const d2 = r[0] ** 2 + r[1] ** 2 + r[2] ** 2 + a * a;
  return r.map((c, i) => U[i] + (s / (4 * Math.PI)) * c / (d2 * Math.sqrt(d2)));
}

test('windSlice samples the whole wind at the cell centres of its square', () => {
  const U = [0.3, -0.1, 0.05];
  const source = { type: 'source', position: [0.1, 0.8, -0.2], strength: 0.5, radius: 0.05 };
  const scene = { ...structuredClone(base), wind: [{ type: 'uniform', velocity: U }, source] };
  scene.field.amplitude = 0;
  // No solid floor here: the closed form is the wind of the primitives alone.
  scene.render.objects = scene.render.objects.map((o) => ({ ...o, solid: false }));
  const sim = new core.SceneSimulation(JSON.stringify(scene));
  const square = sliceGeometry('xz', [0, 0.8, 0], 1.2, 0.1);
  const n = 7;
  const data = sim.windSlice(new Float32Array(square.origin), new Float32Array(square.u), new Float32Array(square.v), n, n);
  assert.equal(data.length, 3 * n * n);
  for (let j = 0; j < n; j++) {
    for (let i = 0; i < n; i++) {
      const x = square.origin.map((c, k) => c + ((i + 0.5) / n) * square.u[k] + ((j + 0.5) / n) * square.v[k]);
      const want = closedForm(x, U, source.position, source.strength, source.radius);
      for (let k = 0; k < 3; k++) {
        const got = data[3 * (j * n + i) + k];
        assert.ok(Math.abs(got - want[k]) < 1e-5, `(${i}, ${j}) component ${k}: ${got} vs ${want[k]}`);
      }
    }
  }
  // With turbulence on, the slice carries it: the samples are no longer the closed form.
  const turbulent = new core.SceneSimulation(JSON.stringify({ ...scene, field: base.field }));
  const t = turbulent.windSlice(new Float32Array(square.origin), new Float32Array(square.u), new Float32Array(square.v), n, n);
  assert.ok(t.some((v, k) => Math.abs(v - data[k]) > 1e-3));
  assert.throws(() => sim.windSlice(new Float32Array([0, 0]), new Float32Array(square.u), new Float32Array(square.v), n, n), /origin/);
  assert.throws(() => sim.windSlice(new Float32Array(square.origin), new Float32Array([NaN, 0, 0]), new Float32Array(square.v), n, n), /u must be/);
  assert.throws(() => sim.windSlice(new Float32Array(square.origin), new Float32Array(square.u), new Float32Array(square.v), 0, n), /between 1 and 256/);
  sim.free();
  turbulent.free();
});

test('the slice square is centred on the target, offset along its normal', () => {
  for (const [plane, normal] of [['xy', [0, 0, 1]], ['xz', [0, 1, 0]], ['yz', [1, 0, 0]]]) {
    const { origin, u, v } = sliceGeometry(plane, [1, 2, 3], 2, 0.5);
    const centre = origin.map((c, i) => c + 0.5 * (u[i] + v[i]));
    centre.forEach((c, i) => assert.ok(Math.abs(c - ([1, 2, 3][i] + 0.5 * normal[i])) < 1e-12, plane));
    assert.deepEqual([Math.hypot(...u), Math.hypot(...v)], [2, 2]);
    const cross = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
    cross.forEach((c, i) => assert.ok(Math.abs(c / 4 - normal[i]) < 1e-12, plane));
  }
  assert.equal(sliceGeometry('off', [0, 0, 0], 1), null);
});
