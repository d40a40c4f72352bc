// GLSL: the opaque objects' shadows (`render::occluded` in the core): S_k is zero where an object
// lies between a point and light k (Eq. 25, the rendering model of docs/FORMATS.md). An exact
// any-hit test of the shadow ray against the objects `views/occluders.js` packs into a texture,
// for the objects' material (one row: every object) and the marches (a row a light: the objects
// that may stand between that light and the gas).

import { VIEW_LIGHTS } from '../../generated/contract.js';
import { OCCLUDER_KIND, OCCLUDER_TEXELS } from '../occluders.js';

/**
 * `lightBlocked(row, x, d, sMax)`: whether an object of `row` (0 every object, 1 + l those
 * that may shadow the gas from light l) lies on x + s·d, 0 < s < sMax (the distance to a point
 * light, 1e30 for a directional one).
 */
export const OCCLUDERS_GLSL = /* glsl */ `
uniform highp sampler2D occluders;             // ${OCCLUDER_TEXELS} texels an object a row: (x, y, z, kind), (axis or normal, radius), (height)
uniform int occluderCount[${VIEW_LIGHTS + 1}];  // objects on each row
const float OCCLUDER_EPS = 1e-4;

// Whether the ray enters object i of the row (a sphere or closed cylinder from outside, a
// two-sided plane from either side) at 0 < s < sMax, beyond OCCLUDER_EPS.
bool entersOccluder(int row, int i, vec3 x, vec3 d, float sMax) {
  vec4 a = texelFetch(occluders, ivec2(${OCCLUDER_TEXELS} * i, row), 0);
  vec4 b = texelFetch(occluders, ivec2(${OCCLUDER_TEXELS} * i + 1, row), 0);
  vec3 oc = x - a.xyz;
  if (a.w == ${OCCLUDER_KIND.sphere.toFixed(1)}) {
    float q = dot(oc, oc) - b.w * b.w;
    float p = dot(oc, d);
    float disc = p * p - q;
    if (q <= 0.0 || disc < 0.0) return false;
    float s = -p - sqrt(disc);
    return s > OCCLUDER_EPS && s < sMax;
  }
  if (a.w == ${OCCLUDER_KIND.plane.toFixed(1)}) {
    float den = dot(d, b.xyz);
    if (abs(den) < 1e-9) return false;
    float s = -dot(oc, b.xyz) / den;
    return s > OCCLUDER_EPS && s < sMax;
  }
  // A closed cylinder: the later of its entries into the slab 0 ≤ along ≤ height and into the
  // infinite cylinder, if before both exits.
  float h = texelFetch(occluders, ivec2(${OCCLUDER_TEXELS} * i + 2, row), 0).x;
  vec3 axis = b.xyz;
  float da = dot(d, axis);
  float oa = dot(oc, axis);
  float t0 = -1e30;
  float t1 = 1e30;
  if (abs(da) > 1e-9) {
    float ta = -oa / da;
    float tb = (h - oa) / da;
    t0 = min(ta, tb);
    t1 = max(ta, tb);
  } else if (oa < 0.0 || oa > h) {
    return false;
  }
  vec3 dp = d - axis * da;
  vec3 op = oc - axis * oa;
  float qa = dot(dp, dp);
  float qb = dot(dp, op);
  float qc = dot(op, op) - b.w * b.w;
  if (qa > 1e-12) {
    float disc = qb * qb - qa * qc;
    if (disc < 0.0) return false;
    float root = sqrt(disc);
    t0 = max(t0, (-qb - root) / qa);
    t1 = min(t1, (-qb + root) / qa);
  } else if (qc > 0.0) {
    return false;
  }
  return t0 < t1 && t0 > OCCLUDER_EPS && t0 < sMax;
}

bool lightBlocked(int row, vec3 x, vec3 d, float sMax) {
  int n = occluderCount[row];
  for (int i = 0; i < n; i++) {
    if (entersOccluder(row, i, x, d, sMax)) return true;
  }
  return false;
}
`;
