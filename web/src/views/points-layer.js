// The points view (paper §6: the animator sees the blobs) drawn as gas: one soft sprite per
// blob, read from the packed frame on the GPU. A sprite is the blob's column seen face on: its
// optical depth at distance r from the centre is κ_t m/(2πσ²) · exp(−r²/2σ²) (the line
// integral of Eq. 13 through the blob), its colour the light the blob scatters plus its emitted
// source (1 − Ω)Q. Without shadows every sprite would scatter the lights' full strength and a
// dense plume would burn out to white; the scattered part is compressed as x / (1 + x) instead,
// a stand-in for the self-shadowing the marches compute.
//
// The sprites' optical depths τ and depth-weighted colours τc are summed in a float target
// (order-independent, so a million faint blobs add up where an 8-bit blend would drop each of
// them), fragments behind the objects left out by the opaque pass's depth. The target holds
// 32-bit floats where the GPU blends them, else 16-bit ones (`precision.js`): sums kept to a
// half float's 11 significant bits draw the same preview (docs/BENCHMARKS.md), and each
// fragment's τ is held under TAU_MOST so that the sums stay finite (a fragment that deep is
// opaque either way). A full-screen pass then lays the gas over the objects and the
// background: opacity 1 − exp(−Στ) (Beer–Lambert through the summed columns), colour Στc / Στ.
// A preview, not the image: the real-time view and the stills are.

import * as THREE from 'three';
import { VIEW_LIGHTS } from '../generated/contract.js';
import { passPrecision, texelType } from './precision.js';
import { ScreenPass } from './screen-pass.js';
import { BLOB_GLSL } from './shaders/blob-record.js';
import { LIGHTS_GLSL } from './shaders/lights.js';

/**
 * Sprites reach this many σ from the centre, by quality: at `draft` (the lighter version's) 2σ,
 * their column scaled by 1/(1 − e^{−2}) so each still carries its whole optical depth, with
 * less than half the fragments to draw.
 */
const REACH = { draft: 2, standard: 3, high: 3 };
/** Smallest sprite (pixels): a blob smaller than this spreads its opacity over it. */
const MIN_SIZE = 2;
/** Most optical depth one fragment adds (e^−64 of the light passes it): 1,000 of them stay under a half float's 65,504. */
const TAU_MOST = 64;

const vertexShader = /* glsl */ `
precision highp float;
precision highp int;
${BLOB_GLSL}
${LIGHTS_GLSL}
uniform float pixelsPerUnit;
uniform float reach;
out vec3 vColor;
out float vDepth;   // κ_t m/(2πσ²) at the centre, spread over the sprite if it was enlarged
out float vReach;   // the sprite's radius in σ
void main() {
  vec3 c;
  float sigma, mass;
  vec3 albedo, source;
  fetchBlob(gl_VertexID, c, sigma, mass, albedo, source);
  vec4 mv = modelViewMatrix * vec4(c, 1.0);
  gl_Position = projectionMatrix * mv;
  float size = 2.0 * reach * sigma * pixelsPerUnit / max(-mv.z, 1e-4);
  float shown = max(size, ${MIN_SIZE.toFixed(1)});
  gl_PointSize = shown;
  vReach = reach * shown / max(size, 1e-6);
  float k = (extinction.r + extinction.g + extinction.b) / 3.0;
  // The share of a blob's column within the sprite's disc: 1 − exp(−reach²/2).
  float held = 1.0 - exp(-0.5 * reach * reach);
  vDepth = k * mass / (6.2831853 * sigma * sigma) / held * min(1.0, (size * size) / (shown * shown));
  vec3 L = vec3(0.0);
  for (int l = 0; l < ${VIEW_LIGHTS}; l++) {
    if (l >= lightCount) break;
    L += lightColor[l];
  }
  vec3 scattered = albedo * L;
  vColor = scattered / (1.0 + scattered) + source;
  if (mass <= 0.0) gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
}
`;

const fragmentShader = /* glsl */ `
precision highp float;
uniform sampler2D opaqueDepth;
uniform vec2 viewSize;
in vec3 vColor;
in float vDepth;
in float vReach;
out vec4 outColor;
void main() {
  vec2 p = (gl_PointCoord * 2.0 - 1.0) * vReach;
  float r2 = dot(p, p);
  if (r2 > vReach * vReach) discard;
  if (gl_FragCoord.z > texture(opaqueDepth, gl_FragCoord.xy / viewSize).x) discard;
  float tau = min(vDepth * exp(-0.5 * r2), ${TAU_MOST.toFixed(1)});
  outColor = vec4(vColor * tau, tau);
}
`;

/** The gas (summed τc, τ) over the opaque pass's colour, or the background where it drew nothing. */
const compositeShader = /* glsl */ `
precision highp float;
uniform sampler2D gasSums;
uniform sampler2D opaqueColor;
uniform vec3 background;
in vec2 vUv;
out vec4 outColor;
void main() {
  vec4 sums = texture(gasSums, vUv);
  vec4 opaque = texture(opaqueColor, vUv);
  vec3 under = mix(background, opaque.rgb, opaque.a);
  float alpha = 1.0 - exp(-sums.a);
  vec3 gas = sums.a > 0.0 ? sums.rgb / sums.a : vec3(0.0);
  outColor = linearToOutputTexel(vec4(gas * alpha + under * (1.0 - alpha), 1.0));
}
`;

export class PointsLayer {
  /** @param {object} gas the shared gas uniforms @param {import('./blob-texture.js').BlobTexture} blobs */
  constructor(gas, blobs) {
    this.blobs = blobs;
    // No attributes: each vertex finds its blob from gl_VertexID.
    this.geometry = new THREE.BufferGeometry();
    this.geometry.setDrawRange(0, 0);
    this.material = new THREE.ShaderMaterial({
      glslVersion: THREE.GLSL3,
      vertexShader,
      fragmentShader,
      transparent: true,
      depthTest: false,
      depthWrite: false,
      blending: THREE.CustomBlending,
      blendSrc: THREE.OneFactor,
      blendDst: THREE.OneFactor,
      blendSrcAlpha: THREE.OneFactor,
      blendDstAlpha: THREE.OneFactor,
      uniforms: {
        ...gas, blobTex: { value: null }, pixelsPerUnit: { value: 500 }, reach: { value: REACH.standard },
        opaqueDepth: { value: null }, viewSize: { value: new THREE.Vector2(1, 1) },
      },
    });
    this.points = new THREE.Points(this.geometry, this.material);
    this.points.frustumCulled = false;
    this.scene = new THREE.Scene().add(this.points);
    this.composite = new ScreenPass(compositeShader, {
      gasSums: { value: null }, opaqueColor: { value: null }, background: { value: new THREE.Color() },
    });
    /** The summed (τc, τ) of the sprites, the view's size. */
    this.sums = null;
    /** The GPU's float formats (`gpuFormats`), set by the view. */
    this.formats = null;
  }

  /** Shows the blobs of the blob texture. */
  update() {
    this.material.uniforms.blobTex.value = this.blobs.texture;
    this.geometry.setDrawRange(0, this.blobs.count);
  }

  setViewport(heightPx, fovYDeg) {
    this.material.uniforms.pixelsPerUnit.value = heightPx / (2 * Math.tan((fovYDeg * Math.PI) / 360));
  }

  /**
   * Draws the sprites seen by `camera` over `opaque` (the opaque pass's target: the objects'
   * colour, transparent where none, and depth) and `background` (linear RGB) into the
   * renderer's current target (the canvas).
   */
  render(renderer, camera, opaque, background, quality = 'standard') {
    this.material.uniforms.reach.value = REACH[quality] ?? REACH.standard;
    const output = renderer.getRenderTarget();
    const { width, height } = opaque;
    if (!this.sums || this.sums.width !== width || this.sums.height !== height) {
      this.sums?.dispose();
      const type = texelType(passPrecision(this.formats).points);
      // Read texel for texel: no filterable format needed.
      this.sums = new THREE.WebGLRenderTarget(width, height, {
        type, depthBuffer: false, minFilter: THREE.NearestFilter, magFilter: THREE.NearestFilter,
      });
    }
    const u = this.material.uniforms;
    u.opaqueDepth.value = opaque.depthTexture;
    u.viewSize.value.set(width, height);
    renderer.setRenderTarget(this.sums);
    renderer.setClearColor(0x000000, 0);
    renderer.clear(true, false, false);
    renderer.render(this.scene, camera);
    renderer.setRenderTarget(output);
    const c = this.composite.material.uniforms;
    c.gasSums.value = this.sums.texture;
    c.opaqueColor.value = opaque.texture;
    c.background.value.setRGB(...background, THREE.LinearSRGBColorSpace);
    this.composite.render(renderer);
  }

  /** Lets go of the target (a lost context); it is made again at the next draw. */
  contextLost() {
    this.sums?.dispose();
    this.sums = null;
  }
}
