//! Catalogue files: which format a text is in, reading one (bounded) and parsing it.

use super::entry::{CatalogueEntry, CatalogueError, err};
use super::omm::{parse_omm_csv, parse_omm_json};
use super::tle::parse_tle;
use crate::Error;
use std::path::Path;

/// The format of a catalogue file, told from its first characters.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Two- or three-line element sets.
    Tle,
    /// OMM as a JSON array of objects (or one object).
    OmmJson,
    /// OMM as CSV with a header line.
    OmmCsv,
}

/// The format of `text`: JSON if it starts with `[` or `{`, CSV if its first line names `NORAD_CAT_ID`,
/// else TLE.
pub fn detect(text: &str) -> Format {
    let text = text.trim_start();
    if text.starts_with(['[', '{']) {
        Format::OmmJson
    } else if text.lines().next().is_some_and(|l| l.contains("NORAD_CAT_ID") && l.contains(',')) {
        Format::OmmCsv
    } else {
        Format::Tle
    }
}

/// Reads a catalogue file of at most [`crate::scenario::MAX_FILE_BYTES`] in any [`Format`].
pub fn load(path: &Path) -> Result<Vec<CatalogueEntry>, Error> {
    let text = crate::scenario::read_limited(path)?;
    Ok(parse(&path.display().to_string(), &text)?)
}

/// Parses `text` (its file named `file` in errors) in the [`Format`] [`detect`] finds. An empty catalogue
/// is an error.
pub fn parse(file: &str, text: &str) -> Result<Vec<CatalogueEntry>, CatalogueError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let entries = match detect(text) {
        Format::Tle => parse_tle(file, text)?,
        Format::OmmJson => parse_omm_json(file, text)?,
        Format::OmmCsv => parse_omm_csv(file, text)?,
    };
    if entries.is_empty() {
        return Err(err(file, 0, "catalogue", "no element set"));
    }
    Ok(entries)
}
