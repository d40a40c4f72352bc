// The <wind-field> element's loading (a feature of the element, after model-viewer's
// features/loading): nothing heavy until the element nears the viewport (`loading="lazy"`, the
// default) or at once (`loading="eager"`, or `load()`); the poster until the scene is ready; the
// Player, imported once for every element on the page, mounted on the element's canvas; the
// scene the attributes name, loaded one after another and simulated to `poster-time` unless
// playing; `ready`, `loaded`, and the `ready` and `error` events.

import { removedError } from '../engine/removed.js';
import {
  $api, $failed, $hideStatus, $parts, $player, $run, $sceneUrl, $showMessage, $showStatus, $updateControls,
  $wantsPlaying, $whenReady,
} from './internals.js';

/** How far beyond the viewport a lazy player starts loading. */
const LOAD_MARGIN = '400px 0px';
/** How long (ms) an engine's notice stays (a failed load's stays until the next load). */
const NOTICE_MS = 8000;

let playerCode = null;
/** The player's code, imported once for every element on the page (a failed import is retried). */
function loadPlayerCode() {
  playerCode ??= import('../player/player.js').catch((err) => {
    playerCode = null;
    throw new Error(`could not load the player's code (${err?.message ?? err})`);
  });
  return playerCode;
}

let approach = null;
/** One observer for every lazy element: starts each as it nears the viewport. */
function approachObserver() {
  approach ??= new IntersectionObserver((entries) => {
    for (const e of entries) if (e.isIntersecting) e.target.load();
  }, { rootMargin: LOAD_MARGIN });
  return approach;
}

/** A promise with its settlers and whether it has settled. Rejections are never unhandled. */
function deferred() {
  const d = { settled: false };
  d.promise = new Promise((resolve, reject) => {
    d.resolve = (v) => { d.settled = true; resolve(v); };
    d.reject = (e) => { d.settled = true; reject(e); };
  });
  d.promise.catch(() => {});
  return d;
}

export const LoadingMixin = (Base) => class extends Base {
  #observers = [];
  /** Counts starts: work begun for an earlier start (before a disconnect) is dropped. */
  #session = 0;
  #starting = false;
  #ready = deferred();
  /** Counts scene loads from the attributes: only the latest settles `ready`. */
  #ticket = 0;
  /** Scene loads run one after another. */
  #queue = Promise.resolve();
  #failed = false;
  #noticeTimer = 0;
  /** The removal's end of the player, waiting to see whether the element comes back (a move). */
  #teardownTimer = 0;

  constructor() {
    super();
    const poster = this[$parts].poster;
    poster.addEventListener('error', () => { poster.hidden = true; });
  }

  /** Resolves once the current scene is loaded and drawn (at `poster-time` when not playing). */
  get ready() { return this.#ready.promise; }
  /** Whether the current scene is ready. */
  get loaded() { return this.#ready.settled && !this.#failed && this[$player] !== null; }
  get [$failed]() { return this.#failed; }

  connectedCallback() {
    super.connectedCallback();
    // Put back in the same task it was taken out in (a move): the player goes on as it was.
    clearTimeout(this.#teardownTimer);
    this.#updatePoster();
    if (this[$player] || this.#starting) return;
    if (this.loading === 'eager') this.load();
    else approachObserver().observe(this);
  }

  /**
   * Taken out of the document: a move (`append` elsewhere, a framework's reorder) puts it back
   * before the task ends and keeps the player running; otherwise the player ends (`#teardown`).
   */
  disconnectedCallback() {
    super.disconnectedCallback();
    approach?.unobserve(this);
    clearTimeout(this.#teardownTimer);
    this.#teardownTimer = setTimeout(() => {
      if (!this.isConnected) this.#teardown();
    });
  }

  /**
   * Removed for good: every call waiting or in flight rejects with an AbortError ("the player was
   * removed from the page"), the worker ends and the GPU's objects and context are let go. Put
   * back later, the element starts afresh.
   */
  #teardown() {
    for (const o of this.#observers) o.disconnect();
    this.#observers = [];
    this.#session += 1;
    this.#starting = false;
    this[$player]?.dispose();
    this[$player] = null;
    this[$api] = null;
    this.#queue = Promise.resolve();
    if (!this.#ready.settled) this.#ready.reject(removedError());
    this.#ready = deferred();
    this.#failed = false;
  }

  attributeChangedCallback(name, before, after) {
    super.attributeChangedCallback(name, before, after);
    if (before === after) return;
    const player = this[$player];
    if (name === 'src' || name === 'preset') {
      if (player) this.#loadScene();
    } else if (name === 'poster') {
      this.#updatePoster();
    } else if (name === 'loading') {
      this.#updatePoster();
      if (after === 'eager' && this.isConnected) this.load();
    } else if (name === 'stir') {
      player?.setStirring(this.stir);
    } else if (name === 'view') {
      player?.setView(this.view);
    }
  }

  /**
   * Starts loading now, whatever `loading` says (a lazy element calls this as it nears the
   * viewport). Does nothing if started already or not in a document.
   */
  load() {
    if (this[$player] || this.#starting || !this.isConnected) return;
    approach?.unobserve(this);
    this.#starting = true;
    const session = this.#session;
    this[$showStatus]('Loading…');
    loadPlayerCode().then(({ Player }) => {
      if (session !== this.#session) return;
      this.#starting = false;
      try {
        this.#mount(Player);
      } catch (err) {
        // No WebGL2, most often: the player cannot draw here.
        this.#fail(new Error(`could not start the player: ${err?.message ?? err}`));
        return;
      }
      this.#loadScene();
    }, (err) => {
      if (session !== this.#session) return;
      this.#starting = false;
      this.#fail(err);
    });
  }

  #mount(Player) {
    const p = this[$parts];
    // The engine's notices (a failed worker restarts with the scene) fade; a failed load's stay.
    const notify = (text) => {
      this[$showMessage](text);
      clearTimeout(this.#noticeTimer);
      this.#noticeTimer = setTimeout(() => { if (!this.#failed) p.message.hidden = true; }, NOTICE_MS);
    };
    const player = new Player(p.canvas, {
      playing: false,
      onProgress: (progress, stage) => {
        if (progress >= 1) {
          this[$hideStatus]();
          return;
        }
        p.bar.style.width = `${Math.round(progress * 100)}%`;
        this[$showStatus](`${stage} (${Math.round(progress * 100)} %)`);
      },
      // The player cannot go on (its GPU context is gone, its scene stops the engine): an error.
      onFault: (message) => this.#fail(new Error(message)),
      onMessage: notify,
      // A machine that draws in software (or slowly) gets the lighter version, and is told.
      onLighter: ({ reason, gaveUp }) => {
        notify(`${reason === 'software'
          ? 'This browser draws 3-D in software'
          : 'This machine draws 3-D slowly'}: showing a lighter version (${gaveUp.join(', ')}).`);
        // The view button names the view shown, which the lighter version may have changed.
        this[$updateControls]();
      },
    });
    // Vertical swipes scroll the page; horizontal ones (and mice) orbit.
    p.canvas.style.touchAction = 'pan-y';
    // The page's `view` is its author's choice; without it, the player's own (the lighter
    // version's points on a machine that draws in software).
    if (this.hasAttribute('view')) player.setView(this.view);
    player.setVisible(false);
    player.setStirring(this.stir);
    this[$player] = player;
    this[$api] = player.api(this.ready);
    const resize = new ResizeObserver(() => player.resize());
    resize.observe(this);
    const visibility = new IntersectionObserver((entries) => {
      player.setVisible(entries.some((e) => e.isIntersecting));
    });
    visibility.observe(this);
    this.#observers = [resize, visibility];
  }

  /** Loads the scene the attributes name (serially); settles `ready` if it is still the latest. */
  #loadScene() {
    if (this.#ready.settled) this.#ready = deferred();
    const ready = this.#ready;
    const ticket = ++this.#ticket;
    const session = this.#session;
    this.#failed = false;
    this[$parts].message.hidden = true;
    this[$run](async (player) => {
      if (ticket !== this.#ticket) return;
      player.setPlaying(false);
      const scene = await player.loadUrl(this[$sceneUrl]().href);
      const steps = this[$wantsPlaying]() ? 0 : Math.round(this.posterTime / scene.simulation.dt);
      if (steps > 0) {
        this[$showStatus](`Simulating ${this.posterTime} s…`);
        await player.step(steps);
      }
      player.setPlaying(this[$wantsPlaying]());
    }).then(() => {
      if (ticket !== this.#ticket || session !== this.#session) return;
      this[$parts].poster.hidden = true;
      this[$hideStatus]();
      this[$updateControls]();
      ready.resolve();
      this.dispatchEvent(new CustomEvent('ready', { detail: { scene: this.getScene() } }));
    }, (err) => {
      if (ticket !== this.#ticket || session !== this.#session) return;
      this.#fail(err);
    });
  }

  /** Runs `fn(player)` after the loads queued before it. */
  [$run](fn) {
    const player = this[$player];
    const next = this.#queue.then(() => fn(player));
    this.#queue = next.catch(() => {});
    return next;
  }

  /** Waits for the scene to be ready (following reloads); resolves with the player's API, rejects when it fails. */
  async [$whenReady]() {
    if (!this.isConnected && !this[$player]) {
      throw new Error('<wind-field> is not in a document: it loads once it is connected');
    }
    for (;;) {
      const ready = this.#ready.promise;
      await ready;
      if (ready !== this.#ready.promise) continue;
      if (!this[$api]) throw removedError();
      return this[$api];
    }
  }

  #fail(err) {
    const message = err?.message ?? String(err);
    this.#failed = true;
    this[$hideStatus]();
    this[$showMessage](message);
    this[$updateControls]();
    this.#updatePoster();
    const error = err instanceof Error ? err : new Error(message);
    // A player that was ready and then failed is ready no more: `ready` rejects from now on.
    if (this.#ready.settled) this.#ready = deferred();
    this.#ready.reject(error);
    this.dispatchEvent(new CustomEvent('error', { detail: { message } }));
  }

  /**
   * The poster (the `poster` attribute's image) until the scene is loaded. A lazy element's
   * poster is fetched as the element nears the viewport (the image's own lazy loading), so a
   * player far down a page costs nothing but the loader until it is scrolled to.
   */
  #updatePoster() {
    const img = this[$parts].poster;
    const url = this.getAttribute('poster');
    if (!url || this.loaded) {
      img.hidden = true;
      return;
    }
    img.loading = this.loading === 'eager' ? 'eager' : 'lazy';
    img.src = new URL(url, document.baseURI).href;
    img.hidden = false;
  }
};
