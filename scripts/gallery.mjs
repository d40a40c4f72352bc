#!/usr/bin/env node
// Regenerates the gallery of current stills in docs/images/gallery/: for each preset at the
// gallery's time, the CPU reference still (`windfield render`) and the browser's real-time view
// and points view (the built site in chromium; SwiftShader draws them on the CPU, as a GPU
// would). The "before" stills are the presets as they were before the many-blob remake and are
// not regenerated. Needs `npm run build` and `cargo build --release` first.
import { execFileSync } from 'node:child_process';
import { writeFileSync } from 'node:fs';
import { root, withSite } from './site.mjs';

/** Presets and the time (s) of their gallery stills. */
const PRESETS = [['steam-mug', 4], ['psychedelic-steam', 4], ['cigarette', 4], ['sphere-smoke', 4], ['morph', 1.5]];
const SIZE = { width: 480, height: 360 };
const dir = `${root}docs/images/gallery`;
const cli = `${root}wasm-core/target/release/windfield`;

for (const [name, seconds] of PRESETS) {
  execFileSync(cli, ['render', `${root}public/scenes/${name}.json`, '--seconds', String(seconds),
    '--width', String(SIZE.width), '--height', String(SIZE.height), '--out', `${dir}/${name}-after.png`], { stdio: 'inherit' });
}

await withSite('?view=points', async (page, open) => {
  for (const [name, seconds] of PRESETS) {
    await open(`?preset=${name}&view=points`);
    const shots = await page.evaluate(async ({ t, size }) => {
      const w = window.windfield;
      await w.ready;
      w.pause();
      const scene = w.getScene();
      await w.setScene(scene);
      await w.step(Math.round(t / scene.simulation.dt));
      return {
        view: await w.captureGPU({ mode: 'raymarch', quality: 'high', ...size }),
        points: await w.captureGPU({ mode: 'points', ...size }),
      };
    }, { t: seconds, size: SIZE });
    for (const [kind, url] of Object.entries(shots)) {
      writeFileSync(`${dir}/${name}-${kind}.png`, Buffer.from(url.split(',')[1], 'base64'));
    }
    console.log(`${name}: reference, real-time view and points at t = ${seconds} s`);
  }
});
