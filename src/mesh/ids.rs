//! Typed keys for the winged-edge tables.

slotmap::new_key_type! {
    /// A vertex of a [`Solid`](super::Solid).
    pub struct VertexId;
    /// An edge of a [`Solid`](super::Solid).
    pub struct EdgeId;
    /// A face of a [`Solid`](super::Solid).
    pub struct FaceId;
    /// A loop (the outer boundary or a ring) of a face of a
    /// [`Solid`](super::Solid).
    pub struct LoopId;
}
