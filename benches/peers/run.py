#!/usr/bin/env python3
"""wingedge and its peers on the same meshes, points and rays, in one run.

    python3 benches/peers/run.py --out /tmp/peers

builds the command line, the benchmark drivers and the parry harness
(`cargo build --release -p wingedge -p wingedge-bench --bins`,
`cargo build --release -p wingedge-peers-parry`), makes the inputs
(seeded; see inputs.py) under OUT/inputs — the meshes sphere_80k, torus_knot
and sphere_1m, and the real models fandisk and spot and their exact
midpoint refinements fandisk_x2 and spot_x4 when the team's shared models
folder is next to the repository — then for each mesh:

  (a) point classification of 1M points uniform in the mesh's box,
  (b) first-hit ray casting of 1M rays from a sphere around the box,
  (c) import + validation of the mesh's OBJ file,
  (d) the harder query sets (--sets; 1M queries each): points near the
      surface, rays from inside the box, rays aimed at vertices, rays
      grazing along faces — wingedge and open3d only,

by wingedge (benches/drivers/src/bin/peers_wingedge.rs), parry3d and parry3d-f64
(benches/peers/parry/, a crate of its own in the workspace), trimesh with
Embree, libigl's fast winding number, open3d's RaycastingScene and
manifold3d (python_peers.py). Everyone gets 2 threads (RAYON_NUM_THREADS,
OMP_NUM_THREADS, open3d's nthreads); every
timing is the best of 3 unless a run takes over 5 s, and wingedge and
open3d (the closest in speed) take turns over --rounds rounds (3), each
keeping its best, so that a slow spell of the shared machine does not fall
on one of them alone; setup (the
acceleration structure's build) is timed apart from the queries, and reading
the input files is not timed. Each validation runs in a fresh process (so
its peak memory is its own), three rounds, wingedge and the peers
alternating.

Every answer is compared with wingedge's. Where a library and wingedge
differ (a point's side; a ray's hit or miss, or its `t` by more than 1e-4
relative), exact rational arithmetic (exact.py, independent of every
library) decides which is right, for up to --arbitrate such queries per mesh
and task, plus a control sample of queries on which everyone agrees.

The table goes to stdout and OUT/peers.md; everything measured to
OUT/peers.json. The inputs take about 2 GB under OUT and are reused by
the next run.

With --booleans CASES (default `spheres`; `none` to skip, `spheres,models`
for the real models too), the boolean table of booleans.py follows: the
difference of two offset spheres of 131k and 524k triangles through
wingedge, manifold3d, MeshLib and CGAL's corefinement, each result checked
by `wingedge validate` (its rows go to OUT/booleans.json).
"""
import argparse
import datetime
import json
import os
import platform
import subprocess
import sys
import time

THREADS = 2
for _var in ("RAYON_NUM_THREADS", "OMP_NUM_THREADS"):
    os.environ[_var] = str(THREADS)

import numpy as np  # noqa: E402  (after the thread settings)

import exact  # noqa: E402
import inputs  # noqa: E402
import python_peers  # noqa: E402
import report  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
# The drivers (benches/drivers/) and the parry harness are workspace members:
# their binaries sit in target/release.
BINARIES = os.path.join(ROOT, "target", "release")
PEERS_PARRY = os.path.join(ROOT, "target", "release", "peers_parry")
BUILD_COMMANDS = [["cargo", "build", "--release", "-p", "wingedge", "-p", "wingedge-bench", "--bins"],
                  ["cargo", "build", "--release", "-p", "wingedge-peers-parry"]]
# The three shared meshes, then the team's real models that fit in
# the caches (a CAD part and a remeshed scan) when their folder is there.
DEFAULT_MESHES = ["sphere_80k", "torus_knot", "sphere_1m"] + (
    ["fandisk", "spot", "fandisk_x2", "spot_x4"] if os.path.isdir(inputs.MODELS) else [])
T_TOLERANCE = 1e-4  # relative, for comparing first-hit parameters
VALIDATE_ROUNDS = 3


def log(*parts):
    print("[%s]" % time.strftime("%H:%M:%S"), *parts, file=sys.stderr, flush=True)


def run_json_lines(command):
    """Runs a command and parses every stdout line as JSON; stops the run with its stderr on failure."""
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        raise SystemExit("%s failed (exit %d):\n%s" % (" ".join(command), done.returncode, done.stderr))
    return [json.loads(line) for line in done.stdout.splitlines() if line.startswith("{")]


# ---------------------------------------------------------------- agreement

def points_differ(ours, peer):
    """Indices where a peer's inside/outside differs from wingedge's (boundary answers excluded)."""
    ours = ours[: len(peer)]
    return np.nonzero((peer != (ours == 1)) & (ours != 2))[0]


def t_differ(a, b):
    hit_a, hit_b = np.isfinite(a), np.isfinite(b)
    both = hit_a & hit_b
    off = np.zeros(len(a), bool)
    off[both] = np.abs(a[both] - b[both]) > T_TOLERANCE * np.maximum(1.0, np.abs(a[both]))
    return (hit_a != hit_b) | off


def rays_differ(ours, peer):
    return np.nonzero(t_differ(ours[: len(peer)], peer))[0]


def max_t_gap(ours, peer):
    """The largest |t - t_wingedge| over the rays on which both hit and agree."""
    ours = ours[: len(peer)]
    both = np.isfinite(ours) & np.isfinite(peer) & ~t_differ(ours, peer)
    return float(np.abs(ours[both] - peer[both]).max()) if both.any() else 0.0


def arbitrate(mesh, points, rays, ours, rows, limit, rng):
    """Exact answers for the queries some row differs on, plus a unanimous control sample."""
    verdicts = {}
    for task in [t for t in ("points", "rays") if t in ours]:
        peers = [r for r in rows if r["task"] == task and r["library"] != "wingedge"]
        disputed = sorted(set().union(*[set(r["differs"].tolist()) for r in peers])) if peers else []
        unanimous = np.setdiff1d(np.arange(len(ours[task])), disputed)
        control = rng.choice(unanimous, size=min(10, len(unanimous)), replace=False).tolist()
        chosen = disputed[:limit] + sorted(control)
        start = time.perf_counter()
        answers = {}
        for i in chosen:
            if task == "points":
                answers[i] = exact.classify_point(mesh, points[i], rng)
            else:
                t, how = exact.first_hit(mesh, rays[i, :3], rays[i, 3:])
                if how == "in_plane":
                    continue  # the ray lies in a face's plane: not settled here
                answers[i] = (np.inf if t is None else float(t), how)
        wingedge_wrong = sum(not _right(task, ours[task][i], answers[i], wingedge=True) for i in answers)
        said = {i: {r["library"]: _answer_word(task, r["answers"][i], r["library"] == "wingedge")
                    for r in rows if r["task"] == task and i < len(r["answers"])}
                for i in disputed[:limit] if i in answers}
        verdicts[task] = {"answers": answers, "disputed": len(disputed), "checked": min(len(disputed), limit),
                          "control": control, "wingedge_wrong": wingedge_wrong, "said": said,
                          "seconds": time.perf_counter() - start}
    for r in rows:
        v = verdicts[r["task"]]["answers"]
        checked = [i for i in r["differs"].tolist() if i in v]
        control = [i for i in verdicts[r["task"]]["control"] if i < len(r["answers"]) and i in v]
        r["checked"] = len(checked)
        r["peer_wrong"] = sum(not _right(r["task"], r["answers"][i], v[i]) for i in checked)
        r["wingedge_wrong"] = sum(not _right(r["task"], ours[r["task"]][i], v[i], wingedge=True) for i in checked)
        r["control_wrong"] = sum(not _right(r["task"], r["answers"][i], v[i],
                                            wingedge=r["library"] == "wingedge") for i in control)
    return verdicts


def _answer_word(task, answer, wingedge):
    if task == "points":
        return {0: "outside", 1: "inside", 2: "boundary"}[int(answer)] if wingedge else (
            "inside" if answer else "outside")
    return float(answer)


def _right(task, answer, truth, wingedge=False):
    if task == "points":
        if wingedge:
            return {0: "outside", 1: "inside", 2: "boundary"}[int(answer)] == truth
        return truth == "boundary" or bool(answer) == (truth == "inside")
    t_exact = truth[0]
    return not t_differ(np.array([t_exact]), np.array([float(answer)]))[0]


# ---------------------------------------------------------------- the run

def best_rows(runs):
    """The rows of several runs of one library, each task's fastest (setup: the fastest too)."""
    best = []
    for rows in zip(*runs):
        fastest = min(rows, key=lambda r: r["seconds"])
        best.append(dict(fastest, setup_s=min(r["setup_s"] for r in rows)))
    return best


def queries_for_mesh(name, directory, args, rng):
    vertices, triangles = inputs.read_obj(os.path.join(directory, name + ".obj"))
    points = np.fromfile(os.path.join(directory, name + ".points.f64"), "<f8").reshape(-1, 3)
    rays = np.fromfile(os.path.join(directory, name + ".rays.f64"), "<f8").reshape(-1, 6)
    # wingedge and open3d, the closest in speed, take turns over several
    # rounds and keep their best, so that a slow spell of the machine does
    # not fall on one of them alone.
    ours_lines, open3d_runs = [], []
    for round_ in range(args.rounds):
        log(name, "wingedge, round %d of %d" % (round_ + 1, args.rounds))
        ours_lines.append(run_json_lines([os.path.join(BINARIES, "peers_wingedge"), "queries", directory, name])[0])
        log(name, "open3d, round %d of %d" % (round_ + 1, args.rounds))
        open3d_runs.append(python_peers.open3d_scene(vertices, triangles, points, rays))
    ours_line = dict(ours_lines[0], **{key: min(line[key] for line in ours_lines)
                                       for key in ("accel_s", "points_s", "rays_s")})
    ours = {"points": np.fromfile(os.path.join(directory, name + ".wingedge.points.u8"), np.uint8),
            "rays": np.fromfile(os.path.join(directory, name + ".wingedge.rays.f64"), "<f8")}
    rows = [dict(library="wingedge", precision="f64, exact signs", threads=ours_line["threads"], task=task,
                 setup_s=ours_line["accel_s"], seconds=ours_line[task + "_s"], queries=ours_line[task],
                 answers=ours[task]) for task in ("points", "rays")]
    log(name, "parry")
    for line in run_json_lines([PEERS_PARRY, "queries", directory,
                                str(args.parry_points), name]):
        tag = line["library"]
        label = {"parry_f32": "parry3d", "parry_f64": "parry3d-f64"}[tag]
        answers = {"points": np.fromfile(os.path.join(directory, "%s.%s.points.u8" % (name, tag)), np.uint8) == 1,
                   "rays": np.fromfile(os.path.join(directory, "%s.%s.rays.f64" % (name, tag)), "<f8")}
        for task in ("points", "rays"):
            rows.append(dict(library=label, precision=tag[-3:], threads=line["threads"], task=task,
                             setup_s=line["build_s"], seconds=line[task + "_s"], queries=line[task],
                             answers=answers[task]))
    log(name, "trimesh")
    rows += python_peers.trimesh_embree(vertices, triangles, points, rays)
    log(name, "libigl")
    rows += python_peers.libigl_fwn(vertices, triangles, points)
    rows += best_rows(open3d_runs)
    log(name, "manifold3d")
    rows += python_peers.manifold3d_rays(vertices, triangles, rays, args.manifold_seconds)
    for r in rows:
        r["mesh"] = name
        r["triangles"] = len(triangles)
        r["differs"] = (points_differ if r["task"] == "points" else rays_differ)(ours[r["task"]], r["answers"])
        if r["task"] == "rays":
            r["max_t_gap"] = max_t_gap(ours["rays"], r["answers"])
    log(name, "exact arbitration")
    verdicts = arbitrate(exact.Mesh(vertices, triangles), points, rays, ours, rows, args.arbitrate, rng)
    return rows, verdicts


def set_for_mesh(name, query_set, directory, args, rng):
    """wingedge and open3d, taking turns, on one of the harder query sets
    (inputs.SETS) of a mesh; their disputes settled exactly."""
    vertices, triangles = inputs.read_obj(os.path.join(directory, name + ".obj"))
    task = inputs.SETS[query_set]
    stem = "%s.%s" % (name, query_set)
    width = 3 if task == "points" else 6
    queries = np.fromfile(os.path.join(directory, "%s.%s.f64" % (stem, task)), "<f8").reshape(-1, width)
    ours_lines, open3d_runs = [], []
    for round_ in range(args.rounds):
        log(stem, "wingedge, round %d of %d" % (round_ + 1, args.rounds))
        ours_lines.append(run_json_lines([os.path.join(BINARIES, "peers_wingedge"), "queries", directory,
                                          "%s@%s" % (name, query_set)])[0])
        log(stem, "open3d, round %d of %d" % (round_ + 1, args.rounds))
        open3d_runs.append(python_peers.open3d_scene(
            vertices, triangles, queries if task == "points" else None, queries if task == "rays" else None))
    seconds = min(line[task + "_s"] for line in ours_lines)
    answers = (np.fromfile(os.path.join(directory, stem + ".wingedge.points.u8"), np.uint8) if task == "points"
               else np.fromfile(os.path.join(directory, stem + ".wingedge.rays.f64"), "<f8"))
    rows = [dict(library="wingedge", precision="f64, exact signs", threads=ours_lines[0]["threads"], task=task,
                 setup_s=min(line["accel_s"] for line in ours_lines), seconds=seconds,
                 queries=ours_lines[0][task], answers=answers)]
    rows += best_rows(open3d_runs)
    for r in rows:
        r["mesh"] = name
        r["set"] = query_set
        r["triangles"] = len(triangles)
        r["differs"] = (points_differ if task == "points" else rays_differ)(answers, r["answers"])
        if task == "rays":
            r["max_t_gap"] = max_t_gap(answers, r["answers"])
    log(stem, "exact arbitration")
    points = queries if task == "points" else None
    rays = queries if task == "rays" else None
    verdicts = arbitrate(exact.Mesh(vertices, triangles), points, rays, {task: answers}, rows, args.arbitrate, rng)
    return rows, verdicts


def validate_python_peers(path):
    """One fresh-process measurement: trimesh.load, then manifold3d's Manifold from its arrays."""
    import manifold3d as m3d
    import trimesh
    start = time.perf_counter()
    mesh = trimesh.load(path, process=False, force="mesh")
    loaded = time.perf_counter()
    solid = m3d.Manifold(m3d.Mesh64(vert_properties=np.ascontiguousarray(mesh.vertices, dtype=np.float64),
                                    tri_verts=np.ascontiguousarray(mesh.faces, dtype=np.uint64)))
    status = solid.status()
    seconds = time.perf_counter() - start
    rss = None
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmHWM:"):
                rss = int(line.split()[1]) / 1024
    print(json.dumps({"file": path, "seconds": seconds, "import_s": loaded - start, "rss_mib": rss,
                      "status": status.name, "valid": status == m3d.Error.NoError,
                      "triangles": int(solid.num_tri()), "genus": int(solid.genus()),
                      "volume": float(solid.volume()),
                      "trimesh_watertight": bool(mesh.is_watertight),
                      "trimesh_winding_consistent": bool(mesh.is_winding_consistent)}))


def validation_for_mesh(name, directory):
    path = os.path.join(directory, name + ".obj")
    commands = {
        "wingedge": [os.path.join(BINARIES, "peers_wingedge"), "validate", path],
        "trimesh.load + manifold3d Manifold": [sys.executable, os.path.abspath(__file__), "--validate-with-python-peers", path],
        "tobj + parry3d-f64 TriMesh topology": [PEERS_PARRY, "validate", path],
    }
    best = {}
    for _ in range(VALIDATE_ROUNDS):
        for library, command in commands.items():
            line = run_json_lines(command)[0]
            if library not in best or line["seconds"] < best[library]["seconds"]:
                best[library] = line
    return best


def machine():
    cpu, virtual = "?", False
    try:
        with open("/proc/cpuinfo") as f:
            text = f.read()
        cpu = text.split("model name", 1)[1].split(":", 1)[1].split("\n", 1)[0].strip()
        virtual = " hypervisor" in text
    except (OSError, IndexError):
        pass
    if virtual:
        cpu += ", a virtual machine"
    from importlib.metadata import version
    packages = {p: version(p) for p in ("numpy", "trimesh", "embreex", "libigl", "open3d", "manifold3d")}
    rustc = subprocess.run(["rustc", "--version"], capture_output=True, text=True).stdout.strip()
    parry = "?"
    with open(os.path.join(ROOT, "Cargo.lock")) as f:
        lock = f.read().split("[[package]]")
    for block in lock:
        if 'name = "parry3d"' in block:
            parry = block.split('version = "')[1].split('"')[0]
    return {"date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
            "cpu": cpu, "cores": os.cpu_count(), "python": platform.python_version(), "rustc": rustc,
            "parry3d": parry, "packages": packages, "threads": THREADS}


def booleans_table(args):
    """The boolean benchmark (booleans.py) on --booleans cases, in this
    Python (its peers must be installed here; a missing one gets a row that
    says so), as a markdown section."""
    log("booleans", args.booleans)
    command = [sys.executable, os.path.join(os.path.dirname(os.path.abspath(__file__)), "booleans.py"),
               "--cases", args.booleans, "--rounds", str(args.rounds),
               "--workdir", os.path.join(os.path.abspath(args.out), "booleans"),
               "--json", os.path.join(os.path.abspath(args.out), "booleans.json")]
    done = subprocess.run(command, cwd=ROOT, capture_output=True, text=True)
    if done.returncode != 0:
        return "## Booleans (A − B)\n\nbooleans.py failed:\n\n```\n%s\n```\n" % done.stderr[-2000:]
    return "## Booleans (A − B)\n\n" + done.stdout


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "--validate-with-python-peers":
        validate_python_peers(sys.argv[2])
        return
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", required=True, help="directory for inputs, answers and the table")
    ap.add_argument("--inputs", help="use NAME.obj/.points.f64/.rays.f64 from this directory instead of making them")
    ap.add_argument("--meshes",
                    help="comma-separated, from: %s (default: %s; with --inputs, those of them that are there)"
                    % (", ".join(inputs.MAKERS), ",".join(DEFAULT_MESHES)))
    ap.add_argument("--queries", type=int, default=1_000_000, help="points and rays per mesh")
    ap.add_argument("--parry-points", type=int, default=50_000,
                    help="points given to parry's contains_point (slow on large curved meshes)")
    ap.add_argument("--manifold-seconds", type=float, default=3.0,
                    help="time budget per mesh for manifold3d's one-at-a-time ray_cast")
    ap.add_argument("--arbitrate", type=int, default=200, help="disputed queries settled exactly per mesh and task")
    ap.add_argument("--rounds", type=int, default=3,
                    help="rounds in which wingedge and open3d take turns (each keeps its best)")
    ap.add_argument("--sets", default=",".join(inputs.SETS),
                    help="the harder query sets run by wingedge and open3d on every mesh, comma-separated "
                    "(default: all of %(default)s; none to skip; not with --inputs)")
    ap.add_argument("--no-build", action="store_true", help="skip cargo build (drivers and parry harness already built)")
    ap.add_argument("--booleans", default="spheres",
                    help="boolean cases after the query table: none, or a comma list of spheres, models")
    args = ap.parse_args()
    started = time.perf_counter()
    load_at_start = os.getloadavg()[0]
    directory = os.path.join(os.path.abspath(args.out), "inputs")
    os.makedirs(directory, exist_ok=True)
    if not args.no_build:
        for command in BUILD_COMMANDS:
            log(" ".join(command))
            subprocess.run(command, cwd=ROOT, check=True)
    if args.meshes:
        names = [n for n in args.meshes.split(",") if n]
    elif args.inputs:
        names = [n for n in DEFAULT_MESHES if os.path.exists(os.path.join(args.inputs, n + ".obj"))]
    else:
        names = DEFAULT_MESHES
    rng = np.random.default_rng(20261121)
    rows, verdicts, validations, metas = [], {}, {}, {}
    for name in names:
        log(name, "inputs")
        metas[name] = (inputs.link_existing(args.inputs, directory, name) if args.inputs
                       else inputs.make(directory, name, args.queries))
        mesh_rows, verdicts[name] = queries_for_mesh(name, directory, args, rng)
        rows += mesh_rows
        log(name, "validation")
        validations[name] = validation_for_mesh(name, directory)
        sets = [] if args.inputs or args.sets == "none" else [q for q in args.sets.split(",") if q]
        if sets:
            metas[name] = inputs.make_sets(directory, name, args.queries, sets)
        for query_set in sets:
            set_rows, verdicts["%s@%s" % (name, query_set)] = set_for_mesh(name, query_set, directory, args, rng)
            rows += set_rows
    info = machine()
    info["minutes"] = (time.perf_counter() - started) / 60
    info["load"] = (load_at_start, os.getloadavg()[0])
    table = report.markdown(rows, verdicts, validations, info, args)
    if args.booleans != "none":
        table += "\n" + booleans_table(args)
    print(table)
    with open(os.path.join(args.out, "peers.md"), "w") as f:
        f.write(table)
    with open(os.path.join(args.out, "peers.json"), "w") as f:
        json.dump(report.as_json(rows, verdicts, validations, metas, info), f, indent=1,
                  default=lambda o: o.item() if hasattr(o, "item") else str(o))
    log("done in %.1f min; table in %s" % (info["minutes"], os.path.join(args.out, "peers.md")))


if __name__ == "__main__":
    main()
