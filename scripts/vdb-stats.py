"""Prints what an OpenVDB file holds, grid by grid, as OpenVDB's own Python bindings see it
(Debian's python3-openvdb; `scripts/setup.sh --readers` installs it): the statistics the
gallery quotes for windfield's volumes.

usage: .venv/bin/python scripts/vdb-stats.py FILE.vdb
"""
import sys

import pyopenvdb as vdb

grids, file_meta = vdb.readAll(sys.argv[1])
print(f"file metadata: {dict(file_meta)}")
for g in grids:
    lo, hi = g.evalActiveVoxelBoundingBox()
    world_lo = g.transform.indexToWorld(lo)
    world_hi = g.transform.indexToWorld(hi)
    vmin, vmax = g.evalMinMax()
    print(f"grid {g.name!r}: {g.valueTypeName}, class {g.gridClass!r}, voxel size {g.transform.voxelSize()}")
    print(f"  active voxels {g.activeVoxelCount():,} in {g.leafCount():,} leaves of 8^3; memory {g.memUsage():,} bytes")
    print(f"  active index box {lo} .. {hi}; world box {tuple(round(v, 4) for v in world_lo)} .. {tuple(round(v, 4) for v in world_hi)} m")
    print(f"  values {vmin} .. {vmax}")
    print(f"  metadata: { {k: v for k, v in g.metadata.items() if not k.startswith('file_')} }")
