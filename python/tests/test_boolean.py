"""Booleans from Python: Solid.union / intersection / difference and their
operators, combine over set expressions, Scene.evaluate, BooleanError.

Volumes and genus are checked against manifold3d, a test requirement
(python/tests/requirements.txt): a missing one fails the import, it is never
skipped.
"""

import pickle

import manifold3d as m3d
import numpy as np
import pytest

import wingedge
from conftest import run_python_block

OPERATIONS = ("union", "intersection", "difference")


def _moved(solid, offset):
    vertices, faces = solid.to_arrays()
    return wingedge.Solid.from_arrays(vertices + np.asarray(offset, dtype=np.float64), faces)


def _boxes():
    a = wingedge.cuboid((0, 0, 0), (2, 2, 2))
    b = wingedge.cuboid((1, 0.5, 0.25), (3, 2.5, 2.25))
    return a, b


def _spheres():
    a = wingedge.sphere(24)
    return a, _moved(a, (0.6, 0.3, 0.2))


def _oracle(ma, mb, operation):
    return {"union": ma + mb, "intersection": ma ^ mb, "difference": ma - mb}[operation]


@pytest.mark.parametrize("operation", OPERATIONS)
@pytest.mark.parametrize("pair", ["boxes", "spheres"])
def test_volume_and_genus_agree_with_manifold3d(pair, operation):
    a, b = _boxes() if pair == "boxes" else _spheres()
    ours = getattr(a, operation)(b)
    theirs = _oracle(a.to_manifold(), b.to_manifold(), operation)
    assert theirs.status() == m3d.Error.NoError
    assert ours.is_closed and ours.shells == 1
    assert ours.volume == pytest.approx(theirs.volume(), rel=1e-9)
    assert ours.genus == theirs.genus() == 0
    assert ours.area == pytest.approx(theirs.surface_area(), rel=1e-9)
    report = wingedge.validate(ours)
    assert report.valid, report.violations[:3]
    # The result goes back to manifold3d as a valid mesh of the same volume.
    assert ours.to_manifold().volume() == pytest.approx(theirs.volume(), rel=1e-9)


def test_the_volumes_add_up_and_the_operators_match_the_methods():
    a, b = _spheres()
    union, both, minus = a | b, a & b, a - b
    assert union.volume + both.volume == pytest.approx(a.volume + b.volume, rel=1e-12)
    assert minus.volume + both.volume == pytest.approx(a.volume, rel=1e-12)
    for got, want in [(union, a.union(b)), (both, a.intersection(b)), (minus, a.difference(b))]:
        assert got.volume == want.volume and got.face_count == want.face_count
    # Anything but a Solid on the other side is not an operand.
    with pytest.raises(TypeError):
        a | 1
    with pytest.raises(TypeError, match="other must be a wingedge.Solid"):
        a.union("cube")


def test_a_drilled_block_has_genus_one_and_its_ring_faces_come_as_triangles():
    block = wingedge.cuboid((0, 0, 0), (2, 2, 2))
    drill = wingedge.cuboid((0.5, 0.5, -1), (1.5, 1.5, 3))
    drilled = block - drill
    theirs = block.to_manifold() - drill.to_manifold()
    assert drilled.volume == pytest.approx(theirs.volume(), rel=1e-12) == 6.0
    assert drilled.genus == theirs.genus() == 1
    # The top and bottom are faces with a ring: 8 triangles each, the four
    # sides and the four tunnel walls stay quadrilaterals.
    _, faces = drilled.to_arrays()
    sizes = sorted(len(f) for f in faces)
    assert sizes == [3] * 16 + [4] * 8
    assert wingedge.validate(drilled).valid


def test_face_origins_name_the_operand_and_its_face():
    a, b = _boxes()
    for result in (a | b, a & b, a - b):
        origins = result.face_origins
        assert origins.shape == (result.face_count, 2) and origins.dtype == np.int64
        assert set(origins[:, 0]) <= {0, 1}
        assert origins[:, 1].min() >= 0 and origins[:, 1].max() < 6
    # a − b: every face lies in the plane of the face it names.
    minus = a - b
    vertices, faces = minus.to_arrays()
    for face, (operand, index) in zip(faces, minus.face_origins):
        ov, of = (a, b)[operand].to_arrays()
        p, q, r = ov[of[index][:3]]
        normal = np.cross(q - p, r - p)
        assert np.all(np.abs((vertices[face] - p) @ normal) == 0), (face, operand, index)
    # Solids not made by a boolean have none.
    assert a.face_origins is None
    # Pickling keeps them.
    clone = pickle.loads(pickle.dumps(minus))
    np.testing.assert_array_equal(clone.face_origins, minus.face_origins)
    assert clone.volume == minus.volume


def test_combine_of_three_operands_equals_the_chained_operators():
    a, b = _spheres()
    c = _moved(a, (-0.2, 0.7, -0.4))
    one_pass = wingedge.combine([a, b, c], ("difference", 0, ("union", 1, 2)))
    chained = a - (b | c)
    assert one_pass.volume == pytest.approx(chained.volume, rel=1e-12)
    assert one_pass.genus == chained.genus
    assert set(one_pass.face_origins[:, 0]) == {0, 1, 2}
    # A flat chain is read left to right: a − b − c.
    flat = wingedge.combine([a, b, c], ("difference", 0, 1, 2))
    assert flat.volume == pytest.approx(chained.volume, rel=1e-12)
    # Lists work as tuples, and a bare index is that operand as it is.
    union = wingedge.combine([a, b, c], ["union", 0, 1, 2])
    assert union.volume == pytest.approx(((a | b) | c).volume, rel=1e-12)
    # numpy integers name operands too.
    indices = ("difference", *np.arange(3))
    assert wingedge.combine([a, b, c], indices).volume == pytest.approx(flat.volume, rel=1e-12)
    alone = wingedge.combine([a, b], 1)
    assert alone.volume == b.volume
    np.testing.assert_array_equal(alone.face_origins[:, 0], 1)
    np.testing.assert_array_equal(alone.face_origins[:, 1], np.arange(b.face_count))


@pytest.mark.parametrize(
    "expression, message",
    [
        (("unoin", 0, 1), r"expression\[0\]: 'unoin' \(str\) is not an operation"),
        (("union", 0), "expression: a union needs at least two operands, got 1"),
        (("union", 0, ("intersection", 1, 5)), r"expression\[2\]\[2\]: operand 5 .* names no solid"),
        (("difference", 0, -1), r"expression\[2\]: operand -1 .* names no solid"),
        (("difference", 0, 2**70), r"expression\[2\]: operand 1180591620717411303424 .* names no solid"),
        (("union", 0, True), r"expression\[2\]: True \(bool\) is a bool"),
        (("union", 0, 1.0), r"expression\[2\]: expected an operand index .* got 1.0 \(float\)"),
        ((), "expression: an empty tuple"),
        ("union", r"expression: expected an operand index .* got 'union' \(str\)"),
    ],
)
def test_a_bad_expression_raises_a_located_error(expression, message):
    a, b = _boxes()
    with pytest.raises(wingedge.BooleanError, match=message):
        wingedge.combine([a, b], expression)


def test_a_too_deep_expression_is_refused_not_a_crash():
    a, b = _boxes()
    expression = 0
    for _ in range(5000):
        expression = ("union", expression, 1)
    with pytest.raises(wingedge.BooleanError, match="nested more than 1000 levels"):
        wingedge.combine([a, b], expression)


def test_a_non_closed_operand_raises_boolean_error_naming_it():
    vertices, faces = wingedge.cuboid((0.5, 0.5, 0.5), (1.5, 1.5, 1.5)).to_arrays()
    open_box = wingedge.Solid.from_arrays(vertices, faces[:5])
    assert not open_box.is_closed
    a, _ = _boxes()
    with pytest.raises(wingedge.BooleanError, match="operand 1 is not a valid solid"):
        a | open_box
    with pytest.raises(wingedge.BooleanError, match="operand 0 is not a valid solid"):
        open_box - a
    with pytest.raises(wingedge.BooleanError, match="operand 2 is not a valid solid") as caught:
        wingedge.combine([a, a, open_box], ("union", 0, 1, 2))
    # The defects come along, and the class is a WingedgeError (a ValueError).
    assert "edge_in_one_face" in str(caught.value)
    assert issubclass(wingedge.BooleanError, wingedge.WingedgeError)
    assert issubclass(wingedge.BooleanError, ValueError)


def test_results_touching_along_an_edge_or_at_a_corner_are_two_shells():
    a = wingedge.cuboid((0, 0, 0), (1, 1, 1))
    for other in [wingedge.cuboid((1, 1, 0), (2, 2, 1)), wingedge.cuboid((1, 1, 1), (2, 2, 2))]:
        touching = a | other
        assert touching.volume == 2.0 and touching.shells == 2
        assert wingedge.validate(touching).valid
        # Each box keeps its own vertices where they touch.
        vertices, _ = touching.to_arrays()
        assert len(vertices) == 16


def test_empty_results_are_empty_solids():
    a = wingedge.cuboid((0, 0, 0), (1, 1, 1))
    far = wingedge.cuboid((5, 5, 5), (6, 6, 6))
    for empty in (a & far, a - a, wingedge.combine([a, far], ("intersection", 0, 1))):
        assert empty.face_count == empty.vertex_count == empty.edge_count == 0
        assert empty.volume == 0.0
        assert empty.face_origins.shape == (0, 2)
        clone = pickle.loads(pickle.dumps(empty))
        assert clone.face_count == 0 and clone.face_origins.shape == (0, 2)
    # The empty set is a valid operand: a ∪ ∅ is a, a − ∅ is a.
    empty = a & far
    assert (a | empty).volume == 1.0 and (a - empty).volume == 1.0
    assert (empty - a).face_count == 0


def test_a_scene_evaluates_to_a_solid():
    scene = wingedge.Scene.from_dict(
        {"root": {"difference": [{"box": {"min": [0, 0, 0], "max": [2, 2, 2]}},
                                 {"box": {"min": [1, 1, 1], "max": [3, 3, 3]}}]}}
    )
    solid = scene.evaluate()
    assert solid.volume == 7.0 and solid.genus == 0
    assert wingedge.validate(solid).valid
    # Each face names its leaf and the leaf's face: the first box keeps its
    # three far faces whole and is cut on three; the second gives three.
    origins = solid.face_origins
    assert origins.shape == (solid.face_count, 2)
    assert sorted(set(origins[:, 0].tolist())) == [0, 1]
    assert (origins[:, 0] == 1).sum() == 3 and (origins[:, 0] == 0).sum() == 6
    assert set(origins[:, 1].tolist()) <= set(range(6))
    ball = wingedge.Scene.from_dict({"root": {"sphere": {"center": [0, 0, 0], "radius": 1}}})
    coarse, fine = ball.evaluate(tolerance=0.05), ball.evaluate()
    # Inscribed polyhedra: below the ball's volume, closer when finer.
    assert coarse.volume < fine.volume < 4 / 3 * np.pi
    assert fine.volume == pytest.approx(4 / 3 * np.pi, rel=5e-3)
    with pytest.raises(wingedge.SceneError, match="chord tolerance"):
        ball.evaluate(tolerance=2.0)


def test_the_booleans_example_of_the_python_page_runs(capsys):
    run_python_block("docs/python.md")
    lines = capsys.readouterr().out.splitlines()
    assert lines[0] == "6.0 1"
    assert lines[1] == "[[0, 0], [0, 2]]"
    assert lines[2] == "2 16"
    assert 8 - np.pi / 6 < float(lines[3]) < 7.5
