// The built site (dist/) served by `vite preview` and opened in Debian's chromium with
// SwiftShader, for the scripts that drive the browser (benchmarks, the gallery).
import { chromium } from '@playwright/test';
import { spawn } from 'node:child_process';
import { fileURLToPath } from 'node:url';

export const root = fileURLToPath(new URL('..', import.meta.url));
/** The preview server's port: WINDFIELD_SITE_PORT, 4179 unless set. */
const PORT = Number(process.env.WINDFIELD_SITE_PORT || 4179);

/**
 * Serves dist/, opens a page on it (`path`, e.g. `?view=points`) once the server answers, runs
 * `fn(page, open)` (`open(path)` navigates again and waits for `window.windfield`), and closes
 * everything. The page shows the full version (as on a machine with a GPU) unless `lighter`:
 * SwiftShader would otherwise get the lighter version (`web/src/player/machine.js`).
 */
export async function withSite(path, fn, { lighter = false } = {}) {
  const server = spawn('npx', ['vite', 'preview', '--config', 'web/vite.config.js', '--host', '127.0.0.1', '--port', String(PORT), '--strictPort'], {
    cwd: root, stdio: 'ignore', detached: true,
  });
  const browser = await chromium.launch({
    executablePath: process.env.CHROMIUM_PATH || '/usr/bin/chromium',
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
  try {
    const page = await browser.newPage({ viewport: { width: 1100, height: 720 } });
    if (!lighter) await page.addInitScript(() => sessionStorage.setItem('windfield.choices', JSON.stringify({ full: true })));
    const open = async (to) => {
      for (let i = 0; i < 50; i++) {
        try {
          await page.goto(`http://127.0.0.1:${PORT}/${to}`);
          break;
        } catch {
          await new Promise((r) => setTimeout(r, 200));
        }
      }
      await page.waitForFunction(() => window.windfield !== undefined);
    };
    await open(path);
    return await fn(page, open);
  } finally {
    await browser.close();
    try {
      process.kill(-server.pid);
    } catch {
      // already gone
    }
  }
}
