// The packed frame (`render::frame` in the core: eight 32-bit words a blob, padded to whole
// rows) on the GPU, as an RGBA32UI texture of two texels a blob, BLOBS_PER_ROW blobs a row.
// The worker's buffer becomes the texture's data as it arrived: nothing per blob runs here.
// Every GPU view reads its blobs from it. The texture keeps the last frame's words as its data,
// so after a lost context is restored the same blobs are uploaded again (`contextRestored`).

import * as THREE from 'three';
import { BLOBS_PER_ROW } from './volume/glsl.js';

export class BlobTexture {
  constructor() {
    this.count = 0;
    this.texture = null;
    this.upload(new Uint32Array(0), 0);
  }

  /** Takes `words` (a Uint32Array of whole rows, or empty) holding `count` packed blobs. */
  upload(words, count) {
    if (words.length === 0) words = new Uint32Array(8 * BLOBS_PER_ROW);
    const rows = Math.max(1, words.length / (8 * BLOBS_PER_ROW));
    if (!Number.isInteger(rows)) throw new Error('packed blobs must fill whole texture rows');
    if (!this.texture || this.texture.image.height !== rows) {
      this.texture?.dispose();
      const tex = new THREE.DataTexture(words, 2 * BLOBS_PER_ROW, rows, THREE.RGBAIntegerFormat, THREE.UnsignedIntType);
      tex.internalFormat = 'RGBA32UI';
      tex.minFilter = THREE.NearestFilter;
      tex.magFilter = THREE.NearestFilter;
      tex.generateMipmaps = false;
      this.texture = tex;
    } else {
      this.texture.image.data = words;
    }
    this.texture.needsUpdate = true;
    this.count = count;
  }

  /** The context is lost: let go of its texture (`context-loss.js`); the data stays. */
  contextLost() {
    this.texture.dispose();
  }

  /** The context is back: upload the last frame's blobs again on the next draw. */
  contextRestored() {
    this.texture.needsUpdate = true;
  }

  dispose() {
    this.texture?.dispose();
  }
}
