// Playwright: Debian's chromium (never a downloaded browser) with WebGL2 through SwiftShader,
// against the built site (dist/) served by `vite preview`, one page at a time. No test times the
// page: a test that needs the page's time runs it on Playwright's clock (`holdClock` and
// `nextFrame` in helpers.js), and `npm run bench` measures the frame rates and delays
// (scripts/bench-browser.mjs; their targets in docs/BENCHMARKS.md). The timeouts here guard
// against hangs only.
import { defineConfig } from '@playwright/test';

const chromium = process.env.CHROMIUM_PATH || '/usr/bin/chromium';
/** The preview server's port (WINDFIELD_E2E_PORT, 4173 unless set). */
const port = Number(process.env.WINDFIELD_E2E_PORT || 4173);

export default defineConfig({
  testDir: '.',
  outputDir: './.output',
  timeout: 90_000,
  expect: { timeout: 30_000 },
  fullyParallel: false,
  workers: 1,
  retries: 0,
  reporter: [['list']],
  use: {
    baseURL: `http://127.0.0.1:${port}/`,
    // Small enough that software drawing stays quick, wide enough for the desktop layout.
    viewport: { width: 900, height: 580 },
    launchOptions: {
      executablePath: chromium,
      args: [
        '--no-sandbox',
        '--use-angle=swiftshader',
        '--enable-unsafe-swiftshader',
        '--disable-background-networking',
        '--disable-component-update',
        '--disable-sync',
      ],
    },
  },
  webServer: {
    command: `npx vite preview --config web/vite.config.js --host 127.0.0.1 --port ${port} --strictPort`,
    cwd: '..',
    url: `http://127.0.0.1:${port}/`,
    reuseExistingServer: !process.env.CI,
    timeout: 60_000,
  },
});
