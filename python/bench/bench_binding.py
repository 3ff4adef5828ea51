#!/usr/bin/env python3
"""wingedge from Python against its peers in the same process, and the
binding's overhead over the Rust call.

    python3 python/bench/bench_binding.py [MODEL.obj] [--queries 1e6] [--out DIR]

Needs the installed package (``pip install ./python``) and the peers of
``benches/peers/python_peers.py`` (trimesh with embreex, open3d, libigl).
Points are uniform in the model's box, rays start on a sphere around it and
aim at random points of the box (seeded). Every library gets 2 threads
(trimesh's Embree queries run on one). The Rust-only rate comes from
``benches/drivers/src/bin/peers_wingedge.rs`` (built with ``cargo build --release
-p wingedge-bench --bin peers_wingedge``) on the same files, so the overhead row compares the same
work with and without Python around it. Prints a Markdown table.
"""

import argparse
import json
import os
import pathlib
import subprocess
import sys
import tempfile

THREADS = 2
ROUNDS = 3
for _var in ("RAYON_NUM_THREADS", "OMP_NUM_THREADS"):
    os.environ[_var] = str(THREADS)

import numpy as np  # noqa: E402  (after the thread settings)

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "benches" / "peers"))

import python_peers  # noqa: E402
import wingedge  # noqa: E402


def queries(solid, n, seed=1):
    rng = np.random.default_rng(seed)
    lo, hi = solid.bounds
    points = rng.uniform(lo, hi, size=(n, 3))
    centre, radius = (lo + hi) / 2, np.linalg.norm(hi - lo)
    d = rng.normal(size=(n, 3))
    origins = centre + radius * d / np.linalg.norm(d, axis=1, keepdims=True)
    targets = rng.uniform(lo, hi, size=(n, 3))
    directions = targets - origins
    directions /= np.linalg.norm(directions, axis=1, keepdims=True)
    return points, np.hstack([origins, directions])


def rust_only(model, points, rays, out):
    """The Rust call's own best-of-3 times, from the peers driver."""
    name = "model"
    (out / f"{name}.obj").write_bytes(pathlib.Path(model).read_bytes())
    points.astype("<f8").tofile(out / f"{name}.points.f64")
    rays.astype("<f8").tofile(out / f"{name}.rays.f64")
    exe = ROOT / "target" / "release" / "peers_wingedge"
    if not exe.exists():
        subprocess.run(["cargo", "build", "--release", "-p", "wingedge-bench", "--bin", "peers_wingedge"], cwd=ROOT, check=True)
    line = subprocess.run(
        [str(exe), "queries", str(out), name], check=True, capture_output=True, text=True
    ).stdout.strip().splitlines()[-1]
    return json.loads(line)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    default_model = ROOT.parent / "shared" / "models" / "spot.obj"
    parser.add_argument("model", nargs="?", default=str(default_model))
    parser.add_argument("--queries", type=float, default=1e6)
    args = parser.parse_args()
    n = int(args.queries)

    solid = wingedge.load_obj(args.model)
    vertices, faces = solid.to_arrays()
    if not isinstance(faces, np.ndarray) or faces.shape[1] != 3:
        raise SystemExit("the benchmark model must be a triangle mesh")
    points, rays = queries(solid, n)
    origins, directions = rays[:, :3].copy(), rays[:, 3:].copy()

    # The binding and the Rust API alone, alternated in rounds so that both
    # see the same machine load; the best of each is kept.
    best = {"points": None, "rays": None, "points_s": np.inf, "rays_s": np.inf}
    rust = {"points_s": np.inf, "rays_s": np.inf}
    with tempfile.TemporaryDirectory() as tmp:
        for _ in range(ROUNDS):
            for task, call in (
                ("points", lambda: solid.contains(points)),
                ("rays", lambda: solid.ray_cast(origins, directions)[0]),
            ):
                seconds, answers = python_peers.best_of_3(call)
                if seconds < best[f"{task}_s"]:
                    best[f"{task}_s"], best[task] = seconds, answers
            line = rust_only(args.model, points, rays, pathlib.Path(tmp))
            for key in rust:
                rust[key] = min(rust[key], line[key])
    results = [
        ("wingedge (Python)", "points", best["points_s"], best["points"]),
        ("wingedge (Python)", "rays", best["rays_s"], best["rays"]),
    ]
    for peer in (
        python_peers.trimesh_embree(vertices, faces, points, rays)
        + python_peers.open3d_scene(vertices, faces, points, rays)
        + python_peers.libigl_fwn(vertices, faces, points)
    ):
        results.append((peer["library"], peer["task"], peer["seconds"], peer["answers"]))

    print(f"model {args.model}: {solid.face_count} triangles, {n:,} points and rays, {THREADS} threads\n")
    print("| library | task | million queries/s | wingedge (Python) is × faster | agrees with wingedge |")
    print("|---|---|---:|---:|---:|")
    ours = {task: (s, a) for lib, task, s, a in results if lib == "wingedge (Python)"}
    for lib, task, s, answers in results:
        ref_s, ref = ours[task]
        if task == "points":
            agree = np.mean(np.asarray(answers, bool) == np.asarray(ref, bool))
        else:
            both = np.isfinite(answers) == np.isfinite(ref)
            close = np.isclose(np.where(np.isfinite(answers), answers, 0), np.where(np.isfinite(ref), ref, 0), rtol=1e-4)
            agree = np.mean(both & close)
        print(f"| {lib} | {task} | {n / s / 1e6:.2f} | {s / ref_s:.2f} | {agree:.6f} |")
    for task, key in (("points", "points_s"), ("rays", "rays_s")):
        py_s = ours[task][0]
        print(f"\nbinding overhead, {task}: Python {py_s:.4f} s vs Rust {rust[key]:.4f} s = {100 * (py_s / rust[key] - 1):+.1f}%")


if __name__ == "__main__":
    main()
