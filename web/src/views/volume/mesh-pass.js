// The particle mesh (the real-time view's path for blobs at least DIRECT_LIMIT voxels wide), as
// `frame::volume::splat` in the core does it: per mesh class k (σ_k = √2^(k − CLASS_BIAS) m), every
// blob of σ classes k − 1 and k deposits its share of mass — the split between classes k and
// k + 1 that keeps its column through the centre, w = 2σ_k²/σ² − 1 — on the eight voxels around
// its centre (cloud in cell), and the class's mesh is then blurred along x, y and z by the kernel
// of variance σ_k² − h²/6, the last pass adding into the density atlas. The work is eight voxels a
// blob plus three passes over the grid a class: it does not grow with the blobs' widths.
//
// The mesh atlas holds the two mesh classes in progress, the even and the odd, in four colour
// attachments: for emissive gas each class's density and source; otherwise each class's density
// in two layers, the slice of a voxel's lower corner and the one above it, so one point (one
// vertex a blob) deposits all eight voxels of its cloud in cell, and the first blur adds the
// layers. σ classes are deposited in ascending order, so mesh class k is whole once σ class k is
// in; it is blurred and cleared before class k + 2, of its parity, is deposited.

import * as THREE from 'three';
import { ScreenPass, sharingUniforms } from '../screen-pass.js';
import { CLASS_BIAS, DIRECT_LIMIT, MAX_BLUR_RADIUS } from '../../generated/contract.js';
import { BLOB_GLSL } from '../shaders/blob-record.js';
import { VOXEL_GRID_GLSL } from '../shaders/voxel-grid.js';
import { ATLAS_PASS_GLSL } from './glsl.js';
import { blurKernel, classOf, classSigma } from './grid.js';
import { ADDITIVE, additivePoints, setDefine } from './point-draws.js';

/**
 * The fragment outputs of a draw into `count` colour attachments, and `emit(density, source)`,
 * which writes the pair at outputs `base` and base + 1 (when there) and zero at the others.
 */
function meshOutputs(count, base) {
  const writes = Array.from({ length: count }, (_, i) => {
    const value = i === base ? 'density' : i === base + 1 ? 'source' : 'vec4(0.0)';
    return `  out${i} = ${value};`;
  });
  return [outputsOf(count), 'void emit(vec4 density, vec4 source) {', ...writes, '}'].join('\n');
}

/** The declarations of `count` fragment outputs, out0 to out{count − 1}. */
function outputsOf(count) {
  return Array.from({ length: count }, (_, i) => `layout(location = ${i}) out vec4 out${i};`).join('\n');
}

/** The mesh atlas's colour attachments: two classes (even, odd) of LAYERS · CHANNELS each. */
export const MESH_ATTACHMENTS = 4;

/** Layers and channels of a mesh class: (2, 1) for density alone, (1, 2) with a source. */
const meshLayout = (emissive) => (emissive ? { layers: 1, channels: 2 } : { layers: 2, channels: 1 });

const depositVertex = /* glsl */ `
precision highp float;
precision highp int;
${BLOB_GLSL}
${VOXEL_GRID_GLSL}
uniform Grid grid;
uniform int atlasCols;
uniform vec2 atlasSize;
uniform int classOffset;
uniform int sigmaClass;   // k: blobs of other classes are left out (a mixed range holds them all)
uniform int layers;       // 2: one vertex a blob writes both slices; 1: one vertex a slice
uniform float densityScale; // stored per unit density (κ̄h: optical depths, \`volume-layer.js\`)
flat out vec2 vFraction;  // bilinear fractions towards the next voxel in x and y
flat out vec4 vScale;     // density of each attachment (outputs 0–3), before the xy weights
flat out vec3 vAlbedo;
flat out vec3 vSource;
flat out ivec2 vCorner;

void main() {
  int perBlob = 3 - layers;
  int blob = classOffset + gl_VertexID / perBlob;
  int s = gl_VertexID % perBlob;
  vec3 c;
  float sigma, mass;
  fetchBlob(blob, c, sigma, mass, vAlbedo, vSource);
  gl_PointSize = 2.0;
  int own = clamp(int((floatBitsToUint(sigma * sigma) >> 23) & 255u) - 127 + ${CLASS_BIAS}, 0, 63);
  if (own != sigmaClass || sigma < ${DIRECT_LIMIT.toFixed(2)} * grid.h || mass <= 0.0) {
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    return;
  }
  // σ_k² = 2^(k − CLASS_BIAS): the lower share goes to mesh class k, the rest to k + 1.
  float lower = clamp(2.0 * exp2(float(own - ${CLASS_BIAS})) / (sigma * sigma) - 1.0, 0.0, 1.0);
  vec2 shares = own % 2 == 0 ? vec2(lower, 1.0 - lower) : vec2(1.0 - lower, lower);
  vec3 top = vec3(grid.dims - 1);
  vec3 g = clamp((c - grid.lo) / grid.h - 0.5, vec3(0.0), top);
  vec3 i0 = min(floor(g), max(top - 1.0, vec3(0.0)));
  vFraction = g.xy - i0.xy;
  float fz = g.z - i0.z;
  float rho = densityScale * mass / (grid.h * grid.h * grid.h);
  // Outputs: (even, odd) × (lower slice, upper slice), or (even, odd) × (density, source) of slice s.
  float wz = s == 0 ? 1.0 - fz : fz;
  vScale = layers == 2
    ? rho * vec4(shares.x * (1.0 - fz), shares.x * fz, shares.y * (1.0 - fz), shares.y * fz)
    : rho * wz * shares.xxyy;
  vCorner = atlasTexel(ivec3(ivec2(i0.xy), int(i0.z) + s), grid.dims, atlasCols);
  vec2 corner = vec2(vCorner);
  gl_Position = vec4((corner + 1.0) / atlasSize * 2.0 - 1.0, 0.0, 1.0);
}
`;

const depositFragment = /* glsl */ `
precision highp float;
precision highp int;
flat in vec2 vFraction;
flat in vec4 vScale;
flat in vec3 vAlbedo;
flat in vec3 vSource;
flat in ivec2 vCorner;
${outputsOf(MESH_ATTACHMENTS)}
void main() {
  ivec2 q = ivec2(gl_FragCoord.xy) - vCorner;
  vec2 w = mix(1.0 - vFraction, vFraction, vec2(q));
  vec4 density = w.x * w.y * vec4(1.0, vAlbedo);
#ifdef EMISSIVE
  vec4 source = w.x * w.y * vec4(vSource, 0.0);
  out0 = vScale.x * density;
  out1 = vScale.y * source;
  out2 = vScale.z * density;
  out3 = vScale.w * source;
#else
  out0 = vScale.x * density;
  out1 = vScale.y * density;
  out2 = vScale.z * density;
  out3 = vScale.w * density;
#endif
}
`;

/**
 * The blur along one axis into `outputs` attachments, the result at output `base` (and base + 1).
 * `layered` (along x or y only): the mesh is read as two layers, the upper one's voxels a slice
 * down in `meshUpper`.
 */
const blurFragment = (outputs, base, layered = false) => /* glsl */ `
${ATLAS_PASS_GLSL}
uniform Grid grid;
uniform int atlasCols;
uniform sampler2D meshDensity;
uniform sampler2D meshSource;
uniform sampler2D meshUpper;
uniform bool emissive;
uniform int axis;
uniform int radius;
uniform float kernel[${2 * MAX_BLUR_RADIUS + 1}];
${meshOutputs(outputs, base)}

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  ivec3 v;
  vec4 density = vec4(0.0);
  vec4 source = vec4(0.0);
  if (!atlasVoxel(px, grid.dims, atlasCols, v)) {
    emit(density, source);
    return;
  }
  // Taps from voxel first to last along the axis (inside the grid); along x and y they lie in
  // this slice's tile, a texel apart.
  int first = max(v[axis] - radius, 0);
  int last = min(v[axis] + radius, grid.dims[axis] - 1);
  int i = first - v[axis] + radius;
  if (axis < 2) {
    ivec2 step = axis == 0 ? ivec2(1, 0) : ivec2(0, 1);
    ivec2 at = px + step * (first - v[axis]);
    for (int t = first; t <= last; t++, i++, at += step) {
      density += kernel[i] * texelFetch(meshDensity, at, 0);
      if (emissive) source += kernel[i] * texelFetch(meshSource, at, 0);
    }${layered ? `
    // What the slice below gave to this one, held in its own tile of the upper layer.
    if (v.z > 0) {
      i = first - v[axis] + radius;
      at = atlasTexel(ivec3(v.xy, v.z - 1), grid.dims, atlasCols) + step * (first - v[axis]);
      for (int t = first; t <= last; t++, i++, at += step) density += kernel[i] * texelFetch(meshUpper, at, 0);
    }` : ''}
  } else {
    for (int t = first; t <= last; t++, i++) {
      ivec2 at = atlasTexel(ivec3(v.xy, t), grid.dims, atlasCols);
      density += kernel[i] * texelFetch(meshDensity, at, 0);
      if (emissive) source += kernel[i] * texelFetch(meshSource, at, 0);
    }
  }
  emit(density, source);
}
`;

const ZERO = new Float32Array(4);

export class MeshPass {
  /**
   * @param {object} shared uniforms: blobTex, grid, densityScale, atlasCols, atlasSize
   */
  constructor(shared) {
    this.shared = shared;
    this.camera = new THREE.OrthographicCamera(-1, 1, 1, -1, 0, 1);
    this.emissive = false;
    // One deposit draw a σ class range, reused frame to frame.
    this.depositScene = new THREE.Scene();
    this.deposits = [];
    // The blurs share one quad and one set of uniforms; each kind of pass has its material.
    this.blur = new ScreenPass(blurFragment(1, 0), {
      grid: shared.grid, atlasCols: shared.atlasCols,
      meshDensity: { value: null }, meshSource: { value: null }, meshUpper: { value: null }, emissive: { value: false },
      axis: { value: 0 }, radius: { value: 1 }, kernel: { value: new Array(2 * MAX_BLUR_RADIUS + 1).fill(0) },
    });
    this.blurs = new Map();
  }

  /** The blur's material into `outputs` attachments at output `base`, copied or `added`, reading a `layered` mesh. */
  #blurInto(outputs, base, added, layered = false) {
    const key = `${outputs}|${base}|${added}|${layered}`;
    if (!this.blurs.has(key)) {
      const material = sharingUniforms(this.blur.material);
      material.fragmentShader = blurFragment(outputs, base, layered);
      if (added) Object.assign(material, ADDITIVE);
      this.blurs.set(key, material);
    }
    return this.blurs.get(key);
  }

  #deposit(i) {
    while (this.deposits.length <= i) {
      const points = additivePoints(depositVertex, depositFragment, { ...this.shared, classOffset: { value: 0 }, sigmaClass: { value: 0 }, layers: { value: 1 } });
      this.depositScene.add(points);
      this.deposits.push(points);
    }
    setDefine(this.deposits[i].material, 'EMISSIVE', this.emissive);
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
   * The draws that deposit σ class k (into mesh classes k and k + 1): its own range, and every
   * mixed range that may hold it, with its other classes left out; each {offset, count, sigmaClass}.
   */
  static deposits(frame, k) {
    const holds = (c) => (c.mixed ? k <= classOf(c.sigmaMax) : c.index === k);
    return frame.classes.filter(holds).map((c) => ({ ...c, sigmaClass: k }));
  }

  /** Clears mesh class k's two attachments in `mesh` (from 2 · (k mod 2)). */
  static #clearClass(renderer, mesh, k) {
    renderer.setRenderTarget(mesh);
    renderer.state.buffers.color.setMask(true);
    const gl = renderer.getContext();
    for (const i of [0, 1]) gl.clearBufferfv(gl.COLOR, 2 * (k % 2) + i, ZERO);
  }

  /**
   * Runs `draw` into `mesh` with only its attachments `first` to first + count − 1 drawn (the
   * others keep what they hold), and draws into all of them again after it.
   */
  static #drawOnly(renderer, mesh, first, count, draw) {
    renderer.setRenderTarget(mesh);
    const gl = renderer.getContext();
    const all = Array.from({ length: MESH_ATTACHMENTS }, (_, i) => gl.COLOR_ATTACHMENT0 + i);
    gl.drawBuffers(all.map((a, i) => (i >= first && i < first + count ? a : gl.NONE)));
    try {
      draw();
    } finally {
      renderer.setRenderTarget(mesh);
      gl.drawBuffers(all);
    }
  }

  /**
   * Adds the wide blobs of `frame` ({classes, emissive}) into `target` through the mesh:
   * `mesh`, an atlas like `target` with MESH_ATTACHMENTS attachments, holds the even and the odd
   * mesh class; `scratch`, an atlas like `target`, takes the blur along x. With `clock` (a
   * stopwatch of GPU passes, ms since its last call) returns the time of the deposits and of the
   * blurs.
   */
  render(renderer, frame, h, target, mesh, scratch, clock = () => 0) {
    const times = { deposit: 0, blur: 0 };
    const u = this.blur.material.uniforms;
    const { layers, channels } = meshLayout(frame.emissive);
    u.emissive.value = frame.emissive;
    this.emissive = frame.emissive;
    const autoClear = renderer.autoClear;
    renderer.autoClear = false;
    renderer.setRenderTarget(mesh);
    renderer.setClearColor(0x000000, 0);
    renderer.clear(true, false, false);
    for (const k of MeshPass.classes(frame, h)) {
      // Deposit σ class k: mesh class k is then whole (class k − 1's upper shares came before).
      const draws = MeshPass.deposits(frame, k);
      draws.forEach((d, i) => {
        const points = this.#deposit(i);
        const m = points.material.uniforms;
        m.classOffset.value = d.offset;
        m.sigmaClass.value = d.sigmaClass;
        m.layers.value = layers;
        points.geometry.setDrawRange(0, (3 - layers) * d.count);
        points.visible = true;
      });
      for (let i = draws.length; i < this.deposits.length; i++) this.deposits[i].visible = false;
      if (draws.length > 0) {
        renderer.setRenderTarget(mesh);
        renderer.render(this.depositScene, this.camera);
      }
      times.deposit += clock();
      // Blur x (mesh → scratch, the layers added), y (scratch → the class's first attachments),
      // z (mesh → target, added); then the class is cleared for class k + 2.
      const kernel = blurKernel(classSigma(k), h);
      u.radius.value = (kernel.length - 1) / 2;
      u.kernel.value.fill(0);
      kernel.forEach((w, i) => { u.kernel.value[i] = w; });
      const own = 2 * (k % 2);
      const read = (atlas, at) => {
        u.meshDensity.value = atlas.textures[at];
        u.meshSource.value = atlas.textures[at + channels - 1];
        u.meshUpper.value = atlas.textures[at + 1] ?? null;
      };
      const pass = (axis, to, material) => {
        u.axis.value = axis;
        this.blur.quad.material = material;
        renderer.setRenderTarget(to);
        this.blur.render(renderer);
      };
      read(mesh, own);
      pass(0, scratch, this.#blurInto(channels, 0, false, layers === 2));
      read(scratch, 0);
      MeshPass.#drawOnly(renderer, mesh, own, channels, () => pass(1, mesh, this.#blurInto(MESH_ATTACHMENTS, own, false)));
      read(mesh, own);
      pass(2, target, this.#blurInto(channels, 0, true));
      MeshPass.#clearClass(renderer, mesh, k);
      times.blur += clock();
    }
    renderer.autoClear = autoClear;
    return times;
  }
}
