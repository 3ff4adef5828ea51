"""Cells of a closed ~100k-triangle solid: wingedge's octree against
trimesh's voxelization, in one run, each in a process of its own so that
its peak memory is its own.

    python3 -m pip install trimesh numpy scipy
    cargo build --release -p wingedge-bench --bin cells_bench
    python3 benches/peers/cells_peer.py [MODEL.obj] [--depth 8]

MODEL defaults to spot subdivided twice (93,696 triangles), made by
closed_model.py from the team's shared models folder next to the
repository into /tmp/wingedge-cells/ (not a fixture: 5 MB).

wingedge: `Octree::classify(solid, depth)` (benches/drivers/src/bin/cells_bench.rs,
2 threads available): exact On cells, In/Out by region, the certified
volume interval; reading the OBJ is not timed. trimesh:
`mesh.voxelized(pitch)` (the surface voxels) then `.fill()` (the inside),
loading not timed, at two pitches: the same cell as wingedge's finest
(`root side / 2^depth`) and `longest side / 2^depth` (the anchor of the
issue's goal, finer when the root cube is larger than the model). Each
side's time is the best of its runs (wingedge 3, trimesh 1: it takes
seconds); peak resident memory is the process's high-water mark.
"""
import argparse
import json
import os
import resource
import subprocess
import sys
import time

THREADS = 2
for _var in ("RAYON_NUM_THREADS", "OMP_NUM_THREADS"):
    os.environ[_var] = str(THREADS)

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SHARED = os.path.join(os.path.dirname(ROOT), "shared", "models")
DEFAULT = "/tmp/wingedge-cells/spot_94k.obj"


def trimesh_child(model, pitch):
    import trimesh

    mesh = trimesh.load(model, force="mesh", process=False)
    start = time.perf_counter()
    surface = mesh.voxelized(pitch)
    middle = time.perf_counter()
    filled = surface.fill()
    end = time.perf_counter()
    print(json.dumps({
        "triangles": len(mesh.faces),
        "pitch": pitch,
        "shape": list(filled.shape),
        "voxelized_seconds": middle - start,
        "fill_seconds": end - middle,
        "seconds": end - start,
        "surface_voxels": int(surface.filled_count),
        "filled_voxels": int(filled.filled_count),
        "filled_volume": float(filled.volume),
        "mesh_volume": float(mesh.volume),
        "peak_rss_mib": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
    }))


def run_json(command):
    out = subprocess.run(command, check=True, capture_output=True, text=True, cwd=ROOT)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "--trimesh-child":
        trimesh_child(sys.argv[2], float(sys.argv[3]))
        return
    parser = argparse.ArgumentParser()
    parser.add_argument("model", nargs="?", default=DEFAULT)
    parser.add_argument("--depth", type=int, default=8)
    args = parser.parse_args()
    if args.model == DEFAULT and not os.path.exists(DEFAULT):
        os.makedirs(os.path.dirname(DEFAULT), exist_ok=True)
        subprocess.run([sys.executable, os.path.join(ROOT, "benches/peers/closed_model.py"),
                        os.path.join(SHARED, "spot.obj"), DEFAULT], check=True)
    driver = os.path.join(ROOT, "target/release/cells_bench")
    we = run_json([driver, args.model, str(args.depth)])
    finer = run_json([driver, args.model, str(args.depth + 1)])
    import trimesh

    extent = float(trimesh.load(args.model, force="mesh", process=False).extents.max())
    runs = []
    for label, pitch in (("same cell", we["cell"]), ("longest side / 2^depth", extent / 2 ** args.depth)):
        tm = run_json([sys.executable, os.path.abspath(__file__), "--trimesh-child", args.model, repr(pitch)])
        runs.append((label, tm))
    exact = we["mesh_volume"]
    print(f"model {args.model}: {we['triangles']:,} triangles, volume {exact:.6f}; {THREADS} threads\n")
    print("| method | cell | time (s) | peak memory (MiB) | volume | ratio |")
    print("|---|---:|---:|---:|---|---:|")
    for w in (we, finer):
        print(f"| wingedge cells, depth {w['depth']} | {w['cell']:.5f} | {w['seconds']:.3f} | "
              f"{w['peak_rss_mib']:.0f} | [{w['v_in']:.5f}, {w['v_high']:.5f}] certified | |")
    for label, tm in runs:
        print(f"| trimesh voxelized + fill ({label}) | {tm['pitch']:.5f} | "
              f"{tm['voxelized_seconds']:.3f} + {tm['fill_seconds']:.3f} | {tm['peak_rss_mib']:.0f} | "
              f"{tm['filled_volume']:.5f} (filled voxels) | "
              f"{tm['seconds'] / we['seconds']:.1f}× (depth {we['depth']}), "
              f"{tm['seconds'] / finer['seconds']:.1f}× (depth {finer['depth']}) |")
    print("\nratio: trimesh's time / wingedge's time, same run")


if __name__ == "__main__":
    main()
