// The scene in the URL hash: `#scene=1.<base64url of the deflate-raw compressed JSON>`.
// The leading "1." is the codec version, so links made today keep decoding after the format
// grows; the scene inside carries its own format version too.

export const HASH_KEY = 'scene';
const CODEC_VERSION = '1';

function toBase64Url(bytes) {
  let binary = '';
  for (let i = 0; i < bytes.length; i += 0x8000) {
    binary += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  }
  return btoa(binary).replace(/\+/g, '-').replace(/\//g, '_').replace(/=+$/, '');
}

function fromBase64Url(text) {
  if (!/^[A-Za-z0-9_-]*$/.test(text)) throw new Error('the link is damaged (characters outside base64url)');
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

/** Encodes a scene object as the hash fragment (without '#'). */
export async function encodeScene(scene) {
  const json = new TextEncoder().encode(JSON.stringify(scene));
  const packed = await pipe(json, new CompressionStream('deflate-raw'));
  return `${HASH_KEY}=${CODEC_VERSION}.${toBase64Url(packed)}`;
}

/**
 * Decodes a hash fragment (with or without '#') to a scene object; null when the hash holds no
 * scene. Throws an Error with a readable message for damaged links.
 */
export async function decodeScene(hash) {
  const params = new URLSearchParams(hash.replace(/^#/, ''));
  const value = params.get(HASH_KEY);
  if (value === null) return null;
  const dot = value.indexOf('.');
  if (dot < 0) throw new Error('the link is damaged (no codec version)');
  const version = value.slice(0, dot);
  if (version !== CODEC_VERSION) throw new Error(`the link uses codec version ${version}; this page reads version ${CODEC_VERSION}`);
  let text;
  try {
    const bytes = await pipe(fromBase64Url(value.slice(dot + 1)), new DecompressionStream('deflate-raw'));
    text = new TextDecoder('utf-8', { fatal: true }).decode(bytes);
  } catch (err) {
    throw new Error(`the link is damaged (${err.message})`);
  }
  let scene;
  try {
    scene = JSON.parse(text);
  } catch {
    throw new Error('the link is damaged (not JSON)');
  }
  if (typeof scene !== 'object' || scene === null || Array.isArray(scene)) throw new Error('the link does not hold a scene object');
  return scene;
}
