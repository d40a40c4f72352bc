// The GPU stepper's blobs sorted by σ class on the GPU, as the core sorts a worker's frame
// (`frame::packed`), so that each pass of the real-time view draws each blob once rather than
// every slot once per class. A counting sort in fragment passes (no atomics, no scatter, no
// read-back of the state): the bins of each block of BLOCK slots (`class-bins.js`), packed in
// one texel; the bins' counts per block; their running sums along each row, down each chunk of
// CHUNK rows and over the chunks; the bins' totals, which come back (BINS floats: the views'
// draws need them), and from them each bin's first place. Then each place of the sorted order
// finds its slot: its bin from the first places, then by bisection over the running sums the
// chunk, the row and the block that hold that bin's blob of its rank, and the slot in the
// block. The order is the slots' own within a bin (a stable sort): the same state sorts the
// same way.
//
// Textures of bin counts hold four texels an entry, texel g the bins 4g to 4g + 3.

import * as THREE from 'three';
import { BLOBS_PER_ROW } from '../generated/contract.js';
import { BIN_GLSL, BINS } from './class-bins.js';
import { ScreenPass } from './passes.js';

/** Slots a block: their bins fit one texel (four bits each and a bit for a blob). */
const BLOCK = 16;
/** Blocks a row of the state. */
const BLOCKS = BLOBS_PER_ROW / BLOCK;
/** Rows a chunk: the rows' running sums restart at each chunk. */
const CHUNK = 32;
/** Texels a set of BINS counts. */
const GROUPS = BINS / 4;

/** A render target of `width × height` texels: RGBA32F, or R32F (`red`), or RGBA32UI (`uint`). */
function target(width, height, { red = false, uint = false } = {}) {
  const t = new THREE.WebGLRenderTarget(width, height, {
    type: uint ? THREE.UnsignedIntType : THREE.FloatType,
    format: uint ? THREE.RGBAIntegerFormat : red ? THREE.RedFormat : THREE.RGBAFormat,
    minFilter: THREE.NearestFilter,
    magFilter: THREE.NearestFilter,
    depthBuffer: false,
    generateMipmaps: false,
  });
  if (uint) t.texture.internalFormat = 'RGBA32UI';
  return t;
}

/**
 * GLSL: a block's bins in one texel (`keys`): the bins of slots 0–7 and 8–15 as four bits each
 * (x, y), and in z a bit for each slot that holds a blob; `binAt(key, t)`, the bin of slot t of
 * the block, −1 for an empty one.
 */
const KEY_GLSL = /* glsl */ `
int binAt(uvec4 key, int t) {
  if ((key.z & (1u << t)) == 0u) return -1;
  return int(((t < 8 ? key.x : key.y) >> (4 * (t % 8))) & 15u);
}
`;

/** Per block, the bins of its slots (slots from `slots` on are empty). */
class KeyPass extends ScreenPass {
  constructor() {
    super(/* glsl */ `
${BIN_GLSL}
uniform highp sampler2D centres;
uniform highp sampler2D masses;
uniform int slots;
layout(location = 0) out highp uvec4 key;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  key = uvec4(0u);
  for (int t = 0; t < ${BLOCK}; t++) {
    ivec2 q = ivec2(${BLOCK} * p.x + t, p.y);
    int bin = q.y * ${BLOBS_PER_ROW} + q.x < slots ? binOf(texelFetch(centres, q, 0), texelFetch(masses, q, 0).x) : -1;
    if (bin < 0) continue;
    key.z |= 1u << t;
    if (t < 8) key.x |= uint(bin) << (4 * t);
    else key.y |= uint(bin) << (4 * (t - 8));
  }
}`, {
      centres: { value: null },
      masses: { value: null },
      slots: { value: 0 },
      firstClass: { value: 0 },
      windowClasses: { value: 0 },
      subBits: { value: 0 },
    });
  }
}

/** Per block, how many of its slots each bin holds. */
class CountPass extends ScreenPass {
  constructor() {
    super(/* glsl */ `
${KEY_GLSL}
uniform highp usampler2D keys;
layout(location = 0) out vec4 counts;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  uvec4 key = texelFetch(keys, ivec2(p.x / 4, p.y), 0);
  ivec4 bins = ivec4(4 * (p.x % 4)) + ivec4(0, 1, 2, 3);
  counts = vec4(0.0);
  for (int t = 0; t < ${BLOCK}; t++) counts += vec4(equal(ivec4(binAt(key, t)), bins));
}`, { keys: { value: null } });
  }
}

/** Per block, how many blobs each bin holds in the blocks before it in its row. */
class RowSumPass extends ScreenPass {
  constructor() {
    super(/* glsl */ `
uniform highp sampler2D counts;
layout(location = 0) out vec4 before;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  before = vec4(0.0);
  for (int x = p.x % 4; x < p.x; x += 4) before += texelFetch(counts, ivec2(x, p.y), 0);
}`, { counts: { value: null } });
  }
}

/** GLSL: `vec4 rowTotal(int g, int y)`, the blobs of the bins of texel g in row y. */
const ROW_TOTAL_GLSL = /* glsl */ `
uniform highp sampler2D counts;
uniform highp sampler2D before;
vec4 rowTotal(int g, int y) {
  ivec2 last = ivec2(${4 * (BLOCKS - 1)} + g, y);
  return texelFetch(before, last, 0) + texelFetch(counts, last, 0);
}
`;

/** Per row, how many blobs each bin holds in the rows before it in its chunk of CHUNK rows. */
class ChunkSumPass extends ScreenPass {
  constructor() {
    super(/* glsl */ `
${ROW_TOTAL_GLSL}
layout(location = 0) out vec4 above;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  above = vec4(0.0);
  for (int y = p.y - p.y % ${CHUNK}; y < p.y; y++) above += rowTotal(p.x, y);
}`, { counts: { value: null }, before: { value: null } });
  }
}

/** GLSL: `vec4 chunkTotal(int g, int c)`, the blobs of the bins of texel g in chunk c. */
const CHUNK_TOTAL_GLSL = /* glsl */ `
${ROW_TOTAL_GLSL}
uniform highp sampler2D rowsAbove;
uniform int rows;
vec4 chunkTotal(int g, int c) {
  int last = min(${CHUNK} * c + ${CHUNK - 1}, rows - 1);
  return texelFetch(rowsAbove, ivec2(g, last), 0) + rowTotal(g, last);
}
`;

/** Per chunk, how many blobs each bin holds in the chunks before it. */
class ChunksPass extends ScreenPass {
  constructor() {
    super(/* glsl */ `
${CHUNK_TOTAL_GLSL}
layout(location = 0) out vec4 earlier;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  earlier = vec4(0.0);
  for (int c = 0; c < p.y; c++) earlier += chunkTotal(p.x, c);
}`, { counts: { value: null }, before: { value: null }, rowsAbove: { value: null }, rows: { value: 1 } });
  }
}

/** The blobs each bin holds: the last chunk's running sums and the chunk's own. */
class TotalsPass extends ScreenPass {
  constructor() {
    super(/* glsl */ `
${CHUNK_TOTAL_GLSL}
uniform highp sampler2D chunksBefore;
uniform int chunks;
layout(location = 0) out vec4 totals;
void main() {
  int g = int(gl_FragCoord.x);
  totals = texelFetch(chunksBefore, ivec2(g, chunks - 1), 0) + chunkTotal(g, chunks - 1);
}`, {
      counts: { value: null }, before: { value: null }, rowsAbove: { value: null }, rows: { value: 1 },
      chunksBefore: { value: null }, chunks: { value: 1 },
    });
  }
}

/**
 * Each place of the sorted order (one channel, BLOBS_PER_ROW places a row, the first `count`
 * filled) gets the number of its slot: its bin is the last whose first place it has reached,
 * and its rank in the bin is found in the chunk, the row and the block whose running sums hold
 * it (bisections: the last entry whose running sum is at most the rank), then among the
 * block's slots.
 */
class GatherPass extends ScreenPass {
  constructor() {
    super(/* glsl */ `
${KEY_GLSL}
uniform highp usampler2D keys;
uniform highp sampler2D before;
uniform highp sampler2D rowsAbove;
uniform highp sampler2D chunksBefore;
uniform float firstPlace[${BINS}];
uniform float count;
uniform int rows;
uniform int chunks;
layout(location = 0) out vec4 order;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  float place = float(p.y * ${BLOBS_PER_ROW} + p.x);
  if (place >= count) {
    order = vec4(-1.0);
    return;
  }
  int bin = 0;
  for (int b = 1; b < ${BINS}; b++) if (firstPlace[b] <= place) bin = b;
  int g = bin / 4;
  int c = bin % 4;
  float rank = place - firstPlace[bin];
  // The chunk: the last whose running sum is at most the rank.
  int chunk = 0;
  for (int hi = chunks - 1; chunk < hi;) {
    int mid = (chunk + hi + 1) / 2;
    if (texelFetch(chunksBefore, ivec2(g, mid), 0)[c] <= rank) chunk = mid;
    else hi = mid - 1;
  }
  rank -= texelFetch(chunksBefore, ivec2(g, chunk), 0)[c];
  // The row of that chunk, likewise.
  int y = ${CHUNK} * chunk;
  for (int hi = min(y + ${CHUNK - 1}, rows - 1); y < hi;) {
    int mid = (y + hi + 1) / 2;
    if (texelFetch(rowsAbove, ivec2(g, mid), 0)[c] <= rank) y = mid;
    else hi = mid - 1;
  }
  rank -= texelFetch(rowsAbove, ivec2(g, y), 0)[c];
  // The block of that row, likewise.
  int block = 0;
  for (int hi = ${BLOCKS - 1}; block < hi;) {
    int mid = (block + hi + 1) / 2;
    if (texelFetch(before, ivec2(4 * mid + g, y), 0)[c] <= rank) block = mid;
    else hi = mid - 1;
  }
  rank -= texelFetch(before, ivec2(4 * block + g, y), 0)[c];
  // The slot of that block: the bin's blob of that rank among its slots.
  uvec4 key = texelFetch(keys, ivec2(block, y), 0);
  int slot = 0;
  for (int t = 0; t < ${BLOCK}; t++) {
    if (binAt(key, t) != bin) continue;
    if (rank < 0.5) {
      slot = t;
      break;
    }
    rank -= 1.0;
  }
  order = vec4(float(y * ${BLOBS_PER_ROW} + ${BLOCK} * block + slot));
}`, {
      keys: { value: null }, before: { value: null }, rowsAbove: { value: null }, chunksBefore: { value: null },
      firstPlace: { value: new Array(BINS).fill(0) }, count: { value: 0 }, rows: { value: 1 }, chunks: { value: 1 },
    });
  }
}

export class Binning {
  constructor() {
    this.keyPass = new KeyPass();
    this.countPass = new CountPass();
    this.rowSumPass = new RowSumPass();
    this.chunkSumPass = new ChunkSumPass();
    this.chunksPass = new ChunksPass();
    this.totalsPass = new TotalsPass();
    this.gatherPass = new GatherPass();
    this.rows = 0;
    this.targets = null;
    this.counts = new Float32Array(BINS);
  }

  /** The targets for a state of `rows` rows (made again when that changes). */
  #targetsFor(rows) {
    if (this.rows === rows) return this.targets;
    this.#disposeTargets();
    this.rows = rows;
    this.targets = {
      keys: target(BLOCKS, rows, { uint: true }),
      counts: target(GROUPS * BLOCKS, rows),
      before: target(GROUPS * BLOCKS, rows),
      rowsAbove: target(GROUPS, rows),
      chunksBefore: target(GROUPS, Math.ceil(rows / CHUNK)),
      totals: target(GROUPS, 1),
      /** The sorted order: the number of the slot at each place. */
      order: target(BLOBS_PER_ROW, rows, { red: true }),
    };
    return this.targets;
  }

  /**
   * Sorts the first `slots` slots of `state` (a StepperState) into the bins of `layout`
   * (`binLayout`): the order (`order`, a texture of the slot at each place, BLOBS_PER_ROW places
   * a row) and the blobs in each bin (`counts`, BINS numbers, read back: a wait for the GPU to
   * finish the passes before, which the frame's drawing waits for anyway). `clock` (a stopwatch,
   * called with each pass's name once it is drawn) may time the passes.
   */
  sort(renderer, state, slots, layout, clock = () => {}) {
    const t = this.#targetsFor(state.rows);
    const chunks = Math.ceil(state.rows / CHUNK);
    let u = this.keyPass.material.uniforms;
    u.centres.value = state.now.textures[0];
    u.masses.value = state.now.textures[1];
    u.slots.value = slots;
    u.firstClass.value = layout.first;
    u.windowClasses.value = layout.classes;
    u.subBits.value = layout.subBits;
    this.keyPass.draw(renderer, t.keys);
    clock('keys');
    this.countPass.material.uniforms.keys.value = t.keys.texture;
    this.countPass.draw(renderer, t.counts);
    this.rowSumPass.material.uniforms.counts.value = t.counts.texture;
    this.rowSumPass.draw(renderer, t.before);
    for (const pass of [this.chunkSumPass, this.chunksPass, this.totalsPass]) {
      u = pass.material.uniforms;
      u.counts.value = t.counts.texture;
      u.before.value = t.before.texture;
      if (u.rowsAbove) u.rowsAbove.value = t.rowsAbove.texture;
      if (u.rows) u.rows.value = state.rows;
      if (u.chunksBefore) u.chunksBefore.value = t.chunksBefore.texture;
      if (u.chunks) u.chunks.value = chunks;
    }
    this.chunkSumPass.draw(renderer, t.rowsAbove);
    this.chunksPass.draw(renderer, t.chunksBefore);
    this.totalsPass.draw(renderer, t.totals);
    renderer.readRenderTargetPixels(t.totals, 0, 0, GROUPS, 1, this.counts);
    clock('counts');
    u = this.gatherPass.material.uniforms;
    let first = 0;
    this.counts.forEach((n, b) => {
      u.firstPlace.value[b] = first;
      first += n;
    });
    u.count.value = first;
    u.keys.value = t.keys.texture;
    u.before.value = t.before.texture;
    u.rowsAbove.value = t.rowsAbove.texture;
    u.chunksBefore.value = t.chunksBefore.texture;
    u.rows.value = state.rows;
    u.chunks.value = chunks;
    this.gatherPass.draw(renderer, t.order);
    clock('gather');
    renderer.setRenderTarget(null);
    return { order: t.order.texture, counts: this.counts };
  }

  #disposeTargets() {
    for (const t of Object.values(this.targets ?? {})) t.dispose();
    this.targets = null;
    this.rows = 0;
  }

  dispose() {
    this.#disposeTargets();
    for (const p of [this.keyPass, this.countPass, this.rowSumPass, this.chunkSumPass, this.chunksPass, this.totalsPass, this.gatherPass]) p.dispose();
  }
}
