"""Validation: :func:`validate` and what it returns, the native
:class:`Report` and :class:`Violation` (typed, immutable, picklable), and
:func:`render_defects`, the picture of a report."""

from __future__ import annotations

from typing import Optional

import numpy as np

from . import _wingedge
from ._solid import Solid
from ._wingedge import Report, Violation


def validate(
    path_or_solid,
    weld=None,
    planarity: Optional[float] = None,
    format: Optional[str] = None,
) -> Report:
    """Validates a mesh file (a path: OBJ, STL, PLY, OFF, 3MF, glTF, GLB,
    by the extension or ``format``) or a :class:`Solid`: every defect named
    and located, a graded verdict, counts and measures."""
    if isinstance(path_or_solid, Solid):
        if weld is not None or format is not None:
            raise ValueError("weld and format apply to files; a Solid is already read")
        return _wingedge.validate_solid(path_or_solid._native, planarity)
    return _wingedge.validate_path(str(path_or_solid), weld, planarity, format)


def render_defects(
    path_or_solid,
    report: Optional[Report] = None,
    width: int = 800,
    height: int = 600,
    weld=None,
    planarity: Optional[float] = None,
    format: Optional[str] = None,
) -> np.ndarray:
    """The mesh drawn with its defects marked, as ``wingedge validate
    --image`` draws it: a ``(height, width, 3)`` uint8 array. Faces of face
    rules are filled in the rule's colour, edges of edge rules drawn thick,
    named vertices drawn as dots, the view framed on the defects (on the
    whole mesh when there are none), with a legend of the count per rule.

    ``report`` is the report to draw (one of this mesh, read with the same
    weld); without it the mesh is validated first. The mesh is a file path
    (any format :func:`validate` reads) or a :class:`Solid`."""
    if isinstance(path_or_solid, Solid):
        if weld is not None or format is not None:
            raise ValueError("weld and format apply to files; a Solid is already read")
        return _wingedge.render_defects_solid(
            path_or_solid._native, int(width), int(height), report, planarity
        )
    return _wingedge.render_defects_path(
        str(path_or_solid), int(width), int(height), report, weld, planarity, format
    )
