//! The checks every scenario format shares: the one-line error naming a field, the bounded file read, and
//! the tests of finite values, positive values and covariances.

use super::{EvaluationSpec, GOSPA_POWER_RANGE, MAX_GOSPA_ORDER};
use std::fmt;
use std::path::Path;

/// The largest scenario file read, in bytes (256 MiB): a longer file is rejected before it is parsed.
pub const MAX_FILE_BYTES: u64 = 256 << 20;

/// The largest magnitude of a covariance entry (of R, a birth cell or a prior object): sums and products
/// of two entries, such as the symmetrisation (A + Aᵀ)/2 and H P Hᵀ + R, stay finite.
pub const MAX_COVARIANCE_ENTRY: f64 = 1e150;

/// A problem with a scenario file: a one-line message that names the field.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ScenarioError(pub String);

impl fmt::Display for ScenarioError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for ScenarioError {}

/// The one-line error `field: message`, the field (a path may end in an unknown key) and quoted input cut
/// to excerpts ([`super::excerpt`], [`super::cut_quotes`]).
pub(crate) fn error(field: impl fmt::Display, message: impl fmt::Display) -> ScenarioError {
    let field = super::excerpt(&field.to_string(), 2 * super::quote::EXCERPT_CHARS);
    ScenarioError(one_line(&super::cut_quotes(&format!("{field}: {message}"))))
}

/// The message with every control character escaped (`\n`, `\r`, `\u{b}`, ...), and every invisible
/// format character, line or paragraph separator and bidirectional control as `\u{202e}`: a file's keys
/// and values may hold any of them, and an error is always one line that reads as it is stored.
pub fn one_line(message: &str) -> String {
    message
        .chars()
        .map(|c| {
            if c.is_control() {
                c.escape_debug().to_string()
            } else if is_format(c) {
                c.escape_unicode().to_string()
            } else {
                c.to_string()
            }
        })
        .collect()
}

/// Unicode's line and paragraph separators (Zl, Zp) and format characters (Cf): invisible, or they move
/// or reverse the text after them.
fn is_format(c: char) -> bool {
    matches!(
        c,
        '\u{ad}'
            | '\u{600}'..='\u{605}'
            | '\u{61c}'
            | '\u{6dd}'
            | '\u{70f}'
            | '\u{890}'..='\u{891}'
            | '\u{8e2}'
            | '\u{180e}'
            | '\u{200b}'..='\u{200f}'
            | '\u{2028}'..='\u{202e}'
            | '\u{2060}'..='\u{2064}'
            | '\u{2066}'..='\u{206f}'
            | '\u{feff}'
            | '\u{fff9}'..='\u{fffb}'
            | '\u{110bd}'
            | '\u{110cd}'
            | '\u{13430}'..='\u{1343f}'
            | '\u{1bca0}'..='\u{1bca3}'
            | '\u{1d173}'..='\u{1d17a}'
            | '\u{e0001}'
            | '\u{e0020}'..='\u{e007f}'
    )
}

/// The text of the file at `path`, read only up to [`MAX_FILE_BYTES`] (`/dev/zero` is rejected, not read to
/// the end).
pub fn read_limited(path: &Path) -> Result<String, ScenarioError> {
    use std::io::Read;
    let file = std::fs::File::open(path).map_err(|e| error(path.display(), e))?;
    let mut bytes = vec![];
    file.take(MAX_FILE_BYTES + 1).read_to_end(&mut bytes).map_err(|e| error(path.display(), e))?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(error(path.display(), format!("longer than the limit of {} MiB", MAX_FILE_BYTES >> 20)));
    }
    String::from_utf8(bytes).map_err(|e| error(path.display(), format!("not UTF-8: {e}")))
}

pub(crate) fn finite(field: &str, value: f64) -> Result<(), ScenarioError> {
    if value.is_finite() { Ok(()) } else { Err(error(field, format!("{} is not finite", super::Readable(value)))) }
}

pub(crate) fn finite_all(field: &str, values: &[f64]) -> Result<(), ScenarioError> {
    values.iter().try_for_each(|&v| finite(field, v))
}

pub(crate) fn positive(field: &str, value: f64) -> Result<(), ScenarioError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(error(field, format!("{} is not finite and > 0", super::Readable(value))))
    }
}

pub(crate) fn check_covariance<const D: usize>(
    field: &str,
    m: nalgebra::SMatrix<f64, D, D>,
) -> Result<(), ScenarioError> {
    if !m.iter().all(|v| v.is_finite()) {
        return Err(error(field, "has a non-finite entry"));
    }
    if let Some(v) = m.iter().find(|v| v.abs() > MAX_COVARIANCE_ENTRY) {
        return Err(error(field, format!("entry {v:?} is beyond ±{MAX_COVARIANCE_ENTRY:e}")));
    }
    if m != m.transpose() {
        return Err(error(field, "is not symmetric"));
    }
    if m.cholesky().is_none() {
        return Err(error(field, "is not positive definite"));
    }
    Ok(())
}

impl EvaluationSpec {
    /// Bounds, GOSPA order and cut-off: every figure of the metrics stays finite and non-zero (see
    /// [`MAX_GOSPA_ORDER`] and [`GOSPA_POWER_RANGE`]).
    pub(crate) fn validate(&self) -> Result<(), ScenarioError> {
        positive("evaluation.error_bound", self.error_bound)?;
        positive("evaluation.gospa_cutoff", self.gospa_cutoff)?;
        let p = self.gospa_order;
        if !(p.is_finite() && (1.0..=MAX_GOSPA_ORDER).contains(&p)) {
            return Err(error(
                "evaluation.gospa_order",
                format!("{} is not in [1, {MAX_GOSPA_ORDER}]", super::Readable(p)),
            ));
        }
        let (low, high) = GOSPA_POWER_RANGE;
        let power = self.gospa_cutoff.powf(p);
        if !(low..=high).contains(&power) {
            return Err(error(
                "evaluation.gospa_cutoff",
                format!("{}^{p} (cut-off^order) is not in [{low:e}, {high:e}]", super::Readable(self.gospa_cutoff)),
            ));
        }
        // The error bound is a GOSPA cut-off of order 1.
        if !(low..=high).contains(&self.error_bound) {
            return Err(error(
                "evaluation.error_bound",
                format!("{} is not in [{low:e}, {high:e}]", super::Readable(self.error_bound)),
            ));
        }
        if !(self.confirmation_existence > 0.0 && self.confirmation_existence <= 1.0) {
            return Err(error("evaluation.confirmation_existence", "must be in (0, 1]"));
        }
        Ok(())
    }
}
