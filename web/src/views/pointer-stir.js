// Stirring the gas with a pointer or a finger: while stirring is on, dragging over the view
// pushes the gas with the pointer (paper §6: wind fields superposed interactively). The pointer
// is followed on the plane through the orbit target facing the camera; each move sends how far
// it went there, and the next steps of the simulation give that motion to the gas near it
// (falling off as exp(−distance/radius)): the gas moves as far as the pointer did, whether the
// view draws 60 frames a second or 2 (`stir` in engine/handlers.js). Orbiting is off meanwhile.

import * as THREE from 'three';

/** The stir's reach as a fraction of the camera's distance to its target. */
const REACH = 0.06;
/** Least time between two stirs sent (ms); the motion in between adds up. */
const SEND_EVERY = 30;

export class PointerStir {
  /**
   * @param {import('./scene-view.js').SceneView} view
   * @param {(position: number[], displacement: number[], radius: number) => void} send gives
   *   the gas the pointer's motion `displacement` (m), ending at `position` (m), with a reach of
   *   `radius` (m)
   */
  constructor(view, send) {
    this.view = view;
    this.send = send;
    this.on = false;
    /** Where the pointer was last seen (world, m), and its motion not yet sent. */
    this.last = null;
    this.unsent = new THREE.Vector3();
    this.sentAt = -Infinity;
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
    this.last = this.worldAt(e.clientX, e.clientY);
    this.unsent.set(0, 0, 0);
  }

  #move(e) {
    if (!this.last) return;
    // Every position the browser saw since the last event (it may hand several at once).
    const events = e.getCoalescedEvents?.().length ? e.getCoalescedEvents() : [e];
    for (const c of events) {
      const at = this.worldAt(c.clientX, c.clientY);
      if (!at) continue;
      this.unsent.add(at.clone().sub(this.last));
      this.last = at;
    }
    if (e.timeStamp - this.sentAt >= SEND_EVERY) this.#flush(e.timeStamp);
  }

  #flush(now) {
    if (!this.last || this.unsent.lengthSq() === 0) return;
    this.sentAt = now;
    this.send(this.last.toArray(), this.unsent.toArray(), this.#radius());
    this.unsent.set(0, 0, 0);
  }

  #up(e) {
    this.view.canvas.releasePointerCapture?.(e.pointerId);
    this.#stop();
  }

  #stop() {
    // The motion since the last send still goes to the gas.
    this.#flush(performance.now());
    this.last = null;
  }
}
