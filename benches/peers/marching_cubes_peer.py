"""scikit-image's marching cubes on the three-blob field against wingedge's,
in one run (the speed goal: wingedge's field + march at 256³ at least 10×
faster than numpy's field + scikit-image's march).

The field (`fixtures/fields/three_blobs.json`, soft-object falloff) is
sampled by numpy on the grid wingedge uses at the same resolution: the
bounds are the union of the sources' influence boxes, the cell is the
longest side / resolution, and the grid is padded by a layer of zeros.
Then `skimage.measure.marching_cubes` (Lewiner's method, one thread)
extracts the level 0.5. wingedge runs `benches/drivers/src/bin/marching_cubes_bench.rs
--goal` (`try_mesh`: the field bounded over blocks of the grid, only the
blocks that may hold the surface sampled and marched; and, for reference,
the whole grid sampled and marched). Each side in a process of its own
(its peak memory is its own), 2 threads, best of three; the table gives
the times, memory, triangles, volumes and the ratio.

    python3 -m pip install scikit-image numpy
    cargo build --release -p wingedge-bench --bin marching_cubes_bench
    python3 benches/peers/marching_cubes_peer.py [RESOLUTION]     (default 256)
"""
import json
import math
import os
import pathlib
import resource
import subprocess
import sys
import time

THREADS = 2
for _var in ("RAYON_NUM_THREADS", "OMP_NUM_THREADS"):
    os.environ[_var] = str(THREADS)

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


def peer(resolution):
    doc = json.loads((ROOT / "fixtures/fields/three_blobs.json").read_text())
    sources = doc["blobs"]
    sample_s, (grid, cell, dims) = best_of_3(lambda: sample(sources, resolution))
    march_s, (verts, faces, _, _) = best_of_3(
        lambda: measure.marching_cubes(grid, level=0.5, spacing=(cell, cell, cell))
    )
    print(json.dumps({
        "version": skimage.__version__,
        "grid": dims,
        "sample_seconds": sample_s,
        "march_seconds": march_s,
        "triangles": len(faces),
        "volume": volume(verts, faces),
        "peak_rss_mib": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
    }))


def run_json(command):
    out = subprocess.run(command, check=True, capture_output=True, text=True, cwd=ROOT)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main():
    if len(sys.argv) > 2 and sys.argv[1] == "--peer":
        peer(int(sys.argv[2]))
        return
    resolution = int(sys.argv[1]) if len(sys.argv) > 1 else 256
    driver = str(ROOT / "target/release/marching_cubes_bench")
    blocks = run_json([driver, "--goal", str(resolution)])
    whole = run_json([driver, "--goal", str(resolution), "--whole"])
    sk = run_json([sys.executable, os.path.abspath(__file__), "--peer", str(resolution)])
    both = sk["sample_seconds"] + sk["march_seconds"]
    grid = "×".join(map(str, blocks["grid"]))
    print(f"three-blob field at resolution {resolution} (grid {grid}), {THREADS} threads\n")
    print("| method | time (s) | peak memory (MiB) | samples | triangles | volume | valid | ratio |")
    print("|---|---:|---:|---:|---:|---:|---|---:|")
    print(f"| numpy field + scikit-image {sk['version']} marching_cubes | "
          f"{sk['sample_seconds']:.3f} + {sk['march_seconds']:.3f} | {sk['peak_rss_mib']:.0f} | "
          f"{blocks['whole_grid_samples']:,} | {sk['triangles']:,} | {sk['volume']:.6f} | not checked | 1 |")
    for w in (whole, blocks):
        print(f"| wingedge, {w['method']} | {w['seconds']:.3f} | {w['peak_rss_mib']:.0f} | "
              f"{w['samples']:,} | {w['triangles']:,} | {w['volume']:.6f} | "
              f"{'valid closed solid' if w['valid'] else 'INVALID'} | {both / w['seconds']:.1f}× |")
    print(f"\nblocks: {blocks['blocks_marched']:,} of {blocks['blocks']:,} sampled and marched")


if __name__ == "__main__":
    main()
