//! The one in-memory type of a scenario file, whatever its version, and the reader that picks the version.

use super::v2::Scenario3d;
use super::{Scenario, ScenarioError, error, read_limited};
use serde::Deserialize;
use std::path::Path;

/// A scenario file of either version, in memory: the one type the commands take ([`crate::pipeline`]
/// picks the world from it).
#[derive(Debug, Clone, PartialEq)]
pub enum AnyScenario {
    /// Version 1: the planar world of paper 003.
    V1(Box<Scenario>),
    /// Version 2: 3-D SSA geometry.
    V2(Box<Scenario3d>),
}

/// Reads a scenario file of either version: a top-level `"version": 2` selects version 2; without a
/// `version` (or with 1) the file is read exactly as version 1 always was.
///
/// # Errors
/// A one-line [`ScenarioError`] naming the problem.
pub fn load_any(path: &Path) -> Result<AnyScenario, ScenarioError> {
    parse_any(&read_limited(path)?)
}

/// Reads a scenario of either version from JSON text, as [`load_any`] reads a file (the Python package
/// builds a tracker from a dict this way).
///
/// # Errors
/// A one-line [`ScenarioError`] naming the problem.
pub fn parse_any(text: &str) -> Result<AnyScenario, ScenarioError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    #[derive(Deserialize)]
    struct Probe {
        #[serde(default)]
        version: Option<serde_json::Value>,
    }
    // Invalid JSON, or JSON that is not an object, is reported by the version 1 reader as always.
    let version = serde_json::from_str::<Probe>(text).ok().and_then(|p| p.version);
    match version {
        Some(v) if v.as_u64() == Some(2) => Ok(AnyScenario::V2(Box::new(Scenario3d::from_json(text)?))),
        Some(v) if v.as_u64() == Some(1) => Ok(AnyScenario::V1(Box::new(Scenario::from_json(text)?))),
        Some(v) => Err(error("version", format!("{v} is not a known format version (1 or 2)"))),
        None => Ok(AnyScenario::V1(Box::new(Scenario::from_json(text)?))),
    }
}
