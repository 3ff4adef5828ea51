//! What validation finds: violations of named rules, a graded verdict and
//! the measures that are reported but are not errors.

use serde::Serialize;

/// A rule an imported polyhedron must satisfy, named after what is wrong
/// when it is broken.
///
/// The first seven are the topological validity rules of a polyhedral
/// boundary model (Baumgart 1975; Mäntylä 1988), numbered 1–6 below; rule
/// 4, "every edge lies on exactly two faces", is split into holes and
/// non-manifold edges. The rest are the defects real files show.
///
/// Each defect is reported once, by the most specific rule: a face with
/// fewer than three distinct vertices is not also reported as having fewer
/// than three edges or as degenerate; a face that is reported by any of those
/// three, and every later copy of a duplicate face, is left out of the edge
/// and vertex counts of the other rules, so that one broken face does not
/// also show up as a hole or a non-manifold edge.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Rule {
    /// Validity rule 1: a vertex lies on fewer than three edges.
    VertexInFewerThanThreeEdges,
    /// Validity rule 2: a vertex lies on fewer than three faces.
    VertexInFewerThanThreeFaces,
    /// Validity rule 3: an edge joins a vertex to itself (a face lists the same
    /// vertex twice in a row).
    EdgeWithoutTwoDistinctVertices,
    /// Validity rule 4, first half: an edge has only one face (it borders a
    /// hole).
    EdgeInOneFace,
    /// Validity rule 4, second half: an edge has three or more faces
    /// (non-manifold edge).
    EdgeInMoreThanTwoFaces,
    /// Validity rule 5: a face has fewer than three distinct vertices.
    FaceWithFewerThanThreeVertices,
    /// Validity rule 6: a face has fewer than three distinct edges.
    FaceWithFewerThanThreeEdges,
    /// A vertex that no face uses.
    UnreferencedVertex,
    /// Two faces with the same vertex cycle, in either orientation.
    DuplicateFace,
    /// Two faces run a shared edge in the same direction.
    InconsistentOrientation,
    /// The faces around a vertex form more than one fan (a pinch point).
    NonManifoldVertex,
    /// A face's vertices lie farther from its plane than the planarity
    /// tolerance allows.
    NonPlanarFace,
    /// A face with zero area or that is not simple: all its vertices
    /// collinear, two of them at the same position, a vertex visited twice,
    /// or two of its edges meeting (a bow tie; decided exactly in the axis
    /// projection nearest to its Newell plane).
    DegenerateFace,
    /// A closed shell whose faces point into the material: an outer shell
    /// with negative signed volume, or a cavity with positive.
    ShellOrientedInward,
    /// A face crosses or touches a face it shares no vertex with, or a
    /// neighbour folds onto it (coplanar, same side of a shared edge) or,
    /// sharing one vertex, passes through it or overlaps it in its plane.
    SelfIntersection,
}

impl Rule {
    /// Every rule, in report order.
    pub const ALL: [Rule; 15] = [
        Rule::VertexInFewerThanThreeEdges,
        Rule::VertexInFewerThanThreeFaces,
        Rule::EdgeWithoutTwoDistinctVertices,
        Rule::EdgeInOneFace,
        Rule::EdgeInMoreThanTwoFaces,
        Rule::FaceWithFewerThanThreeVertices,
        Rule::FaceWithFewerThanThreeEdges,
        Rule::UnreferencedVertex,
        Rule::DuplicateFace,
        Rule::InconsistentOrientation,
        Rule::NonManifoldVertex,
        Rule::NonPlanarFace,
        Rule::DegenerateFace,
        Rule::ShellOrientedInward,
        Rule::SelfIntersection,
    ];

    /// The rule's snake-case name, as in JSON output.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Rule::VertexInFewerThanThreeEdges => "vertex_in_fewer_than_three_edges",
            Rule::VertexInFewerThanThreeFaces => "vertex_in_fewer_than_three_faces",
            Rule::EdgeWithoutTwoDistinctVertices => "edge_without_two_distinct_vertices",
            Rule::EdgeInOneFace => "edge_in_one_face",
            Rule::EdgeInMoreThanTwoFaces => "edge_in_more_than_two_faces",
            Rule::FaceWithFewerThanThreeVertices => "face_with_fewer_than_three_vertices",
            Rule::FaceWithFewerThanThreeEdges => "face_with_fewer_than_three_edges",
            Rule::UnreferencedVertex => "unreferenced_vertex",
            Rule::DuplicateFace => "duplicate_face",
            Rule::InconsistentOrientation => "inconsistent_orientation",
            Rule::NonManifoldVertex => "non_manifold_vertex",
            Rule::NonPlanarFace => "non_planar_face",
            Rule::DegenerateFace => "degenerate_face",
            Rule::ShellOrientedInward => "shell_oriented_inward",
            Rule::SelfIntersection => "self_intersection",
        }
    }

    /// Whether a violation of this rule means the faces do not form a
    /// 2-manifold surface.
    #[must_use]
    pub fn breaks_surface(self) -> bool {
        matches!(
            self,
            Rule::EdgeWithoutTwoDistinctVertices
                | Rule::EdgeInMoreThanTwoFaces
                | Rule::FaceWithFewerThanThreeVertices
                | Rule::FaceWithFewerThanThreeEdges
                | Rule::DuplicateFace
                | Rule::NonManifoldVertex
        )
    }
}

impl std::fmt::Display for Rule {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// One instance of a broken rule, located.
///
/// Element ids are 0-based: `vertices` index the soup's positions (with no
/// weld, vertex `i` is the file's `v` number `i + 1`), `faces` count the
/// file's faces in order. `line` is the OBJ line of the first element named,
/// `lines` those of all of them.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Violation {
    /// The rule broken.
    pub rule: Rule,
    /// A sentence saying what is wrong and where.
    pub message: String,
    /// The OBJ line of the defect, where it has one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub line: Option<usize>,
    /// The OBJ lines of every element involved.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub lines: Vec<usize>,
    /// The vertices involved (for an edge: its two ends, in the direction
    /// that matters).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub vertices: Vec<usize>,
    /// The faces involved.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub faces: Vec<usize>,
    /// A measured quantity, where the rule has one (a non-planar face's
    /// deviation, a shell's signed volume, a vertex's edge count).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub value: Option<f64>,
}

/// How far a polyhedron is from a valid solid: each grade includes all the
/// ones below it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Validity {
    /// Some edge has three or more faces, some vertex is a pinch point, some
    /// face is not a polygon, or a face is duplicated: the faces do not form
    /// a 2-manifold surface (or the winged-edge solid cannot be built).
    NotASurface,
    /// A 2-manifold surface (possibly with holes) whose faces do not agree on
    /// an orientation.
    ManifoldSurface,
    /// A consistently oriented 2-manifold surface with holes.
    OrientedSurface,
    /// A closed, consistently oriented 2-manifold surface that still has a
    /// defect (geometric, a shell facing inward, stray vertices).
    ClosedOrientedSurface,
    /// A closed oriented surface with no defect at all: a valid solid.
    ValidSolid,
    /// The empty solid: no vertices and no faces (what `A − A` is). Valid
    /// vacuously, and ordered above [`Validity::ValidSolid`], so that
    /// `validity >= Validity::ValidSolid` holds for every valid solid.
    Empty,
}

impl Validity {
    /// Words for people.
    #[must_use]
    pub fn describe(self) -> &'static str {
        match self {
            Validity::NotASurface => "not a surface",
            Validity::ManifoldSurface => "manifold surface, not consistently oriented",
            Validity::OrientedSurface => "oriented surface with holes",
            Validity::ClosedOrientedSurface => "closed oriented surface with defects",
            Validity::ValidSolid => "valid closed solid",
            Validity::Empty => "the empty solid (no faces)",
        }
    }
}

/// One connected component of the surface, with its measures.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ShellSummary {
    /// Faces on the shell.
    pub faces: usize,
    /// Vertices on the shell.
    pub vertices: usize,
    /// Edges on the shell.
    pub edges: usize,
    /// Edges with one face (rims of holes).
    pub boundary_edges: usize,
    /// `V − E + F`.
    pub euler_characteristic: i64,
    /// The genus of a closed shell, `None` for one with holes.
    pub genus: Option<i64>,
    /// Signed volume enclosed (meaningful for a closed shell).
    pub volume: f64,
    /// Total face area.
    pub area: f64,
    /// Whether the shell has no hole.
    pub closed: bool,
    /// How many other closed shells contain it (0: an outer shell, 1: a
    /// cavity, 2: an island in a cavity …); `None` when it could not be
    /// decided (the shell touches another).
    pub depth: Option<usize>,
    /// The smallest shell containing it, if any.
    pub parent: Option<usize>,
    /// The OBJ line of the shell's first face.
    pub first_line: Option<usize>,
}

/// Everything validation found out about one polyhedron.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Report {
    /// The grade reached.
    pub validity: Validity,
    /// Vertices (after welding; unreferenced ones included).
    pub vertices: usize,
    /// Distinct edges.
    pub edges: usize,
    /// Faces.
    pub faces: usize,
    /// Connected components of the surface.
    pub shells: usize,
    /// Holes: loops of edges with one face (connected groups of such edges;
    /// holes that touch at a vertex count as one here, and the vertex is
    /// reported by [`Rule::NonManifoldVertex`]).
    pub holes: usize,
    /// Summed genus of the shells when every shell is closed.
    pub genus: Option<i64>,
    /// Enclosed volume when the winged-edge solid was built and every shell
    /// is closed.
    pub volume: Option<f64>,
    /// Total face area.
    pub area: f64,
    /// Why the winged-edge solid could not be built, if it could not.
    pub not_built: Option<String>,
    /// Per-shell measures (empty when the solid could not be built).
    pub shell_details: Vec<ShellSummary>,
    /// Every violation found, grouped by rule in [`Rule::ALL`] order.
    pub violations: Vec<Violation>,
    /// Wall-clock seconds of validation stages, for benchmarks.
    #[serde(skip)]
    pub stage_seconds: Vec<(&'static str, f64)>,
}

impl Report {
    /// Whether the polyhedron is a valid closed solid, or the empty solid.
    #[must_use]
    pub fn is_valid(&self) -> bool {
        self.validity >= Validity::ValidSolid
    }

    /// How many violations of `rule` were found.
    #[must_use]
    pub fn count(&self, rule: Rule) -> usize {
        self.violations.iter().filter(|v| v.rule == rule).count()
    }

    /// The violations of `rule`.
    pub fn of(&self, rule: Rule) -> impl Iterator<Item = &Violation> + '_ {
        self.violations.iter().filter(move |v| v.rule == rule)
    }

    /// The measures that do not fit in `f64` (`"volume"`, `"area"`,
    /// `"shell volume"`): coordinates so large that their products overflow.
    /// The topology and every check are still exact; only these rounded
    /// constructions are lost, and a reader must be told rather than shown
    /// `NaN` or `inf`.
    #[must_use]
    pub fn overflowing_measures(&self) -> Vec<&'static str> {
        let mut out = Vec::new();
        if self.volume.is_some_and(|v| !v.is_finite()) {
            out.push("volume");
        }
        if !self.area.is_finite() {
            out.push("area");
        }
        if self.shell_details.iter().any(|s| !s.volume.is_finite()) {
            out.push("shell volume");
        }
        out
    }
}
