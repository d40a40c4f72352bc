// A page's script that uses windfield's types as a consumer would: compiled with `tsc --noEmit`
// by tests/package.test.js. Lines marked @ts-expect-error must fail to compile.
import type { BlobList, Scene, WindFieldElement, WindFieldStats } from 'windfield';

const player = document.querySelector('wind-field');
if (player) {
  const el: WindFieldElement = player;
  el.preset = 'steam-mug';
  el.src = null;
  el.autoplay = true;
  el.controls = false;
  el.loading = 'eager';
  el.poster = 'poster.png';
  el.posterTime = 1.5;
  el.view = 'points';
  el.alt = 'Steam rising from a mug';
  el.stir = true;
  el.load();
  el.addEventListener('ready', (e) => {
    const scene: Scene = e.detail.scene;
    console.log(scene.simulation.dt, scene.field.size[0]);
  });
  el.addEventListener('error', (e) => console.log(e.detail.message.toUpperCase()));
  el.addEventListener('click', (e) => console.log(e.clientX));
  void (async () => {
    await el.ready;
    const loaded: boolean = el.loaded;
    const scene = el.getScene();
    if (scene) await el.setScene({ ...scene, seed: 2 });
    await el.setScene({ version: 1, gas: { dissipation: 0.3 } });
    await el.step(30);
    const stats: WindFieldStats = el.stats();
    const list: BlobList = await el.exportBlobs({ width: 64, height: 48 });
    const png: string = await el.captureGPU({ mode: 'raymarch', width: 320, height: 240, quality: 'high' });
    const still: string = await el.renderReference({ width: 160 });
    console.log(loaded, stats.blobs + stats.time, list.blobs[0]?.sigma, png.length, still.length);
    const exr: Blob = await el.exportStill({ format: 'exr', alpha: true, width: 64, height: 48 });
    const book = await el.exportFlipbook({ frames: [0, 16], fps: 24, grid: [4, 4], tile: [64, 64], loop: true });
    const vdb: Blob = await el.exportVolume({ voxel: 0.01 });
    console.log(exr.size, book.description.columns * book.description.rows, vdb.type, await el.cancelExport());
    const edited: Scene = await el.editScene({ version: 1, wind: [{ type: 'uniform', velocity: [0, 1, 0] }] });
    const time: number | null | undefined = edited.render.time;
    const stepper: 'cpu' | 'gpu' = await el.setStepper('auto');
    const limit: 'worker' | 'view' | 'display' | 'paused' = stats.limitedBy;
    console.log(time, stepper, stats.stepper, stats.frames, limit);
    const grid = await el.exportFlow();
    const flowStepper: 'cpu' | 'gpu' | null = stats.flowStepper;
    if (grid) console.log(grid.cells[0] * grid.cells[1] * grid.cells[2], grid.velocity.length, grid.temperature[0], grid.box[3], grid.time);
    console.log(flowStepper, stats.flowMs.toFixed(2));
  })();

  // @ts-expect-error: not a view
  el.view = 'wireframe';
  // @ts-expect-error: loading is lazy or eager
  el.loading = 'auto';
  // @ts-expect-error: posterTime is a number
  el.posterTime = '3';
  // @ts-expect-error: ready is read-only
  el.ready = Promise.resolve();
  // @ts-expect-error: a scene needs its version
  void el.setScene({ seed: 1 });
  // @ts-expect-error: not a capture mode
  void el.captureGPU({ mode: 'wireframe' });
  // @ts-expect-error: not a stepper
  void el.setStepper('wasm');
  // @ts-expect-error: a still is PNG or EXR
  void el.exportStill({ format: 'tiff' });
  // @ts-expect-error: a volume needs its voxel size
  void el.exportVolume({});
  // @ts-expect-error: the flow's grid may be null (a scene without a flow)
  void el.exportFlow().then((g) => g.velocity);
  // @ts-expect-error: stir is on or off
  el.stir = 'yes';
  // @ts-expect-error: a uniform wind needs its velocity
  void el.editScene({ version: 1, wind: [{ type: 'uniform' }] });
  el.addEventListener('error', (e) => {
    // @ts-expect-error: the detail carries a message, not a code
    console.log(e.detail.code);
  });
}

const created = document.createElement('wind-field');
created.preset = 'cigarette';
document.body.append(created);

const api = window.windfield;
if (api) {
  void api.ready.then(async () => {
    api.pause();
    api.setView('exact');
    await api.step(10);
    const health = await api.health();
    console.log(health.wasmBytes, health.nonFinite);
    const video: Blob = await api.recordWebM({ frames: 4, mode: 'points' });
    console.log(api.getScene().seed, video.size);
  });
}
