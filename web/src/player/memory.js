// The memory a player may take on a small device, and what it may hold within it. A phone's
// GPU shares the phone's memory, and a tab that asks for too much is closed: on a device that
// looks small the player keeps its blobs and its real-time view's volume within a budget, the
// scene running under a blob cap (`engine/lighten.js`: fewer, heavier, wider blobs of the same
// gas) and the view's grid holding fewer voxels, and `stats().gaveUp` says so. Elsewhere no
// budget applies.
//
// A device looks small when its GPU is phone-class (textures of at most 4096 texels a side, or
// no 32-bit float render targets: `precision.js`) or when the browser reports at most 2 GiB of
// memory (`navigator.deviceMemory`, Chromium's, rounded down to a power of two). The budget is
// an eighth of the device's memory (2 GiB assumed where it is not reported), half of it for
// the blobs, half for the real-time view's volume; in a scene with a flow the view's half is
// shared, a quarter of the budget for the volume and a quarter for the flow's textures on the
// GPU (`flow-gpu/gpu-flow.js`'s `gpuFlowBytes`: a flow larger than that is stepped in the worker,
// where the core's own budget holds it).

import { formatsGaveUp } from '../views/precision.js';

/** Device memory (GiB) at or below which a device counts as small. */
const SMALL_DEVICE_GIB = 2;
/** Largest texture side (texels) at or below which a GPU counts as phone-class. */
const PHONE_TEXTURE_SIZE = 4096;
/** The share of the device's memory the player keeps within. */
const SHARE = 1 / 8;

/**
 * Bytes a live blob takes at most, whoever steps it: in the worker 80 B in the core, 2 × 32 B
 * of packed frames in flight and 32 B of blob texture (176 B); with the GPU stepper 80 B in the
 * core, 144 B of GPU state and 13 B of its sort by σ class (`stepper/binning.js`: a block's
 * keys, two sets of bin counts, the order), 237 B; and room for the exact view's merged list.
 */
export const BYTES_PER_BLOB = 256;

/**
 * The budget on a device with `deviceMemory` GiB (undefined where the browser does not say)
 * and a GPU of `formats` (`gpuFormats`): null where none applies, else `{bytes, deviceGib,
 * reported, phoneClass, blobCap, volumeBytes}` (`blobCap`: most live blobs; `volumeBytes`: most
 * bytes of the real-time view's targets).
 */
export function memoryBudget(deviceMemory, formats) {
  const reported = Number.isFinite(deviceMemory) && deviceMemory > 0;
  const phoneClass = formats.maxTextureSize <= PHONE_TEXTURE_SIZE || !formats.float32Targets;
  if (!phoneClass && !(reported && deviceMemory <= SMALL_DEVICE_GIB)) return null;
  const deviceGib = reported ? deviceMemory : SMALL_DEVICE_GIB;
  const bytes = deviceGib * 2 ** 30 * SHARE;
  return {
    bytes,
    deviceGib,
    reported,
    phoneClass,
    blobCap: Math.floor(bytes / 2 / BYTES_PER_BLOB),
    volumeBytes: bytes / 2,
  };
}

/** What the budget gives up for a scene capped at `cap` blobs (or null), in words. */
function budgetWords(budget) {
  const device = `${budget.deviceGib} GiB${budget.reported ? '' : ' assumed'}`;
  const gpu = budget.phoneClass ? ', a phone-class GPU' : '';
  return `a memory budget of ${Math.round(budget.bytes / 2 ** 20)} MiB (an eighth of ${device}${gpu})`;
}

/**
 * A player's memory budget in use (`memoryBudget`, or none): the blob cap it sets, whether it
 * holds the running scene to fewer blobs, the notice of it (told once a scene), and what it and
 * the largest texture gave up (`stats().gaveUp`).
 */
export class MemoryLimit {
  /** The budget, or null where none applies. */
  #budget;
  /** The scene (its JSON text) whose cap was last told of, so it is told once. */
  #told = null;

  /** @param {number | undefined} deviceMemory @param {object} formats the GPU's (`gpuFormats`) */
  constructor(deviceMemory, formats) {
    this.#budget = memoryBudget(deviceMemory, formats);
  }

  /**
   * Most bytes of the real-time view's targets (Infinity where no budget applies): half the
   * budget, a quarter in a scene `withFlow`.
   */
  volumeBytes(withFlow = false) {
    const half = this.#budget?.volumeBytes ?? Infinity;
    return withFlow ? half / 2 : half;
  }

  /** Most bytes of a flow's textures on the GPU: a quarter of the budget (Infinity where none applies). */
  get flowBytes() {
    return this.#budget ? this.#budget.bytes / 4 : Infinity;
  }

  /** The blob cap a scene runs under: `chosen` (a number, or null for none) within the budget's; null for none. */
  blobCap(chosen) {
    const caps = [chosen, this.#budget?.blobCap].filter((c) => Number.isInteger(c));
    return caps.length > 0 ? Math.min(...caps) : null;
  }

  /** Whether the scene running under `sceneBlobCap` (the engine's) is held to fewer blobs by the budget. */
  #holds(sceneBlobCap) {
    return this.#budget !== null && sceneBlobCap === this.#budget.blobCap;
  }

  /**
   * The notice that the budget holds the scene `sceneJson` (running under `sceneBlobCap`) to
   * fewer blobs, the first time it does; else null.
   */
  notice(sceneJson, sceneBlobCap) {
    if (!this.#holds(sceneBlobCap) || this.#told === sceneJson) return null;
    this.#told = sceneJson;
    return `This device has little memory for 3-D: the scene runs with at most ${this.#budget.blobCap.toLocaleString('en')} blobs `
      + `(fewer, heavier blobs of the same gas), within ${budgetWords(this.#budget)}.`;
  }

  /** `stats().memoryBudget`: `{bytes, blobCap, volumeBytes}`, or null. */
  snapshot() {
    const b = this.#budget;
    return b && { bytes: b.bytes, blobCap: b.blobCap, volumeBytes: b.volumeBytes };
  }

  /**
   * What this device gave up against a full one, one phrase each (`stats().gaveUp`): the float
   * formats its GPU lacks (`views/precision.js`), and what the budget (for a scene running
   * under `sceneBlobCap`) and the largest texture held back of `view`'s.
   */
  gaveUp(view, sceneBlobCap) {
    const formats = view.formats;
    const out = formatsGaveUp(formats);
    const grid = ({ voxels, of }) => `the real-time view's grid of ${voxels.toLocaleString('en')} voxels instead of ${of.toLocaleString('en')}`;
    if (this.#holds(sceneBlobCap)) out.push(`${budgetWords(this.#budget)}: at most ${this.#budget.blobCap.toLocaleString('en')} blobs`);
    const shrunk = view.volume.grid ? view.volume.shrunk : {};
    if (shrunk.memory) out.push(`${budgetWords(this.#budget)}: ${grid(shrunk.memory)}`);
    if (shrunk.textureSize) out.push(`textures of at most ${formats.maxTextureSize} texels a side: ${grid(shrunk.textureSize)}`);
    return out;
  }
}
