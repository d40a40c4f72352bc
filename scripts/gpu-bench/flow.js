// The flow's step on this machine's GPU (web/src/flow-gpu/), for scripts/gpu-bench/run.sh's
// `flow=32,64` query: a box of n³ cells a metre wide round a solid sphere in a uniform wind of
// 1 m/s, stepped at dt = 1/60 s; each step finished on the GPU (a texel read back) before the
// clock stops. One `{flow: n, stepMs, ...}` figure per n: the median of 20 steps after 10, the
// SOR's iterations and the projection's relative residual at the end.
import { GpuFlow, addSolid, flowGpuUnsupported, noSolids } from './flow-gpu/index.js';

export async function flowBench(log, sizes) {
  const gl = document.createElement('canvas').getContext('webgl2');
  const unsupported = flowGpuUnsupported(gl);
  if (unsupported) {
    log({ flow: 'unsupported', reason: unsupported });
    return;
  }
  const texel = new Float32Array(4);
  for (const n of sizes) {
    const h = 1 / n;
    const grid = { origin: [-0.5, -0.5, -0.5], cells: [n, n, n], h };
    const flow = new GpuFlow(gl, { ...grid, faces: 'open', viscosity: 1.5e-5 });
    const solids = addSolid(noSolids(grid.cells), grid, (x) => Math.hypot(x[0] + 0.2, x[1], x[2]) < 0.15);
    flow.setSolids(solids);
    flow.setUniformWind([1, 0, 0]);
    const finish = () => {
      gl.bindFramebuffer(gl.FRAMEBUFFER, flow.u[0].now.framebuffer);
      gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.FLOAT, texel);
    };
    const times = [];
    for (let k = 0; k < 30; k++) {
      finish();
      const t0 = performance.now();
      flow.step(1 / 60);
      finish();
      if (k >= 10) times.push(performance.now() - t0);
      await new Promise((r) => setTimeout(r, 0));
    }
    times.sort((a, b) => a - b);
    log({ flow: n, stepMs: times[times.length >> 1], fastestMs: times[0], iterations: flow.iterations, residual: flow.residual() });
    flow.dispose();
  }
}
