// The playground: a Player runs the scene; this page adds the controls, keeps the scene in the
// URL hash, imports and exports, and exposes `window.windfield` (DESIGN §5).

import GUI from 'lil-gui';
import { showMessage, showProgress } from './page-ui.js';
import { MODES, Player, QUALITY } from './player.js';
import { sceneEditor } from './scene-editor.js';
import { moved } from './views/guides-layer.js';
import { SLICE_PLANES } from './views/wind-slice-layer.js';
import { decodeScene, encodeScene } from './state/url-codec.js';

const $ = (selector) => document.querySelector(selector);
const reduceMotion = window.matchMedia?.('(prefers-reduced-motion: reduce)').matches ?? false;
const DEFAULT_SCENE_URL = new URL('./scenes/default.json', document.baseURI).href;
/** Phone-sized screens start with the panel collapsed (its title opens it). */
const smallScreen = window.matchMedia?.('(max-width: 800px), (max-height: 540px)').matches ?? false;
/** What the view shows, for its text alternative: the preset's name, or the scene being edited. */
let sceneName = 'the default scene';
/** The page's query: `view`, `quality`, `preset`, `profile`. */
const query = new URLSearchParams(location.search);

const player = new Player($('#canvas'), {
  playing: !reduceMotion,
  profile: query.has('profile'),
  onProgress: showProgress,
  onMessage: showMessage,
  onFrame: (frame) => {
    const st = player.stats;
    const grid = state.mode === 'raymarch' ? player.view.volume.grid : null;
    const volume = grid ? ` · volume ${grid.dims.join('×')}` : '';
    const scale = state.mode === 'points' ? '' : ` · resolution ${Math.round(st.scale * 100)} %`;
    $('#status').textContent = `t = ${frame.time.toFixed(2)} s · ${frame.count} blobs · field ${st.fieldMs.toFixed(0)} ms`
      + ` · step ${st.stepMs.toFixed(2)} ms · ${st.fps.toFixed(0)} fps${scale}${volume}`;
  },
  onScene: async (scene) => {
    $('#canvas').setAttribute('aria-label', `Gas in a turbulent wind: ${sceneName}, ${scene.emitters.length} emitter${scene.emitters.length === 1 ? '' : 's'}, ${scene.wind.length} wind primitive${scene.wind.length === 1 ? '' : 's'}`);
    history.replaceState(null, '', `${location.pathname}${location.search}#${await encodeScene(scene)}`);
    controls?.refresh();
  },
});
const state = player.state;
const initialView = query.get('view');
state.mode = MODES.includes(initialView) ? initialView : 'raymarch';
if (Object.hasOwn(QUALITY, query.get('quality') ?? '')) state.quality = query.get('quality');
player.view.showGuides = true;
const loadScene = (scene) => player.load(scene);
const advance = (n) => player.advance(n);
const draw = () => player.draw();
/** Draws after a change of the wind slice; a slice plane turns the guides on (it is one). */
const showSlice = () => {
  if (player.view.slicePlane !== 'off') player.view.showGuides = true;
  draw();
};

function download(name, href) {
  const a = document.createElement('a');
  a.href = href;
  a.download = name;
  a.click();
}

let controls = null;
function buildControls() {
  const gui = new GUI({ container: $('#panel'), title: 'windfield' });
  if (smallScreen) gui.close();
  const actions = {
    play: () => { state.playing = true; },
    pause: () => { state.playing = false; },
    step: () => advance(1),
    reset: () => player.engine.request('reset').then(() => advance(0)),
    copyLink: () => navigator.clipboard?.writeText(location.href).then(() => showMessage('Link copied')),
    exportScene: () => download('scene.json', URL.createObjectURL(new Blob([JSON.stringify(state.scene, null, 2)], { type: 'application/json' }))),
    importScene: () => $('#import').click(),
    still: async () => {
      const url = await player.renderReference({ width: 480, height: 360 });
      $('#still').src = url;
      $('#still').hidden = false;
    },
    png: () => download('windfield.png', $('#canvas').toDataURL('image/png')),
    blobs: async () => {
      const list = await player.exportBlobs();
      download('blobs.json', URL.createObjectURL(new Blob([JSON.stringify(list)], { type: 'application/json' })));
    },
    frames: 120,
    video: async () => {
      state.playing = false;
      try {
        const video = await player.recordWebM({ frames: actions.frames, width: 640, height: 480 });
        download('windfield.webm', URL.createObjectURL(video));
      } catch (e) {
        showMessage(`Could not record: ${e.message}`);
      }
    },
  };
  const sim = gui.addFolder('Simulation');
  sim.add(actions, 'play');
  sim.add(actions, 'pause');
  sim.add(actions, 'step').name('step once');
  sim.add(actions, 'reset');
  sim.add(state, 'speed', 0, 4, 0.05).name('time speed');
  sim.add(state, 'mode', MODES).name('view').onChange(() => player.resize());
  sim.add(state, 'quality', Object.keys(QUALITY)).name('quality').onChange(() => draw());
  const resolution = { scale: 'auto' };
  sim.add(resolution, 'scale', { auto: 'auto', '100 %': 1, '75 %': 0.75, '50 %': 0.5, '25 %': 0.25 }).name('resolution')
    .onChange((v) => { player.resolution.set(v); player.resize(); });
  sim.add(player.view, 'showGuides').name('wind guides').listen().onChange(() => draw());
  sim.add(player.view, 'slicePlane', SLICE_PLANES).name('wind slice').listen().onChange(showSlice);
  sim.add(player.view, 'sliceOffset', -2, 2, 0.01).name('slice offset (m)').onChange(showSlice);
  const handle = { drag: 'none' };
  const handleChoices = () => ['none', ...state.scene.wind.map((p, i) => `wind ${i + 1}: ${p.type}`),
    ...state.scene.emitters.map((e, i) => `emitters ${i + 1}: ${e.shape}`)];
  const selectHandle = (label) => {
    const m = /^(wind|emitters) (\d+)/.exec(label);
    player.view.guides.select(m ? { list: m[1], index: Number(m[2]) - 1 } : null);
    if (m) player.view.showGuides = true;
    draw();
  };
  let dragControl = sim.add(handle, 'drag', handleChoices()).name('drag handle').onChange(selectHandle);
  // Loads an edited scene; a refused one leaves a message and the controls on the last good one.
  const tryLoad = async (next) => {
    try {
      if (!sceneName.endsWith(', edited')) sceneName += ', edited';
      await loadScene(next);
    } catch (e) {
      if (e.message.startsWith('cancelled')) return; // a newer edit is loading
      showMessage(e.message);
      controls.refresh();
    }
  };
  const edit = (fn) => () => {
    const next = structuredClone(state.scene);
    fn(next);
    return tryLoad(next);
  };
  player.view.guides.onMoved = (selection, to) => edit((s) => {
    const list = s[selection.list];
    list[selection.index] = moved(list[selection.index], to.map((v) => Math.round(v * 1000) / 1000));
  })();
  const proxy = {};
  const getters = {};
  const field = gui.addFolder('Small-scale field (§3)');
  const scene = () => state.scene;
  const bind = (folder, label, get, set, ...range) => {
    proxy[label] = get(scene());
    getters[label] = get;
    return folder.add(proxy, label, ...range).onFinishChange(edit((s) => set(s, proxy[label])));
  };
  bind(field, 'ε', (s) => s.field.spectrum.epsilon, (s, v) => { s.field.spectrum.epsilon = v; }, 0.01, 10, 0.01);
  bind(field, 'k inertial', (s) => s.field.spectrum.k_inertial, (s, v) => { s.field.spectrum.k_inertial = v; }, 0.5, 15, 0.5);
  bind(field, 'σ', (s) => s.field.spectrum.sigma, (s, v) => { s.field.spectrum.sigma = v; }, 0, 4, 0.05);
  bind(field, 'amplitude', (s) => s.field.amplitude, (s, v) => { s.field.amplitude = v; }, 0, 5, 0.05);
  bind(field, 'seed', (s) => s.seed, (s, v) => { s.seed = v; }, 0, 10000, 1);
  const gas = gui.addFolder('Gas (§4)');
  bind(gas, 'diffusion κ', (s) => s.gas.diffusion, (s, v) => { s.gas.diffusion = v; }, 0, 0.05, 0.0005);
  bind(gas, 'dissipation α', (s) => s.gas.dissipation, (s, v) => { s.gas.dissipation = v; }, 0, 2, 0.01);
  bind(gas, 'max blobs', (s) => s.gas.max_blobs, (s, v) => { s.gas.max_blobs = v; }, 100, 50000, 100);
  const look = gui.addFolder('Rendering (§5)');
  bind(look, 'shadows', (s) => s.render.shadows, (s, v) => { s.render.shadows = v; });
  const editor = sceneEditor(gui, { scene, apply: (draft) => tryLoad(structuredClone(draft)) });
  const share = gui.addFolder('Share and export');
  share.add(actions, 'copyLink').name('copy link');
  share.add(actions, 'exportScene').name('export scene JSON');
  share.add(actions, 'importScene').name('import scene JSON');
  share.add(actions, 'still').name('render still (CPU)');
  share.add(actions, 'png').name('export PNG of view');
  share.add(actions, 'blobs').name('export blob list JSON');
  share.add(actions, 'frames', 2, 1800, 1).name('video frames');
  share.add(actions, 'video').name('record WebM');
  $('#panel').append($('#status'), $('#still'));
  return {
    refresh: () => {
      for (const [label, get] of Object.entries(getters)) proxy[label] = get(scene());
      for (const c of gui.controllersRecursive()) if (c.object === proxy) c.updateDisplay();
      editor.refresh();
      if (!handleChoices().includes(handle.drag)) handle.drag = 'none';
      dragControl = dragControl.options(handleChoices()).name('drag handle').onChange(selectHandle);
      selectHandle(handle.drag);
    },
    gui,
  };
}

function wireImport() {
  $('#import').addEventListener('change', async (event) => {
    const file = event.target.files?.[0];
    if (!file) return;
    try {
      sceneName = `the imported scene ${file.name}`;
      await loadScene(JSON.parse(await file.text()));
    } catch (e) {
      showMessage(`Could not import ${file.name}: ${e.message}`);
    }
    event.target.value = '';
  });
}

function wireKeys() {
  window.addEventListener('keydown', (e) => {
    if (e.target.closest?.('input, textarea, select')) return;
    if (e.key === ' ') { state.playing = !state.playing; e.preventDefault(); }
    if (e.key === '.') advance(1);
    if (e.key === 'v') { state.mode = state.mode === 'points' ? 'raymarch' : 'points'; player.resize(); }
    if (e.key === 'g') { player.view.showGuides = !player.view.showGuides; draw(); }
    if (e.key === 'w') {
      const view = player.view;
      view.slicePlane = SLICE_PLANES[(SLICE_PLANES.indexOf(view.slicePlane) + 1) % SLICE_PLANES.length];
      showSlice();
    }
  });
}

async function initialScene() {
  const fromHash = await decodeScene(location.hash).catch((e) => {
    showMessage(`The link's scene could not be read (${e.message}); showing the default scene.`);
    return null;
  });
  if (fromHash) {
    try {
      sceneName = 'the scene from the link';
      return await loadScene(fromHash);
    } catch (e) {
      showMessage(`The link's scene is invalid (${e.message}); showing the default scene.`);
    }
  }
  const preset = query.get('preset');
  const url = preset ? new URL(`./scenes/${encodeURIComponent(preset)}.json`, document.baseURI).href : DEFAULT_SCENE_URL;
  let scene = await fetch(url).then((r) => (r.ok ? r.json() : null)).catch(() => null);
  sceneName = preset ? `the ${preset} scene` : 'the default scene';
  if (!scene) {
    showMessage(`No preset named "${preset}"; showing the default scene.`);
    sceneName = 'the default scene';
    scene = await fetch(DEFAULT_SCENE_URL).then((r) => r.json());
  }
  return loadScene(scene);
}

// The view follows its box (window resizes, and the panel's folders opening and closing).
new ResizeObserver(() => player.resize()).observe($('#view'));
const ready = initialScene().then(() => {
  controls = buildControls();
  wireImport();
  wireKeys();
});

window.windfield = {
  ...player.api(ready),
  fieldStats: (spectrum) => player.engine.request('fieldStats', { spectrum }),
  health: () => player.engine.request('health'),
  sample: (x, y, z, t) => player.engine.request('sample', { x, y, z, t }),
};
