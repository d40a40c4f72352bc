"""Reads two OpenVDB files' `wind` grids with OpenVDB's own Python bindings and compares them:
the same active voxels, transform and metadata, and the largest difference of their values
relative to the largest value. Prints one JSON object.

usage: vdb_compare.py A.vdb B.vdb
"""
import json
import sys

import numpy as np
import pyopenvdb as vdb

a, b = (vdb.read(p, "wind") for p in sys.argv[1:3])
box = a.evalActiveVoxelBoundingBox()
shape = tuple(int(hi - lo + 1) for lo, hi in zip(*box)) + (3,)
va, vb = np.zeros(shape, np.float32), np.zeros(shape, np.float32)
a.copyToArray(va, ijk=box[0])
b.copyToArray(vb, ijk=box[0])
keys = ("windfield_time", "windfield_units", "windfield_source", "vector_type")
print(json.dumps({
    "active": [int(a.activeVoxelCount()), int(b.activeVoxelCount())],
    "same_box": box == b.evalActiveVoxelBoundingBox(),
    "same_transform": a.transform.indexToWorld((3, 2, 1)) == b.transform.indexToWorld((3, 2, 1))
    and a.transform.voxelSize() == b.transform.voxelSize(),
    "same_metadata": all(a.metadata.get(k) == b.metadata.get(k) for k in keys),
    "worst": float(np.abs(va - vb).max() / max(np.abs(vb).max(), 1e-30)),
}))
