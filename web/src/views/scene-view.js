// The 3-D view: perspective camera with orbit controls, opaque objects drawn by three.js, and
// the gas drawn in one of three ways (docs/FORMATS.md, the browser API): `points` (a sprite a blob), `raymarch` (the
// real-time volume view) or `exact` (the per-chord march), the marches composited over the
// objects with correct depth. Every view reads the frame's blobs from one texture.
//
// A lost WebGL context (the GPU was reset, or the browser took it for newer contexts): the view
// lets the browser restore it (the lost event is prevented), draws, builds and reads nothing
// meanwhile, and lets go of what it made in it: the real-time view's raw WebGL copier, and
// three.js's objects for its geometries, textures and targets (`context-loss.js`). Once it is
// restored, three.js makes its own objects again as they are drawn, the data textures upload
// the data they kept (the last frame's blobs among them), the real-time view rebuilds its
// volumes from the frame it holds and makes a new copier. The owner hears of both through
// `onContextLost` and `onContextRestored`, and then draws the frame again.

import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { INFO_HEADER, INFO_PER_CLASS, SPHERE_FLOATS } from '../generated/contract.js';
import { BlobTexture } from './blob-texture.js';
import { ExactMarchLayer } from './exact/exact-layer.js';
import { gasUniforms, setLights } from './gas-uniforms.js';
import { PointsLayer } from './points-layer.js';
import { gpuFormats } from './precision.js';
import { classSigma } from './volume/grid.js';
import { VolumeLayer } from './volume/volume-layer.js';
import { CameraLimits } from './camera-limits.js';
import { GuidesLayer } from './guides-layer.js';
import { WindSliceLayer, sliceGeometry } from './wind-slice-layer.js';
import { modelMesh } from './models.js';
import { shadowedLambert } from './object-material.js';
import { Occluders } from './occluders.js';
import { releaseGeometries } from './context-loss.js';

/**
 * Half the side of a plane object's mesh (m), and the camera's far plane twice that. The
 * reference's planes are infinite: a pixel whose centre sees the plane a hair below the horizon
 * (a tenth of a pixel at 120 rows is 4 km away from a camera 2.4 m up) must see it here too.
 */
const PLANE_REACH = 1e6;
/** Cells from a plane's centre to its edge, and the narrowest cell there (m). */
const PLANE_CELLS = 32;
const PLANE_FINEST = 0.25;

/** The colour the views draw for a transparent `render.background` (the scene format's default). */
const SHOWN_FOR_TRANSPARENT = [0.05, 0.06, 0.08];

export class SceneView {
  /** Set between the context's loss and its restoration. */
  #lost = false;
  /** WEBGL_lose_context, got while the context is whole (a lost context gives no extensions). */
  #loseContext = null;

  /** @param {HTMLCanvasElement} canvas */
  constructor(canvas) {
    this.canvas = canvas;
    this.renderer = new THREE.WebGLRenderer({ canvas, antialias: false, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(1);
    this.camera = new THREE.PerspectiveCamera(40, 1, 0.05, 2 * PLANE_REACH);
    this.controls = new OrbitControls(this.camera, canvas);
    // Without damping the controls update the camera only on user input, so an untouched
    // camera stays exactly where the scene put it (deterministic exports).
    this.controls.enableDamping = false;
    /** Keeps the camera near the scene and above its floor; keyboard orbit and zoom. */
    this.limits = new CameraLimits(this.camera, this.controls);
    this.scene = new THREE.Scene();
    this.objects = new THREE.Group();
    this.scene.add(this.objects);
    /** Repulsor spheres, which move every frame. */
    this.spheres = new THREE.Group();
    this.scene.add(this.spheres);
    this.spheresKey = '';
    /** Uniforms every gas-aware shader shares; the layers add their own entries to it. */
    this.gas = gasUniforms();
    /** What the GPU stores, blends and filters in floats, and its largest textures (`precision.js`). */
    this.formats = gpuFormats(this.renderer);
    this.blobs = new BlobTexture();
    this.exact = new ExactMarchLayer(this.gas);
    this.volume = new VolumeLayer(this.gas, this.blobs);
    this.points = new PointsLayer(this.gas, this.blobs);
    this.volume.formats = this.formats;
    this.points.formats = this.formats;
    /** The objects that cast shadows: the scene's objects and the frame's repulsor spheres. */
    this.occluders = new Occluders(this.gas);
    this.sceneObjects = [];
    this.lights = [];
    this.frameSpheres = [];
    this.target = null;
    /** The render settings applied last (the object, with or without stand-ins, and its content). */
    this.settings = null;
    this.settingsStandIns = false;
    this.settingsKey = '';
    this.background = [0, 0, 0];
    /** Draw plain cylinders in place of models (for comparisons with the CPU still). */
    this.standIns = false;
    /** The resolution scale the real-time view's volumes follow (`VolumeLayer.prepare`). */
    this.volumeScale = 1;
    /** Wind guides and the drag handle, drawn over the frame when `showGuides` is set. */
    this.overlay = new THREE.Scene();
    this.guides = new GuidesLayer(this.overlay, this.camera, canvas, this.controls);
    this.showGuides = false;
    /** The wind on a plane through the target, one of the guides: 'off', 'xy', 'xz' or 'yz'. */
    this.windSlice = new WindSliceLayer(this.overlay);
    this.slicePlane = 'off';
    /** Distance of the slice from the target along the plane's normal (m). */
    this.sliceOffset = 0;
    /** Called when the context is lost, and once it is restored and the view ready to draw. */
    this.onContextLost = null;
    this.onContextRestored = null;
    // After three.js's own listeners (the renderer's), so that three.js's state is new by the
    // time this view rebuilds its own on top of it.
    canvas.addEventListener('webglcontextlost', (event) => this.#contextLost(event));
    canvas.addEventListener('webglcontextrestored', () => this.#contextRestored());
    this.#loseContext = this.renderer.getContext().getExtension('WEBGL_lose_context');
  }

  /** True while the WebGL context is lost (from the loss until its restoration, if ever). */
  get contextLost() {
    return this.#lost || this.renderer.getContext().isContextLost();
  }

  /**
   * Asks the browser for the lost context back: one it took for newer pages' contexts (past its
   * limit of live contexts) stays lost until asked. Call it after the lost event, not inside it.
   * The view rebuilds itself when the context arrives (`onContextRestored`). Returns whether it
   * could ask.
   */
  restoreContext() {
    if (!this.contextLost || !this.#loseContext) return false;
    this.#loseContext.restoreContext();
    return true;
  }

  #contextLost(event) {
    event.preventDefault();
    this.#lost = true;
    this.volume.contextLost();
    this.exact.contextLost();
    this.blobs.contextLost();
    this.windSlice.contextLost();
    this.points.contextLost();
    this.occluders.contextLost();
    this.target?.dispose();
    this.opaqueKey = null;
    releaseGeometries(this.scene, this.overlay);
    this.onContextLost?.();
  }

  /**
   * Lets go of everything this view made on the GPU, and of its context (the browser may give
   * it to another page's canvas): the view draws no more.
   */
  dispose() {
    this.onContextLost = null;
    this.onContextRestored = null;
    this.#lost = true;
    this.volume.dispose();
    this.exact.contextLost();
    this.blobs.contextLost();
    this.windSlice.contextLost();
    this.points.contextLost();
    this.target?.dispose();
    this.target = null;
    releaseGeometries(this.scene, this.overlay);
    this.controls.dispose();
    this.renderer.dispose();
    this.renderer.forceContextLoss();
  }

  #contextRestored() {
    this.#lost = false;
    this.#loseContext = this.renderer.getContext().getExtension('WEBGL_lose_context') ?? this.#loseContext;
    this.volume.contextRestored();
    this.exact.contextRestored();
    this.blobs.contextRestored();
    this.windSlice.contextRestored();
    this.occluders.contextRestored();
    this.onContextRestored?.();
  }

  /** The slice's square (`{origin, u, v}`, m) when guides and a slice plane are on, else null. */
  sliceSquare() {
    if (!this.showGuides) return null;
    const distance = this.camera.position.distanceTo(this.controls.target);
    const side = 2 * distance * Math.tan((this.camera.fov * Math.PI) / 360);
    return sliceGeometry(this.slicePlane, this.controls.target.toArray(), side, this.sliceOffset);
  }

  /**
   * Places the camera as the scene's render settings say, with orbit limits for the scene
   * (`objects`: its floor).
   */
  setCamera(camera, objects = []) {
    this.camera.position.fromArray(camera.position);
    this.camera.up.fromArray(camera.up);
    this.controls.target.fromArray(camera.target);
    this.camera.fov = camera.fov_y_deg;
    this.camera.updateProjectionMatrix();
    // Aim without controls.update(): its spherical round trip would move the camera by rounding.
    this.camera.lookAt(this.controls.target);
    this.camera.updateMatrixWorld();
    this.limits.set(camera, objects);
  }

  /** The current camera in the blob list's form (docs/FORMATS.md). */
  cameraSettings() {
    return {
      position: this.camera.position.toArray(),
      target: this.controls.target.toArray(),
      up: this.camera.up.toArray(),
      fov_y_deg: this.camera.fov,
    };
  }

  /** Camera basis for the ray march and the tiles. */
  viewBasis() {
    const forward = this.controls.target.clone().sub(this.camera.position).normalize();
    const right = forward.clone().cross(this.camera.up).normalize();
    const up = right.clone().cross(forward);
    return {
      position: this.camera.position.toArray(),
      forward: forward.toArray(),
      right: right.toArray(),
      up: up.toArray(),
      tanHalf: Math.tan((this.camera.fov * Math.PI) / 360),
    };
  }

  /**
   * Rebuilds the objects and sets the lights and medium when the render settings change. With
   * `standIns`, cylinders that name a model are drawn as the plain cylinders the CPU still uses.
   */
  setRenderSettings(settings, { standIns = this.standIns } = {}) {
    // The same settings object as last time (a scene is replaced, never changed in place): nothing
    // to compare. A new one is compared by its content once.
    if (settings === this.settings && standIns === this.settingsStandIns) return;
    this.settings = settings;
    this.settingsStandIns = standIns;
    const key = JSON.stringify([settings.objects, settings.lights, settings.medium, settings.background, settings.shadows, settings.image, standIns]);
    if (key === this.settingsKey) return;
    this.settingsKey = key;
    // A transparent background (for stills and exports with alpha) is drawn as the default one.
    this.background = settings.background === 'transparent' ? SHOWN_FOR_TRANSPARENT : settings.background;
    this.scene.background = new THREE.Color().setRGB(...this.background, THREE.LinearSRGBColorSpace);
    for (const child of [...this.objects.children]) {
      this.objects.remove(child);
      child.geometry?.dispose();
      child.material?.dispose();
    }
    for (const o of settings.objects) this.objects.add(objectMesh(o, standIns, this.gas));
    this.sceneObjects = settings.objects;
    this.lights = settings.lights;
    setLights(this.gas, settings.lights, settings.medium);
    this.gas.hasShadows.value = Boolean(settings.shadows) && settings.lights.length > 0;
    this.gas.srgb.value = (settings.image?.encoding ?? 'srgb') === 'srgb';
    this.spheresKey = '';
    this.opaqueKey = null;
    this.volume.invalidate();
  }

  /**
   * A new frame: the packed blobs for every view (the worker's words, `blobs`, or a packed
   * texture the GPU stepper keeps, `texture`), their description (`info`) and the repulsor
   * spheres (`spheres`: SPHERE_FLOATS each, x y z radius r g b), moved in place.
   */
  setFrame(frame) {
    // The worker's packed words, or the GPU stepper's packed state where it is.
    if (frame.texture) this.blobs.show(frame.texture, frame.count);
    else this.blobs.upload(frame.blobs, frame.count);
    this.volume.setFrame(frameDescription(frame.info));
    this.points.update();
    const s = frame.spheres;
    const n = s.length / SPHERE_FLOATS;
    const key = `${n}|${Array.from({ length: n }, (_, i) => s.slice(SPHERE_FLOATS * i + 3, SPHERE_FLOATS * (i + 1)).join()).join(';')}`;
    if (key !== this.spheresKey) {
      this.spheresKey = key;
      for (const child of [...this.spheres.children]) {
        this.spheres.remove(child);
        child.geometry.dispose();
        child.material.dispose();
      }
      for (let i = 0; i < n; i++) {
        const at = SPHERE_FLOATS * i;
        const sphere = { type: 'sphere', center: [0, 0, 0], radius: s[at + 3], color: Array.from(s.subarray(at + 4, at + 7)) };
        this.spheres.add(objectMesh(sphere, false, this.gas));
      }
    }
    this.spheres.children.forEach((mesh, i) => mesh.position.fromArray(s, SPHERE_FLOATS * i));
    this.frameSpheres = Array.from({ length: n }, (_, i) => ({
      type: 'sphere',
      center: Array.from(s.subarray(SPHERE_FLOATS * i, SPHERE_FLOATS * i + 3)),
      radius: s[SPHERE_FLOATS * i + 3],
    }));
  }

  resize(width, height) {
    this.renderer.setSize(width, height, false);
    this.camera.aspect = width / Math.max(height, 1);
    this.camera.updateProjectionMatrix();
    this.points.setViewport(height, this.camera.fov);
    this.target?.dispose();
    this.target = opaqueTarget(width, height);
  }

  size() {
    return { width: this.canvas.width, height: this.canvas.height };
  }

  /**
   * The objects alone, colour and depth, into the opaque target (transparent where none).
   * `reuse`: skipped when nothing it draws changed since the last time (the camera, the target,
   * the objects and their lights, the repulsor spheres' places): the points view's objects are
   * not shadowed by the gas, so its opaque pass only changes with those.
   */
  #opaquePass(reuse = false) {
    const key = reuse
      ? `${this.camera.matrixWorld.elements.join()}|${this.camera.projectionMatrix.elements.join()}|${this.settingsKey.length}:${this.settingsKey}|${this.spheres.children.map((m) => m.position.toArray().join()).join(';')}`
      : null;
    if (key !== null && key === this.opaqueKey && this.opaqueDrawnIn === this.target) return;
    this.opaqueKey = key;
    this.opaqueDrawnIn = this.target;
    const background = this.scene.background;
    this.scene.background = null;
    this.renderer.setRenderTarget(this.target);
    this.renderer.setClearColor(0x000000, 0);
    this.renderer.render(this.scene, this.camera);
    this.renderer.setRenderTarget(null);
    this.scene.background = background;
  }

  /**
   * Draws one frame in `mode` ('points', 'raymarch' or 'exact'; `quality` for `raymarch`);
   * nothing while the context is lost.
   */
  render(mode, quality) {
    if (this.contextLost) return;
    const gas = this.gas;
    const casters = [...this.sceneObjects, ...this.frameSpheres];
    if (mode === 'points') {
      gas.shadowSource.value = 0;
      this.occluders.update(casters, this.lights, null);
      // The objects into the opaque target (their depth hides the sprites behind them; drawn
      // again only when they or the camera moved), then the sprites over them and the background.
      this.camera.updateMatrixWorld();
      this.#opaquePass(true);
      this.points.render(this.renderer, this.camera, this.target, this.background, quality);
    } else {
      const layer = mode === 'exact' ? this.exact : this.volume;
      gas.shadowSource.value = mode === 'exact' ? 1 : 2;
      // The volumes first: the objects read their shadows from the light volume.
      if (mode === 'raymarch') this.volume.prepare(this.renderer, quality, this.volumeScale);
      // The real-time view marches inside its grid's box alone: only objects that may shadow
      // that box are tested per sample. The exact march tests every object.
      const grid = mode === 'raymarch' ? this.volume.grid : null;
      const box = grid && { lo: grid.lo, hi: grid.lo.map((v, a) => v + grid.h * grid.dims[a]) };
      this.occluders.update(casters, this.lights, box);
      this.#opaquePass();
      const hasMeshes = this.objects.children.length + this.spheres.children.length > 0;
      layer.setOpaque(hasMeshes ? this.target : null, this.camera.near, this.camera.far);
      const size = this.size();
      layer.setView(this.viewBasis(), size.width, size.height, this.background);
      layer.render(this.renderer);
    }
    this.guides.setVisible(this.showGuides);
    if (this.showGuides) {
      this.renderer.autoClear = false;
      this.renderer.clearDepth();
      this.renderer.render(this.overlay, this.camera);
      this.renderer.autoClear = true;
    }
  }
}

/** The opaque pass's target: colour (linear, half float) and depth, for the marches. */
function opaqueTarget(width, height) {
  const target = new THREE.WebGLRenderTarget(width, height, { type: THREE.HalfFloatType });
  target.depthTexture = new THREE.DepthTexture(width, height);
  return target;
}

/**
 * A frame's description (`info`, the core's `frame::packed::PackedFrame::info`: INFO_HEADER
 * floats, count, lo xyz, hi xyz, emissive, σ_min, classes, then INFO_PER_CLASS a σ class) as an
 * object; each σ class {index, offset, count, sigmaMax, sigmaLow (its lower bound,
 * `classSigma(index)`)}. A class of index −1 is `mixed`: blobs of every σ up to `sigmaMax`,
 * unsorted (the GPU stepper's state, drawn slot by slot), its lower bound 0.
 */
export function frameDescription(info) {
  const classes = [];
  for (let k = 0; k < info[INFO_HEADER - 1]; k++) {
    const at = INFO_HEADER + INFO_PER_CLASS * k;
    const [index, offset, count, sigmaMax] = info.subarray(at, at + INFO_PER_CLASS);
    const mixed = index < 0;
    classes.push({ index, offset, count, sigmaMax, sigmaLow: mixed ? 0 : classSigma(index), mixed });
  }
  return {
    count: info[0],
    lo: Array.from(info.subarray(1, 4)),
    hi: Array.from(info.subarray(4, 7)),
    emissive: info[7] > 0,
    sigmaMin: info[8],
    classes,
  };
}


/**
 * A plane object's mesh: 2·PLANE_REACH metres a side, its cells PLANE_FINEST metres wide at the
 * centre (where the scene is, so shading and shadows are interpolated finely) and widening
 * geometrically to the horizon: x(u) = R sinh(a·n·u) / sinh(a·n) for u in [−1, 1], 2,048
 * triangles where an even grid of the same fineness would need millions.
 */
function horizonPlane() {
  const n = PLANE_CELLS;
  // a such that the first cell is PLANE_FINEST wide: R sinh(a) / sinh(a n) = PLANE_FINEST (bisection).
  let [lo, hi] = [1e-6, 4];
  for (let i = 0; i < 60; i++) {
    const a = (lo + hi) / 2;
    if ((PLANE_REACH * Math.sinh(a)) / Math.sinh(a * n) > PLANE_FINEST) lo = a;
    else hi = a;
  }
  const a = (lo + hi) / 2;
  const stretch = (u) => (PLANE_REACH * Math.sinh(a * n * u)) / Math.sinh(a * n);
  const geometry = new THREE.PlaneGeometry(2, 2, 2 * n, 2 * n);
  const p = geometry.attributes.position;
  for (let i = 0; i < p.count; i++) p.setXY(i, stretch(p.getX(i)), stretch(p.getY(i)));
  geometry.computeBoundingSphere();
  return geometry;
}

function objectMesh(o, standIns, gas) {
  const material = shadowedLambert(o.color, gas);
  const model = o.type === 'cylinder' && !standIns ? modelMesh(o, material) : null;
  if (model) return model;
  if (o.type === 'sphere') {
    const mesh = new THREE.Mesh(new THREE.SphereGeometry(o.radius, 48, 24), material);
    mesh.position.fromArray(o.center);
    return mesh;
  }
  if (o.type === 'plane') {
    const mesh = new THREE.Mesh(horizonPlane(), material);
    mesh.position.fromArray(o.point);
    mesh.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), new THREE.Vector3().fromArray(o.normal).normalize());
    return mesh;
  }
  const axis = new THREE.Vector3().fromArray(o.axis).normalize();
  const mesh = new THREE.Mesh(new THREE.CylinderGeometry(o.radius, o.radius, o.height, 48), material);
  mesh.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), axis);
  mesh.position.fromArray(o.base).addScaledVector(axis, o.height / 2);
  return mesh;
}
