// The error a player's calls reject with once the player is removed from its page: an
// AbortError, as fetch's and other aborted web APIs' are, so callers can tell it from a failure.

/** A new AbortError saying the player was removed from the page. */
export function removedError() {
  return new DOMException('the player was removed from the page', 'AbortError');
}
