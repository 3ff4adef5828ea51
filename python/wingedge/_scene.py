"""Scenes: :class:`Scene`, a CSG tree answered by ray casting."""

from __future__ import annotations

import json
import warnings
from typing import Optional

import numpy as np

from . import _wingedge
from ._arrays import _coords, _point
from ._solid import Solid


class Scene:
    """A CSG tree of meshes, half-spaces, boxes, spheres and cylinders (the
    JSON scene format of ``docs/csg.md``), answered by ray casting: exact
    point classes, first hits, spans, volume and images."""

    __slots__ = ("_native",)

    def __init__(self, native: "_wingedge.NativeScene"):
        self._native = native

    @classmethod
    def load(cls, path, *, allow_paths=()) -> "Scene":
        """Reads a scene file; mesh paths are relative to its folder. A leaf
        (mesh, field or included scene file) must resolve, symbolic links
        followed, inside the scene's folder, the working directory or a
        folder in ``allow_paths``, and be a regular file. Raises
        ``SceneError`` naming the file and the JSON path."""
        return cls(_wingedge.NativeScene.load(str(path), [str(p) for p in allow_paths]))

    @classmethod
    def from_dict(cls, scene: dict, base=".", *, allow_paths=()) -> "Scene":
        """A scene from Python objects shaped like a scene file (dicts,
        lists, numbers, strings); mesh paths are relative to ``base``, and
        leaves must resolve inside ``base``, the working directory or a
        folder in ``allow_paths``."""
        return cls(
            _wingedge.NativeScene.from_json(
                json.dumps(scene), str(base), [str(p) for p in allow_paths]
            )
        )

    bounds = property(
        lambda self: np.array(self._native.bounds, dtype=np.float64),
        doc="Bounds as a (2, 3) array (infinite for an unbounded tree).",
    )
    leaf_count = property(lambda self: self._native.leaf_count, doc="Number of leaves.")

    def classify(self, points) -> np.ndarray:
        """int8 per point: ``1`` inside, ``0`` on the boundary, ``-1`` outside."""
        return self._native._classify(_coords(points, "points"))

    def contains(self, points) -> np.ndarray:
        """Boolean per point: inside or on the boundary."""
        return self.classify(points) >= 0

    def first_hit(self, origins, directions):
        """``(t, leaf)``: the first boundary crossing of each ray (``inf``
        and ``-1`` for a miss) and the leaf whose surface it is."""
        return self._native._first_hit(_coords(origins, "origins"), _coords(directions, "directions"))

    def spans(self, origin, direction) -> np.ndarray:
        """The intervals of one ray inside the solid, ``(n, 2)``."""
        return self._native._spans(_point(origin, "origin"), _point(direction, "direction"))

    def volume(self, spacing: Optional[float] = None) -> float:
        """The volume by ray integration on a grid of cells of side at most
        ``spacing`` (the closed form when the tree is one leaf that has one).
        Without ``spacing``, the default grid: 400 cells across the longest
        side, and at least 4 across every leaf that adds volume. A
        ``RuntimeWarning`` names a leaf narrower than a cell (the grid may
        miss it)."""
        volume, _, _, exact, warning = self._native.volume(
            None if spacing is None else float(spacing)
        )
        if warning is not None and exact is None:
            warnings.warn(warning, RuntimeWarning, stacklevel=2)
        return exact if exact is not None else volume

    def render(self, width: int = 640, height: int = 480) -> np.ndarray:
        """A shaded, ray-cast image as a ``(height, width, 3)`` uint8 array."""
        return self._native.render(int(width), int(height))

    def evaluate(self, tolerance: Optional[float] = None) -> Solid:
        """The tree as one valid :class:`Solid`, by exact booleans over all
        its leaves in one pass (boundary evaluation). Spheres and cylinders
        become inscribed polyhedra within ``tolerance`` times their radius
        (default 1e-3); half-spaces are clipped to the tree's bounds. Raises
        ``SceneError`` naming a leaf that cannot be made a polyhedron, and
        ``BooleanError`` when a leaf is not a valid solid or the result
        cannot be one. The result has no :attr:`Solid.face_origins`."""
        return Solid(self._native.evaluate(None if tolerance is None else float(tolerance)))

    def __repr__(self) -> str:
        return repr(self._native)
