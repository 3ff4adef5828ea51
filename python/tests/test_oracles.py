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
