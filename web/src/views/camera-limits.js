// A camera that cannot get lost: orbit limits that keep it near the scene and above its floor,
// and keyboard orbit and zoom. The scene's camera sets the scale: zoom stays within a range of
// its distance to the target, panning within a few of those distances, and the camera never
// goes below a floor (a plane of the scene facing up) nor beneath the target by more than the
// floor allows.

import * as THREE from 'three';

/** Nearest and farthest zoom, in distances of the scene's camera to its target. */
const ZOOM = [0.15, 4];
/** How far the target may be panned from where the scene put it, in those distances. */
const PAN = 2;
/** Height kept above a floor, in those distances. */
const CLEARANCE = 0.03;
/** Keyboard steps: an arrow key turns this many radians; + and − zoom by this factor. */
const TURN = Math.PI / 36;
const ZOOM_STEP = 1.15;

/** The height of the highest floor under the scene: planes whose normal points mostly up. */
function floorHeight(objects = []) {
  const floors = objects.filter((o) => o.type === 'plane' && o.normal[1] > 0.7 * Math.hypot(...o.normal));
  return floors.length ? Math.max(...floors.map((o) => o.point[1])) : -Infinity;
}

export class CameraLimits {
  /**
   * @param {THREE.PerspectiveCamera} camera
   * @param {import('three/examples/jsm/controls/OrbitControls.js').OrbitControls} controls
   */
  constructor(camera, controls) {
    this.camera = camera;
    this.controls = controls;
    this.floor = -Infinity;
    this.scale = 1;
    this.home = new THREE.Vector3();
    controls.addEventListener('change', () => this.#keepAboveFloor());
  }

  /** Limits for a scene whose camera looks from `position` at `target` over `objects`. */
  set({ position, target }, objects) {
    this.home.fromArray(target);
    this.scale = Math.max(new THREE.Vector3().fromArray(position).distanceTo(this.home), 1e-3);
    this.floor = floorHeight(objects);
    const c = this.controls;
    c.minDistance = ZOOM[0] * this.scale;
    c.maxDistance = ZOOM[1] * this.scale;
    // Panning stays near the scene (OrbitControls measures from its cursor).
    c.cursor.copy(this.home);
    c.maxTargetRadius = PAN * this.scale;
    this.#updatePolarLimit();
  }

  /** The largest polar angle (from straight up) that keeps the camera above the floor. */
  #updatePolarLimit() {
    const c = this.controls;
    const distance = this.camera.position.distanceTo(c.target);
    const floor = this.floor + CLEARANCE * this.scale;
    const cos = Number.isFinite(floor) ? (floor - c.target.y) / Math.max(distance, 1e-6) : -1;
    c.maxPolarAngle = Math.acos(Math.min(Math.max(cos, -1), 0.98));
  }

  #keepAboveFloor() {
    if (this.busy) return;
    this.busy = true;
    try {
      this.#updatePolarLimit();
      const floor = this.floor + CLEARANCE * this.scale;
      if (this.controls.target.y < floor) this.controls.target.y = floor;
      if (this.camera.position.y < floor) this.controls.update();
    } finally {
      this.busy = false;
    }
  }

  /** Turns the camera about the target by `azimuth` and `polar` radians (within the limits). */
  orbit(azimuth, polar) {
    const c = this.controls;
    const offset = this.camera.position.clone().sub(c.target);
    const s = new THREE.Spherical().setFromVector3(offset);
    s.theta += azimuth;
    s.phi = Math.min(Math.max(s.phi + polar, Math.max(c.minPolarAngle, 1e-3)), Math.min(c.maxPolarAngle, Math.PI - 1e-3));
    this.#place(s);
  }

  /** Moves the camera `factor` times its distance from the target (within the limits). */
  zoom(factor) {
    const s = new THREE.Spherical().setFromVector3(this.camera.position.clone().sub(this.controls.target));
    s.radius = Math.min(Math.max(s.radius * factor, this.controls.minDistance), this.controls.maxDistance);
    this.#place(s);
  }

  #place(spherical) {
    const c = this.controls;
    this.camera.position.copy(c.target).add(new THREE.Vector3().setFromSpherical(spherical));
    this.camera.lookAt(c.target);
    this.#updatePolarLimit();
    c.dispatchEvent({ type: 'change' });
  }

  /** Handles an orbit or zoom key (arrows, + and −); true when it was one. */
  key(event) {
    const moves = {
      ArrowLeft: () => this.orbit(TURN, 0),
      ArrowRight: () => this.orbit(-TURN, 0),
      ArrowUp: () => this.orbit(0, -TURN),
      ArrowDown: () => this.orbit(0, TURN),
      '+': () => this.zoom(1 / ZOOM_STEP),
      '=': () => this.zoom(1 / ZOOM_STEP),
      '-': () => this.zoom(ZOOM_STEP),
    };
    const move = moves[event.key];
    if (!move) return false;
    move();
    return true;
  }
}
