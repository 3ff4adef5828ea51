"""Type stub of the native module ``wingedge._wingedge`` (built from
``python/src`` by maturin). The public API is the ``wingedge`` package,
which wraps these classes and checks array shapes and dtypes first; use it
rather than this module."""

from os import PathLike
from typing import Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

_Path = Union[str, PathLike[str]]
_Vec3 = Tuple[float, float, float]
_F64 = npt.NDArray[np.float64]
_I64 = npt.NDArray[np.int64]
_I8 = npt.NDArray[np.int8]

class WingedgeError(ValueError):
    """Base class of every wingedge error."""

class FormatError(WingedgeError):
    """A mesh file could not be read or written: the file and the place in it."""

class ObjError(FormatError):
    """An OBJ file could not be read: the message names the file and line."""

class ValidationError(WingedgeError):
    """Input that cannot be a winged-edge solid: the message names the elements."""

class QueryError(WingedgeError):
    """A query that cannot be answered: the message names the query's index."""

class BooleanError(WingedgeError):
    """A boolean that produced no solid: an invalid operand (named, with its
    defects), a result pinched along an edge, or a bad set expression (the
    offending part named by its place)."""

class SceneError(WingedgeError):
    """A scene file or document that cannot be loaded: the message names the
    file and the JSON path."""

class NativeSolid:
    """A winged-edge solid with its exact query accel (built on first use)."""

    @staticmethod
    def _from_flat(
        vertices: _F64, sizes: _I64, indices: _I64, origins: Optional[_I64] = None
    ) -> NativeSolid:
        """A solid from vertices ``(n, 3)``, face sizes ``(m,)`` and the flat
        face index array (and a boolean result's ``(m, 2)`` face origins);
        raises ``ValidationError`` naming the polygon."""
    @staticmethod
    def _empty(origins: bool) -> NativeSolid:
        """The empty solid (with an empty origins array when ``origins``)."""
    def _save(self, path: _Path, format: Optional[str] = None) -> Tuple[int, int]:
        """Writes the solid; returns (coordinates rounded to f32, coordinates)."""
    def _to_flat(self) -> Tuple[_F64, _I64, _I64]:
        """The soup the solid was built from: vertices, face sizes, indices."""
    def _triangles(self) -> Tuple[_F64, _I64]:
        """Vertices ``(n, 3)`` and every face triangulated exactly ``(t, 3)``."""
    def _classify(self, points: _F64, method: str) -> _I8:
        """``1`` inside, ``0`` on the boundary, ``-1`` outside, per point."""
    def _winding_number(self, points: _F64) -> _F64:
        """Generalized winding number per point."""
    def _ray_cast(self, origins: _F64, directions: _F64) -> Tuple[_F64, _I64, _I8]:
        """First hits: ``t`` (inf for a miss), face (-1), transition (0)."""
    def _ray_crossings(self, origin: _Vec3, direction: _Vec3) -> Tuple[int, _F64, _I64, _I8]:
        """Every crossing of one ray, ascending in ``t``."""
    @property
    def vertex_count(self) -> int: ...
    @property
    def edge_count(self) -> int: ...
    @property
    def face_count(self) -> int: ...
    @property
    def is_closed(self) -> bool: ...
    @property
    def volume(self) -> float: ...
    @property
    def area(self) -> float: ...
    @property
    def genus(self) -> Optional[int]: ...
    @property
    def shells(self) -> int: ...
    @property
    def bounds(self) -> Tuple[_Vec3, _Vec3]: ...
    @property
    def path(self) -> Optional[str]: ...
    @property
    def face_origins(self) -> Optional[_I64]:
        """A boolean result's ``(F, 2)`` rows ``[operand, operand face]``, else None."""

class NativeSoupWinding:
    """A polygon soup's fanned triangles and their accel (need not be a solid)."""

    @staticmethod
    def _from_flat(vertices: _F64, sizes: _I64, indices: _I64) -> NativeSoupWinding:
        """From vertices ``(n, 3)``, face sizes ``(m,)`` and the flat face
        index array; ``ValidationError`` for bad numbers only."""
    @staticmethod
    def load_obj(path: _Path, weld: Optional[object] = None) -> NativeSoupWinding:
        """Reads an OBJ file into a soup; ``ObjError`` names the file and line."""
    @property
    def polygon_count(self) -> int: ...
    @property
    def open_edges(self) -> int: ...
    def _classify(self, points: _F64) -> _I8:
        """``1`` inside, ``0`` on a triangle, ``-1`` outside, per point."""
    def _winding_number(self, points: _F64) -> _F64:
        """Generalized winding number per point."""

class NativeScene:
    """A CSG scene (the JSON scene format) with its leaves' accels."""

    @staticmethod
    def load(path: _Path, allow_paths: Optional[Sequence[_Path]] = None) -> NativeScene:
        """Loads a scene file; leaves must resolve inside its folder, the
        working directory or a folder of ``allow_paths``."""
    @staticmethod
    def from_json(
        text: str, base: _Path, allow_paths: Optional[Sequence[_Path]] = None
    ) -> NativeScene:
        """A scene from JSON text; relative paths resolve against ``base``,
        and leaves must resolve inside it, the working directory or a folder
        of ``allow_paths``."""
    @property
    def bounds(self) -> Tuple[_Vec3, _Vec3]: ...
    @property
    def leaf_count(self) -> int: ...
    def _classify(self, points: _F64) -> _I8:
        """``1`` inside, ``0`` on the boundary, ``-1`` outside, per point."""
    def _first_hit(self, origins: _F64, directions: _F64) -> Tuple[_F64, _I64]:
        """First hits: ``t`` (inf for a miss) and the leaf hit (-1)."""
    def _spans(self, origin: _Vec3, direction: _Vec3) -> _F64:
        """``(n, 2)`` intervals ``[t_enter, t_leave]`` of one ray inside."""
    def volume(
        self, spacing: Optional[float] = None
    ) -> Tuple[float, float, int, Optional[float], Optional[str]]:
        """``(volume, spacing used, rays cast, closed form or None, warning
        or None)``; no spacing: the default grid."""
    def render(self, width: int, height: int) -> npt.NDArray[np.uint8]:
        """A ray-cast image ``(height, width, 3)``."""
    def evaluate(self, tolerance: Optional[float] = None) -> NativeSolid:
        """The tree as one valid solid by exact booleans."""

class Violation:
    """One broken rule, located: ``line`` is the OBJ line of the first
    element named, ``vertices``/``faces`` 0-based element ids. Immutable,
    compared by value, picklable."""

    @property
    def rule(self) -> str:
        """The rule broken, by name (a key of ``Report.counts``)."""
    @property
    def message(self) -> str: ...
    @property
    def line(self) -> Optional[int]: ...
    @property
    def lines(self) -> List[int]: ...
    @property
    def vertices(self) -> List[int]: ...
    @property
    def faces(self) -> List[int]: ...
    @property
    def value(self) -> Optional[float]:
        """A measured quantity (deviation, signed volume, edge count), if any."""
    def to_json(self) -> str:
        """The violation as in ``wingedge validate --json``."""
    @classmethod
    def _from_json(cls, text: str) -> Violation:
        """A violation from the text of ``to_json`` (unpickling)."""

class Report:
    """What validation found: the content of ``wingedge validate --json``
    for one file, as typed fields. Immutable, compared by value, picklable.
    Measures that overflow ``f64`` are None and named in ``overflow``."""

    @property
    def valid(self) -> bool: ...
    @property
    def verdict(self) -> str: ...
    @property
    def validity(self) -> str: ...
    @property
    def vertices(self) -> int: ...
    @property
    def edges(self) -> int: ...
    @property
    def faces(self) -> int: ...
    @property
    def shells(self) -> int: ...
    @property
    def holes(self) -> int: ...
    @property
    def genus(self) -> Optional[int]: ...
    @property
    def volume(self) -> Optional[float]: ...
    @property
    def area(self) -> Optional[float]: ...
    @property
    def not_built(self) -> Optional[str]: ...
    @property
    def counts(self) -> Dict[str, int]:
        """Violations per rule, every rule named."""
    @property
    def violations(self) -> List[Violation]: ...
    @property
    def shell_details(self) -> List[dict]:
        """Per-shell measures, a dict each."""
    @property
    def file(self) -> Optional[str]: ...
    @property
    def weld(self) -> Optional[dict]:
        """For a file: ``mode``, ``merged`` and the ``refused`` merges."""
    @property
    def overflow(self) -> List[str]:
        """The measures too large for ``f64``, reported as None."""
    def to_json(self) -> str:
        """The element ``wingedge validate --json`` prints for the file."""
    def to_dict(self) -> dict:
        """``json.loads(self.to_json())``."""
    @classmethod
    def _from_json(cls, text: str) -> Report:
        """A report from the text of ``to_json`` (unpickling)."""

def load_obj(path: _Path, weld: Optional[object] = None, max_face_corners: Optional[int] = None) -> NativeSolid:
    """Reads an OBJ file into a solid; ``ObjError`` names the file and line."""
def load(
    path: _Path,
    weld: Optional[object] = None,
    max_face_corners: Optional[int] = None,
    format: Optional[str] = None,
) -> NativeSolid:
    """Reads a mesh file of any format into a solid."""
def builtin(name: str) -> NativeSolid:
    """A built-in solid by name."""
def cuboid(min: _Vec3, max: _Vec3) -> NativeSolid:
    """The axis-aligned box between two corners."""
def prism(profile: Sequence[_Vec3], sweep: _Vec3) -> NativeSolid:
    """A planar polygon swept along a vector."""
def sphere(rings: int) -> NativeSolid:
    """A triangulated UV sphere of radius 1."""
def boolean(a: NativeSolid, b: NativeSolid, operation: str, resolve: bool = False) -> NativeSolid:
    """``a op b`` for ``"union"``, ``"intersection"`` or ``"difference"``."""
def combine(solids: Sequence[NativeSolid], expression: object, resolve: bool = False) -> NativeSolid:
    """A set expression of nested tuples over indices into ``solids``."""
def repair_path(
    path: _Path,
    max_hole_edges: Optional[int] = None,
    weld: Optional[object] = None,
    format: Optional[str] = None,
) -> Tuple[Optional[NativeSolid], Dict[str, object]]:
    """A mesh file made a valid solid, and what changed."""
def repair_flat(
    vertices: npt.NDArray[np.float64],
    sizes: npt.NDArray[np.int64],
    indices: npt.NDArray[np.int64],
    max_hole_edges: Optional[int] = None,
) -> Tuple[Optional[NativeSolid], Dict[str, object]]:
    """A soup made a valid solid, and what changed."""
def validate_path(
    path: _Path,
    weld: Optional[object] = None,
    planarity: Optional[float] = None,
    format: Optional[str] = None,
) -> Report:
    """The report ``validate --json`` prints for a file."""
def validate_solid(solid: NativeSolid, planarity: Optional[float] = None) -> Report:
    """The report for a solid's source soup."""
def render_defects_path(
    path: _Path,
    width: int = 800,
    height: int = 600,
    report: Optional[Report] = None,
    weld: Optional[object] = None,
    planarity: Optional[float] = None,
    format: Optional[str] = None,
) -> npt.NDArray[np.uint8]:
    """A file's defect picture, ``(height, width, 3)`` uint8."""
def render_defects_solid(
    solid: NativeSolid,
    width: int = 800,
    height: int = 600,
    report: Optional[Report] = None,
    planarity: Optional[float] = None,
) -> npt.NDArray[np.uint8]:
    """A solid's source soup's defect picture, ``(height, width, 3)`` uint8."""
