"""wingedge repair on real broken meshes: time, peak memory, whether the
output is a valid solid (by wingedge's validator and by manifold3d's
status) and the volume change. Prints a Markdown table.

    cargo build --release --bin wingedge
    python3 benches/peers/repair_peers.py MODEL.obj...

Peers (MeshLib's fixSelfIntersections and fillHoles, PyMeshFix, CGAL's
autorefine) are not run yet: their columns are to be added here.
"""

import json
import os
import resource
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
WINGEDGE = os.path.join(ROOT, "target", "release", "wingedge")


def manifold_status(path):
    """manifold3d's status of an OBJ of triangles, or why it cannot say."""
    try:
        import manifold3d
        import numpy as np
    except ImportError:
        return "manifold3d not installed"
    verts, tris = [], []
    with open(path) as f:
        for line in f:
            parts = line.split()
            if parts and parts[0] == "v":
                verts.append([float(x) for x in parts[1:4]])
            elif parts and parts[0] == "f":
                idx = [int(p.split("/")[0]) - 1 for p in parts[1:]]
                for k in range(1, len(idx) - 1):
                    tris.append([idx[0], idx[k], idx[k + 1]])
    if not tris:
        return "empty"
    mesh = manifold3d.Mesh(
        vert_properties=np.array(verts, dtype=np.float32),
        tri_verts=np.array(tris, dtype=np.uint32),
    )
    return str(manifold3d.Manifold(mesh).status()).split(".")[-1]


def run(model):
    out = os.path.join(tempfile.mkdtemp(), "repaired.obj")
    start = time.perf_counter()
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    p = subprocess.run(
        [WINGEDGE, "repair", model, "-o", out, "--json"],
        capture_output=True,
        text=True,
    )
    seconds = time.perf_counter() - start
    peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    name = os.path.basename(model)
    if p.returncode != 0:
        first = (p.stderr.strip().splitlines() or ["?"])[0][:100]
        return f"| {name} | {seconds:.2f} | {peak // 1024} | refused: {first} | | | |"
    d = json.loads(p.stdout)
    status = manifold_status(out)
    del before
    return (
        f"| {name} | {seconds:.2f} | {peak // 1024} | {d['validity']} | {status} "
        f"| {d['volume_before']:.6g} | {d['volume_after']:.6g} |"
    )


def main():
    print("| model | seconds | peak MiB (largest child so far) | wingedge validator | manifold3d status | volume before | volume after |")
    print("|---|---|---|---|---|---|---|")
    for model in sys.argv[1:]:
        print(run(model), flush=True)


if __name__ == "__main__":
    main()
