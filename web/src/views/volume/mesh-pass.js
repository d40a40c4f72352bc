// The particle mesh (the real-time view's path for blobs at least DIRECT_LIMIT voxels wide), as
// `frame::volume::splat` in the core does it: per mesh class k (σ_k = √2^(k − CLASS_BIAS) m), every
// blob of σ classes k − 1 and k deposits its share of mass — the split between classes k and
// k + 1 that keeps its column through the centre, w = 2σ_k²/σ² − 1 — on the eight voxels around
// its centre (cloud in cell), and the
// class's mesh is then blurred along x, y and z by the kernel of variance σ_k² − h²/6, the last
// pass adding into the density atlas. The work is eight voxels a blob plus three passes over the
// grid a class: it does not grow with the blobs' widths.

import * as THREE from 'three';
import { ScreenPass } from '../screen-pass.js';
import { CLASS_BIAS, DIRECT_LIMIT, MAX_BLUR_RADIUS } from '../../generated/contract.js';
import { BLOB_GLSL } from '../shaders/blob-record.js';
import { VOXEL_GRID_GLSL } from '../shaders/voxel-grid.js';
import { ATLAS_PASS_GLSL } from './glsl.js';
import { blurKernel, classOf, classSigma } from './grid.js';
import { ADDITIVE, additivePoints } from './point-draws.js';

const depositVertex = /* glsl */ `
precision highp float;
precision highp int;
${BLOB_GLSL}
${VOXEL_GRID_GLSL}
uniform Grid grid;
uniform int atlasCols;
uniform vec2 atlasSize;
uniform int classOffset;
uniform float sigmaLow;   // σ_k of the drawn σ class k
uniform int sigmaClass;   // k: blobs of other classes are left out (a mixed range holds them all)
uniform bool upper;       // deposit the share of mesh class k + 1 (else k)
flat out vec3 vFraction;  // trilinear fractions towards the next voxel
flat out float vScale;    // share of density of the slice, before the xy weights
flat out vec3 vAlbedo;
flat out vec3 vSource;
flat out ivec2 vCorner;

void main() {
  int blob = classOffset + gl_VertexID / 2;
  int s = gl_VertexID % 2;
  vec3 c;
  float sigma, mass;
  fetchBlob(blob, c, sigma, mass, vAlbedo, vSource);
  gl_PointSize = 2.0;
  float lower = clamp(2.0 * sigmaLow * sigmaLow / (sigma * sigma) - 1.0, 0.0, 1.0);
  float share = upper ? 1.0 - lower : lower;
  int own = clamp(int((floatBitsToUint(sigma * sigma) >> 23) & 255u) - 127 + ${CLASS_BIAS}, 0, 63);
  if (own != sigmaClass || sigma < ${DIRECT_LIMIT.toFixed(2)} * grid.h || mass <= 0.0 || share <= 0.0) {
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    return;
  }
  vec3 top = vec3(grid.dims - 1);
  vec3 g = clamp((c - grid.lo) / grid.h - 0.5, vec3(0.0), top);
  vec3 i0 = min(floor(g), max(top - 1.0, vec3(0.0)));
  vFraction = g - i0;
  float wz = s == 0 ? 1.0 - vFraction.z : vFraction.z;
  int k = int(i0.z) + s;
  vScale = share * wz * mass / (grid.h * grid.h * grid.h);
  vCorner = atlasTexel(ivec3(ivec2(i0.xy), k), grid.dims, atlasCols);
  vec2 corner = vec2(vCorner);
  gl_Position = vec4((corner + 1.0) / atlasSize * 2.0 - 1.0, 0.0, 1.0);
}
`;

const depositFragment = /* glsl */ `
precision highp float;
precision highp int;
flat in vec3 vFraction;
flat in float vScale;
flat in vec3 vAlbedo;
flat in vec3 vSource;
flat in ivec2 vCorner;
layout(location = 0) out vec4 outDensity;
layout(location = 1) out vec4 outSource;
void main() {
  ivec2 q = ivec2(gl_FragCoord.xy) - vCorner;
  vec2 w = mix(1.0 - vFraction.xy, vFraction.xy, vec2(q));
  float rho = vScale * w.x * w.y;
  outDensity = vec4(rho, rho * vAlbedo);
  outSource = vec4(rho * vSource, 0.0);
}
`;

const blurFragment = /* glsl */ `
${ATLAS_PASS_GLSL}
uniform Grid grid;
uniform int atlasCols;
uniform sampler2D meshDensity;
uniform sampler2D meshSource;
uniform bool emissive;
uniform int axis;
uniform int radius;
uniform float kernel[${2 * MAX_BLUR_RADIUS + 1}];
layout(location = 0) out vec4 outDensity;
layout(location = 1) out vec4 outSource;

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  ivec3 v;
  outDensity = vec4(0.0);
  outSource = vec4(0.0);
  if (!atlasVoxel(px, grid.dims, atlasCols, v)) return;
  // Taps from voxel first to last along the axis (inside the grid); along x and y they lie in
  // this slice's tile, a texel apart.
  int first = max(v[axis] - radius, 0);
  int last = min(v[axis] + radius, grid.dims[axis] - 1);
  int i = first - v[axis] + radius;
  if (axis < 2) {
    ivec2 step = axis == 0 ? ivec2(1, 0) : ivec2(0, 1);
    ivec2 at = px + step * (first - v[axis]);
    for (int t = first; t <= last; t++, i++, at += step) {
      outDensity += kernel[i] * texelFetch(meshDensity, at, 0);
      if (emissive) outSource += kernel[i] * texelFetch(meshSource, at, 0);
    }
  } else {
    for (int t = first; t <= last; t++, i++) {
      ivec2 at = atlasTexel(ivec3(v.xy, t), grid.dims, atlasCols);
      outDensity += kernel[i] * texelFetch(meshDensity, at, 0);
      if (emissive) outSource += kernel[i] * texelFetch(meshSource, at, 0);
    }
  }
}
`;

export class MeshPass {
  /**
   * @param {object} shared uniforms: blobTex, grid, atlasCols, atlasSize
   */
  constructor(shared) {
    this.shared = shared;
    this.camera = new THREE.OrthographicCamera(-1, 1, 1, -1, 0, 1);
    // One deposit draw a σ class (k − 1 upper share, k lower share), reused frame to frame.
    this.depositScene = new THREE.Scene();
    this.deposits = [];
    // Blur x and y into scratch, z added into the density atlas (the same uniforms).
    this.blur = new ScreenPass(blurFragment, {
      grid: shared.grid, atlasCols: shared.atlasCols,
      meshDensity: { value: null }, meshSource: { value: null }, emissive: { value: false },
      axis: { value: 0 }, radius: { value: 1 }, kernel: { value: new Array(2 * MAX_BLUR_RADIUS + 1).fill(0) },
    });
    this.blurAdd = this.blur.material.clone();
    Object.assign(this.blurAdd, ADDITIVE);
    this.blurAdd.uniforms = this.blur.material.uniforms;
    this.blurCopy = this.blur.material;
  }

  #deposit(i) {
    while (this.deposits.length <= i) {
      const points = additivePoints(depositVertex, depositFragment, { ...this.shared, classOffset: { value: 0 }, sigmaLow: { value: 1 }, sigmaClass: { value: 0 }, upper: { value: false } });
      this.depositScene.add(points);
      this.deposits.push(points);
    }
    return this.deposits[i];
  }

  /**
   * Mesh classes that receive blobs: every σ class that holds a blob this wide, and one past it
   * (for a mixed range, every class from its narrowest wide blob's to its widest's).
   */
  static classes(frame, h) {
    const out = new Set();
    for (const c of frame.classes) {
      if (c.sigmaMax < DIRECT_LIMIT * h) continue;
      const [first, last] = c.mixed ? [classOf(Math.max(frame.sigmaMin, DIRECT_LIMIT * h)), classOf(c.sigmaMax)] : [c.index, c.index];
      for (let k = first; k <= last; k++) {
        out.add(k);
        out.add(k + 1);
      }
    }
    return [...out].sort((a, b) => a - b);
  }

  /**
   * The deposits into mesh class k: σ class k − 1's upper shares and class k's lower shares,
   * each {offset, count, sigmaClass, upper}; a mixed range gives both from all its blobs.
   */
  static deposits(frame, k) {
    const out = [];
    for (const c of frame.classes) {
      if (c.mixed) {
        out.push({ ...c, sigmaClass: k - 1, upper: true }, { ...c, sigmaClass: k, upper: false });
      } else if (c.index === k || c.index === k - 1) {
        out.push({ ...c, sigmaClass: c.index, upper: c.index === k - 1 });
      }
    }
    return out;
  }

  /**
   * Adds the wide blobs of `frame` ({classes, emissive}) into `target` through the
   * mesh, using `a` and `b` (atlases like `target`) as scratch. With `clock` (a stopwatch of GPU
   * passes, ms since its last call) returns the time of the deposits and of the blurs.
   */
  render(renderer, frame, h, target, a, b, clock = () => 0) {
    const times = { deposit: 0, blur: 0 };
    const u = this.blur.material.uniforms;
    u.emissive.value = frame.emissive;
    const autoClear = renderer.autoClear;
    renderer.autoClear = false;
    for (const k of MeshPass.classes(frame, h)) {
      // Deposit: σ class k − 1's upper shares and class k's lower shares.
      let used = 0;
      for (const d of MeshPass.deposits(frame, k)) {
        const points = this.#deposit(used++);
        const m = points.material.uniforms;
        m.classOffset.value = d.offset;
        m.sigmaLow.value = classSigma(d.sigmaClass);
        m.sigmaClass.value = d.sigmaClass;
        m.upper.value = d.upper;
        points.geometry.setDrawRange(0, 2 * d.count);
        points.visible = true;
      }
      for (let i = used; i < this.deposits.length; i++) this.deposits[i].visible = false;
      renderer.setRenderTarget(a);
      renderer.setClearColor(0x000000, 0);
      renderer.clear(true, false, false);
      renderer.render(this.depositScene, this.camera);
      times.deposit += clock();
      // Blur x (a → b), y (b → a), z (a → target, added).
      const kernel = blurKernel(classSigma(k), h);
      u.radius.value = (kernel.length - 1) / 2;
      u.kernel.value.fill(0);
      kernel.forEach((w, i) => { u.kernel.value[i] = w; });
      const passes = [[0, a, b, this.blurCopy], [1, b, a, this.blurCopy], [2, a, target, this.blurAdd]];
      for (const [axis, from, to, material] of passes) {
        u.axis.value = axis;
        u.meshDensity.value = from.textures[0];
        u.meshSource.value = from.textures[frame.emissive ? 1 : 0];
        this.blur.quad.material = material;
        renderer.setRenderTarget(to);
        this.blur.render(renderer);
      }
      times.blur += clock();
    }
    renderer.autoClear = autoClear;
    return times;
  }
}
