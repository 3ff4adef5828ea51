"""scikit-image's marching cubes on the three-blob field, for comparison with
`examples/marching_cubes_bench.rs`.

The field (`fixtures/fields/three_blobs.json`, soft-object falloff) is
sampled by numpy on the grid wingedge uses at the same resolution: the
bounds are the union of the sources' influence boxes, the cell is the
longest side / resolution, and the grid is padded by a layer of zeros.
Then `skimage.measure.marching_cubes` (Lewiner's method, one thread)
extracts the level 0.5. Prints the sampling and marching times (best of
three), the triangle count and the mesh's volume.

    python3 -m pip install scikit-image
    python3 benches/peers/marching_cubes_peer.py [RESOLUTION]     (default 256)
"""
import json
import math
import pathlib
import sys
import time

import numpy as np
import skimage
from skimage import measure

ROOT = pathlib.Path(__file__).resolve().parents[2]


def best_of_3(f):
    best, out = float("inf"), None
    for _ in range(3):
        start = time.perf_counter()
        out = f()
        best = min(best, time.perf_counter() - start)
    return best, out


def sample(sources, resolution):
    lo = np.min([np.subtract(s["center"], s["radius"]) for s in sources], axis=0)
    hi = np.max([np.add(s["center"], s["radius"]) for s in sources], axis=0)
    size = hi - lo
    cell = size.max() / resolution
    dims = [math.ceil(x / cell) + 1 for x in size]
    axes = [lo[a] + cell * np.arange(dims[a]) for a in range(3)]
    x, y, z = np.meshgrid(*axes, indexing="ij")
    field = np.zeros(dims)
    for s in sources:
        c, r, w = s["center"], s["radius"], s.get("strength", 1.0)
        s2 = ((x - c[0]) ** 2 + (y - c[1]) ** 2 + (z - c[2]) ** 2) / (r * r)
        g = 1 - 4 / 9 * s2**3 + 17 / 9 * s2**2 - 22 / 9 * s2
        field += w * np.where(s2 < 1, g, 0.0)
    return np.pad(field, 1), cell, dims


def volume(verts, faces):
    a, b, c = verts[faces[:, 0]], verts[faces[:, 1]], verts[faces[:, 2]]
    return abs(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6)


def main():
    resolution = int(sys.argv[1]) if len(sys.argv) > 1 else 256
    doc = json.loads((ROOT / "fixtures/fields/three_blobs.json").read_text())
    sources = doc["blobs"]
    sample_s, (grid, cell, dims) = best_of_3(lambda: sample(sources, resolution))
    march_s, (verts, faces, _, _) = best_of_3(
        lambda: measure.marching_cubes(grid, level=0.5, spacing=(cell, cell, cell))
    )
    print(
        f"scikit-image {skimage.__version__} at resolution {resolution}: grid "
        f"{'×'.join(map(str, dims))} (+ padding), sample {sample_s:.3f} s (numpy), "
        f"march {march_s:.3f} s, {len(faces)} triangles, volume {volume(verts, faces):.6f}"
    )


if __name__ == "__main__":
    main()
