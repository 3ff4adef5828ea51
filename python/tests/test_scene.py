"""Scenes from Python: the JSON scene format loaded from files or dicts."""

import math

import numpy as np
import pytest

import wingedge


def test_the_drilled_cube_classifies_exactly_and_integrates_its_volume(fixtures):
    scene = wingedge.Scene.load(fixtures / "scenes" / "drilled_cube.json")
    assert scene.leaf_count == 4
    codes = scene.classify([[0.9, 0.9, 0.9], [0, 0, 0], [1, 0.9, 0.9], [2, 0, 0]])
    assert codes.tolist() == [1, -1, 0, -1]
    want = 8 - (3 * math.pi / 2 - 2 + (2 - math.sqrt(2)))
    assert scene.volume(0.02) == pytest.approx(want, rel=5e-3)
    t, leaf = scene.first_hit([[-5.0, 0.9, 0.9], [-5.0, 0, 0]], [[1.0, 0, 0], [1.0, 0, 0]])
    assert t[0] == 4.0 and leaf[0] >= 0
    assert t[1] == np.inf and leaf[1] == -1
    spans = scene.spans([-5, 0.9, 0.9], [1, 0, 0])
    assert spans.tolist() == [[4.0, 6.0]]


def test_a_scene_from_a_dict_answers_like_its_closed_form():
    scene = wingedge.Scene.from_dict(
        {"root": {"difference": [{"box": {"min": [0, 0, 0], "max": [2, 2, 2]}},
                                 {"box": {"min": [1, 1, 1], "max": [3, 3, 3]}}]}}
    )
    assert scene.classify([[0.5, 0.5, 0.5], [1.5, 1.5, 1.5], [1, 1, 1]]).tolist() == [1, -1, 0]
    assert scene.volume(0.1) == pytest.approx(7.0, rel=1e-12)
    np.testing.assert_array_equal(scene.bounds, [[0, 0, 0], [2, 2, 2]])


def test_render_returns_an_image_array(fixtures):
    scene = wingedge.Scene.load(fixtures / "scenes" / "platonic.json")
    image = scene.render(32, 24)
    assert image.shape == (24, 32, 3) and image.dtype == np.uint8
    assert len(np.unique(image.reshape(-1, 3), axis=0)) > 10
    with pytest.raises(ValueError, match="image size"):
        scene.render(0, 10)


def test_bad_scenes_and_queries_raise_located_errors(tmp_path, fixtures):
    with pytest.raises(wingedge.SceneError, match="missing.json"):
        wingedge.Scene.load(tmp_path / "missing.json")
    with pytest.raises(wingedge.SceneError, match=r"root"):
        wingedge.Scene.from_dict({"root": {"box": {"min": [0, 0], "max": [1, 1, 1]}}})
    scene = wingedge.Scene.load(fixtures / "scenes" / "drilled_cube.json")
    with pytest.raises(wingedge.QueryError, match="point 2"):
        scene.classify([[0, 0, 0], [1, 1, 1], [np.nan, 0, 0]])
    with pytest.raises(wingedge.QueryError, match="ray 0"):
        scene.first_hit([[0, 0, 0]], [[0, 0, 0]])
    with pytest.raises(ValueError, match="spacing"):
        scene.volume(-1.0)
    assert issubclass(wingedge.SceneError, wingedge.WingedgeError)


def test_scene_rays_are_scaled_and_refused_beyond_f64(fixtures):
    scene = wingedge.Scene.load(fixtures / "scenes" / "drilled_cube.json")
    # A direction 2^-1000 long: the same hits, t scaled by 2^1000 exactly.
    t_unit, _ = scene.first_hit([[-5.0, 0.9, 0.9]], [[1.0, 0, 0]])
    t_tiny, _ = scene.first_hit([[-5.0, 0.9, 0.9]], [[2.0**-1000, 0, 0]])
    assert t_tiny[0] == t_unit[0] * 2.0**1000
    with pytest.raises(wingedge.QueryError, match=r"ray 1 .*cannot be answered in f64"):
        scene.first_hit([[-5.0, 0.9, 0.9], [-1.7e308, 0.9, 0.9]], [[1.0, 0, 0], [1.0, 0, 0]])
    with pytest.raises(wingedge.QueryError, match="overflows"):
        scene.spans([-5, 0.9, 0.9], [5e-324, 0, 0])


def test_numbers_from_python_reach_the_scene_exactly():
    # 1 - 2**-53 is written as 0.9999999999999999, which serde_json's
    # default float parser reads as 1.0; the binding parses floats exactly.
    x = 1 - 2**-53
    scene = wingedge.Scene.from_dict({"root": {"box": {"min": [0, 0, 0], "max": [x, 1, 1]}}})
    assert scene.bounds[1, 0] == x
    assert scene.classify([[x, 0.5, 0.5], [1.0, 0.5, 0.5]]).tolist() == [0, -1]


def _cube_obj(path):
    path.write_text(
        "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
        "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n"
    )
    return path


def test_a_leaf_outside_the_scene_folder_is_refused_unless_allowed(tmp_path):
    outside = tmp_path / "outside"
    scenes = tmp_path / "scenes"
    outside.mkdir()
    scenes.mkdir()
    cube = _cube_obj(outside / "cube.obj")
    scene_file = scenes / "scene.json"
    scene_file.write_text('{"root": {"mesh": "../outside/cube.obj"}}')
    with pytest.raises(wingedge.SceneError, match=r"root\.mesh: .*allow_paths"):
        wingedge.Scene.load(scene_file)
    assert wingedge.Scene.load(scene_file, allow_paths=[outside]).leaf_count == 1
    with pytest.raises(wingedge.SceneError, match=r"root\.mesh: "):
        wingedge.Scene.from_dict({"root": {"mesh": str(cube)}}, base=scenes)
    scene = wingedge.Scene.from_dict({"root": {"mesh": str(cube)}}, base=scenes, allow_paths=[outside])
    assert scene.classify([[0, 0, 0]]).tolist() == [1]
