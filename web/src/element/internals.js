// What the <wind-field> element's skeleton (`../embed.js`) and its features (this folder) share
// of each other: symbol-keyed members, so that none of it is part of the element's public API.

/** The shadow DOM's parts ({canvas, poster, bar, status, play, controls, message, toggle, step, view}). */
export const $parts = Symbol('parts');
/** The Player once mounted (`loading.js`), else null. */
export const $player = Symbol('player');
/** The player's scripting API (`Player.api`) once mounted, else null. */
export const $api = Symbol('api');
/** The URL of the scene the attributes name (the skeleton). */
export const $sceneUrl = Symbol('sceneUrl');
/** The skeleton's status line and notices: show a status, hide it (and the progress bar), show a notice. */
export const $showStatus = Symbol('showStatus');
export const $hideStatus = Symbol('hideStatus');
export const $showMessage = Symbol('showMessage');
/** Whether the current scene failed (`loading.js`). */
export const $failed = Symbol('failed');
/** Resolves with the player's API once the scene is ready, following reloads (`loading.js`). */
export const $whenReady = Symbol('whenReady');
/** Runs `fn(player)` after the scene loads queued before it (`loading.js`). */
export const $run = Symbol('run');
/** Whether the scene should play, and redrawing the play button and control bar (`controls.js`). */
export const $wantsPlaying = Symbol('wantsPlaying');
export const $updateControls = Symbol('updateControls');
