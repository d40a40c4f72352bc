// Uniforms every gas-aware shader shares (the exact march, the real-time view, the objects'
// material): the lights, the medium's extinction and phase function, where gas shadows come
// from, and the objects that cast shadows. One object of {value} holders, owned by the view; each material spreads it into its own
// uniforms, so all of them always see the same frame. Their GLSL is `shaders/lights.js`.

import * as THREE from 'three';
import { VIEW_LIGHTS } from '../generated/contract.js';

/** Fresh holders for the shared uniforms. */
export function gasUniforms() {
  return {
    lightCount: { value: 0 },
    lightType: { value: new Array(VIEW_LIGHTS).fill(0) },
    lightVec: { value: Array.from({ length: VIEW_LIGHTS }, () => new THREE.Vector3()) },
    lightColor: { value: Array.from({ length: VIEW_LIGHTS }, () => new THREE.Vector3()) },
    extinction: { value: new THREE.Vector3(1, 1, 1) },
    hasShadows: { value: false },
    phaseType: { value: 0 },
    phaseG: { value: 0 },
    srgb: { value: true },
    // Where gas shadows come from: 0 none, 1 the exact march's shadow grid, 2 the light volume.
    shadowSource: { value: 0 },
    // The objects' shadows (`occluders.js`): the packed objects and how many each row holds.
    occluders: { value: null },
    occluderCount: { value: new Array(VIEW_LIGHTS + 1).fill(0) },
  };
}

/** Sets the lights (at most VIEW_LIGHTS) and the medium (extinction, phase) of the rendering model (docs/FORMATS.md). */
export function setLights(u, lights, medium) {
  const k = Array.isArray(medium.extinction) ? medium.extinction : [medium.extinction, medium.extinction, medium.extinction];
  u.extinction.value.fromArray(k);
  const used = lights.slice(0, VIEW_LIGHTS);
  u.lightCount.value = used.length;
  used.forEach((l, i) => {
    u.lightType.value[i] = l.type === 'point' ? 0 : 1;
    if (l.type === 'point') u.lightVec.value[i].fromArray(l.position);
    else u.lightVec.value[i].fromArray(l.direction).normalize().negate();
    u.lightColor.value[i].fromArray(l.color);
  });
  u.phaseType.value = medium.phase?.type === 'henyey-greenstein' ? 1 : 0;
  u.phaseG.value = medium.phase?.g ?? 0;
}
