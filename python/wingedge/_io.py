"""Reading files: :func:`load` (any format) and :func:`load_obj`."""

from __future__ import annotations

from typing import Optional

from . import _wingedge
from ._solid import Solid


def load(
    path,
    weld=None,
    max_face_corners: Optional[int] = None,
    format: Optional[str] = None,
) -> Solid:
    """Reads a mesh file into a :class:`Solid`: OBJ, STL (binary or ASCII),
    PLY, OFF, 3MF, glTF or GLB, picked by the extension or by ``format``
    (``"obj"``, ``"stl"``, ``"ply"``, ``"off"``, ``"3mf"``, ``"gltf"``,
    ``"glb"``; an unknown extension reads as OBJ).

    ``weld``: ``None``/``"exact"`` merges bit-identical positions where that
    closes open edges (the default; STL repeats every corner, so this is
    what makes an STL file a solid), ``"none"`` merges nothing, a number is
    a weld tolerance as a fraction of the bounding-box diagonal. Raises
    ``FormatError`` (``ObjError`` for OBJ) naming the file and the place in
    it, and ``ValidationError`` when the faces cannot form a winged-edge
    solid (use :func:`validate` to see every defect)."""
    return Solid(_wingedge.load(str(path), weld, max_face_corners, format))


def load_obj(path, weld=None, max_face_corners: Optional[int] = None) -> Solid:
    """Reads an OBJ file into a :class:`Solid`.

    ``weld``: ``None``/``"exact"`` merges bit-identical positions where that
    closes open edges (the default), ``"none"`` merges nothing, a number is
    a weld tolerance as a fraction of the bounding-box diagonal. Raises
    ``ObjError`` (file and line) for an unreadable file and
    ``ValidationError`` when the faces cannot form a winged-edge solid (use
    :func:`validate` to see every defect)."""
    return Solid(_wingedge.load_obj(str(path), weld, max_face_corners))
