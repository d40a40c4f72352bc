// Holds a frame rate by scaling the internal resolution of the marched views: the canvas's
// drawing buffer is its box times `scale`, and the browser stretches it to the box; the
// real-time view's volumes follow it too (voxels scale³ as many, `VolumeLayer.prepare`). Below the
// target the scale falls at once; above it, it rises slowly and not straight back to where it
// last fell from, so it settles instead of oscillating. Small screens (phones) start lower.

/** The scale a view starts at on small screens (either side of the viewport at most 640 px). */
export const SMALL_SCREEN_SCALE = 0.5;

/**
 * The starting scale for a viewport of `width × height` CSS pixels: `SMALL_SCREEN_SCALE` on a
 * phone-sized screen (a side of at most 640 px, in either orientation), else 1.
 */
export function startScale(width, height) {
  return Math.min(width, height) <= 640 ? SMALL_SCREEN_SCALE : 1;
}

export class ResolutionGovernor {
  /**
   * @param {{target?: number, min?: number, max?: number, start?: number}} options frames per
   *   second to hold, the range of the scale, and the scale to start at (and to go back to on
   *   `set('auto')`; `max` unless given)
   */
  constructor({ target = 60, min = 0.25, max = 1, start = max } = {}) {
    Object.assign(this, { target, min, max });
    this.start = Math.min(max, Math.max(min, start));
    /** `auto`, or a fixed scale. */
    this.mode = 'auto';
    this.scale = this.start;
    this.lastChange = -Infinity;
    this.ceiling = max;
    this.ceilingUntil = -Infinity;
  }

  /**
   * Fixes the scale (a number in (0, 1]) or lets it follow the frame rate ('auto', from the
   * starting scale).
   */
  set(mode) {
    this.mode = mode;
    this.scale = mode === 'auto' ? this.start : Math.min(this.max, Math.max(this.min, Number(mode)));
    this.lastChange = -Infinity;
  }

  /**
   * Takes the frame rate measured at `now` (ms); returns true when the scale changed.
   * @param {number} now @param {number} fps drawn frames per second
   */
  observe(now, fps) {
    if (this.mode !== 'auto' || now - this.lastChange < 500) return false;
    if (fps < 0.85 * this.target && this.scale > this.min) {
      this.ceiling = this.scale;
      this.ceilingUntil = now + 10_000;
      this.scale = Math.max(this.min, this.scale * 0.8);
      this.lastChange = now;
      return true;
    }
    const cap = now < this.ceilingUntil ? 0.95 * this.ceiling : this.max;
    if (fps > 0.95 * this.target && this.scale < cap && now - this.lastChange > 2000) {
      this.scale = Math.min(cap, this.scale * 1.15);
      this.lastChange = now;
      return true;
    }
    return false;
  }
}
