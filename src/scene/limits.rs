//! The limits that refuse hostile scene files quickly, and the count of
//! nodes and their depth that enforces them across included files.

use std::cell::Cell;

use super::SceneError;

/// How deep JSON may nest (arrays and objects); deeper text is refused by
/// the JSON reader before any node is read.
pub use crate::io::json_value::MAX_JSON_DEPTH;
/// How deep nodes may nest, counting through included scene files (a node
/// per operator, transform or inclusion).
pub const MAX_NODE_DEPTH: usize = 256;
/// How many nodes a scene may have, counting included scenes once per
/// inclusion.
pub const MAX_NODES: usize = 1_000_000;
/// How deep scene files may include scene files.
pub const MAX_INCLUDE_DEPTH: usize = 16;

const DEPTH: &str = "node nesting (counting through included scenes)";
const COUNT: &str = "the number of nodes (counting included scenes)";
const INCLUDES: &str = "the nesting of included scene files";

/// The nodes read so far for one scene, all its files together.
///
/// # Invariants
///
/// `nodes <= MAX_NODES`; every counted node was less than
/// [`MAX_NODE_DEPTH`] deep; `deepest` is the deepest of them since the
/// last [`NodeBudget::start_include`].
#[derive(Debug, Default)]
pub(super) struct NodeBudget {
    nodes: Cell<usize>,
    deepest: Cell<usize>,
}

/// How much of the budget an included scene used, to count it again when
/// the same file is included again without reading it.
#[derive(Clone, Copy, Debug)]
pub(super) struct IncludedSize {
    /// Nodes it was read from.
    pub nodes: usize,
    /// Levels of nodes below its root.
    pub height: usize,
}

/// Where an included file's reading started, for [`NodeBudget::end_include`].
#[derive(Clone, Copy, Debug)]
pub(super) struct IncludeStart {
    nodes: usize,
    deepest: usize,
    depth: usize,
}

fn limit(at: &str, what: &'static str, limit: usize) -> SceneError {
    SceneError::Limit {
        at: at.to_string(),
        what,
        limit,
    }
}

impl NodeBudget {
    /// Counts a node at `at`, `depth` nodes below the outermost root.
    ///
    /// # Errors
    ///
    /// [`SceneError::Limit`] when the node is too deep or one too many.
    pub(super) fn enter(&self, at: &str, depth: usize) -> Result<(), SceneError> {
        if depth >= MAX_NODE_DEPTH {
            return Err(limit(at, DEPTH, MAX_NODE_DEPTH));
        }
        let count = self.nodes.get() + 1;
        if count > MAX_NODES {
            return Err(limit(at, COUNT, MAX_NODES));
        }
        self.nodes.set(count);
        self.deepest.set(self.deepest.get().max(depth));
        Ok(())
    }

    /// Refuses an inclusion at `at` from a file that is `files` inclusions
    /// deep.
    ///
    /// # Errors
    ///
    /// [`SceneError::Limit`] past [`MAX_INCLUDE_DEPTH`].
    pub(super) fn check_include_depth(at: &str, files: usize) -> Result<(), SceneError> {
        if files >= MAX_INCLUDE_DEPTH {
            return Err(limit(at, INCLUDES, MAX_INCLUDE_DEPTH));
        }
        Ok(())
    }

    /// Counts again a scene read before, included at `at` whose node is
    /// `depth` deep.
    ///
    /// # Errors
    ///
    /// [`SceneError::Limit`] when its nodes would be too deep or too many.
    pub(super) fn add_included(
        &self,
        at: &str,
        depth: usize,
        size: IncludedSize,
    ) -> Result<(), SceneError> {
        if depth + 1 + size.height >= MAX_NODE_DEPTH {
            return Err(limit(at, DEPTH, MAX_NODE_DEPTH));
        }
        let count = self.nodes.get() + size.nodes;
        if count > MAX_NODES {
            return Err(limit(at, COUNT, MAX_NODES));
        }
        self.nodes.set(count);
        Ok(())
    }

    /// Starts reading an included file whose root is `depth` deep.
    pub(super) fn start_include(&self, depth: usize) -> IncludeStart {
        IncludeStart {
            nodes: self.nodes.get(),
            deepest: self.deepest.replace(0),
            depth,
        }
    }

    /// Ends reading an included file: what it used.
    pub(super) fn end_include(&self, start: IncludeStart) -> IncludedSize {
        let deepest = self.deepest.get();
        self.deepest.set(deepest.max(start.deepest));
        IncludedSize {
            nodes: self.nodes.get() - start.nodes,
            height: deepest.saturating_sub(start.depth),
        }
    }
}
