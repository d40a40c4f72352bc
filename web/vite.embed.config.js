// Vite: dist/embed.js, the standalone <wind-field> for plain pages. embed.js itself is only the
// loader (a few KiB); the player's code (three.js, the views, the engine client) is a chunk in
// dist/wind-field/, and so are the engine worker and the WASM core, as files: nothing is
// inlined, so the element runs under a strict Content Security Policy (`script-src 'self'
// 'wasm-unsafe-eval'`, no inline styles). The loader imports the chunk, and the chunk starts the
// worker, by URLs relative to their own modules: copy embed.js, wind-field/ and scenes/ together
// to any static host.
import { defineConfig } from 'vite';
import { fileURLToPath } from 'node:url';

const here = (p) => fileURLToPath(new URL(p, import.meta.url));
const names = {
  entryFileNames: 'embed.js',
  chunkFileNames: 'wind-field/[name]-[hash].js',
  assetFileNames: 'wind-field/[name]-[hash][extname]',
};

export default defineConfig({
  root: here('.'),
  publicDir: false,
  base: './',
  build: {
    outDir: here('../dist'),
    emptyOutDir: false,
    target: 'es2022',
    assetsDir: 'wind-field',
    assetsInlineLimit: 0,
    chunkSizeWarningLimit: 1500,
    rollupOptions: {
      input: here('src/embed.js'),
      // embed.js keeps its export and may export more: what the player's chunk shares with the
      // loader (the core's contract) stays in embed.js, which the chunk then imports, rather
      // than in a third chunk the loader would have to fetch before it can run.
      preserveEntrySignatures: 'allow-extension',
      output: names,
    },
  },
  worker: {
    format: 'es',
    rollupOptions: { output: { ...names, entryFileNames: 'wind-field/[name]-[hash].js' } },
  },
});
