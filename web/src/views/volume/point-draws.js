// What the volume's point passes share: additive blending into float targets, and a draw of
// points that carries no attributes (each vertex finds its blob from gl_VertexID: instancing a
// one-vertex draw costs a software rasteriser per instance).

import * as THREE from 'three';

/** Blending that adds every fragment to the target (all channels, all attachments). */
export const ADDITIVE = {
  blending: THREE.CustomBlending,
  blendEquation: THREE.AddEquation,
  blendSrc: THREE.OneFactor,
  blendDst: THREE.OneFactor,
  blendSrcAlpha: THREE.OneFactor,
  blendDstAlpha: THREE.OneFactor,
};

/** Points drawn by `vertexShader` and `fragmentShader` (GLSL 3) with `uniforms`, added. */
export function additivePoints(vertexShader, fragmentShader, uniforms) {
  const material = new THREE.ShaderMaterial({
    glslVersion: THREE.GLSL3,
    vertexShader,
    fragmentShader,
    uniforms,
    ...ADDITIVE,
    depthTest: false,
    depthWrite: false,
  });
  const points = new THREE.Points(new THREE.BufferGeometry(), material);
  points.frustumCulled = false;
  return points;
}

/** Compiles `material` with the GLSL define `name` set or not (three.js keeps each program). */
export function setDefine(material, name, on) {
  if (Boolean(material.defines[name]) === on) return;
  material.defines = on ? { [name]: 1 } : {};
  material.needsUpdate = true;
}
