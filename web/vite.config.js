// Vite: the site lives in web/, static files in public/, the build in dist/.
import { defineConfig } from 'vite';
import { mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { dirname } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = (p) => fileURLToPath(new URL(p, import.meta.url));
/** lil-gui's stylesheet as the pages link it (see `panelStylesheet`). */
const PANEL_CSS = here('../node_modules/.cache/windfield/lil-gui.css');

/**
 * lil-gui's stylesheet without its icon font: the font is a data: URL, which a strict Content
 * Security Policy refuses (and Chromium checks it even unused); style.css draws the panel's
 * three glyphs in the page's font instead. Written before each build or dev server start.
 */
function panelStylesheet() {
  return {
    name: 'windfield-panel-stylesheet',
    buildStart() {
      const css = readFileSync(here('../node_modules/lil-gui/dist/lil-gui.css'), 'utf8');
      mkdirSync(dirname(PANEL_CSS), { recursive: true });
      writeFileSync(PANEL_CSS, css.replace(/@font-face\s*\{[^}]*\}/g, ''));
    },
  };
}

export default defineConfig({
  root: here('.'),
  // lil-gui's stylesheet, linked from style.css instead of injected at run time (the pages run
  // under a strict CSP).
  plugins: [panelStylesheet()],
  resolve: { alias: { 'lil-gui-css': PANEL_CSS } },
  publicDir: here('../public'),
  base: './',
  build: {
    outDir: here('../dist'),
    emptyOutDir: true,
    target: 'es2022',
    // three.js alone is over Vite's default warning size; the player's chunk is loaded on demand.
    chunkSizeWarningLimit: 1500,
    rollupOptions: {
      input: { main: here('index.html'), field: here('field.html'), embed: here('embed.html'), classroom: here('classroom.html') },
    },
  },
  worker: { format: 'es' },
  server: { port: 5173 },
  preview: { port: 4173 },
});
