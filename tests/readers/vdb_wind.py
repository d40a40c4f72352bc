"""Reads a windfield wind grid (`windfield generate --out field.vdb`) with OpenVDB's own Python
bindings and holds it to the lattice of the same field (`windfield generate --out field.npy`):
voxel (i, j, k) must be A (L/T) * u(i, j, k, t nt/T), the field linear in time between lattice
times, at world position (i, j, k) * L/n. Prints one JSON object.

usage: vdb_wind.py FIELD.vdb FIELD.npy TIME LX,LY,LZ TIME_PERIOD AMPLITUDE
"""
import json
import sys

import numpy as np
import pyopenvdb as vdb

path, npy = sys.argv[1], sys.argv[2]
t, time_period, amplitude = float(sys.argv[3]), float(sys.argv[5]), float(sys.argv[6])
period = np.array([float(v) for v in sys.argv[4].split(",")])
grid = vdb.read(path, "wind")
u = np.load(npy)  # (nt, nz, ny, nx, 3), lattice units
nt, nz, ny, nx, _ = u.shape
q = t * nt / time_period
t0 = int(np.floor(q)) % nt
f = q - np.floor(q)
slice_ = (1 - f) * u[t0].astype(np.float64) + f * u[(t0 + 1) % nt].astype(np.float64)
want = slice_ * amplitude * period / time_period  # (nz, ny, nx, 3); period per component
got = np.zeros((nx, ny, nz, 3), dtype=np.float32)
grid.copyToArray(got, ijk=(0, 0, 0))
got = np.transpose(got, (2, 1, 0, 3)).astype(np.float64)  # to (nz, ny, nx, 3)
scale = np.abs(want).max()
print(json.dumps({
    "type": grid.valueTypeName,
    "name": grid.name,
    "active": int(grid.activeVoxelCount()),
    "voxels": int(nx * ny * nz),
    "voxel_size": list(grid.transform.voxelSize()),
    "cell": list(period / np.array([nx, ny, nz])),
    "world_of_321": list(grid.transform.indexToWorld((3, 2, 1))),
    "worst": float(np.abs(got - want).max() / scale),
    "worst_each": float((np.abs(got - want) / np.maximum(np.abs(want), 1e-30)).max()),
    "vector_type": grid.metadata.get("vector_type"),
}))
