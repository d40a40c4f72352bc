// WebGL2 for the flow's passes: float textures holding 3-D lattices as 2-D atlases, programs
// drawing every texel of one (a full-screen triangle, no vertex buffer), and reading one back.
//
// Each lattice of samples (a velocity component's faces, or the cells) lies in tiles: its z
// slices side by side, `columns` to a row of tiles, each slice dims[0] × dims[1] texels. A pass
// draws every texel of its target's atlas; a texel past the last slice is written 0.

/** The widest atlas (texels): every WebGL2 holds textures of 4096 texels a side. */
const ATLAS_WIDTH = 4096;

/**
 * Why the flow cannot be stepped with `gl`, or null when it can: WebGL2 and float render
 * targets (EXT_color_buffer_float: the passes write R32F and RGBA32F textures).
 */
export function flowGpuUnsupported(gl) {
  if (typeof WebGL2RenderingContext === 'undefined' || !(gl instanceof WebGL2RenderingContext)) return 'this browser has no WebGL2';
  if (!gl.getExtension('EXT_color_buffer_float')) return 'this GPU cannot render to float textures (no EXT_color_buffer_float)';
  return null;
}

/** Why `gl` cannot add the blobs' heat up on the GPU (`HeatDeposit`) (no float blending), or null when it can. */
export function heatGpuUnsupported(gl) {
  return gl.getExtension('EXT_float_blend') ? null : 'this GPU cannot add into float textures (no EXT_float_blend)';
}

/**
 * Why a flow of `cells` [nx, ny, nz] does not fit `gl`'s textures, or null when it does: every
 * lattice (each component's faces, one more along its own axis) must fit one atlas.
 */
export function flowGpuRefuses(gl, cells) {
  const size = Math.min(ATLAS_WIDTH, gl.getParameter(gl.MAX_TEXTURE_SIZE));
  for (let a = 0; a < 3; a++) {
    const d = [...cells];
    d[a] += 1;
    try {
      atlasOf(d, size);
    } catch (e) {
      return `the flow's ${cells.join(' × ')} cells do not fit this GPU's textures: ${e.message}`;
    }
  }
  return null;
}

/** The atlas (`atlasOf`) of a lattice of `dims` samples on a GPU whose textures are at most `maxTextureSize` a side. */
export function atlasFor(dims, maxTextureSize) {
  return atlasOf(dims, Math.min(ATLAS_WIDTH, maxTextureSize));
}

/** The bytes of a lattice of `dims` samples, `channels` float32s each (`atlasFor`). */
export function latticeBytes(dims, channels, maxTextureSize) {
  const atlas = atlasFor(dims, maxTextureSize);
  return atlas.width * atlas.height * channels * 4;
}

/**
 * The atlas of a lattice of `dims` samples (x, y, z): `columns` slices to a row of tiles,
 * `width` × `height` texels, and the uniform the shaders read it by (dims, columns).
 */
export function atlasOf(dims, maxSize = ATLAS_WIDTH) {
  const [dx, dy, dz] = dims;
  const columns = Math.max(1, Math.min(dz, Math.floor(maxSize / dx)));
  const rows = Math.ceil(dz / columns);
  const width = dx * columns;
  const height = dy * rows;
  if (width > maxSize || height > maxSize) throw new Error(`a lattice of ${dims.join(' × ')} samples does not fit in a ${maxSize}-texel atlas`);
  return { dims: [dx, dy, dz], columns, width, height, uniform: [dx, dy, dz, columns] };
}

/** Where each sample (x fastest, then y, then z) of `atlas` lies in its texels, as an index. */
export function atlasTexel(atlas, i, j, k) {
  const [dx, dy] = atlas.dims;
  const c = atlas.columns;
  return (j + dy * Math.floor(k / c)) * atlas.width + i + dx * (k % c);
}

/**
 * The GLSL of the atlases in cells: a sample's texel, a texel's sample, a trilinear blend of
 * the eight samples around a point given in cells from the grid's origin, and the fade beyond
 * the box (no uniforms: the GPU stepper samples the flow with it too).
 */
export const ATLAS_CELLS_GLSL = /* glsl */ `
// An atlas: (dims.x, dims.y, dims.z, columns).
ivec2 texelOf(ivec3 s, ivec4 L) {
  return ivec2(s.x + L.x * (s.z % L.w), s.y + L.y * (s.z / L.w));
}
// The sample of texel p, z past the last slice for a texel beyond them.
ivec3 sampleOf(ivec2 p, ivec4 L) {
  ivec2 tile = p / L.xy;
  return ivec3(p.x - tile.x * L.x, p.y - tile.y * L.y, tile.y * L.w + tile.x);
}
bool beyond(ivec3 s, ivec4 L) {
  return s.z >= L.z;
}
float fetch1(highp sampler2D t, ivec3 s, ivec4 L) {
  return texelFetch(t, texelOf(s, L), 0).x;
}
// The lower sample and fraction along one axis of n samples at offset o (cells) of the point
// t cells from the origin, clamped to the samples (the core's sample::Axis::locate).
void locate(float t, int n, float o, out int i, out float f) {
  float p = clamp(t - o, 0.0, float(n - 1));
  i = min(int(p), max(n - 2, 0));
  f = n <= 1 ? 0.0 : p - float(i);
}
// The eight corners around q (cells from the origin) of the lattice L at offset o (cells),
// and the fractions.
void cornersCells(highp sampler2D t, ivec4 L, vec3 o, vec3 q, out float c[8], out vec3 f) {
  ivec3 b;
  locate(q.x, L.x, o.x, b.x, f.x);
  locate(q.y, L.y, o.y, b.y, f.y);
  locate(q.z, L.z, o.z, b.z, f.z);
  ivec3 st = ivec3(L.x > 1 ? 1 : 0, L.y > 1 ? 1 : 0, L.z > 1 ? 1 : 0);
  for (int n = 0; n < 8; n++) {
    ivec3 e = ivec3(n & 1, (n >> 1) & 1, (n >> 2) & 1) * st;
    c[n] = fetch1(t, b + e, L);
  }
}
// The fade across one cell beyond the box at a point \`outside\` cells beyond it along each axis
// (0 inside): 1 in the box, 0 a cell or more out (the core's \`frozen_flow::fade_beyond\`).
float fadeBeyond(vec3 outside) {
  if (outside == vec3(0.0)) return 1.0;
  vec3 s = max(vec3(1.0) - outside, vec3(0.0));
  vec3 fade = s * s * (vec3(3.0) - 2.0 * s);
  return fade.x * fade.y * fade.z;
}
// a + (b − a)·t, as the core blends (not mix's a·(1 − t) + b·t).
float lerp(float a, float b, float t) {
  return a + (b - a) * t;
}
vec3 mix3(vec3 a, vec3 b, float t) {
  return a + (b - a) * t;
}
float blend(float c[8], vec3 f) {
  float y0 = lerp(lerp(c[0], c[1], f.x), lerp(c[2], c[3], f.x), f.y);
  float y1 = lerp(lerp(c[4], c[5], f.x), lerp(c[6], c[7], f.x), f.y);
  return lerp(y0, y1, f.z);
}
`;

/** ATLAS_CELLS_GLSL and sampling at a point in metres (the passes' `origin` and `invH`). */
export const ATLAS_GLSL = /* glsl */ `${ATLAS_CELLS_GLSL}
// The eight corners around x (m) of the lattice L at offset o (cells), and the fractions.
void corners(highp sampler2D t, ivec4 L, vec3 o, vec3 x, out float c[8], out vec3 f) {
  cornersCells(t, L, o, (x - origin) * invH, c, f);
}
float trilinear(highp sampler2D t, ivec4 L, vec3 o, vec3 x) {
  float c[8];
  vec3 f;
  corners(t, L, o, x, c, f);
  return blend(c, f);
}
`;

const VERTEX = /* glsl */ `#version 300 es
void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}`;

function shader(gl, type, source) {
  const s = gl.createShader(type);
  gl.shaderSource(s, source);
  gl.compileShader(s);
  if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) {
    const log = gl.getShaderInfoLog(s);
    gl.deleteShader(s);
    throw new Error(`a flow pass did not compile: ${log}`);
  }
  return s;
}

/** A program of the GLSL 3 sources `vertex` and `fragment`, or an Error saying why not. */
export function linkProgram(gl, vertex, fragment) {
  const program = gl.createProgram();
  const vs = shader(gl, gl.VERTEX_SHADER, vertex);
  const fs = shader(gl, gl.FRAGMENT_SHADER, fragment);
  gl.attachShader(program, vs);
  gl.attachShader(program, fs);
  gl.linkProgram(program);
  gl.deleteShader(vs);
  gl.deleteShader(fs);
  if (!gl.getProgramParameter(program, gl.LINK_STATUS)) throw new Error(`a flow pass did not link: ${gl.getProgramInfoLog(program)}`);
  return program;
}

/**
 * Sets the state every pass assumes, whatever else drew with `gl` before (a three.js renderer
 * sharing the context calls its `resetState()` after): no blending, depth, stencil, scissor or
 * culling, every channel written, the default vertex array (the passes read no attributes).
 */
export function passState(gl) {
  for (const cap of [gl.BLEND, gl.DEPTH_TEST, gl.STENCIL_TEST, gl.SCISSOR_TEST, gl.CULL_FACE, gl.RASTERIZER_DISCARD]) gl.disable(cap);
  gl.colorMask(true, true, true, true);
  gl.bindVertexArray(null);
}

/** A program drawing every texel of its target with `body` (GLSL 3 after the common header). */
export class Pass {
  constructor(gl, body) {
    this.gl = gl;
    const fragment = `#version 300 es
precision highp float;
precision highp int;
precision highp sampler2D;
uniform vec3 origin;
uniform float invH;
uniform float h;
uniform ivec3 cells;
uniform ivec4 target;
${ATLAS_GLSL}
${body}`;
    this.program = linkProgram(gl, VERTEX, fragment);
    this.locations = new Map();
  }

  #where(name) {
    if (!this.locations.has(name)) this.locations.set(name, this.gl.getUniformLocation(this.program, name));
    return this.locations.get(name);
  }

  /**
   * Draws into `into` (a Lattice) with `uniforms`: numbers are floats, {int} / {ivec3} / {ivec4}
   * / {vec3} say their type, a Lattice binds its texture (and its atlas to `name + 'L'` when
   * the shader has one).
   */
  draw(into, uniforms) {
    const gl = this.gl;
    gl.useProgram(this.program);
    let unit = 0;
    for (const [name, v] of Object.entries(uniforms)) {
      const at = this.#where(name);
      if (v instanceof Lattice) {
        gl.activeTexture(gl.TEXTURE0 + unit);
        gl.bindTexture(gl.TEXTURE_2D, v.texture);
        if (at) gl.uniform1i(at, unit);
        unit += 1;
        const atlas = this.#where(`${name}L`);
        if (atlas) gl.uniform4iv(atlas, v.atlas.uniform);
      } else if (at === null) {
        continue;
      } else if (typeof v === 'number') gl.uniform1f(at, v);
      else if (typeof v === 'boolean') gl.uniform1i(at, v ? 1 : 0);
      else if ('int' in v) gl.uniform1i(at, v.int);
      else if ('ivec3' in v) gl.uniform3iv(at, v.ivec3);
      else if ('ivec4' in v) gl.uniform4iv(at, v.ivec4);
      else if ('vec3' in v) gl.uniform3fv(at, v.vec3);
    }
    const t = this.#where('target');
    if (t) gl.uniform4iv(t, into.atlas.uniform);
    gl.bindFramebuffer(gl.FRAMEBUFFER, into.framebuffer);
    gl.viewport(0, 0, into.atlas.width, into.atlas.height);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
  }

  dispose() {
    this.gl.deleteProgram(this.program);
  }
}

const FORMATS = {
  1: { internal: 'R32F', format: 'RED' },
  2: { internal: 'RG32F', format: 'RG' },
  4: { internal: 'RGBA32F', format: 'RGBA' },
};

/**
 * One lattice of samples in a float texture of `channels` (1, 2 or 4) per sample, nearest
 * filtered, with a framebuffer to draw into it (`renderable`: R32F and RGBA32F).
 */
export class Lattice {
  constructor(gl, dims, channels = 1, renderable = true) {
    this.gl = gl;
    this.atlas = atlasFor(dims, gl.getParameter(gl.MAX_TEXTURE_SIZE));
    this.channels = channels;
    const f = FORMATS[channels];
    this.internal = gl[f.internal];
    this.format = gl[f.format];
    this.texture = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, this.texture);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
    gl.texImage2D(gl.TEXTURE_2D, 0, this.internal, this.atlas.width, this.atlas.height, 0, this.format, gl.FLOAT, null);
    this.framebuffer = null;
    if (renderable) {
      this.framebuffer = gl.createFramebuffer();
      gl.bindFramebuffer(gl.FRAMEBUFFER, this.framebuffer);
      gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, this.texture, 0);
      const status = gl.checkFramebufferStatus(gl.FRAMEBUFFER);
      if (status !== gl.FRAMEBUFFER_COMPLETE) throw new Error(`a float render target is incomplete (0x${status.toString(16)})`);
    }
  }

  /** The bytes of its texture. */
  get bytes() {
    return this.atlas.width * this.atlas.height * this.channels * 4;
  }

  /** Uploads `values` (`channels` floats a sample, x fastest, then y, then z). */
  upload(values) {
    const gl = this.gl;
    const a = this.atlas;
    const [dx, dy, dz] = a.dims;
    const n = this.channels;
    const texels = new Float32Array(a.width * a.height * n);
    for (let k = 0; k < dz; k++) {
      for (let j = 0; j < dy; j++) {
        const from = n * (dx * (j + dy * k));
        texels.set(values.subarray(from, from + n * dx), n * atlasTexel(a, 0, j, k));
      }
    }
    gl.bindTexture(gl.TEXTURE_2D, this.texture);
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
    gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, a.width, a.height, this.format, gl.FLOAT, texels);
  }

  /** The samples read back (`channels` floats a sample, x fastest, then y, then z). */
  read() {
    const gl = this.gl;
    const a = this.atlas;
    const [dx, dy, dz] = a.dims;
    const rgba = new Float32Array(a.width * a.height * 4);
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.framebuffer);
    gl.readPixels(0, 0, a.width, a.height, gl.RGBA, gl.FLOAT, rgba);
    const n = this.channels;
    const out = new Float32Array(dx * dy * dz * n);
    for (let k = 0; k < dz; k++) {
      for (let j = 0; j < dy; j++) {
        for (let i = 0; i < dx; i++) {
          const t = 4 * atlasTexel(a, i, j, k);
          const s = n * (i + dx * (j + dy * k));
          for (let c = 0; c < n; c++) out[s + c] = rgba[t + c];
        }
      }
    }
    return out;
  }

  dispose() {
    this.gl.deleteTexture(this.texture);
    if (this.framebuffer) this.gl.deleteFramebuffer(this.framebuffer);
  }
}
