#!/usr/bin/env node
// Regenerates the gallery in docs/images/gallery/: for each preset of the catalog
// (public/presets.json) at its still's time, the CPU reference still (`windfield render`)
// and the browser's real-time view and points view (the built site in chromium; SwiftShader
// draws them on the CPU, as a GPU would), and the scene picker's thumbnail. The few-wide-blob stills come from the scenes'
// earlier versions and are not regenerated. Needs `npm run build` and `cargo build --release`
// first; `--views-only` redraws the browser's views and keeps the stills; `--only a,b` redraws
// the rows of those presets alone.
import { execFileSync } from 'node:child_process';
import { readFileSync, writeFileSync } from 'node:fs';
import { root, withSite } from './site.mjs';

/** The presets of the playground's catalog, each at its still's time (`render.time`); `--only A,B` some of them. */
const catalog = JSON.parse(readFileSync(`${root}public/presets.json`, 'utf8')).presets;
const only = process.argv.includes('--only') ? process.argv[process.argv.indexOf('--only') + 1].split(',') : null;
const PRESETS = catalog
  .filter(({ name }) => !only || only.includes(name))
  .map(({ name }) => [name, JSON.parse(readFileSync(`${root}public/scenes/${name}.json`, 'utf8')).render.time]);
const SIZE = { width: 480, height: 360 };
/** The scene picker's thumbnails (public/scenes/thumbs/NAME.png). */
const THUMB = { width: 192, height: 144 };
const dir = `${root}docs/images/gallery`;
const cli = `${root}wasm-core/target/release/windfield`;

// `--views-only`: the browser's views alone, the stills kept.
for (const [name] of process.argv.includes('--views-only') ? [] : PRESETS) {
  execFileSync(cli, ['render', `${root}public/scenes/${name}.json`,
    '--width', String(SIZE.width), '--height', String(SIZE.height), '--out', `${dir}/${name}-still.png`], { stdio: 'inherit' });
}

await withSite('?view=points', async (page, open) => {
  for (const [name, seconds] of PRESETS) {
    await open(`?preset=${name}&view=points`);
    const shots = await page.evaluate(async ({ t, size, THUMB }) => {
      const w = window.windfield;
      await w.ready;
      await w.pause();
      const scene = w.getScene();
      await w.setScene(scene);
      await w.step(Math.round(t / scene.simulation.dt));
      return {
        view: await w.captureGPU({ mode: 'raymarch', quality: 'high', ...size }),
        points: await w.captureGPU({ mode: 'points', ...size }),
        thumb: await w.captureGPU({ mode: 'raymarch', quality: 'high', ...THUMB }),
      };
    }, { t: seconds, size: SIZE, THUMB });
    const png = (url) => Buffer.from(url.split(',')[1], 'base64');
    writeFileSync(`${dir}/${name}-view.png`, png(shots.view));
    writeFileSync(`${dir}/${name}-points.png`, png(shots.points));
    writeFileSync(`${root}public/scenes/thumbs/${name}.png`, png(shots.thumb));
    console.log(`${name}: reference, real-time view and points at t = ${seconds} s`);
  }
});
