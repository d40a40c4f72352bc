// The <wind-field> element's controls (a feature of the element, after model-viewer's
// features/controls): the play button shown while the scene does not play, the control bar
// (`controls`: play/pause, step, the view), `autoplay` (not under reduced motion), and the
// `play()` and `pause()` methods.

import { $failed, $parts, $player, $updateControls, $wantsPlaying } from './internals.js';

const VIEW_NAMES = { raymarch: 'volume', points: 'points', exact: 'exact' };

const reducedMotion = () => window.matchMedia?.('(prefers-reduced-motion: reduce)').matches ?? false;

export const ControlsMixin = (Base) => class extends Base {
  /** Whether the scene should play: null follows `autoplay` (and the reduced-motion setting). */
  #playing = null;

  constructor() {
    super();
    const p = this[$parts];
    p.play.addEventListener('click', () => {
      this.play();
      this.load();
    });
    p.toggle.addEventListener('click', () => (this[$wantsPlaying]() ? this.pause().catch(() => {}) : this.play()));
    p.step.addEventListener('click', () => {
      this.pause().catch(() => {});
      this.step(1).catch(() => {});
    });
    p.view.addEventListener('click', () => { this.view = this.#shownView() === 'points' ? 'raymarch' : 'points'; });
  }

  connectedCallback() {
    super.connectedCallback();
    this[$updateControls]();
  }

  attributeChangedCallback(name, before, after) {
    super.attributeChangedCallback(name, before, after);
    if (before === after) return;
    if (name === 'controls' || name === 'view') this[$updateControls]();
    else if (name === 'autoplay' && after !== null && this[$player] && !reducedMotion()) this.play();
  }

  /** Stops playing; resolves once the steps already in flight are shown. */
  pause() {
    this.#playing = false;
    this[$updateControls]();
    return this[$player]?.pause() ?? Promise.resolve();
  }

  play() {
    this.#playing = true;
    if (this[$player] && this.loaded) this[$player].setPlaying(true);
    this[$updateControls]();
  }

  /** The view the player shows (the lighter version's points where the page named none), else the `view` attribute's. */
  #shownView() {
    return this[$player]?.mode ?? this.view;
  }

  [$wantsPlaying]() {
    return this.#playing ?? (this.autoplay && !reducedMotion());
  }

  /** The play button (shown while not playing) and the control bar. */
  [$updateControls]() {
    const p = this[$parts];
    const playing = this[$wantsPlaying]();
    p.play.hidden = playing || this[$failed];
    p.controls.hidden = !this.controls;
    p.toggle.textContent = playing ? 'Pause' : 'Play';
    p.view.textContent = `View: ${VIEW_NAMES[this.#shownView()]}`;
    p.view.title = 'Switch between the volume and points views';
  }
};
