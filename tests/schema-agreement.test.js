// The shipped JSON Schema (public/scene.schema.json, draft 2020-12) against the core's parser:
// a schema-driven editor must accept what `windfield` accepts and refuse what it refuses.
// A real validator (Ajv) and the core's `validateScene` judge the same scenes: every shipped
// scene and a scene that uses every variant; every number in them set to values in and out of
// its range; and a seeded stream of random numbers put in random places. Where they differ
// it must be a rule that spans several values, which JSON Schema cannot state (listed below).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readdirSync, readFileSync } from 'node:fs';
import Ajv2020 from 'ajv/dist/2020.js';
import { loadCore, root } from './support/core.js';

const core = await loadCore();
const schema = JSON.parse(readFileSync(`${root}public/scene.schema.json`, 'utf8'));
const ajv = new Ajv2020({ allErrors: false, strict: true });
// schemars names each number's Rust type; the ranges carry the meaning.
for (const format of ['float', 'double', 'uint', 'uint32', 'uint64']) ajv.addFormat(format, true);
const schemaAccepts = ajv.compile(schema);

/** The core's verdict: null if it accepts the scene, else its message. */
function coreRefusal(scene) {
  try {
    core.validateScene(JSON.stringify(scene));
    return null;
  } catch (err) {
    const message = String(err?.message ?? err);
    assert.ok(message.length > 0, 'a refusal names its reason');
    return message;
  }
}

/**
 * Rules over several values, which a JSON Schema cannot express: the core refuses these while
 * the schema's per-value ranges accept them. The schema's descriptions state them.
 */
const CROSS_FIELD = [
  /must be a non-zero direction/, // a vector's length, not a component
  /camera\.target: must differ from camera\.position/,
  /camera\.up: must not be parallel to the view direction/,
  /key times must increase strictly/, // a repulsor's path
  /field\.size: .*points/, // the lattice's product, at most 2^24
  /reversed sets keep every step/, // blobs × (reverse_from / dt + 1), and the steps
  /simulation\.dt: .* steps, over the limit/, // reverse_from / dt and render.time / dt, the step budget
  /emitters: .* births a step, over the limit/, // Σ rate × simulation.dt
  /shapes: all shapes together make .* blobs, over the limit/, // Σ count
  /field\.boundary_width: .*half the field's shortest period/, // against field.period
  /lies inside the solid .* render\.objects\[\d+\]/, // an emitter against the solid objects
  /flow\.box\[\d\]: must be greater than flow\.box/, // the flow's upper corner against its lower
  /flow\.cells: the box's sides per cell/, // the cells are cubes: the box against its cells
  /flow\.cells: .* cells .* over the limit/, // the product of the cells, and cells × steps
  /flow\.viscosity: .* substeps a step/, // ν against simulation.dt and the cells' edge
];

/** A scene with every variant: each primitive, emitter shape, light, object, phase and solid. */
const EVERY_VARIANT = {
  version: 1,
  seed: 7,
  field: { size: [12, 10, 8, 6], spectrum: { law: 'paper-literal', epsilon: 2, k_inertial: 2, sigma: 0.5 }, period: [2, 3, 4], time_period: 5, amplitude: 0.5, carried_by_wind: true, carried: true, carry_time: 0.7, boundary_width: 0.2 },
  wind: [
    { type: 'uniform', velocity: [0.1, 0.2, 0], position: [0, 0, 0], decay: 3, enabled: true },
    { type: 'source', position: [0, 1, 0], strength: -0.5, radius: 0.2, decay: 2 },
    { type: 'vortex', position: [0, 1, 0], axis: [0, 1, 0], strength: 0.3, radius: 0.1 },
    { type: 'repulsor', radius: 0.3, strength: 0.5, path: [[0, -1, 1, 0], [2, 1, 1, 0]], color: [0.8, 0.2, 0.2], decay: 4 },
  ],
  emitters: [
    { shape: 'disk', center: [0, 0, 0], normal: [0, 1, 0], radius: 0.1, rate: 40, sigma0: 0.02, mass0: 0.5, albedo: [0.9, 0.8, 0.7], velocity: [0, 0.3, 0], velocity_time: 0.5 },
    { shape: 'box', center: [1, 0, 0], size: [0.2, 0.1, 0.2], rate: 10, sigma0: 0.03, mass0: 1, emission: [0.5, 0.2, 0] },
    { shape: 'sphere', center: [-1, 0, 0], radius: 0.2, rate: 5, sigma0: 0.04, mass0: 1, enabled: false },
  ],
  shapes: [
    { shape: 'torus', center: [0, 1, 0], axis: [1, 0, 0], radius: 0.4, thickness: 0.1, count: 50, sigma0: 0.03, mass0: 0.01 },
    { shape: 'points', center: [0, 1, 0], points: [[0, 0, 0], [0.1, 0.2, 0.3]], sigma0: 0.05, mass0: 0.02, albedo: [0, 0, 0], emission: [1, 1, 1], reverse_from: 1 },
  ],
  gas: { diffusion: 0.001, dissipation: 0.2, split_sigma: 0.2, max_blobs: 5000, min_mass: 1e-5 },
  simulation: { dt: 0.02, integrator: 'euler' },
  render: {
    camera: { position: [0, 1, 4], target: [0, 1, 0], up: [0, 1, 0], fov_y_deg: 35 },
    image: { width: 64, height: 48, encoding: 'linear' },
    medium: { extinction: [1, 2, 3], albedo: [0.9, 0.9, 0.9], phase: { type: 'henyey-greenstein', g: 0.3 } },
    lights: [{ type: 'point', position: [1, 3, 1], color: [2, 2, 2] }, { type: 'directional', direction: [0, -1, 0], color: [1, 1, 1] }],
    shadows: true,
    background: [0.1, 0.1, 0.1],
    time: 1.5,
    objects: [
      { type: 'sphere', center: [0, 0.5, 0], radius: 0.2, color: [0.5, 0.5, 0.5], solid: true },
      { type: 'plane', point: [0, 0, 0], normal: [0, 1, 0], color: [0.3, 0.3, 0.3], solid: true },
      { type: 'cylinder', base: [0, 0, 0], axis: [0, 1, 0], radius: 0.1, height: 0.3, color: [1, 1, 1] },
    ],
  },
};

const SCENES = {
  ...Object.fromEntries(readdirSync(`${root}public/scenes`).filter((f) => f.endsWith('.json'))
    .map((f) => [f, JSON.parse(readFileSync(`${root}public/scenes/${f}`, 'utf8'))])
    .filter(([, json]) => 'version' in json)), // scenes, not the presets' index
  'tests/fixtures/plume.json': JSON.parse(readFileSync(`${root}tests/fixtures/plume.json`, 'utf8')),
  'every variant': EVERY_VARIANT,
  'minimal': { version: 1 },
};

/**
 * Paths to every number in `value` (arrays longer than eight: their first and last entries,
 * which the parser checks as it does the rest).
 */
function numberPaths(value, path = []) {
  if (typeof value === 'number') return [path];
  if (!value || typeof value !== 'object') return [];
  const keys = Array.isArray(value)
    ? (value.length > 8 ? [0, value.length - 1] : value.map((_, i) => i))
    : Object.keys(value);
  return keys.flatMap((k) => numberPaths(value[k], [...path, k]));
}

function withValue(scene, path, v) {
  const copy = structuredClone(scene);
  let node = copy;
  for (const k of path.slice(0, -1)) node = node[k];
  node[path.at(-1)] = v;
  return copy;
}

/** Both judges on one scene: they agree, or the core names a cross-field rule. */
function judge(scene, label) {
  const refusal = coreRefusal(scene);
  const schemaOk = schemaAccepts(scene);
  if (schemaOk && refusal !== null) {
    assert.ok(CROSS_FIELD.some((rule) => rule.test(refusal)),
      `${label}: the schema accepts what the core refuses (${refusal})`);
  } else if (!schemaOk && refusal === null) {
    assert.fail(`${label}: the schema refuses what the core accepts (${ajv.errorsText(schemaAccepts.errors)})`);
  }
  return { schemaOk, coreOk: refusal === null };
}

test('every shipped scene and every variant is valid to both', () => {
  for (const [name, scene] of Object.entries(SCENES)) {
    assert.equal(coreRefusal(scene), null, name);
    assert.ok(schemaAccepts(scene), `${name}: ${ajv.errorsText(schemaAccepts.errors)}`);
  }
});

test('the ranges a schema-driven editor once let through are in the schema', () => {
  for (const [path, v] of [
    [['simulation', 'dt'], -1], [['gas', 'dissipation'], 900000], [['emitters', 0, 'rate'], 1e7],
    [['field', 'amplitude'], -3], [['field', 'period', 1], 0], [['render', 'camera', 'fov_y_deg'], 180],
    [['render', 'medium', 'phase', 'g'], 1], [['wind', 3, 'path', 0, 1], 2e6], [['shapes', 0, 'count'], 0],
    [['render', 'time'], -1], [['render', 'time'], 2e6], [['gas', 'max_blobs'], 1_000_001],
  ]) {
    const scene = withValue(EVERY_VARIANT, path, v);
    assert.equal(schemaAccepts(scene), false, `schema on ${path.join('.')} = ${v}`);
    assert.notEqual(coreRefusal(scene), null, `core on ${path.join('.')} = ${v}`);
  }
});

test('every list one past its limit: the schema and the core both refuse it', () => {
  const longer = (path, n) => {
    const list = path.reduce((node, k) => node[k], EVERY_VARIANT);
    return withValue(EVERY_VARIANT, path, Array.from({ length: n }, (_, i) => structuredClone(list[i % list.length])));
  };
  const path = (n) => Array.from({ length: n }, (_, t) => [t, 0, 1, 0]);
  for (const [list, limit] of [
    [['wind'], 256], [['emitters'], 256], [['shapes'], 256], [['render', 'lights'], 64], [['render', 'objects'], 256],
  ]) {
    // Longer lists of the scene's own items.
    const scene = longer(list, limit + 1);
    assert.equal(schemaAccepts(scene), false, `schema on ${list.join('.')} of ${limit + 1}`);
    assert.match(coreRefusal(scene) ?? 'accepted', new RegExp(`${list.join('\\.')}: must hold at most ${limit}`));
    judge(longer(list, limit), `${list.join('.')} of ${limit}`);
  }
  const keys = withValue(EVERY_VARIANT, ['wind', 3, 'path'], path(10_001));
  assert.equal(schemaAccepts(keys), false);
  assert.match(coreRefusal(keys), /wind\[3\]\.path: must hold at most 10000 keys/);
  assert.equal(coreRefusal(withValue(EVERY_VARIANT, ['wind', 3, 'path'], path(10_000))), null);
});

test('the hostile scenes: refused by both, or by the core for a rule the schema states in words', () => {
  const dir = `${root}wasm-core/tests/hostile`;
  for (const name of readdirSync(dir).filter((f) => f.endsWith('.json'))) {
    const scene = JSON.parse(readFileSync(`${dir}/${name}`, 'utf8'));
    const { coreOk } = judge(scene, name);
    assert.equal(coreOk, name === 'tiny-sigma.json', name);
  }
  // A showcase of exactly 1,000,000 blobs is valid to both.
  const showcase = withValue(SCENES['steam-mug.json'], ['gas', 'max_blobs'], 1_000_000);
  assert.equal(coreRefusal(showcase), null);
  assert.ok(schemaAccepts(showcase));
});

test('every number set in and out of its range: the schema and the core agree', () => {
  const VALUES = [-3, -1, 0, 1e-9, 0.5, 2, 179.5, 900000, 1e7, 1e13, 2 ** 53 + 2];
  let refused = 0;
  let judged = 0;
  for (const [name, scene] of Object.entries(SCENES)) {
    for (const path of numberPaths(scene)) {
      for (const v of VALUES) {
        const { coreOk } = judge(withValue(scene, path, v), `${name}: ${path.join('.')} = ${v}`);
        judged += 1;
        if (!coreOk) refused += 1;
      }
    }
  }
  // Most of these are out of some range: the comparison is mostly about refusals.
  assert.ok(judged > 3000 && refused > judged / 3, `${refused} of ${judged} refused`);
});

test('random numbers in random places (seeded): the schema and the core agree', () => {
  let x = 0x5eed;
  const next = () => { // xorshift32 in [0, 1)
    x ^= x << 13; x >>>= 0; x ^= x >>> 17; x ^= x << 5; x >>>= 0;
    return x / 2 ** 32;
  };
  const names = Object.keys(SCENES);
  const paths = Object.fromEntries(names.map((n) => [n, numberPaths(SCENES[n])]));
  const count = Number(process.env.WINDFIELD_SCHEMA_CASES ?? 5000);
  for (let i = 0; i < count; i++) {
    const name = names[Math.floor(next() * names.length)];
    if (!paths[name].length) continue;
    const path = paths[name][Math.floor(next() * paths[name].length)];
    // Magnitudes from 1e-6 to 1e14, either sign; a third of them whole numbers.
    let v = (next() < 0.3 ? -1 : 1) * 10 ** (-6 + 20 * next());
    if (next() < 0.33) v = Math.round(v);
    judge(withValue(SCENES[name], path, v), `case ${i}, ${name}: ${path.join('.')} = ${v}`);
  }
});
