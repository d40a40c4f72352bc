// Points preview (paper §6: the animator sees blob centres): one soft sprite per blob, its size
// the projected σ, its brightness from mass, its colour the blob's albedo or emission.

import * as THREE from 'three';

const vertexShader = /* glsl */ `
attribute float sigma;
attribute float mass;
attribute vec3 tint;
uniform float pixelsPerUnit;
uniform float massScale;
varying vec3 vColor;
varying float vAlpha;
void main() {
  vec4 mv = modelViewMatrix * vec4(position, 1.0);
  gl_Position = projectionMatrix * mv;
  gl_PointSize = clamp(2.5 * sigma * pixelsPerUnit / max(-mv.z, 1e-3), 2.0, 96.0);
  vColor = tint;
  vAlpha = clamp(mass * massScale, 0.08, 1.0);
}
`;

const fragmentShader = /* glsl */ `
varying vec3 vColor;
varying float vAlpha;
void main() {
  vec2 p = gl_PointCoord * 2.0 - 1.0;
  float r2 = dot(p, p);
  if (r2 > 1.0) discard;
  gl_FragColor = vec4(vColor, vAlpha * exp(-3.0 * r2));
}
`;

export class PointsLayer {
  constructor() {
    this.geometry = new THREE.BufferGeometry();
    this.material = new THREE.ShaderMaterial({
      vertexShader,
      fragmentShader,
      transparent: true,
      depthWrite: false,
      blending: THREE.NormalBlending,
      uniforms: { pixelsPerUnit: { value: 500 }, massScale: { value: 1 } },
    });
    this.points = new THREE.Points(this.geometry, this.material);
    this.points.frustumCulled = false;
  }

  /** Shows a frame of the worker's flat arrays; `mediumAlbedo` colours blobs without their own. */
  update(frame, mediumAlbedo) {
    const n = frame.count;
    const tint = new Float32Array(3 * n);
    let maxMass = 0;
    for (let i = 0; i < n; i++) {
      const emissive = frame.emission[3 * i] + frame.emission[3 * i + 1] + frame.emission[3 * i + 2] > 0;
      const own = frame.albedo[3 * i] >= 0;
      for (let c = 0; c < 3; c++) {
        tint[3 * i + c] = emissive ? frame.emission[3 * i + c] : own ? frame.albedo[3 * i + c] : mediumAlbedo[c];
      }
      maxMass = Math.max(maxMass, frame.mass[i]);
    }
    this.geometry.setAttribute('position', new THREE.BufferAttribute(frame.positions, 3));
    this.geometry.setAttribute('sigma', new THREE.BufferAttribute(frame.sigma, 1));
    this.geometry.setAttribute('mass', new THREE.BufferAttribute(frame.mass, 1));
    this.geometry.setAttribute('tint', new THREE.BufferAttribute(tint, 3));
    this.geometry.setDrawRange(0, n);
    this.material.uniforms.massScale.value = maxMass > 0 ? 1 / maxMass : 1;
  }

  setViewport(heightPx, fovYDeg) {
    this.material.uniforms.pixelsPerUnit.value = heightPx / (2 * Math.tan((fovYDeg * Math.PI) / 360));
  }
}
