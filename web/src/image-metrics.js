// Image comparison shared by the page's self-checks and the tests.

/** Peak signal-to-noise ratio (dB) of two 8-bit arrays of equal length; Infinity when equal. */
export function psnr(a, b) {
  if (a.length !== b.length) throw new Error(`images differ in size (${a.length} vs ${b.length})`);
  let sum = 0;
  for (let i = 0; i < a.length; i++) sum += (a[i] - b[i]) ** 2;
  if (sum === 0) return Infinity;
  return 10 * Math.log10((255 * 255) / (sum / a.length));
}
