// The flow on the GPU: `GpuFlow` steps the grid's u_g with WebGL2 passes where
// `flowGpuUnsupported` finds nothing missing; `noSolids` and `addSolid` mark its solid cells,
// and `gpuFlowOfScene` sets one up from a scene as the core does.
export { GpuFlow, STIR_CELLS, STIR_TIME } from './gpu-flow.js';
export { addSolid, faceDims, noSolids } from './boundary.js';
export { flowGpuRefuses, flowGpuUnsupported } from './gl.js';
export { gpuFlowOfScene, solidDistance } from './scene.js';
