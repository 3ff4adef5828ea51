//! One check per file, each named after what is wrong.
//!
//! Soup checks take the shared [`Context`](super::context::Context) and
//! work on any input; [`shell_oriented_inward`] needs the winged-edge solid.

pub(crate) mod degenerate_face;
pub(crate) mod duplicate_face;
pub(crate) mod edge_in_more_than_two_faces;
pub(crate) mod edge_in_one_face;
pub(crate) mod edge_without_two_distinct_vertices;
pub(crate) mod face_with_fewer_than_three_edges;
pub(crate) mod face_with_fewer_than_three_vertices;
pub(crate) mod inconsistent_orientation;
pub(crate) mod non_manifold_vertex;
pub(crate) mod non_planar_face;
pub(crate) mod self_intersection;
pub(crate) mod shell_oriented_inward;
pub(crate) mod unreferenced_vertex;
pub(crate) mod vertex_in_fewer_than_three_edges;
pub(crate) mod vertex_in_fewer_than_three_faces;

/// How many items of a list a violation's message shows; the full list is
/// in the violation's fields.
const LISTED_IN_MESSAGE: usize = 10;

/// A list for a message: `[a, b, c]`, or the first
/// [`LISTED_IN_MESSAGE`] items and `… and N more`, so that a message stays
/// short however many faces share an edge.
pub(crate) fn preview(items: &[usize]) -> String {
    let shown: Vec<String> = items
        .iter()
        .take(LISTED_IN_MESSAGE)
        .map(ToString::to_string)
        .collect();
    match items.len().checked_sub(LISTED_IN_MESSAGE) {
        Some(more) if more > 0 => format!("[{}, … and {more} more]", shown.join(", ")),
        _ => format!("[{}]", shown.join(", ")),
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn previews_are_capped() {
        assert_eq!(super::preview(&[]), "[]");
        assert_eq!(super::preview(&[1, 2, 3]), "[1, 2, 3]");
        let long: Vec<usize> = (0..25).collect();
        assert_eq!(
            super::preview(&long),
            "[0, 1, 2, 3, 4, 5, 6, 7, 8, 9, … and 15 more]"
        );
    }
}
