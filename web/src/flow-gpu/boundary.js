// The flow's boundary conditions as the GPU passes read them, worked out once per set of solids
// (on the CPU, as the core's `wind::flow::boundary` and the projection's system do):
//
// - each face's kind: free, or fixed with the total normal velocity (u_p + u_g)·n = v·n it must
//   carry (a solid cell's face: the solid's v, the mean of two solids' between them; a closed
//   wall: 0), and whether it holds the air (no-slip) or lets it slip along a solid;
// - each cell's Poisson row: the number of its free faces (0 for a solid cell) and which of
//   them join it to a fluid neighbour, and whether any fluid cell has an open face of the box.

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

/**
 * The total normal velocity (m/s) face `idx` of component `axis` must carry, or null where it
 * is free (the core's `boundary::fixed_normal`); `closed`: whether each axis's box faces are.
 */
function fixedNormal(cells, solids, closed, axis, idx) {
  const n = cells[axis];
  const cell = (m) => {
    const c = [...idx];
    c[axis] = m;
    return cellIndex(cells, c[0], c[1], c[2]);
  };
  const solidV = (c) => (solids.solid[c] ? solids.velocity[3 * c + axis] : null);
  const s = idx[axis];
  if (s === 0 || s === n) {
    const v = solidV(cell(s === 0 ? 0 : n - 1));
    if (v !== null) return v;
    return closed[axis] ? 0 : null;
  }
  const a = solidV(cell(s - 1));
  const b = solidV(cell(s));
  if (a !== null && b !== null) return Math.fround(0.5 * Math.fround(a + b));
  return a ?? b;
}

/** Whether face `idx` of component `axis` touches a no-slip solid cell (`boundary::holds`). */
function holds(cells, solids, axis, idx) {
  const s = idx[axis];
  const n = cells[axis];
  const holding = (m) => {
    const c = [...idx];
    c[axis] = m;
    const q = cellIndex(cells, c[0], c[1], c[2]);
    return solids.solid[q] === 1 && solids.slip[q] === 0;
  };
  return (s > 0 && holding(s - 1)) || (s < n && holding(s));
}

/**
 * Each component's faces as [kind, v] pairs (Float32Arrays laid out x fastest), and each
 * cell's Poisson row as [free faces, links, 0, 0] (links: bit a for the next cell along axis
 * a, bit 3 + a for the previous one), with `definite` (some fluid cell has an open face).
 */
export function boundaryOf(cells, solids, faces) {
  const closed = closedAxes(faces);
  const kinds = [0, 1, 2].map((axis) => {
    const d = faceDims(cells, axis);
    const out = new Float32Array(2 * d[0] * d[1] * d[2]);
    for (let k = 0; k < d[2]; k++) {
      for (let j = 0; j < d[1]; j++) {
        for (let i = 0; i < d[0]; i++) {
          const v = fixedNormal(cells, solids, closed, axis, [i, j, k]);
          if (v === null) continue;
          const f = 2 * (i + d[0] * (j + d[1] * k));
          out[f] = holds(cells, solids, axis, [i, j, k]) ? HOLDING : SLIPPING;
          out[f + 1] = v;
        }
      }
    }
    return out;
  });
  const count = cells[0] * cells[1] * cells[2];
  const diag = new Uint8Array(count);
  const links = new Uint8Array(count);
  const stride = [1, cells[0], cells[0] * cells[1]];
  let definite = false;
  for (let k = 0; k < cells[2]; k++) {
    for (let j = 0; j < cells[1]; j++) {
      for (let i = 0; i < cells[0]; i++) {
        const c = cellIndex(cells, i, j, k);
        if (solids.solid[c]) continue;
        const idx = [i, j, k];
        for (let a = 0; a < 3; a++) {
          for (let side = 0; side < 2; side++) {
            const f = [...idx];
            f[a] += side;
            if (fixedNormal(cells, solids, closed, a, f) !== null) continue;
            diag[c] += 1;
            if (f[a] === 0 || f[a] === cells[a]) definite = true;
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
