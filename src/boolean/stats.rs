//! What a boolean spent and did: the time of each stage and the work it
//! found, for reports, benchmarks and the command line's `--stats`.

/// Where a boolean spent its time, in seconds, and how much work it found.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BooleanStats {
    /// Checking both operands with the validator.
    pub check_seconds: f64,
    /// Triangulating the operands and building their BVHs and classifiers.
    pub prepare_seconds: f64,
    /// The pair walk and the exact contact of each candidate pair.
    pub intersect_seconds: f64,
    /// Merging equal points.
    pub points_seconds: f64,
    /// Cutting triangles along their segments.
    pub split_seconds: f64,
    /// Patches and membership.
    pub classify_seconds: f64,
    /// Rounding, snapping, building the result and merging its faces.
    pub output_seconds: f64,
    /// Proving the result valid with the validator.
    pub proof_seconds: f64,
    /// Pairs of triangles that meet.
    pub contacts: usize,
    /// Points made by the intersection (before merging equal ones).
    pub new_points: usize,
    /// Triangles that were cut.
    pub cut_triangles: usize,
    /// Points where the segments of two different operands cross inside a
    /// triangle of a third (only with three or more operands; each counted
    /// once per triangle it lies in).
    pub segment_crossings: usize,
    /// What the output stage had to do to write the result valid.
    pub output: OutputWork,
}

/// What the output stage did beyond rounding each point once: its rounds
/// of build, merge and proof, and the fixes it learnt between them (see
/// `boolean::output`). All zero but `rounds = 1` when the rounded result
/// proved valid at once; summed over the booleans of a tree.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OutputWork {
    /// Rounds of build, merge and proof (1 when nothing needed fixing).
    pub rounds: usize,
    /// Pairs of points collapsed into one (features smaller than `f64`
    /// can hold, within a few units in the last place).
    pub collapsed_points: usize,
    /// Edges split at a point (a vertex put on an edge it was within a few
    /// ulps of, or a slit given a vertex of its own).
    pub split_edges: usize,
    /// Pieces kept from merging with their neighbours into one face.
    pub unmerged_pieces: usize,
    /// Pairs of near-coplanar neighbouring pieces merged across a fold.
    pub joined_pairs: usize,
    /// Pieces dropped: shells thinner than `f64` can hold.
    pub dropped_pieces: usize,
    /// Operand vertices moved onto a vertex of an earlier operand, or onto
    /// the plane of another operand's axis-aligned face, that `f64` could
    /// not keep apart from them (the last resort, `weld`), or off the plane
    /// of another operand's face they lay nearly in (`apart`): the boolean
    /// was run again on the moved operands.
    pub welded_vertices: usize,
    /// Constructed points of the result written rounded: not exactly
    /// representable in `f64` (not a fix; 0 with nothing fixed means the
    /// written result is exactly the exact one, see
    /// [`OutputWork::is_exact`]).
    pub rounded_points: usize,
}

impl OutputWork {
    /// Whether any fix was needed (a point moved, an edge split, a piece
    /// kept apart, joined or dropped).
    #[must_use]
    pub fn fixed_anything(&self) -> bool {
        self.collapsed_points
            + self.split_edges
            + self.unmerged_pieces
            + self.joined_pairs
            + self.dropped_pieces
            + self.welded_vertices
            > 0
    }

    /// Whether what is written is exactly the exact result: every point of
    /// it representable in `f64` as it is, and nothing fixed. Such a result
    /// can be cut again as an operand with no rounding in between, which
    /// is how `csg::evaluate` splits a tree into several booleans.
    #[must_use]
    pub fn is_exact(&self) -> bool {
        self.rounded_points == 0 && !self.fixed_anything()
    }

    /// The counts as `name value` pairs, named as in reports.
    #[must_use]
    pub fn counts(&self) -> [(&'static str, usize); 7] {
        [
            ("rounds", self.rounds),
            ("collapsed_points", self.collapsed_points),
            ("split_edges", self.split_edges),
            ("unmerged_pieces", self.unmerged_pieces),
            ("joined_pairs", self.joined_pairs),
            ("dropped_pieces", self.dropped_pieces),
            ("welded_vertices", self.welded_vertices),
        ]
    }

    /// One line for people: what had to be fixed for the result to be
    /// written valid, or that nothing had to be.
    #[must_use]
    pub fn describe(&self) -> String {
        if !self.fixed_anything() {
            return "every point rounded once; nothing needed fixing".to_string();
        }
        let welded = if self.welded_vertices > 0 {
            format!(
                ", after {} operand vertices were welded onto another operand's vertices or planes, or pushed off its nearly coincident faces",
                self.welded_vertices
            )
        } else {
            String::new()
        };
        format!(
            "fixed in {} rounds: {} points collapsed, {} edges split, {} pieces kept unmerged, {} pairs joined, {} pieces of thin shells dropped{welded}",
            self.rounds,
            self.collapsed_points,
            self.split_edges,
            self.unmerged_pieces,
            self.joined_pairs,
            self.dropped_pieces
        )
    }
}

impl std::ops::AddAssign<&OutputWork> for OutputWork {
    fn add_assign(&mut self, one: &OutputWork) {
        self.rounds += one.rounds;
        self.collapsed_points += one.collapsed_points;
        self.split_edges += one.split_edges;
        self.unmerged_pieces += one.unmerged_pieces;
        self.joined_pairs += one.joined_pairs;
        self.dropped_pieces += one.dropped_pieces;
        self.welded_vertices += one.welded_vertices;
        self.rounded_points += one.rounded_points;
    }
}

impl BooleanStats {
    /// The time of each stage, in pipeline order, named as in reports
    /// (`check`, `prepare`, `intersect`, `points`, `split`, `classify`,
    /// `output`, `proof`).
    #[must_use]
    pub fn stages(&self) -> [(&'static str, f64); 8] {
        [
            ("check", self.check_seconds),
            ("prepare", self.prepare_seconds),
            ("intersect", self.intersect_seconds),
            ("points", self.points_seconds),
            ("split", self.split_seconds),
            ("classify", self.classify_seconds),
            ("output", self.output_seconds),
            ("proof", self.proof_seconds),
        ]
    }

    /// The stages' times as `name 0.123, …`, in pipeline order.
    #[must_use]
    pub fn stages_text(&self) -> String {
        self.stages()
            .iter()
            .map(|(name, seconds)| format!("{name} {seconds:.3}"))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

impl std::ops::AddAssign<&BooleanStats> for BooleanStats {
    /// Sums the time and work of several booleans (a tree's).
    fn add_assign(&mut self, one: &BooleanStats) {
        self.check_seconds += one.check_seconds;
        self.prepare_seconds += one.prepare_seconds;
        self.intersect_seconds += one.intersect_seconds;
        self.points_seconds += one.points_seconds;
        self.split_seconds += one.split_seconds;
        self.classify_seconds += one.classify_seconds;
        self.output_seconds += one.output_seconds;
        self.proof_seconds += one.proof_seconds;
        self.contacts += one.contacts;
        self.new_points += one.new_points;
        self.cut_triangles += one.cut_triangles;
        self.segment_crossings += one.segment_crossings;
        self.output += &one.output;
    }
}
