"""manifold3d's verdict on wingedge's marching-cubes meshes.

Usage: marching_cubes_oracle.py OBJ...  Prints one JSON object: per file
name, manifold3d's status, genus and volume of the triangles as given (no
merging: `v` and `f` lines only).
"""
import json
import pathlib
import sys

import manifold3d as m3d
import numpy as np


def read_triangles(path):
    verts, tris = [], []
    for line in pathlib.Path(path).read_text().splitlines():
        words = line.split()
        if words and words[0] == "v":
            verts.append([float(w) for w in words[1:4]])
        elif words and words[0] == "f":
            tris.append([int(w.split("/")[0]) - 1 for w in words[1:]])
    return np.array(verts, dtype=np.float64), np.array(tris, dtype=np.uint64)


def main():
    report = {}
    for path in sys.argv[1:]:
        verts, tris = read_triangles(path)
        built = m3d.Manifold(m3d.Mesh64(vert_properties=verts, tri_verts=tris))
        report[pathlib.Path(path).name] = {
            "status": str(built.status()).split(".")[-1],
            "genus": int(built.genus()),
            "volume": float(built.volume()),
            "triangles": int(built.num_tri()),
        }
    print(json.dumps(report))


if __name__ == "__main__":
    main()
