// The playground: a Player runs the scene; this page adds the scene picker, the panel, the
// status line, stirring and notices, keeps the scene in the URL, imports and exports, and
// exposes `window.windfield`.

import GUI from 'lil-gui';
import { Player, QUALITIES, SLICE_PLANES } from '../player/player.js';
import { rememberChoice } from '../player/machine.js';
import { VIEWS } from '../views/modes.js';
import { decodeScene, encodeScene } from '../state/url-codec.js';
import { showMessage, showProgress } from './page-ui.js';
import { sceneEditor } from './scene-editor.js';
import { presetCatalog, PRESET_NAME, scenePicker } from './scene-picker.js';
import { drawSliceLegend } from './slice-legend.js';
import { statusText } from './status-line.js';
import { DEFAULT_RENDER_TIME, MAX_IMAGE_SIDE } from '../generated/contract.js';

const $ = (selector) => document.querySelector(selector);
const reduceMotion = window.matchMedia?.('(prefers-reduced-motion: reduce)').matches ?? false;
/** Phone-sized screens start with the panel collapsed (its title opens it). */
const smallScreen = window.matchMedia?.('(max-width: 800px), (max-height: 540px)').matches ?? false;
/**
 * The page's query: `preset`, `view`, `quality`, `profile`, and `timeout` (seconds the engine
 * may go without answering a request before it is restarted; 30 unless given).
 */
const query = new URLSearchParams(location.search);
/** A number as a person writes it in decimal (no hex, no blanks, no units). */
const DECIMAL = /^[-+]?(\d+\.?\d*|\.\d+)(e[-+]?\d+)?$/i;
/** The default scene's preset name. */
const DEFAULT = 'default';
/** How often the status line is rewritten (ms). */
const STATUS_EVERY = 250;

/** What the view shows, in the user's words: a preset's title, the link's scene, an import. */
let sceneName = 'the default scene';
/** The catalogue of presets ([{name, title, quote, section}]; empty until loaded). */
let presets = [];
const titleOf = (name) => presets.find((p) => p.name === name)?.title ?? name;
const nameOfDefault = () => `the default scene (${titleOf(DEFAULT).toLowerCase()})`;

let lastStatus = 0;
/** `?timeout=S`: seconds (1 to 3600) the engine may go without answering a request. */
const timeout = query.has('timeout') ? Number(query.get('timeout')) : null;
const timeoutOk = timeout === null || (Number.isFinite(timeout) && timeout >= 1 && timeout <= 3600);
/** Scenes the player has shown so far; only the latest one's hash goes in the URL. */
let scenesShown = 0;
const player = new Player($('#canvas'), {
  playing: !reduceMotion,
  ...(timeout !== null && timeoutOk && { requestTimeoutMs: 1000 * timeout }),
  profile: query.has('profile'),
  onProgress: showProgress,
  onMessage: (text) => showMessage(text),
  onNotice: (text) => showMessage(text, { info: true }),
  onLighter: (lighter) => showLighterNotice(lighter),
  onFrame: () => {
    updateStatus();
    // The poster goes once the view shows gas.
    if (player.snapshot().blobs > 0) $('#poster').hidden = true;
  },
  onScene: async (scene) => {
    $('#canvas').setAttribute('aria-label', `Gas in a turbulent wind: ${sceneName}, ${scene.emitters.length} emitter${scene.emitters.length === 1 ? '' : 's'}, ${scene.wind.length} wind primitive${scene.wind.length === 1 ? '' : 's'}`);
    // The URL is read after the scene is encoded: a card chosen meanwhile has pushed its
    // `?preset=`, which stays, and its own scene's hash follows. Only the latest scene shown,
    // with no other asked for since, writes its hash.
    const shown = ++scenesShown;
    const ask = asks;
    const hash = await encodeScene(scene);
    if (shown === scenesShown && ask === asks) history.replaceState(null, '', `${location.pathname}${location.search}#${hash}`);
    controls?.refresh();
  },
});
if (!timeoutOk) showMessage(`The link's timeout was not used: it must be a number of seconds from 1 to 3600 (got ${query.get('timeout')}); the engine's limit stays 30 s.`);
setPlaying(!reduceMotion);
/** `?fps=N`: draw at most N frames a second (0.1 to 240). */
if (query.has('fps')) {
  try {
    player.setMaxFps(Number(query.get('fps')));
  } catch (e) {
    showMessage(`The link's fps was not used: ${e.message.replace(/^setMaxFps: /, '')}.`);
  }
}
const initialView = query.get('view');
if (VIEWS.includes(initialView)) player.setView(initialView);
if (QUALITIES.includes(query.get('quality'))) player.setQuality(query.get('quality'));
player.setGuides(true);

/**
 * The notice of the lighter version (`player/machine.js`): why, what it gave up, and the full
 * version one click away (which holds for the rest of the visit).
 */
function showLighterNotice({ reason, gaveUp, renderer }) {
  const why = reason === 'software'
    ? 'This browser draws 3-D in software: showing a lighter version.'
    : 'This machine draws the 3-D view slowly: showing a lighter version.';
  showMessage(why, {
    info: true,
    details: [
      ...gaveUp.map((g) => `Given up: ${g}.`),
      ...(renderer ? [`The browser draws with ${renderer}.`] : []),
      'Every setting can be changed in the panel; a change holds for the rest of this visit.',
    ],
    actions: [{
      label: 'Show the full version',
      run: () => {
        rememberChoice('full', true);
        player.showFull().catch((e) => showMessage(e.message)).finally(() => { controls?.refresh(); updateStatus(true); });
      },
    }],
  });
}

/** The status line: always visible over the view, rewritten at most four times a second. */
function updateStatus(force = false) {
  const now = performance.now();
  if (!$('#status') || (!force && now - lastStatus < STATUS_EVERY)) return;
  lastStatus = now;
  $('#status').textContent = statusText(player.snapshot(), { mode: player.mode, volume: player.volumeDims(), stirring: player.stirring });
  const legend = player.sliceLegend();
  $('#slice-legend').hidden = !legend;
  if (legend) drawSliceLegend($('#slice-legend'), legend.maxSpeed);
}
setInterval(() => updateStatus(true), 1000);

/** After a change of the wind slice (which redraws): a slice plane turns the guides on (it is one). */
const showSlice = () => {
  if (player.slicePlane !== 'off') player.setGuides(true);
};

function download(name, href) {
  const a = document.createElement('a');
  a.href = href;
  a.download = name;
  a.click();
}

/** Plays or pauses, with the Play button saying which. */
function setPlaying(on) {
  player.setPlaying(on);
  $('#play').setAttribute('aria-pressed', String(on));
  $('#play').textContent = on ? 'Pause' : 'Play';
}

/** Counts scenes loaded: a scene's walk to its `render.time` stops when another is loaded. */
let loads = 0;

/**
 * Paused, walks the scene just loaded to its `render.time` (as a still would show it), a few
 * steps at a time, so that a newer scene, Play or a step asked for meanwhile never waits long.
 */
async function showAtRenderTime(loaded, ticket) {
  let left = Math.round((loaded.render.time ?? DEFAULT_RENDER_TIME) / loaded.simulation.dt);
  while (left > 0 && ticket === loads && !player.playing) {
    const n = Math.min(left, 5);
    await player.step(n);
    left -= n;
  }
}

/**
 * Loads a whole new scene (it starts at t = 0) named `name` for notices and the canvas, with
 * `poster` (an image URL, or null) over the view until its first frame with gas. Paused (with
 * reduced motion, say), the scene then walks to its `render.time`, as a still would show it.
 */
async function loadScene(scene, name, poster = null) {
  const previous = sceneName;
  sceneName = name;
  const ticket = ++loads;
  const img = $('#poster');
  if (poster) {
    img.src = poster;
    img.hidden = false;
  }
  try {
    const loaded = await player.load(scene);
    if (!player.playing) showAtRenderTime(loaded, ticket).catch((e) => showMessage(e.message));
    return loaded;
  } catch (e) {
    sceneName = previous;
    img.hidden = true;
    throw e;
  }
}

/**
 * Applies an edited scene to the running one (the gas keeps moving); a refused edit leaves a
 * notice and the controls on the last good scene.
 */
async function tryEdit(next) {
  try {
    await player.edit(next);
    if (!sceneName.endsWith(', edited')) sceneName += ', edited';
  } catch (e) {
    if (isCancelled(e)) return; // a newer scene is loading
    showMessage(`That change was not applied: ${e.message}`);
    controls?.refresh();
  }
}

/** Stirring on or off (the Stir button and the `s` key). */
function setStirring(on) {
  player.setStirring(on);
  $('#stir').setAttribute('aria-pressed', String(on));
  $('#stir').textContent = on ? 'Stirring: drag the smoke' : 'Stir';
  updateStatus(true);
}

/** Applies `fn` (a change of a copy of the scene) to the running scene. */
const editWith = (fn) => () => {
  const next = structuredClone(player.scene);
  fn(next);
  return tryEdit(next);
};

/** The Simulation folder: playing, the view and its settings, the guides, the drag handle. */
function simulationFolder(gui) {
  const sim = gui.addFolder('Simulation');
  const actions = {
    play: () => setPlaying(true),
    pause: () => setPlaying(false),
    step: () => player.step(1),
    reset: () => player.reset().catch((e) => showMessage(`Could not restart the scene: ${e.message}`)),
  };
  sim.add(actions, 'play');
  sim.add(actions, 'pause');
  sim.add(actions, 'step').name('step once');
  sim.add(actions, 'reset').name('restart at t = 0');
  // The player's settings, as properties for the panel.
  // The view's settings are the user's own choices: each holds for the rest of the visit over
  // the lighter version (`player/machine.js`).
  const settings = {
    get speed() { return player.speed; },
    set speed(v) { player.setSpeed(v); },
    get mode() { return player.mode; },
    set mode(v) { player.setView(v); rememberChoice('view', v); },
    get quality() { return player.quality; },
    set quality(v) { player.setQuality(v); rememberChoice('quality', v); },
    get resolution() { return player.resolutionSetting; },
    set resolution(v) { player.setResolution(v); rememberChoice('resolution', v); },
    get blobCap() { return player.blobCap ?? 'none'; },
    set blobCap(v) {
      const cap = v === 'none' ? null : Number(v);
      rememberChoice('blobCap', cap);
      player.setBlobCap(cap).catch((e) => showMessage(`Could not change the blob cap: ${e.message}`)).finally(() => updateStatus(true));
    },
  };
  sim.add(settings, 'speed', 0, 4, 0.05).name('time speed');
  sim.add(settings, 'mode', VIEWS).name('view').listen();
  sim.add(settings, 'quality', QUALITIES).name('quality').listen();
  const stepping = {
    get stepper() { return player.stepperChoice; },
    set stepper(kind) {
      rememberChoice('stepper', kind);
      player.setStepper(kind)
        .then((now) => { if (kind === 'gpu' && now !== 'gpu') showMessage(`The worker steps the gas: ${player.snapshot().stepperReason}.`); })
        .catch((e) => showMessage(`Could not change what steps the gas: ${e.message}`))
        .finally(() => updateStatus(true));
    },
  };
  sim.add(stepping, 'stepper', { 'auto (GPU where it can)': 'auto', GPU: 'gpu', 'worker (CPU)': 'cpu' }).name('gas stepped by').listen();
  sim.add(settings, 'resolution', { auto: 'auto', '100 %': 1, '75 %': 0.75, '50 %': 0.5, '35 %': 0.35, '25 %': 0.25 }).name('resolution').listen();
  sim.add(settings, 'blobCap', { 'the scene’s own': 'none', '300,000': 300000, '100,000': 100000, '30,000': 30000, '15,000': 15000 }).name('most blobs').listen();
  const view = {
    get guides() { return player.guides; },
    set guides(on) { player.setGuides(on); },
    get slice() { return player.slicePlane; },
    set slice(plane) { player.slicePlane = plane; showSlice(); },
    get offset() { return player.sliceOffset; },
    set offset(d) { player.sliceOffset = d; showSlice(); },
  };
  sim.add(view, 'guides').name('wind guides').listen();
  sim.add(view, 'slice', SLICE_PLANES).name('wind slice').listen();
  sim.add(view, 'offset', -2, 2, 0.01).name('slice offset (m)');
  const handle = { drag: 'none' };
  const handleChoices = () => ['none', ...player.scene.wind.map((p, i) => `wind ${i + 1}: ${p.type}`),
    ...player.scene.emitters.map((e, i) => `emitters ${i + 1}: ${e.shape}`)];
  const selectHandle = (label) => {
    const m = /^(wind|emitters) (\d+)/.exec(label);
    player.selectHandle(m ? { list: m[1], index: Number(m[2]) - 1 } : null);
  };
  let dragControl = sim.add(handle, 'drag', handleChoices()).name('drag handle').onChange(selectHandle);
  player.onHandleMoved((selection, item) => editWith((s) => { s[selection.list][selection.index] = item; })());
  return {
    refresh: () => {
      if (!handleChoices().includes(handle.drag)) handle.drag = 'none';
      dragControl = dragControl.options(handleChoices()).name('drag handle').onChange(selectHandle);
      selectHandle(handle.drag);
    },
  };
}

/** The paper's settings (§3–5) as number fields, and the scene editor's folders. */
function sceneFolders(gui) {
  const proxy = {};
  const getters = {};
  const scene = () => player.scene;
  // Number fields without slider ranges: a typed value goes to the core exactly as typed (not
  // rounded to the field's step), and the core names the valid range when it refuses one; text
  // that is not a decimal number is refused here, with what was typed.
  const bind = (folder, label, get, set) => {
    proxy[label] = get(scene());
    getters[label] = get;
    const c = folder.add(proxy, label);
    // What was typed, before the field reads it as a float and shows that instead.
    let typed = null;
    if (typeof proxy[label] === 'number') c.$input.addEventListener('input', () => { typed = c.$input.value; });
    return c.onFinishChange(() => {
      if (typeof proxy[label] === 'boolean') return editWith((s) => set(s, proxy[label]))();
      const text = (typed ?? String(proxy[label])).trim();
      typed = null;
      const value = DECIMAL.test(text) ? Number(text) : NaN;
      if (!Number.isFinite(value)) {
        showMessage(`That change was not applied: ${label} must be a number written in decimal, like 0.25 or 1e-3 (got “${text.slice(0, 40)}”).`);
        proxy[label] = get(scene());
        c.updateDisplay();
        return undefined;
      }
      return editWith((s) => set(s, value))();
    });
  };
  const field = gui.addFolder('Small-scale field (§3)');
  bind(field, 'ε', (s) => s.field.spectrum.epsilon, (s, v) => { s.field.spectrum.epsilon = v; });
  bind(field, 'k inertial', (s) => s.field.spectrum.k_inertial, (s, v) => { s.field.spectrum.k_inertial = v; });
  bind(field, 'σ', (s) => s.field.spectrum.sigma, (s, v) => { s.field.spectrum.sigma = v; });
  bind(field, 'amplitude', (s) => s.field.amplitude, (s, v) => { s.field.amplitude = v; });
  bind(field, 'seed', (s) => s.seed, (s, v) => { s.seed = v; });
  const gas = gui.addFolder('Gas (§4)');
  bind(gas, 'diffusion κ', (s) => s.gas.diffusion, (s, v) => { s.gas.diffusion = v; });
  bind(gas, 'dissipation α', (s) => s.gas.dissipation, (s, v) => { s.gas.dissipation = v; });
  bind(gas, 'max blobs', (s) => s.gas.max_blobs, (s, v) => { s.gas.max_blobs = v; });
  const look = gui.addFolder('Rendering (§5)');
  bind(look, 'shadows', (s) => s.render.shadows, (s, v) => { s.render.shadows = v; });
  const editor = sceneEditor(gui, { scene, apply: (draft) => tryEdit(structuredClone(draft)) });
  return {
    refresh: () => {
      for (const [label, get] of Object.entries(getters)) proxy[label] = get(scene());
      for (const c of gui.controllersRecursive()) if (c.object === proxy) c.updateDisplay();
      editor.refresh();
    },
  };
}

/** The Share and export folder: the link, the scene, the still, the view, the blobs, a video. */
function shareFolder(gui) {
  const actions = {
    copyLink: () => navigator.clipboard?.writeText(location.href).then(() => showMessage('Link copied', { transient: true })),
    exportScene: () => download('scene.json', URL.createObjectURL(new Blob([JSON.stringify(player.scene, null, 2)], { type: 'application/json' }))),
    importScene: () => $('#import').click(),
    still: async () => {
      const size = { width: 480, height: 360 };
      // Drawn on a canvas from the PNG's bytes: no data: or blob: URL, which a strict Content
      // Security Policy (`img-src 'self'`) refuses.
      const png = await player.referencePng(size);
      const bitmap = await createImageBitmap(new Blob([png], { type: 'image/png' }));
      const canvas = $('#still');
      [canvas.width, canvas.height] = [bitmap.width, bitmap.height];
      canvas.getContext('2d').drawImage(bitmap, 0, 0);
      bitmap.close();
      $('#still-figure .still-caption').textContent = `Reference still (CPU renderer), t = ${player.snapshot().time.toFixed(2)} s, ${size.width} × ${size.height}`;
      $('#still-figure').hidden = false;
    },
    png: async () => {
      // The view as it is drawn, without the wind guides.
      const { width, height } = $('#canvas');
      download('windfield.png', await player.captureGPU({ mode: player.mode, width, height }));
    },
    blobs: async () => {
      const list = await player.exportBlobs();
      download('blobs.json', URL.createObjectURL(new Blob([JSON.stringify(list)], { type: 'application/json' })));
    },
    frames: 120,
    video: async () => {
      setPlaying(false);
      try {
        const video = await player.recordWebM({ frames: actions.frames, width: 640, height: 480 });
        download('windfield.webm', URL.createObjectURL(video));
      } catch (e) {
        showMessage(`Could not record: ${e.message}`);
      }
    },
  };
  const share = gui.addFolder('Share and export');
  pipelineFolder(share);
  share.add(actions, 'copyLink').name('copy link');
  share.add(actions, 'exportScene').name('export scene JSON');
  share.add(actions, 'importScene').name('import scene JSON');
  share.add(actions, 'still').name('render still (CPU)');
  share.add(actions, 'png').name('export PNG of view');
  share.add(actions, 'blobs').name('export blob list JSON');
  share.add(actions, 'frames', 2, 1800, 1).name('video frames');
  share.add(actions, 'video').name('record WebM');
}

/**
 * Runs an export (`make()` resolves with a Blob) and downloads it as `name`, with the progress
 * bar and a cancel button; a cancelled or failed export says so and leaves the scene running.
 */
async function exportFile(what, name, make) {
  const cancel = $('#progress .cancel');
  cancel.hidden = false;
  cancel.onclick = () => player.cancelExport();
  try {
    const blob = await make();
    download(name, URL.createObjectURL(blob));
    return blob;
  } catch (e) {
    if (e.message.startsWith('cancelled')) showMessage(`The ${what} was cancelled`, { transient: true });
    else showMessage(`Could not export the ${what}: ${e.message}`);
    return null;
  } finally {
    cancel.hidden = true;
    showProgress(1, 'done');
  }
}

/**
 * Exports for pipelines (docs/FORMATS.md, exports): a still (PNG or EXR, with alpha), a flipbook
 * sprite sheet and its JSON, and the gas as an OpenVDB volume, each made in the engine worker by
 * the command line's code; the video's alpha where the browser can encode it.
 */
function pipelineFolder(parent) {
  const o = {
    stillFormat: 'png', alpha: true, width: 640, height: 480,
    fromFrame: 0, toFrame: 64, fps: 24, columns: 8, rows: 8, tileWidth: 256, tileHeight: 256, loop: false, sheetFormat: 'png',
    voxelMm: 5,
    still: () => exportFile('still', `windfield.${o.stillFormat}`, () => player.exportStill({
      format: o.stillFormat, alpha: o.alpha, width: o.width, height: o.height,
    })),
    flipbook: async () => {
      const blob = await exportFile('flipbook', `flipbook.${o.sheetFormat}`, () => player.exportFlipbook({
        frames: [o.fromFrame, o.toFrame], fps: o.fps, grid: [o.columns, o.rows], tile: [o.tileWidth, o.tileHeight],
        loop: o.loop, format: o.sheetFormat,
      }));
      if (blob) download('flipbook.json', URL.createObjectURL(new Blob([JSON.stringify(blob.description, null, 2)], { type: 'application/json' })));
    },
    volume: () => exportFile('volume', 'gas.vdb', () => player.exportVolume({ voxel: o.voxelMm / 1000 })),
  };
  const f = parent.addFolder('Export for pipelines').close();
  f.add(o, 'stillFormat', ['png', 'exr']).name('still format');
  f.add(o, 'alpha').name('transparent background');
  f.add(o, 'width', 1, MAX_IMAGE_SIDE, 1).name('still width');
  f.add(o, 'height', 1, MAX_IMAGE_SIDE, 1).name('still height');
  f.add(o, 'still').name('export still (CPU renderer)');
  f.add(o, 'fromFrame', 0, 100000, 1).name('flipbook from frame');
  f.add(o, 'toFrame', 1, 100000, 1).name('flipbook to frame (excl.)');
  f.add(o, 'fps', 1, 240, 1).name('flipbook fps');
  f.add(o, 'columns', 1, 64, 1).name('sheet columns');
  f.add(o, 'rows', 1, 64, 1).name('sheet rows');
  f.add(o, 'tileWidth', 1, 2048, 1).name('tile width');
  f.add(o, 'tileHeight', 1, 2048, 1).name('tile height');
  f.add(o, 'loop').name('seamless loop');
  f.add(o, 'sheetFormat', ['png', 'exr']).name('sheet format');
  f.add(o, 'flipbook').name('export flipbook');
  f.add(o, 'voxelMm', 0.1, 1000, 0.1).name('voxel (mm)');
  f.add(o, 'volume').name('export volume (OpenVDB)');
  return f;
}

let controls = null;
/** The panel; `refresh()` shows the current scene in it. */
function buildControls() {
  // lil-gui's stylesheet is linked (style.css), not injected: the page runs under a strict CSP.
  const gui = new GUI({ container: $('#panel'), title: 'windfield', injectStyles: false });
  if (smallScreen) gui.close();
  const simulation = simulationFolder(gui);
  const scene = sceneFolders(gui);
  shareFolder(gui);
  $('#panel').append($('#still-figure'));
  return {
    refresh: () => {
      scene.refresh();
      simulation.refresh();
    },
    gui,
  };
}

function wireImport() {
  $('#import').addEventListener('change', async (event) => {
    const file = event.target.files?.[0];
    if (!file) return;
    const current = asked();
    try {
      const text = await file.text();
      current();
      await loadScene(JSON.parse(text), `the imported scene ${file.name}`);
      picker?.select(null);
    } catch (e) {
      if (!isCancelled(e)) showMessage(`Could not import ${file.name}: ${e.message}. Still showing ${sceneName}.`);
    }
    event.target.value = '';
  });
}

function wireKeys() {
  window.addEventListener('keydown', (e) => {
    if (e.target.closest?.('input, textarea, select, button, [role="radio"]')) return;
    if (e.target === $('#canvas') && player.orbitKey(e)) {
      e.preventDefault();
      return;
    }
    if (e.key === ' ') { setPlaying(!player.playing); e.preventDefault(); }
    if (e.key === '.') player.step(1);
    if (e.key === 'v') {
      const next = player.mode === 'points' ? 'raymarch' : 'points';
      player.setView(next);
      rememberChoice('view', next);
    }
    if (e.key === 'g') player.setGuides(!player.guides);
    if (e.key === 's') setStirring(!player.stirring);
    if (e.key === 'w') {
      player.slicePlane = SLICE_PLANES[(SLICE_PLANES.indexOf(player.slicePlane) + 1) % SLICE_PLANES.length];
      showSlice();
    }
  });
  $('#stir').addEventListener('click', () => setStirring(!player.stirring));
  $('#play').addEventListener('click', () => setPlaying(!player.playing));
  $('#still-figure .still-close').addEventListener('click', () => { $('#still-figure').hidden = true; });
}

let picker = null;
/** Loads preset `name` chosen in the picker and puts it in the URL (the hash's scene goes). */
async function choosePreset(name) {
  const url = new URL(location.href);
  url.hash = '';
  if (name === DEFAULT) url.searchParams.delete('preset');
  else url.searchParams.set('preset', name);
  history.pushState(null, '', url);
  try {
    await loadPreset(name);
    picker.select(name);
  } catch (e) {
    // Another card chosen before this scene was ready: that one loads instead, nothing failed.
    if (isCancelled(e)) return;
    showMessage(`The ${titleOf(name).toLowerCase()} scene could not be loaded (${e instanceof NoSuchPreset ? 'it is missing' : e.message}). Still showing ${sceneName}.`);
  }
}

/**
 * Scenes asked for so far (the link's, a preset chosen, a file imported, the browser's back and
 * forward).
 */
let asks = 0;

/**
 * Counts a scene asked for, whose file is still to be read; the function it returns throws
 * 'cancelled' once another scene has been asked for since. So a file that arrives late (a
 * first card's preset after a second card's) never replaces the scene asked for after it.
 */
function asked() {
  const ask = ++asks;
  return () => {
    if (ask !== asks) throw new Error('cancelled: another scene was asked for while this one was read');
  };
}

/** Whether a load failed only because another scene was asked for meanwhile. */
const isCancelled = (e) => String(e?.message).startsWith('cancelled');

/** A preset that is not there: no file of that name, or a file that is not a scene. */
class NoSuchPreset extends Error {}

/**
 * Fetches preset `name` and loads it; rejects with a NoSuchPreset when there is none (a name is
 * lower-case letters, digits and hyphens), with the core's message when it is not a valid scene.
 */
async function loadPreset(name) {
  const current = asked();
  if (!PRESET_NAME.test(name)) throw new NoSuchPreset(name);
  const response = await fetch(new URL(`./scenes/${name}.json`, document.baseURI)).catch(() => null);
  const isJson = /json/.test(response?.headers.get('content-type') ?? '');
  const scene = response?.ok && isJson ? await response.json().catch(() => null) : null;
  current();
  if (!scene || typeof scene !== 'object' || !('version' in scene)) throw new NoSuchPreset(name);
  const label = name === DEFAULT ? nameOfDefault() : `the ${titleOf(name).toLowerCase()} scene`;
  return loadScene(scene, label, new URL(`./scenes/thumbs/${name}.png`, document.baseURI).href);
}

/**
 * The scene the page opens on: the link's, else `?preset=`, else the default scene. What could
 * not be opened is said in one notice naming the scene shown instead. Resolves with the preset
 * shown (null for the link's scene), or undefined when a card was chosen before it was ready
 * (that card's scene is the one shown then, and nothing failed).
 */
async function initialScene() {
  const problems = [];
  const current = asked();
  const fromHash = await decodeScene(location.hash).catch((e) => {
    problems.push(`This link's scene could not be read: ${e.message}.`);
    return null;
  });
  if (fromHash) {
    try {
      current();
      await loadScene(fromHash, 'the scene from the link');
      return null;
    } catch (e) {
      if (isCancelled(e)) return undefined;
      problems.push(`This link's scene is not valid (${e.message}).`);
    }
  }
  const preset = query.get('preset');
  let shown = null;
  if (preset !== null) {
    try {
      await loadPreset(preset);
      shown = preset;
    } catch (e) {
      if (isCancelled(e)) return undefined;
      const names = presets.map((p) => p.name).join(', ');
      problems.push(e instanceof NoSuchPreset
        ? `There is no scene named "${preset}". The scenes are: ${names}.`
        : `The scene "${preset}" could not be loaded (${e.message}).`);
    }
  }
  if (shown === null) {
    try {
      await loadPreset(DEFAULT);
    } catch (e) {
      if (isCancelled(e)) return undefined;
      throw e;
    }
    shown = DEFAULT;
  }
  if (problems.length) showMessage(`${problems.join(' ')} Showing ${sceneName} instead.`);
  return shown;
}

// The view follows its box (window resizes, and the panel's folders opening and closing).
new ResizeObserver(() => player.resize()).observe($('#view'));
const ready = (async () => {
  presets = await presetCatalog().catch(() => []);
  picker = scenePicker($('#picker'), presets, choosePreset);
  const shown = await initialScene();
  if (shown !== undefined) picker.select(shown);
  controls = buildControls();
  wireImport();
  wireKeys();
  window.addEventListener('popstate', () => {
    const name = new URLSearchParams(location.search).get('preset') ?? DEFAULT;
    if (!location.hash) {
      loadPreset(name).then(() => picker.select(name), (e) => isCancelled(e) || showMessage(e.message));
    }
  });
})();

window.windfield = {
  ...player.api(ready),
  fieldStats: (spectrum) => player.fieldStats(spectrum),
  health: () => player.health(),
  sample: (x, y, z, t) => player.sample(x, y, z, t),
};
