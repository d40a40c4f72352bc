// The wind on one plane through the view's target: u = u_l + u_s (paper Eq. 3) sampled by the
// core (`windSlice`) on a square that fills the view, coloured by speed (viridis, 0 to the
// slice's largest speed) with arrows for the wind's component in the plane.

import * as THREE from 'three';
import { viridis } from '../charts/colormap.js';

/** Samples per side of the slice. */
export const SLICE_SAMPLES = 48;
/** Every this many samples an arrow. */
const ARROW_EVERY = 3;
/** Unit vectors (u, v) spanning each plane; the plane's normal is u × v. */
const PLANES = {
  xy: [[1, 0, 0], [0, 1, 0]],
  xz: [[1, 0, 0], [0, 0, -1]],
  yz: [[0, 0, -1], [0, 1, 0]],
};
export const SLICE_PLANES = ['off', ...Object.keys(PLANES)];

/**
 * The square of `plane` ('xy', 'xz' or 'yz') centred at `center` and `offset` metres along its
 * normal, with side `side`: `{origin, u, v}` as the core's `windSlice` takes them, or null.
 */
export function sliceGeometry(plane, center, side, offset = 0) {
  const axes = PLANES[plane];
  if (!axes) return null;
  const [a, b] = axes.map((e) => e.map((c) => c * side));
  const normal = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
    .map((c) => c / (side * side));
  const origin = center.map((c, i) => c + offset * normal[i] - 0.5 * (a[i] + b[i]));
  return { origin, u: a, v: b };
}

export class WindSliceLayer {
  /** @param {THREE.Scene} overlay the guides' scene */
  constructor(overlay) {
    const n = SLICE_SAMPLES;
    this.pixels = new Uint8Array(4 * n * n);
    this.texture = new THREE.DataTexture(this.pixels, n, n, THREE.RGBAFormat);
    this.texture.magFilter = THREE.LinearFilter;
    this.texture.colorSpace = THREE.SRGBColorSpace;
    this.plane = new THREE.Mesh(
      new THREE.PlaneGeometry(1, 1),
      new THREE.MeshBasicMaterial({ map: this.texture, transparent: true, opacity: 0.6, side: THREE.DoubleSide, depthWrite: false }),
    );
    const arrows = Math.ceil(n / ARROW_EVERY) ** 2;
    this.arrowPositions = new Float32Array(arrows * 6 * 3);
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(this.arrowPositions, 3));
    this.arrows = new THREE.LineSegments(geometry, new THREE.LineBasicMaterial({ color: 0xffffff, transparent: true, opacity: 0.85 }));
    this.arrows.frustumCulled = false;
    this.group = new THREE.Group();
    this.group.add(this.plane, this.arrows);
    this.group.visible = false;
    this.maxSpeed = 0;
    overlay.add(this.group);
  }

  /** The context is lost: let go of its texture (`context-loss.js`); the colours stay. */
  contextLost() {
    this.texture.dispose();
  }

  /** The context is back: upload the last slice's colours again. */
  contextRestored() {
    this.texture.needsUpdate = true;
  }

  hide() {
    this.group.visible = false;
  }

  /**
   * Draws the samples `data` (3 per sample, u-index fastest, as `windSlice` returns them) over
   * the square `{origin, u, v}`.
   */
  update(data, { origin, u, v }) {
    const n = SLICE_SAMPLES;
    const speed = new Float32Array(n * n);
    for (let k = 0; k < n * n; k++) speed[k] = Math.hypot(data[3 * k], data[3 * k + 1], data[3 * k + 2]);
    const max = speed.reduce((a, b) => Math.max(a, b), 0);
    /** The speed (m/s) the top of the colour scale stands for. */
    this.maxSpeed = max;
    const scale = max > 0 ? 1 / max : 0;
    for (let k = 0; k < n * n; k++) {
      viridis(speed[k] * scale, this.pixels, 4 * k);
      this.pixels[4 * k + 3] = 255;
    }
    this.texture.needsUpdate = true;
    const U = new THREE.Vector3().fromArray(u);
    const V = new THREE.Vector3().fromArray(v);
    const uh = U.clone().normalize();
    const vh = V.clone().normalize();
    const side = U.length();
    const basis = new THREE.Matrix4().makeBasis(uh, vh, uh.clone().cross(vh));
    this.plane.quaternion.setFromRotationMatrix(basis);
    this.plane.scale.set(side, V.length(), 1);
    this.plane.position.fromArray(origin).addScaledVector(U, 0.5).addScaledVector(V, 0.5);
    // Arrows: the in-plane wind, the fastest ARROW_EVERY × 0.9 cells long, with a head.
    const cell = side / n;
    const length = max > 0 ? (ARROW_EVERY * 0.9 * cell) / max : 0;
    const p = this.arrowPositions;
    p.fill(0);
    let o = 0;
    const at = new THREE.Vector3();
    const tip = new THREE.Vector3();
    for (let j = 1; j < n; j += ARROW_EVERY) {
      for (let i = 1; i < n; i += ARROW_EVERY) {
        const k = j * n + i;
        const w = new THREE.Vector3(data[3 * k], data[3 * k + 1], data[3 * k + 2]);
        const du = w.dot(uh) * length;
        const dv = w.dot(vh) * length;
        at.fromArray(origin).addScaledVector(U, (i + 0.5) / n).addScaledVector(V, (j + 0.5) / n);
        tip.copy(at).addScaledVector(uh, du).addScaledVector(vh, dv);
        // Head: two short strokes back from the tip, ±25° off the shaft.
        const back = (angle) => {
          const c = Math.cos(angle) * -0.3;
          const s = Math.sin(angle) * -0.3;
          return tip.clone().addScaledVector(uh, c * du - s * dv).addScaledVector(vh, s * du + c * dv);
        };
        for (const [a, b] of [[at, tip], [tip, back(0.44)], [tip, back(-0.44)]]) {
          a.toArray(p, o);
          b.toArray(p, o + 3);
          o += 6;
        }
      }
    }
    this.arrows.geometry.attributes.position.needsUpdate = true;
    this.group.visible = true;
  }
}
