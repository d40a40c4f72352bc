"""Reads a windfield OpenEXR still with the OpenEXR project's own Python bindings (`OpenEXR` on
PyPI) and prints its channels' types, its header attributes and its pixels (R, G, B, A as lists
of floats, row 0 at the top) as one JSON object.

usage: exr_pixels.py STILL.exr
"""
import json
import sys

import numpy as np
import OpenEXR

def plain(v):
    if isinstance(v, np.ndarray):
        return v.astype(float).tolist()
    if isinstance(v, (tuple, list)):
        return [plain(x) for x in v]
    if isinstance(v, (int, float, str, bool)):
        return v
    return str(v)


with OpenEXR.File(sys.argv[1]) as f:
    header = {k: plain(v) for k, v in f.header().items()}
    channels = f.channels()
    names = sorted(channels)
    if names == ["RGBA"]:
        rgba = channels["RGBA"].pixels
        pixel_type = str(rgba.dtype)
    else:
        rgba = np.stack([channels[c].pixels for c in "RGBA"], axis=-1)
        pixel_type = str(channels["R"].pixels.dtype)


print(json.dumps({
    "pixel_type": pixel_type,
    "width": int(rgba.shape[1]),
    "height": int(rgba.shape[0]),
    "rgba": rgba.astype(np.float64).reshape(-1).tolist(),
    "header": header,
}))
