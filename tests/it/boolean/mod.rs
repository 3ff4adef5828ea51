//! Exact booleans of solids and of whole set expressions.

mod basics;
mod hard;
mod random;
mod scale;
mod stress;
mod structure;
mod tree;
