"""The cases of manifold's boolean tests as trees for manifold_cases.py:
each test's operands built with manifold3d's own constructors and
transforms, read from manifold's test/models, or parsed out of its test
source, and the boolean tree the test evaluates."""
import math, os

import numpy as np
import manifold3d as m3d

M = m3d.Manifold
K_PRECISION = 1e-12  # manifold's kPrecision (src/utils.h)


# ---------------------------------------------------------------- trees
# A tree is ("leaf", Manifold) | ("obj", file name in --models)
# | (op, [trees]) with op in union/difference/intersection
# | ("xf", function Manifold -> Manifold, tree).

def leaf(m): return ("leaf", m)
def obj(name): return ("obj", name)
def U(*c): return ("union", list(c))
def D(*c): return ("difference", list(c))
def I(*c): return ("intersection", list(c))
def XF(f, t): return ("xf", f, t)


def cube(size=(1, 1, 1), center=False):
    if not isinstance(size, (tuple, list)):
        size = (size,) * 3
    return M.cube(tuple(float(s) for s in size), center)


def mesh(verts, tris):
    return M(m3d.Mesh64(vert_properties=np.array(verts, dtype=np.float64).reshape(-1, 3),
                        tri_verts=np.array(tris, dtype=np.uint32).reshape(-1, 3)))


def read_obj(path):
    verts, tris = [], []
    with open(path) as f:
        for line in f:
            p = line.split()
            if not p:
                continue
            if p[0] == "v":
                verts.append([float(x) for x in p[1:4]])
            elif p[0] == "f":
                idx = [int(x.split("/")[0]) - 1 for x in p[1:]]
                for k in range(1, len(idx) - 1):  # manifold reads triangles only
                    tris.append([idx[0], idx[k], idx[k + 1]])
    return mesh(verts, tris)


def cs(polys):
    return m3d.CrossSection([[tuple(map(float, p)) for p in poly] for poly in polys])


# ---------------------------------------------------------------- the cases

def tet():
    return M.tetrahedron()


def perturb2():
    c = cube(2, True)
    g = c.to_mesh64()
    V, T = np.asarray(g.vert_properties)[:, :3], np.asarray(g.tri_verts)
    parts = [leaf(c.rotate((5, 10, 15)))]
    for tri in T:
        tv = [4, 2, 0, 1, 3, 5]
        pv = []
        for v0 in range(3):
            v1 = (v0 + 1) % 3
            a, b = int(tri[v0]), int(tri[v1])
            if b > a:
                tv += [2 * v0, 2 * v1, 2 * v1 + 1, 2 * v0, 2 * v1 + 1, 2 * v0 + 1]
            else:
                tv += [2 * v0, 2 * v1, 2 * v0 + 1, 2 * v1, 2 * v1 + 1, 2 * v0 + 1]
            pv += list(V[a]) + list(2 * V[a])
        parts.append(leaf(mesh(pv, tv).rotate((5, 10, 15))))
    return U(*parts)


def perturb3():
    n, alpha = 16, 90.0 / 16
    c = cube(1, True)
    gear = U(*[leaf(c.rotate((0, 0, alpha * i))) for i in range(n)])
    return D(XF(lambda m: m.scale((2, 2, 1)), gear), gear)


def cylinders():
    rod = M.cylinder(1.0, 0.4, -1.0, 12)
    a1 = [[0, 0, 1, 3, -1, 0, 0, 3, 0, -1, 0, 6], [0, 0, 1, 2, -1, 0, 0, 3, 0, -1, 0, 8],
          [0, 0, 1, 1, -1, 0, 0, 2, 0, -1, 0, 7], [1, 0, 0, 3, 0, 1, 0, 2, 0, 0, 1, 6],
          [0, 0, 1, 3, -1, 0, 0, 3, 0, -1, 0, 7], [0, 0, 1, 1, -1, 0, 0, 3, 0, -1, 0, 7],
          [1, 0, 0, 3, 0, 0, 1, 4, 0, -1, 0, 6], [1, 0, 0, 4, 0, 0, 1, 4, 0, -1, 0, 6]]
    a2 = [[1, 0, 0, 3, 0, 0, 1, 2, 0, -1, 0, 6], [1, 0, 0, 4, 0, 1, 0, 3, 0, 0, 1, 6],
          [0, 0, 1, 2, -1, 0, 0, 2, 0, -1, 0, 7], [1, 0, 0, 3, 0, 1, 0, 3, 0, 0, 1, 7],
          [1, 0, 0, 2, 0, 1, 0, 3, 0, 0, 1, 7], [1, 0, 0, 1, 0, 1, 0, 3, 0, 0, 1, 7],
          [1, 0, 0, 3, 0, 1, 0, 4, 0, 0, 1, 7], [1, 0, 0, 3, 0, 1, 0, 5, 0, 0, 1, 6],
          [0, 0, 1, 3, -1, 0, 0, 4, 0, -1, 0, 6]]
    rods = lambda arrs: [leaf(rod.transform(np.array(a, dtype=float).reshape(3, 4))) for a in arrs]
    return U(U(*rods(a1)), U(*rods(a2)))


def spiral():
    d = 2

    def rec(k, r, add):
        rot = 360.0 / (math.pi * r * 2) * d
        r_next = r + add / 360 * rot
        c = leaf(cube(1, True).translate((0, r, 0)))
        if k > 0:
            return U(XF(lambda m, rot=rot: m.rotate((0, 0, rot)), rec(k - 1, r_next, add)), c)
        return c
    return rec(120, 25, 2)


def gyroid():
    def sdf(x, y, z):
        p = (x, y, z)
        bound = min(min(p), min(2 * math.pi - q for q in p))
        g = math.cos(x) * math.sin(y) + math.cos(y) * math.sin(z) + math.cos(z) * math.sin(x)
        return min(g, bound)
    two = 2 * math.pi
    return M.level_set(sdf, [0, 0, 0, two, two, two], 0.5).simplify(0.0)


def subtract_meshes():
    tris = [0, 1, 2, 2, 3, 0, 4, 5, 6, 5, 4, 7, 6, 2, 1, 6, 5, 2, 5, 3, 2, 5, 7, 3, 7, 0, 3, 7, 4, 0, 4, 1, 0, 4, 6, 1]
    first = mesh([0, 0, 0, 1540, 0, 0, 1540, 70, 0, 0, 70, 0, 0, 0, -278.282, 1540, 70, -278.282,
                  1540, 0, -278.282, 0, 70, -278.282], tris)
    second = mesh([2.04636e-12, 70, 50000, 2.04636e-12, -1.27898e-13, 50000, 1470, -1.27898e-13, 50000,
                   1540, 70, 50000, 2.04636e-12, 70, -28.2818, 1470, -1.27898e-13, 0,
                   2.04636e-12, -1.27898e-13, 0, 1540, 70, -28.2818], tris)
    return D(leaf(first), leaf(second))


def close():
    a = M.sphere(10, 256)
    bb = a.bounding_box()
    eps = K_PRECISION * max(abs(x) for x in bb)  # manifold's epsilon: kPrecision times the box scale
    return I(*[leaf(a)] + [leaf(a.translate((eps / 10 * i, 0, 0))) for i in range(10)])


def meshgl_from_source(text, begin, end, var):
    """The MeshGL `var` built field by field in manifold's test source between
    the markers `begin` and `end` (numProp, vertProperties, triVerts and the
    merge vectors; other fields are properties, not geometry)."""
    import re
    body = text[text.index(begin):]
    body = body[:body.index(end)]
    body = re.sub(r"//[^\n]*", "", body)

    def field(name):
        m = re.search(r"\b%s\.%s\s*=\s*(\{[^}]*\}|[^;]*);" % (var, name), body)
        return [float(x) for x in re.findall(r"-?\d+(?:\.\d*)?(?:[eE][+-]?\d+)?", m.group(1))] if m else []
    n = int(field("numProp")[0])
    props = np.array(field("vertProperties"), dtype=np.float64).reshape(-1, n)
    g = m3d.Mesh64(vert_properties=props, tri_verts=np.array(field("triVerts"), dtype=np.uint32).reshape(-1, 3),
                   merge_from_vert=np.array(field("mergeFromVert"), dtype=np.uint32),
                   merge_to_vert=np.array(field("mergeToVert"), dtype=np.uint32))
    return M(g)


def source_cases(models):
    """The tests whose operands are written out in boolean_complex_test.cpp,
    when that file is in the models folder."""
    path = os.path.join(models, "boolean_complex_test.cpp")
    if not os.path.exists(path):
        return
    text = open(path).read()
    a = meshgl_from_source(text, "TEST(BooleanComplex, InterpolatedNormals)", "Manifold aManifold(a)", "a")
    b = meshgl_from_source(text, "TEST(BooleanComplex, InterpolatedNormals)", "Manifold aManifold(a)", "b")
    yield "InterpolatedNormals", "BooleanComplex.InterpolatedNormals", D(leaf(a), leaf(b))
    r0 = meshgl_from_source(text, "MeshGL mgl_0()", "return m;", "m")
    r1 = meshgl_from_source(text, "MeshGL mgl_1()", "return m;", "m")
    yield "Ring", "BooleanComplex.Ring", D(leaf(r0), leaf(r1))


def cases(models):
    c1, t = cube(), tet()
    blk = D(leaf(cube(1, True)), leaf(M.cylinder(1, 0.5)))
    corner = mesh([0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1], [2, 0, 1, 0, 3, 1, 2, 3, 0, 3, 2, 1])
    big = M.extrude(cs([[(0, 2), (2, 0), (4, 2), (2, 4)], [(1, 2), (2, 3), (3, 2), (2, 1)]]), 1.0)
    little = M.extrude(cs([[(2, 1), (3, 2), (2, 3), (1, 2)]]), 1.0).translate((0, 0, 1))
    punch = M.extrude(cs([[(1, 2), (2, 2), (2, 3)]]), 1.0).translate((0, 0, 1))
    cyl = M.cylinder(1.0, 1.0)
    scale = 100 * K_PRECISION
    big3 = 1000.0
    dist = big3 * (1 - K_PRECISION / 2)
    m1, m2, m4 = cube((1, 1, 1)), cube((2, 1, 1)).translate((1, 0, 0)), cube((4, 1, 1)).translate((3, 0, 0))
    m3, m7 = cube((3, 1, 1)), cube((7, 1, 1))
    e1, e2, e3 = M.cylinder(50, 50), M.cylinder(60, 30), M.cylinder(60, 40).mirror((0, 0, 1))
    e4 = XF(lambda m: m.mirror((0, 0, 1)), U(leaf(e1), leaf(e2)))
    bcube = cube((100, 100, 1))
    bcyl = [M.cylinder(1, 30).translate((-10, 30, 0)), M.cylinder(1, 20).translate((110, 20, 0)),
            M.cylinder(1, 40).translate((50, 110, 0))]
    cube_stl = cube(1, True)
    sph = M.sphere(60)
    s12 = M.sphere(1.0, 12)
    ext = M.extrude(cube(2, True).slice(0.0), 2, 0, 0, (2, 2))
    yield "Tetra", "Boolean.Tetra", D(leaf(t.translate((0.5, 0.5, 0.5))), leaf(t))
    yield "MeshGLRoundTrip", "Boolean.MeshGLRoundTrip", U(leaf(cube(2)), leaf(cube(2).translate((1, 1, 0))))
    yield "Normals", "Boolean.Normals", D(leaf(cube_stl.scale((100, 100, 100))), D(
        leaf(sph.rotate((180, 0, 0))), leaf(sph.scale((0.5, 0.5, 0.5)).rotate((90, 0, 0)).translate((40, 40, 40)))))
    yield "MissingNormals", "Boolean.MissingNormals", U(leaf(cube(1, True)), leaf(cube(2, True).translate((0, 0, -1))))
    yield "EmptyOriginal", "Boolean.EmptyOriginal", D(leaf(t), leaf(c1.translate((3, 4, 5))))
    yield "Mirrored", "Boolean.Mirrored", D(leaf(c1.scale((1, -1, 1))), leaf(c1.scale((0.5, -1, 0.5))))
    yield "Cubes", "Boolean.Cubes", U(leaf(cube((1.2, 1, 1), True).translate((0, -0.5, 0.5))),
                                      leaf(cube((1, 0.8, 0.5)).translate((-0.5, 0, 0.5))),
                                      leaf(cube((1.2, 0.1, 0.5)).translate((-0.6, -0.1, 0))))
    yield "Cubes2", "Boolean.Cubes2", U(leaf(c1), leaf(c1.rotate((0, 0, 45))))
    half = [leaf(cube(1, True)), leaf(cube(1, True).translate((0.5, 0, 0)))]
    yield "DeterminismSimpleSubtract", "Boolean.DeterminismSimpleSubtract", D(*half)
    yield "DeterminismSimpleUnion", "Boolean.DeterminismSimpleUnion", U(*half)
    yield "DeterminismSimpleIntersect", "Boolean.DeterminismSimpleIntersect", I(*half)
    r10 = c1.refine(10)
    yield "Simplify", "Boolean.Simplify", U(leaf(r10), leaf(r10.translate((1, 0, 0))))
    yield "SimplifyCracks", "Boolean.SimplifyCracks (the union, before refine and warp)", U(
        leaf(M.cylinder(2, 50, 50, 180).rotate((-89.999999999999, 0, 0)).translate((50, 0, 50))),
        leaf(cube((100, 2, 50))))
    yield "NoRetainedVerts", "Boolean.NoRetainedVerts", I(leaf(cube(1, True)), leaf(M.sphere(1, 4)))
    yield "PropsMismatch", "Boolean.PropsMismatch", U(leaf(M.cylinder(1, 1)), leaf(c1.translate((50, 0, 0))))
    yield "UnionDifference", "Boolean.UnionDifference", U(blk, XF(lambda m: m.translate((0, 0, 1)), blk))
    two = U(leaf(c1), leaf(c1))
    yield "TreeTransforms", "Boolean.TreeTransforms", U(XF(lambda m: m.translate((1, 0, 0)), two), two)
    yield "CreatePropertiesSlow", "Boolean.CreatePropertiesSlow", U(
        leaf(M.sphere(10, 1024)), leaf(M.sphere(10, 1024).translate((5, 0, 0))))
    yield "SimpleProperties", "Boolean.SimpleProperties", U(leaf(cube(2, True)), leaf(ext))
    yield "SelfSubtract", "Boolean.SelfSubtract", D(leaf(c1), leaf(c1))
    yield "Perturb", "Boolean.Perturb", D(leaf(corner), leaf(corner))
    yield "Perturb1", "Boolean.Perturb1", D(U(leaf(big), leaf(little)), leaf(punch))
    yield "Perturb2", "Boolean.Perturb2", perturb2()
    yield "Perturb3", "Boolean.Perturb3 (nastyGear)", perturb3()
    yield "Coplanar", "Boolean.Coplanar", D(leaf(cyl), leaf(cyl.scale((0.8, 0.8, 1.0)).rotate((0, 0, 185))))
    yield "MultiCoplanar", "Boolean.MultiCoplanar", D(D(leaf(c1), leaf(c1.translate((0.3, 0.3, 0)))),
                                                      leaf(c1.translate((-0.3, -0.3, 0))))
    yield "AlmostCoplanar", "Boolean.AlmostCoplanar", U(
        leaf(t), leaf(t.rotate((0.001, -0.08472872823860228, 0.055910459615905288))), leaf(t))
    yield "FaceUnion", "Boolean.FaceUnion", U(leaf(c1), leaf(c1.translate((1, 0, 0))))
    yield "EdgeUnion", "Boolean.EdgeUnion", U(leaf(c1), leaf(c1.translate((1, 1, 0))))
    yield "EdgeUnion2", "Boolean.EdgeUnion2", U(leaf(t.translate((0, 0, -1))), leaf(t.translate((0, 0, 1)).rotate((0, 0, 90))))
    yield "CornerUnion", "Boolean.CornerUnion", U(leaf(c1), leaf(c1.translate((1, 1, 1))))
    oct_ = M.sphere(1, 4).translate((0, 0, 1))
    yield "Split.first", "Boolean.Split (cube ∩ octahedron)", I(leaf(cube(2, True)), leaf(oct_))
    yield "Split.second", "Boolean.Split (cube − octahedron)", D(leaf(cube(2, True)), leaf(oct_))
    yield "Vug", "Boolean.Vug", D(leaf(cube(4, True)), leaf(c1))
    yield "Winding", "Boolean.Winding", I(leaf(cube(1, True)), U(leaf(cube(3, True)), leaf(cube(2, True))))
    far = c1.scale((2, 2, 2)).translate((3, 0, 0))
    yield "NonIntersecting.union", "Boolean.NonIntersecting", U(leaf(c1), leaf(far))
    yield "NonIntersecting.difference", "Boolean.NonIntersecting", D(leaf(c1), leaf(far))
    yield "NonIntersecting.intersection", "Boolean.NonIntersecting", I(leaf(c1), leaf(far))
    tiny = c1.scale((scale,) * 3).translate((100, 0, 0))
    yield "Precision.1", "Boolean.Precision (cube + cube·1e-10 at 100)", U(leaf(c1), leaf(tiny))
    yield "Precision.2", "Boolean.Precision (… + cube·2e-10 at 100)", U(
        leaf(c1), leaf(tiny), leaf(c1.scale((2 * scale,) * 3).translate((100, 0, 0))))
    k = cube(big3)
    yield "Precision2.1", "Boolean.Precision2 (overlap 5e-10)", I(leaf(k), leaf(k.translate((-dist,) * 3)))
    yield "Precision2.2", "Boolean.Precision2 (overlap 1.5e-9)", I(
        leaf(k), leaf(k.translate((-dist,) * 3).translate((big3 * K_PRECISION,) * 3)))
    yield "SimpleCubeRegression", "Boolean.SimpleCubeRegression", D(U(
        leaf(c1.rotate((-0.10000000000000001, 0.10000000000000001, -1.0))), leaf(c1)),
        leaf(c1.rotate((-0.10000000000000001, -0.10000000000066571, -1.0))))
    yield "BatchBoolean.intersect", "Boolean.BatchBoolean", I(leaf(bcube), *[leaf(c) for c in bcyl])
    yield "BatchBoolean.add", "Boolean.BatchBoolean", U(leaf(bcube), *[leaf(c) for c in bcyl])
    yield "BatchBoolean.subtract", "Boolean.BatchBoolean", D(leaf(bcube), *[leaf(c) for c in bcyl])
    # boolean_complex_test.cpp
    yield "Sphere", "BooleanComplex.Sphere", D(leaf(s12), leaf(s12.translate((0.5, 0.5, 0.5))))
    g = gyroid()
    yield "MeshRelation", "BooleanComplex.MeshRelation (gyroid union)", U(leaf(g), leaf(g.translate((2, 2, 2))))
    yield "Cylinders", "BooleanComplex.Cylinders", cylinders()
    yield "Subtract", "BooleanComplex.Subtract", subtract_meshes()
    yield "Close", "BooleanComplex.Close (^ is intersection)", close()
    for name, tree in [("m1^m2", I(leaf(m1), leaf(m2))), ("m1+m2+m4", U(leaf(m1), leaf(m2), leaf(m4))),
                       ("m1+m2-m4", D(U(leaf(m1), leaf(m2)), leaf(m4))),
                       ("m1+(m2^m4)", U(leaf(m1), I(leaf(m2), leaf(m4)))), ("m7^m4", I(leaf(m7), leaf(m4))),
                       ("m7^m3^m1", I(leaf(m7), leaf(m3), leaf(m1))), ("m7^(m1+m2)", I(leaf(m7), U(leaf(m1), leaf(m2)))),
                       ("m7-m4", D(leaf(m7), leaf(m4))), ("m7-m4-m2", D(leaf(m7), leaf(m4), leaf(m2))),
                       ("m7-(m7-m1)", D(leaf(m7), D(leaf(m7), leaf(m1)))),
                       ("m7-(m1+m2)", D(leaf(m7), U(leaf(m1), leaf(m2))))]:
        yield "BooleanVolumes " + name, "BooleanComplex.BooleanVolumes", tree
    yield "Spiral", "BooleanComplex.Spiral", spiral()
    yield "SelfIntersect", "BooleanComplex.SelfIntersect", U(obj("self_intersectA.obj"), obj("self_intersectB.obj"))
    yield "GenericTwin7081", "BooleanComplex.GenericTwinBooleanTest7081", U(
        obj("Generic_Twin_7081.1.t0_left.obj"), obj("Generic_Twin_7081.1.t0_right.obj"))
    yield "GenericTwin7863", "BooleanComplex.GenericTwinBooleanTest7863", U(
        obj("Generic_Twin_7863.1.t0_left.obj"), obj("Generic_Twin_7863.1.t0_right.obj"))
    yield "Havocglass8", "BooleanComplex.Havocglass8Bool", U(obj("Havocglass8_left.obj"), obj("Havocglass8_right.obj"))
    yield "Craycloud", "BooleanComplex.CraycloudBool", D(obj("Cray_left.obj"), obj("Cray_right.obj"))
    yield "HullMask", "BooleanComplex.HullMask", D(obj("hull-body.obj"), obj("hull-mask.obj"))
    yield "LazyCollider.ele4", "BooleanComplex.LazyCollider", e4
    yield "LazyCollider.r1", "BooleanComplex.LazyCollider", D(e4, leaf(e2.translate((0, 0, -20))))
    yield "LazyCollider.r2", "BooleanComplex.LazyCollider", D(XF(lambda m: m.translate((0, 0, 1)), e4), leaf(e3))
    yield "Offset1+2", "BooleanComplex.OffsetTriangulationFailure", U(obj("Offset1.obj"), obj("Offset2.obj"))
    yield "Offset3+4", "BooleanComplex.OffsetSelfIntersect", U(obj("Offset3.obj"), obj("Offset4.obj"))
    yield from source_cases(models)
