"""Loading a 1M-triangle binary STL and binary PLY: wingedge against
trimesh, MeshLib and Open3D, each loader one whole process (start-up and
imports included), timed by `farm-bench` (best of 3 wall seconds, peak
memory of that run's process).

    cargo build --release
    pip install trimesh meshlib open3d   # open3d needs: apt-get install -y libusb-1.0-0
    python3 benches/peers/formats.py [--work DIR] [--runs 3] [--write-docs]

The files are generated into DIR (default: a temporary folder; nothing is
committed): a UV sphere of 996,000 triangles (`trimesh.creation.uv_sphere`,
500 × 500 segments), written by trimesh as binary STL and binary PLY.

What each loader does, so that the rows can be read:

- wingedge: `wingedge info FILE`: reads, welds (STL repeats every corner:
  bit-identical corners merged only where that closes open edges), builds
  the winged-edge solid and prints its counts, shells, volume, area and
  centroid.
- trimesh: `trimesh.load(FILE)`: arrays, vertices merged (its default
  processing).
- MeshLib: `mrmeshpy.loadMesh(FILE)`: its half-edge mesh.
- Open3D: `o3d.io.read_triangle_mesh(FILE)`: arrays.

With `--write-docs` the table replaces the one between the markers in
docs/formats.md.
"""

from __future__ import annotations

import argparse
import datetime
import os
import pathlib
import re
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[2]
WINGEDGE = ROOT / "target" / "release" / "wingedge"
DOC = ROOT / "docs" / "formats.md"
START, END = "<!-- formats-speed:start -->", "<!-- formats-speed:end -->"

LOADERS = {
    "wingedge": lambda f: [str(WINGEDGE), "info", f],
    "trimesh": lambda f: [sys.executable, "-c", "import sys, trimesh; m = trimesh.load(sys.argv[1]); print(len(m.faces))", f],
    "MeshLib": lambda f: [sys.executable, "-c", "import sys, meshlib.mrmeshpy as mr; m = mr.loadMesh(sys.argv[1]); print(m.topology.numValidFaces())", f],
    "Open3D": lambda f: [sys.executable, "-c", "import sys, open3d as o3d; m = o3d.io.read_triangle_mesh(sys.argv[1]); print(len(m.triangles))", f],
}


def generate(work: pathlib.Path) -> dict[str, pathlib.Path]:
    import trimesh

    files = {"STL": work / "sphere_1m.stl", "PLY": work / "sphere_1m.ply"}
    if all(f.exists() for f in files.values()):
        return files
    mesh = trimesh.creation.uv_sphere(radius=1.0, count=[500, 500])
    mesh.export(files["STL"])
    files["PLY"].write_bytes(trimesh.exchange.ply.export_ply(mesh, encoding="binary"))
    return files


def bench(command: list[str], runs: int) -> tuple[float, float]:
    """Best wall seconds of `runs` and the peak MiB (min) from farm-bench."""
    out = subprocess.run(
        ["farm-bench", "-n", str(runs), "--warmup", "1", "--timeout", "900", "--", *command],
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    wall = re.search(r"^A wall s\s+([\d.]+)", out, re.M)
    peak = re.search(r"^A peak MiB\s+([\d.]+)", out, re.M)
    exit_ok = re.search(r"^A exit 0 \((\d+) of (\d+)\)", out, re.M)
    if not (wall and peak and exit_ok and exit_ok.group(1) == exit_ok.group(2)):
        raise SystemExit(f"{' '.join(command)} failed:\n{out}")
    return float(wall.group(1)), float(peak.group(1))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--work", type=pathlib.Path)
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--write-docs", action="store_true")
    args = parser.parse_args()
    if not WINGEDGE.exists():
        raise SystemExit("build it first: cargo build --release")
    work = args.work or pathlib.Path(tempfile.mkdtemp(prefix="wingedge-formats-"))
    work.mkdir(parents=True, exist_ok=True)
    files = generate(work)
    rows = []
    for kind, path in files.items():
        size = path.stat().st_size / 2**20
        for name, command in LOADERS.items():
            wall, peak = bench(command(str(path)), args.runs)
            rows.append((kind, size, name, wall, peak))
            print(f"{kind} {name}: {wall:.2f} s, {peak:.0f} MiB", flush=True)
    load = os.getloadavg()[0]
    table = [
        f"Measured {datetime.date.today()} on {os.cpu_count()} cores (load average {load:.1f} at the end), "
        f"`python3 benches/peers/formats.py --write-docs`; best of {args.runs} whole-process wall times.",
        "",
        "| file | loader | wall s (best) | peak MiB | vs wingedge |",
        "|---|---|---:|---:|---:|",
    ]
    for kind, size, name, wall, peak in rows:
        ours = next(w for k, _, n, w, _ in rows if k == kind and n == "wingedge")
        table.append(f"| {kind}, {size:.0f} MB | {name} | {wall:.2f} | {peak:.0f} | {wall / ours:.2f}× |")
    text = "\n".join(table)
    print(text)
    if args.write_docs:
        doc = DOC.read_text()
        before, rest = doc.split(START, 1)
        _, after = rest.split(END, 1)
        DOC.write_text(f"{before}{START}\n{text}\n{END}{after}")


if __name__ == "__main__":
    main()
