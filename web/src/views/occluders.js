// The opaque objects as the GPU views' shadow casters (`shaders/occluders.js`; the core's
// `render::occluded`): every object of the scene — a model drawn in a cylinder's place casts its
// cylinder's shadow, as in the CPU still — and the frame's repulsor spheres, packed into a float
// texture of OCCLUDER_TEXELS texels an object. Row 0 holds every object, for the objects'
// material; row 1 + l the objects that may stand between light l and the gas's box, for the
// marches, which test them at every sample. An object that cannot (a floor under gas lit from
// above, a sphere off to the side of a directional light's path) is left off those rows by the
// conservative tests of `mayShadowBox`, so the marches pay only for the objects that matter.

import * as THREE from 'three';
import { VIEW_LIGHTS } from '../generated/contract.js';

/** Texels an object: (x, y, z, kind), (axis or normal, radius), (height, 0, 0, 0). */
export const OCCLUDER_TEXELS = 3;
/** The `kind` each object type is stored as. */
export const OCCLUDER_KIND = { sphere: 0, plane: 1, cylinder: 2 };

const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const unit = (v) => {
  const n = Math.hypot(v[0], v[1], v[2]);
  return [v[0] / n, v[1] / n, v[2] / n];
};

/** The 4 × OCCLUDER_TEXELS floats of a scene object (`{type: 'sphere' | 'plane' | 'cylinder', ...}`). */
export function occluderRecord(o) {
  const k = OCCLUDER_KIND;
  if (o.type === 'sphere') return [...o.center, k.sphere, 0, 0, 0, o.radius, 0, 0, 0, 0];
  if (o.type === 'plane') return [...o.point, k.plane, ...unit(o.normal), 0, 0, 0, 0, 0];
  return [...o.base, k.cylinder, ...unit(o.axis), o.radius, o.height, 0, 0, 0];
}

/** A sphere holding a sphere or a cylinder: {centre, radius}. */
function boundingSphere(o) {
  if (o.type === 'sphere') return { centre: o.center, radius: o.radius };
  const a = unit(o.axis);
  const centre = [0, 1, 2].map((i) => o.base[i] + a[i] * o.height / 2);
  return { centre, radius: Math.hypot(o.radius, o.height / 2) };
}

/** Whether the ray o + t·d, t ≥ 0, meets the box [lo, hi] (slab test). */
function rayMeetsBox(o, d, lo, hi) {
  let near = 0;
  let far = Infinity;
  for (let a = 0; a < 3; a++) {
    if (d[a] === 0) {
      if (o[a] < lo[a] || o[a] > hi[a]) return false;
      continue;
    }
    const t0 = (lo[a] - o[a]) / d[a];
    const t1 = (hi[a] - o[a]) / d[a];
    near = Math.max(near, Math.min(t0, t1));
    far = Math.min(far, Math.max(t0, t1));
  }
  return near <= far;
}

/** Distance from p to the segment [a, b]. */
function segmentDistance(p, a, b) {
  const ab = sub(b, a);
  const t = Math.min(Math.max(dot(sub(p, a), ab) / Math.max(dot(ab, ab), 1e-30), 0), 1);
  return Math.hypot(...sub(p, [0, 1, 2].map((i) => a[i] + ab[i] * t)));
}

/**
 * Whether object `o` may lie between some point of the box [lo, hi] and `light` (a scene light):
 * false only where it cannot. A plane: some corner of the box on the other side of it from the
 * light. A sphere or a cylinder, by its bounding sphere (c, r): for a directional light, the
 * ray from c away from the light meets the box grown by r (the shadow of the ball is that ray
 * grown by r); for a point light P, c lies within r + R of the segment from the box's centre to
 * P, R the box's half diagonal (every segment from the box to P lies within R of that one).
 */
export function mayShadowBox(o, light, lo, hi) {
  const directional = light.type !== 'point';
  const towards = directional ? unit(light.direction).map((c) => -c) : null;
  if (o.type === 'plane') {
    const lightSide = directional ? dot(o.normal, towards) : dot(o.normal, sub(light.position, o.point));
    if (lightSide === 0) return false;
    for (let c = 0; c < 8; c++) {
      const corner = [0, 1, 2].map((a) => ((c >> a) & 1 ? hi[a] : lo[a]));
      if (dot(o.normal, sub(corner, o.point)) * lightSide < 0) return true;
    }
    return false;
  }
  const { centre, radius } = boundingSphere(o);
  if (directional) {
    return rayMeetsBox(centre, towards.map((c) => -c), lo.map((v) => v - radius), hi.map((v) => v + radius));
  }
  const middle = [0, 1, 2].map((a) => (lo[a] + hi[a]) / 2);
  const halfDiagonal = Math.hypot(...sub(hi, lo)) / 2;
  return segmentDistance(centre, middle, light.position) <= radius + halfDiagonal;
}

/**
 * The rows of the occluder texture: row 0 every object's index, row 1 + l those that may shadow
 * the box {lo, hi} from light l (every object when `box` is null; none past the lights).
 */
export function occluderRows(objects, lights, box) {
  const all = objects.map((_, i) => i);
  const rows = [all];
  for (let l = 0; l < VIEW_LIGHTS; l++) {
    if (l >= lights.length) rows.push([]);
    else if (!box) rows.push(all);
    else rows.push(all.filter((i) => mayShadowBox(objects[i], lights[l], box.lo, box.hi)));
  }
  return rows;
}

/** The occluder texture and its counts, in the shared gas uniforms (`occluders`, `occluderCount`). */
export class Occluders {
  /** @param {object} gas the shared gas uniforms (`gasUniforms()`) */
  constructor(gas) {
    this.gas = gas;
    this.texture = null;
    this.update([], [], null);
  }

  /**
   * Packs `objects` (scene objects; cylinders that name a model as their stand-ins) for
   * `lights`, the marches' rows culled against `box` ({lo, hi}, m; null for none). Uploads only
   * what changed.
   */
  update(objects, lights, box) {
    const rows = occluderRows(objects, lights, box);
    const records = objects.map(occluderRecord);
    const width = OCCLUDER_TEXELS * Math.max(1, ...rows.map((r) => r.length));
    const data = new Float32Array(4 * width * rows.length);
    rows.forEach((row, r) => row.forEach((i, k) => data.set(records[i], 4 * (r * width + OCCLUDER_TEXELS * k))));
    this.gas.occluderCount.value = rows.map((r) => r.length);
    const t = this.texture;
    if (t && t.image.width === width) {
      if (t.image.data.every((v, i) => v === data[i])) return;
      t.image.data.set(data);
      t.needsUpdate = true;
      return;
    }
    t?.dispose();
    this.texture = new THREE.DataTexture(data, width, rows.length, THREE.RGBAFormat, THREE.FloatType);
    this.texture.needsUpdate = true;
    this.gas.occluders.value = this.texture;
  }

  /** The context is lost: let go of the texture (its data stays). */
  contextLost() {
    this.texture?.dispose();
  }

  /** The context is back: upload the texture again. */
  contextRestored() {
    if (this.texture) this.texture.needsUpdate = true;
  }
}
