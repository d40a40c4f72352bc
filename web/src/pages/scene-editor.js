// The playground's scene editor: lil-gui folders for every list in the scene (wind primitives,
// emitters, lights, objects) with add, remove, edit and on/off, plus the world mapping and the
// medium, and the flow (paper §7: the large scales solved on a coarse grid). Every change goes
// through `apply(draft)`, which validates and loads the edited copy;
// the folders are then rebuilt from the scene that loaded (or the last good one). A slider
// whose range is a rule of the format takes it from the core (the contract).

import { MAX_ALBEDO } from '../generated/contract.js';
import { closedAxes } from '../flow-gpu/boundary.js';

/** New items, one per kind: valid as they stand (docs/FORMATS.md: the scene format, the blob list). */
export const TEMPLATES = {
  wind: {
    uniform: { type: 'uniform', velocity: [0.3, 0, 0] },
    source: { type: 'source', position: [0, 0.5, 0], strength: 0.2, radius: 0.1 },
    vortex: { type: 'vortex', position: [0, 0.6, 0], axis: [0, 1, 0], strength: 0.5, radius: 0.1 },
    repulsor: { type: 'repulsor', radius: 0.25, strength: 0.2, path: [[0, -1, 0.6, 0], [6, 1, 0.6, 0]], color: [0.8, 0.3, 0.2] },
  },
  emitters: Object.fromEntries(['point', 'disk', 'sphere', 'box'].map((shape) => [shape, {
    shape, center: [0, 0, 0], normal: [0, 1, 0], radius: 0.08, size: [0.2, 0.2, 0.2], rate: 60, sigma0: 0.03, mass0: 0.004,
  }])),
  lights: {
    point: { type: 'point', position: [2, 3, 2], color: [1, 1, 1] },
    directional: { type: 'directional', direction: [-0.3, -1, -0.3], color: [1, 1, 1] },
  },
  // New objects are solid: the wind and the gas go round them (a switch makes them not).
  objects: {
    sphere: { type: 'sphere', center: [0.6, 0.3, 0], radius: 0.2, color: [0.7, 0.7, 0.7], solid: true },
    plane: { type: 'plane', point: [0, 0, 0], normal: [0, 1, 0], color: [0.45, 0.45, 0.42], solid: true },
    cylinder: { type: 'cylinder', base: [0, 0, 0], axis: [0, 1, 0], radius: 0.1, height: 0.2, color: [0.8, 0.8, 0.8], solid: true },
  },
};

/** Cells offered along the flow box's longest side (the others follow, so that the cells stay cubes). */
export const FLOW_CELLS = [8, 12, 16, 20, 24, 32, 40, 48, 64];
/** The cells a new flow has along its box's longest side: a few ms a step in the worker. */
const FLOW_LONGEST = 24;
/** Fewest and most cells of a flow along each axis (docs/FORMATS.md, the flow). */
const FLOW_AXIS = [8, 256];
/** A new flow's room round the emitters (m): beside and below them, and above them (smoke rises). */
const FLOW_MARGIN = { side: 0.4, below: 0.2, above: 1.2 };

/**
 * The box `bounds` ([x0, y0, z0, x1, y1, z1], m) fitted to cubes with `longest` cells along its
 * longest side: edge h = longest side / `longest`, each axis round(side/h) cells (8 at least),
 * each side made exactly that many h about its centre. Returns `{box, cells}`.
 */
export function fitFlowBox(bounds, longest) {
  const sides = [0, 1, 2].map((a) => bounds[a + 3] - bounds[a]);
  const h = Math.max(...sides) / longest;
  const cells = sides.map((s) => Math.min(FLOW_AXIS[1], Math.max(FLOW_AXIS[0], Math.round(s / h))));
  const round = (v) => Math.round(v * 1e6) / 1e6;
  const box = [0, 1, 2].map((a) => (bounds[a] + bounds[a + 3]) / 2);
  const half = cells.map((n) => (n * h) / 2);
  return { box: [...box.map((c, a) => round(c - half[a])), ...box.map((c, a) => round(c + half[a]))], cells };
}

/** The cells along the longest side of a flow's box. */
export const flowLongest = (flow) => {
  const sides = [0, 1, 2].map((a) => flow.box[a + 3] - flow.box[a]);
  return flow.cells[sides.indexOf(Math.max(...sides))];
};

/**
 * A flow round the scene's emitters (room beside, below and above them, the floor kept as
 * its lower bound when the emitters sit above y = 0), with air's constants and open faces.
 */
export function defaultFlow(scene) {
  const lo = [Infinity, Infinity, Infinity];
  const hi = [-Infinity, -Infinity, -Infinity];
  for (const e of scene.emitters.length ? scene.emitters : [{ center: [0, 0, 0], radius: 0.1 }]) {
    const half = e.shape === 'box' ? e.size.map((s) => s / 2) : [e.radius ?? 0, e.radius ?? 0, e.radius ?? 0];
    const at = e.path?.length ? e.path.map(([, ...p]) => p) : [e.center];
    for (const c of at) {
      for (let a = 0; a < 3; a += 1) {
        lo[a] = Math.min(lo[a], c[a] - half[a]);
        hi[a] = Math.max(hi[a], c[a] + half[a]);
      }
    }
  }
  const bounds = [
    lo[0] - FLOW_MARGIN.side, lo[1] >= 0 ? Math.max(0, lo[1] - FLOW_MARGIN.below) : lo[1] - FLOW_MARGIN.below, lo[2] - FLOW_MARGIN.side,
    hi[0] + FLOW_MARGIN.side, hi[1] + FLOW_MARGIN.above, hi[2] + FLOW_MARGIN.side,
  ];
  return { ...fitFlowBox(bounds, FLOW_LONGEST), viscosity: 1.5e-5, buoyancy: 1 / 293.15, gravity: [0, -9.81, 0], cooling: 0.5, faces: 'open', enabled: true };
}

/** Where each list lives in a scene. */
export const LISTS = {
  wind: { title: 'Wind primitives', get: (s) => s.wind, kind: (item) => item.type, optional: ['decay', 'color'] },
  emitters: { title: 'Emitters', get: (s) => s.emitters, kind: (item) => item.shape, optional: ['albedo', 'emission'] },
  lights: { title: 'Lights', get: (s) => s.render.lights, kind: (item) => item.type, optional: [] },
  objects: { title: 'Objects', get: (s) => s.render.objects, kind: (item) => item.type, optional: ['model'] },
};

/** Values an optional (null) field takes when switched on. */
const SWITCH_ON = { decay: 1, albedo: [0.9, 0.9, 0.9], emission: [1, 0.8, 0.5], color: [0.8, 0.8, 0.8], model: 'mug' };
/** Fields edited elsewhere or not by hand (paths, the kind itself). */
const SKIP = new Set(['type', 'path', 'enabled']);
/** Fields shown under another name (with their units). */
const NAMES = { temperature: 'temperature (K over the air)' };
const COLOUR = new Set(['color', 'albedo', 'emission']);
const CHOICES = { shape: ['point', 'disk', 'sphere', 'box'], model: ['mug', 'teapot'] };
/**
 * Lattice extents offered (any even number from MIN_EXTENT to MAX_EXTENT is valid; powers of
 * two are the fastest).
 */
const LATTICE = [8, 12, 16, 24, 32, 48, 64];
/**
 * The offered extents that hold wave numbers up to `kInertial` (a spatial extent n has modes up
 * to n/2 − 1, so the core refuses a smaller one), plus the scene's own `n`, in order.
 */
export const latticeChoices = (n, kInertial = 0) => [...new Set([...LATTICE.filter((m) => m / 2 - 1 >= kInertial), n])].sort((a, b) => a - b);

/**
 * Items of one list shown with their own folder; a longer list (a link may hold hundreds)
 * shows the first ones and says how many more there are, to edit in the scene's JSON.
 */
const MAX_ITEM_FOLDERS = 24;

const isTriple = (v) => Array.isArray(v) && v.length === 3 && v.every((x) => typeof x === 'number');

/**
 * Adds controllers for `item`'s fields to `folder`: numbers, switches, triples (three numbers),
 * choices, and an on/off switch for each `optional` field (null when off). `changed` runs
 * after each edit.
 */
function addFields(folder, item, changed, optional = []) {
  for (const [key, value] of Object.entries(item)) {
    if (SKIP.has(key)) continue;
    if (typeof value === 'number') {
      folder.add(item, key).name(NAMES[key] ?? key).onFinishChange(changed);
    } else if (typeof value === 'boolean') {
      folder.add(item, key).onChange(changed);
    } else if (typeof value === 'string' && CHOICES[key]) {
      folder.add(item, key, CHOICES[key]).onChange(changed);
    } else if (isTriple(value)) {
      const axes = COLOUR.has(key) ? ['r', 'g', 'b'] : ['x', 'y', 'z'];
      value.forEach((_, a) => folder.add(value, a).name(`${key} ${axes[a]}`).onFinishChange(changed));
    }
    if (optional.includes(key)) {
      // Present (null when off) in every validated scene where the kind has it.
      const toggle = { on: value !== null && value !== undefined };
      folder.add(toggle, 'on').name(`${key} on`).onChange((on) => {
        item[key] = on ? structuredClone(SWITCH_ON[key]) : null;
        changed();
      });
    }
  }
}

/** Folder state kept across rebuilds: which titles were open. */
function openTitles(gui) {
  return new Set(gui.foldersRecursive().filter((f) => !f._closed).map((f) => f._title));
}

/**
 * Builds (and on `refresh`, rebuilds) the scene folders inside `parent`.
 * `scene()` returns the current scene; `apply(draft)` loads an edited copy (a Promise).
 */
export function sceneEditor(parent, { scene, apply }) {
  let root = null;
  const build = () => {
    const open = root ? openTitles(root) : new Set();
    root?.destroy();
    root = parent.addFolder('Scene');
    const draft = structuredClone(scene());
    const changed = () => apply(draft);
    world(root, draft, changed);
    for (const [key, list] of Object.entries(LISTS)) listFolder(root, key, list, draft, changed);
    medium(root, draft, changed);
    flowFolder(root, draft, changed);
    for (const f of root.foldersRecursive()) if (!open.has(f._title)) f.close();
    if (open.has('Scene') || !open.size) root.open();
  };
  build();
  return { refresh: build, get gui() { return root; } };
}

function world(root, draft, changed) {
  const f = root.addFolder('World mapping (§3)');
  const field = draft.field;
  const lattice = { space: field.size[0], time: field.size[3] };
  f.add(lattice, 'space', latticeChoices(lattice.space, field.spectrum.k_inertial)).name('lattice N (x, y, z)').onChange((n) => { field.size = [n, n, n, field.size[3]]; changed(); });
  f.add(lattice, 'time', latticeChoices(lattice.time)).name('lattice N (t)').onChange((n) => { field.size[3] = n; changed(); });
  field.period.forEach((_, a) => f.add(field.period, a).name(`period ${'xyz'[a]} (m)`).onFinishChange(changed));
  f.add(field, 'time_period').name('time period (s)').onFinishChange(changed);
  f.add(field, 'carried').name('carried by the large scales (§7)').onChange(changed);
  f.add(field, 'boundary_width').name('layer over solids (m)').onFinishChange(changed);
}

function listFolder(root, key, list, draft, changed) {
  const items = list.get(draft);
  const f = root.addFolder(list.title);
  const kinds = Object.keys(TEMPLATES[key]);
  const adder = {
    kind: kinds[0],
    add: () => {
      items.push(structuredClone(TEMPLATES[key][adder.kind]));
      changed();
    },
  };
  f.add(adder, 'kind', kinds).name('new');
  f.add(adder, 'add').name(`add ${key === 'wind' ? 'primitive' : key.replace(/s$/, '')}`);
  items.slice(0, MAX_ITEM_FOLDERS).forEach((item, i) => {
    const sub = f.addFolder(`${key} ${i + 1}: ${list.kind(item)}`);
    if ('enabled' in item) sub.add(item, 'enabled').name('on').onChange(changed);
    // An object's `solid` is left out of a scene when false: offer the switch on every object.
    if (key === 'objects') item.solid ??= false;
    // An emitter's `temperature` (the heat that lifts its gas in a flow) is left out when 0.
    if (key === 'emitters') item.temperature ??= 0;
    addFields(sub, item, changed, list.optional);
    sub.add({ remove: () => { items.splice(i, 1); changed(); } }, 'remove');
  });
  if (items.length > MAX_ITEM_FOLDERS) {
    const more = { note: 'not shown' };
    f.add(more, 'note').name(`${items.length - MAX_ITEM_FOLDERS} more: edit them in the scene JSON`).disable();
  }
}

function medium(root, draft, changed) {
  const render = draft.render;
  const m = render.medium;
  const f = root.addFolder('Medium (§5)');
  if (!Array.isArray(m.extinction)) m.extinction = [m.extinction, m.extinction, m.extinction];
  m.extinction.forEach((_, a) => f.add(m.extinction, a).name(`extinction ${'rgb'[a]}`).onFinishChange(changed));
  m.albedo.forEach((_, a) => f.add(m.albedo, a, 0, MAX_ALBEDO, 0.01).name(`albedo ${'rgb'[a]}`).onFinishChange(changed));
  const phase = { type: m.phase.type, g: m.phase.g ?? 0.3 };
  const setPhase = () => {
    m.phase = phase.type === 'isotropic' ? { type: 'isotropic' } : { type: 'henyey-greenstein', g: phase.g };
    changed();
  };
  f.add(phase, 'type', ['isotropic', 'henyey-greenstein']).name('phase').onChange(setPhase);
  if (phase.type !== 'isotropic') f.add(phase, 'g', -0.99, 0.99, 0.01).name('phase g').onFinishChange(setPhase);
  // A transparent background (stills and exports with alpha) has no colour to edit.
  if (Array.isArray(render.background)) {
    render.background.forEach((_, a) => f.add(render.background, a, 0, 1, 0.01).name(`background ${'rgb'[a]}`).onFinishChange(changed));
  }
}

/**
 * A scene's `flow.faces` from what the faces across each axis do (`across`: {x, y, z}, each
 * 'open' or 'closed'): one word where all three agree, the object otherwise.
 */
export function flowFaces(across) {
  const words = new Set(['x', 'y', 'z'].map((a) => across[a]));
  return words.size === 1 ? [...words][0] : { x: across.x, y: across.y, z: across.z };
}

/**
 * The flow (paper §7): on/off (on adds a flow round the emitters, off keeps it switched off),
 * the cells along the box's longest side (the others in proportion, the box refitted so the
 * cells stay cubes), the box's corners, ν, β, the cooling and the faces across each axis.
 */
function flowFolder(root, draft, changed) {
  const f = root.addFolder('Flow (§7)');
  const flow = draft.flow;
  const state = { on: Boolean(flow?.enabled) };
  f.add(state, 'on').name('flow (physical large scales)').onChange((on) => {
    if (on && !draft.flow) draft.flow = defaultFlow(draft);
    else if (draft.flow) draft.flow.enabled = on;
    changed();
  });
  if (!flow) return;
  const grid = { longest: flowLongest(flow) };
  const refit = () => Object.assign(flow, fitFlowBox(flow.box, grid.longest));
  f.add(grid, 'longest', [...new Set([...FLOW_CELLS, grid.longest])].sort((a, b) => a - b))
    .name('cells (longest side)').onChange(() => { refit(); changed(); });
  f.add({ cells: flow.cells.join(' × ') }, 'cells').name('cells (x × y × z)').disable();
  flow.box.forEach((_, i) => f.add(flow.box, i).name(`box ${i < 3 ? 'from' : 'to'} ${'xyz'[i % 3]} (m)`)
    .onFinishChange(() => { refit(); changed(); }));
  f.add(flow, 'viscosity').name('viscosity ν (m²/s)').onFinishChange(changed);
  f.add(flow, 'buoyancy').name('buoyancy β (1/K)').onFinishChange(changed);
  f.add(flow, 'cooling').name('cooling (1/s)').onFinishChange(changed);
  const across = Object.fromEntries(['x', 'y', 'z'].map((a, i) => [a, closedAxes(flow.faces)[i] ? 'closed' : 'open']));
  const setFaces = () => {
    flow.faces = flowFaces(across);
    changed();
  };
  for (const a of ['x', 'y', 'z']) f.add(across, a, ['open', 'closed']).name(`faces across ${a}`).onChange(setFaces);
}
