//! What a repair changed, located in the input by polygon index (the
//! caller maps an index to its OBJ line or file place).

/// Why a polygon was dropped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DropReason {
    /// Fewer than three distinct corners (after merging equal positions).
    FewerThanThreeCorners,
    /// A corner visited twice, not in a row.
    VisitsACornerTwice,
    /// Every corner on one line.
    ZeroArea,
    /// The same corners in the same cyclic order as the earlier polygon.
    Repeats(usize),
    /// The same corners in the reverse order as this polygon: the two
    /// cancel (both dropped).
    CancelsReverse(usize),
}

impl std::fmt::Display for DropReason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            DropReason::FewerThanThreeCorners => write!(f, "fewer than three distinct corners"),
            DropReason::VisitsACornerTwice => write!(f, "visits a corner twice"),
            DropReason::ZeroArea => write!(f, "zero area (every corner on one line)"),
            DropReason::Repeats(p) => write!(f, "repeats polygon {p}"),
            DropReason::CancelsReverse(p) => write!(f, "cancels its reverse, polygon {p}"),
        }
    }
}

/// A polygon left out of the repair.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DroppedPolygon {
    /// The input polygon (0-based).
    pub polygon: usize,
    /// Why.
    pub reason: DropReason,
}

/// A boundary loop (a hole), filled or left open.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct HoleLoop {
    /// How many edges the loop has.
    pub edges: usize,
    /// Triangles added to fill it (0 when left open, or when its edges lie
    /// on one line and it encloses no area).
    pub triangles: usize,
    /// An input polygon on its rim.
    pub next_to: usize,
}

/// Why a hole was left open.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OpenReason {
    /// More edges than the `max_hole_edges` option allows.
    LargerThanLimit(usize),
    /// Its exact triangulation failed (a loop that crosses itself in
    /// every axis projection).
    NotTriangulable,
}

/// Input polygons turned over, as one piece.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TurnedOver {
    /// The input polygons turned (sorted).
    pub polygons: Vec<usize>,
    /// Why: to agree with their neighbours, or the whole piece to face out.
    pub whole_piece: bool,
}

/// Everything a repair changed.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RepairReport {
    /// Input vertices merged into an earlier one at the same position.
    pub welded: usize,
    /// Polygons dropped, by input index.
    pub dropped: Vec<DroppedPolygon>,
    /// Polygons turned over.
    pub turned_over: Vec<TurnedOver>,
    /// Pieces that cannot be oriented consistently (a Möbius band): how
    /// many, left as they are.
    pub non_orientable_pieces: usize,
    /// Holes filled.
    pub filled: Vec<HoleLoop>,
    /// Holes left open, with the reason.
    pub left_open: Vec<(HoleLoop, OpenReason)>,
    /// Pairs of input polygons that cross or overlap, resolved by the
    /// arrangement (smaller index first, sorted).
    pub crossing_pairs: Vec<(usize, usize)>,
    /// Whether the arrangement ran (always, unless resolving is off).
    pub resolved: bool,
    /// The volume `∫ w dV` of the cleaned, oriented and filled soup
    /// (`w` its winding number: counted twice where two shells overlap),
    /// as its signed volume (rounded `f64`).
    pub volume_before: f64,
    /// The volume of the result.
    pub volume_after: f64,
    /// Why the result is empty, when it is.
    pub empty_because: Option<String>,
    /// Seconds spent in each stage, in order (the arrangement's stages as
    /// a boolean's, when it ran).
    pub stage_seconds: Vec<(&'static str, f64)>,
}

impl RepairReport {
    /// How many input polygons were turned over.
    #[must_use]
    pub fn turned_over_count(&self) -> usize {
        self.turned_over.iter().map(|t| t.polygons.len()).sum()
    }
}
