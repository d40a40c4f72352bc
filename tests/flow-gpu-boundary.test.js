// The GPU flow's boundary conditions and atlases (web/src/flow-gpu/), worked out on the CPU:
// each face's kind and fixed normal velocity and each cell's Poisson row, as the core's
// `wind::flow::boundary` and projection set them, every lattice sample in its own texel, the
// grids too large for a GPU's textures, and the solid objects' signed distances.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { addSolid, boundaryOf, closedAxes, faceDims, FREE, HOLDING, noSolids, repulsorSolids, sameSolids, SLIPPING } from '../web/src/flow-gpu/boundary.js';
import { atlasOf, atlasTexel, flowGpuRefuses } from '../web/src/flow-gpu/gl.js';
import { gpuFlowRefusesScene, solidDistance } from '../web/src/flow-gpu/scene.js';
import { REPULSOR_KIND, WIND_TABLE_HEADER, WIND_TABLE_PRIMITIVE } from '../web/src/generated/contract.js';

const cells = [3, 3, 3];
const grid = { origin: [0, 0, 0], cells, h: 1 };
const cell = (i, j, k) => i + 3 * (j + 3 * k);
/** [kind, v] of face (i, j, k) of component `a`. */
const faceOf = (kinds, a, i, j, k) => {
  const d = faceDims(cells, a);
  const f = 2 * (i + d[0] * (j + d[1] * k));
  return [kinds[a][f], kinds[a][f + 1]];
};

test('a 3³ open box round a moving solid centre cell: its faces carry its velocity, the box\'s faces are free', () => {
  const solids = addSolid(noSolids(cells), grid, (x) => x.every((v) => v === 1.5), [0.25, -0.5, 1]);
  assert.equal(solids.solid[cell(1, 1, 1)], 1);
  assert.equal(solids.solid.reduce((s, v) => s + v, 0), 1);
  const { kinds, rows, definite } = boundaryOf(cells, solids, 'open');
  assert.equal(definite, true);
  // The solid cell's six faces: fixed at its velocity's normal component, holding the air.
  assert.deepEqual(faceOf(kinds, 0, 1, 1, 1), [HOLDING, 0.25]);
  assert.deepEqual(faceOf(kinds, 0, 2, 1, 1), [HOLDING, 0.25]);
  assert.deepEqual(faceOf(kinds, 1, 1, 2, 1), [HOLDING, -0.5]);
  assert.deepEqual(faceOf(kinds, 2, 1, 1, 1), [HOLDING, 1]);
  // The box's faces and the others inside: free.
  assert.deepEqual(faceOf(kinds, 0, 0, 1, 1), [FREE, 0]);
  assert.deepEqual(faceOf(kinds, 1, 0, 0, 0), [FREE, 0]);
  // A corner cell: six free faces (three open), linked to its three neighbours.
  assert.equal(rows[4 * cell(0, 0, 0)], 6);
  assert.equal(rows[4 * cell(0, 0, 0) + 1], 0b000111);
  // Beside the solid: five free faces, not linked to it.
  assert.equal(rows[4 * cell(0, 1, 1)], 5);
  assert.equal(rows[4 * cell(0, 1, 1) + 1] & 1, 0);
  assert.equal(rows[4 * cell(1, 1, 1)], 0);
});

test('a 3³ closed box: the walls are fixed at 0 and slip, the system is singular, a corner cell has three free faces', () => {
  const { kinds, rows, definite } = boundaryOf(cells, noSolids(cells), 'closed');
  assert.equal(definite, false);
  assert.deepEqual(faceOf(kinds, 0, 0, 1, 2), [SLIPPING, 0]);
  assert.deepEqual(faceOf(kinds, 2, 1, 1, 3), [SLIPPING, 0]);
  assert.deepEqual(faceOf(kinds, 1, 1, 1, 1), [FREE, 0]);
  assert.equal(rows[4 * cell(0, 0, 0)], 3);
  assert.equal(rows[4 * cell(1, 1, 1)], 6);
  assert.equal(rows[4 * cell(2, 2, 2) + 1], 0b111000);
});

test('a 3³ box with walls across y alone: those faces fixed at 0, the faces across x and z free, the system definite', () => {
  const { kinds, rows, definite } = boundaryOf(cells, noSolids(cells), { y: 'closed' });
  assert.equal(definite, true);
  assert.deepEqual(faceOf(kinds, 1, 1, 0, 1), [SLIPPING, 0]);
  assert.deepEqual(faceOf(kinds, 1, 1, 3, 1), [SLIPPING, 0]);
  assert.deepEqual(faceOf(kinds, 0, 0, 1, 1), [FREE, 0]);
  assert.deepEqual(faceOf(kinds, 2, 1, 1, 3), [FREE, 0]);
  // A corner cell: its two faces on the box across x and z free, the one across y a wall.
  assert.equal(rows[4 * cell(0, 0, 0)], 5);
  assert.deepEqual(closedAxes({ y: 'closed' }), [false, true, false]);
  assert.deepEqual(closedAxes({ x: 'closed', y: 'open', z: 'closed' }), [true, false, true]);
  assert.deepEqual(closedAxes('closed'), [true, true, true]);
  assert.deepEqual(closedAxes(undefined), [false, false, false]);
});

test('every sample of a lattice has a texel of its own in its atlas', () => {
  for (const dims of [[17, 16, 16], [65, 64, 64], [8, 9, 200]]) {
    const atlas = atlasOf(dims, 4096);
    assert.ok(atlas.width <= 4096 && atlas.height <= 4096);
    const seen = new Set();
    for (let k = 0; k < dims[2]; k++) {
      for (let j = 0; j < dims[1]; j++) {
        for (let i = 0; i < dims[0]; i++) seen.add(atlasTexel(atlas, i, j, k));
      }
    }
    assert.equal(seen.size, dims[0] * dims[1] * dims[2]);
    for (const t of seen) assert.ok(t < atlas.width * atlas.height);
  }
  assert.throws(() => atlasOf([257, 256, 256], 4096), /does not fit/);
});

test('a grid whose faces do not fit 4096-texel atlases is refused, naming its cells', () => {
  const gl = { MAX_TEXTURE_SIZE: 0x0d33, getParameter: () => 4096 };
  assert.equal(flowGpuRefuses(gl, [128, 128, 128]), null);
  assert.equal(flowGpuRefuses(gl, [64, 64, 64]), null);
  assert.match(flowGpuRefuses(gl, [256, 256, 256]), /256 × 256 × 256 cells do not fit/);
});

test('the solid objects\' signed distances: a sphere, a plane, a capped cylinder', () => {
  const near = (a, b) => assert.ok(Math.abs(a - b) < 1e-6, `${a} against ${b}`);
  near(solidDistance({ type: 'sphere', center: [1, 0, 0], radius: 0.5 }, [1, 2, 0]), 1.5);
  near(solidDistance({ type: 'plane', point: [0, 1, 0], normal: [0, 2, 0] }, [3, 0.25, 1]), -0.75);
  const cylinder = { type: 'cylinder', base: [0, 0, 0], axis: [0, 0, 1], radius: 0.5, height: 2 };
  near(solidDistance(cylinder, [0.2, 0, 1]), -0.3);
  near(solidDistance(cylinder, [0, 0, 1.9]), -0.1);
  near(solidDistance(cylinder, [0, 0, -0.5]), 0.5);
  near(solidDistance(cylinder, [1.5, 0, 3]), Math.SQRT2);
  assert.equal(solidDistance({ type: 'box' }, [0, 0, 0]), Infinity);
});

test('the GPU takes a scene\'s flow under any primitives, and says why it does not take one without a flow', () => {
  const flow = { box: [0, 0, 0, 1, 1, 1], cells: [8, 8, 8] };
  const uniform = { type: 'uniform', velocity: [0.5, 0, 0], decay: null };
  assert.equal(gpuFlowRefusesScene({ flow, wind: [uniform, { ...uniform, velocity: [0, 0.1, 0] }] }), null);
  assert.equal(gpuFlowRefusesScene({ flow, wind: [] }), null);
  assert.equal(gpuFlowRefusesScene({ flow, wind: [{ ...uniform, decay: 0.5 }, { type: 'source', position: [0, 0, 0], strength: 1 }] }), null);
  assert.equal(gpuFlowRefusesScene({ flow, wind: [uniform, { type: 'repulsor', radius: 0.1 }] }), null);
  assert.match(gpuFlowRefusesScene({ flow: { ...flow, enabled: false }, wind: [] }), /no flow/);
  assert.match(gpuFlowRefusesScene({ wind: [] }), /no flow/);
});

test('a wind table\'s repulsors are solid cells over the objects\' where their spheres are, moving with them; their mirror images are not', () => {
  const grid = { origin: [0, 0, 0], cells: [8, 8, 8], h: 0.125 };
  const fixed = noSolids(grid.cells);
  addSolid(fixed, grid, (x) => x[1] < 0.125);
  const table = new Float32Array(WIND_TABLE_HEADER + 2 * WIND_TABLE_PRIMITIVE);
  table[19] = 2;
  const put = (j, plane, centre) => {
    const at = WIND_TABLE_HEADER + WIND_TABLE_PRIMITIVE * j;
    table.set([REPULSOR_KIND, 0, 0.2, 0.1, 0, 0, 0, plane, ...centre, -1, 0.3, -0.1, 0, 0], at);
  };
  put(0, -1, [0.5, 0.5, 0.5]);
  // An image of it in a solid plane (plane 0): no solid cells of its own.
  put(1, 0, [0.5, 0.5, 0.9]);
  const solids = repulsorSolids(fixed, grid, table);
  const cell = (i, j, k) => i + 8 * (j + 8 * k);
  // Centres 0.0625 + 0.125·n: (0.4375, 0.4375, 0.4375) is 0.108 m from the centre, (0.1875, …) 0.54.
  assert.equal(solids.solid[cell(3, 3, 3)], 1);
  assert.deepEqual(Array.from(solids.velocity.subarray(3 * cell(3, 3, 3), 3 * cell(3, 3, 3) + 3)), [0.3, -0.1, 0].map(Math.fround));
  assert.equal(solids.solid[cell(1, 3, 3)], 0);
  assert.equal(solids.solid[cell(3, 3, 7)], 0);
  assert.equal(solids.solid[cell(5, 0, 2)], 1);
  assert.equal(solids.solid.reduce((n, v) => n + v, 0), 64 + 8);
  assert.equal(fixed.solid.reduce((n, v) => n + v, 0), 64);
  assert.ok(sameSolids(fixed, noSolids(grid.cells)) === false && sameSolids(solids, repulsorSolids(fixed, grid, table)));
  table[19] = 0;
  assert.equal(repulsorSolids(fixed, grid, table), null);
});
