// Field slice view: one xy plane of the small-scale field at a time t, coloured by speed
// (viridis) with arrows for the in-plane velocity (u₁, u₂), and optionally its colour bar.

import * as THREE from 'three';
import { viridis } from '../charts/colormap.js';
import { ColourBar } from '../charts/colour-bar.js';
import { releaseGeometries } from './context-loss.js';

/** Arrows drawn per side of the slice. */
const ARROWS = 16;

export class SliceView {
  /**
   * @param {HTMLCanvasElement} canvas
   * @param {{ legend?: HTMLCanvasElement }} options `legend`: a canvas for the speed's colour bar
   */
  constructor(canvas, { legend } = {}) {
    this.legend = legend ? new ColourBar(legend, { title: 'speed |u|', unit: 'lattice units', extend: true }) : null;
    this.renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0x101418);
    this.camera = new THREE.OrthographicCamera(-1, 1, 1, -1, 0, 10);
    this.camera.position.z = 5;
    this.texture = null;
    this.plane = new THREE.Mesh(
      new THREE.PlaneGeometry(2, 2),
      new THREE.MeshBasicMaterial({ color: 0xffffff }),
    );
    this.scene.add(this.plane);
    const arrowGeometry = new THREE.BufferGeometry();
    arrowGeometry.setAttribute(
      'position',
      new THREE.BufferAttribute(new Float32Array(ARROWS * ARROWS * 6 * 3), 3),
    );
    this.arrows = new THREE.LineSegments(
      arrowGeometry,
      new THREE.LineBasicMaterial({ color: 0xffffff, transparent: true, opacity: 0.85 }),
    );
    this.arrows.position.z = 0.01;
    this.scene.add(this.arrows);
    // A lost context: let go of three.js's objects while it is lost (`context-loss.js`); once
    // it is restored, draw the last slice again (it is drawn only when asked otherwise).
    canvas.addEventListener('webglcontextlost', () => {
      this.texture?.dispose();
      releaseGeometries(this.scene);
    });
    canvas.addEventListener('webglcontextrestored', () => {
      if (this.texture) this.texture.needsUpdate = true;
      this.render();
    });
  }

  /** Fits the square slice into a `width × height` CSS-pixel canvas. */
  resize(width, height) {
    this.renderer.setSize(width, height, false);
    const aspect = width / Math.max(height, 1);
    const half = 1.05;
    const hx = aspect >= 1 ? half * aspect : half;
    const hy = aspect >= 1 ? half : half / aspect;
    Object.assign(this.camera, { left: -hx, right: hx, top: hy, bottom: -hy });
    this.camera.updateProjectionMatrix();
  }

  /**
   * Shows a slice: `data` holds `width*height` velocities (u₁, u₂, u₃), row-major from y = 0;
   * `speedScale` is the speed drawn at the top of the colour map (faster is clipped to it).
   */
  update(data, width, height, speedScale) {
    this.legend?.set(0, speedScale);
    if (!this.texture || this.texture.image.width !== width || this.texture.image.height !== height) {
      this.texture?.dispose();
      this.texture = new THREE.DataTexture(new Uint8Array(width * height * 4), width, height);
      this.texture.magFilter = THREE.LinearFilter;
      this.texture.colorSpace = THREE.SRGBColorSpace;
      this.plane.material.map = this.texture;
      this.plane.material.needsUpdate = true;
    }
    const pixels = this.texture.image.data;
    for (let i = 0; i < width * height; i++) {
      const u = data[3 * i];
      const v = data[3 * i + 1];
      const w = data[3 * i + 2];
      viridis(Math.sqrt(u * u + v * v + w * w) / speedScale, pixels, 4 * i);
      pixels[4 * i + 3] = 255;
    }
    this.texture.needsUpdate = true;

    const pos = this.arrows.geometry.attributes.position.array;
    const cell = 2 / ARROWS;
    let o = 0;
    for (let j = 0; j < ARROWS; j++) {
      for (let i = 0; i < ARROWS; i++) {
        const sx = Math.floor(((i + 0.5) * width) / ARROWS);
        const sy = Math.floor(((j + 0.5) * height) / ARROWS);
        const k = 3 * (sy * width + sx);
        const ax = (data[k] / speedScale) * cell * 0.9;
        const ay = (data[k + 1] / speedScale) * cell * 0.9;
        const x0 = -1 + (i + 0.5) * cell - ax / 2;
        const y0 = -1 + (j + 0.5) * cell - ay / 2;
        const x1 = x0 + ax;
        const y1 = y0 + ay;
        // Shaft, then the two strokes of the head.
        const hx = -ax * 0.3;
        const hy = -ay * 0.3;
        const segments = [
          x0, y0, x1, y1,
          x1, y1, x1 + hx - hy * 0.5, y1 + hy + hx * 0.5,
          x1, y1, x1 + hx + hy * 0.5, y1 + hy - hx * 0.5,
        ];
        for (let s = 0; s < segments.length; s += 2) {
          pos[o++] = segments[s];
          pos[o++] = segments[s + 1];
          pos[o++] = 0;
        }
      }
    }
    this.arrows.geometry.attributes.position.needsUpdate = true;
  }

  render() {
    this.renderer.render(this.scene, this.camera);
  }
}
