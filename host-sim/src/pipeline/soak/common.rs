//! What the soaks of every world share: the soak's scenario, the scan limit, the health counts of a run,
//! the times per scan in constant memory, the non-finite value count and the progress bar.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::collections::BTreeMap;
use std::io::IsTerminal;
use tracker_core::{MeasurementModel, MotionModel, Tracker};

/// The most scans of one soak: the run keeps one time per scan (4 bytes) for its percentiles.
pub const MAX_SCANS: u64 = 10_000_000;

/// The scenario of a soak.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Scenario {
    /// Paper 003's planar SSA geometry with births and deaths ([`crate::pipeline::soak::planar`]).
    Planar,
    /// `generate radar-leo`'s radars and objects, observed without end ([`crate::pipeline::soak::orbital`]).
    RadarLeo,
    /// `generate optical-geo`'s telescope and objects, observed without end ([`crate::pipeline::soak::orbital`]).
    OpticalGeo,
    /// `generate ssa-network`'s sensors of mixed kinds and objects (births included), observed without end, by
    /// one fused tracker ([`crate::pipeline::soak::orbital`]).
    SsaNetwork,
}

impl Scenario {
    /// The name on the command line and in the report.
    pub fn name(self) -> &'static str {
        match self {
            Scenario::Planar => "planar",
            Scenario::RadarLeo => "radar-leo",
            Scenario::OpticalGeo => "optical-geo",
            Scenario::SsaNetwork => "ssa-network",
        }
    }
}

/// Counts of what one run saw.
#[derive(Default)]
pub(crate) struct Health {
    pub(crate) non_finite: u64,
    pub(crate) non_finite_scans: u64,
    pub(crate) first_non_finite_scan: Option<u64>,
    pub(crate) errors: BTreeMap<String, u64>,
    pub(crate) first_error: Option<(u64, String)>,
    pub(crate) max_hypotheses: usize,
    pub(crate) max_tracks: usize,
    pub(crate) max_measurements: usize,
    pub(crate) births_beyond_capacity: u64,
    pub(crate) children_dropped_for_store: u64,
    pub(crate) numerical_drops: u64,
}

impl Health {
    /// Scan `k`'s step result and the number of non-finite values in the tracker after it.
    pub(crate) fn record(
        &mut self,
        k: u64,
        result: Result<tracker_core::StepReport<f64>, tracker_core::StepError>,
        bad: u64,
    ) {
        match result {
            Ok(report) => {
                self.max_hypotheses = self.max_hypotheses.max(report.hypotheses);
                self.max_tracks = self.max_tracks.max(report.tracks);
                self.births_beyond_capacity += report.births_beyond_object_capacity;
                self.children_dropped_for_store += report.children_dropped_for_store as u64;
                self.numerical_drops += report.numerical_drops.count as u64;
            }
            Err(error) => self.error(k, variant(&error), error.to_string()),
        }
        if bad > 0 {
            self.non_finite += bad;
            self.non_finite_scans += 1;
            self.first_non_finite_scan.get_or_insert(k + 1);
        }
    }

    /// An error of kind `kind` at scan `k`.
    pub(crate) fn error(&mut self, k: u64, kind: String, message: String) {
        *self.errors.entry(kind).or_default() += 1;
        self.first_error.get_or_insert((k + 1, message));
    }
}

/// The times per scan in constant memory, so that the soak's own bookkeeping does not grow with the scans
/// it measures: the maximum and the mean exactly, the percentiles from a histogram of bins 1 % wide (from
/// 1 ns to 10⁶ ms; the percentile is its bin's geometric centre, within 0.5 %), the means over the first
/// and the last tenth of the planned scans exactly.
pub(crate) struct ScanTimes {
    tenth: u64,
    planned: u64,
    count: u64,
    max: f64,
    sum: f64,
    first_tenth: (f64, u64),
    last_tenth: (f64, u64),
    bins: Vec<u64>,
}

/// The smallest time the histogram resolves (ms) and its bins' width ratio.
const SMALLEST_MS: f64 = 1e-6;
const BIN_RATIO: f64 = 1.01;
const BINS: usize = 2_800; // 1.01^2800 ≈ 1.2e12: up to 10⁶ ms

impl ScanTimes {
    /// For a run of `planned` scans.
    pub(crate) fn new(planned: u64) -> Self {
        ScanTimes {
            tenth: (planned / 10).max(1),
            planned,
            count: 0,
            max: 0.0,
            sum: 0.0,
            first_tenth: (0.0, 0),
            last_tenth: (0.0, 0),
            bins: vec![0; BINS],
        }
    }

    /// Records the time of scan `k` (ms).
    pub(crate) fn record(&mut self, k: u64, ms: f64) {
        self.count += 1;
        self.max = self.max.max(ms);
        self.sum += ms;
        if k < self.tenth {
            self.first_tenth.0 += ms;
            self.first_tenth.1 += 1;
        }
        if k >= self.planned.saturating_sub(self.tenth) {
            self.last_tenth.0 += ms;
            self.last_tenth.1 += 1;
        }
        let bin = ((ms / SMALLEST_MS).max(1.0).ln() / BIN_RATIO.ln()) as usize;
        self.bins[bin.min(BINS - 1)] += 1;
    }

    /// The percentile `p` in [0, 1] (ms): the centre of the bin holding it.
    fn percentile(&self, p: f64) -> f64 {
        let rank = (p * self.count.saturating_sub(1) as f64).round() as u64;
        let mut seen = 0;
        for (bin, &n) in self.bins.iter().enumerate() {
            seen += n;
            if seen > rank {
                return SMALLEST_MS * BIN_RATIO.powf(bin as f64 + 0.5);
            }
        }
        0.0
    }

    /// (max, mean, p50, p99) in ms.
    pub(crate) fn timing(&self) -> (f64, f64, f64, f64) {
        let mean = self.sum / self.count.max(1) as f64;
        (self.max, mean, self.percentile(0.5), self.percentile(0.99))
    }

    /// The mean time per scan (ms) over the first and the last tenth of the scans.
    pub(crate) fn tenths(&self) -> (f64, f64) {
        let mean = |(sum, n): (f64, u64)| sum / n.max(1) as f64;
        (mean(self.first_tenth), mean(self.last_tenth))
    }
}

/// The name of an error's variant (`Numerical { .. }` → `Numerical`).
fn variant(error: &tracker_core::StepError) -> String {
    let text = format!("{error:?}");
    text.split(|c: char| !c.is_alphanumeric()).next().unwrap_or_default().to_string()
}

/// Non-finite values among the tracker's weights, means, covariances and existence probabilities.
pub(crate) fn non_finite_values<
    M: MotionModel<f64, S>,
    G: MeasurementModel<f64, S, D>,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
>(
    tracker: &Tracker<f64, M, G, S, D, H, N, Z, K, B>,
) -> u64 {
    let weights = tracker.hypotheses().filter(|h| !h.weight().is_finite() || !h.log_weight().is_finite()).count();
    let tracks: usize = tracker
        .tracks()
        .iter()
        .map(|t| {
            let state = &t.state;
            state.mean.iter().chain(state.covariance.iter()).filter(|v| !v.is_finite()).count()
                + usize::from(!t.existence.is_finite())
        })
        .sum();
    (weights + tracks) as u64
}

pub(crate) fn progress(scans: u64, quiet: bool) -> ProgressBar {
    if quiet || !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::with_draw_target(Some(scans), ProgressDrawTarget::stderr());
    if let Ok(style) = ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} scans, {elapsed} (eta {eta})") {
        bar.set_style(style.progress_chars("=> "));
    }
    bar.set_message("soak");
    bar
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scan_times_in_constant_memory_match_the_exact_figures() {
        // 1000 scans of 1, 2, …, 1000 µs: exact max and mean, percentiles within the bins' 0.5 %.
        let mut times = ScanTimes::new(1000);
        for k in 0..1000u64 {
            times.record(k, (k + 1) as f64 * 1e-3);
        }
        let (max, mean, p50, p99) = times.timing();
        assert_eq!(max, 1.0);
        assert!((mean - 0.5005).abs() < 1e-12);
        assert!((p50 / 0.5005 - 1.0).abs() < 0.006, "{p50}");
        assert!((p99 / 0.990 - 1.0).abs() < 0.006, "{p99}");
        let (first, last) = times.tenths();
        assert!((first - 0.0505).abs() < 1e-12 && (last - 0.9505).abs() < 1e-12, "{first} {last}");
        assert_eq!(times.bins.len(), BINS, "the histogram does not grow");
    }
}
