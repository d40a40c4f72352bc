// The lighter version of a scene for a slow machine: at most `cap` live blobs, the same gas.
// A scene whose `gas.max_blobs` is over the cap runs with every count scaled by f = cap /
// max_blobs (emitters' rates, shapes' counts, the cap itself) and every blob standing for 1/f of
// the original ones: mass m0/f (so the gas's mass, its density and its optical depth stay those of
// the full scene) and width σ0·f^(−1/3) (so the blobs fill the same volume: N σ³ is kept), with
// `min_mass` and `split_sigma` scaled alike so blobs dissipate and split when the full scene's
// would. A scene's flow may run on a coarser grid: half the cells along each side (`coarserCells`).
// The scene the user sees and shares stays the full one; only the simulation runs on this.

/** Whether `scene` (normalised, parsed) has more live blobs than `cap` allows. */
export function overCap(scene, cap) {
  return Number.isFinite(cap) && cap > 0 && scene.gas.max_blobs > cap;
}

/** `scene` (normalised, parsed; not changed) with at most `cap` live blobs, as described above. */
export function lightenScene(scene, cap) {
  if (!overCap(scene, cap)) return scene;
  const f = cap / scene.gas.max_blobs;
  const widen = f ** (-1 / 3);
  const lighter = structuredClone(scene);
  const gas = lighter.gas;
  gas.max_blobs = Math.max(1, Math.floor(cap));
  gas.min_mass /= f;
  if (gas.split_sigma !== null && gas.split_sigma !== undefined) gas.split_sigma *= widen;
  for (const e of lighter.emitters) {
    e.rate *= f;
    e.mass0 /= f;
    e.sigma0 *= widen;
  }
  for (const s of lighter.shapes ?? []) {
    // Listed points are kept as they are (a set of points is its own count).
    if (s.shape === 'points') continue;
    s.count = Math.max(1, Math.round(s.count * f));
    s.mass0 /= f;
    s.sigma0 *= widen;
  }
  return lighter;
}

/** Fewest cells along a side of the flow's grid on the coarser grid (the scene format's least). */
const LEAST_CELLS = 8;

/**
 * The coarser grid of a scene's enabled `flow` (normalised): each of `cells` halved (rounded,
 * not below `LEAST_CELLS`), kept only where the box's sides per cell still agree with their mean
 * within 1 % (the cube rule, docs/FORMATS.md, the flow). Null where there is no such grid: no
 * flow, a disabled one, cells already at the least, or a halving that breaks the cube rule.
 */
export function coarserCells(flow) {
  if (!flow || flow.enabled === false) return null;
  const cells = flow.cells.map((n) => Math.max(LEAST_CELLS, Math.round(n / 2)));
  if (cells.every((n, i) => n === flow.cells[i])) return null;
  const sides = cells.map((n, i) => (flow.box[i + 3] - flow.box[i]) / n);
  const h = (sides[0] + sides[1] + sides[2]) / 3;
  return sides.every((s) => Math.abs(s - h) <= 0.01 * h) ? cells : null;
}

/** `scene` (normalised, parsed; not changed) with its flow on the coarser grid (`coarserCells`), or itself. */
export function coarsenFlow(scene) {
  const cells = coarserCells(scene.flow);
  if (!cells) return scene;
  return { ...scene, flow: { ...scene.flow, cells } };
}
