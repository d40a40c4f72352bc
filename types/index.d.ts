// TypeScript declarations for windfield in the browser: the <wind-field> element (web/src/embed.js,
// dist/embed.js), its attributes, properties, methods and events, the playground's
// `window.windfield` (docs/FORMATS.md, the browser API), and the scene (docs/FORMATS.md) and blob list (docs/FORMATS.md) formats.
// Importing the package's main entry defines the element; `import type` from it costs nothing.
//
// The scene's types are generated from its JSON Schema (public/scene.schema.json) into
// ./scene.d.ts by scripts/scene-types.mjs (`npm run types:scene`): `Scene` as the core normalised
// it, `SceneInput` as it may be given. The rest is written here.

import type { RenderSettings, Scene, SceneInput } from './scene.js';

export type * from './scene.js';

/** Three numbers: a point or a vector (m), or a colour (linear RGB). */
export type Vec3 = [number, number, number];

/** The views: the real-time volume view, one sprite a blob, or the exact per-chord march. */
export type WindFieldView = 'raymarch' | 'points' | 'exact';
/** Quality of the marched views: the volume's voxels and steps, the exact march's shadow grid. */
export type WindFieldQuality = 'draft' | 'standard' | 'high';
/** What steps the gas: the engine worker's core, or the GPU. */
export type WindFieldStepper = 'cpu' | 'gpu';

/** The blob list (docs/FORMATS.md): the render input of the reference renderer and the CLI. */
export interface BlobList extends Omit<RenderSettings, 'image' | 'time'> {
  image: { width: number; height: number; encoding: 'srgb' | 'linear' };
  blobs: { center: Vec3; sigma: number; mass: number; albedo?: Vec3; emission?: Vec3; age?: number; sigma0?: number; mass0?: number }[];
}

/** `stats()`: the player's counters (times in ms). */
export interface WindFieldStats {
  blobs: number;
  /** The simulated time (s). */
  time: number;
  fieldMs: number;
  stepMs: number;
  frameMs: number;
  fps: number;
  /** The real-time view's internal resolution (a share of the canvas's box). */
  scale: number;
  packMs: number;
  frameBytes: number;
  /** Frames drawn since the player started. */
  frames: number;
  /** What holds the frame rate down: the worker's step, drawing the view, the display itself, or nothing (paused). */
  limitedBy: 'worker' | 'view' | 'display' | 'paused';
  /** What steps the gas now. */
  stepper: WindFieldStepper;
  /** Why the worker steps the gas where the GPU was asked for (`setStepper('gpu' | 'auto')`); absent otherwise. */
  stepperReason?: string;
  /** The last flow step's time (ms: the worker's, or on the GPU the GPU's own time for its passes by a timer query, else the page's time to issue them); 0 for a scene without a flow. */
  flowMs: number;
  /** What steps the scene's flow: the engine worker's core ('cpu', where it steps the gas) or the GPU beside the GPU stepper's blobs ('gpu'); null for a scene without a flow. */
  flowStepper: 'cpu' | 'gpu' | null;
  /** With the playground's `?profile`: the real-time view's passes on the GPU (ms). */
  passes?: Record<string, number>;
  /** How each pass stores its floats: 16-bit where the GPU cannot render to, blend or filter 32-bit ones. Absent before the scene is loaded. */
  precision?: { density: WindFieldPrecision; light: WindFieldPrecision; points: WindFieldPrecision };
  /** On a small device, the memory the player keeps within (bytes), the most live blobs and the most bytes of the real-time view's targets; else null. */
  memoryBudget?: { bytes: number; blobCap: number; volumeBytes: number } | null;
  /** What this device gives up against a full one, one phrase each (empty on a full GPU). */
  gaveUp?: string[];
  /** The renderer WebGL names (the unmasked one where the browser gives it). */
  renderer?: string;
  /** Whether that renderer draws on the CPU (SwiftShader, llvmpipe, Microsoft Basic Render). */
  software?: boolean;
  /** While the lighter version is shown: why (`'software'`, the renderer; `'slow'`, the view kept under 10 frames a second at its lowest resolution) and the settings it gave up, in words; else null. */
  lighter?: { reason: 'software' | 'slow'; gaveUp: string[] } | null;
  /** The most live blobs the scene runs with under the lighter version's cap or the memory budget's (its own `gas.max_blobs` is larger); else null. */
  sceneBlobCap?: number | null;
}

/**
 * The flow's grid at one time (`exportFlow()`): the layout `windfield flow --out FILE.npy`
 * writes, split into its velocity and its temperature.
 */
export interface WindFieldFlowGrid {
  /** The box `[x0, y0, z0, x1, y1, z1]` (m). */
  box: number[];
  /** The cells `[nx, ny, nz]`. */
  cells: number[];
  /** The simulated time of the grid (s). */
  time: number;
  /** u_g at the cells' centres (m/s): `(nz, ny, nx, 3)`, x fastest, 3·nx·ny·nz floats. */
  velocity: Float32Array;
  /** The gas's temperature excess T at the cells' centres (K): `(nz, ny, nx)`, x fastest. */
  temperature: Float32Array;
}

/** How a GPU pass stores floats. */
export type WindFieldPrecision = 'float32' | 'float16';

export interface CaptureOptions {
  mode?: WindFieldView;
  width?: number;
  height?: number;
  quality?: WindFieldQuality;
  /** Draw models (the mug, the teapot) as the cylinders the CPU still uses. */
  standIns?: boolean;
}

/** The methods of the browser API (docs/FORMATS.md), on every <wind-field> and on the playground's `window.windfield`. */
export interface WindFieldMethods {
  /** The current scene (a copy); the element returns null before its scene is loaded. */
  getScene(): Scene | null;
  /** Loads `scene` from its start; rejects with an Error naming the bad key, and keeps the old one. */
  setScene(scene: SceneInput): Promise<Scene>;
  /**
   * Applies an edited scene to the running one: the gas keeps its blobs and its time (a change
   * of the field's settings is synthesised meanwhile); rejects like `setScene`.
   */
  editScene(scene: SceneInput): Promise<Scene>;
  /** Chooses what steps the gas (`gpu` and `auto`: the GPU where it can, else the worker); resolves with the one that steps now. */
  setStepper(kind: WindFieldStepper | 'auto'): Promise<WindFieldStepper>;
  /** Stops playing; resolves once the steps already in flight are shown, so `stats()` holds still. */
  pause(): Promise<void>;
  play(): void;
  /** Takes `n` fixed steps (deterministic) and draws. */
  step(n?: number): Promise<void>;
  stats(): WindFieldStats;
  /** The blob list of the current state as the current view sees it. */
  exportBlobs(size?: { width: number; height: number }): Promise<BlobList>;
  /** A PNG data URL of a view drawn on the GPU at the size asked for. */
  captureGPU(options?: CaptureOptions): Promise<string>;
  /** A PNG data URL from the WASM CPU reference renderer. */
  renderReference(options?: { width?: number; height?: number }): Promise<string>;
  /**
   * The CPU reference still of the current state from the view's camera as a file: PNG (8-bit;
   * RGBA with straight colour when `alpha`) or OpenEXR (half-float linear RGBA, premultiplied);
   * the bytes `windfield render` writes for the same blob list. Default: PNG, no alpha, the
   * view's size.
   */
  exportStill(options?: ExportStillOptions): Promise<Blob>;
  /**
   * The scene's frames `frames[0]` to `frames[1]` (half-open, frame k at k/fps, simulated from
   * t = 0 apart from the running scene) as one sprite sheet with alpha, from the view's camera;
   * the bytes of `windfield flipbook`. The Blob carries the sheet's JSON as `description`.
   */
  exportFlipbook(options?: ExportFlipbookOptions): Promise<Blob & { description: FlipbookDescription }>;
  /** The gas's density (and emission) as an OpenVDB file, voxels of `voxel` m; the bytes of `windfield volume`. */
  exportVolume(options: { voxel: number; format?: 'vdb' }): Promise<Blob>;
  /** Cancels the exports in flight (they reject with "cancelled: …"); resolves with how many there were. */
  cancelExport(): Promise<number>;
  /** The flow's grid now (velocity and temperature, whole typed arrays); null for a scene without a flow. */
  exportFlow(): Promise<WindFieldFlowGrid | null>;
}

export interface ExportStillOptions {
  format?: 'png' | 'exr';
  /** A transparent background: alpha = 1 − T(∞) over the gas, 1 on objects. */
  alpha?: boolean;
  width?: number;
  height?: number;
}

export interface ExportFlipbookOptions {
  /** [A, B]: frames A..B, half-open (default [0, 64]). */
  frames?: [number, number];
  /** Frames per second (default 24). */
  fps?: number;
  /** [columns, rows] (default [8, 8]). */
  grid?: [number, number];
  /** [width, height] of a tile in pixels (default [256, 256]). */
  tile?: [number, number];
  /** A seamless loop: true blends a quarter of the frames across the wrap, a number that many. */
  loop?: boolean | number;
  format?: 'png' | 'exr';
}

/** The JSON description beside a sprite sheet (`windfield flipbook`'s `SHEET.json`). */
export interface FlipbookDescription {
  format: 'windfield-flipbook/1';
  image: string;
  columns: number;
  rows: number;
  fps: number;
  tile_width: number;
  tile_height: number;
  sheet_width: number;
  sheet_height: number;
  frame_count: number;
  frames: [number, number];
  frame_times: number[];
  order: string;
  alpha: 'straight' | 'premultiplied';
  encoding: 'srgb' | 'linear';
  loop: { fade_frames: number; seconds: number; field_periods: number } | null;
  time_period: number;
  windfield: string;
}

export interface WindFieldReadyDetail {
  /** The scene now shown. */
  scene: Scene;
}

export interface WindFieldErrorDetail {
  /** What went wrong, e.g. `field.size[1]: must be an even number between 4 and 256`. */
  message: string;
}

/** The element's own events. */
export interface WindFieldEventMap {
  /** A scene is loaded and drawn (at `poster-time` unless playing). */
  ready: CustomEvent<WindFieldReadyDetail>;
  /** The scene (or the player's code) could not be loaded. */
  error: CustomEvent<WindFieldErrorDetail>;
}

/** `<wind-field>`: a player for one scene. Each attribute is mirrored by the property named here. */
export declare class WindFieldElement extends HTMLElement {
  /** `src`: a scene JSON URL, relative to the page; wins over `preset`. */
  src: string | null;
  /** `preset`: a scene in `scenes/` (`default` when neither is set). */
  preset: string | null;
  /** `controls`: play/pause, step and view buttons. */
  controls: boolean;
  /** `autoplay`: play from t = 0 once ready (not under `prefers-reduced-motion: reduce`). */
  autoplay: boolean;
  /** `loading`: `lazy` (default) loads as the element nears the viewport; `eager` at once. */
  loading: 'lazy' | 'eager';
  /** `poster`: an image URL shown until the scene is ready. */
  poster: string | null;
  /** `poster-time`: seconds the scene is simulated to when not playing (by default the scene's `render.time`, else 3). */
  posterTime: number;
  /** `view`: `raymarch` (default), `points` or `exact`. */
  view: WindFieldView;
  /** `alt`: the canvas's text alternative (by default one naming the scene). */
  alt: string | null;
  /** `stir`: dragging over the view stirs the gas instead of orbiting it (off unless set). */
  stir: boolean;
  /** Resolves once the current scene is loaded and drawn; rejects when it cannot be. */
  readonly ready: Promise<void>;
  /** Whether the current scene is loaded. */
  readonly loaded: boolean;
  /** Starts loading now, whatever `loading` says. */
  load(): void;

  addEventListener<K extends keyof WindFieldEventMap>(type: K, listener: (this: WindFieldElement, ev: WindFieldEventMap[K]) => any, options?: boolean | AddEventListenerOptions): void;
  addEventListener<K extends keyof HTMLElementEventMap>(type: K, listener: (this: WindFieldElement, ev: HTMLElementEventMap[K]) => any, options?: boolean | AddEventListenerOptions): void;
  addEventListener(type: string, listener: EventListenerOrEventListenerObject, options?: boolean | AddEventListenerOptions): void;
  removeEventListener<K extends keyof WindFieldEventMap>(type: K, listener: (this: WindFieldElement, ev: WindFieldEventMap[K]) => any, options?: boolean | EventListenerOptions): void;
  removeEventListener<K extends keyof HTMLElementEventMap>(type: K, listener: (this: WindFieldElement, ev: HTMLElementEventMap[K]) => any, options?: boolean | EventListenerOptions): void;
  removeEventListener(type: string, listener: EventListenerOrEventListenerObject, options?: boolean | EventListenerOptions): void;
}

/** The methods of the browser API (docs/FORMATS.md) (declaration merging adds them to the class). */
export interface WindFieldElement extends WindFieldMethods {}

/** The playground's `window.windfield`: the methods of the browser API (docs/FORMATS.md) and a few for scripts and benchmarks. */
export interface WindFieldPageAPI extends WindFieldMethods {
  getScene(): Scene;
  /** Resolves once the page's first scene is loaded. */
  ready: Promise<void>;
  /** Shows the view `mode`; throws for any other. */
  setView(mode: WindFieldView): void;
  /** A WebM of `frames` fixed steps, one a frame. */
  recordWebM(options?: { frames?: number; width?: number; height?: number; fps?: number; mode?: WindFieldView }): Promise<Blob>;
  /** Times frames drawn from scratch (ms, the median). */
  timeFrames(options?: { mode?: WindFieldView; width?: number; height?: number; frames?: number; quality?: WindFieldQuality; rebuild?: boolean }): Promise<number>;
  /** The real-time view's volumes as the GPU holds them, beside the core's twin of them. */
  inspectVolume(options?: { quality?: WindFieldQuality }): Promise<unknown>;
  /** The field's statistics (`windfield stats`). */
  fieldStats(spectrum?: Partial<Scene['field']['spectrum']>): Promise<unknown>;
  /** The small-scale field at lattice coordinates (x, y, z, t), quadrilinearly: velocity in lattice units. */
  sample(x: number, y: number, z: number, t: number): Promise<unknown>;
  /**
   * The GPU stepper's own σ (m), mass and centre (xyz, m) of every blob and its slot, slot order,
   * and the views' frame of them as the GPU sorted and packed it; null while the worker steps.
   */
  inspectStepper(): Promise<{
    sigma: Float32Array; mass: Float32Array; centre: Float32Array; slot: number[];
    frame: { words: Uint32Array; info: Float32Array };
  } | null>;
  /** The median time (ms) of one GPU step of the current gas, finished on the GPU; null while the worker steps. */
  timeGpuStep(options?: { repeats?: number }): Promise<number | null>;
  /** The median time (ms) of sorting the GPU stepper's gas by σ class and packing it for the views, and of each pass; null while the worker steps. */
  timeGpuSort(options?: { repeats?: number }): Promise<{ ms: number; passes: Record<string, number> } | null>;
  /** The engine's health: its memory (bytes), the blob count, blobs whose centre is not finite. */
  health(): Promise<{ wasmBytes: number; blobs: number; nonFinite: number }>;
}

declare global {
  interface HTMLElementTagNameMap {
    'wind-field': WindFieldElement;
  }
  interface Window {
    /** Set by the playground page (index.html). */
    windfield?: WindFieldPageAPI;
  }
}
