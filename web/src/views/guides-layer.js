// Wind guides: what the large-scale primitives and the emitters are, drawn in the scene
// (arrows for uniform wind, sources and sinks; a circulating ring for a vortex; the path of a
// repulsor; the outline of each emitter; the edges of the flow's box and its closed faces), and a drag handle (three.js TransformControls) that
// moves one of them. Guides are a view aid: captures and recordings leave them out. The drag
// handle's code is fetched when the guides are first shown or something is first picked, so a
// player that never shows them (a docs page's) never fetches it.

import * as THREE from 'three';
import { closedAxes } from '../flow-gpu/boundary.js';

/** three.js's TransformControls, fetched once, on first use. */
let transformControls = null;
function loadTransformControls() {
  transformControls ??= import('three/examples/jsm/controls/TransformControls.js').then((m) => m.TransformControls);
  return transformControls;
}

const WIND = 0x6fc3ff;
const SINK = 0xff8a65;
const EMITTER = 0xffd54f;
const FLOW = 0x9ccc65;
/** Arrow length (m) per m/s of wind, and its bounds. */
const ARROW_PER_SPEED = 0.8;
const ARROW_MIN = 0.15;
const ARROW_MAX = 1.2;

/** The point a guide is dragged by: a wind primitive's position, an emitter's centre. */
export function anchorOf(item) {
  if (item.type === 'repulsor') return item.path[0].slice(1, 4);
  return item.position ?? item.center;
}

/** `item` moved so that its anchor is at `to` (a repulsor's whole path moves with it). */
export function moved(item, to) {
  const next = structuredClone(item);
  const from = anchorOf(item);
  const d = to.map((v, a) => v - from[a]);
  if (next.type === 'repulsor') next.path = next.path.map(([t, ...p]) => [t, ...p.map((v, a) => v + d[a])]);
  else if ('position' in next) next.position = to;
  else next.center = to;
  return next;
}

function arrow(from, dir, length, color) {
  const d = new THREE.Vector3().fromArray(dir);
  if (d.lengthSq() === 0) d.set(0, 1, 0);
  return new THREE.ArrowHelper(d.normalize(), new THREE.Vector3().fromArray(from), length, color, 0.25 * length, 0.12 * length);
}

const clampLength = (speed) => Math.min(Math.max(speed * ARROW_PER_SPEED, ARROW_MIN), ARROW_MAX);

function ring(center, axis, radius, color) {
  const points = [];
  for (let k = 0; k <= 48; k += 1) {
    const a = (k / 48) * Math.PI * 2;
    points.push(new THREE.Vector3(Math.cos(a) * radius, 0, Math.sin(a) * radius));
  }
  const line = new THREE.Line(new THREE.BufferGeometry().setFromPoints(points), new THREE.LineBasicMaterial({ color }));
  line.position.fromArray(center);
  line.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), new THREE.Vector3().fromArray(axis).normalize());
  return line;
}

function primitiveGuide(p) {
  const g = new THREE.Group();
  if (p.type === 'uniform') {
    const speed = Math.hypot(...p.velocity);
    g.add(arrow(p.position, p.velocity, clampLength(speed), WIND));
  } else if (p.type === 'source') {
    const color = p.strength >= 0 ? WIND : SINK;
    for (const d of [[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]]) {
      const len = 0.3;
      const from = p.strength >= 0 ? p.position : p.position.map((v, a) => v + d[a] * len);
      g.add(arrow(from, p.strength >= 0 ? d : d.map((v) => -v), len, color));
    }
  } else if (p.type === 'vortex') {
    const axis = new THREE.Vector3().fromArray(p.axis).normalize();
    const r = Math.max(3 * p.radius, 0.15);
    g.add(ring(p.position, p.axis, r, WIND));
    g.add(arrow(p.position.map((v, a) => v - axis.getComponent(a) * 0.3), p.axis, 0.6, WIND));
    // Arrowheads along the ring show the sense of rotation (Γ > 0: right-handed about the axis).
    const q = new THREE.Quaternion().setFromUnitVectors(new THREE.Vector3(0, 1, 0), axis);
    for (let k = 0; k < 4; k += 1) {
      const a = (k / 4) * Math.PI * 2;
      const at = new THREE.Vector3(Math.cos(a) * r, 0, Math.sin(a) * r).applyQuaternion(q).add(new THREE.Vector3().fromArray(p.position));
      const tangent = new THREE.Vector3(Math.sin(a), 0, -Math.cos(a)).applyQuaternion(q).multiplyScalar(Math.sign(p.strength) || 1);
      g.add(arrow(at.toArray(), tangent.toArray(), 0.12, WIND));
    }
  } else if (p.type === 'repulsor') {
    const keys = p.path.map(([, x, y, z]) => new THREE.Vector3(x, y, z));
    const points = keys.length > 1 ? new THREE.CatmullRomCurve3(keys).getPoints(64) : keys;
    g.add(new THREE.Line(new THREE.BufferGeometry().setFromPoints(points), new THREE.LineDashedMaterial({ color: WIND, dashSize: 0.05, gapSize: 0.04 })));
    g.children[0].computeLineDistances();
  }
  return g;
}

function emitterGuide(e) {
  if (e.shape === 'disk') return ring(e.center, e.normal, e.radius, EMITTER);
  let geometry;
  if (e.shape === 'sphere') geometry = new THREE.EdgesGeometry(new THREE.IcosahedronGeometry(e.radius, 1));
  else if (e.shape === 'box') geometry = new THREE.EdgesGeometry(new THREE.BoxGeometry(...e.size));
  else geometry = new THREE.EdgesGeometry(new THREE.OctahedronGeometry(0.03));
  const lines = new THREE.LineSegments(geometry, new THREE.LineBasicMaterial({ color: EMITTER }));
  lines.position.fromArray(e.center);
  return lines;
}

/**
 * The flow's box (paper §7: the grid the large scales are solved on): its twelve edges, and each
 * closed face (a wall the air does not cross) a faint pane.
 */
export function flowGuide(flow) {
  const [x0, y0, z0, x1, y1, z1] = flow.box;
  const size = [x1 - x0, y1 - y0, z1 - z0];
  const guide = new THREE.Group();
  guide.position.set((x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2);
  const lines = new THREE.LineSegments(
    new THREE.EdgesGeometry(new THREE.BoxGeometry(...size)),
    new THREE.LineDashedMaterial({ color: FLOW, dashSize: 0.06, gapSize: 0.04 }),
  );
  lines.computeLineDistances();
  guide.add(lines);
  closedAxes(flow.faces).forEach((closed, a) => {
    if (!closed) return;
    // A pane across axis a: a plane in x and y (its width along x, its height along y), turned
    // to face along a (across x its width then lies along z; across y its height along z).
    const [width, height] = [[size[2], size[1]], [size[0], size[2]], [size[0], size[1]]][a];
    for (const side of [-0.5, 0.5]) {
      const pane = new THREE.Mesh(
        new THREE.PlaneGeometry(width, height),
        new THREE.MeshBasicMaterial({ color: FLOW, transparent: true, opacity: 0.08, side: THREE.DoubleSide, depthWrite: false }),
      );
      if (a === 0) pane.rotation.y = Math.PI / 2;
      if (a === 1) pane.rotation.x = -Math.PI / 2;
      pane.position.setComponent(a, side * size[a]);
      guide.add(pane);
    }
  });
  return guide;
}

/** A guide of something switched off (`enabled: false`) is drawn faint. */
function faintIfOff(guide, enabled) {
  if (!enabled) {
    guide.traverse((o) => {
      if (o.material) {
        o.material.transparent = true;
        o.material.opacity *= 0.3;
      }
    });
  }
  return guide;
}

export class GuidesLayer {
  /** The drag handle (TransformControls), null until its code has come. */
  #drag = null;
  /** Its helper, drawn in the guides' scene, null until then. */
  #helper = null;
  /** Whether the drag handle's code was asked for. */
  #asked = false;

  /**
   * @param {THREE.Scene} scene
   * @param {THREE.Camera} camera
   * @param {HTMLCanvasElement} canvas
   * @param {import('three/examples/jsm/controls/OrbitControls.js').OrbitControls} orbit
   */
  constructor(scene, camera, canvas, orbit) {
    this.group = new THREE.Group();
    this.group.visible = false;
    scene.add(this.group);
    this.handle = new THREE.Object3D();
    scene.add(this.handle);
    this.overlay = scene;
    this.camera = camera;
    this.canvas = canvas;
    this.orbit = orbit;
    this.key = '';
    this.selected = null;
    /** Called with (selection, [x, y, z]) when a drag ends. */
    this.onMoved = null;
  }

  /** Fetches the drag handle's code once and makes the handle; it then follows the selection and the guides' visibility. */
  #wantDrag() {
    if (this.#asked) return;
    this.#asked = true;
    loadTransformControls().then((TransformControls) => {
      const drag = new TransformControls(this.camera, this.canvas);
      drag.setSize(0.8);
      drag.enabled = false;
      this.#helper = drag.getHelper();
      this.#helper.visible = false;
      this.overlay.add(this.#helper);
      drag.addEventListener('dragging-changed', (event) => {
        this.orbit.enabled = !event.value;
        if (!event.value && this.selected) this.onMoved?.(this.selected, this.handle.position.toArray());
      });
      this.#drag = drag;
      this.select(this.selected);
    });
  }

  /** Rebuilds the guides when the scene's primitives, emitters or flow change (a new scene is compared once). */
  update(scene) {
    if (scene === this.scene) return;
    const key = JSON.stringify([scene.wind, scene.emitters, scene.flow ?? null]);
    if (key === this.key) {
      this.scene = scene;
      return;
    }
    this.key = key;
    for (const child of [...this.group.children]) {
      this.group.remove(child);
      child.traverse((o) => { o.geometry?.dispose(); o.material?.dispose(); });
    }
    for (const p of scene.wind) this.group.add(faintIfOff(primitiveGuide(p), p.enabled));
    for (const e of scene.emitters) this.group.add(faintIfOff(emitterGuide(e), e.enabled));
    if (scene.flow) this.group.add(faintIfOff(flowGuide(scene.flow), scene.flow.enabled));
    this.scene = scene;
    this.select(this.selected);
  }

  /** Shows or hides the guides and the drag handle. */
  setVisible(visible) {
    this.group.visible = visible;
    if (visible) this.#wantDrag();
    if (!this.#helper) return;
    this.#helper.visible = visible && this.selected !== null;
    this.#drag.enabled = this.#helper.visible;
  }

  /** Attaches the drag handle to `selection` ({list: 'wind'|'emitters', index}) or to nothing. */
  select(selection) {
    const item = selection && this.scene?.[selection.list]?.[selection.index];
    this.selected = item ? selection : null;
    if (item) {
      this.handle.position.fromArray(anchorOf(item));
      this.#wantDrag();
      this.#drag?.attach(this.handle);
    } else {
      this.#drag?.detach();
    }
    this.setVisible(this.group.visible);
  }
}
