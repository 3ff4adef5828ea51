"""The meshes, points and rays every library in the peer comparison answers.

Each mesh is made with manifold3d (or built here, or read from one of the
team's real models, and accepted by manifold3d as a closed 2-manifold) and
written as an OBJ with every coordinate printed
to 17 significant digits, so the file holds exactly the `f64` vertices the
Python peers see in memory. Next to `<name>.obj` go:

    <name>.points.f64   N x 3 little-endian f64: uniform in the mesh's box
    <name>.rays.f64     N x 6 little-endian f64: origin on a sphere around
                        the box (1.5 x its half-diagonal), unit direction
                        towards a uniform point in the box
    <name>.json         how it was made (recipe, seed, counts, volume)

and, for the harder query sets (`SETS`), `<name>.<set>.points.f64` or
`<name>.<set>.rays.f64` in the same layouts:

    near1e-3, near1e-6  points at 1e-3 (1e-6) of the box diagonal from a
                        surface point (a uniform point of a triangle picked
                        by area), in a uniform random direction
    inside              rays from uniform points in the box, in uniform
                        random directions (many start inside the solid)
    vertices            rays from the sphere around the box, aimed at a
                        random vertex of the mesh
    grazing             rays along a triangle's plane: through a uniform
                        point of a random triangle, in a direction that is a
                        random combination of two of its edges (in the plane
                        up to rounding), starting a box diagonal back

Everything is seeded; a directory whose `<name>.json` already describes the
same recipe and query count is reused as is.
"""
import json
import os
import zlib

import numpy as np
import manifold3d as m3d

RECIPES = {
    "sphere_80k": "manifold3d Manifold.sphere(1, circular_segments=400): 80,000 triangles",
    "torus_knot": "(2,3) torus-knot tube, radius 0.14 around the curve with R=1, a=0.42; "
                  "2,000 x 50 quads split in two: 200,000 triangles",
    "sphere_1m": "manifold3d Manifold.sphere(1, circular_segments=1416): 1,002,528 triangles",
    "csg_diff": "manifold3d cube(2) - sphere(0.7, 128 segments, at (0,0,1)) - cylinder along x "
                "(r 0.4, 128 segments): a CAD-like part with long thin fan triangles, genus 2",
    "fandisk": "the team's real model fandisk.obj (a CAD part, 12,946 triangles), as read",
    "spot": "the team's real model spot.obj (a scanned-and-remeshed cow, 5,856 triangles), as read",
    "spot_x4": "spot.obj with every triangle split in four at its edge midpoints (exact in f64): "
               "23,424 triangles",
    "fandisk_x2": "fandisk.obj with triangles paired greedily across a shared edge (in file order) and "
                  "each pair split in four at that edge's midpoint (exact in f64): 25,498 triangles",
}

# The query sets beyond the uniform points and sphere rays: name -> task.
SETS = {"near1e-3": "points", "near1e-6": "points", "inside": "rays", "vertices": "rays", "grazing": "rays"}

# The team's real-world models (not part of the repository: the comparison
# reads them from the shared folder next to it when they are asked for).
MODELS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "shared", "models")


def read_obj(path):
    """The vertices (`f64`) and triangles (0-based) of an OBJ's `v` and `f`
    lines: polygons split into fans, texture and normal indices ignored,
    negative indices counted back from the last vertex read."""
    vertices, triangles = [], []
    with open(path) as f:
        for line in f:
            fields = line.split()
            if fields[:1] == ["v"]:
                vertices.append([float(x) for x in fields[1:4]])
            elif fields[:1] == ["f"]:
                corners = [int(c.split("/")[0]) for c in fields[1:]]
                corners = [c - 1 if c > 0 else len(vertices) + c for c in corners]
                triangles += [[corners[0], corners[k], corners[k + 1]] for k in range(1, len(corners) - 1)]
    return np.array(vertices, dtype=np.float64).reshape(-1, 3), np.array(triangles, dtype=np.int64).reshape(-1, 3)


def _model(name):
    """A real model as read from its OBJ, accepted by manifold3d."""
    path = os.path.join(MODELS, name + ".obj")
    if not os.path.exists(path):
        raise SystemExit("%s: not found (the real models live in the team's shared folder)" % path)
    vertices, triangles = read_obj(path)
    mesh = m3d.Mesh64(vert_properties=np.ascontiguousarray(vertices),
                      tri_verts=np.ascontiguousarray(triangles, dtype=np.uint64))
    return m3d.Manifold(mesh)


def _manifold(vertices, triangles):
    mesh = m3d.Mesh64(vert_properties=np.ascontiguousarray(vertices),
                      tri_verts=np.ascontiguousarray(triangles, dtype=np.uint64))
    return m3d.Manifold(mesh)


def _split_in_four(name):
    """A real model with every triangle split in four at its edge midpoints.

    `(a + b) / 2` is exact in `f64`, so the surface is the same point set and
    a closed solid stays closed, with the same volume.
    """
    vertices, triangles = read_obj(os.path.join(MODELS, name + ".obj"))
    vertices = list(map(tuple, vertices.tolist()))
    midpoint = {}

    def mid(a, b):
        key = (min(a, b), max(a, b))
        if key not in midpoint:
            vertices.append(tuple((x + y) / 2 for x, y in zip(vertices[a], vertices[b])))
            midpoint[key] = len(vertices) - 1
        return midpoint[key]

    out = []
    for a, b, c in triangles.tolist():
        ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
        out += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
    return _manifold(np.array(vertices), np.array(out))


def _split_pairs(name):
    """A real model with about twice its triangles: triangles are paired
    greedily (in file order, each with its first unpaired neighbour across
    an edge) and each pair's shared edge is split at its exact midpoint,
    which splits both triangles in two. Unpaired triangles stay as they
    are; no other edge is touched, so the mesh stays conforming and closed."""
    vertices, triangles = read_obj(os.path.join(MODELS, name + ".obj"))
    vertices = list(map(tuple, vertices.tolist()))
    triangles = triangles.tolist()
    by_edge = {}
    for k, tri in enumerate(triangles):
        for i in range(3):
            by_edge.setdefault(frozenset((tri[i], tri[(i + 1) % 3])), []).append(k)
    partner = {}
    for k, tri in enumerate(triangles):
        if k in partner:
            continue
        for i in range(3):
            edge = frozenset((tri[i], tri[(i + 1) % 3]))
            other = [j for j in by_edge[edge] if j != k and j not in partner]
            if other:
                partner[k], partner[other[0]] = edge, edge
                break
    out, midpoint = [], {}
    for k, (a, b, c) in enumerate(triangles):
        edge = partner.get(k)
        if edge is None:
            out.append((a, b, c))
            continue
        if edge not in midpoint:
            p, q = tuple(edge)
            vertices.append(tuple((x + y) / 2 for x, y in zip(vertices[p], vertices[q])))
            midpoint[edge] = len(vertices) - 1
        m = midpoint[edge]
        # Rotate the corners so that the split edge runs a -> b.
        while frozenset((a, b)) != edge:
            a, b, c = b, c, a
        out += [(a, m, c), (m, b, c)]
    return _manifold(np.array(vertices), np.array(out))


def _sphere(segments):
    return m3d.Manifold.sphere(1.0, segments)


def _knot_curve(u, R=1.0, a=0.42):
    """The (2,3) torus knot and its derivative at parameters `u`."""
    r = R + a * np.cos(3 * u)
    c = np.stack([r * np.cos(2 * u), r * np.sin(2 * u), a * np.sin(3 * u)], axis=-1)
    dr = -3 * a * np.sin(3 * u)
    dc = np.stack([dr * np.cos(2 * u) - 2 * r * np.sin(2 * u),
                   dr * np.sin(2 * u) + 2 * r * np.cos(2 * u),
                   3 * a * np.cos(3 * u)], axis=-1)
    return c, dc


def _torus_knot(n_u=2000, n_v=50, radius=0.14):
    """A tube around the torus knot, with checks that it does not touch itself."""
    u = np.linspace(0.0, 2 * np.pi, n_u, endpoint=False)
    centre, tangent = _knot_curve(u)
    tangent /= np.linalg.norm(tangent, axis=1, keepdims=True)
    # A smooth periodic frame: the direction from the torus' core circle to
    # the curve, made orthogonal to the tangent.
    core = np.stack([np.cos(2 * u), np.sin(2 * u), np.zeros_like(u)], axis=-1)
    normal = centre - core
    normal -= np.sum(normal * tangent, axis=1, keepdims=True) * tangent
    normal /= np.linalg.norm(normal, axis=1, keepdims=True)
    binormal = np.cross(tangent, normal)
    v = np.linspace(0.0, 2 * np.pi, n_v, endpoint=False)
    ring = np.cos(v)[None, :, None] * normal[:, None, :] + np.sin(v)[None, :, None] * binormal[:, None, :]
    vertices = (centre[:, None, :] + radius * ring).reshape(-1, 3)
    i, j = np.meshgrid(np.arange(n_u), np.arange(n_v), indexing="ij")
    a = i * n_v + j
    b = ((i + 1) % n_u) * n_v + j
    c = ((i + 1) % n_u) * n_v + (j + 1) % n_v
    d = i * n_v + (j + 1) % n_v
    triangles = np.concatenate([np.stack([a, b, c], -1).reshape(-1, 3),
                                np.stack([a, c, d], -1).reshape(-1, 3)])
    if _signed_volume(vertices, triangles) < 0:
        triangles = triangles[:, ::-1]
    # The tube must not touch itself: far-apart stretches of the curve stay
    # more than two radii apart, and the curve bends less than the radius.
    s = np.linspace(0.0, 2 * np.pi, 3000, endpoint=False)
    pts, _ = _knot_curve(s)
    gap = np.abs(s[:, None] - s[None, :])
    gap = np.minimum(gap, 2 * np.pi - gap)
    dist = np.linalg.norm(pts[:, None, :] - pts[None, :, :], axis=-1)
    clearance = dist[gap > 0.5].min()
    _, d1 = _knot_curve(s)
    _, d1b = _knot_curve(s + 1e-5)
    curvature = np.linalg.norm(np.cross(d1, (d1b - d1) / 1e-5), axis=1) / np.linalg.norm(d1, axis=1) ** 3
    if clearance <= 2.2 * radius or 1.0 / curvature.max() <= 1.2 * radius:
        raise RuntimeError("torus knot tube would touch itself: clearance %.3f, min radius of curvature %.3f"
                           % (clearance, 1.0 / curvature.max()))
    mesh = m3d.Mesh64(vert_properties=np.ascontiguousarray(vertices),
                      tri_verts=np.ascontiguousarray(triangles, dtype=np.uint64))
    return m3d.Manifold(mesh)


def _csg_diff():
    cube = m3d.Manifold.cube((2.0, 2.0, 2.0), True)
    dimple = m3d.Manifold.sphere(0.7, 128).translate((0.0, 0.0, 1.0))
    hole = m3d.Manifold.cylinder(3.0, 0.4, -1.0, 128, True).rotate((0.0, 90.0, 0.0))
    return cube - dimple - hole


MAKERS = {
    "sphere_80k": lambda: _sphere(400),
    "torus_knot": _torus_knot,
    "sphere_1m": lambda: _sphere(1416),
    "csg_diff": _csg_diff,
    "fandisk": lambda: _model("fandisk"),
    "spot": lambda: _model("spot"),
    "spot_x4": lambda: _split_in_four("spot"),
    "fandisk_x2": lambda: _split_pairs("fandisk"),
}


def _signed_volume(vertices, triangles):
    a, b, c = (vertices[triangles[:, k]] for k in range(3))
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


def _write_obj(path, vertices, triangles):
    with open(path, "w") as f:
        f.write("# wingedge peer comparison input (benches/peers/inputs.py)\n")
        f.write("".join("v %r %r %r\n" % tuple(v) for v in vertices.tolist()))
        f.write("".join("f %d %d %d\n" % tuple(t) for t in (triangles + 1).tolist()))


def _queries(bmin, bmax, n, seed):
    rng = np.random.default_rng(seed)
    points = bmin + (bmax - bmin) * rng.random((n, 3))
    centre = 0.5 * (bmin + bmax)
    radius = 0.75 * np.linalg.norm(bmax - bmin)
    on_sphere = rng.normal(size=(n, 3))
    on_sphere /= np.linalg.norm(on_sphere, axis=1, keepdims=True)
    origins = centre + radius * on_sphere
    directions = bmin + (bmax - bmin) * rng.random((n, 3)) - origins
    directions /= np.linalg.norm(directions, axis=1, keepdims=True)
    return points, np.hstack([origins, directions])


def _area_weighted_surface_points(vertices, triangles, n, rng):
    a, b, c = (vertices[triangles[:, k]] for k in range(3))
    area = np.linalg.norm(np.cross(b - a, c - a), axis=1)
    pick = rng.choice(len(triangles), size=n, p=area / area.sum())
    u, v = rng.random(n), rng.random(n)
    flip = u + v > 1
    u[flip], v[flip] = 1 - u[flip], 1 - v[flip]
    return a[pick] + u[:, None] * (b[pick] - a[pick]) + v[:, None] * (c[pick] - a[pick])


def _unit_vectors(n, rng):
    d = rng.normal(size=(n, 3))
    return d / np.linalg.norm(d, axis=1, keepdims=True)


def query_set(vertices, triangles, name, n, seed):
    """The `n` queries of the set `name` (see `SETS`) on a mesh, seeded."""
    rng = np.random.default_rng([seed, zlib.crc32(name.encode())])
    bmin, bmax = vertices.min(0), vertices.max(0)
    diagonal = float(np.linalg.norm(bmax - bmin))
    if name.startswith("near"):
        surface = _area_weighted_surface_points(vertices, triangles, n, rng)
        return surface + float(name[len("near"):]) * diagonal * _unit_vectors(n, rng)
    if name == "inside":
        origins = bmin + (bmax - bmin) * rng.random((n, 3))
        return np.hstack([origins, _unit_vectors(n, rng)])
    if name == "vertices":
        origins = 0.5 * (bmin + bmax) + 0.75 * diagonal * _unit_vectors(n, rng)
        directions = vertices[rng.integers(len(vertices), size=n)] - origins
        return np.hstack([origins, directions / np.linalg.norm(directions, axis=1, keepdims=True)])
    if name == "grazing":
        pick = rng.integers(len(triangles), size=n)
        a, b, c = (vertices[triangles[pick, k]] for k in range(3))
        u, v = rng.random(n), rng.random(n)
        flip = u + v > 1
        u[flip], v[flip] = 1 - u[flip], 1 - v[flip]
        through = a + u[:, None] * (b - a) + v[:, None] * (c - a)
        directions = rng.normal(size=(n, 1)) * (b - a) + rng.normal(size=(n, 1)) * (c - a)
        directions /= np.linalg.norm(directions, axis=1, keepdims=True)
        return np.hstack([through - diagonal * directions, directions])
    raise SystemExit("unknown query set %r (known: %s)" % (name, ", ".join(SETS)))


def make_sets(directory, name, n_queries, sets):
    """Writes (or reuses) the query sets `sets` of the mesh `name` already made in `directory`."""
    meta_path = os.path.join(directory, name + ".json")
    with open(meta_path) as f:
        meta = json.load(f)
    made = meta.setdefault("sets", {})
    vertices, triangles = None, None
    for s in sets:
        path = os.path.join(directory, "%s.%s.%s.f64" % (name, s, SETS[s]))
        if made.get(s) == n_queries and os.path.exists(path):
            continue
        if vertices is None:
            vertices, triangles = read_obj(os.path.join(directory, name + ".obj"))
        if os.path.lexists(path):
            os.remove(path)
        query_set(vertices, triangles, s, n_queries, meta["seed"]).astype("<f8").tofile(path)
        made[s] = n_queries
    with open(meta_path, "w") as f:
        json.dump(meta, f, indent=1)
    return meta


def make(directory, name, n_queries):
    """Writes (or reuses) `name`'s mesh, points and rays in `directory`; returns its description."""
    if name not in MAKERS:
        raise SystemExit("unknown mesh %r (known: %s)" % (name, ", ".join(MAKERS)))
    meta_path = os.path.join(directory, name + ".json")
    seed = zlib.crc32(name.encode())
    wanted = {"recipe": RECIPES[name], "seed": seed, "queries": n_queries}
    if os.path.exists(meta_path):
        with open(meta_path) as f:
            meta = json.load(f)
        if all(meta.get(k) == v for k, v in wanted.items()) and all(
                os.path.exists(os.path.join(directory, name + ext)) for ext in (".obj", ".points.f64", ".rays.f64")):
            return meta
    for ext in (".obj", ".points.f64", ".rays.f64", ".json"):
        stale = os.path.join(directory, name + ext)
        if os.path.lexists(stale):
            os.remove(stale)  # never write through a link to someone else's file
    solid = MAKERS[name]()
    if solid.status() != m3d.Error.NoError:
        raise RuntimeError("%s: manifold3d status %s" % (name, solid.status()))
    mesh = solid.to_mesh64()
    vertices = np.asarray(mesh.vert_properties, dtype=np.float64)[:, :3]
    triangles = np.asarray(mesh.tri_verts, dtype=np.int64)
    _write_obj(os.path.join(directory, name + ".obj"), vertices, triangles)
    points, rays = _queries(vertices.min(0), vertices.max(0), n_queries, seed)
    points.astype("<f8").tofile(os.path.join(directory, name + ".points.f64"))
    rays.astype("<f8").tofile(os.path.join(directory, name + ".rays.f64"))
    meta = dict(wanted, triangles=int(solid.num_tri()), vertices=int(solid.num_vert()),
                genus=int(solid.genus()), volume=float(solid.volume()))
    with open(meta_path, "w") as f:
        json.dump(meta, f, indent=1)
    return meta


def link_existing(source, directory, name):
    """Uses `source/<name>.{obj,points.f64,rays.f64}` (made elsewhere) through symbolic links."""
    stale = os.path.join(directory, name + ".json")
    if os.path.exists(stale):
        os.remove(stale)  # the files below are no longer the ones it describes
    for ext in (".obj", ".points.f64", ".rays.f64"):
        src = os.path.join(os.path.abspath(source), name + ext)
        if not os.path.exists(src):
            raise SystemExit("%s is missing" % src)
        dst = os.path.join(directory, name + ext)
        if os.path.lexists(dst):
            os.remove(dst)
        os.symlink(src, dst)
    return {"recipe": "taken from " + os.path.abspath(source)}
