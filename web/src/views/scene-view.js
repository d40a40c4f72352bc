// The 3-D view: perspective camera with orbit controls, opaque objects drawn by three.js, and
// the gas drawn as points or ray marched, composited over the objects with correct depth.

import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { PointsLayer } from './points-layer.js';
import { RaymarchLayer } from './raymarch-layer.js';
import { GuidesLayer } from './guides-layer.js';
import { WindSliceLayer, sliceGeometry } from './wind-slice-layer.js';
import { modelMesh } from './models.js';
import { shadowedLambert } from './object-material.js';

export class SceneView {
  /** @param {HTMLCanvasElement} canvas */
  constructor(canvas) {
    this.canvas = canvas;
    this.renderer = new THREE.WebGLRenderer({ canvas, antialias: false, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(1);
    this.camera = new THREE.PerspectiveCamera(40, 1, 0.05, 4000);
    this.controls = new OrbitControls(this.camera, canvas);
    // Without damping the controls update the camera only on user input, so an untouched
    // camera stays exactly where the scene put it (deterministic exports).
    this.controls.enableDamping = false;
    this.scene = new THREE.Scene();
    this.objects = new THREE.Group();
    this.scene.add(this.objects);
    this.points = new PointsLayer();
    this.scene.add(this.points.points);
    this.raymarch = new RaymarchLayer();
    this.target = null;
    this.settingsKey = '';
    this.background = [0, 0, 0];
    /** Draw plain cylinders in place of models (for comparisons with the CPU still). */
    this.standIns = false;
    /** Wind guides and the drag handle, drawn over the frame when `showGuides` is set. */
    this.overlay = new THREE.Scene();
    this.guides = new GuidesLayer(this.overlay, this.camera, canvas, this.controls);
    this.showGuides = false;
    /** The wind on a plane through the target, one of the guides: 'off', 'xy', 'xz' or 'yz'. */
    this.windSlice = new WindSliceLayer(this.overlay);
    this.slicePlane = 'off';
    /** Distance of the slice from the target along the plane's normal (m). */
    this.sliceOffset = 0;
  }

  /** The slice's square (`{origin, u, v}`, m) when guides and a slice plane are on, else null. */
  sliceSquare() {
    if (!this.showGuides) return null;
    const distance = this.camera.position.distanceTo(this.controls.target);
    const side = 2 * distance * Math.tan((this.camera.fov * Math.PI) / 360);
    return sliceGeometry(this.slicePlane, this.controls.target.toArray(), side, this.sliceOffset);
  }

  /** Places the camera as the scene's render settings say. */
  setCamera(camera) {
    this.camera.position.fromArray(camera.position);
    this.camera.up.fromArray(camera.up);
    this.controls.target.fromArray(camera.target);
    this.camera.fov = camera.fov_y_deg;
    this.camera.updateProjectionMatrix();
    // Aim without controls.update(): its spherical round trip would move the camera by rounding.
    this.camera.lookAt(this.controls.target);
    this.camera.updateMatrixWorld();
  }

  /** The current camera in DESIGN §4's form. */
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
   * Rebuilds the objects and three.js lights when the render settings change. With
   * `standIns`, cylinders that name a model are drawn as the plain cylinders the CPU still uses.
   */
  setRenderSettings(settings, { standIns = this.standIns } = {}) {
    const key = JSON.stringify([settings.objects, settings.lights, settings.medium, settings.background, standIns]);
    if (key === this.settingsKey) return;
    this.settingsKey = key;
    this.background = settings.background;
    this.scene.background = new THREE.Color().setRGB(...settings.background, THREE.LinearSRGBColorSpace);
    for (const child of [...this.objects.children]) {
      this.objects.remove(child);
      child.geometry?.dispose();
      child.material?.dispose();
    }
    for (const o of settings.objects) this.objects.add(objectMesh(o, standIns, this.raymarch.material.uniforms));
    // Lights reach the objects through the shared uniforms; set them now so the points view
    // shades the objects before the first ray-march frame.
    this.raymarch.setLights(settings.lights, settings.medium);
  }

  resize(width, height) {
    this.renderer.setSize(width, height, false);
    this.camera.aspect = width / Math.max(height, 1);
    this.camera.updateProjectionMatrix();
    this.points.setViewport(height, this.camera.fov);
    this.target?.dispose();
    this.target = new THREE.WebGLRenderTarget(width, height, { type: THREE.HalfFloatType });
    this.target.depthTexture = new THREE.DepthTexture(width, height);
  }

  size() {
    return { width: this.canvas.width, height: this.canvas.height };
  }

  /** Draws one frame in `mode` ('points' or 'raymarch'). */
  render(mode) {
    if (mode === 'raymarch') {
      this.points.points.visible = false;
      this.renderer.setRenderTarget(this.target);
      this.scene.background = null;
      this.renderer.setClearColor(0x000000, 0);
      this.renderer.render(this.scene, this.camera);
      this.renderer.setRenderTarget(null);
      this.raymarch.setOpaque(this.objects.children.some((c) => c.isMesh) ? this.target : null, this.camera.near, this.camera.far);
      this.raymarch.render(this.renderer);
      this.scene.background = new THREE.Color().setRGB(...this.background, THREE.LinearSRGBColorSpace);
    } else {
      this.points.points.visible = true;
      this.renderer.render(this.scene, this.camera);
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

function objectMesh(o, standIns, shared) {
  const material = shadowedLambert(o.color, shared);
  const model = o.type === 'cylinder' && !standIns ? modelMesh(o, material) : null;
  if (model) return model;
  if (o.type === 'sphere') {
    const mesh = new THREE.Mesh(new THREE.SphereGeometry(o.radius, 48, 24), material);
    mesh.position.fromArray(o.center);
    return mesh;
  }
  if (o.type === 'plane') {
    const mesh = new THREE.Mesh(new THREE.PlaneGeometry(4000, 4000, 200, 200), material);
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
