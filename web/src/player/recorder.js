// Frame-accurate WebM recording: each frame is drawn on demand and encoded with WebCodecs
// (VP8) at an exact timestamp k/fps, then muxed by webm-muxer. Nothing depends on how fast
// frames are drawn, so a recording of n frames is the same n simulation steps at any speed.

import { ArrayBufferTarget, Muxer } from 'webm-muxer';

/**
 * Records `frames` frames of `canvas` at `fps`; `renderFrame(k)` draws frame k (awaited).
 * @returns {Promise<Blob>} a video/webm Blob
 */
export async function recordWebM({ canvas, frames, fps = 30, renderFrame, onProgress }) {
  if (typeof VideoEncoder === 'undefined') throw new Error('this browser cannot encode video (no WebCodecs)');
  const { width, height } = canvas;
  if (width % 2 || height % 2) throw new Error(`video needs an even width and height (got ${width}×${height})`);
  const config = { codec: 'vp8', width, height, bitrate: 6e6, framerate: fps };
  const support = await VideoEncoder.isConfigSupported(config);
  if (!support.supported) throw new Error('this browser cannot encode VP8 video');
  const muxer = new Muxer({ target: new ArrayBufferTarget(), video: { codec: 'V_VP8', width, height, frameRate: fps } });
  let failure = null;
  const encoder = new VideoEncoder({
    output: (chunk, meta) => muxer.addVideoChunk(chunk, meta),
    error: (e) => { failure = e; },
  });
  encoder.configure(config);
  const frameUs = 1e6 / fps;
  for (let k = 0; k < frames && !failure; k++) {
    await renderFrame(k);
    const frame = new VideoFrame(canvas, { timestamp: Math.round(k * frameUs), duration: Math.round(frameUs) });
    encoder.encode(frame, { keyFrame: k % fps === 0 });
    frame.close();
    onProgress?.((k + 1) / frames);
  }
  await encoder.flush();
  encoder.close();
  if (failure) throw failure;
  muxer.finalize();
  return new Blob([muxer.target.buffer], { type: 'video/webm' });
}
