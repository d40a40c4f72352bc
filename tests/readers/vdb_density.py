"""Reads a windfield volume with OpenVDB's own Python bindings (Debian's python3-openvdb) and
holds it to the density of its blob list, evaluated here from the rendering model's formula:
rho(x) = sum_j m_j / ((2 pi)^(3/2) s_j^3) exp(-|x - c_j|^2 / (2 s_j^2)), in double precision, at
the voxel centres (i, j, k) * H. Prints one JSON object for the calling test.

usage: vdb_density.py VOLUME.vdb BLOBS.json H
"""
import json
import sys

import numpy as np
import pyopenvdb as vdb

path, blobs_path, h = sys.argv[1], sys.argv[2], float(sys.argv[3])
grids, file_meta = vdb.readAll(path)
by_name = {g.name: g for g in grids}
density = by_name["density"]
(lo, hi) = density.evalActiveVoxelBoundingBox()
lo, hi = np.array(lo), np.array(hi)
# The grid's voxels over its active box, and a margin of inactive ones around it.
lo, hi = lo - 2, hi + 2
shape = tuple(int(v) for v in hi - lo + 1)
got = np.zeros(shape, dtype=np.float32)
density.copyToArray(got, ijk=tuple(int(v) for v in lo))

blobs = [b for b in json.load(open(blobs_path))["blobs"] if b["mass"] > 0]
want = np.zeros(shape, dtype=np.float64)
axes = [(lo[a] + np.arange(shape[a])) * h for a in range(3)]
for b in blobs:
    c, s, m = np.array(b["center"], dtype=np.float64), float(b["sigma"]), float(b["mass"])
    g = [np.exp(-((axes[a] - c[a]) ** 2) / (2 * s * s)) for a in range(3)]
    peak = m / ((2 * np.pi) ** 1.5 * s ** 3)
    want += peak * g[0][:, None, None] * g[1][None, :, None] * g[2][None, None, :]

peak = float(want.max())
active = got != 0
inactive_want = float(want[~active].max()) if (~active).any() else 0.0
world = density.transform.indexToWorld((1, 2, 3))
print(json.dumps({
    "class": density.gridClass,
    "type": density.valueTypeName,
    "grids": sorted(by_name),
    "voxel_size": list(density.transform.voxelSize()),
    "index_to_world_123": list(world),
    "active": int(density.activeVoxelCount()),
    "peak": peak,
    "worst": float(np.abs(got.astype(np.float64) - want)[active].max() / peak),
    "inactive_below": inactive_want / peak,
    "smallest_active": float(got[active].min() / peak),
    "mass_grid": float(got.astype(np.float64).sum() * h ** 3),
    "mass_blobs": float(sum(b["mass"] for b in blobs)),
    "metadata": {k: (v if isinstance(v, (str, int, float, bool)) else list(v)) for k, v in density.metadata.items()},
    "creator": file_meta.get("creator"),
}))
