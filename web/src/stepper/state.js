// The gas's state on the GPU: one texel per slot (`gas::slots` in the core), BLOBS_PER_ROW slots
// a row, in float render targets.
//
// - `moving` (ping-pong, two attachments): [centre xyz (m), σ² (m²)] and [mass, age (s), τ (s), 0];
//   a step reads one and writes the other. With carried turbulence two more: the carried offsets
//   [o_a xyz (m), 0] and [o_b xyz (m), 0] of the two phases (`gas::carried` in the core).
// - `fixed` (three attachments, written only when a blob is born): [own velocity v0 xyz (m/s), 0],
//   [albedo Ω rgb (a negative r: the medium's), 0], [emission Q rgb, 0].
//
// An empty slot has mass 0: the step leaves it so and the views skip it.

import * as THREE from 'three';
import { BLOBS_PER_ROW } from '../generated/contract.js';

function target(rows, count) {
  return new THREE.WebGLRenderTarget(BLOBS_PER_ROW, rows, {
    count,
    type: THREE.FloatType,
    format: THREE.RGBAFormat,
    minFilter: THREE.NearestFilter,
    magFilter: THREE.NearestFilter,
    depthBuffer: false,
    generateMipmaps: false,
  });
}

export class StepperState {
  /** State for at least `capacity` slots (whole rows), with carried offsets when `carried`. */
  constructor(capacity, carried = false) {
    this.rows = Math.max(1, Math.ceil(capacity / BLOBS_PER_ROW));
    this.capacity = this.rows * BLOBS_PER_ROW;
    this.carried = carried;
    const moving = carried ? 4 : 2;
    this.moving = [target(this.rows, moving), target(this.rows, moving)];
    this.fixed = target(this.rows, 3);
    /** Which of `moving` holds the current state. */
    this.current = 0;
  }

  get now() {
    return this.moving[this.current];
  }

  get next() {
    return this.moving[1 - this.current];
  }

  swap() {
    this.current = 1 - this.current;
  }

  dispose() {
    for (const t of [...this.moving, this.fixed]) t.dispose();
  }
}
