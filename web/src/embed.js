// <wind-field>: an embeddable player. Attributes: `src` (scene JSON URL), `preset` (a name in
// scenes/), `controls` (show play/pause/step/view buttons), `autoplay` (start playing), `view`
// (`raymarch`, the real-time volume view, by default; `points`; `exact`). Each
// element owns its worker and canvas, carries DESIGN §5's methods (`ready`, `getScene()`,
// `setScene()`, `pause()`, `play()`, `step(n)`, `stats()`, `exportBlobs()`, `captureGPU()`,
// `renderReference()`), is sized by CSS, and pauses while off-screen. Importing this module
// defines the element and nothing else.

import { MODES, Player } from './player.js';

const STYLE = `
:host { display: block; position: relative; width: 100%; aspect-ratio: 4 / 3; background: #0b0e11; color: #e6e9ec;
        font: 13px system-ui, sans-serif; overflow: hidden; border-radius: 6px; }
canvas { position: absolute; inset: 0; width: 100%; height: 100%; display: block; }
.bar { position: absolute; left: 0; bottom: 0; height: 3px; background: #7cc4ff; width: 0; transition: width 60ms linear; }
.message { position: absolute; left: 8px; right: 8px; top: 8px; padding: 6px 8px; background: #5a1d1d; border-radius: 4px; }
.controls { position: absolute; left: 8px; bottom: 8px; display: flex; gap: 4px; }
button { font: inherit; color: inherit; background: rgba(0, 0, 0, 0.55); border: 1px solid #3a4450; border-radius: 4px; padding: 3px 8px; cursor: pointer; }
`;

/**
 * Where presets live: `scenes/` beside the standalone `embed.js`; for a copy bundled into a
 * site (under `assets/`, or `src/` in development), `scenes/` beside the page.
 */
const MODULE_DIR = new URL(/* @vite-ignore */ './', import.meta.url);
const SCENES = /\/(src|assets)\/$/.test(MODULE_DIR.pathname)
  ? new URL('./scenes/', document.baseURI)
  : new URL('./scenes/', MODULE_DIR);

class WindFieldElement extends HTMLElement {
  #player = null;
  #api = null;
  #observers = [];
  #resolveReady;

  constructor() {
    super();
    this.attachShadow({ mode: 'open' });
    this.ready = new Promise((resolve, reject) => {
      this.#resolveReady = { resolve, reject };
    });
  }

  connectedCallback() {
    if (this.#player) return;
    const root = this.shadowRoot;
    root.innerHTML = `<style>${STYLE}</style><canvas part="canvas"></canvas><div class="bar"></div>
      <div class="message" hidden role="alert"></div><div class="controls" hidden></div>`;
    const message = root.querySelector('.message');
    const bar = root.querySelector('.bar');
    this.#player = new Player(root.querySelector('canvas'), {
      playing: this.hasAttribute('autoplay'),
      onProgress: (p) => { bar.style.width = p >= 1 ? '0' : `${Math.round(p * 100)}%`; },
      onMessage: (text) => { message.textContent = text; message.hidden = false; },
    });
    const view = this.getAttribute('view');
    if (MODES.includes(view)) this.#player.state.mode = view;
    this.#api = this.#player.api(this.ready);
    if (this.hasAttribute('controls')) this.#buildControls(root.querySelector('.controls'));
    const resize = new ResizeObserver(() => this.#player.resize());
    resize.observe(this);
    const visibility = new IntersectionObserver((entries) => {
      this.#player.state.visible = entries.some((e) => e.isIntersecting);
    });
    visibility.observe(this);
    this.#observers = [resize, visibility];
    this.#load().then(this.#resolveReady.resolve, (err) => {
      message.textContent = err.message;
      message.hidden = false;
      this.#resolveReady.reject(err);
    });
  }

  disconnectedCallback() {
    for (const o of this.#observers) o.disconnect();
    this.#player?.dispose();
    this.#player = null;
  }

  #load() {
    const src = this.getAttribute('src');
    const preset = this.getAttribute('preset') ?? 'default';
    const url = src ? new URL(src, document.baseURI) : new URL(`${encodeURIComponent(preset)}.json`, SCENES);
    return this.#player.loadUrl(url.href);
  }

  #buildControls(box) {
    box.hidden = false;
    const add = (label, fn) => {
      const b = document.createElement('button');
      b.textContent = label;
      b.addEventListener('click', fn);
      box.append(b);
    };
    add('play', () => this.play());
    add('pause', () => this.pause());
    add('step', () => this.step(1));
    add('view', () => {
      const s = this.#player.state;
      s.mode = s.mode === 'points' ? 'raymarch' : 'points';
      this.#player.resize();
    });
  }

  getScene() { return this.#api.getScene(); }
  setScene(scene) { return this.#api.setScene(scene); }
  pause() { this.#api.pause(); }
  play() { this.#api.play(); }
  step(n) { return this.#api.step(n); }
  stats() { return this.#api.stats(); }
  exportBlobs(size) { return this.#api.exportBlobs(size); }
  captureGPU(options) { return this.#api.captureGPU(options); }
  renderReference(options) { return this.#api.renderReference(options); }
}

if (!customElements.get('wind-field')) customElements.define('wind-field', WindFieldElement);

export { WindFieldElement };
