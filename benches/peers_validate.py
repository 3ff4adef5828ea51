#!/usr/bin/env python3
"""wingedge validate vs trimesh load + manifold3d construction, one run.

For each OBJ file given, alternately (so both see the same machine load):

  * wingedge: `target/release/examples/validate_bench FILE 1` in a fresh
    process: import (tobj + line pass + weld), build the winged-edge solid and
    run every check (self-intersection included); the process's peak RSS.
  * peers: a fresh Python process doing `trimesh.load(FILE, process=False,
    force="mesh")` then `manifold3d.Manifold(Mesh64(...))` with `status()`
    (as ../shared/peers/bench_peers.py does); its peak RSS.

Reports the best of REPEATS for each, and the ratio.

    cargo build --release --example validate_bench
    python3 benches/peers_validate.py [--repeats N] FILE.obj ...
"""
import argparse
import datetime
import json
import os
import platform
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXAMPLE = os.path.join(ROOT, "target", "release", "examples", "validate_bench")

PEER = r'''
import sys, time, json
import numpy as np, trimesh, manifold3d as m3d
path = sys.argv[1]
t0 = time.perf_counter()
mesh = trimesh.load(path, process=False, force="mesh")
t1 = time.perf_counter()
V = np.ascontiguousarray(mesh.vertices, dtype=np.float64)
F = np.ascontiguousarray(mesh.faces, dtype=np.uint64)
man = m3d.Manifold(m3d.Mesh64(vert_properties=V, tri_verts=F))
status = man.status()
n = man.num_tri()
t2 = time.perf_counter()
rss = 0
for line in open("/proc/self/status"):
    if line.startswith("VmHWM:"):
        rss = int(line.split()[1]) / 1024
print(json.dumps({"load": t1 - t0, "manifold": t2 - t1, "total": t2 - t0,
                  "rss_mib": rss, "status": str(status), "tris": int(n),
                  "genus": int(man.genus()), "volume": float(man.volume())}))
'''


def run_wingedge(path):
    out = subprocess.run([EXAMPLE, path, "1"], check=True, capture_output=True, text=True).stdout
    total = float(re.search(r"\| import \+ full validate \| ([0-9.]+) \|", out).group(1))
    imp = float(re.search(r"\| import \(tobj[^|]*\| ([0-9.]+) \|", out).group(1))
    rss = float(re.search(r"peak RSS ([0-9.]+) MiB", out).group(1))
    verdict = out.splitlines()[0]
    return {"total": total, "import": imp, "validate": total - imp, "rss_mib": rss, "summary": verdict}


def run_peer(path):
    out = subprocess.run([sys.executable, "-c", PEER, path], check=True, capture_output=True, text=True).stdout
    return json.loads(out.strip().splitlines()[-1])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("files", nargs="+")
    args = ap.parse_args()
    if not os.path.exists(EXAMPLE):
        sys.exit("build first: cargo build --release --example validate_bench")
    print("# wingedge validate vs trimesh + manifold3d, %s UTC, %s, nproc %d, load %s" % (
        datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M"),
        platform.processor() or platform.machine(), os.cpu_count(),
        " ".join("%.2f" % x for x in os.getloadavg())))
    print()
    print("| file | wingedge import+build+validate s | of which import s | peak RSS MiB | trimesh.load s | manifold3d s | peers total s | peers peak RSS MiB | ratio (peers / wingedge) |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for path in args.files:
        w_best, p_best = None, None
        for _ in range(args.repeats):
            w = run_wingedge(path)
            p = run_peer(path)
            if w_best is None or w["total"] < w_best["total"]:
                w_best = w
            if p_best is None or p["total"] < p_best["total"]:
                p_best = p
        print("| %s | %.3f | %.3f | %.0f | %.3f | %.3f | %.3f | %.0f | %.2f |" % (
            os.path.basename(path), w_best["total"], w_best["import"], w_best["rss_mib"],
            p_best["load"], p_best["manifold"], p_best["total"], p_best["rss_mib"],
            p_best["total"] / w_best["total"]))
        print("<!-- wingedge: %s; manifold3d: status %s, %d tris, genus %d, volume %.6f -->" % (
            w_best["summary"], p_best["status"], p_best["tris"], p_best["genus"], p_best["volume"]), file=sys.stderr)


if __name__ == "__main__":
    main()
