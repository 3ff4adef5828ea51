"""Validation: :func:`validate` and what it returns, the native
:class:`Report` and :class:`Violation` (typed, immutable, picklable)."""

from __future__ import annotations

from typing import Optional

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
