// The page's handle on the engine worker: promise-returning requests, progress callbacks, a
// time limit on every request, and a restart (with a visible message) if the worker dies,
// traps, or stops answering.

/** A request with no reply and no progress for this long (ms) has lost its worker. */
export const REQUEST_TIMEOUT_MS = 30_000;

export class Engine {
  #worker = null;
  #pending = new Map();
  #nextId = 1;
  #listeners;
  #timeoutMs;

  /**
   * @param {{onProgress?: (p: {progress: number, stage: string}) => void,
   *          onError?: (message: string) => void,
   *          onRestart?: (reason: string) => void}} listeners
   * @param {{timeoutMs?: number}} options how long a request may go without a reply or progress
   */
  constructor(listeners = {}, { timeoutMs = REQUEST_TIMEOUT_MS } = {}) {
    this.#listeners = listeners;
    this.#timeoutMs = timeoutMs;
    this.#start();
  }

  #start() {
    const worker = new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });
    worker.onmessage = (event) => this.#receive(event.data);
    worker.onmessageerror = () => this.#fail('the engine sent a reply the page could not read');
    worker.onerror = (event) => {
      event.preventDefault?.();
      this.#fail(`the engine worker failed (${event.message ?? 'unknown error'})`);
    };
    this.#worker = worker;
  }

  #receive(msg) {
    if (!msg || typeof msg !== 'object') return;
    if (msg.type === 'fatal' || msg.type === 'crashed') {
      this.#fail(msg.error, msg.type === 'crashed');
      return;
    }
    const pending = this.#pending.get(msg.id);
    if (!pending) {
      // Progress of work that goes on after its request was answered (a field synthesised for
      // an edit) still reaches the page.
      if (msg.type === 'progress') this.#listeners.onProgress?.(msg);
      return;
    }
    this.#arm(msg.id, pending);
    if (msg.type === 'progress') {
      pending.onProgress?.(msg);
      this.#listeners.onProgress?.(msg);
      return;
    }
    clearTimeout(pending.timer);
    this.#pending.delete(msg.id);
    if (msg.ok) pending.resolve(msg.result);
    else pending.reject(new Error(msg.error));
  }

  /** (Re)starts request `id`'s clock: no word from the worker for the time limit fails it. */
  #arm(id, pending) {
    clearTimeout(pending.timer);
    pending.timer = setTimeout(() => {
      if (this.#pending.get(id) !== pending) return;
      this.#fail(`the engine did not answer for ${Math.round(this.#timeoutMs / 1000)} s`);
    }, this.#timeoutMs);
  }

  /** Rejects everything in flight, reports the failure and (if `restart`) starts a new worker. */
  #fail(message, restart = true) {
    for (const p of this.#pending.values()) {
      clearTimeout(p.timer);
      p.reject(new Error(message));
    }
    this.#pending.clear();
    this.#listeners.onError?.(restart ? `${message}; restarting the engine` : message);
    this.#worker?.terminate();
    this.#worker = null;
    if (restart) {
      this.#start();
      this.#listeners.onRestart?.(message);
    }
  }

  /**
   * Sends one request; resolves with its result, rejects with the worker's error, or when the
   * worker gives no reply nor progress for the time limit (the worker is then restarted).
   */
  request(type, args = {}, { transfer = [], onProgress } = {}) {
    if (!this.#worker) return Promise.reject(new Error('the engine is not running'));
    const id = this.#nextId++;
    return new Promise((resolve, reject) => {
      const pending = { resolve, reject, onProgress, timer: 0 };
      this.#pending.set(id, pending);
      this.#arm(id, pending);
      try {
        this.#worker.postMessage({ id, type, ...args }, transfer);
      } catch (err) {
        clearTimeout(pending.timer);
        this.#pending.delete(id);
        reject(new Error(`could not send the request to the engine (${err?.message ?? err})`));
      }
    });
  }

  terminate() {
    for (const p of this.#pending.values()) clearTimeout(p.timer);
    this.#worker?.terminate();
    this.#worker = null;
  }
}
