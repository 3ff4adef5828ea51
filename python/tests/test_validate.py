"""wingedge.validate: the same content as `wingedge validate --json`."""

import numpy as np
import pytest

import wingedge


def test_valid_fixtures_are_valid_solids_with_their_counts(fixtures):
    cases = {
        "tetrahedron.obj": (4, 6, 4, 0),
        "cube.obj": (8, 12, 6, 0),
        "torus_genus1.obj": (32, 64, 32, 1),
        "double_torus_genus2.obj": (48, 100, 50, 2),
    }
    for name, (v, e, f, genus) in cases.items():
        report = wingedge.validate(fixtures / "valid" / name)
        assert report.valid, name
        assert report.verdict == "valid closed solid"
        assert report.validity == "valid_solid"
        assert (report.vertices, report.edges, report.faces, report.genus) == (v, e, f, genus)
        assert report.violations == []
        assert set(report.counts.values()) == {0}
        assert report.file.endswith(name)
        assert report.weld["mode"] == "exact"
    assert wingedge.validate(fixtures / "valid" / "torus_genus1.obj").volume == pytest.approx(8.0)


def test_each_broken_fixture_reports_its_rule_located(fixtures):
    for path in sorted((fixtures / "broken").glob("*.obj")):
        rule = path.stem
        report = wingedge.validate(path)
        assert not report.valid, rule
        assert report.counts[rule] >= 1, rule
        hits = [v for v in report.violations if v.rule == rule]
        assert hits and all(v.message for v in hits), rule
        assert any(v.line is not None for v in hits), rule


def test_a_solid_validates_like_its_file(fixtures):
    path = fixtures / "valid" / "prism.obj"
    from_file = wingedge.validate(path)
    solid = wingedge.load_obj(path)
    from_solid = wingedge.validate(solid)
    assert from_solid.valid and from_file.valid
    assert from_solid.volume == from_file.volume == pytest.approx(3.0)
    assert from_solid.file == str(path)


def test_a_broken_solid_from_arrays_is_located_by_face():
    # A unit cube whose corner (1, 1, 1) is lifted to z = 1.5: the faces
    # x = 1 and y = 1 stay planar, the top face does not.
    v = np.array([[x, y, z] for z in (0.0, 1.0) for y in (0.0, 1.0) for x in (0.0, 1.0)])
    f = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [3, 2, 6, 7], [0, 4, 6, 2], [1, 3, 7, 5]]
    cube = wingedge.Solid.from_arrays(v, f)
    assert wingedge.validate(cube).valid
    moved = v.copy()
    moved[7] = [1.0, 1.0, 1.5]
    report = wingedge.validate(wingedge.Solid.from_arrays(moved, f))
    assert not report.valid
    assert [(x.rule, x.faces, x.vertices) for x in report.violations] == [
        ("non_planar_face", [1], [4, 5, 7, 6])
    ]
    assert report.violations[0].value == pytest.approx(0.5 / np.sqrt(18), rel=1e-12)


def test_unreadable_files_raise_obj_error_with_the_file(tmp_path):
    missing = tmp_path / "missing.obj"
    with pytest.raises(wingedge.ObjError, match="missing.obj"):
        wingedge.validate(missing)
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n")
    with pytest.raises(wingedge.ObjError, match=r"bad.obj.*:4|line 4"):
        wingedge.load_obj(bad)
    with pytest.raises(ValueError, match="weld"):
        wingedge.validate(missing, weld="sometimes")
    with pytest.raises(ValueError, match="planarity"):
        wingedge.validate(missing, planarity=-1.0)


def test_load_obj_refuses_a_non_manifold_file_but_validate_reports_it(fixtures):
    path = fixtures / "broken" / "edge_in_more_than_two_faces.obj"
    with pytest.raises(wingedge.ValidationError, match="edge_in_more_than_two_faces.obj"):
        wingedge.load_obj(path)
    report = wingedge.validate(path)
    assert report.validity == "not_a_surface"
    assert report.not_built
