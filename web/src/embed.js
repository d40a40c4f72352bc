// <wind-field>: an embeddable player (docs/FORMATS.md, the browser API). This module is only the loader: it defines
// the element, its poster, play button and attributes, and nothing heavy. The player's code
// (the engine worker with the WASM core, three.js and the views, `player/player.js`) is
// imported when the first element nears the viewport (`loading="lazy"`, the default) or at
// once (`loading="eager"`), once for every player on the page.
//
// Attributes (each mirrored by a property): `src` (scene JSON URL), `preset` (a name in
// scenes/), `controls`, `autoplay`, `loading` (`lazy` | `eager`), `poster` (an image URL shown
// until the scene is ready), `poster-time` (`posterTime`: seconds; without `autoplay` the scene
// is shown simulated to this time, by default the scene's `render.time`, with a play button),
// `view` (`raymarch`, the real-time volume view, by default; `points`; `exact`), `alt` (the text
// alternative; by default one naming the scene), `stir` (dragging over the view stirs the gas
// instead of orbiting it; off unless set). Events: `ready`, `error` (`detail.message`). Methods:
// the player's scripting API (getScene, setScene, editScene, setStepper, pause, play, step,
// stats, exportBlobs, captureGPU, renderReference); called before the scene is ready they wait
// for it (`ready`), and reject with a clear Error if it fails or the element is not in a
// document. Each element owns its worker and canvas, is sized by CSS (4:3 unless told
// otherwise), and pauses while off-screen.
//
// This file is the element's skeleton: its shadow DOM, its attributes mirrored as properties,
// its text alternative, status line and notices. Its features are one module each in
// `element/` (after model-viewer's features/), applied as mixins: `loading.js` (lazy loading,
// the poster, the player and its scene), `controls.js` (the play button and the control bar),
// `api.js` (the scripting methods). None of them imports anything heavy.

import { DEFAULT_RENDER_TIME } from './generated/contract.js';
import { ApiMixin } from './element/api.js';
import { ControlsMixin } from './element/controls.js';
import {
  $api, $hideStatus, $parts, $player, $sceneUrl, $showMessage, $showStatus, $updateControls, $wantsPlaying,
} from './element/internals.js';
import { LoadingMixin } from './element/loading.js';
import { attachParts } from './element/shadow.js';
import { VIEWS } from './views/modes.js';

/**
 * Where presets live: `scenes/` beside the standalone `embed.js`; for a copy bundled into a
 * site (under `assets/`, or `src/` in development), `scenes/` beside the page.
 */
const MODULE_DIR = new URL(/* @vite-ignore */ './', import.meta.url);
const SCENES = /\/(src|assets)\/$/.test(MODULE_DIR.pathname)
  ? new URL('./scenes/', document.baseURI)
  : new URL('./scenes/', MODULE_DIR);

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

class WindFieldBase extends HTMLElement {
  static get observedAttributes() {
    return ['src', 'preset', 'controls', 'autoplay', 'loading', 'poster', 'poster-time', 'view', 'alt', 'stir'];
  }

  constructor() {
    super();
    this[$parts] = attachParts(this);
    this[$player] = null;
    this[$api] = null;
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
   * the scene's `render.time`, else DEFAULT_RENDER_TIME (3).
   */
  get posterTime() {
    const fallback = this[$player]?.scene?.render.time ?? DEFAULT_RENDER_TIME;
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
    return VIEWS.includes(v) ? v : VIEWS[0];
  }
  set view(v) { this.setAttribute('view', v); }

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
  }

  disconnectedCallback() {}

  attributeChangedCallback(name, before, after) {
    if (before !== after && (name === 'src' || name === 'preset' || name === 'alt')) this.#updateLabel();
  }

  /** The URL of the scene the attributes name; a preset is a name, not a path. */
  [$sceneUrl]() {
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

  #updateLabel() {
    const p = this[$parts];
    const label = this.getAttribute('alt') || `Gas in a turbulent wind: ${this.#sceneName()}`;
    p.canvas.setAttribute('aria-label', label);
    p.play.setAttribute('aria-label', `Play ${this.#sceneName()}`);
  }

  [$showMessage](text) {
    const m = this[$parts].message;
    m.textContent = text;
    m.hidden = false;
  }

  [$showStatus](text) {
    this[$parts].status.textContent = text;
    this[$parts].status.hidden = false;
  }

  [$hideStatus]() {
    this[$parts].status.hidden = true;
    this[$parts].bar.style.width = '0';
  }

  // What the controls feature provides (`controls.js`).
  [$wantsPlaying]() { return false; }
  [$updateControls]() {}
}

/** `<wind-field>`: the skeleton with its features. */
class WindFieldElement extends ApiMixin(ControlsMixin(LoadingMixin(WindFieldBase))) {}

if (!customElements.get('wind-field')) customElements.define('wind-field', WindFieldElement);

export { WindFieldElement };
