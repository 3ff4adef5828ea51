"""Exact answers for a few points and rays, in rational arithmetic.

Used to settle the queries on which the libraries disagree, independently of
every library in the comparison (wingedge included): the mesh's `f64`
coordinates and the query's are converted to `fractions.Fraction` exactly,
and every sign and every intersection parameter below is computed without
rounding.

A float pass first discards the triangles a line certainly misses: for the
line `o + t d` and triangle `abc` the three signed volumes
`det(a-o, b-o, d)`, `det(b-o, c-o, d)`, `det(c-o, a-o, d)` must not have
opposite signs for the line to meet the closed triangle. A triangle is
dropped only when two of the float values have opposite signs and each is
larger than a bound (1e-9 times the product of the operand norms) that
covers the rounding error of the float evaluation many times over; every
other triangle is decided exactly.
"""
from fractions import Fraction

import numpy as np

SLACK = 1e-9


class Mesh:
    """A triangle mesh prepared for exact line queries."""

    def __init__(self, vertices, triangles):
        self.vertices = np.asarray(vertices, dtype=np.float64)
        self.triangles = np.asarray(triangles, dtype=np.int64)
        self.corners = [self.vertices[self.triangles[:, k]] for k in range(3)]
        self._exact_vertices = {}

    def _vertex(self, i):
        v = self._exact_vertices.get(i)
        if v is None:
            v = tuple(Fraction(float(x)) for x in self.vertices[i])
            self._exact_vertices[i] = v
        return v

    def candidates(self, origin, direction):
        """Indices of the triangles the line `origin + t direction` may meet."""
        o = np.asarray(origin, dtype=np.float64)
        d = np.asarray(direction, dtype=np.float64)
        rel = [c - o for c in self.corners]
        norms = [np.linalg.norm(r, axis=1) for r in rel]
        dn = np.linalg.norm(d)
        positive = np.zeros(len(self.triangles), dtype=bool)
        negative = np.zeros(len(self.triangles), dtype=bool)
        for i, j in ((0, 1), (1, 2), (2, 0)):
            s = np.cross(rel[i], rel[j]) @ d
            bound = SLACK * norms[i] * norms[j] * dn
            positive |= s > bound
            negative |= s < -bound
        return np.nonzero(~(positive & negative))[0]

    def exact_triangle(self, index):
        return [self._vertex(int(i)) for i in self.triangles[index]]


def _sub(p, q):
    return (p[0] - q[0], p[1] - q[1], p[2] - q[2])


def _det(u, v, w):
    return (u[0] * (v[1] * w[2] - v[2] * w[1])
            - u[1] * (v[0] * w[2] - v[2] * w[0])
            + u[2] * (v[0] * w[1] - v[1] * w[0]))


def _sign(x):
    return (x > 0) - (x < 0)


def line_meets_triangle(o, d, a, b, c):
    """How the line `o + t d` meets the closed triangle `abc`, exactly.

    Returns `None` when it misses, `("interior", t)` when it crosses the open
    triangle at parameter `t`, `("edge", t)` when it passes through an edge
    or a corner, and `("in_plane", None)` when the line lies in the
    triangle's plane and meets it.
    """
    ao, bo, co = _sub(a, o), _sub(b, o), _sub(c, o)
    signs = [_sign(_det(ao, bo, d)), _sign(_det(bo, co, d)), _sign(_det(co, ao, d))]
    if 1 in signs and -1 in signs:
        return None
    normal_dot_d = _det(_sub(b, a), _sub(c, a), d)  # (b-a) x (c-a) . d
    if normal_dot_d == 0:
        # Every sign is zero: the line is in the plane (whether it meets the
        # triangle there is not needed by the callers, which re-aim).
        return ("in_plane", None)
    t = _det(_sub(b, a), _sub(c, a), ao) / normal_dot_d
    return ("interior" if 0 not in signs else "edge", t)


def _fractions(v):
    return tuple(Fraction(float(x)) for x in v)


def classify_point(mesh, point, rng, attempts=20):
    """`"inside"`, `"outside"` or `"boundary"` for a closed mesh, by ray parity.

    The ray's direction is a random vector of small integers; a direction
    whose line passes through an edge, a corner or lies in a face's plane is
    replaced by another (the point itself on the surface is `"boundary"`).
    """
    p = _fractions(point)
    for _ in range(attempts):
        d_int = rng.integers(-1000, 1001, size=3)
        if not d_int.any():
            continue
        d = tuple(Fraction(int(x)) for x in d_int)
        crossings = 0
        clean = True
        for index in mesh.candidates(point, d_int.astype(np.float64)):
            met = line_meets_triangle(p, d, *mesh.exact_triangle(index))
            if met is None:
                continue
            kind, t = met
            if t == 0 and kind != "in_plane":
                return "boundary"
            if kind != "interior":
                clean = False
                continue
            crossings += t > 0
        if clean:
            return "inside" if crossings % 2 else "outside"
    raise RuntimeError("no generic direction found for point %r" % (point,))


def first_hit(mesh, origin, direction):
    """The exact smallest `t > 0` at which the ray meets the closed surface.

    Returns `(t, how)` with `t` a `Fraction` (or `None` for a miss) and
    `how` = `"interior"` or `"edge"` (the ray passes exactly through an edge
    or a corner there). Triangles whose plane contains the ray are reported
    as `"in_plane"` hits with `t = None` (never seen on these inputs).
    """
    o, d = _fractions(origin), _fractions(direction)
    best, how = None, None
    for index in mesh.candidates(origin, direction):
        met = line_meets_triangle(o, d, *mesh.exact_triangle(index))
        if met is None:
            continue
        kind, t = met
        if kind == "in_plane":
            return None, "in_plane"
        if t > 0 and (best is None or t < best):
            best, how = t, kind
    return best, how
