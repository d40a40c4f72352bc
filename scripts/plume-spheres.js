// `count` solid spheres of radius 1.2 cm spread through the dense plume's region by a
// low-discrepancy sequence (as examples/bench.rs): the scenes of the solids benchmarks
// (scripts/bench.mjs, scripts/bench-browser.mjs, scripts/gpu-bench/page.js). A plain module, so
// the GPU machine's page loads it as it is.
export const plumeSpheres = (count) => Array.from({ length: count }, (_, i) => {
  const f = (k) => ((i + 0.5) * k) % 1;
  return {
    type: 'sphere', center: [0.6 * f(0.618034) - 0.3, 1.05 * f(0.4142136) + 0.15, 0.6 * f(0.7320508) - 0.3],
    radius: 0.012, color: [0.5, 0.5, 0.5], solid: true,
  };
});
