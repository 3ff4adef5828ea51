"""wingedge: an exact B-rep polyhedron kernel (Baumgart's winged edge), from numpy.

Every inside/outside and ray decision is exact: signs come from exact
predicates, never from an epsilon. Arrays go in as ``(n, 3)`` coordinates and
come back as numpy arrays; batch calls release the interpreter lock and use
every core.

>>> import wingedge, numpy as np
>>> cube = wingedge.cube()
>>> cube.classify(np.array([[0.0, 0, 0], [1, 0, 0], [2, 0, 0]])).tolist()
[1, 0, -1]

The package is split by topic: ``_solid`` (solids, built-in solids,
``combine``), ``_scene``, ``_report`` (``validate``; ``Report`` and
``Violation`` are the native module's), ``_io`` and ``_arrays`` (the array
checks they share). Import from ``wingedge`` itself.
"""

from . import _wingedge
from ._io import load, load_obj, repair
from ._report import Report, Violation, render_defects, validate
from ._scene import Scene
from ._solid import (
    Solid,
    SoupWinding,
    _rebuild_solid,
    builtin,
    combine,
    cube,
    cuboid,
    dodecahedron,
    icosahedron,
    octahedron,
    prism,
    sphere,
    tetrahedron,
)
from ._wingedge import (
    BooleanError,
    FormatError,
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
    "load",
    "load_obj",
    "repair",
    "render_defects",
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
    "FormatError",
    "ObjError",
    "ValidationError",
    "QueryError",
    "SceneError",
    "BooleanError",
]

# The topic modules are private: their classes and functions say they are
# `wingedge`'s (in reprs, in help and in pickles), so a Solid pickles by
# reference to `wingedge._rebuild_solid`, as it did before the split.
for _obj in [globals()[name] for name in __all__] + [_rebuild_solid]:
    if _obj.__module__.startswith(__name__ + "._"):
        _obj.__module__ = __name__
del _obj
