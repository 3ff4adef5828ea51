"""Solids from Python: builders, arrays, measures, queries and their errors."""

import pickle

import numpy as np
import pytest

import wingedge

UNIT_CUBE_V = np.array(
    [[x, y, z] for z in (0.0, 1.0) for y in (0.0, 1.0) for x in (0.0, 1.0)]
)
UNIT_CUBE_F = np.array(
    [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [3, 2, 6, 7], [0, 4, 6, 2], [1, 3, 7, 5]]
)


def test_builtins_have_their_closed_form_measures():
    assert wingedge.cube().volume == pytest.approx(8.0, rel=1e-15)
    assert wingedge.tetrahedron().volume == pytest.approx(8.0 / 3.0, rel=1e-15)
    assert wingedge.octahedron().volume == pytest.approx(4.0 / 3.0, rel=1e-15)
    cube = wingedge.cube()
    assert (cube.vertex_count, cube.edge_count, cube.face_count) == (8, 12, 6)
    assert cube.genus == 0 and cube.shells == 1 and cube.is_closed
    assert cube.area == pytest.approx(24.0, rel=1e-15)
    np.testing.assert_array_equal(cube.bounds, [[-1, -1, -1], [1, 1, 1]])
    with pytest.raises(ValueError, match="no built-in solid"):
        wingedge.builtin("klein_bottle")


def test_from_arrays_accepts_quads_as_an_array_or_a_list():
    a = wingedge.Solid.from_arrays(UNIT_CUBE_V, UNIT_CUBE_F)
    b = wingedge.Solid.from_arrays(UNIT_CUBE_V.tolist(), [list(f) for f in UNIT_CUBE_F])
    assert a.volume == b.volume == 1.0
    v, f = a.to_arrays()
    np.testing.assert_array_equal(v, UNIT_CUBE_V)
    np.testing.assert_array_equal(f, UNIT_CUBE_F)


def test_mixed_faces_come_back_as_a_list():
    # A square pyramid: one quad and four triangles.
    v = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0.5, 0.5, 1]]
    f = [[0, 3, 2, 1], [0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]]
    solid = wingedge.Solid.from_arrays(v, f)
    assert solid.volume == pytest.approx(1.0 / 3.0, rel=1e-15)
    _, faces = solid.to_arrays()
    assert [x.tolist() for x in faces] == f


def test_classify_is_exact_on_the_boundary_and_one_ulp_off_it():
    cube = wingedge.cube()
    up = np.nextafter(1.0, 2.0)
    down = np.nextafter(1.0, 0.0)
    pts = np.array([[0, 0, 0], [1, 0, 0], [up, 0, 0], [down, 0, 0], [1, 1, 1], [3, 3, 3]])
    for method in ("parity", "normals", "winding"):
        assert cube.classify(pts, method=method).tolist() == [1, 0, -1, 1, 0, -1], method
    assert cube.contains(pts).tolist() == [True, True, False, True, True, False]
    assert cube.classify(pts).dtype == np.int8


def test_methods_agree_on_random_points(rng):
    solid = wingedge.icosahedron()
    pts = rng.uniform(-1.5, 1.5, size=(20000, 3))
    parity = solid.classify(pts)
    assert np.array_equal(parity, solid.classify(pts, method="normals"))
    assert np.array_equal(parity, solid.classify(pts, method="winding"))
    w = solid.winding_number(pts)
    assert np.allclose(w[parity == 1], 1.0) and np.allclose(w[parity == -1], 0.0, atol=1e-9)
    assert 0 < (parity == 1).sum() < len(pts)


def test_ray_cast_reports_t_face_and_transition():
    cube = wingedge.cube()
    origins = np.array([[-5.0, 0.25, 0.25], [0.0, 0.0, 0.0], [-5.0, 5.0, 5.0]])
    dirs = np.array([[1.0, 0, 0], [0, 0, 2.0], [1.0, 0, 0]])
    t, face, transition = cube.ray_cast(origins, dirs)
    assert t.tolist() == [4.0, 0.5, np.inf]
    assert transition.tolist() == [1, -1, 0]
    assert face[2] == -1 and 0 <= face[0] < 6 and 0 <= face[1] < 6
    _, faces = cube.to_arrays()
    v, _ = cube.to_arrays()
    assert np.all(v[faces[face[0]]][:, 0] == -1.0)  # the face x = -1
    assert np.all(v[faces[face[1]]][:, 2] == 1.0)  # the face z = 1
    origin_class, ts, fs, trs = cube.ray_crossings([-5, 0, 0], [1, 0, 0])
    assert origin_class == -1 and ts.tolist() == [4.0, 6.0] and trs.tolist() == [1, -1]


def test_non_contiguous_float32_and_integer_inputs_work():
    cube = wingedge.cube()
    big = np.zeros((4, 6))
    big[:, ::2] = [[0, 0, 0], [2, 0, 0], [0.5, 0.5, 0.5], [1, 1, 1]]
    strided = big[:, ::2]
    assert not strided.flags.c_contiguous
    assert cube.classify(strided).tolist() == [1, -1, 1, 0]
    assert cube.classify(strided.astype(np.float32)).tolist() == [1, -1, 1, 0]
    assert cube.classify(np.array([[0, 0, 0], [2, 0, 0]], dtype=np.int32)).tolist() == [1, -1]
    assert cube.classify(np.zeros((0, 3))).tolist() == []


def test_bad_arrays_and_queries_raise_located_errors():
    cube = wingedge.cube()
    with pytest.raises(ValueError, match=r"shape \(n, 3\)"):
        cube.classify(np.zeros((5, 2)))
    with pytest.raises(ValueError, match="dtype"):
        cube.classify(np.zeros((2, 3), dtype=complex))
    with pytest.raises(wingedge.QueryError, match="point 1"):
        cube.classify([[0, 0, 0], [np.nan, 0, 0]])
    with pytest.raises(wingedge.QueryError, match="ray 0"):
        cube.ray_cast([[0, 0, 0]], [[0, 0, 0]])
    with pytest.raises(ValueError, match="2 origins but 1 directions"):
        cube.ray_cast(np.zeros((2, 3)), np.ones((1, 3)))
    with pytest.raises(ValueError, match="method"):
        cube.classify([[0, 0, 0]], method="guess")
    with pytest.raises(wingedge.QueryError, match="convex"):
        wingedge.builtin("prism").classify([[0.5, 0.5, 0.5]], method="normals")
    assert issubclass(wingedge.QueryError, ValueError)


def test_bad_solids_raise_validation_errors_naming_the_polygon():
    with pytest.raises(wingedge.ValidationError, match="polygon 1 refers to vertex 9"):
        wingedge.Solid.from_arrays(UNIT_CUBE_V, [[0, 2, 3, 1], [4, 5, 9, 6]])
    with pytest.raises(wingedge.ValidationError, match="non-finite"):
        v = UNIT_CUBE_V.copy()
        v[3, 1] = np.inf
        wingedge.Solid.from_arrays(v, UNIT_CUBE_F)
    with pytest.raises(ValueError, match="never negative"):
        wingedge.Solid.from_arrays(UNIT_CUBE_V, [[0, -1, 3]])
    with pytest.raises(wingedge.ValidationError, match="no polygons"):
        wingedge.Solid.from_arrays(UNIT_CUBE_V, [])
    open_box = wingedge.Solid.from_arrays(UNIT_CUBE_V, UNIT_CUBE_F[:5])
    assert not open_box.is_closed and open_box.genus is None
    with pytest.raises(wingedge.QueryError, match="not closed"):
        open_box.classify([[0.5, 0.5, 0.5]])
    # The winding number still answers on the open box.
    assert open_box.classify([[0.5, 0.5, 0.5]], method="winding").tolist() == [1]


def test_pickled_solids_answer_identically(rng):
    solid = wingedge.sphere(12)
    clone = pickle.loads(pickle.dumps(solid))
    pts = rng.uniform(-1.2, 1.2, size=(5000, 3))
    assert np.array_equal(solid.classify(pts), clone.classify(pts))
    dirs = rng.normal(size=(5000, 3))
    for a, b in zip(solid.ray_cast(pts, dirs), clone.ray_cast(pts, dirs)):
        assert np.array_equal(a, b)
    assert clone.volume == solid.volume


def test_builders_refuse_bad_arguments():
    with pytest.raises(wingedge.ValidationError):
        wingedge.cuboid((0, 0, 0), (0, 1, 1))
    with pytest.raises(ValueError, match="rings"):
        wingedge.sphere(1)
    square = np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]])
    assert wingedge.prism(square, (0, 0, 2)).volume == pytest.approx(2.0, rel=1e-15)
    assert wingedge.cuboid((0, 0, 0), (1, 2, 3)).volume == pytest.approx(6.0, rel=1e-15)
