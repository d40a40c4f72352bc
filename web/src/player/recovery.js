// What a player does when something under it fails: the engine worker (restarted by its
// client, `engine/client.js`) gets the scene back, or the last scene that ran well, and a scene
// that keeps stopping the engine halts the player instead of sending it into a loop of
// restarts; a lost GPU context is waited for, and reported once it stays lost.

/** A scene that has run this many steps without the engine failing is one to go back to. */
const GOOD_AFTER_STEPS = 120;

/** How long (ms) a lost GPU context may stay lost before the player reports it. */
const CONTEXT_GRACE_MS = 3000;

export class Recovery {
  /** The player's hooks (`onFault`, `onMessage`). */
  #hooks;
  /** Loads a scene's JSON text again in its turn. */
  #reload;
  /** The running scene's normalised JSON text, or null. */
  #sceneJson;
  /** Failures of the engine per scene (its normalised JSON text). */
  #failures = new Map();
  /** The last scene that ran well (its text). */
  #lastGood = null;
  /** Steps taken since the current scene was loaded (it is good after `GOOD_AFTER_STEPS`). */
  #stepsSinceLoad = 0;
  /** Why the player stopped (the engine keeps failing on its scene), or null. */
  #halted = null;
  /** Whether the view's GPU context is lost (drawing waits for it to come back). */
  #contextLost = false;
  #contextTimer = 0;

  /**
   * @param {object} hooks the player's hooks
   * @param {{reload: (text: string) => Promise<unknown>, sceneJson: () => string | null}} parts
   */
  constructor(hooks, { reload, sceneJson }) {
    this.#hooks = hooks;
    this.#reload = reload;
    this.#sceneJson = sceneJson;
  }

  /** Why the player stopped (its scene stopped the engine twice), or null. */
  get halted() {
    return this.#halted;
  }

  /** Whether the view's GPU context is lost. */
  get contextLost() {
    return this.#contextLost;
  }

  /** A scene was loaded: it has taken no steps yet, and the player goes on. */
  loaded() {
    this.#halted = null;
    this.#stepsSinceLoad = 0;
  }

  /** The running scene took `steps` steps more. */
  stepped(steps) {
    this.#stepsSinceLoad += steps;
    const json = this.#sceneJson();
    if (this.#stepsSinceLoad >= GOOD_AFTER_STEPS && json) this.#lastGood = json;
  }

  /** Reports that the player cannot go on as it is. */
  fault(message) {
    this.#hooks.onFault?.(message);
    if (!this.#hooks.onFault) this.#hooks.onMessage?.(message);
  }

  /**
   * After the engine failed (and was restarted): reloads the scene that ran, unless it has made
   * the engine fail before, in which case it goes back to the last scene that ran well, or stops
   * with a message; a scene never sends the engine into a loop of restarts.
   */
  engineRestarted(reason, { recycled = false } = {}) {
    const json = this.#sceneJson();
    if (!json) return;
    // In its turn, so that steps asked for meanwhile wait for the reloaded scene.
    const reload = (text) => this.#reload(text).catch((e) => this.#hooks.onMessage?.(e.message));
    if (recycled) {
      // The engine was restarted to give back memory, not because this scene failed.
      this.#hooks.onMessage?.(`The engine was restarted to give back memory (${reason}); the scene starts again.`);
      reload(json);
      return;
    }
    const failures = (this.#failures.get(json) ?? 0) + 1;
    this.#failures.set(json, failures);
    if (failures === 1) {
      reload(json);
    } else if (this.#lastGood && this.#lastGood !== json) {
      this.#hooks.onMessage?.(`This scene stopped the engine twice (${reason}); back to the last scene that ran.`);
      reload(this.#lastGood);
    } else {
      this.fault(`this scene stopped the engine twice (${reason}); load another scene`);
      this.#halted = reason;
    }
  }

  /**
   * Follows `view`'s GPU context: `lost()` when it is lost, `restored()` when it comes back; a
   * context that stays lost longer than `CONTEXT_GRACE_MS` is a fault.
   */
  watchContext(view, { lost, restored }) {
    view.onContextLost = () => {
      this.#contextLost = true;
      lost();
      clearTimeout(this.#contextTimer);
      this.#contextTimer = setTimeout(() => this.fault('the view lost its GPU context and the browser did not give it back (too many 3-D views open at once, or the GPU was reset)'), CONTEXT_GRACE_MS);
    };
    view.onContextRestored = () => {
      clearTimeout(this.#contextTimer);
      this.#contextLost = false;
      restored();
    };
  }

  /** The player ended: no fault is reported any more for its context. */
  dispose() {
    clearTimeout(this.#contextTimer);
  }
}
