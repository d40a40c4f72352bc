// How the player's frames go: the frames drawn per second (`stats().fps`), what holds the rate
// down (`stats().limitedBy`), the time a frame takes (`frameMs`, which sets how many steps a
// frame may take), and the pace the view itself keeps up, which the resolution governor follows
// (`resolution.js`) while playing as well as while the camera moves.

/** `stats().fps` counts the frames begun in this window (ms): 0.2 frames a second shows as 0.2. */
const RATE_WINDOW_MS = 5000;
/**
 * A frame is late once the time since the last one exceeds this many of the window's mean
 * intervals: only then does the open interval lower the rate (a frame whose step or drawing
 * takes long does not), and once the next frame is late with none begun in the window, the
 * rate is zero.
 */
const LATE = 1.5;

export class FramePace {
  /**
   * When the last frames began (ms), the newest last: those within `RATE_WINDOW_MS` and the one
   * before them (where their first interval began). Begun, not ended: a frame cap spaces the
   * beginnings, while a frame's end comes as late as its step and its drawing take.
   */
  #times = [];
  /** When the count began (ms): a window shorter than `RATE_WINDOW_MS` until it has run that long. */
  #since = null;
  /** When the last frame was drawn (ms). */
  #lastDrawn = -Infinity;
  /** Frames a second the view itself keeps up (smoothed): the governor's input. */
  #pace = 0;
  /** How long the frame being drawn waited for the worker's step (ms), and the share of recent frames spent so. */
  #waited = 0;
  #waitShare = 0;

  /**
   * @param {object} stats the player's counters: `fps`, `frames` and `limitedBy` are kept here
   * @param {import('./resolution.js').ResolutionGovernor} resolution
   */
  constructor(stats, resolution) {
    this.stats = stats;
    this.resolution = resolution;
    /** A frame's time (ms, smoothed) from one drawn frame to the next while they come back to back. */
    this.frameMs = 1000 / 60;
    /**
     * The time (ms, smoothed) from one drawn frame to the next less its wait for the worker's
     * step: how long the worker may step for a frame without being the one that paces it.
     */
    this.freeMs = 1000 / 60;
  }

  /** The view's own frames a second (smoothed; 0 before the first frame). */
  get pace() {
    return this.#pace;
  }

  /** The frame being drawn waited `ms` for the worker's step. */
  waitedFor(ms) {
    this.#waited = ms;
  }

  /** The loop found nothing to do at `now` (rAF ms). */
  idle(now) {
    this.#countRate(now);
  }

  /** At `now` (ms): the rate falls while nothing is drawn. */
  tick(now) {
    this.#countRate(now);
  }

  /**
   * Counts a frame drawn from `start` to `end` (ms), while `playing`. `stats().fps` is the
   * frames begun in the last five seconds per second of the intervals that bring them (from the
   * frame before them), an interval still open counted once the next frame is late; so it says
   * what the screen shows, however slow, and a steady rate shows as itself; `stats().limitedBy`
   * what holds the rate down: `worker` (frames spend most of their time waiting for the step),
   * `view` (drawing takes the time), `display` (the frames keep up with the display) or `paused`.
   * The view's own pace is a frame's time less its wait for the worker, so the resolution
   * follows the view's cost whether the scene plays or the camera moves. Returns whether the
   * governor changed the resolution (the view's resolution follows it).
   */
  drawn(start, end, { playing }) {
    this.#times.push(start);
    this.#since ??= start;
    this.stats.frames += 1;
    this.#countRate(end);
    // Back to back: this frame began soon after the last one ended.
    const busy = start - this.#lastDrawn < 100;
    const ms = busy ? end - this.#lastDrawn : end - start;
    const interval = Math.min(end - this.#lastDrawn, 1000);
    if (playing && interval > 0) this.freeMs = 0.7 * this.freeMs + 0.3 * Math.max(interval - this.#waited, 1);
    this.#lastDrawn = end;
    if (busy) this.frameMs = 0.7 * this.frameMs + 0.3 * ms;
    const own = Math.max(ms - this.#waited, 0.5);
    // The share of the frame spent waiting for the worker's step (smoothed).
    if (ms > 0) this.#waitShare = 0.8 * this.#waitShare + 0.2 * Math.min(this.#waited / ms, 1);
    this.#waited = 0;
    this.stats.limitedBy = !playing ? 'paused'
      : this.#waitShare > 0.5 ? 'worker'
        : this.stats.fps < 0.9 * this.resolution.target ? 'view' : 'display';
    // Only frames drawn back to back tell the view's pace (a lone frame's time is the time to
    // ask for it, not for the GPU to draw it).
    if (!busy) return false;
    this.#pace = this.#pace > 0 ? 0.7 * this.#pace + 0.3 * (1000 / own) : 1000 / own;
    return this.resolution.observe(end, this.#pace);
  }

  /**
   * `stats().fps` at `now` (ms): the frames begun in the last five seconds over the time their
   * intervals span, and the open one since the last frame beyond `LATE` intervals. With a
   * single frame, over the time since the count began (at least a second); with none in the
   * window, zero unless the last one is only a little late for a slow, steady rate.
   */
  #countRate(now) {
    const times = this.#times;
    const start = now - RATE_WINDOW_MS;
    while (times.length > 2 && times[1] <= start) times.shift();
    const last = times.at(-1);
    if (this.#since === null || last === undefined) {
      this.stats.fps = 0;
      return;
    }
    if (times.length === 1) {
      const seconds = Math.min(RATE_WINDOW_MS, Math.max(now - this.#since, 1000)) / 1000;
      this.stats.fps = last > start ? 1 / seconds : 0;
      return;
    }
    const intervals = times.length - 1;
    const span = last - times[0];
    const mean = span / intervals;
    const open = now - last;
    if (last <= start && open > LATE * mean) {
      this.stats.fps = 0;
      return;
    }
    this.stats.fps = (1000 * intervals) / Math.max(span + Math.max(open - LATE * mean, 0), 1);
  }
}
