// The exact GPU march (the `exact` view, docs/FORMATS.md) of the blob list in a fragment shader.
// Each pixel gathers the chords of the blobs in its screen tile, then steps along the ray as the
// CPU reference does (`render/renderer.rs`: paper Appendix B, Eqs. 22–28): steps of
// STEP_FRACTION of the smallest σ met, the exact Gaussian line integral of every chord over each
// step (Eq. 28, via erf), the density-weighted source Ω L + (1 − Ω) Q (Eq. 24), L the lights
// through the phase function and the shadow transmittance S_k (Eq. 25), front-to-back
// compositing (Eqs. 26–27). Shadows come from a grid of shadow columns ∫ρ towards each light
// computed by the WASM core and interpolated trilinearly, and are complete where an object
// blocks the light (an exact ray test, `shaders/occluders.js`). The opaque pass's colour and
// depth sit behind the gas. Everything arrives from the engine worker as whole buffers
// (`exactFrame`): the blobs packed as for every view (the core's level of detail, `marchFrame`:
// blobs much closer than their width merged by moments), the shadow grid, and the screen tiles;
// this layer only uploads them.

import * as THREE from 'three';
import { BLOBS_PER_ROW, STEP_FRACTION, TRUNCATION, VIEW_LIGHTS, WORDS_PER_BLOB } from '../../generated/contract.js';
import { BlobTexture } from '../blob-texture.js';
import { releaseGeometries } from '../context-loss.js';
import { MarchQuad } from '../march-quad.js';
import { BLOB_GLSL } from '../shaders/blob-record.js';
import { ERF_GLSL } from '../shaders/erf.js';
import { GRID_SHADOW_GLSL } from '../shaders/grid-shadow.js';
import { LIGHTS_GLSL } from '../shaders/lights.js';
import { MARCH_PREAMBLE } from '../shaders/march-preamble.js';
import { OCCLUDERS_GLSL } from '../shaders/occluders.js';

/**
 * Where the shadow grid's header (`frame::shadow_grid`: SHADOW_GRID_HEADER floats, lo xyz, hi
 * xyz, res, lights) holds its corners (m) and its points per axis.
 */
const GRID_LO = 0;
const GRID_HI = 3;
const GRID_RES = 6;

const fragmentShader = /* glsl */ `
${MARCH_PREAMBLE}
uniform sampler2D headTex;    // a texel a tile: start, count
uniform sampler2D listTex;    // blob indices (in .x)
uniform int tilesX;
uniform int tileSide;          // pixels (tileFor in exact-frame.js)

const int W = ${BLOBS_PER_ROW};
const float TRUNC = ${TRUNCATION.toFixed(2)};
vec4 fetch(sampler2D t, int i) { return texelFetch(t, ivec2(i % W, i / W), 0); }

${ERF_GLSL}
${BLOB_GLSL}
${LIGHTS_GLSL}
${GRID_SHADOW_GLSL}
${OCCLUDERS_GLSL}
const int MAX_HITS = 64;
const int MAX_STEPS = 4000;
const int MAX_WINDOWS = 256;

// The chord of blob idx along the ray: [s0, s1] clipped to [0, sMax]; false if none.
bool chordOf(int idx, vec3 rd, float sMax, out float s0, out float s1, out float sm, out float r2, out float sigma) {
  uvec4 a = texelFetch(blobTex, ivec2((idx % ${BLOBS_PER_ROW}) * ${WORDS_PER_BLOB / 4}, idx / ${BLOBS_PER_ROW}), 0);
  sigma = uintBitsToFloat(a.w);
  vec3 oc = uintBitsToFloat(a.xyz) - camPos;
  sm = dot(oc, rd);
  r2 = max(dot(oc, oc) - sm * sm, 0.0);
  float R = TRUNC * sigma;
  if (r2 >= R * R) return false;
  float h = sqrt(R * R - r2);
  s0 = max(sm - h, 0.0);
  s1 = min(sm + h, sMax);
  return s1 > s0;
}

// m/(4πσ²) exp(−r²/2σ²): the chord's line integral per unit of erf.
float peakOf(int idx, float sigma, float r2) {
  float m = uintBitsToFloat(texelFetch(blobTex, ivec2((idx % ${BLOBS_PER_ROW}) * ${WORDS_PER_BLOB / 4} + 1, idx / ${BLOBS_PER_ROW}), 0).x);
  return m / (12.566370614 * sigma * sigma) * exp(-r2 / (2.0 * sigma * sigma));
}

// Adds blob idx's share of the step [s, e] (its chord [s0, s1]) to the density-weighted sums.
void addChord(int idx, float s0, float s1, float sm, float pk, float iw, float s, float e,
              inout float w, inout vec3 albedo, inout vec3 emitted) {
  float a = max(s, s0);
  float b = min(e, s1);
  if (b <= a) return;
  float wk = pk * (erf1((b - sm) * iw) - erf1((a - sm) * iw));
  vec3 centre, al, q;
  float sigma, mass;
  fetchBlob(idx, centre, sigma, mass, al, q);
  w += wk;
  albedo += al * wk;
  emitted += q * wk;
}

void main() {
  vec3 rd, behind;
  float sMax;
  viewRay(vUv, rd, sMax, behind);
  ivec2 tile = ivec2(gl_FragCoord.xy) / tileSide;
  vec4 head = fetch(headTex, tile.y * tilesX + tile.x);
  int start = int(head.x);
  int count = int(head.y);
  float s0, s1, sm, r2, sigma;
  // Where the ray's chords begin and end, and the smallest σ it meets.
  float first = 1e30;
  float last = 0.0;
  float sigmaMin = 1e30;
  int chords = 0;
  for (int k = 0; k < count; k++) {
    if (!chordOf(int(fetch(listTex, start + k).x), rd, sMax, s0, s1, sm, r2, sigma)) continue;
    first = min(first, s0);
    last = max(last, s1);
    sigmaMin = min(sigmaMin, sigma);
    chords++;
  }
  // March [first, last) in windows that each meet at most MAX_HITS chords, kept in registers:
  // a window that meets more is halved and gathered again. Where more than MAX_HITS chords
  // overlap within a blob's width, that window is marched reading every candidate per step.
  // No blob is ever dropped.
  float sIn[MAX_HITS], sOut[MAX_HITS], sMid[MAX_HITS], peak[MAX_HITS], invW[MAX_HITS];
  int id[MAX_HITS];
  vec3 T = vec3(1.0);
  vec3 rad = vec3(0.0);
  float sA = first;
  // First window: the whole ray when its chords fit, else a share sized for them to.
  float width = (last - first) * (chords <= MAX_HITS ? 1.0 : 0.5 * float(MAX_HITS) / float(chords));
  int steps = 0;
  for (int win = 0; win < MAX_WINDOWS && sA < last && steps < MAX_STEPS; win++) {
    float sB = min(sA + width, last);
    int hits = 0;
    bool full = false;
    float minSigma = 1e30;
    float nextIn = 1e30;
    for (int k = 0; k < count; k++) {
      int idx = int(fetch(listTex, start + k).x);
      if (!chordOf(idx, rd, sMax, s0, s1, sm, r2, sigma)) continue;
      if (s1 <= sA || s0 >= sB) continue;
      minSigma = min(minSigma, sigma);
      nextIn = min(nextIn, s0);
      if (hits == MAX_HITS) {
        full = true;
        if (width > sigmaMin) break; // this window is halved and gathered again
        continue;
      }
      sIn[hits] = s0; sOut[hits] = s1; sMid[hits] = sm; id[hits] = idx;
      invW[hits] = 0.70710678 / sigma;
      peak[hits] = peakOf(idx, sigma, r2);
      hits++;
    }
    if (full && width > sigmaMin) {
      width *= 0.5;
      continue;
    }
    float step = ${STEP_FRACTION.toFixed(1)} * minSigma;
    float s = max(sA, nextIn);
    while (hits > 0 && s < sB && steps < MAX_STEPS) {
      steps++;
      float e = min(s + step, sB);
      float w = 0.0;
      vec3 albedo = vec3(0.0);
      vec3 emitted = vec3(0.0);
      float upcoming = 1e30;
      if (full) {
        for (int k = 0; k < count; k++) {
          int idx = int(fetch(listTex, start + k).x);
          if (!chordOf(idx, rd, sMax, s0, s1, sm, r2, sigma)) continue;
          if (s0 >= e) { upcoming = min(upcoming, s0); continue; }
          addChord(idx, s0, s1, sm, peakOf(idx, sigma, r2), 0.70710678 / sigma, s, e, w, albedo, emitted);
        }
      } else {
        for (int k = 0; k < hits; k++) {
          if (sIn[k] >= e) { upcoming = min(upcoming, sIn[k]); continue; }
          addChord(id[k], sIn[k], sOut[k], sMid[k], peak[k], invW[k], s, e, w, albedo, emitted);
        }
      }
      if (w > 0.0) {
        albedo /= w;
        vec3 x = camPos + rd * (0.5 * (s + e));
        vec3 L = vec3(0.0);
        for (int l = 0; l < ${VIEW_LIGHTS}; l++) {
          if (l >= lightCount) break;
          float dist;
          vec3 toLight = towardsLight(l, x, dist);
          if (hasShadows && lightBlocked(1 + l, x, toLight, dist)) continue;
          float column = hasShadows ? shadowColumn(l, x) : 0.0;
          L += phase(dot(rd, toLight)) * exp(-extinction * column) * lightColor[l]; // Eq. 25
        }
        vec3 C = albedo * L + emitted / w; // Eq. 24
        vec3 absorbed = 1.0 - exp(-extinction * w); // 1 − τ_i (Eq. 28)
        rad += T * absorbed * C; // Eq. 27
        T *= 1.0 - absorbed;
        if (max(T.r, max(T.g, T.b)) < 1e-4) break;
        s = e;
      } else {
        s = max(e, upcoming); // jump the gap to the next chord
      }
    }
    if (max(T.r, max(T.g, T.b)) < 1e-4) break;
    sA = sB;
    width *= 1.5;
  }
  outColor = vec4(encode(rad + T * behind), 1.0);
}
`;

/** A float texture BLOBS_PER_ROW wide over `data` (whole rows, as the worker pads them). */
function floatTexture(data, format) {
  const channels = format === THREE.RGBAFormat ? 4 : 1;
  const rows = Math.max(1, data.length / (channels * BLOBS_PER_ROW));
  if (!Number.isInteger(rows)) throw new Error('float texture data must fill whole rows');
  const tex = new THREE.DataTexture(data, BLOBS_PER_ROW, rows, format, THREE.FloatType);
  tex.needsUpdate = true;
  return tex;
}

export class ExactMarchLayer extends MarchQuad {
  /** @param {object} gas the shared gas uniforms; this layer fills the shadow grid's entries */
  constructor(gas) {
    Object.assign(gas, {
      shadowTex: gas.shadowTex ?? { value: null },
      gridMin: gas.gridMin ?? { value: new THREE.Vector3() },
      gridMax: gas.gridMax ?? { value: new THREE.Vector3(1, 1, 1) },
      gridRes: gas.gridRes ?? { value: 2 },
    });
    super(fragmentShader, { ...gas, blobTex: { value: null }, headTex: { value: null }, listTex: { value: null }, tilesX: { value: 1 }, tileSide: { value: 16 } });
    this.gas = gas;
    this.blobs = new BlobTexture();
    this.textures = [];
  }

  /**
   * Uploads the worker's `exactFrame` (packed merged blobs, shadow grid, tiles); returns
   * whether it has a shadow grid.
   */
  update(frame) {
    this.blobs.upload(frame.blobs, frame.count);
    for (const t of this.textures) t.dispose();
    const u = this.material.uniforms;
    const g = this.gas;
    const res = frame.grid[GRID_RES];
    g.shadowTex.value = floatTexture(frame.columns, THREE.RedFormat);
    if (res > 1) {
      g.gridMin.value.fromArray(frame.grid.subarray(GRID_LO, GRID_LO + 3));
      g.gridMax.value.fromArray(frame.grid.subarray(GRID_HI, GRID_HI + 3));
      g.gridRes.value = res;
    }
    u.blobTex.value = this.blobs.texture;
    u.headTex.value = floatTexture(frame.heads, THREE.RGBAFormat);
    u.listTex.value = floatTexture(frame.list, THREE.RedFormat);
    this.textures = [g.shadowTex.value, u.headTex.value, u.listTex.value];
    u.tilesX.value = frame.tilesX;
    u.tileSide.value = frame.tile;
    return res > 1;
  }

  /** The context is lost: let go of its textures and quad (`context-loss.js`); the data stays. */
  contextLost() {
    this.blobs.contextLost();
    for (const t of this.textures) t.dispose();
    releaseGeometries(this.scene);
  }

  /** The context is back: upload the last `update`'s textures (they keep their data) again. */
  contextRestored() {
    this.blobs.contextRestored();
    for (const t of this.textures) t.needsUpdate = true;
  }
}
