//! What the commands print on stdout: a short summary a person reads (what ran, the headline figures,
//! where the files are), or with `--json` the full JSON the command also writes to its files.

use crate::io::catalogue::sgp4_check::Sgp4CheckReport;
use crate::io::report::{Compare3dSummary, CompareReport, RunSummary, SamplerCheckReport, SoakReport};
use serde::Serialize;
use std::fmt::Write;
use std::path::Path;

/// Prints `value` as pretty JSON when `json`, else the human summary `human`.
pub(super) fn print(json: bool, value: &impl Serialize, human: impl FnOnce() -> String) {
    if json {
        println!("{}", serde_json::to_string_pretty(value).unwrap_or_default());
    } else {
        print!("{}", human());
    }
}

/// A figure or `-` when there is none.
fn or_dash(value: Option<f64>) -> String {
    value.map_or_else(|| "-".into(), |v| format!("{v:.4}"))
}

/// The summary of `run`, `track` and `run-catalogue` (files in `out`).
pub(super) fn run(summary: &RunSummary, out: &Path) -> String {
    let mut s = String::new();
    let sensors = summary.sensors.map_or_else(String::new, |n| format!(", {}", count(n, "sensor")));
    let _ = writeln!(
        s,
        "{}: {} ({} profile) over {} scans{sensors}",
        summary.scenario, summary.tracker, summary.profile, summary.scans
    );
    let truth = summary.true_final_cardinality.map_or_else(|| "no truth".into(), |n| format!("true {n}"));
    let _ = writeln!(
        s,
        "  objects at the end: expected {:.2}, MAP {} ({truth})",
        summary.final_expected_cardinality, summary.final_map_cardinality
    );
    let _ = writeln!(
        s,
        "  mean GOSPA {} (cut-off {}), mean OSPA {}, label switches {}",
        or_dash(summary.mean_gospa),
        summary.gospa_cutoff,
        or_dash(summary.mean_ospa),
        summary.label_switches
    );
    let births = &summary.births;
    let _ = writeln!(
        s,
        "  births confirmed {}/{}, false tracks {}, in-view misses {}, in-view red stars {}",
        births.births_confirmed,
        births.births_total,
        births.false_tracks.map_or_else(|| "-".into(), |n| n.to_string()),
        summary.in_view_misses_after_confirmation,
        summary.in_view_red_stars
    );
    let _ = writeln!(
        s,
        "  {:.3} ms per scan (max {:.3}), peak {} hypotheses, captured mass mean {:.6} (min {:.6})",
        summary.mean_ms_per_scan,
        summary.max_ms_per_scan,
        summary.peak_hypotheses,
        summary.mean_captured_mass,
        summary.min_captured_mass
    );
    let refused = summary.refused_scans.count;
    if summary.rejected_scans.len() > refused {
        let rejected = summary.rejected_scans.len() - refused;
        let _ = writeln!(s, "  {rejected} scans rejected (rejected_scans in summary.json)");
    }
    if refused > 0 {
        let _ = writeln!(s, "  {refused} scans refused for their input (refused_scans in summary.json)");
    }
    if summary.numerical_drops.count > 0 {
        let count = summary.numerical_drops.count;
        let _ = writeln!(s, "  {count} tracks dropped for a numerical failure (numerical_drops in summary.json)");
    }
    let _ = writeln!(s, "  files in {} (summary.json holds every figure; --json prints it)", out.display());
    s
}

/// The summary of `compare` on a version 1 file.
pub(super) fn compare(report: &CompareReport, out: &Path) -> String {
    let c = &report.summary;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{}: {} ({} profile) against the unbounded reference over {} scans",
        c.scenario, c.bounded_tracker, c.profile, c.scans
    );
    let _ = writeln!(
        s,
        "  captured mass mean {:.6} (min {:.6}), weight L1 mean {:.6}, MAP agreement {:.1}%",
        c.mean_captured_mass,
        c.min_captured_mass,
        c.mean_weight_l1,
        100.0 * c.map_agreement
    );
    for side in [&c.bounded, &c.reference] {
        let _ = writeln!(
            s,
            "  {}: mean GOSPA {}, {:.3} ms per scan (max {:.3})",
            side.tracker,
            or_dash(side.mean_gospa),
            side.mean_ms_per_scan,
            side.max_ms_per_scan
        );
    }
    let _ = writeln!(s, "  written to {}", out.join("compare.json").display());
    s
}

/// The summary of `compare` on a version 2 file.
pub(super) fn compare3d(c: &Compare3dSummary, out: &Path) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{} ({} profile) against the unbounded reference over {} scans of {}",
        c.tracker,
        c.profile,
        c.scans,
        count(c.sensors, "sensor")
    );
    let _ = writeln!(
        s,
        "  captured mass mean {:.6} (min {:.6}), MAP agreement {:.1}%, rejected scans: core {}, reference {}",
        c.mean_captured_mass,
        c.min_captured_mass,
        100.0 * c.map_agreement,
        c.core_rejected_scans,
        c.reference_rejected_scans
    );
    let _ = writeln!(s, "  written to {}", out.join("compare.json").display());
    s
}

/// The summary of `soak`.
pub(super) fn soak(r: &SoakReport, out: &Path) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "soak {}: {} scans (seed {})", r.scenario, r.scans, r.seed);
    let _ = writeln!(
        s,
        "  {:.3} ms per scan (max {:.3}), peak {} hypotheses, {} NaN, {} errors",
        r.mean_ms_per_scan,
        r.max_ms_per_scan,
        r.max_hypotheses,
        r.nan_count,
        r.errors_by_kind.values().sum::<u64>()
    );
    let _ = writeln!(
        s,
        "  final expected cardinality {:.2}, mean |cardinality error| {:.3}",
        r.final_expected_cardinality, r.mean_abs_cardinality_error
    );
    let _ = writeln!(s, "  written to {}", out.display());
    s
}

/// The summary of `sampler-check`.
pub(super) fn sampler_check(r: &SamplerCheckReport, out: &Path) -> String {
    format!(
        "sampler-check: {} cases (seed {}), {:.1} children per case on average\n  written to {}\n",
        r.cases,
        r.seed,
        r.mean_children_per_case,
        out.display()
    )
}

/// The summary of `sgp4-check`.
pub(super) fn sgp4_check(r: &Sgp4CheckReport, out: &Path) -> String {
    format!(
        "sgp4-check: {} cases, {} states, max error {:.3e} km / {:.3e} km/s, {} mismatched\n  written to {}\n",
        r.cases,
        r.states,
        r.max_position_error_km,
        r.max_velocity_error_km_s,
        r.mismatched_cases,
        out.display()
    )
}

/// The summary of a report with no figures of its own here (`perf`).
pub(super) fn written(what: &str, out: &Path) -> String {
    format!("{what}: written to {}\n", out.display())
}

/// `n` and `noun`, the noun in the plural unless `n` is 1.
fn count(n: usize, noun: &str) -> String {
    if n == 1 { format!("1 {noun}") } else { format!("{n} {noun}s") }
}
