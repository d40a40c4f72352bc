// Browser benchmarks over the built site (dist/) in Debian's chromium with SwiftShader:
// navigation to first frame, worker step time at 50k blobs, GPU ray-march frame time at 1k and
// 16k blobs (320×240), and the gzipped JS and WASM sizes. Prints {name, value, unit} objects.
import { chromium } from '@playwright/test';
import { spawn } from 'node:child_process';
import { readdirSync, readFileSync, statSync } from 'node:fs';
import { gzipSync } from 'node:zlib';
import { fileURLToPath } from 'node:url';

const root = fileURLToPath(new URL('..', import.meta.url));
const PORT = 4179;

/** Gzipped size (KiB) of the files under `dir` whose names match `pattern`. */
export function gzipKiB(dir, pattern) {
  let total = 0;
  for (const name of readdirSync(dir)) {
    const path = `${dir}/${name}`;
    if (statSync(path).isDirectory()) total += gzipKiB(path, pattern) * 1024;
    else if (pattern.test(name)) total += gzipSync(readFileSync(path), { level: 9 }).length;
  }
  return total / 1024;
}

/** Runs the benchmarks against the built site; returns the results. */
export async function benchBrowser() {
  const results = [];
  const emit = (name, value, unit) => results.push({ name, value: Math.round(value * 1000) / 1000, unit });

  const server = spawn('npx', ['vite', 'preview', '--config', 'web/vite.config.js', '--host', '127.0.0.1', '--port', String(PORT), '--strictPort'], {
    cwd: root, stdio: 'ignore', detached: true,
  });
  const browser = await chromium.launch({
    executablePath: process.env.CHROMIUM_PATH || '/usr/bin/chromium',
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
  try {
    const page = await browser.newPage({ viewport: { width: 1100, height: 720 } });
    for (let i = 0; i < 50; i++) {
      try {
        await page.goto(`http://127.0.0.1:${PORT}/`);
        break;
      } catch {
        await new Promise((r) => setTimeout(r, 200));
      }
    }
    await page.waitForFunction(() => window.windfield !== undefined);
    const firstFrame = await page.evaluate(async () => {
      await window.windfield.ready;
      return performance.now();
    });
    emit('first_frame_ms', firstFrame, 'ms');

    const sceneWith = (count) => page.evaluate(async (n) => {
      const w = window.windfield;
      w.pause();
      const s = w.getScene();
      s.emitters[0].rate = n * 2;
      s.gas.max_blobs = n;
      s.gas.dissipation = 0;
      s.gas.min_mass = 0;
      await w.setScene(s);
      await w.step(Math.ceil(0.55 / s.simulation.dt));
      return w.stats().blobs;
    }, count);

    const n50 = await sceneWith(50_000);
    const stepMs = await page.evaluate(async () => {
      const t = [];
      for (let i = 0; i < 7; i++) {
        await window.windfield.step(1);
        t.push(window.windfield.stats().stepMs);
      }
      return t.sort((a, b) => a - b)[3];
    });
    emit(`worker_step_${Math.round(n50 / 1000)}k_ms`, stepMs, 'ms');

    const frameMs = {};
    for (const n of [1000, 16000]) {
      await sceneWith(n);
      frameMs[n] = await page.evaluate(async () => {
        const t = [];
        for (let i = 0; i < 5; i++) {
          const s = performance.now();
          await window.windfield.captureGPU({ mode: 'raymarch', width: 320, height: 240 });
          t.push(performance.now() - s);
        }
        return t.sort((a, b) => a - b)[2];
      });
      emit(`raymarch_320x240_${n / 1000}k_ms`, frameMs[n], 'ms');
    }
    emit('raymarch_16k_over_1k', frameMs[16000] / frameMs[1000], 'ratio');
  } finally {
    await browser.close();
    try {
      process.kill(-server.pid);
    } catch {
      // already gone
    }
  }
  return results;
}
