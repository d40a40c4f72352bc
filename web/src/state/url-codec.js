// The scene in the URL hash: `#scene=1.<base64url of the deflate-raw compressed JSON>`.
// The leading "1." is the codec version, so links made today keep decoding after the format
// grows; the scene inside carries its own format version too. A link may also carry the scene
// as plain JSON, percent-encoded or not (`#scene={"version":1,…}`), as a person or another
// program writes one by hand; the page's own links are compressed.
//
// Links are opened by strangers: a link longer than `MAX_LINK_CHARS`, or one that inflates past
// `MAX_LINK_SCENE_BYTES`, is refused before more of it is read. Errors say what is wrong with the
// link in a reader's words.

export const HASH_KEY = 'scene';
const CODEC_VERSION = '1';
/** Longest encoded scene a link may carry (characters of base64url): 1 MiB. */
const MAX_LINK_CHARS = 1 << 20;
/**
 * Largest scene a link may inflate to (bytes of JSON): 4 MiB, far more than any scene needs. The
 * link's own bound, below the core's for any scene text (`scene::limits::MAX_SCENE_BYTES`).
 */
const MAX_LINK_SCENE_BYTES = 4 << 20;

const DAMAGED = 'the link is damaged or cut short';

function toBase64Url(bytes) {
  let binary = '';
  for (let i = 0; i < bytes.length; i += 0x8000) {
    binary += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  }
  return btoa(binary).replace(/\+/g, '-').replace(/\//g, '_').replace(/=+$/, '');
}

function fromBase64Url(text) {
  if (!/^[A-Za-z0-9_-]*$/.test(text) || text.length % 4 === 1) throw new Error(DAMAGED);
  const padded = text.replace(/-/g, '+').replace(/_/g, '/') + '==='.slice((text.length + 3) % 4);
  const binary = atob(padded);
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; i++) bytes[i] = binary.charCodeAt(i);
  return bytes;
}

async function pipe(bytes, stream) {
  const out = new Blob([bytes]).stream().pipeThrough(stream);
  return new Uint8Array(await new Response(out).arrayBuffer());
}

/** Inflates `bytes`, reading no more than `limit` bytes of output (then throws). */
async function inflate(bytes, limit) {
  const reader = new Blob([bytes]).stream().pipeThrough(new DecompressionStream('deflate-raw')).getReader();
  const chunks = [];
  let total = 0;
  for (;;) {
    const { done, value } = await reader.read();
    if (done) break;
    total += value.length;
    if (total > limit) {
      await reader.cancel();
      throw new Error(`the link's scene is larger than ${limit / (1 << 20)} MiB, more than any scene needs`);
    }
    chunks.push(value);
  }
  const out = new Uint8Array(total);
  let at = 0;
  for (const c of chunks) {
    out.set(c, at);
    at += c.length;
  }
  return out;
}

/** Encodes a scene object as the hash fragment (without '#'). */
export async function encodeScene(scene) {
  const json = new TextEncoder().encode(JSON.stringify(scene));
  const packed = await pipe(json, new CompressionStream('deflate-raw'));
  return `${HASH_KEY}=${CODEC_VERSION}.${toBase64Url(packed)}`;
}

/**
 * Decodes a hash fragment (with or without '#') to a scene object; null when the hash holds no
 * scene. Throws an Error with a readable message for a damaged, foreign or oversized link.
 */
export async function decodeScene(hash) {
  if (hash.length > MAX_LINK_CHARS + 64) throw new Error(`the link is longer than ${MAX_LINK_CHARS / (1 << 20)} MiB, more than any scene needs`);
  const params = new URLSearchParams(hash.replace(/^#/, ''));
  const value = params.get(HASH_KEY);
  if (value === null) return null;
  if (value.trimStart().startsWith('{')) return plainScene(value);
  const dot = value.indexOf('.');
  if (dot < 0) throw new Error(DAMAGED);
  const version = value.slice(0, dot);
  if (version !== CODEC_VERSION) throw new Error(`the link was made by another version of this page (codec version ${version}; this page reads version ${CODEC_VERSION})`);
  let bytes;
  try {
    bytes = fromBase64Url(value.slice(dot + 1));
  } catch {
    throw new Error(DAMAGED);
  }
  let text;
  try {
    text = new TextDecoder('utf-8', { fatal: true }).decode(await inflate(bytes, MAX_LINK_SCENE_BYTES));
  } catch (err) {
    throw err.message.startsWith("the link's scene is larger") ? err : new Error(DAMAGED);
  }
  let scene;
  try {
    scene = JSON.parse(text);
  } catch {
    throw new Error(DAMAGED);
  }
  return sceneObject(scene);
}

/** A scene given as plain JSON in the link (`#scene={…}`). */
function plainScene(text) {
  let scene;
  try {
    scene = JSON.parse(text);
  } catch {
    throw new Error("the link's scene is not valid JSON (written by hand, it must be percent-encoded: encodeURIComponent)");
  }
  return sceneObject(scene);
}

/** `scene` if it is a JSON object, else the link's error. */
function sceneObject(scene) {
  if (typeof scene !== 'object' || scene === null || Array.isArray(scene)) throw new Error('the link holds no scene object');
  return scene;
}
