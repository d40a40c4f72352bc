// The browser API (docs/FORMATS.md, types/index.d.ts: `window.windfield` on the playground,
// and the methods of every <wind-field> element): its methods by name, each bound to one Player.

/** The methods of the browser API bound to `player`; `ready` resolves once its scene is ready. */
export function browserApi(player, ready) {
  return {
    ready,
    getScene: () => structuredClone(player.scene),
    setScene: (scene) => player.load(scene),
    pause: () => player.pause(),
    setView: (mode) => player.setView(mode),
    play: () => player.setPlaying(true),
    step: (n = 1) => player.step(n),
    stats: () => player.snapshot(),
    editScene: (scene) => player.edit(scene),
    setStepper: (kind) => player.setStepper(kind),
    exportBlobs: (size) => player.exportBlobs(size),
    captureGPU: (options) => player.captureGPU(options),
    renderReference: (options) => player.renderReference(options),
    exportStill: (options) => player.exportStill(options),
    exportFlipbook: (options) => player.exportFlipbook(options),
    exportVolume: (options) => player.exportVolume(options),
    exportFlow: () => player.exportFlow(),
    cancelExport: () => player.cancelExport(),
    recordWebM: (options) => player.recordWebM(options),
    inspectVolume: (options) => player.inspectVolume(options),
    inspectStepper: () => player.inspectStepper(),
    timeFrames: (options) => player.timeFrames(options),
    timeGpuSort: (options) => player.timeGpuSort(options),
    timeGpuStep: (options) => player.timeGpuStep(options),
  };
}
