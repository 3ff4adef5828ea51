//! The CSG tree: leaves, operators, transforms, and the bounds hierarchy.

use crate::SetOp;
use std::sync::Arc;

use glam::{DAffine3, DVec3};
use thiserror::Error;

use super::{Primitive, TransformError, Transformed};
use crate::geom::Aabb;

/// The index of a leaf in a [`Csg`] tree (in the order the leaves were
/// given).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct LeafId(pub u32);

/// A CSG expression as written by a user or a scene file: what the tree
/// means, before it is arranged for fast queries.
///
/// N-ary operators fold left: `Union([a, b, c])` is `(a ∪ b) ∪ c` and
/// `Difference([a, b, c])` is `(a − b) − c`.
#[derive(Clone, Debug)]
pub enum CsgExpr {
    /// A primitive, with a label that names it in answers (scene files use
    /// the JSON path).
    Leaf {
        /// The solid.
        primitive: Arc<dyn Primitive>,
        /// What to call it.
        label: String,
    },
    /// The union of one or more children.
    Union(Vec<CsgExpr>),
    /// The intersection of one or more children.
    Intersection(Vec<CsgExpr>),
    /// The first child minus all the others (at least two children).
    Difference(Vec<CsgExpr>),
    /// A child moved by an affine map (child frame → parent frame).
    Transform {
        /// The map.
        transform: DAffine3,
        /// What it moves.
        child: Box<CsgExpr>,
    },
}

impl CsgExpr {
    /// A leaf labelled with the primitive's kind.
    #[must_use]
    pub fn leaf(primitive: impl Primitive + 'static) -> CsgExpr {
        let label = primitive.kind().to_string();
        CsgExpr::Leaf {
            primitive: Arc::new(primitive),
            label,
        }
    }

    /// `self ∪ other`.
    #[must_use]
    pub fn union(self, other: CsgExpr) -> CsgExpr {
        CsgExpr::Union(vec![self, other])
    }

    /// `self ∩ other`.
    #[must_use]
    pub fn intersection(self, other: CsgExpr) -> CsgExpr {
        CsgExpr::Intersection(vec![self, other])
    }

    /// `self − other`.
    #[must_use]
    pub fn difference(self, other: CsgExpr) -> CsgExpr {
        CsgExpr::Difference(vec![self, other])
    }

    /// `self` moved by `transform`.
    #[must_use]
    pub fn transformed(self, transform: DAffine3) -> CsgExpr {
        CsgExpr::Transform {
            transform,
            child: Box::new(self),
        }
    }
}

/// Why an expression is not a tree.
#[derive(Debug, Error)]
pub enum CsgError {
    /// A union or intersection without children.
    #[error("{op} at {at} has no children")]
    NoChildren {
        /// `union`, `intersection` or `difference`.
        op: &'static str,
        /// Where in the expression (a path of child indices).
        at: String,
    },
    /// A difference needs a first operand and something to take away.
    #[error("difference at {at} has {children} child(ren); it needs at least two")]
    DifferenceArity {
        /// Where in the expression.
        at: String,
        /// How many it has.
        children: usize,
    },
    /// A transform that cannot be inverted, or a leaf that does not
    /// survive it ([`Transformed::try_new`]).
    #[error("{leaf}: {source} (transform at {at})")]
    Transform {
        /// Where in the expression.
        at: String,
        /// The label of the leaf moved (a scene's JSON path).
        leaf: String,
        /// Why.
        source: TransformError,
    },
}

/// A leaf of a built tree.
#[derive(Clone, Debug)]
pub struct Leaf {
    /// The solid, in world coordinates (transforms above it are folded in).
    pub primitive: Arc<dyn Primitive>,
    /// Its label.
    pub label: String,
}

/// The index of a node in a [`Csg`].
pub(crate) type NodeIndex = usize;

#[derive(Clone, Copy, Debug)]
pub(crate) enum NodeKind {
    Leaf(LeafId),
    Op {
        op: SetOp,
        left: NodeIndex,
        right: NodeIndex,
    },
}

#[derive(Clone, Copy, Debug)]
pub(crate) struct Node {
    pub(crate) kind: NodeKind,
    /// Holds every point of the node's solid (∪: union of the children's,
    /// ∩: their intersection, −: the left child's).
    pub(crate) bounds: Aabb,
}

/// A CSG tree ready for queries.
///
/// Built from a [`CsgExpr`]: transforms are pushed down to the leaves
/// (affine maps commute with ∪, ∩ and −), and n-ary unions and
/// intersections are regrouped into a balanced binary tree split along the
/// longest axis of their children's bounds, so each internal node carries a
/// box of its subtree: a bounds hierarchy. ∪ and ∩ are associative and
/// commutative on point sets, and `a − b − c = a − (b ∪ c)`, so the
/// regrouped tree is the same solid as the left fold; only the order of the
/// work changes. Equal crossings are merged the same way in any grouping.
///
/// Why these bounds are not the shared BVH (`spatial::Bvh`): the
/// hierarchy here is the operator tree itself, which the span merge walks
/// node by node (Roth's state machine combines exactly two children under
/// one operator). A node's box follows its operator — the intersection of
/// its children's boxes under ∩, the left child's under − — where a BVH's
/// node box is always the union of its children's; and a difference fixes
/// the grouping of its operands, where a BVH groups items freely (up to
/// eight children a node, four items a leaf). Only the n-ary unions and
/// intersections may be regrouped at all, and they are regrouped here
/// (by a median split along the widest axis of the children's centres)
/// into binary operator nodes, which the merge can walk and a BVH's
/// eight-wide nodes are not.
///
/// # Invariants
///
/// `root` and every child index name nodes of `nodes`; every leaf id names
/// an element of `leaves`; every node's bounds hold its solid.
#[derive(Clone, Debug)]
pub struct Csg {
    pub(crate) nodes: Vec<Node>,
    pub(crate) leaves: Vec<Leaf>,
    pub(crate) root: NodeIndex,
}

impl Csg {
    /// Builds the tree of `expr`.
    ///
    /// # Errors
    ///
    /// [`CsgError`] for an operator without enough children or a singular
    /// transform.
    pub fn try_new(expr: CsgExpr) -> Result<Csg, CsgError> {
        let mut csg = Csg {
            nodes: Vec::new(),
            leaves: Vec::new(),
            root: 0,
        };
        csg.root = csg.build(expr, None, "root")?;
        Ok(csg)
    }

    /// A tree of one primitive.
    #[must_use]
    pub fn from_primitive(primitive: impl Primitive + 'static) -> Csg {
        let leaf = CsgExpr::leaf(primitive);
        // A single untransformed leaf cannot fail.
        Csg::try_new(leaf).unwrap_or_else(|_| unreachable!("a lone leaf is a valid tree"))
    }

    /// The leaf `id`, or `None` if there is no such leaf.
    #[must_use]
    pub fn leaf(&self, id: LeafId) -> Option<&Leaf> {
        self.leaves.get(id.0 as usize)
    }

    /// All leaves, in the order the expression gave them.
    #[must_use]
    pub fn leaves(&self) -> &[Leaf] {
        &self.leaves
    }

    /// The number of operator nodes.
    #[must_use]
    pub fn operator_count(&self) -> usize {
        self.nodes.len() - self.leaves.len()
    }

    /// The box holding the whole solid (possibly infinite, e.g. for a lone
    /// half-space).
    #[must_use]
    pub fn bounds(&self) -> Aabb {
        self.nodes[self.root].bounds
    }

    /// The number of nodes on the longest path from the root to a leaf (a
    /// single leaf has depth 1).
    #[must_use]
    pub fn depth(&self) -> usize {
        fn depth(csg: &Csg, node: NodeIndex) -> usize {
            match csg.nodes[node].kind {
                NodeKind::Leaf(_) => 1,
                NodeKind::Op { left, right, .. } => 1 + depth(csg, left).max(depth(csg, right)),
            }
        }
        depth(self, self.root)
    }

    /// The leaf when the whole tree is one leaf.
    #[must_use]
    pub fn single_leaf(&self) -> Option<&Leaf> {
        match self.nodes[self.root].kind {
            NodeKind::Leaf(id) => self.leaf(id),
            NodeKind::Op { .. } => None,
        }
    }

    fn push(&mut self, kind: NodeKind, bounds: Aabb) -> NodeIndex {
        self.nodes.push(Node { kind, bounds });
        self.nodes.len() - 1
    }

    fn op_node(&mut self, op: SetOp, left: NodeIndex, right: NodeIndex) -> NodeIndex {
        let (a, b) = (self.nodes[left].bounds, self.nodes[right].bounds);
        let bounds = match op {
            SetOp::Union => a.union(b),
            SetOp::Intersection => a.intersection(b),
            SetOp::Difference => a,
            SetOp::ReverseDifference => b,
        };
        let bounds = if bounds.is_empty() {
            Aabb::EMPTY
        } else {
            bounds
        };
        self.push(NodeKind::Op { op, left, right }, bounds)
    }

    fn build(
        &mut self,
        expr: CsgExpr,
        transform: Option<DAffine3>,
        at: &str,
    ) -> Result<NodeIndex, CsgError> {
        let children = |csg: &mut Csg, kids: Vec<CsgExpr>, name: &str| {
            kids.into_iter()
                .enumerate()
                .map(|(i, kid)| csg.build(kid, transform, &format!("{at}.{name}[{i}]")))
                .collect::<Result<Vec<_>, _>>()
        };
        match expr {
            CsgExpr::Leaf { primitive, label } => {
                let primitive: Arc<dyn Primitive> = match transform {
                    None => primitive,
                    Some(m) => Arc::new(Transformed::try_new(primitive, m).map_err(|source| {
                        CsgError::Transform {
                            at: at.to_string(),
                            leaf: label.clone(),
                            source,
                        }
                    })?),
                };
                let id = LeafId(self.leaves.len() as u32);
                let bounds = primitive.bounds();
                self.leaves.push(Leaf { primitive, label });
                Ok(self.push(NodeKind::Leaf(id), bounds))
            }
            CsgExpr::Union(kids) | CsgExpr::Intersection(kids) if kids.is_empty() => {
                Err(CsgError::NoChildren {
                    op: "union or intersection",
                    at: at.to_string(),
                })
            }
            CsgExpr::Union(kids) => {
                let ids = children(self, kids, "union")?;
                Ok(self.balanced(SetOp::Union, ids))
            }
            CsgExpr::Intersection(kids) => {
                let ids = children(self, kids, "intersection")?;
                Ok(self.balanced(SetOp::Intersection, ids))
            }
            CsgExpr::Difference(kids) => {
                if kids.len() < 2 {
                    return Err(CsgError::DifferenceArity {
                        at: at.to_string(),
                        children: kids.len(),
                    });
                }
                let mut ids = children(self, kids, "difference")?;
                let rest = ids.split_off(1);
                let cut = self.balanced(SetOp::Union, rest);
                Ok(self.op_node(SetOp::Difference, ids[0], cut))
            }
            CsgExpr::Transform {
                transform: m,
                child,
            } => {
                let composed = transform.map_or(m, |outer| outer * m);
                self.build(*child, Some(composed), &format!("{at}.transform"))
            }
        }
    }

    /// Groups `ids` (non-empty) under `op` as a balanced tree, splitting at
    /// the median of the children's box centres along their widest axis.
    fn balanced(&mut self, op: SetOp, mut ids: Vec<NodeIndex>) -> NodeIndex {
        if ids.len() == 1 {
            return ids[0];
        }
        let centre = |csg: &Csg, id: NodeIndex| {
            let c = csg.nodes[id].bounds.center();
            DVec3::select(c.is_finite_mask(), c, DVec3::ZERO)
        };
        let spread = ids
            .iter()
            .fold(Aabb::EMPTY, |b, &id| b.grow(centre(self, id)));
        let size = spread.size();
        let axis = if size.x >= size.y && size.x >= size.z {
            0
        } else if size.y >= size.z {
            1
        } else {
            2
        };
        ids.sort_by(|&a, &b| centre(self, a)[axis].total_cmp(&centre(self, b)[axis]));
        let right = ids.split_off(ids.len() / 2);
        let left = self.balanced(op, ids);
        let right = self.balanced(op, right);
        self.op_node(op, left, right)
    }
}
