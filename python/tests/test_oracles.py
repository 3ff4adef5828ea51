"""Agreement with manifold3d (volume, genus, manifold status) and trimesh
(containment of points away from the surface) on seeded meshes.

Both packages are test requirements (python/tests/requirements.txt): a
missing one fails the import, it is never skipped.
"""

import manifold3d as m3d
import numpy as np
import pytest
import trimesh

import wingedge


def _seeded_manifolds():
    """Spheres, cubes, cylinders and a drilled block (genus 1 and 3), at
    seeded rotations and offsets."""
    rng = np.random.default_rng(7)
    out = []
    for k in range(6):
        base = [
            m3d.Manifold.sphere(1.0, 24 + 8 * k),
            m3d.Manifold.cube([1.0 + k, 2.0, 0.5], center=True),
            m3d.Manifold.cylinder(2.0, 0.7, 0.7, 16 + 4 * k, center=True),
        ][k % 3]
        angles = rng.uniform(0, 360, size=3)
        out.append(base.rotate(list(angles)).translate(list(rng.uniform(-5, 5, size=3))))
    block = m3d.Manifold.cube([4.0, 4.0, 1.0], center=True)
    drill = m3d.Manifold.cylinder(3.0, 0.4, 0.4, 24, center=True)
    out.append(block - drill)  # genus 1
    out.append(block - drill.translate([1.2, 0, 0]) - drill.translate([-1.2, 0, 0]) - drill)
    return out


@pytest.mark.parametrize("index", range(8))
def test_volume_genus_and_status_agree_with_manifold3d(index):
    m = _seeded_manifolds()[index]
    assert m.status() == m3d.Error.NoError
    solid = wingedge.Solid.from_manifold(m)
    report = wingedge.validate(solid)
    assert report.valid, report.violations[:3]
    assert solid.volume == pytest.approx(m.volume(), rel=1e-9)
    assert solid.genus == m.genus()
    assert solid.area == pytest.approx(m.surface_area(), rel=1e-9)


def test_contains_agrees_with_trimesh_off_the_surface():
    rng = np.random.default_rng(11)
    m = _seeded_manifolds()[7]
    mesh = m.to_mesh64()
    tm = trimesh.Trimesh(
        np.asarray(mesh.vert_properties)[:, :3], np.asarray(mesh.tri_verts), process=False
    )
    solid = wingedge.Solid.from_trimesh(tm)
    lo, hi = tm.bounds
    pts = rng.uniform(lo - 0.2, hi + 0.2, size=(4000, 3))
    # Keep points clearly away from the surface, where a float ray test is
    # reliable: trimesh's own closest-point distance.
    _, dist, _ = trimesh.proximity.closest_point(tm, pts)
    pts = pts[dist > 1e-3 * np.linalg.norm(hi - lo)]
    ours = solid.contains(pts)
    theirs = tm.contains(pts)
    assert len(pts) > 3000
    assert np.array_equal(ours, theirs), np.flatnonzero(ours != theirs)[:10]
    assert 0 < ours.sum() < len(pts)


@pytest.mark.parametrize("name", ["cube", "dodecahedron", "prism"])
def test_polygon_faces_reach_trimesh_and_manifold3d_as_exact_triangulations(name):
    solid = wingedge.builtin(name)
    vertices, triangles = solid.triangles()
    corners = sum(len(f) for f in solid.to_arrays()[1])
    # A face of k corners becomes k - 2 triangles, on the solid's own vertices.
    assert len(triangles) == corners - 2 * solid.face_count
    np.testing.assert_array_equal(vertices, solid.to_arrays()[0])

    mesh = solid.to_trimesh()
    assert mesh.is_watertight and mesh.is_winding_consistent
    assert mesh.volume == pytest.approx(solid.volume, rel=1e-12)
    assert mesh.area == pytest.approx(solid.area, rel=1e-12)

    manifold = solid.to_manifold()
    assert manifold.status() == m3d.Error.NoError
    assert manifold.volume() == pytest.approx(solid.volume, rel=1e-12)
    assert manifold.genus() == solid.genus
    back = wingedge.Solid.from_manifold(manifold)
    assert back.volume == pytest.approx(solid.volume, rel=1e-12)


def test_a_non_planar_face_is_refused_by_name():
    vertices = [[0, 0, 0], [1, 0, 0], [1, 1, 0.5], [0, 1, 0], [0.5, 0.5, 1]]
    faces = [[3, 2, 1, 0], [0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]]
    solid = wingedge.Solid.from_arrays(vertices, faces)
    # A bent quadrilateral still has a triangulation in its projection; the
    # refusal is for faces whose projection is not a simple polygon.
    assert len(solid.triangles()[1]) == 6
    bowtie = [[0, 0, 0], [1, 1, 0], [1, 0, 0], [0, 1, 0], [0.5, 0.5, 1]]
    solid = wingedge.Solid.from_arrays(bowtie, faces)
    with pytest.raises(wingedge.ValidationError, match="face 0"):
        solid.triangles()
