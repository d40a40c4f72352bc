// The packed frame (`frame::packed` in the core: WORDS_PER_BLOB 32-bit words a blob, padded to
// whole rows) on the GPU, as an RGBA32UI texture of WORDS_PER_BLOB / 4 texels a blob,
// BLOBS_PER_ROW blobs a row (`shaders/blob-record.js` reads it).
// The worker's buffer becomes the texture's data as it arrived: nothing per blob runs here.
// Every GPU view reads its blobs from it. The texture keeps the last frame's words as its data,
// so after a lost context is restored the same blobs are uploaded again (`contextRestored`).

import * as THREE from 'three';
import { BLOBS_PER_ROW, WORDS_PER_BLOB } from '../generated/contract.js';

/** RGBA32UI texels a blob. */
const TEXELS_PER_BLOB = WORDS_PER_BLOB / 4;

export class BlobTexture {
  /** The texture holding the worker's words, and one another pass keeps (the GPU stepper's). */
  #own = null;
  #shown = null;

  constructor() {
    this.count = 0;
    this.upload(new Uint32Array(0), 0);
  }

  /** The texture the views read. */
  get texture() {
    return this.#shown ?? this.#own;
  }

  /**
   * The words of the blobs shown, in the core's packed order (`frame::packed`), or null when
   * another pass's texture is shown (its state is on the GPU only).
   */
  get words() {
    return this.#shown ? null : this.#own.image.data;
  }

  /**
   * Shows `texture`, an RGBA32UI texture in the same layout that another pass keeps on the GPU
   * (the GPU stepper's packed state), holding `count` blobs (empty ones with mass 0).
   */
  show(texture, count) {
    this.#shown = texture;
    this.count = count;
  }

  /** Takes `words` (a Uint32Array of whole rows, or empty) holding `count` packed blobs. */
  upload(words, count) {
    if (words.length === 0) words = new Uint32Array(WORDS_PER_BLOB * BLOBS_PER_ROW);
    const rows = Math.max(1, words.length / (WORDS_PER_BLOB * BLOBS_PER_ROW));
    if (!Number.isInteger(rows)) throw new Error('packed blobs must fill whole texture rows');
    this.#shown = null;
    if (!this.#own || this.#own.image.height !== rows) {
      this.#own?.dispose();
      const tex = new THREE.DataTexture(words, TEXELS_PER_BLOB * BLOBS_PER_ROW, rows, THREE.RGBAIntegerFormat, THREE.UnsignedIntType);
      tex.internalFormat = 'RGBA32UI';
      tex.minFilter = THREE.NearestFilter;
      tex.magFilter = THREE.NearestFilter;
      tex.generateMipmaps = false;
      this.#own = tex;
    } else {
      this.#own.image.data = words;
    }
    this.#own.needsUpdate = true;
    this.count = count;
  }

  /** The context is lost: let go of its texture (`context-loss.js`); the data stays. */
  contextLost() {
    this.#own.dispose();
  }

  /** The context is back: upload the last frame's blobs again on the next draw. */
  contextRestored() {
    this.#own.needsUpdate = true;
  }

  dispose() {
    this.#own?.dispose();
  }
}
