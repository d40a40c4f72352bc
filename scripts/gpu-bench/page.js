// The real-time view's frame on a real GPU, for scripts/gpu-bench/run.sh: loaded into a copy of
// the playground, it drives window.windfield and reports through the console (one
// `GPUBENCH {json}` line per figure), so it needs no driver program beside the browser. Query:
// frames, counts, qualities; `profile` adds the volume passes' times (each waits for the GPU).
const log = (o) => console.log(`GPUBENCH ${JSON.stringify(o)}`);
const query = new URLSearchParams(location.search);
const frames = Number(query.get('frames') || 10);
const counts = (query.get('counts') || '10000,100000').split(',').map(Number);
const qualities = (query.get('qualities') || 'standard,high').split(',');

/** The WebGL2 renderer's name, unmasked where the browser allows. */
function renderer() {
  const gl = document.createElement('canvas').getContext('webgl2');
  if (!gl) return 'no WebGL2';
  const info = gl.getExtension('WEBGL_debug_renderer_info');
  return gl.getParameter(info ? info.UNMASKED_RENDERER_WEBGL : gl.RENDERER);
}

/** One plume, 5 s of emission, at `n` blobs (as scripts/bench-browser.mjs). */
async function plumeOf(w, plume, n) {
  const scene = structuredClone(plume);
  w.pause();
  scene.emitters[0].rate = n / 5;
  scene.gas.max_blobs = n;
  await w.setScene(scene);
  await w.step(Math.round(5 / scene.simulation.dt));
  return w.stats().blobs;
}

async function main() {
  log({ renderer: renderer() });
  while (!window.windfield) await new Promise((r) => setTimeout(r, 100));
  const w = window.windfield;
  await w.ready;
  const plume = await (await fetch('./dense-plume.json')).json();
  for (const n of counts) {
    const blobs = await plumeOf(w, plume, n);
    const frame = async (mode, width, height, quality) => {
      const ms = await w.timeFrames({ mode, width, height, frames, quality });
      // With `profile` in the query, the volumes' passes of the last frame (ms each).
      const passes = mode === 'raymarch' ? w.stats().passes : undefined;
      log({ blobs, mode, quality, width, height, ms, fps: 1000 / ms, passes });
    };
    for (const quality of qualities) await frame('raymarch', 1920, 1080, quality);
    await frame('raymarch', 640, 360, 'standard');
    await frame('points', 1920, 1080);
  }
}

main().then(() => log({ done: true }), (e) => log({ error: String(e?.stack || e) }));
