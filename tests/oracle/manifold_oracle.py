#!/usr/bin/env python3
"""manifold3d as wingedge's independent oracle.

Writes, into OUT_DIR, meshes made by manifold3d's own primitives and booleans
(seeded, deterministic) and manifold3d's answers about them:

    OUT_DIR/<name>.obj        v/f lines; coordinates with 17 significant digits
                              (every f64 round-trips exactly)
    OUT_DIR/oracle.json       per mesh: status, genus, volume, counts, and for
                              each seeded ray its manifold3d ray_cast hits;
                              per CSG case: the leaves, the tree as a wingedge
                              scene, and the boolean result mesh

Usage: manifold_oracle.py OUT_DIR [--rays N] [--csg-cases N]

The Rust test tests/it/oracles/manifold.rs runs this script and compares.
"""
import argparse
import json
import os
import sys

try:
    import numpy as np
    import manifold3d as m3d
except ImportError as exc:  # the Rust test turns this into its message
    sys.stderr.write(
        "manifold3d oracle unavailable (%s): install it with\n"
        "    python3 -m pip install numpy manifold3d\n" % exc
    )
    sys.exit(3)

M = m3d.Manifold


def write_obj(path, manifold):
    mesh = manifold.to_mesh64()
    verts = np.asarray(mesh.vert_properties, dtype=np.float64)[:, :3]
    tris = np.asarray(mesh.tri_verts, dtype=np.int64) + 1
    with open(path, "w") as f:
        f.write("# made by manifold3d (tests/oracle/manifold_oracle.py)\n")
        f.write("".join("v %.17g %.17g %.17g\n" % tuple(v) for v in verts.tolist()))
        f.write("".join("f %d %d %d\n" % tuple(t) for t in tris.tolist()))
    return verts


def broken_meshes(manifold):
    """Meshes manifold3d refuses, made by breaking one of its own: removed
    triangles (holes, half a sphere), flipped triangles (inconsistent
    orientation), a fin and a duplicated face (edges of three faces)."""
    mesh = manifold.to_mesh64()
    verts = np.asarray(mesh.vert_properties, dtype=np.float64)[:, :3]
    tris = np.asarray(mesh.tri_verts, dtype=np.int64)
    holed = tris[1:]
    flipped = tris.copy()
    flipped[0] = flipped[0][::-1]
    far = len(tris) // 2
    two_holes = np.delete(tris, [0, far], axis=0)
    # An edge of three faces: a fin on the first triangle's first edge.
    tip = verts[tris[0]].mean(axis=0) * 1.5
    fin_verts = np.vstack([verts, tip])
    fin = np.vstack([tris, [[tris[0][1], tris[0][0], len(verts)]]])
    duplicated = np.vstack([tris, tris[:1]])
    half = tris[: len(tris) // 2]
    many_flipped = tris.copy()
    many_flipped[::7] = many_flipped[::7, ::-1]
    return {
        "b_hole": (verts, holed),
        "b_flipped": (verts, flipped),
        "b_two_holes": (verts, two_holes),
        "b_fin": (fin_verts, fin),
        "b_duplicated_face": (verts, duplicated),
        "b_half_open": (verts, half),
        "b_many_flipped": (verts, many_flipped),
    }


def status_of(verts, tris):
    built = M(m3d.Mesh64(vert_properties=np.array(verts, dtype=np.float64), tri_verts=np.array(tris, dtype=np.uint64)))
    return str(built.status()).split(".")[-1]


def write_raw_obj(path, verts, tris):
    with open(path, "w") as f:
        f.write("# broken on purpose (tests/oracle/manifold_oracle.py)\n")
        f.write("".join("v %.17g %.17g %.17g\n" % tuple(v) for v in verts.tolist()))
        f.write("".join("f %d %d %d\n" % tuple(t) for t in (tris + 1).tolist()))


def read_polygon_obj(path):
    """A minimal OBJ reader for the bundled fixtures: `v` and `f` lines,
    `v/vt/vn` corners, negative indices; bit-identical positions merged (the
    same weld wingedge applies by default)."""
    positions, index_of, remap, faces = [], {}, [], []
    with open(path) as f:
        for line in f:
            words = line.split()
            if not words:
                continue
            if words[0] == "v":
                p = tuple(float(x) for x in words[1:4])
                remap.append(index_of.setdefault(p, len(positions)))
                if remap[-1] == len(positions):
                    positions.append(p)
            elif words[0] == "f":
                corners = [int(w.split("/")[0]) for w in words[1:]]
                faces.append([remap[c - 1 if c > 0 else len(remap) + c] for c in corners])
    return np.array(positions, dtype=np.float64), faces


def triangulated(verts, faces):
    """Triangles of polygon faces (non-convex ones included), by manifold3d's
    own triangulator on each face projected to its dominant axis plane."""
    tris = []
    for face in faces:
        pts = verts[face]
        normal = np.zeros(3)
        for i in range(len(pts)):
            normal += np.cross(pts[i], pts[(i + 1) % len(pts)])
        axis = int(np.argmax(np.abs(normal)))
        keep = [(axis + 1) % 3, (axis + 2) % 3]
        flat = pts[:, keep]
        if normal[axis] < 0:
            flat = flat[:, ::-1]
        for t in m3d.triangulate([np.ascontiguousarray(flat)]):
            tris.append([face[int(i)] for i in t])
    return np.array(tris, dtype=np.uint64)


def fixture_answers(fixtures_dir):
    """manifold3d's status, genus, Euler characteristic and volume for every
    closed bundled fixture (polygons triangulated by manifold3d)."""
    out = {}
    for name in sorted(os.listdir(fixtures_dir)):
        if not name.endswith(".obj"):
            continue
        verts, faces = read_polygon_obj(os.path.join(fixtures_dir, name))
        tris = triangulated(verts, faces)
        built = M(m3d.Mesh64(vert_properties=np.array(verts), tri_verts=tris))
        out[name] = {
            "status": str(built.status()).split(".")[-1],
            "genus": int(built.genus()),
            "volume": float(built.volume()),
            "euler": int(built.num_vert()) - int(built.num_edge()) + int(built.num_tri()),
        }
    return out


def named_meshes(rng):
    """Closed meshes from manifold3d primitives and booleans."""
    cube = M.cube((2.0, 2.0, 2.0), center=True)
    sphere = M.sphere(1.0, 48)
    cylinder = M.cylinder(2.0, 0.7, 0.7, 40, center=True)
    meshes = {
        "m_cube": cube,
        "m_sphere": sphere,
        "m_cylinder": cylinder,
        "m_union": cube + sphere.translate((0.9, 0.7, 0.5)),
        "m_difference": cube - sphere.translate((0.0, 0.0, 1.0)),
        "m_intersection": cube ^ sphere.scale((1.3, 1.3, 1.3)),
        # Two through-holes: genus 2.
        "m_genus2": M.cube((4.0, 2.0, 1.0), center=True)
        - M.cylinder(3.0, 0.5, 0.5, 32, center=True).translate((-1.0, 0.0, 0.0))
        - M.cylinder(3.0, 0.5, 0.5, 32, center=True).translate((1.0, 0.0, 0.0)),
    }
    # Seeded random booleans of spheres, cubes and cylinders.
    for i in range(3):
        a = random_leaf(rng)
        b = random_leaf(rng)
        op = ["union", "difference", "intersection"][i]
        meshes["m_random_%s" % op] = boolean(a, b, op)
    return meshes


def random_leaf(rng):
    kind = rng.integers(0, 4)
    centre = rng.uniform(-0.6, 0.6, 3)
    if kind == 0:
        leaf = M.sphere(float(rng.uniform(0.6, 1.0)), int(rng.integers(16, 40)))
    elif kind == 1:
        size = rng.uniform(0.8, 1.6, 3)
        leaf = M.cube(tuple(size), center=True).rotate(tuple(rng.uniform(0, 90, 3)))
    elif kind == 2:
        r = float(rng.uniform(0.3, 0.7))
        leaf = M.cylinder(float(rng.uniform(1.0, 2.0)), r, r, int(rng.integers(12, 32)), center=True)
        leaf = leaf.rotate(tuple(rng.uniform(0, 90, 3)))
    else:
        # A torus: a circle revolved about the z axis, then turned.
        tube = float(rng.uniform(0.15, 0.3))
        ring = m3d.CrossSection.circle(tube, int(rng.integers(8, 16))).translate((float(rng.uniform(0.5, 0.8)), 0.0))
        leaf = ring.revolve(int(rng.integers(16, 32))).rotate(tuple(rng.uniform(0, 90, 3)))
    return leaf.translate(tuple(centre))


def boolean(a, b, op):
    return {"union": a + b, "difference": a - b, "intersection": a ^ b}[op]


def seeded_rays(rng, verts, n):
    """Origins on a sphere around the mesh, directions towards random points in
    its bounding box; a tenth of the rays aim exactly at vertices."""
    lo, hi = verts.min(axis=0), verts.max(axis=0)
    centre = (lo + hi) / 2
    radius = 1.5 * np.linalg.norm(hi - lo) / 2
    u = rng.normal(size=(n, 3))
    origins = centre + radius * u / np.linalg.norm(u, axis=1, keepdims=True)
    targets = rng.uniform(lo, hi, size=(n, 3))
    k = n // 10
    targets[:k] = verts[rng.integers(0, len(verts), k)]
    dirs = targets - origins
    return origins, dirs


def ray_hits(manifold, origins, dirs, length):
    """t values (in units of the direction) of every crossing manifold3d
    reports along the segment origin .. origin + length * dir."""
    out = []
    for o, d in zip(origins, dirs):
        end = o + length * d
        hits = manifold.ray_cast(tuple(o), tuple(end))
        out.append([h.distance * length for h in hits])
    return out


def csg_cases(rng, count, out_dir):
    """Seeded random trees of depth >= 3 over manifold3d leaves, written as
    wingedge scenes, with manifold3d's boolean result."""
    cases = []
    for c in range(count):
        leaves = []

        def tree(depth):
            if depth == 0:
                leaf = random_leaf(rng)
                name = "csg%d_leaf%d" % (c, len(leaves))
                write_obj(os.path.join(out_dir, name + ".obj"), leaf)
                leaves.append(name)
                return leaf, {"mesh": name + ".obj"}
            op = ["union", "difference", "intersection"][int(rng.integers(0, 3))]
            a, sa = tree(depth - 1)
            b, sb = tree(depth - 1 if rng.random() < 0.7 else 0)
            return boolean(a, b, op), {op: [sa, sb]}

        result, node = tree(3)
        name = "csg%d_result" % c
        write_obj(os.path.join(out_dir, name + ".obj"), result)
        scene_path = os.path.join(out_dir, "csg%d.scene.json" % c)
        with open(scene_path, "w") as f:
            json.dump({"root": node}, f, indent=1)
        cases.append({
            "scene": os.path.basename(scene_path),
            "result": name + ".obj",
            "volume": float(result.volume()),
            "status": str(result.status()).split(".")[-1],
            "empty": bool(result.is_empty()),
            "genus": int(result.genus()),
            "shells": len(result.decompose()),
        })
    return cases


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("out_dir")
    parser.add_argument("--rays", type=int, default=10000)
    parser.add_argument("--csg-cases", type=int, default=8)
    parser.add_argument("--seed", type=int, default=20261121)
    parser.add_argument("--fixtures", help="a folder of closed OBJ fixtures to judge too")
    parser.add_argument("--nonce", default="", help="written back in oracle.json, so a caller can tell this run's answers")
    args = parser.parse_args()
    os.makedirs(args.out_dir, exist_ok=True)
    rng = np.random.default_rng(args.seed)
    report = {"manifold3d": m3d_version(), "nonce": args.nonce, "meshes": {}, "csg": []}
    for name, manifold in named_meshes(rng).items():
        verts = write_obj(os.path.join(args.out_dir, name + ".obj"), manifold)
        entry = {
            "status": str(manifold.status()).split(".")[-1],
            "genus": int(manifold.genus()),
            "volume": float(manifold.volume()),
            "vertices": int(manifold.num_vert()),
            "edges": int(manifold.num_edge()),
            "faces": int(manifold.num_tri()),
        }
        if args.rays > 0:
            origins, dirs = seeded_rays(rng, verts, args.rays)
            length = 4.0
            entry["rays"] = np.concatenate([origins, dirs], axis=1).tolist()
            entry["hits"] = ray_hits(manifold, origins, dirs, length)
            entry["ray_length"] = length
        report["meshes"][name] = entry
    report["broken"] = {}
    for name, (verts, tris) in broken_meshes(M.sphere(1.0, 24)).items():
        write_raw_obj(os.path.join(args.out_dir, name + ".obj"), verts, tris)
        report["broken"][name] = {"status": status_of(verts, tris)}
    report["csg"] = csg_cases(rng, args.csg_cases, args.out_dir)
    report["revolve"], report["extrude"] = profile_cases()
    if args.fixtures:
        report["fixtures"] = fixture_answers(args.fixtures)
    with open(os.path.join(args.out_dir, "oracle.json"), "w") as f:
        json.dump(report, f)


def profile_cases():
    """manifold3d's revolve and extrude of a few polygons (counter-clockwise,
    in the x >= 0 half-plane for revolve): their volumes, for the same
    tessellation made by wingedge's revolve and sweep."""
    profiles = [
        [[1, 0], [2, 0], [2.5, 1], [1, 1.5]],
        [[0.5, -1], [1.5, -0.5], [1.2, 0.7], [0.4, 1.1], [0.8, 0]],
        [[0, 0], [1, 0], [1, 1], [0, 1]],
    ]
    revolve, extrude = [], []
    for k, profile in enumerate(profiles):
        section = m3d.CrossSection([profile])
        segments = 12 + 20 * k
        revolve.append({
            "profile": profile,
            "segments": segments,
            "volume": float(M.revolve(section, segments).volume()),
        })
        height = 0.5 + k
        extrude.append({
            "profile": profile,
            "height": height,
            "volume": float(M.extrude(section, height).volume()),
        })
    return revolve, extrude


def m3d_version():
    try:
        from importlib.metadata import version
        return version("manifold3d")
    except Exception:
        return "unknown"


if __name__ == "__main__":
    main()
