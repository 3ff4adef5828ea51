"""Self-intersection validation against MeshLib and CGAL: time and peak
memory of the whole process (start, load, check, exit), one process per
tool and mesh, measured by `/usr/bin/time`.

    python3 benches/peers/validate_peers.py --wingedge target/release/wingedge \
        [--models DIR ...] [--own DIR] [--repeat N] [--timeout S] [--json OUT.json] \
    [--tools wingedge,meshlib,cgal] [--earlier EARLIER.json]

- wingedge: `wingedge validate --json MESH` (every check, the exact
  self-intersection check among them, and the winged-edge solid);
- MeshLib: `mrmeshpy.loadMesh` then `findSelfCollidingTriangles` (every
  pair of colliding triangles);
- CGAL: `Polyhedron_3` read from an OFF copy of the mesh (written before
  timing) then `Polygon_mesh_processing.self_intersections` (every pair,
  not `does_self_intersect`, which stops at the first).

The peers run in Python (`pip install meshlib cgal`), so their processes
include the interpreter and the import of the module; the table says so.
Meshes: every `.obj` of each `--models` directory (the shared models,
manifold's `test/models/`) and, with `--own DIR`, a set written there
(fans, slivers, a scan-like subdivided mesh, self-intersecting spheres; see
`own_meshes`). Prints a markdown table; a peer that cannot read a mesh or
fails gets its message instead of a time.
"""
import argparse
import json
import math
import os
import signal
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))

MESHLIB_CHILD = """
import sys
import meshlib.mrmeshpy as m
mesh = m.loadMesh(sys.argv[1])
pairs = m.findSelfCollidingTriangles(m.MeshPart(mesh))
print(len(pairs))
"""

CGAL_CHILD = """
import sys
from CGAL.CGAL_Polyhedron_3 import Polyhedron_3
from CGAL import CGAL_Polygon_mesh_processing as pmp
p = Polyhedron_3(sys.argv[1])
if p.size_of_facets() == 0:
    sys.exit("cannot read the mesh as a polyhedron")
out = []
pmp.self_intersections(p, out)
print(len(out))
"""


def read_obj(path):
    """Positions (as written, hex floats included) and 0-based polygons."""
    positions, polygons = [], []
    with open(path) as f:
        for line in f:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "v":
                positions.append(tuple(float.fromhex(x) if "x" in x else float(x)
                                       for x in parts[1:4]))
            elif parts[0] == "f":
                corners = [int(p.split("/")[0]) for p in parts[1:]]
                polygons.append([c - 1 if c > 0 else len(positions) + c for c in corners])
    return positions, polygons


def write_obj(path, positions, polygons):
    with open(path, "w") as f:
        for p in positions:
            f.write("v %r %r %r\n" % p)
        for poly in polygons:
            f.write("f " + " ".join(str(i + 1) for i in poly) + "\n")


def write_off(path, positions, polygons):
    with open(path, "w") as f:
        f.write(f"OFF\n{len(positions)} {len(polygons)} 0\n")
        for p in positions:
            f.write("%r %r %r\n" % p)
        for poly in polygons:
            f.write(f"{len(poly)} " + " ".join(map(str, poly)) + "\n")


def cone(n):
    """A closed cone of `n` rim vertices whose base is fanned from one rim
    vertex (long chords: slivers)."""
    p = [(0.0, 0.0, 1.0)]
    p += [(math.cos(2 * math.pi * k / n), math.sin(2 * math.pi * k / n), 0.0) for k in range(n)]
    f = [[0, 1 + k, 1 + (k + 1) % n] for k in range(n)]
    f += [[1, 1 + k + 1, 1 + k] for k in range(1, n - 1)]
    return p, f


def twin_fans(m, cells):
    """Two fans of `m` slivers from hubs a hair apart, sloping along each
    other over a bumpy plate that they cut (the shape of
    manifold's Generic_Twin models; as in the unit test)."""
    p, f = [], []
    at = lambda i, j: i * (cells + 1) + j
    for i in range(cells + 1):
        for j in range(cells + 1):
            p.append((float(i), float(j), 0.45 * ((i * 7 + j * 3) % 5) / 4.0))
    for i in range(cells):
        for j in range(cells):
            f.append([at(i, j), at(i + 1, j), at(i + 1, j + 1)])
            f.append([at(i, j), at(i + 1, j + 1), at(i, j + 1)])
    far = cells + 1.0
    for hub_z, rim_z, shift in [(0.6, 0.3, 0.0), (0.7, 0.35, 0.5)]:
        hub = len(p)
        p.append((-1.0, -1.0, hub_z))
        for k in range(m + 1):
            s = (k + shift) / (m + 1.0)
            p.append((far - s * (far + 1.0), -1.0 + s * (far + 1.0), rim_z))
        f += [[hub, hub + 1 + k, hub + 2 + k] for k in range(m)]
    return p, f


def uv_sphere(centre, r, rings, segments):
    p = [(centre[0], centre[1], centre[2] + r), (centre[0], centre[1], centre[2] - r)]
    for i in range(1, rings):
        t = math.pi * i / rings
        for j in range(segments):
            a = 2 * math.pi * j / segments
            p.append((centre[0] + r * math.sin(t) * math.cos(a),
                      centre[1] + r * math.sin(t) * math.sin(a),
                      centre[2] + r * math.cos(t)))
    ring = lambda i, j: 2 + (i - 1) * segments + j % segments
    f = [[0, ring(1, j), ring(1, j + 1)] for j in range(segments)]
    for i in range(1, rings - 1):
        for j in range(segments):
            f.append([ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)])
            f.append([ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)])
    f += [[1, ring(rings - 1, j + 1), ring(rings - 1, j)] for j in range(segments)]
    return p, f


def merged(*parts):
    p, f = [], []
    for q, g in parts:
        base = len(p)
        p += q
        f += [[base + i for i in poly] for poly in g]
    return p, f


def own_meshes(directory, shared_models):
    """The benchmark's own meshes, written into `directory`."""
    os.makedirs(directory, exist_ok=True)
    out = []
    cases = [
        ("cone_corner_fan_40k", lambda: cone(40_000)),
        ("twin_fans_6k_slivers", lambda: twin_fans(3_000, 60)),
        ("two_spheres_crossing", lambda: merged(uv_sphere((0, 0, 0), 1.0, 150, 300),
                                                uv_sphere((1.2, 0.1, 0.05), 1.0, 150, 300))),
    ]
    for name, make in cases:
        path = os.path.join(directory, name + ".obj")
        if not os.path.exists(path):
            write_obj(path, *make())
        out.append(path)
    spot = os.path.join(shared_models, "spot.obj")
    scan = os.path.join(directory, "spot_94k.obj")
    if os.path.exists(spot) and not os.path.exists(scan):
        subprocess.run([sys.executable, os.path.join(HERE, "closed_model.py"), spot, scan, "2"],
                       check=True, stdout=subprocess.DEVNULL)
    if os.path.exists(scan):
        out.append(scan)
    return out


def timed(command, timeout):
    """(seconds, peak MiB, CPU seconds, stdout, error or None) of one
    process; one that
    runs past `timeout` seconds is stopped (its process group)."""
    with tempfile.NamedTemporaryFile("r", suffix=".time") as t:
        proc = subprocess.Popen(["/usr/bin/time", "-f", "%e %M %U %S", "-o", t.name] + command,
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                start_new_session=True)
        try:
            stdout, stderr = proc.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.communicate()
            return float(timeout), 0.0, 0.0, "", "> %d s (stopped)" % timeout
        r = subprocess.CompletedProcess(command, proc.returncode, stdout, stderr)
        fields = t.read().split()
    seconds, kib = float(fields[-4]), int(fields[-3])
    cpu = float(fields[-2]) + float(fields[-1])
    error = None
    if r.returncode not in (0, 1):
        error = (r.stderr.strip().splitlines() or ["exit %d" % r.returncode])[-1][:60]
    return seconds, kib / 1024.0, cpu, r.stdout, error


def measure(args, mesh, off):
    row = {"mesh": os.path.basename(mesh)}
    positions, polygons = read_obj(mesh)
    row["triangles"] = sum(len(p) - 2 for p in polygons)
    write_off(off, positions, polygons)
    runs = {
        "wingedge": [args.wingedge, "validate", "--json", mesh],
        "meshlib": [sys.executable, "-c", MESHLIB_CHILD, mesh],
        "cgal": [sys.executable, "-c", CGAL_CHILD, off],
    }
    for tool, command in runs.items():
        if tool not in args.tools:
            row[tool] = args.earlier.get(
                (row["mesh"], tool), {"seconds": 0.0, "mib": 0.0, "cpu": 0.0, "error": "not run"})
            continue
        best = None
        for _ in range(args.repeat):
            run = timed(command, args.timeout)
            if best is None or run[0] < best[0]:
                best = run
        seconds, mib, cpu, stdout, error = best
        cell = {"seconds": seconds, "mib": mib, "cpu": cpu, "error": error}
        if error is None:
            if tool == "wingedge":
                report = json.loads(stdout)[0]
                cell["pairs"] = report["counts"]["self_intersection"]
                cell["valid"] = report["valid"]
            else:
                cell["pairs"] = int(stdout.split()[-1])
        row[tool] = cell
    return row


def budget_mib(triangles):
    """The goal: 300 bytes per triangle plus a fixed 50 MB."""
    return (300 * triangles + 50e6) / 2**20


def table(rows):
    lines = [
        "| mesh | triangles | wingedge s (CPU) | MeshLib s (CPU) | CGAL s (CPU) | wingedge MiB "
        "| MeshLib MiB | CGAL MiB | budget MiB | pairs (w / M / C) | goal |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---|---|",
    ]
    for r in rows:
        def s(t):
            c = r[t]
            return c["error"] if c["error"] else "%.2f (%.2f)" % (c["seconds"], c["cpu"])

        def m(t):
            c = r[t]
            return "—" if c["error"] else "%.0f" % c["mib"]

        def p(t):
            return str(r[t].get("pairs", "—"))

        w = r["wingedge"]
        peers = [r[t]["seconds"] for t in ("meshlib", "cgal") if not r[t]["error"]]
        fast = not w["error"] and (not peers or w["seconds"] <= min(peers))
        small = w["mib"] <= budget_mib(r["triangles"])
        goal = {(True, True): "yes", (False, True): "slower", (True, False): "memory"}.get(
            (fast, small), "slower, memory")
        lines.append(
            f"| {r['mesh']} | {r['triangles']:,} | {s('wingedge')} | {s('meshlib')} | {s('cgal')} "
            f"| {m('wingedge')} | {m('meshlib')} | {m('cgal')} | {budget_mib(r['triangles']):.0f} "
            f"| {p('wingedge')} / {p('meshlib')} / {p('cgal')} | {goal} |")
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--wingedge", required=True)
    parser.add_argument("--models", action="append", default=[])
    parser.add_argument("--own", help="directory for the benchmark's own meshes")
    parser.add_argument("--shared", default="/work/shared/models")
    parser.add_argument("--repeat", type=int, default=1)
    parser.add_argument("--timeout", type=int, default=300, help="seconds per process")
    parser.add_argument("--json", help="also write the rows here")
    parser.add_argument("--tools", default="wingedge,meshlib,cgal",
                        help="the tools to run (comma-separated); the others' cells come from "
                             "--earlier")
    parser.add_argument("--earlier", dest="earlier_path", help="the --json of an earlier run")
    args = parser.parse_args()
    args.tools = args.tools.split(",")
    args.earlier = {}
    if args.earlier_path:
        with open(args.earlier_path) as f:
            for row in json.load(f):
                for tool in ("wingedge", "meshlib", "cgal"):
                    args.earlier[(row["mesh"], tool)] = row[tool]
    meshes = []
    for d in args.models:
        meshes += sorted(os.path.join(d, n) for n in os.listdir(d) if n.endswith(".obj"))
    if args.own:
        meshes += own_meshes(args.own, args.shared)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for mesh in meshes:
            rows.append(measure(args, mesh, os.path.join(tmp, "mesh.off")))
            print(table(rows[-1:]).splitlines()[-1], file=sys.stderr, flush=True)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1)
    print(table(rows))


if __name__ == "__main__":
    main()
