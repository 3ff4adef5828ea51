//! Which way along `x` a point's ray is cast, and why parity may choose.

/// Which way along `x` a point's ray is cast.
///
/// Parity may use either way, with the same answer, because of this fact:
/// on a closed surface (every edge shared by two faces) the symbolically
/// moved line `p' + t·(1, 0, 0)`, `t ∈ ℝ` (see
/// [`Accel::classify_with`](crate::query::Accel::classify_with))
/// crosses the fan triangles an even number of times in all. Proof: the
/// moved point `q' = (y + ε, z + ε²)` lies on no projected edge's line (an
/// edge whose two projected ends differ; such a tie is exactly what the
/// perturbation decides) and on no projected vertex, so the line meets the
/// triangles only in their interiors and crosses each one it meets
/// transversally, once, and a triangle with zero projected area not at all.
/// Summed mod 2, the fan triangles of a face have the face's boundary as
/// their boundary (inner diagonals cancel), so all of them form a 2-cycle
/// mod 2 when every edge has two faces; a 2-cycle in `ℝ³` bounds a finite
/// 3-chain, which the line enters and leaves a total of an even number of
/// times (it starts and ends outside it). With integer coefficients and
/// faces oriented consistently the same argument gives signed crossings
/// summing to 0.
///
/// Let `p` be off the surface. Each crossing of the moved line is strictly
/// in front of `p` or strictly behind it: a crossed triangle's plane is not
/// parallel to `x` (its projection has non-zero area), `p` is not on it
/// (else `p`, projecting into the closed projected triangle and lying in the
/// plane, would be on the triangle), and `ε` is infinitesimal, so the side
/// is the exact `orient3d` of `p` against the plane. Hence
/// `front + behind = total`, even, and the parities of the crossings in
/// front and behind agree (and the signed counts are opposite on an oriented
/// surface). If `p` is on the surface, every triangle holding it has
/// `min x ≤ p.x ≤ max x` and a closed projection holding `(p.y, p.z)`, so
/// either way tests it and answers `XRay::OnBoundary`. The perturbation,
/// `q'`, is the same in both directions. So the answer does not depend on
/// the direction, for parity.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum XDirection {
    /// Towards `+x`: the triangles in front of `p` count.
    Plus,
    /// Towards `−x`: the triangles behind `p` count (negated).
    Minus,
}

/// Which way each point's ray goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum RayChoice {
    /// Every ray the same way.
    Always(XDirection),
    /// Per point, the way along which fewer of its grid cell's triangles can
    /// be met (ties: `+x`). Only for parity (see [`XDirection`]).
    Fewer,
}
