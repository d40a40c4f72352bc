// How the player's frames go: the frames drawn per second (`stats().fps`), what holds the rate
// down (`stats().limitedBy`), and the pace the view keeps up, which the resolution governor
// follows (`resolution.js`).

/** A frame that waited longer than this (ms) for the worker's step was paced by the worker. */
const WORKER_WAIT_MS = 2;

export class FramePace {
  /** When the last frames were drawn (ms), the newest last: `stats().fps` counts them. */
  #times = [];
  /** When the loop last found nothing to do (rAF ms). */
  #idleAt = -Infinity;
  /** When the last frame was drawn (ms). */
  #lastDrawn = 0;
  /** Frames per second the view keeps up, from frames drawn back to back (the governor's input). */
  #pace = 0;
  /** How long the frame being drawn waited for the worker (ms), and the share of recent frames spent so. */
  #waited = 0;
  #waitShare = 0;

  /**
   * @param {object} stats the player's counters: `fps`, `frames` and `limitedBy` are kept here
   * @param {import('./resolution.js').ResolutionGovernor} resolution
   */
  constructor(stats, resolution) {
    this.stats = stats;
    this.resolution = resolution;
  }

  /** The frame being drawn waited `ms` for the worker's step. */
  waitedFor(ms) {
    this.#waited = ms;
  }

  /** The loop found nothing to do at `now` (rAF ms). */
  idle(now) {
    this.#idleAt = now;
  }

  /** At `now` (ms): frames stop counting while nothing is drawn. */
  tick(now) {
    if (now - (this.#times.at(-1) ?? -Infinity) > 2000 && this.stats.fps > 0) this.#countRate(now);
  }

  /**
   * Counts a frame drawn from `start` to `end` (ms), while `playing`. `stats().fps` is the
   * number of frames drawn in the last second (the last two while the rate is low), so it says
   * what the screen shows; `stats().limitedBy` what holds the rate down: `worker` (frames spend
   * most of their time waiting for the step), `view` (drawing takes the time), `display` (the
   * frames keep up with the display) or `paused`. The resolution follows the pace of frames the
   * view itself paced: drawn back to back, not after an idle animation frame (a scene stepping
   * slower than the display) nor after waiting for the worker. Returns whether the governor
   * changed the resolution (when `scaled`, the view's resolution follows it).
   */
  drawn(start, end, { playing, scaled }) {
    const times = this.#times;
    times.push(end);
    while (times.length > 2 && times[0] < end - 2000) times.shift();
    this.stats.frames += 1;
    this.#countRate(end);
    const busy = start - this.#lastDrawn < 100;
    const seconds = (busy ? end - this.#lastDrawn : end - start) / 1000;
    // The share of the frame spent waiting for the worker's step (smoothed).
    if (seconds > 0) this.#waitShare = 0.8 * this.#waitShare + 0.2 * Math.min(this.#waited / (1000 * seconds), 1);
    const paced = this.#idleAt > this.#lastDrawn || this.#waited > WORKER_WAIT_MS;
    this.#waited = 0;
    this.#lastDrawn = end;
    this.stats.limitedBy = !playing ? 'paused'
      : this.#waitShare > 0.5 ? 'worker'
        : this.stats.fps < 0.9 * this.resolution.target ? 'view' : 'display';
    if (!(seconds > 0) || paced) return false;
    this.#pace = this.#pace > 0 && busy ? 0.8 * this.#pace + 0.2 / seconds : 1 / seconds;
    return scaled && this.resolution.observe(end, this.#pace);
  }

  /** Frames drawn per second at `now` (ms): those of the last second, or of two when few. */
  #countRate(now) {
    const times = this.#times;
    const inLast = (ms) => times.filter((t) => t > now - ms).length;
    const recent = inLast(1000);
    this.stats.fps = recent >= 10 ? recent : inLast(2000) / 2;
  }
}
