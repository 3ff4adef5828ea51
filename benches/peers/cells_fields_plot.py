"""The accuracy-against-time plot of cells and marching cubes
(docs/cells_fields_accuracy.png) and its table.

    python3 -m pip install matplotlib manifold3d numpy
    cargo build --release -p wingedge-bench --bin cells_fields_accuracy
    python3 benches/peers/cells_fields_plot.py [MODEL.obj]

MODEL (default: the team's shared spot.obj next to the repository, else
the genus-1 torus fixture) is a closed mesh whose reference volume comes
from manifold3d; the driver (benches/drivers/src/bin/cells_fields_accuracy.rs) prints
the tables and writes the CSV this script plots: the certified interval's
relative width against time per depth for each cells target, and the
marching-cubes volume error against time per resolution.
"""
import csv
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SPOT = os.path.join(os.path.dirname(ROOT), "shared", "models", "spot.obj")
TORUS = os.path.join(ROOT, "fixtures", "valid", "torus_genus1.obj")
OUT_CSV = "/tmp/wingedge_cells_fields_accuracy.csv"
OUT_PNG = os.path.join(ROOT, "docs", "cells_fields_accuracy.png")


def manifold_volume(path):
    import manifold3d
    import numpy as np

    positions, triangles = [], []
    with open(path) as f:
        for line in f:
            parts = line.split()
            if parts and parts[0] == "v":
                positions.append([float(x) for x in parts[1:4]])
            elif parts and parts[0] == "f":
                corners = [int(p.split("/")[0]) - 1 for p in parts[1:]]
                for i in range(1, len(corners) - 1):  # fan: the fixtures' quads are convex
                    triangles.append([corners[0], corners[i], corners[i + 1]])
    mesh = manifold3d.Mesh(
        vert_properties=np.array(positions, dtype=np.float32),
        tri_verts=np.array(triangles, dtype=np.uint32),
    )
    manifold = manifold3d.Manifold(mesh)
    if manifold.status() != manifold3d.Error.NoError:
        sys.exit(f"{path}: manifold3d refuses it: {manifold.status()}")
    return manifold.volume()


def main():
    model = sys.argv[1] if len(sys.argv) > 1 else (SPOT if os.path.exists(SPOT) else TORUS)
    volume = manifold_volume(model)
    print(f"{model}: manifold3d volume {volume!r}")
    driver = os.path.join(ROOT, "target", "release", "cells_fields_accuracy")
    subprocess.run([driver, "--mesh", model, "--mesh-volume", repr(volume), "--csv", OUT_CSV],
                   check=True, cwd=ROOT)
    rows = list(csv.DictReader(open(OUT_CSV)))

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (cells, march) = plt.subplots(1, 2, figsize=(11, 4.4))
    for target in dict.fromkeys(r["target"] for r in rows if r["kind"] == "cells"):
        mine = [r for r in rows if r["kind"] == "cells" and r["target"] == target]
        t = [float(r["seconds"]) for r in mine]
        w = [float(r["relative"]) for r in mine]
        cells.loglog(t, w, "o-", label=os.path.splitext(os.path.basename(target))[0])
        for r, x, y in zip(mine, t, w):
            cells.annotate(r["n"], (x, y), textcoords="offset points", xytext=(4, 3), fontsize=7)
    cells.set_xlabel("time (s)")
    cells.set_ylabel("interval width V_on / exact volume")
    cells.set_title("octree cells: certified interval (labels: depth)")
    cells.grid(True, which="both", alpha=0.3)
    cells.legend(fontsize=8)
    mine = [r for r in rows if r["kind"] == "marching"]
    t = [float(r["seconds"]) for r in mine]
    e = [float(r["relative"]) for r in mine]
    march.loglog(t, e, "s-", color="tab:red", label="sphere field")
    for r, x, y in zip(mine, t, e):
        march.annotate(r["n"], (x, y), textcoords="offset points", xytext=(4, 3), fontsize=7)
    march.set_xlabel("time (s)")
    march.set_ylabel("|volume − 4π/3| / (4π/3)")
    march.set_title("marching cubes: volume error (labels: resolution)")
    march.grid(True, which="both", alpha=0.3)
    march.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(OUT_PNG, dpi=110)
    print(f"wrote {OUT_PNG}")


if __name__ == "__main__":
    main()
