// The scene's TypeScript types (types/scene.d.ts) are generated from its JSON Schema
// (public/scene.schema.json) by scripts/scene-types.mjs: the file is what the script writes
// now, and the normalised form it types as `Scene` (every key with a default present) is what
// the core's normalisation gives, for every shipped scene and for minimal scenes of every
// variant (where the core fills in the most).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readdirSync, readFileSync } from 'node:fs';
import Ajv2020 from 'ajv/dist/2020.js';
import { normalisedSchema, sceneTypes, SCHEMA_PATH, TYPES_PATH } from '../scripts/scene-types.mjs';
import { loadCore, root } from './support/core.js';

const schema = JSON.parse(readFileSync(SCHEMA_PATH, 'utf8'));

test('types/scene.d.ts is what scripts/scene-types.mjs writes from the schema now', async () => {
  const shipped = readFileSync(TYPES_PATH, 'utf8');
  assert.ok(shipped === await sceneTypes(schema), 'types/scene.d.ts is stale: run `npm run types:scene`');
});

/** Minimal scenes of every variant: the core fills in every default. */
const MINIMAL = [
  { version: 1 },
  {
    version: 1,
    wind: [
      { type: 'uniform', velocity: [0, 1, 0] },
      { type: 'source', position: [0, 0, 0], strength: 1 },
      { type: 'vortex', position: [0, 0, 0], axis: [0, 1, 0], strength: 1 },
      { type: 'repulsor', radius: 0.1, strength: 1, path: [[0, 0, 0, 0]] },
    ],
    emitters: [{}, { shape: 'disk' }, { shape: 'sphere' }, { shape: 'box' }],
    shapes: [{}, { shape: 'torus' }, { shape: 'points', points: [[0, 0, 0]] }],
    render: {
      objects: [
        { type: 'sphere', center: [0, 0, 0], radius: 1, color: [1, 1, 1] },
        { type: 'plane', point: [0, 0, 0], normal: [0, 1, 0], color: [1, 1, 1] },
        { type: 'cylinder', base: [0, 0, 0], axis: [0, 1, 0], radius: 0.1, height: 0.2, color: [1, 1, 1] },
      ],
      lights: [{ type: 'point', position: [0, 2, 0], color: [1, 1, 1] }],
      medium: { phase: { type: 'henyey-greenstein', g: 0.2 } },
    },
  },
];

test('the core\'s normalised scenes hold every key the generated `Scene` type requires', async () => {
  const core = await loadCore();
  const ajv = new Ajv2020({ allErrors: true, strict: true });
  for (const format of ['float', 'double', 'uint', 'uint32', 'uint64']) ajv.addFormat(format, true);
  const normalised = ajv.compile(normalisedSchema(schema));
  const shipped = readdirSync(`${root}public/scenes`).filter((f) => f.endsWith('.json'))
    .map((f) => [f, JSON.parse(readFileSync(`${root}public/scenes/${f}`, 'utf8'))]);
  const scenes = [...shipped, ...MINIMAL.map((s, i) => [`minimal ${i}`, s])];
  for (const [name, scene] of scenes) {
    const normal = JSON.parse(core.validateScene(JSON.stringify(scene)));
    assert.ok(normalised(normal), `${name}: ${ajv.errorsText(normalised.errors)}`);
  }
});
