// The <wind-field> element's scripting methods (docs/FORMATS.md, the browser API; a feature of the element, after
// model-viewer's features/): the player's API, each call waiting for the scene to be ready
// (`ready`) and rejecting with a clear Error if it fails or the element is not in a document.
// `play()` and `pause()` are the controls' (`controls.js`).

import { $api, $player, $run, $whenReady } from './internals.js';

/** `stats()` before the scene is loaded. */
const NO_STATS = Object.freeze({
  blobs: 0, time: 0, fieldMs: 0, stepMs: 0, packMs: 0, frameBytes: 0, frameMs: 0, fps: 0, scale: 1, frames: 0, limitedBy: 'paused', stepper: 'cpu',
  flowMs: 0, flowStepper: null,
});

export const ApiMixin = (Base) => class extends Base {
  /** The current scene (a copy), or null before one is loaded. */
  getScene() {
    const scene = this[$player]?.scene;
    return scene ? structuredClone(scene) : null;
  }

  /** Loads `scene` from its start (validated by the core); rejects with a clear Error and keeps the old one. */
  async setScene(scene) {
    await this[$whenReady]();
    return this[$run]((player) => player.load(scene));
  }

  /** Applies an edited scene to the running one, keeping its blobs and time; rejects like `setScene`. */
  async editScene(scene) {
    await this[$whenReady]();
    return this[$run]((player) => player.edit(scene));
  }

  /** Chooses what steps the gas: 'cpu', 'gpu' or 'auto'; resolves with the one that steps now. */
  async setStepper(kind) {
    return (await this[$whenReady]()).setStepper(kind);
  }

  /** Takes `n` fixed steps (deterministic) and draws. */
  async step(n = 1) {
    return (await this[$whenReady]()).step(n);
  }

  /** {blobs, time, fieldMs, stepMs, frameMs, fps, …}; zeros before the scene is loaded. */
  stats() {
    return this[$api] ? this[$api].stats() : { ...NO_STATS };
  }

  async exportBlobs(size) {
    return (await this[$whenReady]()).exportBlobs(size);
  }

  async captureGPU(options) {
    return (await this[$whenReady]()).captureGPU(options);
  }

  async renderReference(options) {
    return (await this[$whenReady]()).renderReference(options);
  }

  async exportStill(options) {
    return (await this[$whenReady]()).exportStill(options);
  }

  async exportFlipbook(options) {
    return (await this[$whenReady]()).exportFlipbook(options);
  }

  async exportVolume(options) {
    return (await this[$whenReady]()).exportVolume(options);
  }

  /** The flow's grid now ({box, cells, time, velocity, temperature}); null for a scene without a flow. */
  async exportFlow() {
    return (await this[$whenReady]()).exportFlow();
  }

  async cancelExport() {
    return (await this[$whenReady]()).cancelExport();
  }
};
