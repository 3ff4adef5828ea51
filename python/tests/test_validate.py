"""wingedge.validate: the same content as `wingedge validate --json`."""

import json
import os
import pathlib
import pickle
import subprocess

import numpy as np
import pytest
from conftest import ROOT

import wingedge
from wingedge import _wingedge

# A valid tetrahedron whose volume and area overflow f64 (tests/cli/info.rs).
HUGE_TETRAHEDRON = "v 0 0 0\nv 1e308 0 0\nv 0 1e308 0\nv 0 0 1e308\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"
# A quad with corners 1 and 2 a hair apart and two triangles that would glue
# them together: a weld within 1e-6 refuses (src/io/weld.rs).
REPEATING_WELD = (
    "v 0 0 0\nv 1 0 0\nv 1 1e-7 0\nv 0 1 0\nv 0 0 0\nv 1 1e-7 0\nv 0.5 -1 0\nv 0 1 0\nv 0.5 2 0\n"
    "f 1 2 3 4\nf 6 5 7\nf 8 6 9\n"
)


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


def test_a_report_is_the_native_typed_object_with_the_fixtures_content(fixtures):
    # A square pyramid whose base corner 3 is raised by 0.01: one non-planar
    # face, the base (the first `f`, line 7).
    path = fixtures / "broken" / "non_planar_face.obj"
    report = wingedge.validate(path)
    assert type(report) is _wingedge.Report is wingedge.Report
    assert (report.valid, report.verdict, report.validity) == (
        False,
        "closed oriented surface with defects",
        "closed_oriented_surface",
    )
    assert (report.vertices, report.edges, report.faces, report.shells, report.holes) == (5, 8, 5, 1, 0)
    assert report.genus == 0 and report.not_built is None and report.overflow == []
    assert report.volume == pytest.approx(1 / 3 - 0.01 / 6, rel=1e-12)
    assert {rule for rule, n in report.counts.items() if n} == {"non_planar_face"}
    assert len(report.counts) == 15 and report.counts["non_planar_face"] == 1
    [violation] = report.violations
    assert type(violation) is _wingedge.Violation is wingedge.Violation
    assert (violation.rule, violation.line, violation.lines) == ("non_planar_face", 7, [7])
    assert (violation.faces, violation.vertices) == ([0], [0, 3, 2, 1])
    assert violation.value == pytest.approx(0.0025, rel=1e-4)
    assert "not planar" in violation.message
    [shell] = report.shell_details
    assert shell["closed"] and (shell["faces"], shell["euler_characteristic"], shell["first_line"]) == (5, 2, 7)
    assert report.weld == {"mode": "exact", "merged": 0, "refused": []}
    assert report.file == str(path)
    assert "non_planar_face" in repr(report) and "line=7" in repr(violation)
    with pytest.raises(AttributeError):
        report.valid = True


def test_reports_and_violations_pickle_and_compare_by_value(fixtures, tmp_path):
    huge = tmp_path / "huge.obj"
    huge.write_text(HUGE_TETRAHEDRON)
    for path in (fixtures / "broken" / "duplicate_face.obj", huge):
        report = wingedge.validate(path)
        clone = pickle.loads(pickle.dumps(report))
        assert type(clone) is wingedge.Report and clone == report and clone is not report
        assert clone.to_json() == report.to_json()
        assert clone.violations == report.violations
        assert [pickle.loads(pickle.dumps(v)) for v in report.violations] == report.violations
    assert report != wingedge.validate(fixtures / "valid" / "cube.obj")


def test_measures_that_overflow_are_none_and_named(tmp_path):
    huge = tmp_path / "huge.obj"
    huge.write_text(HUGE_TETRAHEDRON)
    report = wingedge.validate(huge)
    assert report.valid and report.verdict == "valid closed solid"
    assert (report.volume, report.area) == (None, None)
    assert report.overflow == ["volume", "area", "shell volume"]
    assert report.shell_details[0]["volume"] is None


def test_a_refused_weld_is_reported(tmp_path):
    path = tmp_path / "repeat.obj"
    path.write_text(REPEATING_WELD)
    weld = wingedge.validate(path, weld=1e-6).weld
    assert weld["mode"] == "within 0.000001"
    assert [r for r in weld["refused"] if "face 0 (line 10) would visit a vertex twice" in r]


# What a violation in the printed JSON leaves out when it has none.
OPTIONAL_VIOLATION_FIELDS = {"line": None, "lines": [], "vertices": [], "faces": [], "value": None}


def _command_line():
    """The `wingedge` binary that `cargo test` or `cargo build` left (the
    newest), or None."""
    target = pathlib.Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    built = [p for p in (target / "debug" / "wingedge", target / "release" / "wingedge") if p.is_file()]
    return max(built, key=lambda p: p.stat().st_mtime, default=None)


def test_reports_are_what_the_command_line_prints(fixtures, tmp_path):
    cli = _command_line()
    if cli is None:
        pytest.fail("no wingedge binary in target/: run the README's test command (its `cargo test` builds one)")
    huge = tmp_path / "huge.obj"
    huge.write_text(HUGE_TETRAHEDRON)
    repeat = tmp_path / "repeat.obj"
    repeat.write_text(REPEATING_WELD)
    paths = [*sorted((fixtures / "broken").glob("*.obj")), *sorted((fixtures / "valid").glob("*.obj")), huge, repeat]
    for weld, flags in ((None, []), ("none", ["--no-weld"]), (1e-6, ["--weld", "1e-6"])):
        run = subprocess.run(
            [str(cli), "validate", "--json", *flags, *map(str, paths)], capture_output=True, text=True
        )
        printed = json.loads(run.stdout)
        assert len(printed) == len(paths)
        for path, expected in zip(paths, printed):
            report = wingedge.validate(path, weld=weld)
            assert report.to_dict() == expected, path
            # Every field typed, as printed (a violation leaves out empty fields).
            for key, value in expected.items():
                if key != "violations":
                    assert getattr(report, key) == value, (path, key)
            assert len(report.violations) == len(expected["violations"])
            for violation, fields in zip(report.violations, expected["violations"]):
                assert (violation.rule, violation.message) == (fields["rule"], fields["message"])
                for key, absent in OPTIONAL_VIOLATION_FIELDS.items():
                    assert getattr(violation, key) == fields.get(key, absent), (path, key)
