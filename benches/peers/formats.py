"""Loading a 1M-triangle binary STL and binary PLY: wingedge against
trimesh, MeshLib and Open3D, each loader one whole process (start-up and
imports included), best and median wall seconds of several runs after a
warm-up, and the peak resident memory of the process (`os.wait4`).

    cargo build --release --bin wingedge -p wingedge-bench --bin load_bench
    pip install trimesh meshlib open3d   # open3d needs: apt-get install -y libusb-1.0-0
    python3 benches/peers/formats.py [--work DIR] [--runs 5] [--write-docs]

The files are generated into DIR (default: a temporary folder; nothing is
committed): a UV sphere of 996,000 triangles (`trimesh.creation.uv_sphere`,
500 × 500 segments), written by trimesh as binary STL and binary PLY
(`float` coordinates, `int` indices).

What each loader does, so that the rows can be read:

- wingedge load: `load_bench load FILE` (benches/drivers), `io::import`
  with the default options, what every command that reads a mesh does
  first: reads the file, parses it with every face located, checks every
  coordinate finite and every index in range, and welds (STL repeats every
  corner: bit-identical corners merged only where that closes open edges,
  never into a pinch); prints the counts.
- wingedge solid: `load_bench solid FILE`, the same and then the
  winged-edge solid (every edge paired with its two faces, every wing
  linked, a plane per face).
- wingedge info: `wingedge info FILE`, the solid and then its shells,
  genus, volume, area and centroid, printed.
- trimesh: `trimesh.load(FILE)`: arrays, vertices merged (its default
  processing).
- MeshLib: `mrmeshpy.loadMesh(FILE)`: its half-edge mesh (STL corners
  merged by position).
- Open3D: `o3d.io.read_triangle_mesh(FILE)`: arrays.

Each command prints the vertex and face counts it ended with; the table
shows them, so a loader that merged less is seen to.

With `--write-docs` the table replaces the one between the markers in
docs/formats.md.
"""

from __future__ import annotations

import argparse
import datetime
import os
import pathlib
import platform
import re
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[2]
WINGEDGE = ROOT / "target" / "release" / "wingedge"
LOAD_BENCH = ROOT / "target" / "release" / "load_bench"
DOC = ROOT / "docs" / "formats.md"
START, END = "<!-- formats-speed:start -->", "<!-- formats-speed:end -->"

PEER = "import sys, {module}; m = {load}(sys.argv[1]); print({counts})"
LOADERS = {
    "wingedge load": lambda f: [str(LOAD_BENCH), "load", f],
    "wingedge solid": lambda f: [str(LOAD_BENCH), "solid", f],
    "wingedge info": lambda f: [str(WINGEDGE), "info", f],
    "trimesh": lambda f: [sys.executable, "-c", PEER.format(
        module="trimesh", load="trimesh.load", counts="len(m.vertices), len(m.faces)"), f],
    "MeshLib": lambda f: [sys.executable, "-c", PEER.format(
        module="meshlib.mrmeshpy as mr", load="mr.loadMesh",
        counts="m.topology.numValidVerts(), m.topology.numValidFaces()"), f],
    "Open3D": lambda f: [sys.executable, "-c", PEER.format(
        module="open3d as o3d", load="o3d.io.read_triangle_mesh",
        counts="len(m.vertices), len(m.triangles)"), f],
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


def run_once(command: list[str]) -> tuple[float, float, str]:
    """Wall seconds, peak resident MiB and standard output of one run of
    `command` as a process of its own."""
    start = time.perf_counter()
    child = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    # The pipes are read after the exit: what these commands print is a
    # line or a few.
    _, status, usage = os.wait4(child.pid, 0)
    wall = time.perf_counter() - start
    out, err = child.stdout.read().decode(), child.stderr.read().decode()
    child.stdout.close()
    child.stderr.close()
    if os.waitstatus_to_exitcode(status) != 0:
        raise SystemExit(f"{' '.join(command)} failed ({status}):\n{out}{err}")
    return wall, usage.ru_maxrss / 1024, out


def counts(printed: str) -> str:
    """The vertex and face counts a loader printed, as `V / F`: wingedge's
    `vertices V … faces F`, a peer's `(V, F)`."""
    named = re.search(r"vertices (\d+).*?faces (\d+)", printed, re.S)
    numbers = [int(n) for n in (named.groups() if named else re.findall(r"\d+", printed))]
    return f"{numbers[0]:,} / {numbers[1]:,}" if len(numbers) >= 2 else "?"


def bench(path: pathlib.Path, runs: int) -> list[tuple[str, float, float, float, str]]:
    """Every loader on `path`, in rounds (one run of each loader per round,
    so that a change in the machine's load falls on all of them alike):
    one warm-up round, then `runs` counted. Per loader: the name, best and
    median wall seconds, the largest peak MiB, and the counts printed."""
    walls: dict[str, list[float]] = {name: [] for name in LOADERS}
    peaks = dict.fromkeys(LOADERS, 0.0)
    printed = {}
    for round_ in range(runs + 1):
        for name, command in LOADERS.items():
            wall, peak, out = run_once(command(str(path)))
            peaks[name] = max(peaks[name], peak)
            printed.setdefault(name, out)
            if round_ > 0:
                walls[name].append(wall)
    return [
        (name, min(w), statistics.median(w), peaks[name], counts(printed[name]))
        for name, w in walls.items()
    ]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--work", type=pathlib.Path)
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--write-docs", action="store_true")
    args = parser.parse_args()
    for binary in (WINGEDGE, LOAD_BENCH):
        if not binary.exists():
            raise SystemExit(
                "build them first: cargo build --release --bin wingedge -p wingedge-bench --bin load_bench"
            )
    work = args.work or pathlib.Path(tempfile.mkdtemp(prefix="wingedge-formats-"))
    work.mkdir(parents=True, exist_ok=True)
    files = generate(work)
    rows = []
    for kind, path in files.items():
        size = path.stat().st_size / 1e6
        for name, best, median, peak, count in bench(path, args.runs):
            rows.append((kind, size, name, best, median, peak, count))
            print(f"{kind} {name}: best {best:.2f} s, median {median:.2f} s, {peak:.0f} MiB, {count}", flush=True)
    load = os.getloadavg()[0]
    versions = ", ".join(f"{m} {version(m)}" for m in ("trimesh", "meshlib", "open3d"))
    table = [
        f"Measured {datetime.date.today()} on {platform.processor() or platform.machine()}, "
        f"{os.cpu_count()} cores (load average {load:.1f} at the end), Python {platform.python_version()}, "
        f"{versions}; `python3 benches/peers/formats.py --write-docs`: "
        f"{args.runs} runs of each loader after a warm-up, taking turns.",
        "",
        "| file | loader | vertices / faces | wall s, best | median | peak MiB | median over wingedge load |",
        "|---|---|---:|---:|---:|---:|---:|",
    ]
    for kind, size, name, best, median, peak, count in rows:
        ours = next(m for k, _, n, _, m, _, _ in rows if k == kind and n == "wingedge load")
        table.append(
            f"| {kind}, {size:.0f} MB | {name} | {count} | {best:.2f} | {median:.2f} | {peak:.0f} | {median / ours:.2f}× |"
        )
    text = "\n".join(table)
    print(text)
    if args.write_docs:
        doc = DOC.read_text()
        before, rest = doc.split(START, 1)
        _, after = rest.split(END, 1)
        DOC.write_text(f"{before}{START}\n{text}\n{END}{after}")


def version(module: str) -> str:
    from importlib.metadata import version as installed

    return installed(module)


if __name__ == "__main__":
    main()
