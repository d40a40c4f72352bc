// Richer meshes the browser draws in place of a cylinder stand-in (`"model"` on a cylinder
// object): a mug and the teapot that ships with three.js. Each is scaled to the stand-in's
// radius and height and stood on its base along its axis; the CPU still keeps the cylinder.

import * as THREE from 'three';
import { TeapotGeometry } from 'three/examples/jsm/geometries/TeapotGeometry.js';
import { mergeGeometries } from 'three/examples/jsm/utils/BufferGeometryUtils.js';

/** A mug of unit radius and unit height standing on y = 0: a lathed wall and a torus handle. */
function mugGeometry() {
  const wall = 0.08;
  const profile = [
    [0, 0], [1, 0], [1, 1], [1 - wall, 1], [1 - wall, wall], [0, wall],
  ].map(([x, y]) => new THREE.Vector2(x, y));
  const body = new THREE.LatheGeometry(profile, 64);
  const handle = new THREE.TorusGeometry(0.3, 0.07, 16, 48, Math.PI);
  handle.rotateZ(-Math.PI / 2);
  handle.translate(1, 0.5, 0);
  return mergeGeometries([body, handle]);
}

/** The teapot scaled to unit radius (body) standing on y = 0, spout towards +x. */
function teapotGeometry() {
  const g = new TeapotGeometry(1, 8);
  g.computeBoundingBox();
  const box = g.boundingBox;
  // The body's radius is the box's half depth (z); spout and handle stick out along x.
  const s = 1 / ((box.max.z - box.min.z) / 2);
  g.translate(0, -box.min.y, 0);
  g.scale(s, s, s);
  return g;
}

const makers = { mug: mugGeometry, teapot: teapotGeometry };

/**
 * The mesh of `object.model` fitted to the cylinder stand-in `object`, or null.
 * @param {{model?: string, base: number[], axis: number[], radius: number, height: number}} object
 * @param {THREE.Material} material
 */
export function modelMesh(object, material) {
  const make = makers[object.model];
  if (!make) return null;
  const geometry = make();
  geometry.computeBoundingBox();
  const unitHeight = geometry.boundingBox.max.y;
  const mesh = new THREE.Mesh(geometry, material);
  mesh.scale.set(object.radius, object.height / unitHeight, object.radius);
  const axis = new THREE.Vector3().fromArray(object.axis).normalize();
  mesh.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), axis);
  mesh.position.fromArray(object.base);
  return mesh;
}
