"""wingedge.repair: meshes that are no solid made valid solids, exactly."""

import numpy as np
import pytest

import wingedge


def box(lo, hi, offset=0):
    """The box [lo, hi] as 8 vertices and 6 outward quads (indices + offset)."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
         (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    f = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    return v, [tuple(i + offset for i in q) for q in f]


def test_a_file_with_a_hole_comes_out_a_valid_solid():
    solid, report = wingedge.repair("fixtures/broken/edge_in_one_face.obj")
    assert solid is not None
    assert wingedge.validate(solid).validity == "valid_solid"
    assert report["validity"] == "valid_solid"
    assert report["filled"], report
    assert solid.volume > 0


def test_two_overlapping_boxes_in_one_soup_become_their_union():
    a, fa = box((0, 0, 0), (1, 1, 1))
    b, fb = box((0.5, 0, 0), (1.5, 1, 1), offset=8)
    solid, report = wingedge.repair((np.array(a + b, float), fa + fb))
    assert wingedge.validate(solid).validity == "valid_solid"
    assert solid.volume == 1.5
    assert report["volume_before"] == 2.0 and report["volume_after"] == 1.5
    assert report["crossing_pairs"] > 0


def test_a_hole_larger_than_the_limit_stays_open():
    v, f = box((0, 0, 0), (1, 1, 1))
    solid, report = wingedge.repair((np.array(v, float), f[1:]), max_hole_edges=3)
    assert solid is None
    assert report["left_open"] == [(4, "larger than max_hole_edges")]
    solid, report = wingedge.repair((np.array(v, float), f[1:]))
    assert solid.volume == 1.0 and report["filled"] == [(4, 2)]


def test_a_sheet_encloses_nothing():
    solid, report = wingedge.repair((np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], float), [(0, 1, 2)]))
    assert solid is not None and solid.face_count == 0
    assert report["empty_because"]


def test_bad_indices_are_refused_by_name():
    with pytest.raises(wingedge.ValidationError):
        wingedge.repair((np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], float), [(0, 1, 7)]))


def test_combine_takes_a_self_intersecting_operand_with_resolve():
    a, fa = box((0, 0, 0), (1, 1, 1))
    b, fb = box((0.5, 0, 0), (1.5, 1, 1), offset=8)
    tangled = wingedge.Solid.from_arrays(np.array(a + b, float), fa + fb)
    assert wingedge.validate(tangled).validity != "valid_solid"
    slab = wingedge.cuboid((0, 0, 1), (2, 1, 2))
    with pytest.raises(wingedge.BooleanError, match="resolve"):
        wingedge.combine([tangled, slab], ("union", 0, 1))
    union = wingedge.combine([tangled, slab], ("union", 0, 1), resolve=True)
    assert wingedge.validate(union).validity == "valid_solid"
    assert union.volume == 3.5
