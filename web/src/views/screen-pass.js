// A full-screen pass: one quad over the whole target, each fragment drawn by a GLSL 3 fragment
// shader (`vUv` in [0, 1]² is there for it, and gl_FragCoord the target's texel).

import * as THREE from 'three';

const vertexShader = /* glsl */ `
out vec2 vUv;
void main() { vUv = uv; gl_Position = vec4(position.xy, 0.0, 1.0); }
`;

/**
 * A copy of `material` that shares its uniforms (the same objects, not copies): a variant of a
 * pass's shader reading the same inputs. three.js's `clone` would copy the uniforms first (and
 * warn about every render target's texture among them).
 */
export function sharingUniforms(material) {
  const { uniforms } = material;
  material.uniforms = {};
  try {
    const copy = material.clone();
    copy.uniforms = uniforms;
    return copy;
  } finally {
    material.uniforms = uniforms;
  }
}

export class ScreenPass {
  /**
   * @param {string} fragmentShader GLSL 3
   * @param {object} uniforms
   * @param {object} [options] more material settings (blending, defines)
   */
  constructor(fragmentShader, uniforms, options = {}) {
    this.material = new THREE.ShaderMaterial({
      glslVersion: THREE.GLSL3,
      vertexShader,
      fragmentShader,
      uniforms,
      depthTest: false,
      depthWrite: false,
      ...options,
    });
    this.quad = new THREE.Mesh(new THREE.PlaneGeometry(2, 2), this.material);
    this.quad.frustumCulled = false;
    this.scene = new THREE.Scene();
    this.scene.add(this.quad);
    this.camera = new THREE.OrthographicCamera(-1, 1, 1, -1, 0, 1);
  }

  /** Draws the quad into the renderer's current target. */
  render(renderer) {
    renderer.render(this.scene, this.camera);
  }

  dispose() {
    this.quad.geometry.dispose();
    this.material.dispose();
  }
}
