// <wind-field>: an embeddable player (DESIGN §5). This module is only the loader: it defines
// the element, its poster, play button and attributes, and nothing heavy. The player's code
// (the engine worker with the WASM core, three.js and the views, `player.js`) is imported when
// the first element nears the viewport (`loading="lazy"`, the default) or at once
// (`loading="eager"`), once for every player on the page.
//
// Attributes (each mirrored by a property): `src` (scene JSON URL), `preset` (a name in
// scenes/), `controls`, `autoplay`, `loading` (`lazy` | `eager`), `poster` (an image URL shown
// until the scene is ready), `poster-time` (`posterTime`: seconds; without `autoplay` the scene
// is shown simulated to this time, by default the scene's `render.time`, with a play button),
// `view` (`raymarch`, the real-time volume view, by default; `points`; `exact`), `alt` (the text
// alternative; by default one naming the scene), `stir` (dragging over the view stirs the gas
// instead of orbiting it; off unless set). Events: `ready`, `error` (`detail.message`). Methods:
// the player's scripting API (getScene, setScene, editScene, setStepper, pause, play, step,
// stats, exportBlobs, captureGPU, renderReference); called before the scene is ready they wait for it (`ready`), and reject with a clear
// Error if it fails or the element is not in a document. Each element owns its worker and
// canvas, is sized by CSS (4:3 unless told otherwise), and pauses while off-screen.

const STYLE = `
:host { display: block; position: relative; width: 100%; aspect-ratio: 4 / 3; background: #0b0e11; color: #e6e9ec;
        font: 13px system-ui, sans-serif; overflow: hidden; border-radius: 6px; contain: content; }
:host([hidden]) { display: none; }
canvas, .poster { position: absolute; inset: 0; width: 100%; height: 100%; display: block; }
.poster { object-fit: cover; }
.bar { position: absolute; left: 0; bottom: 0; height: 3px; background: #7cc4ff; width: 0; transition: width 60ms linear; }
.status { position: absolute; left: 8px; top: 8px; padding: 2px 6px; border-radius: 4px; background: rgba(0, 0, 0, 0.6); }
.message { position: absolute; left: 8px; right: 8px; top: 8px; padding: 6px 8px; background: #5a1d1d; color: #fff; border-radius: 4px; }
.controls { position: absolute; left: 8px; bottom: 8px; display: flex; gap: 4px; }
button { font: inherit; color: inherit; background: rgba(0, 0, 0, 0.7); border: 1px solid #6b7785; border-radius: 4px; padding: 3px 8px; cursor: pointer; }
button:hover { background: rgba(20, 28, 36, 0.85); }
button:focus-visible { outline: 3px solid #7cc4ff; outline-offset: 2px; }
.play { position: absolute; left: 50%; top: 50%; width: 64px; height: 64px; margin: -32px 0 0 -32px; padding: 0;
        border-radius: 50%; border: 2px solid #e6e9ec; display: grid; place-items: center; }
.play svg { width: 26px; height: 26px; margin-left: 4px; fill: currentColor; }
[hidden] { display: none !important; }
`;

const TEMPLATE = `<canvas part="canvas" role="img"></canvas>
<img class="poster" part="poster" alt="" hidden>
<div class="bar" part="progress"></div>
<div class="status" part="status" role="status" hidden></div>
<button class="play" part="play-button" type="button" hidden><svg viewBox="0 0 24 24" aria-hidden="true"><path d="M5 3l16 9-16 9z"/></svg></button>
<div class="controls" part="controls" hidden>
  <button type="button" data-action="toggle">Play</button>
  <button type="button" data-action="step" aria-label="Step once">Step</button>
  <button type="button" data-action="view"></button>
</div>
<div class="message" part="message" role="alert" hidden></div>`;

/** The views, and the default. */
const VIEWS = ['raymarch', 'points', 'exact'];
const VIEW_NAMES = { raymarch: 'volume', points: 'points', exact: 'exact' };
/** Default `poster-time` (s). */
const DEFAULT_POSTER_TIME = 3;
/** How far beyond the viewport a lazy player starts loading. */
const LOAD_MARGIN = '400px 0px';

/**
 * Where presets live: `scenes/` beside the standalone `embed.js`; for a copy bundled into a
 * site (under `assets/`, or `src/` in development), `scenes/` beside the page.
 */
const MODULE_DIR = new URL(/* @vite-ignore */ './', import.meta.url);
const SCENES = /\/(src|assets)\/$/.test(MODULE_DIR.pathname)
  ? new URL('./scenes/', document.baseURI)
  : new URL('./scenes/', MODULE_DIR);

let sheet = null;
/**
 * The element's styles, one constructed stylesheet shared by every player (adopted by each
 * shadow root: no inline <style>, so pages with a strict CSP style it too).
 */
function styleSheet() {
  if (!sheet) {
    sheet = new CSSStyleSheet();
    sheet.replaceSync(STYLE);
  }
  return sheet;
}

let playerCode = null;
/** The player's code, imported once for every element on the page (a failed import is retried). */
function loadPlayerCode() {
  playerCode ??= import('./player.js').catch((err) => {
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

const reducedMotion = () => window.matchMedia?.('(prefers-reduced-motion: reduce)').matches ?? false;

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

/** The properties that mirror attributes. */
const PROPERTIES = ['src', 'preset', 'poster', 'alt', 'controls', 'autoplay', 'loading', 'posterTime', 'view', 'stir'];

/** `text` URL-decoded, or as it is when it is not valid URL encoding. */
function decoded(text) {
  try {
    return decodeURIComponent(text);
  } catch {
    return text;
  }
}

class WindFieldElement extends HTMLElement {
  static get observedAttributes() {
    return ['src', 'preset', 'controls', 'autoplay', 'loading', 'poster', 'poster-time', 'view', 'alt', 'stir'];
  }

  #parts;
  /** The Player (from `player.js`) once started. */
  #player = null;
  #api = null;
  #observers = [];
  /** Counts starts: work begun for an earlier start (before a disconnect) is dropped. */
  #session = 0;
  #starting = false;
  #ready = deferred();
  /** Counts scene loads from the attributes: only the latest settles `ready`. */
  #ticket = 0;
  /** Scene loads run one after another. */
  #queue = Promise.resolve();
  /** Whether the scene should play: null follows `autoplay` (and the reduced-motion setting). */
  #playing = null;
  #failed = false;
  #messageTimer = 0;

  constructor() {
    super();
    const root = this.attachShadow({ mode: 'open' });
    root.adoptedStyleSheets = [styleSheet()];
    root.innerHTML = TEMPLATE;
    const $ = (s) => root.querySelector(s);
    this.#parts = {
      canvas: $('canvas'), poster: $('.poster'), bar: $('.bar'), status: $('.status'),
      play: $('.play'), controls: $('.controls'), message: $('.message'),
      toggle: $('[data-action="toggle"]'), step: $('[data-action="step"]'), view: $('[data-action="view"]'),
    };
    const p = this.#parts;
    p.play.addEventListener('click', () => {
      this.play();
      this.load();
    });
    p.toggle.addEventListener('click', () => (this.#wantsPlaying() ? this.pause() : this.play()));
    p.step.addEventListener('click', () => {
      this.pause();
      this.step(1).catch(() => {});
    });
    p.view.addEventListener('click', () => { this.view = this.view === 'points' ? 'raymarch' : 'points'; });
    p.poster.addEventListener('error', () => { p.poster.hidden = true; });
  }

  // Attributes mirrored as properties.

  /** Scene JSON URL (relative to the page). */
  get src() { return this.getAttribute('src'); }
  set src(v) { this.#setString('src', v); }
  /** A preset's name (a file in `scenes/`); `default` when neither this nor `src` is set. */
  get preset() { return this.getAttribute('preset'); }
  set preset(v) { this.#setString('preset', v); }
  /** An image URL shown until the scene is ready. */
  get poster() { return this.getAttribute('poster'); }
  set poster(v) { this.#setString('poster', v); }
  /** The canvas's text alternative; by default one naming the scene. */
  get alt() { return this.getAttribute('alt'); }
  set alt(v) { this.#setString('alt', v); }
  get controls() { return this.hasAttribute('controls'); }
  set controls(v) { this.toggleAttribute('controls', Boolean(v)); }
  get autoplay() { return this.hasAttribute('autoplay'); }
  set autoplay(v) { this.toggleAttribute('autoplay', Boolean(v)); }
  /** `lazy` (the default: load when near the viewport) or `eager`. */
  get loading() { return this.getAttribute('loading') === 'eager' ? 'eager' : 'lazy'; }
  set loading(v) { this.setAttribute('loading', v); }
  /**
   * Seconds the scene is simulated to before it is shown, when not playing: the attribute, else
   * the scene's `render.time`, else 3.
   */
  get posterTime() {
    const fallback = this.#player?.state.scene?.render.time ?? DEFAULT_POSTER_TIME;
    const attribute = this.getAttribute('poster-time');
    const t = attribute === null ? fallback : Number(attribute);
    return Number.isFinite(t) && t >= 0 ? t : fallback;
  }
  set posterTime(v) { this.setAttribute('poster-time', String(v)); }
  /** Whether dragging over the view stirs the gas (instead of orbiting); off unless set. */
  get stir() { return this.hasAttribute('stir'); }
  set stir(v) { this.toggleAttribute('stir', Boolean(v)); }
  /** `raymarch` (the real-time volume view, default), `points` or `exact`. */
  get view() {
    const v = this.getAttribute('view');
    return VIEWS.includes(v) ? v : 'raymarch';
  }
  set view(v) { this.setAttribute('view', v); }

  /** Resolves once the current scene is loaded and drawn (at `poster-time` when not playing). */
  get ready() { return this.#ready.promise; }
  /** Whether the current scene is ready. */
  get loaded() { return this.#ready.settled && !this.#failed && this.#player !== null; }

  #setString(name, value) {
    if (value === null || value === undefined) this.removeAttribute(name);
    else this.setAttribute(name, String(value));
  }

  connectedCallback() {
    // Properties set before the element was defined shadow the accessors: pass them on.
    for (const name of PROPERTIES) {
      if (Object.prototype.hasOwnProperty.call(this, name)) {
        const value = this[name];
        delete this[name];
        this[name] = value;
      }
    }
    this.#updateLabel();
    this.#updatePoster();
    this.#updateControls();
    if (this.#player || this.#starting) return;
    if (this.loading === 'eager') this.load();
    else approachObserver().observe(this);
  }

  disconnectedCallback() {
    approach?.unobserve(this);
    for (const o of this.#observers) o.disconnect();
    this.#observers = [];
    this.#session += 1;
    this.#starting = false;
    this.#player?.dispose();
    this.#player = null;
    this.#api = null;
    this.#queue = Promise.resolve();
    if (this.#ready.settled) this.#ready = deferred();
    this.#failed = false;
  }

  attributeChangedCallback(name, before, after) {
    if (before === after) return;
    if (name === 'src' || name === 'preset') {
      this.#updateLabel();
      if (this.#player) this.#loadScene();
    } else if (name === 'alt') {
      this.#updateLabel();
    } else if (name === 'poster') {
      this.#updatePoster();
    } else if (name === 'controls') {
      this.#updateControls();
    } else if (name === 'autoplay') {
      if (after !== null && this.#player && !reducedMotion()) this.play();
    } else if (name === 'loading') {
      if (after === 'eager' && this.isConnected) this.load();
    } else if (name === 'stir') {
      if (this.#player) this.#player.stirring.enabled = this.stir;
    } else if (name === 'view') {
      if (this.#player) {
        this.#player.state.mode = this.view;
        this.#player.resize();
      }
      this.#updateControls();
    }
  }

  /**
   * Starts loading now, whatever `loading` says (a lazy element calls this as it nears the
   * viewport). Does nothing if started already or not in a document.
   */
  load() {
    if (this.#player || this.#starting || !this.isConnected) return;
    approach?.unobserve(this);
    this.#starting = true;
    const session = this.#session;
    this.#showStatus('Loading…');
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
    const p = this.#parts;
    const player = new Player(p.canvas, {
      playing: false,
      onProgress: (progress, stage) => {
        if (progress >= 1) {
          this.#hideStatus();
          return;
        }
        p.bar.style.width = `${Math.round(progress * 100)}%`;
        this.#showStatus(`${stage} (${Math.round(progress * 100)} %)`);
      },
      // The player cannot go on (its GPU context is gone, its scene stops the engine): an error.
      onFault: (message) => this.#fail(new Error(message)),
      // The engine's messages (a failed worker restarts with the scene) fade; a failed load's stay.
      onMessage: (text) => {
        this.#showMessage(text);
        clearTimeout(this.#messageTimer);
        this.#messageTimer = setTimeout(() => { if (!this.#failed) this.#parts.message.hidden = true; }, 8000);
      },
    });
    // Vertical swipes scroll the page; horizontal ones (and mice) orbit.
    p.canvas.style.touchAction = 'pan-y';
    player.state.mode = this.view;
    player.state.visible = false;
    player.stirring.enabled = this.stir;
    this.#player = player;
    this.#api = player.api(this.ready);
    const resize = new ResizeObserver(() => player.resize());
    resize.observe(this);
    const visibility = new IntersectionObserver((entries) => {
      player.state.visible = entries.some((e) => e.isIntersecting);
    });
    visibility.observe(this);
    this.#observers = [resize, visibility];
  }

  /** The URL of the scene the attributes name; a preset is a name, not a path. */
  #sceneUrl() {
    const src = this.getAttribute('src');
    if (src) return new URL(src, document.baseURI);
    const preset = this.getAttribute('preset') || 'default';
    if (!/^[a-z0-9-]+$/.test(preset)) throw new Error(`preset: "${preset}" is not a scene name (lower-case letters, digits and hyphens)`);
    return new URL(`${preset}.json`, SCENES);
  }

  /** A name for the scene the attributes pick, for the text alternative. */
  #sceneName() {
    const src = this.getAttribute('src');
    if (src) {
      const file = decoded(new URL(src, document.baseURI).pathname.split('/').pop() || src);
      return `the scene ${file.replace(/\.json$/i, '')}`;
    }
    return `the ${this.getAttribute('preset') || 'default'} scene`;
  }

  /** Loads the scene the attributes name (serially); settles `ready` if it is still the latest. */
  #loadScene() {
    if (this.#ready.settled) this.#ready = deferred();
    const ready = this.#ready;
    const ticket = ++this.#ticket;
    const session = this.#session;
    this.#failed = false;
    this.#parts.message.hidden = true;
    this.#run(async (player) => {
      if (ticket !== this.#ticket) return;
      player.state.playing = false;
      const scene = await player.loadUrl(this.#sceneUrl().href);
      const playing = this.#wantsPlaying();
      const steps = playing ? 0 : Math.round(this.posterTime / scene.simulation.dt);
      if (steps > 0) {
        this.#showStatus(`Simulating ${this.posterTime} s…`);
        await player.exclusive(() => player.advance(steps));
      }
      player.state.playing = this.#wantsPlaying();
    }).then(() => {
      if (ticket !== this.#ticket || session !== this.#session) return;
      this.#parts.poster.hidden = true;
      this.#hideStatus();
      this.#updateControls();
      ready.resolve();
      this.dispatchEvent(new CustomEvent('ready', { detail: { scene: this.getScene() } }));
    }, (err) => {
      if (ticket !== this.#ticket || session !== this.#session) return;
      this.#fail(err);
    });
  }

  /** Runs `fn(player)` after the loads queued before it. */
  #run(fn) {
    const player = this.#player;
    const next = this.#queue.then(() => fn(player));
    this.#queue = next.catch(() => {});
    return next;
  }

  #fail(err) {
    const message = err?.message ?? String(err);
    this.#failed = true;
    this.#hideStatus();
    this.#showMessage(message);
    this.#updateControls();
    this.#updatePoster();
    const error = err instanceof Error ? err : new Error(message);
    // A player that was ready and then failed is ready no more: `ready` rejects from now on.
    if (this.#ready.settled) this.#ready = deferred();
    this.#ready.reject(error);
    this.dispatchEvent(new CustomEvent('error', { detail: { message } }));
  }

  #showMessage(text) {
    const m = this.#parts.message;
    m.textContent = text;
    m.hidden = false;
  }

  #showStatus(text) {
    this.#parts.status.textContent = text;
    this.#parts.status.hidden = false;
  }

  #hideStatus() {
    this.#parts.status.hidden = true;
    this.#parts.bar.style.width = '0';
  }

  #wantsPlaying() {
    return this.#playing ?? (this.autoplay && !reducedMotion());
  }

  #updateLabel() {
    const label = this.getAttribute('alt') || `Gas in a turbulent wind: ${this.#sceneName()}`;
    this.#parts.canvas.setAttribute('aria-label', label);
    this.#parts.play.setAttribute('aria-label', `Play ${this.#sceneName()}`);
  }

  #updatePoster() {
    const img = this.#parts.poster;
    const url = this.getAttribute('poster');
    if (!url || this.loaded) {
      img.hidden = true;
      return;
    }
    img.src = new URL(url, document.baseURI).href;
    img.hidden = false;
  }

  /** The play button (shown while not playing) and the control bar. */
  #updateControls() {
    const p = this.#parts;
    const playing = this.#wantsPlaying();
    p.play.hidden = playing || this.#failed;
    p.controls.hidden = !this.controls;
    p.toggle.textContent = playing ? 'Pause' : 'Play';
    p.view.textContent = `View: ${VIEW_NAMES[this.view]}`;
    p.view.title = 'Switch between the volume and points views';
  }

  /** Waits for the scene to be ready (following reloads); rejects when it fails. */
  async #whenReady() {
    if (!this.isConnected && !this.#player) {
      throw new Error('<wind-field> is not in a document: it loads once it is connected');
    }
    for (;;) {
      const ready = this.#ready.promise;
      await ready;
      if (ready !== this.#ready.promise) continue;
      if (!this.#api) throw new Error('<wind-field> was removed from its document');
      return this.#api;
    }
  }

  // DESIGN §5's methods.

  /** The current scene (a copy), or null before one is loaded. */
  getScene() {
    const scene = this.#player?.state.scene;
    return scene ? structuredClone(scene) : null;
  }

  /** Loads `scene` from its start (validated by the core); rejects with a clear Error and keeps the old one. */
  async setScene(scene) {
    await this.#whenReady();
    return this.#run((player) => player.load(scene));
  }

  pause() {
    this.#playing = false;
    if (this.#player) this.#player.state.playing = false;
    this.#updateControls();
  }

  play() {
    this.#playing = true;
    if (this.#player && this.loaded) this.#player.state.playing = true;
    this.#updateControls();
  }

  /** Applies an edited scene to the running one, keeping its blobs and time; rejects like `setScene`. */
  async editScene(scene) {
    await this.#whenReady();
    return this.#run((player) => player.edit(scene));
  }

  /** Chooses what steps the gas: 'cpu', 'gpu' or 'auto'; resolves with the one that steps now. */
  async setStepper(kind) {
    return (await this.#whenReady()).setStepper(kind);
  }

  /** Takes `n` fixed steps (deterministic) and draws. */
  async step(n = 1) {
    const api = await this.#whenReady();
    return api.step(n);
  }

  /** {blobs, time, fieldMs, stepMs, frameMs, fps, …}; zeros before the scene is loaded. */
  stats() {
    return this.#api
      ? this.#api.stats()
      : { blobs: 0, time: 0, fieldMs: 0, stepMs: 0, packMs: 0, frameBytes: 0, frameMs: 0, fps: 0, scale: 1, frames: 0, limitedBy: 'paused', stepper: 'cpu' };
  }

  async exportBlobs(size) {
    return (await this.#whenReady()).exportBlobs(size);
  }

  async captureGPU(options) {
    return (await this.#whenReady()).captureGPU(options);
  }

  async renderReference(options) {
    return (await this.#whenReady()).renderReference(options);
  }
}

if (!customElements.get('wind-field')) customElements.define('wind-field', WindFieldElement);

export { WindFieldElement };
