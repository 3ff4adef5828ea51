"""Reading files: :func:`load` (any format) and :func:`load_obj`; making a
mesh that is no solid into one: :func:`repair`."""

from __future__ import annotations

from typing import Optional

from . import _wingedge
from ._arrays import _coords, _faces_flat
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


def repair(source, *, max_hole_edges: Optional[int] = None, weld=None, format: Optional[str] = None):
    """Makes a mesh that is no valid solid into one, exactly: merges equal
    positions, drops faces that bound nothing, orients every piece, fills
    holes (only those of at most ``max_hole_edges`` edges, when given) and
    resolves self-intersecting and overlapping shells, keeping the region
    where the winding number is positive (the library's ``repair::repair``;
    docs/repair.md).

    ``source`` is a mesh file's path (any format :func:`load` reads;
    ``weld`` and ``format`` as there) or a pair ``(vertices, faces)`` as
    :meth:`Solid.from_arrays` takes. Returns ``(solid, report)``: the valid
    :class:`Solid` (empty when the mesh encloses nothing; ``None`` when a
    hole was left open) and a dict of what changed (``dropped``: polygon
    index and why, ``turned_over``, ``filled`` and ``left_open`` holes by
    their edges, ``crossing_pairs``, ``volume_before`` (the winding-number
    volume), ``volume_after``, ``empty_because``, ``validity``). Raises
    ``FormatError`` for an unreadable file and ``ValidationError`` for bad
    indices or positions."""
    if isinstance(source, tuple):
        vertices, faces = source
        sizes, indices = _faces_flat(faces)
        native, report = _wingedge.repair_flat(
            _coords(vertices, "vertices"), sizes, indices, max_hole_edges
        )
    else:
        native, report = _wingedge.repair_path(str(source), max_hole_edges, weld, format)
    return (Solid(native) if native is not None else None), report
