// Decodes 8-bit PNGs (the CLI's stills, the browser's captures) to RGB bytes for comparisons.
import { PNG } from 'pngjs';

/** Decodes PNG bytes; returns `{ width, height, rgb }`, three bytes per pixel, rows top-down. */
export function decodePng(bytes) {
  const { width, height, data } = PNG.sync.read(Buffer.from(bytes));
  const rgb = new Uint8Array(width * height * 3);
  for (let i = 0, j = 0; i < rgb.length; i += 3, j += 4) {
    rgb[i] = data[j];
    rgb[i + 1] = data[j + 1];
    rgb[i + 2] = data[j + 2];
  }
  return { width, height, rgb };
}
