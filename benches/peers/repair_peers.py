"""Repair of real broken meshes, wingedge beside its peers: for each model
and tool, the whole process's time and peak memory, whether the output is
a valid solid (by wingedge's validator and by manifold3d's status) and its
volume against the input's winding-number volume; and two oracles: how
many sampled points each output holds exactly where libigl's winding
number of the input is above 1/2, and its volume against manifold3d's of
the input where manifold3d accepts the input. Prints a Markdown table.

    cargo build --release --bin wingedge
    python3 -m pip install meshlib pymeshfix manifold3d trimesh libigl
    python3 benches/peers/repair_peers.py MODEL.obj...

The tools, each run as its own process (`--one TOOL IN OUT`):

- wingedge: `wingedge repair IN -o OUT` (clean, orient, fill, resolve by
  winding number; exact).
- MeshLib: `fillHoles` on every hole, then `fixSelfIntersections` (by
  voxels, of size 1/500 of the box diagonal: it rebuilds the whole surface).
- PyMeshFix: `MeshFix.repair()` (MeshFix: holes filled, the largest
  component kept, intersecting faces removed and their holes filled).

Oracles: 4,000 points drawn (seed 37) in the input's box padded by 5 %;
those nearer the input's surface than 1 % of the box diagonal or with a
winding number within 1/4 of 1/2 are left out (near a hole the input does
not say on which side a point is). A point is inside the input when
libigl's `fast_winding_number` of the input exceeds 1/2, inside an output
when that of the output does. manifold3d's volume of the input
(`Mesh64`, as it is) where its status is `NoError`.

CGAL's pip package exposes `orient_polygon_soup` and hole filling but not
`autorefine`, so it cannot resolve self-intersections and is not run.
"""

import json
import os
import signal
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
WINGEDGE = os.path.join(ROOT, "target", "release", "wingedge")
# REPAIR_PEERS_TOOLS=wingedge,meshlib runs only those.
TOOLS = tuple(os.environ.get("REPAIR_PEERS_TOOLS", "wingedge,meshlib,pymeshfix").split(","))
TIMEOUT = 300


def one(tool, source, target):
    """Runs one tool in this process (the child of `measure`)."""
    if tool == "meshlib":
        import meshlib.mrmeshpy as mr

        mesh = mr.loadMesh(source)
        holes = mesh.topology.findHoleRepresentiveEdges()
        if holes.size():
            mr.fillHoles(mesh, holes)
        box = mesh.computeBoundingBox()
        mr.fixSelfIntersections(mesh, box.diagonal() / 500.0)
        mr.saveMesh(mesh, target)
    elif tool == "pymeshfix":
        import numpy as np
        import pymeshfix
        import trimesh

        t = trimesh.load(source, process=False, force="mesh")
        fix = pymeshfix.MeshFix(np.asarray(t.vertices), np.asarray(t.faces))
        fix.repair()
        trimesh.Trimesh(fix.points, fix.faces, process=False).export(target)
    else:
        raise SystemExit(f"unknown tool {tool}")


def measure(argv):
    """Runs `argv`: (seconds, None, returncode, stdout, stderr), or Nones when stopped."""
    start = time.perf_counter()
    # A session of its own, so that a timeout stops the tool under
    # /usr/bin/time too (killing only `time` would leave it holding the pipes).
    p = subprocess.Popen(
        argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True
    )
    try:
        out, err = p.communicate(timeout=TIMEOUT)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        p.communicate()
        return None, None, None, "", f"stopped after {TIMEOUT} s"
    return time.perf_counter() - start, None, p.returncode, out, err


def timed(argv):
    """`measure` under /usr/bin/time -f %M for the child's own peak."""
    seconds, _, code, out, err = measure(["/usr/bin/time", "-f", "%M"] + argv)
    if seconds is None:
        return None, None, None, out, err
    lines = err.strip().splitlines()
    peak = int(lines[-1]) / 1024 if lines and lines[-1].isdigit() else None
    return seconds, peak, code, out, "\n".join(lines[:-1])


def judged(path):
    """wingedge's validity and volume of a written mesh, and manifold3d's status."""
    p = subprocess.run([WINGEDGE, "validate", path, "--json"], capture_output=True, text=True)
    try:
        report = json.loads(p.stdout)[0]
        validity, volume = report.get("validity"), report.get("volume")
    except (ValueError, IndexError, KeyError):
        validity, volume = "unreadable", None
    return validity, volume, manifold_status(path)


def manifold_status(path):
    """manifold3d's status of the mesh at `path` (triangulated)."""
    import manifold3d
    import numpy as np
    import trimesh

    try:
        t = trimesh.load(path, process=False, force="mesh")
    except Exception as e:  # noqa: BLE001 - any reader failure is the answer
        return f"unreadable ({type(e).__name__})"
    if len(t.faces) == 0:
        return "empty"
    mesh = manifold3d.Mesh(
        vert_properties=np.asarray(t.vertices, dtype=np.float32),
        tri_verts=np.asarray(t.faces, dtype=np.uint32),
    )
    return str(manifold3d.Manifold(mesh).status()).split(".")[-1]


def oracle(model):
    """The sampled points kept, libigl's verdict on them, and manifold3d's
    volume of the input (or its status when it refuses it)."""
    import igl
    import manifold3d
    import numpy as np
    import trimesh

    t = trimesh.load(model, process=False, force="mesh")
    v, f = np.asarray(t.vertices, float), np.asarray(t.faces, np.int64)
    lo, hi = v.min(axis=0), v.max(axis=0)
    points = np.random.default_rng(37).uniform(lo - 0.05 * (hi - lo), hi + 0.05 * (hi - lo), (4000, 3))
    w = igl.fast_winding_number(v, f, points)
    squared, _, _ = igl.point_mesh_squared_distance(points, v, f)
    far = (np.abs(w - 0.5) > 0.25) & (np.sqrt(squared) > 0.01 * np.linalg.norm(hi - lo))
    m = manifold3d.Manifold(manifold3d.Mesh64(vert_properties=v, tri_verts=f.astype(np.uint64)))
    status = str(m.status()).split(".")[-1]
    volume = m.volume() if status == "NoError" else None
    return points[far], w[far] > 0.5, volume, status


def agreement(out, points, inside):
    """How many of `points` the output at `out` holds as libigl says the input does."""
    import igl
    import numpy as np
    import trimesh

    try:
        t = trimesh.load(out, process=False, force="mesh")
    except Exception:  # noqa: BLE001 - any reader failure is the answer
        return "unreadable"
    if len(t.faces) == 0:
        got = np.zeros(len(points), bool)
    else:
        got = igl.fast_winding_number(np.asarray(t.vertices, float), np.asarray(t.faces, np.int64), points) > 0.5
    return f"{np.count_nonzero(got == inside)}/{len(points)}"


def row(model, tool, before, oracles):
    out = os.path.join(tempfile.mkdtemp(), f"{tool}.obj")
    if tool == "wingedge":
        argv = [WINGEDGE, "repair", model, "-o", out, "--json"]
    else:
        argv = [sys.executable, os.path.abspath(__file__), "--one", tool, model, out]
    seconds, peak, code, stdout, err = timed(argv)
    name = os.path.basename(model)
    if seconds is None:
        return f"| {name} | {tool} | > {TIMEOUT} s | | stopped | | | | |", before
    if tool == "wingedge" and code == 0:
        before = json.loads(stdout)["volume_before"]
    if not os.path.exists(out):
        first = (err.strip().splitlines() or ["?"])[-1][:80]
        return f"| {name} | {tool} | {seconds:.2f} | {peak:.0f} | no output: {first} | | | | |", before
    validity, volume, status = judged(out)
    change = "" if volume is None or not before else f"{(volume - before) / before:+.2e}"
    vol = "" if volume is None else f"{volume:.6g}"
    points, inside, m_volume, m_status = oracles
    agrees = agreement(out, points, inside)
    if m_volume is None:
        versus = f"input refused ({m_status})"
    else:
        versus = "" if volume is None else f"{(volume - m_volume) / m_volume:+.2e}"
    return (f"| {name} | {tool} | {seconds:.2f} | {peak:.0f} | {validity} | {status} | {vol} ({change}) "
            f"| {agrees} | {versus} |"), before


def main():
    if sys.argv[1:2] == ["--one"]:
        one(*sys.argv[2:5])
        return
    print("| model | tool | seconds | peak MiB | wingedge validator | manifold3d status | volume (change against the input's winding-number volume) "
          "| agrees with libigl winding number | volume vs manifold3d |")
    print("|---|---|---:|---:|---|---|---|---:|---:|")
    for model in sys.argv[1:]:
        before = None
        oracles = oracle(model)
        for tool in TOOLS:
            line, before = row(model, tool, before, oracles)
            print(line, flush=True)


if __name__ == "__main__":
    main()
