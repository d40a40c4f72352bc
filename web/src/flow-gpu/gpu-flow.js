// The flow stepped on the GPU (paper §7's physical large scales; docs/CONVENTIONS.md, the flow):
// the grid's velocity u_g (m/s) on a MAC grid, each component's faces in an R32F atlas (`gl.js`),
// stepped by the core's laws in the core's order (`wind::flow::step`): advect u_g by u_p + u_g
// (semi-Lagrangian with MacCormack's clamped correction, the traces in cells through the cells'
// velocity), diffuse it (explicit substeps, ν·dt_sub/h² ≤ 1/8), with `eddies` let Smagorinsky's
// eddy viscosity ν_t act on it (`wind::flow::subgrid`: ν_t from the step's first u_g, one explicit
// pass on the free faces), add the buoyancy −β T g and the force splats, set the fixed faces so
// that (u_p + u_g)·n = v·n, and project: the divergence, a Poisson solve for φ = p·dt/ρ, and the
// free faces lose ∇φ.
//
// The Poisson solve is red-black successive over-relaxation in f32 from the last step's φ (a warm
// start, as the core's conjugate gradients take), a number of iterations a step (two passes
// each): at first 3 × the longest side of cells + 30 with open faces, 5 × + 30 with closed ones
// (the Neumann problem converges slower), which reached a relative residual max|b − Aφ| / max|b|
// of 1e-4 or better on the boxes checked (`residual()` measures it: at 32³ round a sphere in a
// wind and a stir, 3e-6–7e-7 open, 3e-6–7e-5 closed, where f32 sets the floor: φ is some n times
// b, and A·φ cancels to b; the core's MIC(0) conjugate gradients stop at 1e-5 in f64). The count
// is then sized to the tolerance, GPU_TOLERANCE: at the SIZING_STEP-th step the residual is read
// back, and while it is above the tolerance the next step takes half as many iterations again
// and is measured in turn (`#size`), up to MOST_ITERATIONS × that first count; where more
// iterations gain little (f32's floor) the count before them stays. With no
// open face b's mean over the fluid cells is taken out first, as the core does. Where b is 0 on
// every cell the core sets φ = 0; the sweeps here relax the last φ towards 0 instead (the same
// from rest). Nothing is read back unless asked (`faces`, `cellVelocity`, `velocityAt`,
// `residual`, `eddyViscosity`). The passes set the context's state they need (`passState`); a
// three.js renderer sharing the context calls `resetState()` after them.
//
// Cost per step: 1 carrier pass (u_p + u_g at the cells' centres), 6 advection passes (a face's
// two traces blend the carrier's three components at once at their midpoints, and its value
// where each lands), 3 per diffusion substep, with eddies 2 for ν_t and 3 for its diffusion, up
// to 3 for buoyancy and for each splat, 3 to impose, 1 divergence (and, closed, a reduction of
// 3–4 passes and 1 to centre b), 2 per SOR iteration, 3 for the gradient: at 64³ open, 222
// iterations, about 460 passes. A multigrid solve would take fewer.

import { boundaryOf, closedAxes, faceDims, noSolids } from './boundary.js';
import { REDUCE_BLOCK, textureTable } from './textures.js';
import { Lattice, Pass, passState } from './gl.js';
import {
  ADVECT_BACK, ADVECT_CORRECT, BUOYANCY, CARRIER, CENTRES, DIFFUSE, DIVERGENCE, EDDY_DIFFUSE, EDDY_VISCOSITY, GRADIENT, IMPOSE, PROBE, REDUCE, CENTRE_B, RELAX, RESIDUAL, SPLAT,
  WIND_ON_FACES,
} from './passes.js';

/** How long a stir takes to bring the flow at its centre to its velocity (s, `scene_flow::STIR_TIME`). */
export const STIR_TIME = 0.05;
/** A stir's width in cells, fewest and most (`scene_flow::STIR_CELLS`). */
export const STIR_CELLS = [1.5, 4];
/** The relative residual max|b − Aφ| / max|b| the projection is held to (the flow's, 1e-4). */
export const GPU_TOLERANCE = 1e-4;
/** The step at which the projection's residual is first read back to size its iterations. */
export const SIZING_STEP = 10;
/** The most iterations the sizing takes, as a multiple of the first count. */
const MOST_ITERATIONS = 4;
/** The largest ν·dt/h² of one diffusion substep (the core's `diffuse::STABLE`). */
const STABLE = 0.125;
/** Air's kinematic viscosity (m²/s) and an ideal gas's expansion at room temperature (1/K). */
const AIR = { viscosity: 1.5e-5, buoyancy: 1 / 293.15 };
/** Smagorinsky's constant C_s (`subgrid::SMAGORINSKY`). */
export const SMAGORINSKY = 0.17;

const f32 = Math.fround;

/** Where component `axis`'s samples lie, in cells from the origin (the core's `Grid::offset`). */
function offsetOf(axis) {
  const o = [0.5, 0.5, 0.5];
  o[axis] = 0;
  return o;
}

/** A ping-pong pair of lattices: `now` read, `next` written, then swapped. */
class Pair {
  constructor(gl, dims, channels = 1) {
    this.both = [new Lattice(gl, dims, channels), new Lattice(gl, dims, channels)];
    this.current = 0;
  }

  get now() {
    return this.both[this.current];
  }

  get next() {
    return this.both[1 - this.current];
  }

  swap() {
    this.current = 1 - this.current;
  }

  get bytes() {
    return this.both[0].bytes + this.both[1].bytes;
  }

  dispose() {
    for (const l of this.both) l.dispose();
  }
}

export class GpuFlow {
  #sizing = null;

  /**
   * The flow at rest on the grid of `origin` (m), `cells` [nx, ny, nz] and cube edge `h` (m)
   * with `faces` 'open', 'closed' or {x, y, z} of those (each axis's two faces), ν `viscosity`
   * (m²/s), β `buoyancy` (1/K), `gravity` (m/s²), Smagorinsky's eddy viscosity when `eddies`
   * (a scene's flow has it, the core's bare `Flow` not), and the SOR's `iterations` a step to
   * start from (sized to the tolerance from the SIZING_STEP-th step) and `omega`, on the
   * WebGL2 context `gl` (float render targets: `flowGpuUnsupported`).
   */
  constructor(gl, { origin, cells, h, faces = 'open', viscosity = AIR.viscosity, buoyancy = AIR.buoyancy, gravity = [0, -9.81, 0], eddies = false, iterations, omega }) {
    this.gl = gl;
    this.origin = origin.map(f32);
    this.cells = [...cells];
    this.h = f32(h);
    // The box's faces as the scene says them (`faces()` reads u_g back), and 1 on the axes
    // whose faces are open, 0 on the closed (the advection's fade and the gradient read it).
    this.boxFaces = faces;
    const closed = closedAxes(faces);
    this.openAxes = { vec3: closed.map((c) => (c ? 0 : 1)) };
    const allClosed = closed.every(Boolean);
    this.viscosity = f32(viscosity);
    this.buoyancy = f32(buoyancy);
    this.gravity = gravity.map(f32);
    this.eddies = eddies;
    const longest = Math.max(...cells);
    const first = (allClosed ? 5 : 3) * longest + 30;
    this.iterations = iterations ?? first;
    // The sizing of the iterations to the tolerance (`#size`): when it next reads the residual,
    // the last residual it read and the count then. `sizedResidual` is the last it read.
    this.#sizing = { due: SIZING_STEP, last: Infinity, previous: this.iterations, most: MOST_ITERATIONS * Math.max(first, this.iterations) };
    this.sizedResidual = null;
    // SOR's best ω for the model problem on a cube of the longest side: 2/(1 + π/n) with the
    // box's faces open (p = 0 beyond them), 2/(1 + π/(√3 n)) with them closed (the Neumann
    // problem's smallest eigenvalue but the constant's is a third of the Dirichlet one's).
    const side = allClosed ? Math.sqrt(3) * longest : longest;
    this.omega = omega ?? 2 / (1 + Math.sin(Math.PI / side));
    const textures = textureTable(cells, gl.getParameter(gl.MAX_TEXTURE_SIZE));
    const make = (t) => (t.pair ? new Pair(gl, t.dims, t.channels) : new Lattice(gl, t.dims, t.channels, t.renderable));
    for (const [name, t] of Object.entries(textures)) this[name] = Array.isArray(t) ? t.map(make) : make(t);
    this.textureNames = Object.keys(textures);
    // The wind table u_p is read from where the primitives are not uniform (`setWindTable`).
    this.table = null;
    this.passes = Object.fromEntries(Object.entries({
      CARRIER, ADVECT_BACK, ADVECT_CORRECT, DIFFUSE, EDDY_VISCOSITY, EDDY_DIFFUSE, BUOYANCY, SPLAT, IMPOSE, DIVERGENCE, RELAX, RESIDUAL, GRADIENT, CENTRES, PROBE, REDUCE, CENTRE_B, WIND_ON_FACES,
    }).map(([name, body]) => [name, new Pass(gl, body)]));
    this.setSolids(noSolids(cells));
    this.setUniformWind([0, 0, 0]);
    this.clear();
  }

  /** The uniforms every pass reads. */
  get #grid() {
    return { origin: { vec3: this.origin }, invH: f32(1 / this.h), h: this.h, cells: { ivec3: this.cells } };
  }

  /** u_g = 0, φ = 0 and ν_t = 0. */
  clear() {
    passState(this.gl);
    const gl = this.gl;
    gl.clearColor(0, 0, 0, 0);
    for (const l of [...this.u.flatMap((p) => p.both), ...this.phi.both, this.nuT]) {
      gl.bindFramebuffer(gl.FRAMEBUFFER, l.framebuffer);
      gl.clear(gl.COLOR_BUFFER_BIT);
    }
  }

  /**
   * The solid cells: `solid` (one byte a cell, x fastest), `velocity` (m/s, three floats a
   * cell) and `slip` (one byte a cell: the air slips along it), as `boundary.js` builds them.
   */
  setSolids(solids) {
    const { kinds, rows, definite } = boundaryOf(this.cells, solids, this.boxFaces);
    kinds.forEach((k, a) => this.kind[a].upload(k));
    this.rows.upload(rows);
    this.definite = definite;
    let fluid = 0;
    for (let c = 0; c < rows.length; c += 4) if (rows[c] > 0) fluid += 1;
    this.fluid = fluid;
  }

  /** The primitives' wind u_p on each component's faces (three Float32Arrays, m/s). */
  setWind(faces) {
    faces.forEach((v, a) => this.up[a].upload(v));
  }

  /** A uniform primitives' wind `v` (m/s) on every face. */
  setUniformWind(v) {
    this.setWind([0, 1, 2].map((a) => {
      const d = faceDims(this.cells, a);
      return new Float32Array(d[0] * d[1] * d[2]).fill(v[a]);
    }));
  }

  /**
   * u_p on every face from the wind table `table` (a Float32Array of one time in the core's
   * `WindFrame::write_gpu_table` layout, the step's start): the constant wind and the scene's
   * own primitives (not their mirror images) at each face, as the core's `SceneFlow::step`.
   */
  setWindTable(table) {
    const gl = this.gl;
    const texels = table.length / 4;
    if (this.table?.atlas.dims[0] !== texels) {
      this.table?.dispose();
      this.table = new Lattice(gl, [texels, 1, 1], 4, false);
    }
    this.table.upload(table);
    passState(gl);
    for (let a = 0; a < 3; a++) {
      this.passes.WIND_ON_FACES.draw(this.up[a], { ...this.#grid, windTable: this.table, offset: { vec3: offsetOf(a) }, axis: { int: a } });
    }
  }

  /** Draws `pass` into component `a`'s next u_g with `uniforms` and makes it the current one. */
  #update(a, pass, uniforms) {
    this.passes[pass].draw(this.u[a].next, { ...this.#grid, ...uniforms });
    this.u[a].swap();
  }

  /** u_g on each component's faces (three Float32Arrays, m/s, as `faces()` reads them) from now on. */
  setFaces(faces) {
    faces.forEach((v, a) => this.u[a].now.upload(v));
  }

  /**
   * One step of `dt` (s) with the temperature excess `temperature` on the cells (K, a
   * Float32Array, x fastest; this flow's own `temperature` lattice where the heat was
   * deposited on the GPU, `heat.js`; null: no heat) and `splats` ({centre (m), radius (m),
   * force (m/s²)} each).
   */
  step(dt, temperature = null, splats = []) {
    passState(this.gl);
    const grid = this.#grid;
    dt = f32(dt);
    if (this.eddies) this.#eddyViscosity(dt);
    const [px, py, pz] = this.up;
    const [ux, uy, uz] = this.u.map((p) => p.now);
    this.passes.CARRIER.draw(this.carrier, { ...grid, px, py, pz, ux, uy, uz });
    for (let a = 0; a < 3; a++) {
      const trace = { carrier: this.carrier, dt, offset: { vec3: offsetOf(a) }, axis: { int: a } };
      this.passes.ADVECT_BACK.draw(this.back[a], { ...grid, ...trace, q: this.u[a].now, open: this.openAxes });
      this.#update(a, 'ADVECT_CORRECT', { ...trace, q: this.u[a].now, back: this.back[a] });
    }
    this.#diffuse(dt);
    if (this.eddies) this.#diffuseEddies(dt);
    if (temperature) {
      if (temperature !== this.temperature) this.temperature.upload(temperature);
      const dtBeta = f32(dt * this.buoyancy);
      for (let a = 0; a < 3; a++) {
        if (this.gravity[a] === 0) continue;
        this.#update(a, 'BUOYANCY', { u: this.u[a].now, temperature: this.temperature, axis: { int: a }, dtBeta, g: this.gravity[a] });
      }
    }
    for (const s of splats) {
      for (let a = 0; a < 3; a++) {
        if (s.force[a] === 0) continue;
        this.#update(a, 'SPLAT', {
          u: this.u[a].now, offset: { vec3: offsetOf(a) }, centre: { vec3: s.centre.map(f32) }, radius: f32(s.radius), dtForce: f32(dt * s.force[a]),
        });
      }
    }
    for (let a = 0; a < 3; a++) this.#update(a, 'IMPOSE', { u: this.u[a].now, up: this.up[a], kind: this.kind[a] });
    this.#project();
    if (this.#sizing && --this.#sizing.due === 0) this.#size();
  }

  /**
   * Sizes the SOR's iterations to GPU_TOLERANCE from the residual the last projection left (a
   * read-back): within it, or at the most, the count stays; above it the next step takes half as
   * many iterations again and is measured in turn, unless this count's residual is more than
   * two thirds of the last one's (f32's floor: more iterations would only cost), when the last
   * count comes back.
   */
  #size() {
    const s = this.#sizing;
    const r = this.residual();
    this.sizedResidual = r;
    if (r <= GPU_TOLERANCE || this.iterations >= s.most) {
      this.#sizing = null;
    } else if (r > (2 / 3) * s.last) {
      this.iterations = s.previous;
      this.#sizing = null;
    } else {
      s.previous = this.iterations;
      s.last = r;
      this.iterations = Math.min(s.most, Math.ceil(1.5 * this.iterations));
      s.due = 1;
    }
  }

  /** ν∇²(u_p + u_g) for `dt` (s) in explicit substeps. */
  #diffuse(dt) {
    if (this.viscosity <= 0 || dt <= 0) return;
    const r = f32(f32(this.viscosity * dt) / f32(this.h * this.h));
    const substeps = Math.max(1, Math.ceil(f32(r / STABLE)));
    const rs = f32(r / substeps);
    for (let a = 0; a < 3; a++) {
      for (let k = 0; k < substeps; k++) {
        this.#update(a, 'DIFFUSE', { old: this.u[a].now, up: this.up[a], kind: this.kind[a], axis: { int: a }, r: rs });
      }
    }
  }

  /** ν_t (m²/s per cell) of u_g as the step finds it, capped at h²/(8 dt). */
  #eddyViscosity(dt) {
    const grid = this.#grid;
    const [ux, uy, uz] = this.u.map((p) => p.now);
    this.passes.CENTRES.draw(this.centred, { ...grid, ux, uy, uz });
    const h2 = f32(this.h * this.h);
    const cap = f32(h2 / f32(8 * Math.max(dt, 2 ** -126)));
    const scale = f32(f32(f32(SMAGORINSKY) * this.h) ** 2);
    this.passes.EDDY_VISCOSITY.draw(this.nuT, { ...grid, centred: this.centred, scale, cap });
  }

  /** ν_t's diffusion of u_g for `dt` (s): one explicit pass on each component's free faces. */
  #diffuseEddies(dt) {
    const invH2 = f32(1 / f32(this.h * this.h));
    for (let a = 0; a < 3; a++) {
      this.#update(a, 'EDDY_DIFFUSE', { old: this.u[a].now, kind: this.kind[a], nuT: this.nuT, axis: { int: a }, dt, invH2 });
    }
  }

  /** The projection: b = −h²∇·u_g, SOR sweeps from the last φ, the free faces lose ∇φ. */
  #project() {
    const grid = this.#grid;
    const [ux, uy, uz] = this.u.map((p) => p.now);
    this.passes.DIVERGENCE.draw(this.b, { ...grid, ux, uy, uz, rows: this.rows });
    const b = this.definite || this.fluid === 0 ? this.b : this.#centred();
    const omega = this.omega;
    for (let n = 0; n < this.iterations; n++) {
      for (const parity of [0, 1]) {
        this.passes.RELAX.draw(this.phi.next, { ...grid, phi: this.phi.now, rows: this.rows, b, omega, parity: { int: parity } });
        this.phi.swap();
      }
    }
    for (let a = 0; a < 3; a++) {
      this.#update(a, 'GRADIENT', { u: this.u[a].now, phi: this.phi.now, rows: this.rows, axis: { int: a }, open: this.openAxes });
    }
  }

  /** b less its mean over the fluid cells (with no open face the system is singular). */
  #centred() {
    let src = this.b;
    for (const sum of this.sums) {
      this.passes.REDUCE.draw(sum, { src, size: { ivec4: [src.atlas.width, src.atlas.height, REDUCE_BLOCK, 0] } });
      src = sum;
    }
    this.passes.CENTRE_B.draw(this.bCentred, { ...this.#grid, b: this.b, rows: this.rows, total: src, fluid: this.fluid });
    return this.bCentred;
  }

  /**
   * The last projection's relative residual max|b − Aφ| / max|b| over the fluid cells (with no
   * open face, b less its mean over them, as the core solves it), read back.
   */
  residual() {
    passState(this.gl);
    const b = this.definite || this.fluid === 0 ? this.b : this.bCentred;
    this.passes.RESIDUAL.draw(this.cellOut, { ...this.#grid, phi: this.phi.now, rows: this.rows, b });
    const v = this.cellOut.read();
    let worst = 0;
    let scale = 0;
    for (let c = 0; c < v.length; c += 4) {
      if (v[c + 2] === 0) continue;
      worst = Math.max(worst, Math.abs(v[c]));
      scale = Math.max(scale, Math.abs(v[c + 1]));
    }
    return scale === 0 ? 0 : worst / scale;
  }

  /** The wind u_p + u_g at `x` (m), m/s, read back (one texel). */
  velocityAt(x) {
    passState(this.gl);
    const [ux, uy, uz] = this.u.map((p) => p.now);
    const [px, py, pz] = this.up;
    this.passes.PROBE.draw(this.probe, { ...this.#grid, ux, uy, uz, px, py, pz, point: { vec3: x.map(f32) } });
    return Array.from(this.probe.read().subarray(0, 3));
  }

  /**
   * The force splat of a stir (the pointer's `velocity` (m/s) at `centre` (m) over `radius`
   * (m), clamped to STIR_CELLS cells): the force (velocity − u)/STIR_TIME, u the wind at the
   * centre now (`scene_flow::SceneFlow::step`).
   */
  splatOf({ centre, velocity, radius }) {
    const [lo, hi] = STIR_CELLS;
    const r = Math.min(Math.max(f32(radius), f32(lo * this.h)), f32(hi * this.h));
    const u = this.velocityAt(centre);
    return { centre, radius: r, force: velocity.map((v, a) => f32(f32(f32(v) - u[a]) / STIR_TIME)) };
  }

  /** The last step's eddy viscosity ν_t (m²/s per cell, x fastest; 0 without eddies), read back. */
  eddyViscosity() {
    passState(this.gl);
    return this.nuT.read();
  }

  /** u_g on each component's faces (three Float32Arrays, m/s), read back. */
  faces() {
    passState(this.gl);
    return this.u.map((p) => p.now.read());
  }

  /** T on the cells (K, x fastest: as `exportFlow()`), the last laid there, read back. */
  temperatures() {
    passState(this.gl);
    return this.temperature.read();
  }

  /** u_g at the cells' centres (m/s, xyz interleaved, x fastest: as `exportFlow()`), read back. */
  cellVelocity() {
    passState(this.gl);
    const [ux, uy, uz] = this.u.map((p) => p.now);
    this.passes.CENTRES.draw(this.cellOut, { ...this.#grid, ux, uy, uz });
    const v = this.cellOut.read();
    const out = new Float32Array((3 * v.length) / 4);
    for (let c = 0; c < v.length / 4; c++) out.set(v.subarray(4 * c, 4 * c + 3), 3 * c);
    return out;
  }

  /** Every lattice (and pair of them) it holds. */
  /** Its textures (`textureTable`'s), each a Lattice or a Pair. */
  #lattices() {
    return this.textureNames.flatMap((name) => this[name]);
  }

  /** The bytes of its textures (`gpuFlowBytes` beforehand). */
  get bytes() {
    return this.#lattices().reduce((n, l) => n + l.bytes, 0);
  }

  dispose() {
    for (const l of this.#lattices()) l.dispose();
    this.table?.dispose();
    for (const p of Object.values(this.passes)) p.dispose();
  }
}
