// The flow's boundary conditions as the GPU passes read them, worked out once per set of solids
// (on the CPU, as the core's `wind::flow::boundary` and the projection's system do):
//
// - each face's kind: free, or fixed with the total normal velocity (u_p + u_g)·n = v·n it must
//   carry (a solid cell's face: the solid's v, the mean of two solids' between them; a closed
//   wall: 0), and whether it holds the air (no-slip) or lets it slip along a solid;
// - each cell's Poisson row: the number of its free faces (0 for a solid cell) and which of
//   them join it to a fluid neighbour, and whether any fluid cell has an open face of the box;
// - the solid cells a step's moving repulsors add over the objects' (`repulsorSolids`).

import { REPULSOR_KIND, WIND_TABLE_HEADER, WIND_TABLE_PRIMITIVE } from '../generated/contract.js';

const f32 = Math.fround;

/** A face's kind: free (the projection sets it). */
export const FREE = 0;
/** A fixed face touching a no-slip solid cell. */
export const HOLDING = 1;
/** A fixed face touching no no-slip solid cell (a slipping solid's, or a closed wall). */
export const SLIPPING = 2;

/**
 * Whether the box's faces across x, y and z are closed, from a scene's `flow.faces`: 'open',
 * 'closed' or {x, y, z} of those (each axis's two faces; an axis left out is open).
 */
export function closedAxes(faces = 'open') {
  if (typeof faces === 'string') return [0, 1, 2].map(() => faces === 'closed');
  return ['x', 'y', 'z'].map((a) => faces[a] === 'closed');
}

/** The grid's cells: `cells` [nx, ny, nz], x fastest. */
function cellIndex(cells, i, j, k) {
  return i + cells[0] * (j + cells[1] * k);
}

/** The face counts of component `axis`. */
export function faceDims(cells, axis) {
  const d = [...cells];
  d[axis] += 1;
  return d;
}

/** No solid cell on `cells`. */
export function noSolids(cells) {
  const n = cells[0] * cells[1] * cells[2];
  return { solid: new Uint8Array(n), velocity: new Float32Array(3 * n), slip: new Uint8Array(n) };
}

/**
 * Marks solid, moving at `v` (m/s), each cell whose centre (m) `inside` holds, on the grid of
 * `origin` (m), `cells` and edge `h` (m); `slip` lets the air slip along it.
 */
export function addSolid(solids, { origin, cells, h }, inside, v = [0, 0, 0], slip = false) {
  const f = Math.fround;
  for (let k = 0; k < cells[2]; k++) {
    for (let j = 0; j < cells[1]; j++) {
      for (let i = 0; i < cells[0]; i++) {
        const x = [i, j, k].map((s, a) => f(origin[a] + f(h * f(s + 0.5))));
        if (!inside(x)) continue;
        const c = cellIndex(cells, i, j, k);
        solids.solid[c] = 1;
        solids.velocity.set(v, 3 * c);
        solids.slip[c] = slip ? 1 : 0;
      }
    }
  }
  return solids;
}

/** Index `axis` of (i, j, k), with no array made. */
function along(axis, i, j, k) {
  return axis === 0 ? i : axis === 1 ? j : k;
}

/** Cell index strides of `cells` along x, y and z. */
function stridesOf(cells) {
  return [1, cells[0], cells[0] * cells[1]];
}

/**
 * The total normal velocity (m/s) that a face of component `axis` must carry, or null where it
 * is free (the core's `boundary::fixed_normal`): the face `s` along the axis from the cell
 * `base` (the cell at 0 along the axis, the face's other indices as they are); `closed`:
 * whether each axis's box faces are, `stride` the cells' strides (`stridesOf`).
 */
function fixedNormal(cells, solids, closed, stride, axis, s, base) {
  const n = cells[axis];
  const { solid, velocity } = solids;
  if (s === 0 || s === n) {
    const c = base + (s === 0 ? 0 : n - 1) * stride[axis];
    if (solid[c]) return velocity[3 * c + axis];
    return closed[axis] ? 0 : null;
  }
  const a = base + (s - 1) * stride[axis];
  const b = a + stride[axis];
  if (solid[a] && solid[b]) return Math.fround(0.5 * Math.fround(velocity[3 * a + axis] + velocity[3 * b + axis]));
  if (solid[a]) return velocity[3 * a + axis];
  return solid[b] ? velocity[3 * b + axis] : null;
}

/** Whether that face touches a no-slip solid cell (`boundary::holds`), `s` and `base` as there. */
function holds(cells, solids, stride, axis, s, base) {
  const holding = (m) => {
    const q = base + m * stride[axis];
    return solids.solid[q] === 1 && solids.slip[q] === 0;
  };
  return (s > 0 && holding(s - 1)) || (s < cells[axis] && holding(s));
}

/**
 * Each component's faces as [kind, v] pairs (Float32Arrays laid out x fastest), and each
 * cell's Poisson row as [free faces, links, 0, 0] (links: bit a for the next cell along axis
 * a, bit 3 + a for the previous one), with `definite` (some fluid cell has an open face).
 */
export function boundaryOf(cells, solids, faces) {
  const closed = closedAxes(faces);
  const stride = stridesOf(cells);
  const kinds = [0, 1, 2].map((axis) => {
    const d = faceDims(cells, axis);
    const out = new Float32Array(2 * d[0] * d[1] * d[2]);
    let f = 0;
    for (let k = 0; k < d[2]; k++) {
      for (let j = 0; j < d[1]; j++) {
        for (let i = 0; i < d[0]; i++, f += 2) {
          const s = along(axis, i, j, k);
          const base = cellIndex(cells, i, j, k) - s * stride[axis];
          const v = fixedNormal(cells, solids, closed, stride, axis, s, base);
          if (v === null) continue;
          out[f] = holds(cells, solids, stride, axis, s, base) ? HOLDING : SLIPPING;
          out[f + 1] = v;
        }
      }
    }
    return out;
  });
  const count = cells[0] * cells[1] * cells[2];
  const diag = new Uint8Array(count);
  const links = new Uint8Array(count);
  const dims = [0, 1, 2].map((a) => faceDims(cells, a));
  const faceStrides = dims.map(stridesOf);
  let definite = false;
  for (let k = 0; k < cells[2]; k++) {
    for (let j = 0; j < cells[1]; j++) {
      for (let i = 0; i < cells[0]; i++) {
        const c = cellIndex(cells, i, j, k);
        if (solids.solid[c]) continue;
        for (let a = 0; a < 3; a++) {
          // The cell's lower face across axis a, and its upper one a face further on.
          const lower = cellIndex(dims[a], i, j, k);
          const s = along(a, i, j, k);
          for (let side = 0; side < 2; side++) {
            if (kinds[a][2 * (lower + side * faceStrides[a][a])] !== FREE) continue;
            diag[c] += 1;
            if (s + side === 0 || s + side === cells[a]) definite = true;
            else if (side === 1) {
              links[c] |= 1 << a;
              links[c + stride[a]] |= 8 << a;
            }
          }
        }
      }
    }
  }
  const rows = new Float32Array(4 * count);
  for (let c = 0; c < count; c++) {
    rows[4 * c] = diag[c];
    rows[4 * c + 1] = links[c];
  }
  return { kinds, rows, definite };
}

/**
 * The solid cells of a step whose wind table `table` (one time, the core's
 * `WindFrame::write_gpu_table` layout) has repulsors: the scene's own, `fixed`, with each
 * repulsor's sphere (not its mirror images) marked solid over them, moving at the sphere's
 * velocity (the core's `SceneFlow::step`: `Solids::add_sphere`, a cell whose centre lies within
 * the radius) on `grid` ({origin, cells, h}); null where the table has none.
 */
export function repulsorSolids(fixed, grid, table) {
  // The header's fifth texel: [constant wind xyz, primitive count].
  const count = table[4 * 4 + 3];
  let solids = null;
  for (let j = 0; j < count; j++) {
    const at = WIND_TABLE_HEADER + WIND_TABLE_PRIMITIVE * j;
    // [kind, 1/decay, radius, strength], [origin, plane], [centre, first image], [velocity, images].
    if (table[at] !== REPULSOR_KIND || table[at + 7] >= 0) continue;
    solids ??= { solid: fixed.solid.slice(), velocity: fixed.velocity.slice(), slip: fixed.slip.slice() };
    const radius = table[at + 2];
    const centre = table.subarray(at + 8, at + 11);
    const r2 = f32(radius * radius);
    const inside = (x) => {
      let d = 0;
      for (let a = 0; a < 3; a++) {
        const e = f32(x[a] - centre[a]);
        d = f32(d + f32(e * e));
      }
      return d <= r2;
    };
    addSolid(solids, grid, inside, Array.from(table.subarray(at + 12, at + 15)));
  }
  return solids;
}

/** Whether two sets of solid cells (`noSolids`' layout) are the same cells, velocities and slips. */
export function sameSolids(a, b) {
  const same = (x, y) => x.length === y.length && x.every((v, i) => v === y[i]);
  return same(a.solid, b.solid) && same(a.slip, b.slip) && same(a.velocity, b.velocity);
}
