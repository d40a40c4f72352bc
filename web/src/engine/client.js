// The page's handle on the engine worker: promise-returning requests, progress callbacks, a
// time limit on every request, and a restart (with a visible message) if the worker dies,
// traps, or stops answering.

import { removedError } from './removed.js';

/** A request with no reply and no progress for this long (ms) has lost its worker. */
const REQUEST_TIMEOUT_MS = 30_000;
/** The range a request's time limit may be set in (ms): a second to an hour. */
const MIN_TIMEOUT_MS = 1000;
const MAX_TIMEOUT_MS = 3_600_000;


export class Engine {
  #worker = null;
  #pending = new Map();
  #nextId = 1;
  #listeners;
  #timeoutMs;

  /**
   * @param {{onProgress?: (p: {progress: number, stage: string}) => void,
   *          onError?: (message: string) => void,
   *          onRestart?: (reason: string, how: {recycled: boolean}) => void}} listeners
   * @param {{timeoutMs?: number}} options how long a request may go without a reply or
   *   progress (ms; held within MIN_TIMEOUT_MS to MAX_TIMEOUT_MS, REQUEST_TIMEOUT_MS when it is
   *   not a number)
   */
  constructor(listeners = {}, { timeoutMs = REQUEST_TIMEOUT_MS } = {}) {
    this.#listeners = listeners;
    this.#timeoutMs = Number.isFinite(timeoutMs) ? Math.min(Math.max(timeoutMs, MIN_TIMEOUT_MS), MAX_TIMEOUT_MS) : REQUEST_TIMEOUT_MS;
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
    // Nothing else failed: a new worker gives back the memory the refused request took.
    if (!msg.ok && msg.recycle) this.#fail(msg.recycle, true, { recycled: true });
  }

  /** (Re)starts request `id`'s clock: no word from the worker for the time limit fails it. */
  #arm(id, pending) {
    clearTimeout(pending.timer);
    pending.timer = setTimeout(() => {
      if (this.#pending.get(id) !== pending) return;
      this.#fail(`the engine did not answer for ${Math.round(this.#timeoutMs / 1000)} s`);
    }, this.#timeoutMs);
  }

  /**
   * Rejects everything in flight, reports the failure and (if `restart`) starts a new worker;
   * `recycled`: nothing failed, the worker was restarted to give back memory (not reported as
   * an error).
   */
  #fail(message, restart = true, { recycled = false } = {}) {
    for (const p of this.#pending.values()) {
      clearTimeout(p.timer);
      p.reject(new Error(message));
    }
    this.#pending.clear();
    if (!recycled) this.#listeners.onError?.(restart ? `${message}; restarting the engine` : message);
    this.#worker?.terminate();
    this.#worker = null;
    if (restart) {
      this.#start();
      this.#listeners.onRestart?.(message, { recycled });
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

  /** Ends the worker; every request in flight rejects with `error` (by default `removedError()`). */
  terminate(error = removedError()) {
    for (const p of this.#pending.values()) {
      clearTimeout(p.timer);
      p.reject(error);
    }
    this.#pending.clear();
    this.#worker?.terminate();
    this.#worker = null;
  }

  /** Whether the worker runs (false once terminated). */
  get running() {
    return this.#worker !== null;
  }
}
