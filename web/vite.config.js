// Vite: the site lives in web/, static files in public/, the build in dist/.
import { defineConfig } from 'vite';
import { fileURLToPath } from 'node:url';

const here = (p) => fileURLToPath(new URL(p, import.meta.url));

export default defineConfig({
  root: here('.'),
  publicDir: here('../public'),
  base: './',
  build: {
    outDir: here('../dist'),
    emptyOutDir: true,
    target: 'es2022',
    rollupOptions: {
      input: { main: here('index.html'), field: here('field.html'), embed: here('embed.html'), classroom: here('classroom.html') },
    },
  },
  worker: { format: 'es' },
  server: { port: 5173 },
  preview: { port: 4173 },
});
