// GPU ray march of the blob list (DESIGN §4) in a fragment shader. Each pixel gathers the
// chords of the blobs in its screen tile, then steps along the ray as the CPU reference does:
// steps of half the smallest σ met, the exact Gaussian line integral of every chord over each
// step (erf), the density-weighted source Ω L + (1 − Ω) Q, front-to-back compositing. Shadows
// come from a grid of shadow columns ∫ρ towards each light computed by the WASM core and
// interpolated trilinearly. The opaque pass's colour and depth sit behind the gas. Blob data,
// shadow grid and tile lists live in float textures. The list drawn is the core's level of
// detail (`marchList`): blobs much closer than their width merged by moments, so a dense plume
// costs what its volume does, not what its blob count does.

import * as THREE from 'three';
import { binBlobs, TRUNCATION } from './tiles.js';

export const MAX_LIGHTS = 4;
export const TILE = 16;
const TEX_WIDTH = 1024;

const vertexShader = /* glsl */ `
out vec2 vUv;
void main() { vUv = uv; gl_Position = vec4(position.xy, 0.0, 1.0); }
`;

/** Uniforms and functions for gas shadows (shared by the ray march and the objects' material). */
export const SHADOW_GLSL = /* glsl */ `
uniform sampler2D shadowTex;  // shadow columns: light-major, then z, y, x (in .x)
uniform vec3 gridMin, gridMax;
uniform int gridRes;
uniform bool hasShadows;
uniform int lightCount;
uniform int lightType[${MAX_LIGHTS}]; // 0 point, 1 directional
uniform vec3 lightVec[${MAX_LIGHTS}]; // position, or unit vector towards the light
uniform vec3 lightColor[${MAX_LIGHTS}];
uniform vec3 kappa;
float fetchShadow(int i) { return texelFetch(shadowTex, ivec2(i % ${TEX_WIDTH}, i / ${TEX_WIDTH}), 0).x; }

// Shadow column ∫ρ towards light l from x, trilinear on the grid of the gas's bounds. Outside
// the grid the column is the one from where the path to the light enters it (no gas lies
// outside), or 0 if it never does.
float gridColumn(int l, vec3 g) {
  ivec3 i0 = min(ivec3(floor(g)), ivec3(gridRes - 2));
  vec3 f = g - vec3(i0);
  int base = l * gridRes * gridRes * gridRes;
  float v[8];
  for (int c = 0; c < 8; c++) {
    ivec3 o = ivec3(c & 1, (c >> 1) & 1, (c >> 2) & 1);
    ivec3 p = i0 + o;
    v[c] = fetchShadow(base + (p.z * gridRes + p.y) * gridRes + p.x);
  }
  float x00 = mix(v[0], v[1], f.x), x10 = mix(v[2], v[3], f.x);
  float x01 = mix(v[4], v[5], f.x), x11 = mix(v[6], v[7], f.x);
  return mix(mix(x00, x10, f.y), mix(x01, x11, f.y), f.z);
}

float shadowColumn(int l, vec3 x) {
  if (!hasShadows) return 0.0;
  float top = float(gridRes - 1);
  vec3 scale = top / (gridMax - gridMin);
  vec3 g = (x - gridMin) * scale;
  if (all(greaterThanEqual(g, vec3(0.0))) && all(lessThanEqual(g, vec3(top)))) return gridColumn(l, g);
  // Enter the grid's box along the path towards the light (slab test in grid units).
  vec3 d = (lightType[l] == 0 ? lightVec[l] - x : lightVec[l]) * scale;
  float sMax = lightType[l] == 0 ? 1.0 : 1e30;
  vec3 inv = 1.0 / d;
  vec3 t0 = (vec3(0.0) - g) * inv, t1 = (vec3(top) - g) * inv;
  float near = max(max(min(t0.x, t1.x), min(t0.y, t1.y)), max(min(t0.z, t1.z), 0.0));
  float far = min(min(max(t0.x, t1.x), max(t0.y, t1.y)), min(max(t0.z, t1.z), sMax));
  if (near > far) return 0.0;
  return gridColumn(l, clamp(g + d * near, vec3(0.0), vec3(top)));
}
`;

const fragmentShader = /* glsl */ `
precision highp float;
precision highp int;
precision highp sampler2D;
in vec2 vUv;
out vec4 outColor;
uniform sampler2D blobTex;    // 3 texels a blob: centre, σ | mass, albedo | emission
uniform sampler2D headTex;    // a texel a tile: start, count
uniform sampler2D listTex;    // blob indices
uniform sampler2D opaqueColor;
uniform sampler2D opaqueDepth;
uniform bool hasOpaque;
uniform vec2 resolution;
uniform int tilesX;
uniform vec3 camPos, camForward, camRight, camUp;
uniform float tanHalf, camNear, camFar;
uniform vec3 background;
uniform int phaseType; // 0 isotropic, 1 Henyey-Greenstein
uniform float phaseG;
uniform bool srgb;

const int W = ${TEX_WIDTH};
const float TRUNC = ${TRUNCATION.toFixed(2)};
vec4 fetch(sampler2D t, int i) { return texelFetch(t, ivec2(i % W, i / W), 0); }

// erf, Abramowitz & Stegun 7.1.26 (|error| < 1.5e-7).
float erf1(float x) {
  float s = sign(x); x = abs(x);
  float t = 1.0 / (1.0 + 0.3275911 * x);
  float y = 1.0 - (((((1.061405429 * t - 1.453152027) * t) + 1.421413741) * t - 0.284496736) * t + 0.254829592) * t * exp(-x * x);
  return s * y;
}

float phase(float c) {
  if (phaseType == 0) return 1.0;
  float g = phaseG;
  return (1.0 - g * g) / pow(1.0 + g * g - 2.0 * g * c, 1.5);
}

vec3 encode(vec3 v) {
  v = clamp(v, 0.0, 1.0);
  if (!srgb) return v;
  return mix(12.92 * v, 1.055 * pow(v, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), v));
}

${SHADOW_GLSL}
const int MAX_HITS = 64;
const int MAX_STEPS = 4000;
const int MAX_WINDOWS = 256;

// The chord of blob idx along the ray: [s0, s1] clipped to [0, sMax]; false if none.
bool chordOf(int idx, vec3 rd, float sMax, out float s0, out float s1, out float sm, out float r2, out float sigma) {
  vec4 a = fetch(blobTex, 3 * idx);
  sigma = a.w;
  vec3 oc = a.xyz - camPos;
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
  float m = fetch(blobTex, 3 * idx + 1).x;
  return m / (12.566370614 * sigma * sigma) * exp(-r2 / (2.0 * sigma * sigma));
}

// Adds blob idx's share of the step [s, e] (its chord [s0, s1]) to the density-weighted sums.
void addChord(int idx, float s0, float s1, float sm, float pk, float iw, float s, float e,
              inout float w, inout vec3 albedo, inout vec3 emitted) {
  float a = max(s, s0);
  float b = min(e, s1);
  if (b <= a) return;
  float wk = pk * (erf1((b - sm) * iw) - erf1((a - sm) * iw));
  vec4 bb = fetch(blobTex, 3 * idx + 1);
  vec3 q = fetch(blobTex, 3 * idx + 2).rgb;
  w += wk;
  albedo += bb.yzw * wk;
  emitted += (1.0 - bb.yzw) * q * wk;
}

void main() {
  vec2 ndc = gl_FragCoord.xy / resolution * 2.0 - 1.0;
  float aspect = resolution.x / resolution.y;
  vec3 rd = normalize(camForward + camRight * ndc.x * tanHalf * aspect + camUp * ndc.y * tanHalf);
  vec3 behind = background;
  float sMax = 1e30;
  if (hasOpaque) {
    float d = texture(opaqueDepth, vUv).x;
    if (d < 1.0) {
      float zN = d * 2.0 - 1.0;
      float viewZ = 2.0 * camNear * camFar / (camFar + camNear - zN * (camFar - camNear));
      sMax = viewZ / dot(rd, camForward);
      behind = texture(opaqueColor, vUv).rgb;
    }
  }
  ivec2 tile = ivec2(gl_FragCoord.xy) / ${TILE};
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
    float step = 0.5 * minSigma;
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
        for (int l = 0; l < ${MAX_LIGHTS}; l++) {
          if (l >= lightCount) break;
          vec3 toLight = lightType[l] == 0 ? normalize(lightVec[l] - x) : lightVec[l];
          L += phase(dot(rd, toLight)) * exp(-kappa * shadowColumn(l, x)) * lightColor[l];
        }
        vec3 C = albedo * L + emitted / w;
        vec3 absorbed = 1.0 - exp(-kappa * w);
        rad += T * absorbed * C;
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

function floatTexture(data, texels) {
  const rows = Math.max(1, Math.ceil(texels / TEX_WIDTH));
  const buf = new Float32Array(TEX_WIDTH * rows * 4);
  buf.set(data.subarray(0, Math.min(data.length, buf.length)));
  const tex = new THREE.DataTexture(buf, TEX_WIDTH, rows, THREE.RGBAFormat, THREE.FloatType);
  tex.needsUpdate = true;
  return tex;
}

export class RaymarchLayer {
  constructor() {
    this.material = new THREE.ShaderMaterial({
      glslVersion: THREE.GLSL3,
      vertexShader,
      fragmentShader,
      depthTest: false,
      depthWrite: false,
      uniforms: {
        blobTex: { value: null }, shadowTex: { value: null }, headTex: { value: null }, listTex: { value: null },
        gridMin: { value: new THREE.Vector3() }, gridMax: { value: new THREE.Vector3(1, 1, 1) },
        gridRes: { value: 2 }, hasShadows: { value: false },
        opaqueColor: { value: null }, opaqueDepth: { value: null }, hasOpaque: { value: false },
        resolution: { value: new THREE.Vector2(1, 1) }, tilesX: { value: 1 },
        camPos: { value: new THREE.Vector3() }, camForward: { value: new THREE.Vector3() },
        camRight: { value: new THREE.Vector3() }, camUp: { value: new THREE.Vector3() },
        tanHalf: { value: 1 }, camNear: { value: 0.01 }, camFar: { value: 100 },
        kappa: { value: new THREE.Vector3(1, 1, 1) }, background: { value: new THREE.Vector3() },
        phaseType: { value: 0 }, phaseG: { value: 0 }, lightCount: { value: 0 },
        lightType: { value: new Array(MAX_LIGHTS).fill(0) },
        lightVec: { value: Array.from({ length: MAX_LIGHTS }, () => new THREE.Vector3()) },
        lightColor: { value: Array.from({ length: MAX_LIGHTS }, () => new THREE.Vector3()) },
        srgb: { value: true },
      },
    });
    this.quad = new THREE.Mesh(new THREE.PlaneGeometry(2, 2), this.material);
    this.quad.frustumCulled = false;
    this.scene = new THREE.Scene();
    this.scene.add(this.quad);
    this.ortho = new THREE.OrthographicCamera(-1, 1, 1, -1, 0, 1);
    this.textures = [];
  }

  /**
   * Uploads the blob list for one frame: `list` is DESIGN §4's object (camera is taken from
   * `view`), `grid` the core's shadow grid (header, then columns; `shadowGrid` in the core) or null.
   */
  update(list, grid, view, width, height) {
    const n = list.blobs.length;
    const medium = list.medium;
    const mediumAlbedo = medium.albedo;
    const blobData = new Float32Array(12 * Math.max(n, 1));
    const positions = new Float32Array(3 * n);
    const sigma = new Float32Array(n);
    list.blobs.forEach((b, i) => {
      const al = b.albedo ?? mediumAlbedo;
      const q = b.emission ?? [0, 0, 0];
      blobData.set([...b.center, b.sigma, b.mass, ...al, ...q, 0], 12 * i);
      positions.set(b.center, 3 * i);
      sigma[i] = b.sigma;
    });
    const res = grid ? grid[6] : 0;
    const columns = res > 1 ? grid.subarray(8) : new Float32Array(1);
    const shadowData = new Float32Array(4 * Math.max(columns.length, 1));
    columns.forEach((v, i) => { shadowData[4 * i] = v; });
    const tiles = binBlobs({ positions, sigma, count: n }, view, width, height, TILE);
    for (const t of this.textures) t.dispose();
    const u = this.material.uniforms;
    u.blobTex.value = floatTexture(blobData, 3 * n);
    u.shadowTex.value = floatTexture(shadowData, columns.length);
    u.hasShadows.value = res > 1;
    if (res > 1) {
      u.gridMin.value.fromArray(grid.subarray(0, 3));
      u.gridMax.value.fromArray(grid.subarray(3, 6));
      u.gridRes.value = res;
    }
    u.headTex.value = floatTexture(tiles.heads, tiles.tilesX * tiles.tilesY);
    const listData = new Float32Array(4 * tiles.list.length);
    tiles.list.forEach((v, i) => { listData[4 * i] = v; });
    u.listTex.value = floatTexture(listData, tiles.list.length);
    this.textures = [u.blobTex.value, u.shadowTex.value, u.headTex.value, u.listTex.value];
    u.tilesX.value = tiles.tilesX;
    u.resolution.value.set(width, height);
    u.camPos.value.fromArray(view.position);
    u.camForward.value.fromArray(view.forward);
    u.camRight.value.fromArray(view.right);
    u.camUp.value.fromArray(view.up);
    u.tanHalf.value = view.tanHalf;
    u.background.value.fromArray(list.background);
    u.phaseType.value = medium.phase?.type === 'henyey-greenstein' ? 1 : 0;
    u.phaseG.value = medium.phase?.g ?? 0;
    this.setLights(list.lights, medium);
    u.srgb.value = (list.image?.encoding ?? 'srgb') === 'srgb';
  }

  /** Lights (at most MAX_LIGHTS) and the medium's extinction κ_t, shared with the objects. */
  setLights(lights, medium) {
    const u = this.material.uniforms;
    const k = Array.isArray(medium.extinction) ? medium.extinction : [medium.extinction, medium.extinction, medium.extinction];
    u.kappa.value.fromArray(k);
    const used = lights.slice(0, MAX_LIGHTS);
    u.lightCount.value = used.length;
    used.forEach((l, i) => {
      u.lightType.value[i] = l.type === 'point' ? 0 : 1;
      if (l.type === 'point') u.lightVec.value[i].fromArray(l.position);
      else u.lightVec.value[i].fromArray(l.direction).normalize().negate();
      u.lightColor.value[i].fromArray(l.color);
    });
  }

  /** Binds the opaque pass (colour and depth targets) and its camera's clip planes. */
  setOpaque(target, near, far) {
    const u = this.material.uniforms;
    u.hasOpaque.value = Boolean(target);
    u.opaqueColor.value = target?.texture ?? null;
    u.opaqueDepth.value = target?.depthTexture ?? null;
    u.camNear.value = near;
    u.camFar.value = far;
  }

  render(renderer) {
    renderer.render(this.scene, this.ortho);
  }
}
