// The flow on the GPU: `GpuFlow` steps the grid's u_g with WebGL2 passes where
// `flowGpuUnsupported` finds nothing missing; `noSolids` and `addSolid` mark its solid cells,
// `gpuFlowOfScene` sets one up from a scene as the core does, `gpuFlowBytes` says what its
// textures take before it is made; `HeatDeposit` adds the GPU
// stepper's blobs' heat up on its cells, and FLOW_SAMPLE_GLSL samples its u_g for their step.
export { GpuFlow, STIR_CELLS, STIR_TIME } from './gpu-flow.js';
export { gpuFlowBytes } from './textures.js';
export { addSolid, faceDims, noSolids, repulsorSolids, sameSolids } from './boundary.js';
export { flowGpuRefuses, flowGpuUnsupported, heatGpuUnsupported } from './gl.js';
export { gpuFlowOfScene, gpuFlowRefusesScene, solidDistance } from './scene.js';
export { HeatDeposit } from './heat.js';
export { FLOW_SAMPLE_GLSL, flowUniforms } from './sample-glsl.js';
