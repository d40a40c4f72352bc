"""Reads the flow's grid (`windfield flow SCENE --seconds T --out flow.vdb`) with OpenVDB's own
Python bindings and holds it to the same grid written as `.npy` (shape (nz, ny, nx, 4): u, v, w,
then T): voxel (i, j, k) of `velocity` and of `temperature` must be the npy's [k, j, i], at world
position the cell's centre. Prints one JSON object.

usage: vdb_flow.py FLOW.vdb FLOW.npy
"""
import json
import sys

import numpy as np
import pyopenvdb as vdb

want = np.load(sys.argv[2]).astype(np.float64)  # (nz, ny, nx, 4)
nz, ny, nx, _ = want.shape
velocity = vdb.read(sys.argv[1], "velocity")
temperature = vdb.read(sys.argv[1], "temperature")
u = np.zeros((nx, ny, nz, 3), dtype=np.float32)
velocity.copyToArray(u, ijk=(0, 0, 0))
t = np.zeros((nx, ny, nz), dtype=np.float32)
temperature.copyToArray(t, ijk=(0, 0, 0))
u = np.transpose(u, (2, 1, 0, 3)).astype(np.float64)
t = np.transpose(t, (2, 1, 0)).astype(np.float64)
print(json.dumps({
    "types": [velocity.valueTypeName, temperature.valueTypeName],
    "active": [int(velocity.activeVoxelCount()), int(temperature.activeVoxelCount())],
    "voxel_size": list(velocity.transform.voxelSize()),
    "world_of_000": list(temperature.transform.indexToWorld((0, 0, 0))),
    "worst": float(max(np.abs(u - want[..., :3]).max(), np.abs(t - want[..., 3]).max())),
    "hottest": float(want[..., 3].max()),
    "time": velocity.metadata.get("windfield_time"),
}))
