"""The boolean benchmark: the difference A − B of the same triangle meshes
through wingedge, manifold3d, MeshLib and CGAL's corefinement.

    python3 -m venv /tmp/bb && /tmp/bb/bin/pip install manifold3d meshlib cgal numpy
    cargo build --release -p wingedge -p wingedge-bench --bin wingedge --bin boolean_bench
    /tmp/bb/bin/python benches/peers/booleans.py [--rounds 3] [--cases spheres,models]

Operands (written once to --workdir, default /tmp/wingedge-booleans):

- `spheres-131k`, `spheres-524k`: manifold3d's `Manifold.sphere(1, n)`
  (n = 512 and 1024 segments: 131,072 and 524,288 triangles) minus the
  same sphere moved by (0.3, 0.2, 0.1).
- one pair per model of ../shared/models/ (--models): the model, fanned
  into triangles, minus itself turned 3° about an oblique axis through its
  box centre and moved by 1% of its box diagonal. A model that
  `wingedge validate` does not call a valid closed solid is skipped, and
  the table says so.

Every coordinate is rounded to `f32` before it is written (MeshLib and
manifold3d's `Mesh` hold `f32`), so every tool reads the same triangles:
OBJ for wingedge, manifold3d and MeshLib, OFF with the same numbers for
CGAL. Each operand file is checked with `wingedge validate` after rounding.

Each measurement is its own process, so its peak resident memory is its
own: the child reports its `VmHWM` just after the boolean, before it
writes its result (`ru_maxrss` from `wait4` is the
fallback for a child that dies; it is not used otherwise because Linux
carries the parent's high-water mark into a vfork-and-exec child); it reads the operands (untimed),
times one difference, and writes the result (untimed). Tools alternate
within a round; each tool's time is the best of --rounds, its memory the
largest peak. Each result file is then checked with `wingedge validate`
(closed, oriented, manifold, no self-intersection, exact). A tool that
cannot be imported, refuses an operand, crashes or times out gets a row
that says so.

wingedge runs `benches/drivers/src/bin/boolean_bench.rs` with RAYON_NUM_THREADS=2; the
peers' thread pools are capped at 2 where they read an environment
variable (the benchmark machine has 2 cores).
"""

import argparse
import json
import math
import os
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
TOOLS = ["wingedge", "manifold3d", "meshlib", "cgal"]
THREADS = "2"


# ---------------------------------------------------------------- operands


def read_obj_triangles(path):
    """Positions (float64) and triangles (polygons fanned) of an OBJ file."""
    verts, tris = [], []
    with open(path) as f:
        for line in f:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "v":
                verts.append([float(x) for x in parts[1:4]])
            elif parts[0] == "f":
                idx = []
                for c in parts[1:]:
                    i = int(c.split("/")[0])
                    idx.append(i - 1 if i > 0 else len(verts) + i)
                for k in range(1, len(idx) - 1):
                    tris.append([idx[0], idx[k], idx[k + 1]])
    return np.array(verts, dtype=np.float64), np.array(tris, dtype=np.int64)


def read_off_triangles(path):
    """Positions and triangles (polygons fanned) of an OFF file."""
    with open(path) as f:
        tokens = [ln.split("#")[0] for ln in f]
    words = " ".join(tokens).split()
    assert words[0] == "OFF", path
    nv, nf = int(words[1]), int(words[2])
    at = 4
    verts = np.array(words[at : at + 3 * nv], dtype=np.float64).reshape(nv, 3)
    at += 3 * nv
    tris = []
    for _ in range(nf):
        k = int(words[at])
        idx = [int(w) for w in words[at + 1 : at + 1 + k]]
        at += 1 + k
        for j in range(1, k - 1):
            tris.append([idx[0], idx[j], idx[j + 1]])
    return verts, np.array(tris, dtype=np.int64).reshape(-1, 3)


def as_f32(verts):
    """Coordinates rounded to f32, held as the f64 values they are."""
    return verts.astype(np.float32).astype(np.float64)


def write_obj(path, verts, tris):
    with open(path, "w") as f:
        f.write("".join(f"v {x!r} {y!r} {z!r}\n" for x, y, z in verts.tolist()))
        f.write("".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in tris.tolist()))


def write_off(path, verts, tris):
    with open(path, "w") as f:
        f.write(f"OFF\n{len(verts)} {len(tris)} 0\n")
        f.write("".join(f"{x!r} {y!r} {z!r}\n" for x, y, z in verts.tolist()))
        f.write("".join(f"3 {a} {b} {c}\n" for a, b, c in tris.tolist()))


def rotation(axis, degrees):
    axis = np.asarray(axis, dtype=np.float64)
    axis /= np.linalg.norm(axis)
    t = math.radians(degrees)
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + math.sin(t) * k + (1 - math.cos(t)) * (k @ k)


def validate(wingedge_bin, obj):
    """`wingedge validate --json`: (valid, short reason)."""
    p = subprocess.run([wingedge_bin, "validate", "--json", obj], capture_output=True, text=True)
    if p.returncode == 0:
        return True, "valid"
    try:
        doc = json.loads(p.stdout)
        if isinstance(doc, list):
            doc = doc[0]
        return False, summarize_report(doc)
    except (json.JSONDecodeError, IndexError, KeyError, TypeError):
        return False, (p.stderr or p.stdout).strip().splitlines()[-1][:120] if (p.stderr or p.stdout).strip() else f"exit {p.returncode}"


def summarize_report(doc):
    """The verdict and the rules with violations, from a validate report."""
    bad = [f"{rule} ×{n}" for rule, n in sorted(doc.get("counts", {}).items()) if n]
    verdict = doc.get("verdict", "invalid")
    return f"{verdict}: " + ", ".join(bad[:3]) if bad else verdict


def make_cases(args):
    os.makedirs(args.workdir, exist_ok=True)
    cases, skipped = [], []
    wanted = set(args.cases.split(","))
    if "spheres" in wanted:
        import manifold3d as m3d

        for n, name in [(512, "spheres-131k"), (1024, "spheres-524k")]:
            mesh = m3d.Manifold.sphere(1.0, n).to_mesh()
            verts = np.asarray(mesh.vert_properties, dtype=np.float64)[:, :3]
            tris = np.asarray(mesh.tri_verts, dtype=np.int64)
            cases.append((name, as_f32(verts), tris, as_f32(verts + [0.3, 0.2, 0.1]), tris))
    if "models" in wanted:
        for model in sorted(os.listdir(args.models)):
            if not model.endswith(".obj"):
                continue
            path = os.path.join(args.models, model)
            ok, why = validate(args.wingedge, path)
            if not ok:
                skipped.append((model, why))
                continue
            verts, tris = read_obj_triangles(path)
            lo, hi = verts.min(axis=0), verts.max(axis=0)
            centre, diagonal = (lo + hi) / 2, np.linalg.norm(hi - lo)
            turned = (verts - centre) @ rotation([1, 2, 3], 3.0).T + centre
            moved = turned + 0.01 * diagonal * np.array([1, 1, 1]) / math.sqrt(3)
            cases.append((model[:-4], as_f32(verts), tris, as_f32(moved), tris))
    ready = []
    for name, va, ta, vb, tb in cases:
        files = {}
        for side, v, t in (("a", va, ta), ("b", vb, tb)):
            obj = os.path.join(args.workdir, f"{name}.{side}.obj")
            off = os.path.join(args.workdir, f"{name}.{side}.off")
            write_obj(obj, v, t)
            write_off(off, v, t)
            np.save(obj[:-4] + ".v.npy", v)
            np.save(obj[:-4] + ".t.npy", t.astype(np.uint64))
            files[side] = (obj, off)
        checks = [validate(args.wingedge, files[s][0]) for s in "ab"]
        bad = [f"{s}: {why}" for s, (ok, why) in zip("AB", checks) if not ok]
        if bad:
            skipped.append((name, "after rounding to f32, " + "; ".join(bad)))
            continue
        ready.append({"name": name, "triangles": [len(ta), len(tb)], "files": files})
    return ready, skipped


# ---------------------------------------------------------------- children


def child(tool, a_obj, a_off, b_obj, b_off, out):
    """One difference in this process; prints one JSON line."""
    if tool == "manifold3d":
        import manifold3d as m3d

        def load(path):
            # The OBJ's numbers, saved by make_cases: no parsing in this process.
            v, t = np.load(path[:-4] + ".v.npy"), np.load(path[:-4] + ".t.npy")
            mesh = m3d.Mesh64(vert_properties=v, tri_verts=t)
            solid = m3d.Manifold(mesh)
            if solid.status() != m3d.Error.NoError:
                raise RuntimeError(f"{os.path.basename(path)} refused: {solid.status()}")
            return solid

        a, b = load(a_obj), load(b_obj)
        clock = time.perf_counter()
        r = a - b
        triangles = r.num_tri()  # forces the lazy CSG tree
        seconds = time.perf_counter() - clock
        peak = peak_rss_mib()
        if r.status() != m3d.Error.NoError:
            raise RuntimeError(f"result status {r.status()}")
        mesh = r.to_mesh64()
        write_obj(out, np.asarray(mesh.vert_properties)[:, :3], np.asarray(mesh.tri_verts))
    elif tool == "meshlib":
        from meshlib import mrmeshpy as mr

        a, b = mr.loadMesh(a_obj), mr.loadMesh(b_obj)
        clock = time.perf_counter()
        r = mr.boolean(a, b, mr.BooleanOperation.DifferenceAB)
        seconds = time.perf_counter() - clock
        peak = peak_rss_mib()
        if not r.valid():
            raise RuntimeError(f"boolean failed: {r.errorString}")
        triangles = r.mesh.topology.numValidFaces()
        mr.saveMesh(r.mesh, out)
    elif tool == "cgal":
        from CGAL.CGAL_Polygon_mesh_processing import corefine_and_compute_difference
        from CGAL.CGAL_Polyhedron_3 import Polyhedron_3

        a, b, r = Polyhedron_3(a_off), Polyhedron_3(b_off), Polyhedron_3()
        if a.size_of_facets() == 0 or b.size_of_facets() == 0:
            raise RuntimeError("an operand read as empty")
        clock = time.perf_counter()
        done = corefine_and_compute_difference(a, b, r)
        seconds = time.perf_counter() - clock
        peak = peak_rss_mib()
        if done is False:
            raise RuntimeError("corefine_and_compute_difference returned false")
        triangles = r.size_of_facets()
        off = out[:-4] + ".off"
        r.write_to_file(off)  # the faces; its coordinates have 6 digits only
        _, t = read_off_triangles(off)
        os.remove(off)
        v = np.array([(q.x(), q.y(), q.z()) for q in r.points()], dtype=np.float64)
        write_obj(out, v, t)
    else:
        raise ValueError(tool)
    print(json.dumps({"tool": tool, "seconds": seconds, "reported_triangles": int(triangles), "peak_rss_mib": peak}))


def peak_rss_mib():
    """This process's peak resident memory (VmHWM), MiB."""
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) / 1024
    return None


def measure(args, tool, case, round_index):
    """Runs one child process; returns its JSON (or an error) and peak MiB."""
    a_obj, a_off = case["files"]["a"]
    b_obj, b_off = case["files"]["b"]
    out = os.path.join(args.workdir, f"{case['name']}.{tool}.r{round_index}.obj")
    env = dict(os.environ, RAYON_NUM_THREADS=THREADS, OMP_NUM_THREADS=THREADS, TBB_NUM_THREADS=THREADS)
    if tool == "wingedge":
        cmd = [args.driver, a_obj, b_obj, "1", out]
    else:
        cmd = [sys.executable, os.path.abspath(__file__), "--child", tool, a_obj, a_off, b_obj, b_off, out]
    with open(os.path.join(args.workdir, "child.err"), "w+") as err:
        p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=err, env=env, text=True)
        deadline = time.time() + args.timeout
        while True:
            pid, status, usage = os.wait4(p.pid, os.WNOHANG)
            if pid:
                break
            if time.time() > deadline:
                p.kill()
                _, status, usage = os.wait4(p.pid, 0)
                p.returncode = -9
                return {"error": f"timed out after {args.timeout} s"}, usage.ru_maxrss / 1024
            time.sleep(0.02)
        p.returncode = os.waitstatus_to_exitcode(status)
        text = p.stdout.read()
        err.seek(0)
        stderr = err.read().strip()
    peak = usage.ru_maxrss / 1024
    lines = [ln for ln in text.splitlines() if ln.startswith("{")]
    if p.returncode != 0 or not lines:
        last = stderr.splitlines()[-1] if stderr else ""
        return {"error": f"exit {p.returncode}: {last[:160]}"}, peak
    result = json.loads(lines[-1])
    result["out"] = out
    return result, result.get("peak_rss_mib") or peak


def run(args):
    cases, skipped = make_cases(args)
    rows = []
    for case in cases:
        best = {t: None for t in TOOLS}
        peaks = {t: 0.0 for t in TOOLS}
        errors = {t: None for t in TOOLS}
        for r in range(args.rounds):
            for tool in TOOLS:
                if errors[tool] is not None:
                    continue
                result, peak = measure(args, tool, case, r)
                peaks[tool] = max(peaks[tool], peak)
                print(f"# {case['name']} {tool} round {r + 1}: "
                      + (f"{result['seconds'] * 1e3:.0f} ms" if "error" not in result else result["error"])
                      + f", {peak:.0f} MiB", file=sys.stderr, flush=True)
                if "error" in result:
                    errors[tool] = result["error"]
                elif best[tool] is None or result["seconds"] < best[tool]["seconds"]:
                    if best[tool] is not None:
                        os.remove(best[tool]["out"])
                    best[tool] = result
                else:
                    os.remove(result["out"])
        for tool in TOOLS:
            row = dict(best[tool] or {"error": errors[tool]})
            row.update(case=case["name"], operands=case["triangles"], tool=tool, peak_mib=peaks[tool])
            if best[tool] is not None:
                _, t = read_obj_triangles(best[tool]["out"])
                row["triangles_out"] = len(t)
                row["valid"], row["verdict"] = validate(args.wingedge, best[tool]["out"])
            rows.append(row)
    return rows, skipped


# ---------------------------------------------------------------- table


def table(rows, skipped):
    out = []
    out.append("| case | triangles A + B | tool | ms | × manifold3d | peak MiB | result triangles | closed manifold (wingedge validate) |")
    out.append("|---|---:|---|---:|---:|---:|---:|---|")
    by_case = {}
    for row in rows:
        by_case.setdefault(row["case"], {})[row["tool"]] = row
    for name, tools in by_case.items():
        ref = tools.get("manifold3d", {}).get("seconds")
        for tool in TOOLS:
            row = tools[tool]
            tri = " + ".join(f"{n:,}" for n in row["operands"])
            if "error" in row:
                out.append(f"| {name} | {tri} | {tool} | failed: {row['error']} | | {row['peak_mib']:.0f} | | |")
                continue
            ms = row["seconds"] * 1e3
            ratio = f"{row['seconds'] / ref:.2f}" if ref else "n/a"
            verdict = "yes" if row["valid"] else f"no ({row['verdict']})"
            out.append(f"| {name} | {tri} | {tool} | {ms:,.0f} | {ratio} | {row['peak_mib']:.0f} | {row['triangles_out']:,} | {verdict} |")
    stages = ["prepare", "intersect", "points", "split", "classify", "output", "proof"]
    out.append("")
    out.append("wingedge's time by stage, ms (share of the boolean):")
    out.append("")
    out.append("| case | " + " | ".join(stages) + " | contacts | cut triangles |")
    out.append("|---|" + "---:|" * (len(stages) + 2))
    for row in rows:
        if row["tool"] != "wingedge" or "error" in row:
            continue
        s = row["stages"]
        cells = [f"{s[k] * 1e3:,.0f} ({100 * s[k] / row['seconds']:.0f}%)" for k in stages]
        out.append(f"| {row['case']} | " + " | ".join(cells) + f" | {row['contacts']:,} | {row['cut_triangles']:,} |")
    if skipped:
        out.append("")
        for name, why in skipped:
            out.append(f"- skipped {name}: {why}")
    return "\n".join(out)


IMPORTS = {
    "manifold3d": "import manifold3d",
    "meshlib": "from meshlib import mrmeshpy",
    "cgal": "from CGAL import CGAL_Polygon_mesh_processing, CGAL_Polyhedron_3",
}


def import_baselines():
    """Peak MiB of a Python process that only imports numpy and each peer."""
    found = {}
    for tool, statement in IMPORTS.items():
        code = f"import numpy; {statement}\n" + "print(next(int(l.split()[1]) for l in open('/proc/self/status') if l.startswith('VmHWM:')) / 1024)"
        p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
        found[tool] = float(p.stdout) if p.returncode == 0 else None
    return found


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "--child":
        child(*sys.argv[2:8])
        return
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--cases", default="spheres,models", help="comma list of: spheres, models")
    ap.add_argument("--models", default=os.path.join(os.path.dirname(REPO), "shared", "models"))
    ap.add_argument("--workdir", default="/tmp/wingedge-booleans")
    ap.add_argument("--wingedge", default=os.path.join(REPO, "target", "release", "wingedge"))
    ap.add_argument("--driver", default=os.path.join(REPO, "target", "release", "boolean_bench"))
    ap.add_argument("--timeout", type=float, default=900)
    ap.add_argument("--json", help="also write the rows to this file")
    args = ap.parse_args()
    load_before = os.getloadavg()[0]
    rows, skipped = run(args)
    load_after = os.getloadavg()[0]
    baselines = import_baselines()
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"rows": rows, "skipped": skipped, "import_mib": baselines,
                       "load_average": [load_before, load_after], "cpus": os.cpu_count()}, f, indent=1)
    print(table(rows, skipped))
    print()
    print("A Python peer's peak includes the interpreter and its library; after the imports alone: "
          + ", ".join(f"{t} {m:.0f} MiB" if m else f"{t} n/a" for t, m in baselines.items()) + ".")
    print(f"Load average (1 min) {load_before:.1f} at the start, {load_after:.1f} at the end, on {os.cpu_count()} CPUs.")


if __name__ == "__main__":
    main()
