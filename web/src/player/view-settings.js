// How a player draws: the view shown (one of VIEWS) and the marched views' quality, the
// canvas's resolution (held to the frame rate by `resolution.js`, or fixed), the most frames a
// second, and what is drawn over the gas (the wind guides, the drag handle, the wind slice).
// Each setting is checked here, by name and range; who chose it is `lighter.js`'s to know.

import { EXACT_QUALITY } from '../views/exact/exact-frame.js';
import { moved } from '../views/guides-layer.js';
import { VIEWS } from '../views/modes.js';
import { SLICE_PLANES } from '../views/wind-slice-layer.js';
import { ResolutionGovernor, startScale } from './resolution.js';

/** The qualities of the marched views (the exact march's `EXACT_QUALITY`, the volume's `VOLUME_QUALITY`). */
export const QUALITIES = Object.keys(EXACT_QUALITY);
/** The wind slice's planes (`slicePlane`): 'off', 'xy', 'xz', 'yz'. */
export { SLICE_PLANES };

/** `mode` if it is one of VIEWS, else an Error naming `method`. */
export function checkView(method, mode) {
  if (!VIEWS.includes(mode)) throw new Error(`${method}: the view must be one of ${VIEWS.join(', ')} (got ${mode})`);
  return mode;
}

/** `quality` if it is one of QUALITIES, else an Error naming `method`. */
export function checkQuality(method, quality) {
  if (!QUALITIES.includes(quality)) throw new Error(`${method}: the quality must be one of ${QUALITIES.join(', ')} (got ${quality})`);
  return quality;
}

/** `scale` if it is 'auto' or a scale in (0, 1], else an Error. */
export function checkResolution(scale) {
  if (scale !== 'auto' && !(Number.isFinite(Number(scale)) && Number(scale) > 0 && Number(scale) <= 1)) {
    throw new Error(`setResolution: the resolution must be 'auto' or a scale in (0, 1] (got ${scale})`);
  }
  return scale;
}

export class ViewSettings {
  /** The 3-D view (`views/scene-view.js`). */
  #view;
  /** Sizes the canvas again (the resolution or the view changed), and redraws at the next frame. */
  #resize;
  #invalidate;
  /** The view shown: one of VIEWS. */
  #mode;
  /** The marched views' quality: one of QUALITIES. */
  #quality;
  /** The most frames a second to draw (`setMaxFps`). */
  #maxFps = Infinity;
  /**
   * Holds the frame rate by scaling the canvas's internal resolution and the real-time
   * view's voxels (`stats().scale`), starting lower on phone-sized screens.
   */
  #resolution = new ResolutionGovernor({ start: startScale(window.innerWidth, window.innerHeight) });

  /**
   * @param {import('../views/scene-view.js').SceneView} view
   * @param {{resize: () => void, invalidate: () => void}} changed
   */
  constructor(view, { resize, invalidate }) {
    this.#view = view;
    this.#resize = resize;
    this.#invalidate = invalidate;
  }

  /** The resolution governor: its scale is the canvas's drawing buffer over its box. */
  get resolution() {
    return this.#resolution;
  }

  get mode() {
    return this.#mode;
  }

  get quality() {
    return this.#quality;
  }

  get maxFps() {
    return this.#maxFps;
  }

  /** Applies `value` to the setting `name` ('view', 'quality' or 'resolution'), whoever chose it. */
  apply(name, value) {
    if (name === 'view') {
      this.#mode = value;
      this.#resize();
    } else if (name === 'quality') {
      this.#quality = value;
      this.#invalidate();
    } else if (name === 'resolution') {
      this.#resolution.set(value);
      this.#resize();
    }
  }

  /**
   * Draws in `mode` at `quality` for a while (an offscreen picture) without anyone choosing
   * them; returns what was shown before, to be given back the same way.
   */
  drawAs({ mode, quality }) {
    const before = { mode: this.#mode, quality: this.#quality };
    this.#mode = mode;
    this.#quality = quality;
    return before;
  }

  /** The resolution's setting: 'auto' or a fixed scale. */
  get resolutionSetting() {
    return this.#resolution.mode === 'auto' ? 'auto' : this.#resolution.scale;
  }

  /** Draws at most `fps` frames a second (see `Player.setMaxFps`). */
  setMaxFps(fps) {
    if (!(fps === Infinity || (Number.isFinite(fps) && fps >= 0.1 && fps <= 240))) {
      throw new Error(`setMaxFps: the frame rate must be between 0.1 and 240 frames a second, or Infinity (got ${fps})`);
    }
    this.#maxFps = fps;
  }

  /** Whether the wind guides (and the drag handle, and the wind slice) are drawn. */
  get guides() {
    return this.#view.showGuides;
  }

  set guides(on) {
    this.#view.showGuides = on;
    this.#invalidate();
  }

  /** The wind slice's plane ('off', 'xy', 'xz', 'yz') and its offset along the normal (m). */
  get slicePlane() {
    return this.#view.slicePlane;
  }

  set slicePlane(plane) {
    this.#view.slicePlane = plane;
    this.#invalidate();
  }

  get sliceOffset() {
    return this.#view.sliceOffset;
  }

  set sliceOffset(d) {
    this.#view.sliceOffset = d;
    this.#invalidate();
  }

  /** The wind slice's colour scale while it is drawn: `{plane, maxSpeed}` (m/s), else null. */
  sliceLegend() {
    const slice = this.#view.windSlice;
    return slice.group.visible ? { plane: this.#view.slicePlane, maxSpeed: slice.maxSpeed } : null;
  }

  /** The real-time view's density volume in voxels `[nx, ny, nz]`, when that view is shown. */
  volumeDims() {
    return this.#mode === 'raymarch' ? this.#view.volume.grid?.dims ?? null : null;
  }

  /** Picks the wind primitive or emitter (`{list, index}`) the drag handle moves, or none. */
  selectHandle(selection) {
    this.#view.guides.select(selection);
    if (selection) this.#view.showGuides = true;
    this.#invalidate();
  }

  /**
   * Calls `fn(selection, item)` when the drag handle has moved its item: `item` is a copy of
   * `scene()`'s wind primitive or emitter with its anchor where the handle was let go (m, to
   * the millimetre; a repulsor's whole path moves with it).
   */
  onHandleMoved(scene, fn) {
    this.#view.guides.onMoved = (selection, to) => {
      const item = scene()?.[selection.list]?.[selection.index];
      if (item) fn(selection, moved(item, to.map((v) => Math.round(v * 1000) / 1000)));
    };
  }

  /** Orbits or zooms for a key pressed on the view (arrows, + and −); true when it did. */
  orbitKey(event) {
    const handled = this.#view.limits.key(event);
    if (handled) this.#invalidate();
    return handled;
  }
}
