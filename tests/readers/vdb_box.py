"""Reads the wind over a box (`windfield wind SCENE --box … --out wind.vdb`) with OpenVDB's own
Python bindings and holds it to the same box written as `.npy` (shape (NZ, NY, NX, 3)): voxel
(i, j, k) must be the npy's [k, j, i], at world position the cell centre. Prints one JSON object.

usage: vdb_box.py WIND.vdb WIND.npy
"""
import json
import sys

import numpy as np
import pyopenvdb as vdb

grid = vdb.read(sys.argv[1], "wind")
want = np.load(sys.argv[2]).astype(np.float64)  # (nz, ny, nx, 3)
nz, ny, nx, _ = want.shape
got = np.zeros((nx, ny, nz, 3), dtype=np.float32)
grid.copyToArray(got, ijk=(0, 0, 0))
got = np.transpose(got, (2, 1, 0, 3)).astype(np.float64)
print(json.dumps({
    "type": grid.valueTypeName,
    "name": grid.name,
    "active": int(grid.activeVoxelCount()),
    "voxel_size": list(grid.transform.voxelSize()),
    "world_of_000": list(grid.transform.indexToWorld((0, 0, 0))),
    "world_of_321": list(grid.transform.indexToWorld((3, 2, 1))),
    "worst": float(np.abs(got - want).max()),
    "largest": float(np.abs(want).max()),
    "time": grid.metadata.get("windfield_time"),
}))
