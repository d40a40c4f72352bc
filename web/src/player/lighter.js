// Where each of a player's settings came from, and the lighter version a slow machine gets
// (`machine.js`): each setting is the full version's ('full'), the lighter version's ('light')
// or chosen by the page, the user or a script ('chosen'; the lighter version leaves it alone).
// The player starts with `startingSettings`, takes the lighter version when its machine draws
// in software or is measured slow, and goes back to the full version at `showFull`.

import { coarserFlowWords, lightenedWords, LIGHT, SLOW_FPS, startingSettings } from './machine.js';

/** The settings a player starts with on a machine that draws the full version. */
const FULL = Object.freeze({ view: 'raymarch', quality: 'standard', resolution: 'auto', stepper: 'auto', blobCap: null, flow: 'full' });

export class LighterVersion {
  /** Where each of `FULL`'s settings comes from: 'full', 'light' or 'chosen'. */
  #from = { view: 'full', quality: 'full', resolution: 'full', stepper: 'full', blobCap: 'full', flow: 'full' };
  /** The running scene's flow on the coarser grid: {cells, from (the scene's own)}, or null. */
  #coarserFlow = null;
  /** Why the lighter version is shown ('software': WebGL drawn on the CPU; 'slow': measured so), or null. */
  #reason = null;
  /** The user's own settings this player started with (`machine.js`, `userChoices`), `full` among them once asked for. */
  #choices;
  /** The machine that draws: {renderer, software} (`describeRenderer`). */
  #machine;
  /** Whether a slow machine gets the lighter version (the page may turn it off). */
  #adapt;
  /** Applies a value to one of `FULL`'s settings, whoever chose it. */
  #apply;
  /** Hears of the lighter version once shown (`onLighter`). */
  #onLighter;
  /** Runs the running scene again under the settings as they now are (its stepper, its blob cap). */
  #rerun;
  /** Hears why a rerun failed. */
  #onMessage;

  /**
   * Applies the starting settings (`startingSettings`): the user's `choices`, the lighter
   * version's on a machine that draws in software (when `adapt`), else the full version's.
   * @param {{machine: {renderer: string, software: boolean}, choices: object, adapt: boolean,
   *   apply: (name: string, value: unknown) => void, onLighter?: (lighter: object) => void,
   *   rerun: () => Promise<unknown>, onMessage?: (text: string) => void}} parts
   */
  constructor({ machine, choices, adapt, apply, onLighter, rerun, onMessage }) {
    this.#machine = machine;
    this.#choices = choices;
    this.#adapt = adapt;
    this.#apply = apply;
    this.#onLighter = onLighter;
    this.#rerun = rerun;
    this.#onMessage = onMessage;
    const software = adapt && !choices.full && machine.software;
    const { settings, lightened } = startingSettings(FULL, software, choices);
    for (const name of Object.keys(FULL)) {
      if (Object.hasOwn(choices, name)) this.#from[name] = 'chosen';
      else if (lightened.includes(name)) this.#from[name] = 'light';
      apply(name, settings[name]);
    }
    if (software) this.#shown('software');
  }

  /** Sets `name` (one of `FULL`'s settings) to `value` as chosen: the lighter version leaves it alone. */
  choose(name, value) {
    this.#from[name] = 'chosen';
    this.#apply(name, value);
  }

  /**
   * The running scene's flow runs on `cells` in place of its own `from` (the engine's answer to a
   * load or an edit; `cells` null: on its own, or no flow). A change is told as the lighter
   * version is (`onLighter`): the grids named, or the flow's line gone.
   */
  flowRuns(cells, from) {
    const next = cells && from ? { cells: [...cells], from: [...from] } : null;
    const same = JSON.stringify(next) === JSON.stringify(this.#coarserFlow);
    this.#coarserFlow = next;
    if (!same && this.#reason) this.#tell();
  }

  /** `stats().lighter`: why the lighter version is shown and what it gave up, or null. */
  snapshot() {
    return this.#reason ? { reason: this.#reason, gaveUp: this.#gaveUp() } : null;
  }

  /**
   * The view kept up `pace` frames a second (`FramePace`) after `frames` frames, at the
   * resolution `resolution` holds, while `playing`: a machine slower than `SLOW_FPS` at the
   * lowest resolution gets the lighter version.
   */
  measured(pace, resolution, frames, playing) {
    const slow = pace > 0 && pace < SLOW_FPS && resolution.mode === 'auto' && resolution.scale <= resolution.min;
    if (slow && playing && frames >= 15 && this.#adapt && !this.#reason && !this.#choices.full) this.#lighten('slow');
  }

  /**
   * Shows the lighter version (`LIGHT`) for every setting nobody chose, because of `reason`
   * ('software' or 'slow'); a scene running already goes on under the lighter settings.
   */
  #lighten(reason) {
    if (this.#reason) return;
    for (const [name, value] of Object.entries(LIGHT)) {
      if (this.#from[name] === 'full') {
        this.#from[name] = 'light';
        this.#apply(name, value);
      }
    }
    this.#shown(reason);
    this.#rerun().catch((e) => this.#onMessage?.(e.message));
  }

  /** The lighter version is shown because of `reason`: the page hears of it. */
  #shown(reason) {
    this.#reason = reason;
    this.#tell();
  }

  /** The page hears why the lighter version is shown and what it gives up now. */
  #tell() {
    // After the constructor and what the page sets in the same task (the page's handle on the
    // player, a link's `view` or `quality`): what it gave up is read then, so a setting the
    // link chose is not told as given up.
    queueMicrotask(() => {
      if (this.#reason) this.#onLighter?.({ reason: this.#reason, gaveUp: this.#gaveUp(), renderer: this.#machine.renderer });
    });
  }

  /**
   * The full version: every setting the lighter version set goes back to the full version's
   * (the user's own choices stay). Resolves once the scene runs so.
   */
  showFull() {
    this.#choices = { ...this.#choices, full: true };
    for (const [name, from] of Object.entries(this.#from)) {
      if (from === 'light') {
        this.#from[name] = 'full';
        this.#apply(name, FULL[name]);
      }
    }
    this.#reason = null;
    return this.#rerun();
  }

  /**
   * What the lighter version gives up now, in words (empty when it is not shown). The flow is
   * named only where the running scene's flow is on the coarser grid, with both grids: a scene
   * without a flow, or one whose flow has no coarser grid (`coarserCells`), gives up none.
   */
  #gaveUp() {
    if (!this.#reason) return [];
    const lightened = Object.keys(this.#from).filter((name) => this.#from[name] === 'light');
    const flow = this.#coarserFlow;
    return lightened.flatMap((name) => {
      if (name !== 'flow') return lightenedWords([name]);
      return flow ? [coarserFlowWords(flow.cells, flow.from)] : [];
    });
  }
}
