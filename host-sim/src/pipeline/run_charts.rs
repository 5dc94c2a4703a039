//! The line charts every world's run writes: the expected (and true) number of objects and the GOSPA of the
//! MAP estimates over the run (`expected_cardinality` and `gospa`, PNG and SVG).

use crate::error::Error;
use crate::pipeline::world::ScanRecord;
use crate::plots::{self, Scale, Series};
use std::path::Path;

/// Writes both charts into `out`, each scan placed at `x(record)` on an axis labelled `x_label`; the GOSPA
/// chart only when the run was scored against a truth.
pub(crate) fn write(
    out: &Path,
    records: &[ScanRecord],
    x_label: &str,
    x: impl Fn(&ScanRecord) -> f64,
    gospa_name: &str,
    gospa_label: &str,
) -> Result<(), Error> {
    let mut series = vec![Series {
        name: "expected number of objects".into(),
        points: records.iter().map(|r| (x(r), r.expected_cardinality)).collect(),
        markers: false,
    }];
    if records.iter().any(|r| r.true_cardinality.is_some()) {
        series.push(Series {
            name: "true number of objects".into(),
            points: records.iter().filter_map(|r| r.true_cardinality.map(|c| (x(r), c as f64))).collect(),
            markers: false,
        });
    }
    plots::plot_series(
        &out.join("expected_cardinality"),
        "Expected number of objects",
        x_label,
        "objects",
        Scale::Linear,
        Scale::Linear,
        &series,
    )?;
    if records.iter().any(|r| r.gospa.is_some()) {
        let gospa_series = [Series {
            name: gospa_name.into(),
            points: records.iter().filter_map(|r| r.gospa.map(|g| (x(r), g))).collect(),
            markers: false,
        }];
        plots::plot_series(
            &out.join("gospa"),
            "GOSPA over the run",
            x_label,
            gospa_label,
            Scale::Linear,
            Scale::Linear,
            &gospa_series,
        )?;
    }
    Ok(())
}
