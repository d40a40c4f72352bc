// The GPU stepper's twin checks against the core: their scenes and measures, shared by
// e2e/gpu-stepper.spec.js (in software) and scripts/gpu-bench/page.js (on a real GPU).

/** A scene about 2 m across with every primitive kind and every emitter shape. */
export const everyKind = {
  version: 1,
  seed: 5,
  field: { size: [8, 8, 8, 8], spectrum: { k_inertial: 2 }, period: [1.5, 2, 2.5], time_period: 3, amplitude: 1.2, carried_by_wind: true },
  wind: [
    { type: 'uniform', velocity: [0.1, 0.3, 0] },
    { type: 'uniform', velocity: [0, 0, 0.2], position: [0.2, 0.5, 0], decay: 0.5 },
    { type: 'source', position: [0.3, 0.2, 0.1], strength: 0.4, radius: 0.15 },
    { type: 'source', position: [-0.3, 0.8, 0], strength: -0.2, decay: 0.7 },
    { type: 'vortex', position: [0, 0.6, 0], axis: [0.2, 1, 0.1], strength: 0.6, radius: 0.1 },
    { type: 'repulsor', radius: 0.2, strength: 0.3, path: [[0, -1, 0.5, 0], [2, 0.5, 0.6, 0.2], [4, 1, 0.4, 0]], color: [0.8, 0.2, 0.1] },
  ],
  emitters: [
    { shape: 'point', center: [0, 0, 0], rate: 200, velocity: [0, 0.4, 0], velocity_time: 0.3 },
    { shape: 'disk', center: [0.2, 0, 0], radius: 0.1, rate: 300, mass0: 0.5 },
    { shape: 'sphere', center: [-0.2, 0.1, 0], radius: 0.1, rate: 250, albedo: [0.9, 0.5, 0.2] },
    { shape: 'box', center: [0, 0.2, 0.3], size: [0.2, 0.1, 0.2], rate: 150, emission: [1, 0.5, 0.2] },
  ],
  gas: { diffusion: 0.002, dissipation: 0.4, min_mass: 0.3, max_blobs: 600 },
};

/** The scene of every kind with solid objects (a plane, a sphere, a cylinder) and carried eddies. */
export const withSolids = {
  ...everyKind,
  field: { ...everyKind.field, carried: true, carry_time: 0.3, boundary_width: 0.15 },
  wind: everyKind.wind.map((w) => (w.type === 'vortex' ? { ...w, axis: [1, 0, 0.2] } : w)),
  // Gas born in the sphere's layer, carried up into it.
  emitters: [...everyKind.emitters, { shape: 'point', center: [0.5, 0.58, 0.2], rate: 300 }],
  render: {
    objects: [
      { type: 'plane', point: [0, -0.3, 0], normal: [0, 1, 0.1], color: [1, 1, 1], solid: true },
      { type: 'sphere', center: [0.5, 0.9, 0.2], radius: 0.25, color: [1, 1, 1], solid: true },
      { type: 'cylinder', base: [-0.6, 0.3, -0.2], axis: [0.2, 1, 0], radius: 0.2, height: 0.5, color: [1, 1, 1], solid: true },
    ],
  },
};

/**
 * `withSolids` among 150 more small solid spheres through its gas (a low-discrepancy spread, none
 * holding an emitter's centre), so a blob's cell of the core's grid lists a few of the many.
 */
export const amongManySpheres = (() => {
  const centres = withSolids.emitters.map((e) => e.center);
  const spheres = [];
  for (let i = 0; i < 150; i++) {
    const f = (k) => ((i + 0.5) * k) % 1;
    const center = [0.8 * f(0.7548777) - 0.4, 0.6 * f(0.5698403) - 0.1, 0.7 * f(0.4301597) - 0.3];
    const radius = 0.015 + 0.01 * f(0.618034);
    if (centres.every((c) => Math.hypot(...c.map((v, a) => v - center[a])) > radius + 0.02)) {
      spheres.push({ type: 'sphere', center, radius, color: [1, 1, 1], solid: true });
    }
  }
  return {
    ...withSolids,
    field: { ...withSolids.field, boundary_width: 0.02 },
    render: { objects: [...withSolids.render.objects, ...spheres] },
  };
})();

/** Each blob's distance (m) from the same blob of `other` (exportBlobs lists), Infinity where `other` has none. */
export function distances(list, other) {
  return list.map((b, i) => (other[i] ? Math.hypot(...b.center.map((v, a) => v - other[i].center[a])) : Infinity));
}

/** The blobs' total mass. */
export function totalMass(list) {
  return list.reduce((m, b) => m + b.mass, 0);
}

/** The centres' mean and spread (standard deviation) along x, y and z (m). */
export function centreStatistics(list) {
  return [0, 1, 2].map((a) => {
    const mean = list.reduce((s, b) => s + b.center[a], 0) / list.length;
    const spread = Math.sqrt(list.reduce((s, b) => s + (b.center[a] - mean) ** 2, 0) / list.length);
    return { mean, spread };
  });
}
