// The objects the marches test for shadows (`web/src/views/occluders.js`): an object left off a
// light's row never stands between that light and any point of the gas's box (checked by
// sampling shadow rays from random points of random boxes), the culling leaves off what it
// should (a floor under gas lit from above), and the records hold what the shader reads.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { mayShadowBox, occluderRecord, occluderRows, OCCLUDER_KIND, OCCLUDER_TEXELS } from '../web/src/views/occluders.js';

/** A small seeded generator (mulberry32), uniform in [0, 1). */
function random(seed) {
  let a = seed >>> 0;
  return () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

const norm = (v) => Math.hypot(...v);
const unit = (v) => v.map((c) => c / norm(v));

/** Whether the point (x, y, z) lies inside the sphere or cylinder. */
function inside(o, x, y, z) {
  if (o.type === 'sphere') return Math.hypot(x - o.center[0], y - o.center[1], z - o.center[2]) < o.radius;
  const a = unit(o.axis);
  const [rx, ry, rz] = [x - o.base[0], y - o.base[1], z - o.base[2]];
  const along = rx * a[0] + ry * a[1] + rz * a[2];
  const radial = Math.hypot(rx - a[0] * along, ry - a[1] * along, rz - a[2] * along);
  return along > 0 && along < o.height && radial < o.radius;
}

/**
 * Whether the segment from x towards the light meets the object, by sampling the part of it
 * inside the object's bounding sphere for a point inside (planes: by the sides of its ends).
 */
function blockedBySampling(o, light, x) {
  const point = light.type === 'point';
  const d = point ? unit(light.position.map((c, i) => c - x[i])) : unit(light.direction).map((c) => -c);
  const length = point ? norm(light.position.map((c, i) => c - x[i])) : Infinity;
  if (o.type === 'plane') {
    const side = (p) => o.normal.reduce((s, n, i) => s + n * (p[i] - o.point[i]), 0);
    const end = point ? side(light.position) : o.normal.reduce((s, n, i) => s + n * d[i], 0);
    return side(x) * end < 0;
  }
  if (inside(o, ...x)) return false;
  const a = o.type === 'sphere' ? [0, 0, 0] : unit(o.axis);
  const c = o.type === 'sphere' ? o.center : o.base.map((b, i) => b + a[i] * o.height / 2);
  const R = o.type === 'sphere' ? o.radius : Math.hypot(o.radius, o.height / 2);
  const tc = d.reduce((s, di, i) => s + di * (c[i] - x[i]), 0);
  const miss = Math.hypot(...x.map((xi, i) => xi + d[i] * tc - c[i]));
  if (miss >= R) return false;
  const w = Math.sqrt(R * R - miss * miss);
  const [t0, t1] = [Math.max(tc - w, 0), Math.min(tc + w, length)];
  for (let k = 1; k < 400; k++) {
    const t = t0 + (t1 - t0) * k / 400;
    if (inside(o, x[0] + d[0] * t, x[1] + d[1] * t, x[2] + d[2] * t)) return true;
  }
  return false;
}

function randomObject(r) {
  const v = (s) => [0, 1, 2].map(() => (r() * 2 - 1) * s);
  const kind = Math.floor(r() * 3);
  if (kind === 0) return { type: 'sphere', center: v(3), radius: 0.1 + r() };
  if (kind === 1) return { type: 'plane', point: v(2), normal: v(1) };
  return { type: 'cylinder', base: v(3), axis: v(1), radius: 0.05 + 0.5 * r(), height: 0.1 + 1.5 * r() };
}

function randomLight(r) {
  const v = (s) => [0, 1, 2].map(() => (r() * 2 - 1) * s);
  return r() < 0.5 ? { type: 'point', position: v(5) } : { type: 'directional', direction: v(1) };
}

test('an object left off a light\'s row shadows no point of the box from that light', () => {
  const r = random(32);
  let kept = 0;
  let left = 0;
  let shadowing = 0;
  for (let trial = 0; trial < 400; trial++) {
    const lo = [0, 1, 2].map(() => (r() * 2 - 1) * 1.5);
    const hi = lo.map((v) => v + 0.2 + 1.5 * r());
    const o = randomObject(r);
    const light = randomLight(r);
    const may = mayShadowBox(o, light, lo, hi);
    if (may) kept++;
    else left++;
    for (let k = 0; k < 40; k++) {
      const x = lo.map((v, a) => v + (hi[a] - v) * r());
      if (!blockedBySampling(o, light, x)) continue;
      shadowing++;
      assert.ok(may, `trial ${trial}: ${JSON.stringify({ o, light, lo, hi, x })} is shadowed but left off`);
    }
  }
  // The check saw both outcomes plenty of times.
  assert.ok(shadowing > 500 && left > 50 && kept > 50, `${shadowing} shadowed points, ${left} left off, ${kept} kept`);
});

test('a floor under gas lit from above is left off the gas rows, a ceiling kept; the material sees all', () => {
  const floor = { type: 'plane', point: [0, 0, 0], normal: [0, 1, 0], color: [1, 1, 1] };
  const ceiling = { type: 'plane', point: [0, 2, 0], normal: [0, -1, 0], color: [1, 1, 1] };
  const aside = { type: 'sphere', center: [5, 0.5, 0], radius: 0.3, color: [1, 1, 1] };
  const above = { type: 'sphere', center: [0.2, 1.5, 0.1], radius: 0.3, color: [1, 1, 1] };
  const box = { lo: [-0.5, 0.1, -0.5], hi: [0.5, 1, 0.5] };
  const sun = { type: 'directional', direction: [0, -1, 0], color: [1, 1, 1] };
  const lamp = { type: 'point', position: [0, 3, 0], color: [1, 1, 1] };
  const rows = occluderRows([floor, ceiling, aside, above], [sun, lamp], box);
  assert.deepEqual(rows, [[0, 1, 2, 3], [1, 3], [1, 3], [], []]);
  // Without a box (the exact march) every object is on every light's row.
  assert.deepEqual(occluderRows([floor, above], [sun], null), [[0, 1], [0, 1], [], [], []]);
});

test('the records hold what the shader reads: position and kind, unit axis or normal and radius, height', () => {
  const k = OCCLUDER_KIND;
  assert.equal(OCCLUDER_TEXELS, 3);
  assert.deepEqual(occluderRecord({ type: 'sphere', center: [1, 2, 3], radius: 0.5 }), [1, 2, 3, k.sphere, 0, 0, 0, 0.5, 0, 0, 0, 0]);
  assert.deepEqual(occluderRecord({ type: 'plane', point: [0, 1, 0], normal: [0, 2, 0] }), [0, 1, 0, k.plane, 0, 1, 0, 0, 0, 0, 0, 0]);
  assert.deepEqual(occluderRecord({ type: 'cylinder', base: [1, 0, 0], axis: [0, 0, 3], radius: 0.2, height: 0.9, model: 'mug' }),
    [1, 0, 0, k.cylinder, 0, 0, 1, 0.2, 0.9, 0, 0, 0]);
});
