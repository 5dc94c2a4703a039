//! What the experiments share: their error conversion, their run options, a mean.

use crate::error::Error;
use crate::pipeline::planar::Options;
use crate::pipeline::{Profile, ReferenceBudget};

/// An internal failure of an experiment.
pub(crate) fn err(e: impl std::fmt::Display) -> Error {
    Error::internal(e)
}

/// The options of an experiment's runs: the embedded profile, the reference's default budget.
pub(crate) fn options(quiet: bool) -> Options {
    Options { profile: Profile::Embedded, reference: ReferenceBudget::default(), max_hypotheses_out: 32, quiet }
}

/// The mean of `v` (0 when empty).
pub(crate) fn mean(v: &[f64]) -> f64 {
    if v.is_empty() { 0.0 } else { v.iter().sum::<f64>() / v.len() as f64 }
}
