"""SoupWinding: the winding number of meshes that cannot be solids."""

import numpy as np
import pytest

import wingedge


def test_a_fin_is_no_solid_but_answers_as_its_cube(fixtures, rng):
    path = fixtures / "soups" / "fin.obj"
    with pytest.raises(wingedge.ValidationError, match="used by 3 polygons"):
        wingedge.load_obj(path)
    soup = wingedge.SoupWinding.load_obj(path)
    assert soup.polygon_count == 7
    assert soup.open_edges == 4
    cube = wingedge.cuboid((0, 0, 0), (1, 1, 1))
    points = rng.uniform(-0.5, 2.5, size=(5000, 3))
    assert np.array_equal(soup.classify(points), cube.classify(points))
    assert soup.classify([[1.5, 0.5, -0.5]]).tolist() == [0]  # on the fin
    assert soup.winding_number([[0.5, 0.5, 0.5]])[0] > 0.5


def test_two_cubes_on_one_edge_are_exact(fixtures):
    soup = wingedge.SoupWinding.load_obj(fixtures / "broken" / "edge_in_more_than_two_faces.obj")
    assert soup.open_edges == 0
    got = soup.classify([[0.5, 0.5, 0.5], [1.5, 1.5, 0.5], [1.5, 0.5, 0.5], [1, 1, 0.5]])
    assert got.tolist() == [1, 1, -1, 0]


def test_from_arrays_and_bad_numbers():
    vertices = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    faces = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3], [0, 1, 3]]
    soup = wingedge.SoupWinding.from_arrays(vertices, faces)
    assert soup.open_edges == 3
    with pytest.raises(wingedge.ValidationError, match="non-finite"):
        bad = vertices.copy()
        bad[1, 0] = np.nan
        wingedge.SoupWinding.from_arrays(bad, faces)
    with pytest.raises(wingedge.ValidationError, match="no polygons"):
        wingedge.SoupWinding.from_arrays(vertices, np.zeros((0, 3), dtype=np.int64))
    with pytest.raises(wingedge.QueryError, match="point 1"):
        soup.classify([[0.1, 0.1, 0.1], [np.inf, 0, 0]])
