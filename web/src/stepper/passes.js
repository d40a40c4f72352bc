// The GPU stepper's passes, each a pure per-texel map (no atomics, so WebGL2 fragment shaders
// carry them): the step of paper §4 for every slot, the writing of newborn and emptied slots,
// the packing of the state into the views' blob texture (in the order `binning.js` sorts it
// into), and the reduction to the gas's bounds.

import * as THREE from 'three';
import { BLOB_FLOATS, BLOBS_PER_ROW, FOOTPRINT } from '../generated/contract.js';
import { FLOW_SAMPLE_GLSL } from '../flow-gpu/sample-glsl.js';
import { WIND_GLSL, WIND_PARTS_GLSL } from './wind-glsl.js';

const SCREEN_VERTEX = /* glsl */ `
in vec3 position;
void main() { gl_Position = vec4(position.xy, 0.0, 1.0); }
`;

/** A pass drawing every texel of its target with `fragmentShader` (GLSL 3). */
export class ScreenPass {
  constructor(fragmentShader, uniforms) {
    this.material = new THREE.RawShaderMaterial({
      glslVersion: THREE.GLSL3,
      vertexShader: SCREEN_VERTEX,
      fragmentShader: `precision highp float;\nprecision highp int;\n${fragmentShader}`,
      uniforms,
      depthTest: false,
      depthWrite: false,
    });
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.Float32BufferAttribute([-1, -1, 0, 3, -1, 0, -1, 3, 0], 3));
    this.mesh = new THREE.Mesh(geometry, this.material);
    this.mesh.frustumCulled = false;
    this.scene = new THREE.Scene().add(this.mesh);
    this.camera = new THREE.OrthographicCamera(-1, 1, 1, -1, 0, 1);
  }

  /** Draws into `target` (all of it). */
  draw(renderer, target) {
    renderer.setRenderTarget(target);
    renderer.render(this.scene, this.camera);
  }

  dispose() {
    this.mesh.geometry.dispose();
    this.material.dispose();
  }
}

/**
 * One step (Eq. 14 by RK2's midpoint rule or Euler, through the wind at the step's start and
 * middle, plus the blob's own velocity v0·exp(−age/τ)); σ² += κ·dt (Eq. 15); m ← m·exp(−α·dt)
 * (Eq. 16). Empty slots (mass 0) stay empty. With SOLIDS the wind goes round the solids and a
 * blob the step carried into one is put back just outside; with CARRIED each blob's carried
 * offsets (attachments 2 and 3) move against the large-scale wind, o ← o − u_l dt, and a phase
 * that reset in the step (the late table's header) starts again at −u_l·τ
 * (`gas::blob_gas` in the core).
 */
export class StepPass extends ScreenPass {
  constructor() {
    super(/* glsl */ `
#ifdef FLOW
${FLOW_SAMPLE_GLSL}
#endif
${WIND_GLSL}
${WIND_PARTS_GLSL}
uniform highp sampler2D centres;
uniform highp sampler2D masses;
uniform highp sampler2D ownVelocities;
uniform highp sampler2D offsetsA;
uniform highp sampler2D offsetsB;
uniform float dt;
uniform float diffusion;
uniform float alpha;
uniform bool rk2;
layout(location = 0) out vec4 outCentre;
layout(location = 1) out vec4 outMass;
#ifdef CARRIED
layout(location = 2) out vec4 outOffsetA;
layout(location = 3) out vec4 outOffsetB;
#endif
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 a = texelFetch(centres, p, 0);
  vec4 b = texelFetch(masses, p, 0);
  vec3 oa = vec3(0.0);
  vec3 ob = vec3(0.0);
#ifdef CARRIED
  oa = texelFetch(offsetsA, p, 0).xyz;
  ob = texelFetch(offsetsB, p, 0).xyz;
#endif
  if (b.x <= 0.0) {
    outCentre = a;
    outMass = vec4(0.0);
#ifdef CARRIED
    outOffsetA = vec4(oa, 0.0);
    outOffsetB = vec4(ob, 0.0);
#endif
    return;
  }
  vec3 x = a.xyz;
  float tau = b.z;
  vec3 v = texelFetch(ownVelocities, p, 0).xyz * exp(-b.y / tau);
#if defined(SOLIDS) || defined(CARRIED)
  vec3 l;
  vec3 s;
  vec3 moved;
  // How far the step's start surely lies from every solid: a shorter move cannot end inside one.
  float clear;
  if (rk2) {
    windPartsAndClearance(0, x, oa, ob, l, s, clear);
    vec3 half_ = l * (-0.5 * dt);
    vec3 xm = x + (l + s + v) * (0.5 * dt);
    vec3 lm;
    vec3 sm;
    windParts(1, xm, oa + half_, ob + half_, lm, sm);
    x += (lm + sm + v * exp(-0.5 * dt / tau)) * dt;
    moved = lm * -dt;
  } else {
    windPartsAndClearance(0, x, oa, ob, l, s, clear);
    x += (l + s + v) * dt;
    moved = l * -dt;
  }
#ifdef SOLIDS
  vec3 step_ = x - a.xyz;
  if (!(clear > 0.0 && dot(step_, step_) < clear * clear)) x = pushOut(0, x);
#endif
#ifdef CARRIED
  oa += moved;
  ob += moved;
  int late = rk2 ? 1 : 0;
  vec4 resets = tableTexel(late, 7);
  if (resets.z >= 0.0 || resets.w >= 0.0) {
    vec3 lr;
    vec3 sr;
    windParts(late, x, vec3(0.0), vec3(0.0), lr, sr);
    if (resets.z >= 0.0) oa = lr * -resets.z;
    if (resets.w >= 0.0) ob = lr * -resets.w;
  }
  outOffsetA = vec4(oa, 0.0);
  outOffsetB = vec4(ob, 0.0);
#endif
#else
  if (rk2) {
    vec3 xm = x + (wind(0, x) + v) * (0.5 * dt);
    x += (wind(1, xm) + v * exp(-0.5 * dt / tau)) * dt;
  } else {
    x += (wind(0, x) + v) * dt;
  }
#endif
  outCentre = vec4(x, a.w + diffusion * dt);
  outMass = vec4(b.x * exp(-alpha * dt), b.y + dt, tau, b.w);
}`, {
      windTable: { value: null },
      lattice: { value: null },
      potentialLattice: { value: null },
      solidGrid: { value: null },
      solidGridWidth: { value: 1 },
      latticeSize: { value: new THREE.Vector4(1, 1, 1, 1) },
      latticeWidth: { value: 1 },
      centres: { value: null },
      masses: { value: null },
      ownVelocities: { value: null },
      offsetsA: { value: null },
      offsetsB: { value: null },
      dt: { value: 0 },
      diffusion: { value: 0 },
      alpha: { value: 0 },
      rk2: { value: true },
      flowU: { value: null },
      flowV: { value: null },
      flowW: { value: null },
      flowUL: { value: [1, 1, 1, 1] },
      flowVL: { value: [1, 1, 1, 1] },
      flowWL: { value: [1, 1, 1, 1] },
      flowOrigin: { value: new THREE.Vector3() },
      flowInvH: { value: 1 },
      flowLo: { value: new THREE.Vector3() },
      flowHi: { value: new THREE.Vector3() },
    });
  }

  /**
   * Compiles the pass for solids, carried offsets and a flow's u_g, or without (recompiled
   * only on a change).
   */
  configure({ solids, carried, flow = false }) {
    const key = `${solids}${carried}${flow}`;
    if (this.key === key) return;
    this.key = key;
    const defines = {};
    if (solids) defines.SOLIDS = '';
    if (carried) defines.CARRIED = '';
    if (flow) defines.FLOW = '';
    this.material.defines = defines;
    this.material.needsUpdate = true;
  }
}

const WRITE_VERTEX = /* glsl */ `
precision highp float;
in float slot;
in vec4 a;
in vec4 b;
in vec4 c0;
in vec4 c1;
in vec4 c2;
in vec4 d0;
in vec4 d1;
uniform vec2 size;
out vec4 va;
out vec4 vb;
out vec4 vc0;
out vec4 vc1;
out vec4 vc2;
out vec4 vd0;
out vec4 vd1;
void main() {
  float column = mod(slot, ${BLOBS_PER_ROW}.0);
  float row = floor(slot / ${BLOBS_PER_ROW}.0);
  gl_Position = vec4((column + 0.5) / size.x * 2.0 - 1.0, (row + 0.5) / size.y * 2.0 - 1.0, 0.0, 1.0);
  gl_PointSize = 1.0;
  va = a; vb = b; vc0 = c0; vc1 = c1; vc2 = c2; vd0 = d0; vd1 = d1;
}`;

/** The parts of a blob record (`frame::gpu_steps`), one vec4 attribute each. */
const RECORD_PARTS = ['a', 'b', 'c0', 'c1', 'c2', 'd0', 'd1'];

/**
 * Writes blob records into their slots: one point a slot, each record's moving part into the
 * moving state (with carried offsets, when the state has them) and (for births) its fixed part
 * into the fixed state. An emptied slot is a record of zeros.
 */
export class WritePass {
  constructor() {
    this.geometry = new THREE.BufferGeometry();
    this.capacity = 0;
    const material = (outputs) => new THREE.RawShaderMaterial({
      glslVersion: THREE.GLSL3,
      vertexShader: WRITE_VERTEX,
      fragmentShader: `precision highp float;\nin vec4 va;\nin vec4 vb;\nin vec4 vc0;\nin vec4 vc1;\nin vec4 vc2;\nin vec4 vd0;\nin vec4 vd1;\n${outputs}`,
      uniforms: { size: { value: new THREE.Vector2(1, 1) } },
      depthTest: false,
      depthWrite: false,
    });
    this.movingMaterial = material(`layout(location = 0) out vec4 o0;
layout(location = 1) out vec4 o1;
void main() { o0 = va; o1 = vb; }`);
    this.carriedMaterial = material(`layout(location = 0) out vec4 o0;
layout(location = 1) out vec4 o1;
layout(location = 2) out vec4 o2;
layout(location = 3) out vec4 o3;
void main() { o0 = va; o1 = vb; o2 = vd0; o3 = vd1; }`);
    this.fixedMaterial = material(`layout(location = 0) out vec4 o0;
layout(location = 1) out vec4 o1;
layout(location = 2) out vec4 o2;
void main() { o0 = vc0; o1 = vc1; o2 = vc2; }`);
    this.points = new THREE.Points(this.geometry, this.movingMaterial);
    this.points.frustumCulled = false;
    this.scene = new THREE.Scene().add(this.points);
    this.camera = new THREE.OrthographicCamera(-1, 1, 1, -1, 0, 1);
  }

  /** Room for `n` records (grown by half again when short). */
  #reserve(n) {
    if (n <= this.capacity) return;
    this.capacity = Math.max(n, Math.ceil(1.5 * this.capacity), 1024);
    this.geometry.dispose();
    this.geometry.setAttribute('slot', new THREE.BufferAttribute(new Float32Array(this.capacity), 1));
    for (const name of RECORD_PARTS) {
      this.geometry.setAttribute(name, new THREE.BufferAttribute(new Float32Array(4 * this.capacity), 4));
    }
  }

  /**
   * Writes `records` (BLOB_FLOATS each: see `frame::gpu_steps`) into `slots`, then empties
   * `emptied`, in `state` (its moving state `into`); with `newborns` (a NewbornPass) the
   * records' moving parts are written by it, their blobs advanced on the GPU.
   */
  write(renderer, state, into, records, slots, emptied, newborns = null) {
    const born = slots.length;
    const n = born + emptied.length;
    if (n === 0) return;
    this.#reserve(n);
    const g = this.geometry.attributes;
    const parts = RECORD_PARTS.map((name) => g[name].array);
    for (let i = 0; i < born; i++) {
      g.slot.array[i] = slots[i];
      for (let k = 0; k < parts.length; k++) {
        parts[k].set(records.subarray(BLOB_FLOATS * i + 4 * k, BLOB_FLOATS * i + 4 * k + 4), 4 * i);
      }
    }
    for (let j = 0; j < emptied.length; j++) {
      g.slot.array[born + j] = emptied[j];
      for (const k of [0, 1, 5, 6]) parts[k].fill(0, 4 * (born + j), 4 * (born + j + 1));
    }
    for (const name of ['slot', ...RECORD_PARTS]) {
      g[name].clearUpdateRanges();
      g[name].addUpdateRange(0, g[name].itemSize * n);
      g[name].needsUpdate = true;
    }
    const size = new THREE.Vector2(BLOBS_PER_ROW, state.rows);
    const autoClear = renderer.autoClear;
    renderer.autoClear = false;
    this.movingMaterial.uniforms.size.value = size;
    this.carriedMaterial.uniforms.size.value = size;
    this.fixedMaterial.uniforms.size.value = size;
    this.points.material = state.carried ? this.carriedMaterial : this.movingMaterial;
    renderer.setRenderTarget(into);
    if (newborns && born > 0) {
      const material = newborns.configured();
      material.uniforms.size.value = size;
      this.points.material = material;
      this.geometry.setDrawRange(0, born);
      renderer.render(this.scene, this.camera);
      this.points.material = state.carried ? this.carriedMaterial : this.movingMaterial;
      this.geometry.setDrawRange(born, n - born);
    } else {
      this.geometry.setDrawRange(0, n);
    }
    renderer.render(this.scene, this.camera);
    if (born > 0) {
      this.points.material = this.fixedMaterial;
      this.geometry.setDrawRange(0, born);
      renderer.setRenderTarget(state.fixed);
      renderer.render(this.scene, this.camera);
    }
    renderer.autoClear = autoClear;
  }

  dispose() {
    this.geometry.dispose();
    this.movingMaterial.dispose();
    this.carriedMaterial.dispose();
    this.fixedMaterial.dispose();
  }
}

/**
 * The newborns of a step the GPU advances itself (while it steps a flow the core does not see,
 * `frame::gpu_steps`): each record's blob, at its birth place, moves by its age through the
 * late wind table's wind (the flow's u_g in it) and its own velocity v0, in one Euler step, and
 * is put back outside a solid; with CARRIED its offsets are made −u_l·τ from the record's phase
 * ages τ (vec4 5), u_l the large-scale wind there (the core's `gas::blob_gas` emit). Drawn over
 * the births' slots in place of their moving part; it reads the step pass's uniforms (the same
 * objects) and compiles with its defines.
 */
export class NewbornPass {
  constructor(stepPass) {
    this.stepPass = stepPass;
    this.material = new THREE.RawShaderMaterial({
      glslVersion: THREE.GLSL3,
      vertexShader: WRITE_VERTEX,
      fragmentShader: /* glsl */ `precision highp float;
precision highp int;
#ifdef FLOW
${FLOW_SAMPLE_GLSL}
#endif
${WIND_GLSL}
${WIND_PARTS_GLSL}
uniform bool rk2;
in vec4 va;
in vec4 vb;
in vec4 vc0;
in vec4 vc1;
in vec4 vc2;
in vec4 vd0;
in vec4 vd1;
layout(location = 0) out vec4 o0;
layout(location = 1) out vec4 o1;
#ifdef CARRIED
layout(location = 2) out vec4 o2;
layout(location = 3) out vec4 o3;
#endif
void main() {
  int late = rk2 ? 1 : 0;
  vec3 x = va.xyz;
  vec3 oa = vec3(0.0);
  vec3 ob = vec3(0.0);
  vec3 l;
  vec3 s;
#ifdef CARRIED
  windParts(late, x, oa, ob, l, s);
  oa = l * -vd0.x;
  ob = l * -vd0.y;
#endif
  windParts(late, x, oa, ob, l, s);
  x += (l + s + vc0.xyz) * vb.y;
#ifdef SOLIDS
  x = pushOut(late, x);
#endif
  o0 = vec4(x, va.w);
  o1 = vb;
#ifdef CARRIED
  o2 = vec4(oa, 0.0);
  o3 = vec4(ob, 0.0);
#endif
}`,
      uniforms: { ...stepPass.material.uniforms, size: { value: new THREE.Vector2(1, 1) } },
      depthTest: false,
      depthWrite: false,
    });
  }

  /** The material for the births, compiled as the step pass is now. */
  configured() {
    if (this.key !== this.stepPass.key) {
      this.key = this.stepPass.key;
      this.material.defines = { ...this.stepPass.material.defines };
      this.material.needsUpdate = true;
    }
    return this.material;
  }

  dispose() {
    this.material.dispose();
  }
}

/**
 * The state packed as the views read a frame (`frame::packed`: eight 32-bit words a blob, two
 * RGBA32UI texels): centre, σ, mass, albedo (the medium's where the blob has none) and the
 * emitted source (1 − Ω)Q as halves, blob after blob in the sorted order (`binning.js`: at each
 * place the number of its slot); the places past the `count` sorted pack as zeros.
 */
export class PackPass extends ScreenPass {
  constructor() {
    super(/* glsl */ `
uniform highp sampler2D centres;
uniform highp sampler2D masses;
uniform highp sampler2D albedos;
uniform highp sampler2D emissions;
uniform highp sampler2D order;
uniform int count;
uniform vec3 mediumAlbedo;
layout(location = 0) out highp uvec4 words;
void main() {
  ivec2 t = ivec2(gl_FragCoord.xy);
  int place = t.y * ${BLOBS_PER_ROW} + t.x / 2;
  if (place >= count) {
    words = uvec4(0u);
    return;
  }
  int slot = int(texelFetch(order, ivec2(place % ${BLOBS_PER_ROW}, place / ${BLOBS_PER_ROW}), 0).x);
  ivec2 p = ivec2(slot % ${BLOBS_PER_ROW}, slot / ${BLOBS_PER_ROW});
  vec4 a = texelFetch(centres, p, 0);
  if (t.x % 2 == 0) {
    words = uvec4(floatBitsToUint(a.xyz), floatBitsToUint(sqrt(max(a.w, 0.0))));
    return;
  }
  float mass = texelFetch(masses, p, 0).x;
  vec3 albedo = texelFetch(albedos, p, 0).xyz;
  if (albedo.r < 0.0) albedo = mediumAlbedo;
  vec3 source = (1.0 - albedo) * texelFetch(emissions, p, 0).xyz;
  words = uvec4(floatBitsToUint(max(mass, 0.0)), packHalf2x16(albedo.rg), packHalf2x16(vec2(albedo.b, source.r)), packHalf2x16(source.gb));
}`, {
      centres: { value: null },
      masses: { value: null },
      albedos: { value: null },
      emissions: { value: null },
      order: { value: null },
      count: { value: 0 },
      mediumAlbedo: { value: new THREE.Vector3(1, 1, 1) },
    });
    this.target = null;
  }

  /**
   * Packs the `count` blobs of `state` that `order` puts first (the slots' numbers, place by
   * place) into its blob texture (sized to the state); returns the texture.
   */
  pack(renderer, state, order, count, mediumAlbedo) {
    if (!this.target || this.target.height !== state.rows) {
      this.target?.dispose();
      this.target = new THREE.WebGLRenderTarget(2 * BLOBS_PER_ROW, state.rows, {
        type: THREE.UnsignedIntType,
        format: THREE.RGBAIntegerFormat,
        internalFormat: 'RGBA32UI',
        minFilter: THREE.NearestFilter,
        magFilter: THREE.NearestFilter,
        depthBuffer: false,
        generateMipmaps: false,
      });
    }
    const u = this.material.uniforms;
    u.centres.value = state.now.textures[0];
    u.masses.value = state.now.textures[1];
    u.albedos.value = state.fixed.textures[1];
    u.emissions.value = state.fixed.textures[2];
    u.order.value = order;
    u.count.value = count;
    u.mediumAlbedo.value.fromArray(mediumAlbedo);
    this.draw(renderer, this.target);
    return this.target.texture;
  }

  dispose() {
    super.dispose();
    this.target?.dispose();
  }
}

/**
 * The gas's bounds, reduced on the GPU: every blob with mass's centre ± FOOTPRINT σ, the least
 * and the greatest per axis, halving the state's texels a pass down to one.
 */
export class BoundsPass {
  constructor() {
    const reduce = (first) => new ScreenPass(/* glsl */ `
uniform highp sampler2D lows;
uniform highp sampler2D highs;
uniform highp sampler2D masses;
uniform ivec2 from;
layout(location = 0) out vec4 low;
layout(location = 1) out vec4 high;
void main() {
  ivec2 p = 2 * ivec2(gl_FragCoord.xy);
  vec3 lo = vec3(3.0e38);
  vec3 hi = vec3(-3.0e38);
  for (int k = 0; k < 4; k++) {
    ivec2 q = p + ivec2(k & 1, k >> 1);
    if (q.x >= from.x || q.y >= from.y) continue;
    ${first ? `vec4 c = texelFetch(lows, q, 0);
    if (texelFetch(masses, q, 0).x <= 0.0) continue;
    float reach = ${FOOTPRINT.toFixed(1)} * sqrt(max(c.w, 0.0));
    lo = min(lo, c.xyz - reach);
    hi = max(hi, c.xyz + reach);` : `lo = min(lo, texelFetch(lows, q, 0).xyz);
    hi = max(hi, texelFetch(highs, q, 0).xyz);`}
  }
  low = vec4(lo, 0.0);
  high = vec4(hi, 0.0);
}`, { lows: { value: null }, highs: { value: null }, masses: { value: null }, from: { value: new THREE.Vector2() } });
    this.first = reduce(true);
    this.rest = reduce(false);
    this.levels = [];
    /** The last bounds read back: [lo xyz, hi xyz] (m), or null. */
    this.bounds = null;
  }

  #levelsFor(width, height) {
    const sizes = [];
    for (let w = width, h = height; w > 1 || h > 1;) {
      w = Math.ceil(w / 2);
      h = Math.ceil(h / 2);
      sizes.push([w, h]);
    }
    const key = sizes.map((s) => s.join('x')).join();
    if (this.levelsKey !== key) {
      for (const t of this.levels) t.dispose();
      this.levels = sizes.map(([w, h]) => new THREE.WebGLRenderTarget(w, h, {
        count: 2, type: THREE.FloatType, minFilter: THREE.NearestFilter, magFilter: THREE.NearestFilter, depthBuffer: false,
      }));
      this.levelsKey = key;
    }
    return this.levels;
  }

  /**
   * Reduces `state` to its bounds on the GPU and reads them back (`bounds`: [lo xyz, hi xyz], m,
   * or null without blobs): a wait for the GPU to finish what it was given before.
   */
  update(renderer, state) {
    const levels = this.#levelsFor(BLOBS_PER_ROW, state.rows);
    let from = [BLOBS_PER_ROW, state.rows];
    let source = state.now;
    levels.forEach((target, i) => {
      const pass = i === 0 ? this.first : this.rest;
      const u = pass.material.uniforms;
      u.lows.value = source.textures[0];
      u.highs.value = source.textures[i === 0 ? 0 : 1];
      u.masses.value = state.now.textures[1];
      u.from.value.set(from[0], from[1]);
      pass.draw(renderer, target);
      from = [target.width, target.height];
      source = target;
    });
    const last = levels.at(-1);
    const lo = new Float32Array(4);
    const hi = new Float32Array(4);
    renderer.readRenderTargetPixels(last, 0, 0, 1, 1, lo, undefined, 0);
    renderer.readRenderTargetPixels(last, 0, 0, 1, 1, hi, undefined, 1);
    this.bounds = lo[0] <= hi[0] ? [lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]] : null;
  }

  dispose() {
    this.first.dispose();
    this.rest.dispose();
    for (const t of this.levels) t.dispose();
  }
}
