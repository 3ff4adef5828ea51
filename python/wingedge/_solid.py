"""Solids: :class:`Solid`, :class:`SoupWinding`, the built-in solids and
:func:`combine`."""

from __future__ import annotations

import warnings
from typing import Optional, Sequence

import numpy as np

from . import _wingedge
from ._arrays import _coords, _faces_flat, _point
from ._wingedge import ValidationError


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

    def save(self, path, format: Optional[str] = None) -> int:
        """Writes the solid to ``path`` (atomically: a failed write leaves
        the old file) in ``format`` (default: by the extension): ``"obj"``,
        ``"ply"`` (binary ``double``), ``"off"`` and ``"3mf"`` keep every
        ``f64`` bit; ``"stl"`` (binary), ``"gltf"`` and ``"glb"`` hold 32-bit
        floats, and a ``UserWarning`` says how many coordinates rounding
        changed. Returns that number (0 for the exact formats). Raises
        ``FormatError`` for a file that cannot be written or a coordinate
        beyond the range of f32."""
        rounded, coordinates = self._native._save(str(path), format)
        if rounded:
            warnings.warn(
                f"{path}: {rounded} of {coordinates} coordinates changed when rounded "
                "to f32 (obj, ply, off and 3mf keep every f64 bit)",
                UserWarning,
                stacklevel=2,
            )
        return rounded

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


def combine(solids: Sequence[Solid], expression, *, resolve: bool = False) -> Solid:
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
    raises ``BooleanError`` naming its index and defects, unless
    ``resolve`` is true: then such an operand (self-intersecting or
    overlapping shells) is taken as the region where its winding number is
    positive, as :func:`repair` makes it. The result's
    :attr:`Solid.face_origins` name operands by their index in ``solids``.
    The interpreter lock is released while the boolean runs."""
    natives = [_native_of(s, f"solids[{i}]") for i, s in enumerate(solids)]
    return Solid(_wingedge.combine(natives, expression, resolve))


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
