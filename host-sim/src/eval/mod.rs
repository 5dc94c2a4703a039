//! Scoring runs against the truth: births and their confirmation, the exactness of a bounded tracker
//! against the unbounded reference.

pub mod births;
pub mod exactness;
pub mod score;
