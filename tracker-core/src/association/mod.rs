//! Data association: the matrix of one (parent, event) pair and its column layout.
//!
//! The matrix holds the log ratios δ of docs/maths.md §4.2; the layout says which of the parent's objects, or
//! which birth cell, each column stands for. A generator reads only the matrix; materialisation reads a
//! child's association vector back through the layout.

mod layout;
mod matrix;

pub use layout::{Column, ColumnLayout, ParentColumns};
pub use matrix::{AssociationMatrix, CLUTTER, association_count};
