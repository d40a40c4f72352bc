// What kind of machine draws the view, and the lighter version a slow one gets. A browser that
// draws WebGL in software (SwiftShader, llvmpipe, Microsoft's Basic Render Driver: GPU-blocked
// laptops, virtual machines, remote desktops) runs every shader on the CPU, so the full view is
// a slideshow there; a weak GPU may be as slow. Such a machine gets the lighter version: the
// points view, `draft` quality, 35 % resolution, the gas stepped by the worker (a GPU stepper
// in software is many times slower than the worker), at most `LIGHT.blobCap` blobs and a scene's
// flow on a coarser grid, half the cells along each side (`engine/lighten.js`). Each
// choice the user makes stands over it for the rest of the session (sessionStorage), and the
// full version is one choice away.

/** Renderer names that mean WebGL drawn on the CPU. */
const SOFTWARE = /swiftshader|llvmpipe|softpipe|microsoft basic render|software rasterizer|mesa offscreen/i;

/** The lighter version's settings. */
export const LIGHT = Object.freeze({ view: 'points', quality: 'draft', resolution: 0.35, stepper: 'cpu', blobCap: 15_000, flow: 'coarse' });

/** Frames a second below which a machine counts as slow once measured (the view at its lightest full settings). */
export const SLOW_FPS = 10;

/** The session's key for the user's own choices. */
const CHOICES_KEY = 'windfield.choices';

/**
 * The renderer behind `gl` in words, and whether it draws in software: `{renderer, software}`.
 * The unmasked name where the browser gives it (WEBGL_debug_renderer_info), else the masked one.
 */
export function describeRenderer(gl) {
  let renderer = '';
  try {
    const info = gl.getExtension('WEBGL_debug_renderer_info');
    renderer = String(gl.getParameter(info ? info.UNMASKED_RENDERER_WEBGL : gl.RENDERER) ?? '');
  } catch {
    renderer = '';
  }
  return { renderer, software: SOFTWARE.test(renderer) };
}

function storage() {
  try {
    return window.sessionStorage;
  } catch {
    return null;
  }
}

/**
 * The choices the user made this session, each standing over the lighter version: any of
 * `view`, `quality`, `resolution`, `stepper`, `blobCap` (a number, or `null` for none), `flow`
 * (`'full'`: a scene's flow on its own cells; `'coarse'`: on the coarser grid), and
 * `full` (true: the full version, whatever the machine).
 */
export function userChoices() {
  try {
    const parsed = JSON.parse(storage()?.getItem(CHOICES_KEY) ?? '{}');
    return parsed && typeof parsed === 'object' && !Array.isArray(parsed) ? parsed : {};
  } catch {
    return {};
  }
}

/** Records the user's choice `name` = `value` for the rest of the session. */
export function rememberChoice(name, value) {
  const choices = { ...userChoices(), [name]: value };
  try {
    storage()?.setItem(CHOICES_KEY, JSON.stringify(choices));
  } catch {
    // Storage refused (private mode, a full quota): the choice holds for this page only.
  }
  return choices;
}

/**
 * The settings a player starts with: the lighter version's where `lighter` and the user has
 * not chosen otherwise, the user's choices where made, else the full version (`full`). Returns
 * the settings and the names of those the lighter version set.
 */
export function startingSettings(full, lighter, choices = userChoices()) {
  const settings = { ...full };
  const lightened = [];
  for (const [name, value] of Object.entries(LIGHT)) {
    if (Object.hasOwn(choices, name)) settings[name] = choices[name];
    else if (lighter && !choices.full) {
      settings[name] = value;
      lightened.push(name);
    }
  }
  return { settings, lightened };
}

/**
 * What the lighter version gave up, in words, for `lightened` (names of `LIGHT`'s settings):
 * one phrase each; the flow's is `coarserFlowWords`, which names the grids.
 */
export function lightenedWords(lightened) {
  const words = {
    view: 'the points view instead of the volume view',
    quality: 'draft quality',
    resolution: `${Math.round(LIGHT.resolution * 100)} % resolution`,
    stepper: 'the gas stepped by the worker',
    blobCap: `at most ${LIGHT.blobCap.toLocaleString('en')} blobs`,
  };
  return lightened.map((name) => words[name]).filter(Boolean);
}

/** The coarser flow in words: the `cells` it runs on in place of the scene's own (`from`). */
export function coarserFlowWords(cells, from) {
  return `the flow on a coarser grid: ${cells.join('×')} in place of ${from.join('×')}`;
}
