//! Where a point lies relative to a solid.

/// Where a point lies relative to a closed solid: the three-way answer of
/// every point query.
///
/// `OnBoundary` means exactly on the boundary surface (decided exactly for
/// polyhedral leaves and half-spaces), never "close to it".
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Containment {
    /// Strictly inside the solid.
    Inside,
    /// Strictly outside the solid.
    Outside,
    /// Exactly on its boundary.
    OnBoundary,
}

impl Containment {
    /// The word the command line prints: `inside`, `outside` or `boundary`.
    #[must_use]
    pub fn word(self) -> &'static str {
        match self {
            Containment::Inside => "inside",
            Containment::Outside => "outside",
            Containment::OnBoundary => "boundary",
        }
    }
}

impl std::fmt::Display for Containment {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.word())
    }
}
