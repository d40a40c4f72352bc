// Vite, library mode: dist/embed.js, one ES module defining <wind-field> (worker and WASM
// inlined, so it needs no other file and no special headers).
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
    lib: { entry: here('src/embed.js'), formats: ['es'], fileName: () => 'embed.js' },
  },
  worker: { format: 'es' },
});
