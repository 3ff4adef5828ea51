"""wingedge.render_defects: the picture `wingedge validate --image` draws."""

import numpy as np
import pytest

import wingedge

# The colours of src/render/defects.rs (`defect_colour`).
RIM = (230, 25, 75)  # edge_in_one_face
CROSSING = (255, 160, 0)  # self_intersection


def _grey(image):
    return (image[..., 0] == image[..., 1]) & (image[..., 1] == image[..., 2])


def test_a_hole_is_drawn_in_the_rim_colour_at_the_size_asked(fixtures):
    path = fixtures / "broken" / "edge_in_one_face.obj"
    image = wingedge.render_defects(path, width=320, height=200)
    assert isinstance(image, np.ndarray)
    assert image.shape == (200, 320, 3) and image.dtype == np.uint8
    rim = np.all(image == RIM, axis=-1).sum()
    assert rim > 49 + 50, rim  # the legend's swatch and the rim's lines
    # The same picture from a report given, and as the CLI draws it.
    report = wingedge.validate(path)
    again = wingedge.render_defects(path, report=report, width=320, height=200)
    assert np.array_equal(image, again)


def test_a_self_intersection_is_filled_and_a_valid_solid_is_grey(fixtures):
    image = wingedge.render_defects(fixtures / "broken" / "self_intersection.obj")
    assert image.shape == (600, 800, 3)
    r, g, b = (image[..., c].astype(float) for c in range(3))
    amber = (b == 0) & (r > 60) & (np.abs(g - r * CROSSING[1] / CROSSING[0]) <= 3)
    assert amber.sum() > 500, amber.sum()
    cube = wingedge.render_defects(wingedge.cube(), width=200, height=150)
    assert cube.shape == (150, 200, 3)
    assert _grey(cube).all()
    assert (cube != 255).any(axis=-1).sum() > 200 * 150 / 20


def test_bad_sizes_and_unknown_rules_are_value_errors(fixtures):
    with pytest.raises(ValueError, match="image size 0x10"):
        wingedge.render_defects(wingedge.cube(), width=0, height=10)
    with pytest.raises(ValueError, match="weld and format apply to files"):
        wingedge.render_defects(wingedge.cube(), weld=1e-6)
