"""A closed, valid ~100k-triangle solid for the cells benchmark, made from a
closed triangle mesh by midpoint subdivision.

Each pass splits every triangle into four at its edge midpoints (each
midpoint made once per edge, so the mesh stays welded and closed). A
midpoint `(a + b) / 2` is exact in floating point, so the surface is the
same point set, face for face: a valid closed solid stays one, with the
same volume. Two passes over spot (5,856 triangles) give 93,696.

    python3 benches/peers/closed_model.py IN.obj OUT.obj [PASSES]   (default 2)

Only `v` and triangular `f` lines are read (`f a/b/c` forms allowed).
"""
import sys


def read(path):
    positions, triangles = [], []
    with open(path) as f:
        for line in f:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "v":
                positions.append(tuple(float(x) for x in parts[1:4]))
            elif parts[0] == "f":
                corners = [int(p.split("/")[0]) for p in parts[1:]]
                corners = [c - 1 if c > 0 else len(positions) + c for c in corners]
                if len(corners) != 3:
                    sys.exit(f"{path}: a face with {len(corners)} corners (triangles only)")
                triangles.append(tuple(corners))
    return positions, triangles


def subdivide(positions, triangles):
    positions = list(positions)
    midpoint = {}

    def mid(a, b):
        key = (min(a, b), max(a, b))
        if key not in midpoint:
            pa, pb = positions[a], positions[b]
            positions.append(tuple((x + y) / 2 for x, y in zip(pa, pb)))
            midpoint[key] = len(positions) - 1
        return midpoint[key]

    out = []
    for a, b, c in triangles:
        ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
        out += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
    return positions, out


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    passes = int(sys.argv[3]) if len(sys.argv) > 3 else 2
    positions, triangles = read(sys.argv[1])
    for _ in range(passes):
        positions, triangles = subdivide(positions, triangles)
    with open(sys.argv[2], "w") as f:
        f.write(f"# {sys.argv[1]} subdivided {passes} times at edge midpoints\n")
        f.writelines(f"v {x!r} {y!r} {z!r}\n" for x, y, z in positions)
        f.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in triangles)
    print(f"{sys.argv[2]}: {len(positions)} vertices, {len(triangles)} triangles")


if __name__ == "__main__":
    main()
