// Stirring the gas with a pointer or a finger: while stirring is on, dragging over the view
// moves a transient wind primitive with the pointer (paper §6: wind fields superposed
// interactively). The pointer is followed on the plane through the orbit target facing the
// camera; the wind there is the pointer's own velocity, falling off as exp(−distance/radius)
// around it (a uniform primitive with decay, outside the scene). Orbiting is off meanwhile.

import * as THREE from 'three';

/** The stir's reach as a fraction of the camera's distance to its target. */
const REACH = 0.06;
/** Fastest wind the pointer makes (m/s). */
const MAX_SPEED = 4;
/** Least time between two stirs sent (ms). */
const SEND_EVERY = 30;
/** A pointer resting this long (ms) stirs no more. */
const REST_AFTER = 120;

export class PointerStir {
  /**
   * @param {import('./scene-view.js').SceneView} view
   * @param {(position: number[], velocity: number[], radius: number) => void} send stirs the
   *   gas (radius 0 stops it)
   */
  constructor(view, send) {
    this.view = view;
    this.send = send;
    this.on = false;
    this.last = null;
    this.sentAt = -Infinity;
    this.restTimer = 0;
    this.raycaster = new THREE.Raycaster();
    this.handlers = {
      pointerdown: (e) => this.#down(e),
      pointermove: (e) => this.#move(e),
      pointerup: (e) => this.#up(e),
      pointercancel: (e) => this.#up(e),
    };
  }

  /** Whether a drag stirs (true) or orbits (false). */
  get enabled() {
    return this.on;
  }

  set enabled(on) {
    if (on === this.on) return;
    this.on = on;
    const canvas = this.view.canvas;
    for (const [type, handler] of Object.entries(this.handlers)) {
      if (on) canvas.addEventListener(type, handler);
      else canvas.removeEventListener(type, handler);
    }
    this.view.controls.enabled = !on;
    canvas.style.cursor = on ? 'crosshair' : '';
    canvas.style.touchAction = on ? 'none' : '';
    if (!on) this.#stop();
  }

  /** The world point (m) under client coordinates, on the plane through the target facing the camera. */
  worldAt(clientX, clientY) {
    const { camera, controls, canvas } = this.view;
    const box = canvas.getBoundingClientRect();
    const ndc = new THREE.Vector2(((clientX - box.left) / box.width) * 2 - 1, -((clientY - box.top) / box.height) * 2 + 1);
    this.raycaster.setFromCamera(ndc, camera);
    const normal = camera.getWorldDirection(new THREE.Vector3());
    const plane = new THREE.Plane().setFromNormalAndCoplanarPoint(normal, controls.target);
    return this.raycaster.ray.intersectPlane(plane, new THREE.Vector3());
  }

  #radius() {
    return REACH * this.view.camera.position.distanceTo(this.view.controls.target);
  }

  #down(e) {
    this.view.canvas.setPointerCapture?.(e.pointerId);
    const at = this.worldAt(e.clientX, e.clientY);
    this.last = at && { at, time: e.timeStamp, velocity: new THREE.Vector3() };
  }

  #move(e) {
    if (!this.last) return;
    const at = this.worldAt(e.clientX, e.clientY);
    const dt = (e.timeStamp - this.last.time) / 1000;
    if (!at || !(dt > 0)) return;
    const velocity = at.clone().sub(this.last.at).divideScalar(dt).clampLength(0, MAX_SPEED);
    // Smoothed over a few events, so one jittery event does not jerk the gas.
    this.last = { at, time: e.timeStamp, velocity: this.last.velocity.lerp(velocity, 0.5) };
    if (e.timeStamp - this.sentAt >= SEND_EVERY) {
      this.sentAt = e.timeStamp;
      this.send(at.toArray(), this.last.velocity.toArray(), this.#radius());
    }
    clearTimeout(this.restTimer);
    this.restTimer = setTimeout(() => this.last && this.send(this.last.at.toArray(), [0, 0, 0], this.#radius()), REST_AFTER);
  }

  #up(e) {
    this.view.canvas.releasePointerCapture?.(e.pointerId);
    this.#stop();
  }

  #stop() {
    clearTimeout(this.restTimer);
    if (this.last) this.send([0, 0, 0], [0, 0, 0], 0);
    this.last = null;
  }
}
