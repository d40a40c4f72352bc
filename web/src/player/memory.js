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
// the blobs, half for the real-time view's volume.

/** Device memory (GiB) at or below which a device counts as small. */
const SMALL_DEVICE_GIB = 2;
/** Largest texture side (texels) at or below which a GPU counts as phone-class. */
export const PHONE_TEXTURE_SIZE = 4096;
/** The share of the device's memory the player keeps within. */
const SHARE = 1 / 8;

/**
 * Bytes a live blob takes at most, whoever steps it: in the worker 80 B in the core, 2 × 32 B
 * of packed frames in flight and 32 B of blob texture (176 B); with the GPU stepper 80 B in the
 * core and 144 B of GPU state (224 B); and room for the exact view's merged list.
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
export function budgetWords(budget) {
  const device = `${budget.deviceGib} GiB${budget.reported ? '' : ' assumed'}`;
  const gpu = budget.phoneClass ? ', a phone-class GPU' : '';
  return `a memory budget of ${Math.round(budget.bytes / 2 ** 20)} MiB (an eighth of ${device}${gpu})`;
}
