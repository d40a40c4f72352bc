// A scene's flow (docs/FORMATS.md, the flow) set up on the GPU as the core's `SceneFlow` sets
// it up: the grid of `flow.box` and `flow.cells` (cubes of edge h, the mean of the three
// spacings), its faces and constants (air's ν and β and Earth's g where the scene names none),
// Smagorinsky's eddy viscosity (a scene's flow always has it; `options.eddies` false leaves it
// out), the solid objects' cells (a cell whose centre is inside: the signed distance of the
// sphere, the plane or the capped cylinder below 0) and the primitives' wind u_p on the faces.
// u_p is set here from the uniform winds without a decay (the same on every face); with other
// primitives the GPU stepper sets each step's on the faces from its wind table, and a
// repulsor's sphere is solid cells over the objects' where the table puts it
// (`boundary.js`'s `repulsorSolids`).

import { GpuFlow } from './gpu-flow.js';
import { addSolid, noSolids } from './boundary.js';
import { flowGpuRefuses } from './gl.js';

const f32 = Math.fround;

/** The signed distance (m, negative inside) from `x` (m) of a solid object of the scene format. */
export function solidDistance(o, x) {
  const sub = (a, b) => a.map((v, i) => f32(v - b[i]));
  const dot = (a, b) => f32(a.reduce((s, v, i) => s + v * b[i], 0));
  const unit = (a) => {
    const n = Math.hypot(...a);
    return a.map((v) => f32(v / n));
  };
  if (o.type === 'sphere') return f32(Math.hypot(...sub(x, o.center)) - o.radius);
  if (o.type === 'plane') return dot(sub(x, o.point), unit(o.normal));
  if (o.type === 'cylinder') {
    const axis = unit(o.axis);
    const r = sub(x, o.base);
    const s = dot(r, axis);
    const rho = Math.hypot(...r.map((v, i) => v - axis[i] * s));
    const dr = f32(rho - o.radius);
    const ds = s > 0.5 * o.height ? f32(s - o.height) : -s;
    return dr > 0 && ds > 0 ? f32(Math.hypot(dr, ds)) : Math.max(dr, ds);
  }
  return Infinity;
}

/**
 * Why the GPU's flow cannot take `scene` whatever the GPU, or null when it can: it needs an
 * enabled flow.
 */
export function gpuFlowRefusesScene(scene) {
  const f = scene.flow;
  if (!f || f.enabled === false) return 'the scene has no flow';
  return null;
}

/**
 * The flow of `scene` on the GPU of `gl` at rest (`{flow, solids}`, solids its objects' cells),
 * or why not (`{refused}`): no enabled flow, or a grid too large for its textures.
 * `options` override GpuFlow's settings (`eddies: false`, the SOR's `iterations`, ...).
 */
export function gpuFlowOfScene(gl, scene, options = {}) {
  const refused = gpuFlowRefusesScene(scene);
  if (refused) return { refused };
  const f = scene.flow;
  const winds = (scene.wind ?? []).filter((p) => p.enabled !== false);
  const cells = f.cells;
  const large = flowGpuRefuses(gl, cells);
  if (large) return { refused: large };
  const origin = f.box.slice(0, 3);
  const h = [0, 1, 2].map((a) => (f.box[a + 3] - f.box[a]) / cells[a]).reduce((s, v) => s + v) / 3;
  const flow = new GpuFlow(gl, {
    origin, cells, h,
    faces: f.faces ?? 'open',
    viscosity: f.viscosity ?? 1.5e-5,
    buoyancy: f.buoyancy ?? 1 / 293.15,
    gravity: f.gravity ?? [0, -9.81, 0],
    eddies: true,
    ...options,
  });
  const solids = noSolids(cells);
  for (const o of (scene.render?.objects ?? []).filter((o) => o.solid)) {
    addSolid(solids, { origin: flow.origin, cells, h: flow.h }, (x) => solidDistance(o, x) < 0);
  }
  flow.setSolids(solids);
  // u_p from the uniform winds without a decay; the GPU stepper sets each step's from its wind
  // table where the scene has other primitives (`GpuFlow.setWindTable`).
  const constant = winds.filter((p) => p.type === 'uniform' && (p.decay ?? null) === null);
  flow.setUniformWind([0, 1, 2].map((a) => f32(constant.reduce((s, p) => f32(s + p.velocity[a]), 0))));
  return { flow, solids };
}
