// Moves a 2-D atlas of slices into a 3-D texture, as many slices a draw as the context has
// colour attachments (up to eight), each attachment one layer of the 3-D texture. WebGL2 draws
// into one layer per attachment and has no call that copies a tiled atlas into a volume: a copy
// a slice costs a render pass a slice, which on some drivers (ANGLE on Vulkan) outweighs the
// copying itself. Raw WebGL2 beside three.js: three.js cannot attach several layers of one 3-D
// texture, so this draws with its own program and framebuffer and then hands the context's
// state back to three.js (`resetState`). Values are copied exactly (texelFetch, same format).
// Its program, framebuffer and vertex array belong to the context they were made in and three.js
// does not know them: when the context is lost the owner drops the SliceCopy and makes a new one
// once it is restored (`VolumeLayer.contextLost`).

const MAX_LAYERS = 8;

const vertexSource = `#version 300 es
void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
`;

const fragmentSource = (layers) => `#version 300 es
precision highp float;
precision highp int;
precision highp sampler2D;
uniform sampler2D atlas;
uniform ivec2 tile;   // a slice's texels (nx, ny)
uniform int cols;     // slice k is the tile at column k mod cols, row ⌊k / cols⌋
uniform int first;    // the first slice of this draw
uniform int last;     // the grid's last slice
${Array.from({ length: layers }, (_, i) => `layout(location = ${i}) out vec4 out${i};`).join('\n')}
vec4 slice(int k) {
  k = min(k, last);
  return texelFetch(atlas, ivec2(k % cols, k / cols) * tile + ivec2(gl_FragCoord.xy), 0);
}
void main() {
${Array.from({ length: layers }, (_, i) => `  out${i} = slice(first + ${i});`).join('\n')}
}
`;

function compile(gl, type, source) {
  const shader = gl.createShader(type);
  gl.shaderSource(shader, source);
  gl.compileShader(shader);
  if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS)) {
    throw new Error(`slice copy: ${gl.getShaderInfoLog(shader)}`);
  }
  return shader;
}

export class SliceCopy {
  /** @param {import('three').WebGLRenderer} renderer */
  constructor(renderer) {
    const gl = renderer.getContext();
    if (gl.isContextLost()) throw new Error('slice copy: the WebGL context is lost');
    this.renderer = renderer;
    this.layers = Math.min(MAX_LAYERS, gl.getParameter(gl.MAX_DRAW_BUFFERS), gl.getParameter(gl.MAX_COLOR_ATTACHMENTS));
    const program = gl.createProgram();
    gl.attachShader(program, compile(gl, gl.VERTEX_SHADER, vertexSource));
    gl.attachShader(program, compile(gl, gl.FRAGMENT_SHADER, fragmentSource(this.layers)));
    gl.linkProgram(program);
    if (!gl.getProgramParameter(program, gl.LINK_STATUS)) throw new Error(`slice copy: ${gl.getProgramInfoLog(program)}`);
    this.program = program;
    this.uniforms = Object.fromEntries(['atlas', 'tile', 'cols', 'first', 'last'].map((n) => [n, gl.getUniformLocation(program, n)]));
    this.framebuffer = gl.createFramebuffer();
    this.vertexArray = gl.createVertexArray();
  }

  /** The WebGL texture behind a three.js texture (made if three.js has not made it yet). */
  #handle(texture) {
    return this.renderer.properties.get(texture).__webglTexture;
  }

  /**
   * Copies slices 0..dims[2]−1 of `atlas` (a three.js texture of tiles dims[0] × dims[1], `cols`
   * to a row) into layers 0..dims[2]−1 of `volume` (the texture of an initialised 3-D target).
   * @returns {number} the draws made
   */
  copy(atlas, volume, dims, cols) {
    const gl = this.renderer.getContext();
    const [nx, ny, nz] = dims;
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.framebuffer);
    gl.useProgram(this.program);
    gl.bindVertexArray(this.vertexArray);
    for (const cap of [gl.BLEND, gl.DEPTH_TEST, gl.STENCIL_TEST, gl.SCISSOR_TEST, gl.CULL_FACE, gl.RASTERIZER_DISCARD]) gl.disable(cap);
    gl.colorMask(true, true, true, true);
    gl.activeTexture(gl.TEXTURE0);
    gl.bindTexture(gl.TEXTURE_2D, this.#handle(atlas));
    gl.uniform1i(this.uniforms.atlas, 0);
    gl.uniform2i(this.uniforms.tile, nx, ny);
    gl.uniform1i(this.uniforms.cols, cols);
    gl.uniform1i(this.uniforms.last, nz - 1);
    gl.viewport(0, 0, nx, ny);
    const target = this.#handle(volume);
    const buffers = [];
    let draws = 0;
    for (let first = 0; first < nz; first += this.layers) {
      buffers.length = 0;
      for (let i = 0; i < this.layers; i++) {
        const used = first + i < nz;
        gl.framebufferTextureLayer(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0 + i, used ? target : null, 0, used ? first + i : 0);
        buffers.push(used ? gl.COLOR_ATTACHMENT0 + i : gl.NONE);
      }
      gl.drawBuffers(buffers);
      gl.uniform1i(this.uniforms.first, first);
      gl.drawArrays(gl.TRIANGLES, 0, 3);
      draws += 1;
    }
    for (let i = 0; i < this.layers; i++) gl.framebufferTextureLayer(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0 + i, null, 0, 0);
    gl.bindVertexArray(null);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    this.renderer.resetState();
    return draws;
  }

  dispose() {
    const gl = this.renderer.getContext();
    gl.deleteProgram(this.program);
    gl.deleteFramebuffer(this.framebuffer);
    gl.deleteVertexArray(this.vertexArray);
  }
}
