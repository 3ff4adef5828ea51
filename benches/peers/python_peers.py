"""The Python peers, timed in this process on the shared inputs.

Each function takes the mesh (`f64` vertices, triangle indices) and the
queries and returns a list of results: `{"library", "task", "setup_s",
"seconds", "queries", "answers", ...}`. `setup_s` is the acceleration
structure's build, `seconds` the best query time. Answers: points as a bool
array (inside), rays as an `f64` array of first-hit `t` (`inf` = miss).

Threads: open3d gets `nthreads=2`; libigl's fast winding number runs on
the threads the environment allows (the runner sets `OMP_NUM_THREADS=2`);
trimesh's Embree queries run on one thread.
"""
import time

import numpy as np

import igl
import manifold3d as m3d
import open3d as o3d
import trimesh

THREADS = 2
REPEAT_BELOW_S = 5.0


def best_of_3(f):
    """Best wall time of up to three calls (one if a call takes over 5 s) and the last result."""
    best, out = float("inf"), None
    for _ in range(3):
        start = time.perf_counter()
        out = f()
        best = min(best, time.perf_counter() - start)
        if best > REPEAT_BELOW_S:
            break
    return best, out


def _first_hit_t(origins, directions, ray_index, locations):
    t = np.full(len(origins), np.inf)
    t[ray_index] = np.einsum("ij,ij->i", locations - origins[ray_index], directions[ray_index])
    return t


def trimesh_embree(vertices, triangles, points, rays):
    """trimesh with its Embree intersector: `contains` (ray parity) and `intersects_id` (first hit)."""
    if not trimesh.ray.has_embree:
        raise SystemExit("trimesh cannot find Embree: pip install embreex")
    mesh = trimesh.Trimesh(vertices, triangles, process=False)

    def build():
        intersector = trimesh.ray.ray_pyembree.RayMeshIntersector(mesh)
        intersector.intersects_first(rays[:1, :3], rays[:1, 3:])  # builds the scene
        return intersector

    setup_s, intersector = best_of_3(build)
    mesh.ray = intersector
    origins, directions = np.ascontiguousarray(rays[:, :3]), np.ascontiguousarray(rays[:, 3:])
    points_s, inside = best_of_3(lambda: mesh.contains(points))

    def cast():
        _, ray_index, locations = intersector.intersects_id(
            origins, directions, multiple_hits=False, return_locations=True)
        return _first_hit_t(origins, directions, ray_index, locations)

    rays_s, t = best_of_3(cast)
    common = {"library": "trimesh+Embree", "precision": "f32", "threads": 1,
              "setup_s": setup_s}
    return [dict(common, task="points", seconds=points_s, queries=len(points), answers=np.asarray(inside, bool)),
            dict(common, task="rays", seconds=rays_s, queries=len(rays), answers=t)]


def libigl_fwn(vertices, triangles, points):
    """libigl's fast winding number (its BVH kept between queries); inside when > 1/2."""
    fwn = igl.FastWindingNumberBVH()
    setup_s, _ = best_of_3(lambda: fwn.init(vertices, triangles))
    seconds, w = best_of_3(lambda: fwn.winding_number(points))
    return [{"library": "libigl fast winding number", "precision": "f64, approximate",
             "threads": THREADS, "task": "points", "setup_s": setup_s, "seconds": seconds,
             "queries": len(points), "answers": w > 0.5}]


def open3d_scene(vertices, triangles, points, rays):
    """open3d's RaycastingScene (Embree, `f32`): `compute_occupancy` and `cast_rays`.

    `points` or `rays` may be `None` (a query set of one kind): that task is
    left out of the result.
    """
    v32 = o3d.core.Tensor(vertices.astype(np.float32))
    f32 = o3d.core.Tensor(triangles.astype(np.uint32))
    probe = o3d.core.Tensor(vertices[:1].astype(np.float32))

    def build():
        scene = o3d.t.geometry.RaycastingScene(nthreads=THREADS)
        scene.add_triangles(v32, f32)
        scene.compute_occupancy(probe, nthreads=THREADS)  # commits the scene
        return scene

    setup_s, scene = best_of_3(build)
    common = {"library": "open3d RaycastingScene", "precision": "f32", "threads": THREADS, "setup_s": setup_s}
    rows = []
    if points is not None:
        p32 = o3d.core.Tensor(points.astype(np.float32))
        points_s, occupancy = best_of_3(lambda: scene.compute_occupancy(p32, nthreads=THREADS).numpy())
        rows.append(dict(common, task="points", seconds=points_s, queries=len(points), answers=occupancy > 0.5))
    if rays is not None:
        r32 = o3d.core.Tensor(rays.astype(np.float32))
        rays_s, t = best_of_3(lambda: scene.cast_rays(r32, nthreads=THREADS)["t_hit"].numpy())
        rows.append(dict(common, task="rays", seconds=rays_s, queries=len(rays), answers=t.astype(np.float64)))
    return rows


def manifold3d_rays(vertices, triangles, rays, budget_s):
    """manifold3d's `ray_cast` (a segment query), on the first rays that fit in `budget_s`.

    Its cost grows with the segment's bounding box, so random rays through a
    large mesh are slow: only a prefix of the set is cast, one at a time.
    """
    mesh = m3d.Mesh64(vert_properties=np.ascontiguousarray(vertices),
                      tri_verts=np.ascontiguousarray(triangles, dtype=np.uint64))
    start = time.perf_counter()
    solid = m3d.Manifold(mesh)
    solid.num_tri()
    setup_s = time.perf_counter() - start
    length = 4.0 * float(np.linalg.norm(vertices.max(0) - vertices.min(0))) + float(
        np.abs(rays[:, :3]).max())
    t = []
    start = time.perf_counter()
    while len(t) < len(rays) and (time.perf_counter() - start < budget_s or len(t) < 10):
        o, d = rays[len(t), :3], rays[len(t), 3:]
        hits = solid.ray_cast(o, o + length * d)
        t.append(hits[0].distance * length if hits else np.inf)
    seconds = time.perf_counter() - start
    return [{"library": "manifold3d ray_cast", "precision": "f64", "threads": 1, "task": "rays",
             "setup_s": setup_s, "seconds": seconds, "queries": len(t), "answers": np.array(t)}]
