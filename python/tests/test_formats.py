"""wingedge.load and Solid.save in every format; trimesh's exports of one
model load as its OBJ does; errors name the file and the place."""

import pathlib
import warnings

import numpy as np
import pytest
import trimesh

import wingedge

ROOT = pathlib.Path(__file__).resolve().parents[2]
FORMATS = ROOT / "fixtures" / "formats"


@pytest.mark.parametrize(
    "name",
    ["torus.obj", "torus.stl", "torus_ascii.stl", "torus.ply", "torus_ascii.ply", "torus.off", "torus.3mf", "torus.glb", "torus.gltf"],
)
def test_the_fixtures_load_as_the_obj(name):
    obj = wingedge.load(FORMATS / "torus.obj")
    solid = wingedge.load(FORMATS / name)
    assert (solid.vertex_count, solid.edge_count, solid.face_count, solid.genus) == (96, 288, 192, 1)
    assert solid.volume == pytest.approx(obj.volume, rel=1e-6)
    assert wingedge.validate(FORMATS / name).valid


def test_save_keeps_f64_where_the_format_can_and_warns_where_it_cannot(tmp_path):
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float) * np.pi + 0.1
    tet = wingedge.Solid.from_arrays(v, [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    for ext in ["obj", "ply", "off", "3mf"]:
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            assert tet.save(tmp_path / f"t.{ext}") == 0
        back, _ = wingedge.load(tmp_path / f"t.{ext}").to_arrays()
        assert sorted(map(tuple, back)) == sorted(map(tuple, v)), ext
    for ext in ["stl", "gltf", "glb"]:
        with pytest.warns(UserWarning, match="coordinates changed when rounded to f32"):
            rounded = tet.save(tmp_path / f"t.{ext}")
        assert rounded == int(np.sum(v.astype(np.float32).astype(np.float64) != v))
        back, _ = wingedge.load(tmp_path / f"t.{ext}").to_arrays()
        assert sorted(map(tuple, back)) == sorted(map(tuple, v.astype(np.float32).astype(np.float64))), ext
    # trimesh reads what wingedge writes.
    for ext in ["stl", "ply", "off", "glb"]:
        mesh = trimesh.load(tmp_path / f"t.{ext}", force="mesh")
        assert mesh.is_watertight and mesh.volume == pytest.approx(tet.volume, rel=1e-6), ext
    with pytest.raises(ValueError, match="cannot tell the format"):
        tet.save(tmp_path / "t.mesh")
    assert tet.save(tmp_path / "t.mesh", format="off") == 0


def test_errors_name_the_file_and_the_place(tmp_path):
    stl = (FORMATS / "torus.stl").read_bytes()
    lying = bytearray(stl[:1024])
    lying[80:84] = (10**9).to_bytes(4, "little")
    path = tmp_path / "lying.stl"
    path.write_bytes(bytes(lying))
    with pytest.raises(wingedge.FormatError, match=r"lying.stl: byte 80: the file ends after 1024 bytes"):
        wingedge.load(path)
    with pytest.raises(wingedge.ObjError):
        wingedge.load(tmp_path / "missing.obj")
    assert issubclass(wingedge.ObjError, wingedge.FormatError)
    copy = tmp_path / "torus.bin"
    copy.write_bytes(stl)
    assert wingedge.load(copy, format="stl").face_count == 192
    with pytest.raises(ValueError, match="unknown format"):
        wingedge.load(copy, format="stp")
