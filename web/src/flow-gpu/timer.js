// The GPU's own time for a stretch of passes, where WebGL2 gives a timer query
// (EXT_disjoint_timer_query_webgl2): a query per stretch, its result read once the GPU has it
// (a later task, never the one that ended it), none kept over a disjoint period (the GPU's
// clock was interrupted), nor the first stretch's: the first draw of each pass compiles its
// program too (seconds in software), which is no step's time. Without the extension `ms` stays
// null.

/** Queries waiting for their results, at most; older ones are let go. */
const MOST_PENDING = 8;

export class GpuTimer {
  /** @param {WebGL2RenderingContext} gl */
  constructor(gl) {
    this.gl = gl;
    this.ext = gl.getExtension('EXT_disjoint_timer_query_webgl2');
    this.pending = [];
    this.active = null;
    /** The last stretch the GPU finished, ms; null before one (or without the extension). */
    this.ms = null;
    /** Whether the first stretch's result, its programs' compilation in it, is still to be let go. */
    this.warming = true;
  }

  /** Starts timing (nothing without the extension, or while a stretch is open). */
  begin() {
    if (!this.ext || this.active) return;
    this.poll();
    this.active = this.gl.createQuery();
    this.gl.beginQuery(this.ext.TIME_ELAPSED_EXT, this.active);
  }

  /** Ends the stretch begun. */
  end() {
    if (!this.active) return;
    this.gl.endQuery(this.ext.TIME_ELAPSED_EXT);
    this.pending.push(this.active);
    this.active = null;
    while (this.pending.length > MOST_PENDING) this.gl.deleteQuery(this.pending.shift());
  }

  /** Takes the results the GPU has: `ms` becomes the latest. */
  poll() {
    const gl = this.gl;
    if (!this.ext || this.pending.length === 0) return;
    const disjoint = gl.getParameter(this.ext.GPU_DISJOINT_EXT);
    while (this.pending.length > 0 && gl.getQueryParameter(this.pending[0], gl.QUERY_RESULT_AVAILABLE)) {
      const q = this.pending.shift();
      if (this.warming) this.warming = false;
      else if (!disjoint) this.ms = gl.getQueryParameter(q, gl.QUERY_RESULT) / 1e6;
      gl.deleteQuery(q);
    }
  }

  dispose() {
    if (this.active) this.gl.endQuery(this.ext.TIME_ELAPSED_EXT);
    for (const q of [...this.pending, ...(this.active ? [this.active] : [])]) this.gl.deleteQuery(q);
    this.pending = [];
    this.active = null;
  }
}
