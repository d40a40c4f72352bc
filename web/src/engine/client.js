// The page's handle on the engine worker: promise-returning requests, progress callbacks,
// and a restart (with a visible message) if the worker dies.

export class Engine {
  #worker = null;
  #pending = new Map();
  #nextId = 1;
  #listeners;

  /**
   * @param {{onProgress?: (p: {progress: number, stage: string}) => void,
   *          onError?: (message: string) => void,
   *          onRestart?: () => void}} listeners
   */
  constructor(listeners = {}) {
    this.#listeners = listeners;
    this.#start();
  }

  #start() {
    const worker = new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });
    worker.onmessage = (event) => this.#receive(event.data);
    worker.onerror = (event) => {
      event.preventDefault?.();
      this.#fail(`engine worker failed: ${event.message ?? 'unknown error'}`);
    };
    this.#worker = worker;
  }

  #receive(msg) {
    if (msg.type === 'fatal' || msg.type === 'crashed') {
      this.#fail(msg.error, msg.type === 'crashed');
      return;
    }
    const pending = this.#pending.get(msg.id);
    if (!pending) return;
    if (msg.type === 'progress') {
      pending.onProgress?.(msg);
      this.#listeners.onProgress?.(msg);
      return;
    }
    this.#pending.delete(msg.id);
    if (msg.ok) pending.resolve(msg.result);
    else pending.reject(new Error(msg.error));
  }

  /** Rejects everything in flight, reports the failure and (if `restart`) starts a new worker. */
  #fail(message, restart = true) {
    for (const p of this.#pending.values()) p.reject(new Error(message));
    this.#pending.clear();
    this.#listeners.onError?.(restart ? `${message}; restarting the engine` : message);
    this.#worker?.terminate();
    this.#worker = null;
    if (restart) {
      this.#start();
      this.#listeners.onRestart?.();
    }
  }

  /** Sends one request; resolves with its result. */
  request(type, args = {}, { transfer = [], onProgress } = {}) {
    if (!this.#worker) return Promise.reject(new Error('engine is not running'));
    const id = this.#nextId++;
    return new Promise((resolve, reject) => {
      this.#pending.set(id, { resolve, reject, onProgress });
      this.#worker.postMessage({ id, type, ...args }, transfer);
    });
  }

  terminate() {
    this.#worker?.terminate();
    this.#worker = null;
  }
}
