// Where a scene's flow can be stepped: whether it has one that acts, and why the GPU of a WebGL2
// context cannot step it beside the GPU stepper's blobs (its float textures and blending, the
// size of its textures, a memory budget's share), worked out without the flow's passes, which
// come with the first flow the GPU steps (`flow-handoff.js`).

import { flowGpuRefuses, flowGpuUnsupported, heatGpuUnsupported } from '../flow-gpu/gl.js';
import { gpuFlowBytes } from '../flow-gpu/textures.js';

/** Whether `scene` has a flow that acts: an enabled `flow`. */
export function hasFlow(scene) {
  return Boolean(scene?.flow && scene.flow.enabled !== false);
}

/**
 * Why a flow of `cells` must not take the GPU's memory, or null: its textures
 * (`gpuFlowBytes`, on a GPU of textures at most `maxTextureSize` a side) against the `most`
 * bytes a memory budget gives a flow (`MemoryLimit.flowBytes`; Infinity where none applies).
 */
export function flowMemoryRefuses(cells, maxTextureSize, most) {
  const bytes = gpuFlowBytes(cells, maxTextureSize);
  if (bytes <= most) return null;
  const mib = (n) => `${(n / 2 ** 20).toFixed(1)} MiB`;
  return `its ${cells.join(' × ')} cells take ${mib(bytes)} of textures on the GPU, more than the ${mib(most)} this device's memory budget gives a flow`;
}

/**
 * Why the GPU of `gl` cannot step `scene`'s flow beside the blobs, or null when it can (or the
 * scene has no flow): float render targets and blending, textures large
 * enough for its cells, and their bytes within the `most` a memory budget gives a flow.
 */
export function flowKeepsGpuAway(scene, gl, most = Infinity) {
  if (!hasFlow(scene)) return null;
  return flowGpuUnsupported(gl)
    || heatGpuUnsupported(gl)
    || flowGpuRefuses(gl, scene.flow.cells)
    || flowMemoryRefuses(scene.flow.cells, gl.getParameter(gl.MAX_TEXTURE_SIZE), most);
}
