"""wingedge: an exact B-rep polyhedron kernel (Baumgart's winged edge), from numpy.

Every inside/outside and ray decision is exact: signs come from exact
predicates, never from an epsilon. Arrays go in as ``(n, 3)`` coordinates and
come back as numpy arrays; batch calls release the interpreter lock and use
every core.

>>> import wingedge, numpy as np
>>> cube = wingedge.cube()
>>> cube.classify(np.array([[0.0, 0, 0], [1, 0, 0], [2, 0, 0]])).tolist()
[1, 0, -1]
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from typing import List, Optional, Sequence, Tuple, Union

import numpy as np

from . import _wingedge
from ._wingedge import (
    BooleanError,
    ObjError,
    QueryError,
    SceneError,
    ValidationError,
    WingedgeError,
)

__version__ = _wingedge.__version__

__all__ = [
    "Solid",
    "SoupWinding",
    "Scene",
    "Report",
    "Violation",
    "load_obj",
    "validate",
    "combine",
    "builtin",
    "tetrahedron",
    "cube",
    "octahedron",
    "dodecahedron",
    "icosahedron",
    "cuboid",
    "prism",
    "sphere",
    "WingedgeError",
    "ObjError",
    "ValidationError",
    "QueryError",
    "SceneError",
    "BooleanError",
]


def _coords(array, name: str) -> np.ndarray:
    """An ``(n, 3)`` C-contiguous float64 copy-or-view of ``array``.

    Float and integer dtypes are converted (float32 and integers of up to 53
    bits convert exactly); anything else (complex, object, strings) and any
    other shape is a ``ValueError`` naming ``name``.
    """
    a = np.asarray(array)
    if a.dtype.kind not in "fiu":
        raise ValueError(f"{name} must be a float or integer array, got dtype {a.dtype}")
    if a.ndim != 2 or a.shape[1] != 3:
        raise ValueError(f"{name} must have shape (n, 3), got {a.shape}")
    return np.ascontiguousarray(a, dtype=np.float64)


def _point(p, name: str) -> Tuple[float, float, float]:
    a = np.asarray(p, dtype=np.float64)
    if a.shape != (3,):
        raise ValueError(f"{name} must have 3 coordinates, got shape {a.shape}")
    return (float(a[0]), float(a[1]), float(a[2]))


def _faces_flat(faces) -> Tuple[np.ndarray, np.ndarray]:
    """Face sizes and the flat index array of an ``(m, k)`` integer array or
    a sequence of index sequences."""
    if isinstance(faces, np.ndarray) and faces.ndim == 2:
        if faces.dtype.kind not in "iu":
            raise ValueError(f"faces must be an integer array, got dtype {faces.dtype}")
        m, k = faces.shape
        return np.full(m, k, dtype=np.int64), np.ascontiguousarray(faces, dtype=np.int64).ravel()
    sizes = []
    flat = []
    for i, face in enumerate(faces):
        f = np.asarray(face)
        if f.ndim != 1 or (f.size and f.dtype.kind not in "iu"):
            raise ValueError(f"faces[{i}] must be a sequence of integer indices")
        sizes.append(f.size)
        flat.append(f.astype(np.int64, copy=False))
    indices = np.concatenate(flat) if flat else np.zeros(0, dtype=np.int64)
    return np.asarray(sizes, dtype=np.int64), indices


class Solid:
    """A winged-edge solid (vertices, edges, faces linked by their wings).

    Build one with :func:`load_obj`, :meth:`Solid.from_arrays` or a builder
    (:func:`cube`, :func:`prism`, ...). Queries use an acceleration
    structure built on first use. A ``Solid`` pickles (as the soup it was
    built from, rebuilt identically), so it can be sent to worker processes.
    """

    __slots__ = ("_native",)

    def __init__(self, native: "_wingedge.NativeSolid"):
        self._native = native

    def __reduce__(self):
        return (_rebuild_solid, (*self._native._to_flat(), self._native.face_origins))

    # -- construction ---------------------------------------------------

    @classmethod
    def from_arrays(cls, vertices, faces) -> "Solid":
        """A solid from ``vertices`` ``(n, 3)`` and ``faces``: an ``(m, k)``
        integer array or a list of index sequences, each face
        counter-clockwise seen from outside. Raises ``ValidationError``
        naming the polygon when the faces cannot form a winged-edge solid
        (bad index, non-finite position, an edge of three faces, ...)."""
        v = _coords(vertices, "vertices")
        sizes, indices = _faces_flat(faces)
        return cls(_wingedge.NativeSolid._from_flat(v, sizes, indices))

    def to_arrays(self):
        """``(vertices, faces)``: vertices ``(n, 3)`` float64; faces an
        ``(m, k)`` int64 array when every face has ``k`` corners, else a list
        of int64 arrays. The faces and vertex order the solid was built from."""
        v, sizes, indices = self._native._to_flat()
        if sizes.size and np.all(sizes == sizes[0]):
            return v, indices.reshape(-1, int(sizes[0]))
        return v, np.split(indices, np.cumsum(sizes)[:-1]) if sizes.size else []

    # -- measures ---------------------------------------------------------

    vertex_count = property(lambda self: self._native.vertex_count, doc="Number of vertices.")
    edge_count = property(lambda self: self._native.edge_count, doc="Number of edges.")
    face_count = property(lambda self: self._native.face_count, doc="Number of faces.")
    is_closed = property(lambda self: self._native.is_closed, doc="Whether every edge has two faces.")
    volume = property(lambda self: self._native.volume, doc="Enclosed volume (rounded construction).")
    area = property(lambda self: self._native.area, doc="Total face area.")
    genus = property(
        lambda self: self._native.genus,
        doc="Summed genus of the shells; None when a shell has holes.",
    )
    shells = property(lambda self: self._native.shells, doc="Number of connected shells.")
    bounds = property(
        lambda self: np.array(self._native.bounds, dtype=np.float64),
        doc="Bounding box as a (2, 3) array: min corner, max corner.",
    )
    face_origins = property(
        lambda self: self._native.face_origins,
        doc="For a boolean's result, an (F, 2) int64 array, a row per face in "
        "face order: the operand's index (0 for self, 1 for other in "
        "a.union(other); the list index in combine) and the index of the "
        "operand's face this face is part of, in that operand's face order. "
        "None for any other solid (a scene's evaluation included).",
    )

    # -- booleans -----------------------------------------------------------

    def union(self, other: "Solid") -> "Solid":
        """``self ∪ other`` as a new valid solid, exact (see :func:`combine`).
        Also ``self | other``."""
        return Solid(_wingedge.boolean(self._native, _native_of(other, "other"), "union"))

    def intersection(self, other: "Solid") -> "Solid":
        """``self ∩ other`` as a new valid solid, exact. Also ``self & other``."""
        return Solid(_wingedge.boolean(self._native, _native_of(other, "other"), "intersection"))

    def difference(self, other: "Solid") -> "Solid":
        """``self − other`` as a new valid solid, exact. Also ``self - other``."""
        return Solid(_wingedge.boolean(self._native, _native_of(other, "other"), "difference"))

    def __or__(self, other):
        return self.union(other) if isinstance(other, Solid) else NotImplemented

    def __and__(self, other):
        return self.intersection(other) if isinstance(other, Solid) else NotImplemented

    def __sub__(self, other):
        return self.difference(other) if isinstance(other, Solid) else NotImplemented

    # -- queries ------------------------------------------------------------

    def classify(self, points, method: str = "parity") -> np.ndarray:
        """Where each point is: int8 ``1`` inside, ``0`` exactly on the
        boundary, ``-1`` outside (the sign of a signed distance that is
        positive inside, as trimesh's). Exact for every finite point.

        ``method``: ``"parity"`` (ray crossings, needs a closed solid),
        ``"normals"`` (convex solids only; anything else raises
        ``QueryError``) or ``"winding"`` (also for open surfaces)."""
        return self._native._classify(_coords(points, "points"), method)

    def contains(self, points) -> np.ndarray:
        """Boolean per point: inside or on the boundary (the solid is a
        closed set). Use :meth:`classify` to tell the boundary apart."""
        return self.classify(points) >= 0

    def winding_number(self, points) -> np.ndarray:
        """The generalized winding number of the surface around each point
        (float64; 1 inside and 0 outside a closed outward-oriented solid)."""
        return self._native._winding_number(_coords(points, "points"))

    def ray_cast(self, origins, directions):
        """First hits of rays ``origin + t * direction`` with ``t > 0``:
        ``(t, face, transition)``, float64 ``t`` (``inf`` for a miss), int64
        face index in the solid's face order (``-1`` for a miss), int8
        transition (``1`` entering, ``-1`` leaving, ``0`` miss)."""
        return self._native._ray_cast(_coords(origins, "origins"), _coords(directions, "directions"))

    def ray_crossings(self, origin, direction):
        """Every crossing of one ray: ``(origin_class, t, face, transition)``
        with ``origin_class`` as :meth:`classify` and the arrays as
        :meth:`ray_cast`, ascending in ``t``."""
        return self._native._ray_crossings(_point(origin, "origin"), _point(direction, "direction"))

    # -- interop -------------------------------------------------------------

    def triangles(self):
        """``(vertices, triangles)``: the vertices as :meth:`to_arrays` and
        an ``(t, 3)`` int64 array with every face triangulated exactly
        (constrained to the face's edges: no flipped or degenerate triangle).
        Raises ``ValidationError`` naming a face that is not a simple planar
        polygon."""
        return self._native._triangles()

    @classmethod
    def from_trimesh(cls, mesh) -> "Solid":
        """A solid from a ``trimesh.Trimesh`` (its vertices and triangles)."""
        return cls.from_arrays(np.asarray(mesh.vertices), np.asarray(mesh.faces))

    @classmethod
    def from_manifold(cls, manifold) -> "Solid":
        """A solid from a ``manifold3d.Manifold`` (its first three vertex
        properties are the positions, taken in float64)."""
        mesh = manifold.to_mesh64()
        vertices = np.asarray(mesh.vert_properties, dtype=np.float64)[:, :3]
        return cls.from_arrays(vertices, np.asarray(mesh.tri_verts, dtype=np.int64))

    def to_trimesh(self):
        """A ``trimesh.Trimesh`` of :meth:`triangles` (vertices kept as they
        are: ``process=False``). Needs trimesh installed."""
        import trimesh

        vertices, triangles = self.triangles()
        return trimesh.Trimesh(vertices=vertices, faces=triangles, process=False)

    def to_manifold(self):
        """A ``manifold3d.Manifold`` of :meth:`triangles`, in float64
        (``Mesh64``). Needs manifold3d installed; manifold3d's own status is
        raised as ``ValidationError`` when it refuses the mesh."""
        import manifold3d

        vertices, triangles = self.triangles()
        mesh = manifold3d.Mesh64(
            vert_properties=np.ascontiguousarray(vertices),
            tri_verts=np.ascontiguousarray(triangles, dtype=np.uint64),
        )
        manifold = manifold3d.Manifold(mesh)
        status = manifold.status()
        if status != manifold3d.Error.NoError:
            raise ValidationError(f"manifold3d refused the mesh: {status}")
        return manifold

    def __repr__(self) -> str:
        return repr(self._native)


class SoupWinding:
    """Inside/outside by the generalized winding number of any polygon soup,
    also one that cannot be a :class:`Solid` (an edge of three faces, faces
    wound against their neighbours), the way libigl's winding number works.

    Each polygon is fanned into triangles as a :class:`Solid` fans its
    faces. Exactly on a triangle is ``0``; when every edge is run as often
    one way as the other (:attr:`open_edges` is 0) the answer is the exact
    signed crossing count, otherwise a solid-angle sum above one half is
    inside. Near a face wound the wrong way that sum may say outside.
    Parity is undefined on such input and not offered.
    """

    __slots__ = ("_native",)

    def __init__(self, native: "_wingedge.NativeSoupWinding"):
        self._native = native

    @classmethod
    def from_arrays(cls, vertices, faces) -> "SoupWinding":
        """From ``vertices`` ``(n, 3)`` and ``faces`` (an ``(m, k)`` integer
        array or a list of index sequences). Raises ``ValidationError`` only
        for bad numbers: no face, a face of fewer than three corners, an
        index out of range, a non-finite position."""
        v = _coords(vertices, "vertices")
        sizes, indices = _faces_flat(faces)
        return cls(_wingedge.NativeSoupWinding._from_flat(v, sizes, indices))

    @classmethod
    def load_obj(cls, path, weld=None) -> "SoupWinding":
        """Reads an OBJ file (welded as :func:`load_obj` welds)."""
        return cls(_wingedge.NativeSoupWinding.load_obj(str(path), weld))

    polygon_count = property(lambda self: self._native.polygon_count, doc="Number of polygons.")
    open_edges = property(
        lambda self: self._native.open_edges,
        doc="Edges run more often one way than the other (0: a closed cycle).",
    )

    def classify(self, points) -> np.ndarray:
        """int8 per point: ``1`` inside, ``0`` on a triangle, ``-1`` outside."""
        return self._native._classify(_coords(points, "points"))

    def winding_number(self, points) -> np.ndarray:
        """The generalized winding number of the soup around each point."""
        return self._native._winding_number(_coords(points, "points"))

    def __repr__(self) -> str:
        return repr(self._native)


class Scene:
    """A CSG tree of meshes, half-spaces, boxes, spheres and cylinders (the
    JSON scene format of ``docs/csg.md``), answered by ray casting: exact
    point classes, first hits, spans, volume and images."""

    __slots__ = ("_native",)

    def __init__(self, native: "_wingedge.NativeScene"):
        self._native = native

    @classmethod
    def load(cls, path) -> "Scene":
        """Reads a scene file; mesh paths are relative to its folder. Raises
        ``SceneError`` naming the file and the JSON path."""
        return cls(_wingedge.NativeScene.load(str(path)))

    @classmethod
    def from_dict(cls, scene: dict, base=".") -> "Scene":
        """A scene from Python objects shaped like a scene file (dicts,
        lists, numbers, strings); mesh paths are relative to ``base``."""
        return cls(_wingedge.NativeScene.from_json(json.dumps(scene), str(base)))

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

    def volume(self, spacing: float) -> float:
        """The volume by ray integration on a grid of cells of side at most
        ``spacing`` (the closed form when the tree is one leaf that has one)."""
        volume, _, _, exact = self._native.volume(float(spacing))
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


def _rebuild_solid(vertices, sizes, indices, origins=None) -> Solid:
    """Unpickles a :class:`Solid` from the soup it was built from (and a
    boolean result's face origins)."""
    if sizes.size == 0:
        return Solid(_wingedge.NativeSolid._empty(origins is not None))
    return Solid(_wingedge.NativeSolid._from_flat(vertices, sizes, indices, origins))


def _native_of(solid, name: str) -> "_wingedge.NativeSolid":
    if not isinstance(solid, Solid):
        raise TypeError(f"{name} must be a wingedge.Solid, got {type(solid).__name__}")
    return solid._native


def combine(solids: Sequence[Solid], expression) -> Solid:
    """The regularized set ``expression`` of ``solids`` as one valid
    :class:`Solid`, evaluated in one exact pass: every solid's surface is cut
    by every other's, and no constructed point is rounded before the result
    is written.

    ``expression`` is an ``int`` naming a solid by its index in ``solids``,
    or a tuple ``(operation, x, y, ...)`` of ``"union"``, ``"intersection"``
    or ``"difference"`` and two or more sub-expressions, applied left to
    right: ``("difference", 0, ("union", 1, 2))`` is ``s0 − (s1 ∪ s2)``.
    A bad expression raises ``BooleanError`` naming the offending part as
    ``expression[2][0]``; an operand that is not a valid closed solid
    raises ``BooleanError`` naming its index and defects. The result's
    :attr:`Solid.face_origins` name operands by their index in ``solids``.
    The interpreter lock is released while the boolean runs."""
    natives = [_native_of(s, f"solids[{i}]") for i, s in enumerate(solids)]
    return Solid(_wingedge.combine(natives, expression))


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


def load_obj(path, weld=None, max_face_corners: Optional[int] = None) -> Solid:
    """Reads an OBJ file into a :class:`Solid`.

    ``weld``: ``None``/``"exact"`` merges bit-identical positions where that
    closes open edges (the default), ``"none"`` merges nothing, a number is a
    weld tolerance as a fraction of the bounding-box diagonal. Raises
    ``ObjError`` (file and line) for an unreadable file and
    ``ValidationError`` when the faces cannot form a winged-edge solid (use
    :func:`validate` to see every defect)."""
    return Solid(_wingedge.load_obj(str(path), weld, max_face_corners))


def validate(path_or_solid, weld=None, planarity: Optional[float] = None) -> Report:
    """Validates an OBJ file (a path) or a :class:`Solid`: every defect
    named and located, a graded verdict, counts and measures."""
    if isinstance(path_or_solid, Solid):
        if weld is not None:
            raise ValueError("weld applies to files; a Solid is already welded")
        return Report._from_json(_wingedge.validate_solid(path_or_solid._native, planarity))
    return Report._from_json(_wingedge.validate_path(str(path_or_solid), weld, planarity))


def builtin(name: str) -> Solid:
    """A built-in solid by name: ``tetrahedron``, ``cube``, ``octahedron``,
    ``dodecahedron``, ``icosahedron`` or ``prism`` (an L-shaped prism)."""
    return Solid(_wingedge.builtin(name))


def tetrahedron() -> Solid:
    """The regular tetrahedron with vertices (1,1,1), (1,−1,−1), (−1,1,−1), (−1,−1,1)."""
    return builtin("tetrahedron")


def cube() -> Solid:
    """The cube [−1, 1]³."""
    return builtin("cube")


def octahedron() -> Solid:
    """The regular octahedron with vertices ±x, ±y, ±z."""
    return builtin("octahedron")


def dodecahedron() -> Solid:
    """The regular dodecahedron (12 pentagons)."""
    return builtin("dodecahedron")


def icosahedron() -> Solid:
    """The regular icosahedron (20 triangles)."""
    return builtin("icosahedron")


def cuboid(min_corner, max_corner) -> Solid:
    """The axis-aligned box between two corners."""
    return Solid(_wingedge.cuboid(_point(min_corner, "min_corner"), _point(max_corner, "max_corner")))


def prism(profile, sweep) -> Solid:
    """A planar polygon ``(n, 3)`` swept along the vector ``sweep``."""
    return Solid(_wingedge.prism(_coords(profile, "profile"), _point(sweep, "sweep")))


def sphere(rings: int = 16) -> Solid:
    """A triangulated UV sphere of radius 1 with ``rings`` bands of latitude."""
    return Solid(_wingedge.sphere(int(rings)))
