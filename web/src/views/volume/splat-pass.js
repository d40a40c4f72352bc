// The direct splat (the real-time view's first pass, for blobs narrower than DIRECT_LIMIT
// voxels): every such blob adds its average over each voxel of its footprint to the density
// atlas, renormalised over the footprint so the mass is kept, exactly as `frame::volume::splat`
// in the core does. The sprite covers the footprint's rows and columns in a slice's tile; its
// fragments are voxels. Additive blending into float targets: [ρ, ρΩ] and [ρ(1 − Ω)Q, 0] (the
// density-weighted source of docs/FORMATS.md), each times `densityScale` (stored as optical
// depths, `volume-layer.js`). Blobs are drawn σ class by class
// (`frameDescription` in `scene-view.js`); wider blobs are culled here and go through the
// particle mesh (`mesh-pass.js`).
//
// Without emission one point a blob writes all its slices (a footprint narrower than 3 voxels
// meets at most four): into four layers of an atlas of four colour attachments (the mesh's,
// free before the mesh is drawn), the layer l of slice z holding slice z + l, which a pass over
// the grid then adds into the density atlas. With emission a blob takes one point a slice, into
// density and source.
import * as THREE from 'three';
import { DIRECT_LIMIT, FOOTPRINT } from '../../generated/contract.js';
import { BLOB_GLSL } from '../shaders/blob-record.js';
import { ERF_GLSL } from '../shaders/erf.js';
import { VOXEL_GRID_GLSL } from '../shaders/voxel-grid.js';
import { additivePoints, setDefine } from './point-draws.js';
import { ScreenPass } from '../screen-pass.js';
import { ATLAS_PASS_GLSL } from './glsl.js';

const vertexShader = /* glsl */ `
precision highp float;
precision highp int;
${BLOB_GLSL}
${ERF_GLSL}
${VOXEL_GRID_GLSL}
uniform Grid grid;
uniform int atlasCols;   // slice k is the tile at column k mod atlasCols, row ⌊k / atlasCols⌋
uniform vec2 atlasSize;  // texels
uniform int classOffset;
uniform int slices;       // points a blob: one a slice, or 1 with LAYERS
uniform float densityScale; // stored per unit density (κ̄h)
flat out vec3 vCentre;
flat out float vInvWidth;
flat out float vScale;
flat out ivec4 vRange;   // first and last voxel in x and y
flat out ivec2 vCorner;  // atlas texel of the footprint's first voxel
flat out vec3 vAlbedo;
flat out vec3 vSource;
flat out vec4 vLayers;   // the share of slices first.z + 0…3 (LAYERS)

// Σ over voxels first..last of Φ(x_{i+1}) − Φ(x_i), Φ = ½ erf((x − c)/(σ√2)), inv = 1/(σ√2).
float total(float lo, float h, float c, float inv, float first, float last) {
  return 0.5 * (erf1((lo + (last + 1.0) * h - c) * inv) - erf1((lo + first * h - c) * inv));
}

void main() {
  int blob = classOffset + gl_VertexID / slices;
  int s = gl_VertexID % slices;
  vec3 c;
  float sigma, mass;
  fetchBlob(blob, c, sigma, mass, vAlbedo, vSource);
  vec3 top = vec3(grid.dims - 1);
  vec3 first = clamp(floor((c - ${FOOTPRINT.toFixed(1)} * sigma - grid.lo) / grid.h), vec3(0.0), top);
  vec3 last = clamp(floor((c + ${FOOTPRINT.toFixed(1)} * sigma - grid.lo) / grid.h), vec3(0.0), top);
  float k = first.z + float(s);
  gl_PointSize = 1.0;
  if (k > last.z || mass <= 0.0 || sigma >= ${DIRECT_LIMIT.toFixed(2)} * grid.h) {
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0); // outside the clip volume: no fragments
    return;
  }
  float inv = 0.70710678 / sigma;
  float nx = total(grid.lo.x, grid.h, c.x, inv, first.x, last.x);
  float ny = total(grid.lo.y, grid.h, c.y, inv, first.y, last.y);
  float nz = total(grid.lo.z, grid.h, c.z, inv, first.z, last.z);
  float wz = total(grid.lo.z, grid.h, c.z, inv, k, k) / nz;
  if (!(nx > 1e-12 && ny > 1e-12 && nz > 1e-12)) {
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    return;
  }
  vCentre = c;
  vInvWidth = inv;
  vScale = densityScale * mass / (grid.h * grid.h * grid.h) / (nx * ny);
#ifdef LAYERS
  for (int l = 0; l < 4; l++) vLayers[l] = k + float(l) <= last.z ? total(grid.lo.z, grid.h, c.z, inv, k + float(l), k + float(l)) / nz : 0.0;
#else
  vScale *= wz;
#endif
  vRange = ivec4(first.xy, last.xy);
  vCorner = atlasTexel(ivec3(ivec2(first.xy), int(k)), grid.dims, atlasCols);
  vec2 corner = vec2(vCorner);
  float size = max(last.x - first.x, last.y - first.y) + 1.0;
  gl_PointSize = size;
  gl_Position = vec4((corner + 0.5 * size) / atlasSize * 2.0 - 1.0, 0.0, 1.0);
}
`;

const fragmentShader = /* glsl */ `
precision highp float;
precision highp int;
${ERF_GLSL}
${VOXEL_GRID_GLSL}
uniform Grid grid;
flat in vec3 vCentre;
flat in float vInvWidth;
flat in float vScale;
flat in ivec4 vRange;
flat in ivec2 vCorner;
flat in vec3 vAlbedo;
flat in vec3 vSource;
flat in vec4 vLayers;
layout(location = 0) out vec4 outDensity;
layout(location = 1) out vec4 outSource;
#ifdef LAYERS
layout(location = 2) out vec4 outLayer2;
layout(location = 3) out vec4 outLayer3;
#endif

// The blob's average over voxel i along one axis (unnormalised).
float share(float lo, float h, float c, float i) {
  return 0.5 * (erf1((lo + (i + 1.0) * h - c) * vInvWidth) - erf1((lo + i * h - c) * vInvWidth));
}

void main() {
  ivec2 q = ivec2(gl_FragCoord.xy) - vCorner;
  ivec2 v = vRange.xy + q;
  if (v.x > vRange.z || v.y > vRange.w) discard;
  float rho = vScale * share(grid.lo.x, grid.h, vCentre.x, float(v.x)) * share(grid.lo.y, grid.h, vCentre.y, float(v.y));
  vec4 density = vec4(rho, rho * vAlbedo);
#ifdef LAYERS
  outDensity = vLayers.x * density;
  outSource = vLayers.y * density;
  outLayer2 = vLayers.z * density;
  outLayer3 = vLayers.w * density;
#else
  outDensity = density;
  outSource = vec4(rho * vSource, 0.0);
#endif
}
`;

/** Adds the four layers into the density atlas: voxel z gets layer l of slice z − l. */
const layersFragment = /* glsl */ `
${ATLAS_PASS_GLSL}
uniform Grid grid;
uniform int atlasCols;
uniform sampler2D layer0;
uniform sampler2D layer1;
uniform sampler2D layer2;
uniform sampler2D layer3;
layout(location = 0) out vec4 outDensity;

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  ivec3 v;
  outDensity = vec4(0.0);
  if (!atlasVoxel(px, grid.dims, atlasCols, v)) return;
  outDensity = texelFetch(layer0, px, 0);
  if (v.z >= 1) outDensity += texelFetch(layer1, atlasTexel(v - ivec3(0, 0, 1), grid.dims, atlasCols), 0);
  if (v.z >= 2) outDensity += texelFetch(layer2, atlasTexel(v - ivec3(0, 0, 2), grid.dims, atlasCols), 0);
  if (v.z >= 3) outDensity += texelFetch(layer3, atlasTexel(v - ivec3(0, 0, 3), grid.dims, atlasCols), 0);
}
`;

/** Layers of the splat without emission: a footprint under 3 voxels meets at most four slices. */
export const SPLAT_LAYERS = 4;

export class SplatPass {
  /** @param {{blobTex: {value: THREE.Texture}, grid: {value: object}, densityScale: {value: number}, atlasCols: {value: number}, atlasSize: {value: number[]}}} shared uniforms */
  constructor(shared) {
    this.shared = shared;
    this.scene = new THREE.Scene();
    this.camera = new THREE.OrthographicCamera(-1, 1, 1, -1, 0, 1);
    this.draws = [];
    this.layers = new ScreenPass(layersFragment, {
      grid: shared.grid, atlasCols: shared.atlasCols,
      layer0: { value: null }, layer1: { value: null }, layer2: { value: null }, layer3: { value: null },
    });
  }

  #draw(i, layered) {
    while (this.draws.length <= i) {
      const points = additivePoints(vertexShader, fragmentShader, { ...this.shared, classOffset: { value: 0 }, slices: { value: 1 } });
      this.scene.add(points);
      this.draws.push(points);
    }
    setDefine(this.draws[i].material, 'LAYERS', layered);
    return this.draws[i];
  }

  /**
   * Splats the narrow blobs of the frame's `classes` (`frameDescription`: {offset, count,
   * sigmaMax}) into `target` (all of it written) on voxels of side `h`. Without `emissive`
   * gas, `layers` (an atlas like `target` with SPLAT_LAYERS attachments, free for now) takes
   * the points first.
   */
  render(renderer, target, classes, h, { emissive, layers }) {
    classes = classes.filter((c) => c.sigmaLow < DIRECT_LIMIT * h);
    const layered = !emissive;
    classes.forEach((cls, i) => {
      const points = this.#draw(i, layered);
      // A footprint w = 2·FOOTPRINT·σ/h voxels long meets at most ⌈w⌉ + 1 slices.
      const slices = layered ? 1 : Math.ceil((2 * FOOTPRINT * Math.min(cls.sigmaMax, DIRECT_LIMIT * h)) / h) + 1;
      points.visible = true;
      points.material.uniforms.classOffset.value = cls.offset;
      points.material.uniforms.slices.value = slices;
      points.geometry.setDrawRange(0, cls.count * slices);
    });
    for (let i = classes.length; i < this.draws.length; i++) this.draws[i].visible = false;
    renderer.setRenderTarget(layered ? layers : target);
    renderer.setClearColor(0x000000, 0);
    renderer.clear(true, false, false);
    if (classes.length) renderer.render(this.scene, this.camera);
    if (!layered) return;
    const u = this.layers.material.uniforms;
    ['layer0', 'layer1', 'layer2', 'layer3'].forEach((name, l) => { u[name].value = layers.textures[l]; });
    renderer.setRenderTarget(target);
    this.layers.render(renderer);
  }
}
