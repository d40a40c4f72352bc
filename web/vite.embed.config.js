// Vite, library mode: dist/embed.js, the standalone <wind-field> for plain pages. embed.js
// itself is only the loader (a few KiB); the player's code (three.js, the views, the engine
// client) is a chunk in dist/wind-field/, and so is the engine worker with the WASM core
// inlined. The loader imports the chunk, and the chunk starts the worker, by URLs relative to
// their own modules: copy embed.js, wind-field/ and scenes/ together to any static host.
import { defineConfig } from 'vite';
import { fileURLToPath } from 'node:url';

const here = (p) => fileURLToPath(new URL(p, import.meta.url));

export default defineConfig({
  root: here('.'),
  publicDir: false,
  base: './',
  build: {
    outDir: here('../dist'),
    emptyOutDir: false,
    target: 'es2022',
    assetsDir: 'wind-field',
    lib: { entry: here('src/embed.js'), formats: ['es'], fileName: () => 'embed.js' },
    rollupOptions: { output: { chunkFileNames: 'wind-field/[name]-[hash].js' } },
  },
  worker: { format: 'es' },
});
