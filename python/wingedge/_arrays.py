"""Array coercion shared by the package: coordinates, points and face lists
checked and converted once, before they reach the native module."""

from __future__ import annotations

from typing import Tuple

import numpy as np


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

