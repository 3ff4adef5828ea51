"""Validation: :func:`validate` and what it returns, :class:`Report` and
:class:`Violation`."""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from typing import List, Optional

from . import _wingedge
from ._solid import Solid


@dataclass
class Violation:
    """One broken rule, located: ``line`` is the OBJ line of the first
    element named, ``vertices``/``faces`` 0-based element ids."""

    rule: str
    message: str
    line: Optional[int] = None
    lines: List[int] = field(default_factory=list)
    vertices: List[int] = field(default_factory=list)
    faces: List[int] = field(default_factory=list)
    value: Optional[float] = None


@dataclass
class Report:
    """What validation found: the content of ``wingedge validate --json``."""

    valid: bool
    verdict: str
    validity: str
    vertices: int
    edges: int
    faces: int
    shells: int
    holes: int
    genus: Optional[int]
    volume: Optional[float]
    area: float
    not_built: Optional[str]
    counts: dict
    violations: List[Violation]
    shell_details: List[dict]
    file: Optional[str] = None
    weld: Optional[dict] = None

    @classmethod
    def _from_json(cls, text: str) -> "Report":
        d = json.loads(text)
        return cls(
            valid=d["valid"],
            verdict=d["verdict"],
            validity=d["validity"],
            vertices=d["vertices"],
            edges=d["edges"],
            faces=d["faces"],
            shells=d["shells"],
            holes=d["holes"],
            genus=d["genus"],
            volume=d["volume"],
            area=d["area"],
            not_built=d["not_built"],
            counts=d["counts"],
            violations=[Violation(**v) for v in d["violations"]],
            shell_details=d["shell_details"],
            file=d.get("file"),
            weld=d.get("weld"),
        )


def validate(path_or_solid, weld=None, planarity: Optional[float] = None) -> Report:
    """Validates an OBJ file (a path) or a :class:`Solid`: every defect
    named and located, a graded verdict, counts and measures."""
    if isinstance(path_or_solid, Solid):
        if weld is not None:
            raise ValueError("weld applies to files; a Solid is already welded")
        return Report._from_json(_wingedge.validate_solid(path_or_solid._native, planarity))
    return Report._from_json(_wingedge.validate_path(str(path_or_solid), weld, planarity))
