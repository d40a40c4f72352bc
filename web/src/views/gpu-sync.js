// Waiting for the GPU, for timings: WebGL queues its work, so a clock read after a draw call
// measures nothing until something forces the queue through.

const pixel = new Uint8Array(4);

/** Waits until the GPU has done everything asked of it (reads back one pixel of the canvas); keeps the render target. */
export function waitForGpu(renderer) {
  const target = renderer.getRenderTarget();
  const gl = renderer.getContext();
  renderer.setRenderTarget(null);
  gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
  renderer.setRenderTarget(target);
}
