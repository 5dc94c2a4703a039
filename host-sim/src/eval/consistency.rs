//! Judging a run without truth (issue 29 item 5): per sensor, the residuals and the normalised innovation
//! squared (NIS) of the measurements associated with the MAP tracks, with the χ² band of their mean; the MAP
//! labels started and ended; the measurements per track.
//!
//! Association rule (docs/maths.md, "Judging a run without truth"): before each scan, every MAP track is
//! predicted to the scan's time and put through the scan's placed measurement model (ν = z − ẑ as the
//! model forms it, angles wrapped; S = H P⁻ Hᵀ + R); a measurement is associated with the MAP track of
//! smallest d² = νᵀ S⁻¹ ν when that d² lies below the χ²_d 99.9 % gate ([`gate`]), and with none
//! otherwise. Only scans the tracker took count. A sensor is flagged ([`inconsistent`]) when its mean NIS
//! lies outside its band, or when it has measurements and none is associated.
//!
//! χ² quantiles use the Wilson–Hilferty approximation χ²_p(k) ≈ k (1 − 2/(9k) + z_p √(2/(9k)))³, z_p the
//! standard normal quantile ([`chi2_quantile`]).

use crate::io::report::SensorResiduals;
use std::collections::{BTreeMap, BTreeSet};

/// z of the standard normal at 0.975 (the upper end of a two-sided 95 % band).
const Z_975: f64 = 1.959_963_984_540_054;
/// z of the standard normal at 0.999 (the association gate).
const Z_999: f64 = 3.090_232_306_167_813;

/// The χ² quantile of `k` degrees of freedom at the standard normal quantile `z` (Wilson–Hilferty).
pub fn chi2_quantile(z: f64, k: f64) -> f64 {
    let a = 2.0 / (9.0 * k);
    (k * (1.0 - a + z * a.sqrt()).powi(3)).max(0.0)
}

/// The association gate on d² for a measurement of `dimension` components: χ²_d at 99.9 %.
pub fn gate(dimension: usize) -> f64 {
    chi2_quantile(Z_999, dimension as f64)
}

/// The two-sided 95 % band of the mean of `n` NIS values of `dimension` components:
/// [χ²_{0.025}(n d) / n, χ²_{0.975}(n d) / n].
pub fn nis_band(n: usize, dimension: usize) -> [f64; 2] {
    let k = (n * dimension) as f64;
    [chi2_quantile(-Z_975, k) / n as f64, chi2_quantile(Z_975, k) / n as f64]
}

/// One measurement associated with a MAP track.
#[derive(Debug, Clone, PartialEq)]
pub struct Associated {
    /// The MAP track's label.
    pub label: u32,
    /// ν = z − ẑ per component, in the file's units (km, degrees, km/s).
    pub residual: Vec<f64>,
    /// νᵀ S⁻¹ ν.
    pub nis: f64,
}

/// A scan's measurements and those associated with MAP tracks.
#[derive(Debug, Clone, PartialEq)]
pub struct ScanAssociations {
    /// The scan's sensor.
    pub sensor: String,
    /// Components per measurement.
    pub dimension: usize,
    /// Measurements in the scan.
    pub measurements: usize,
    /// The associated ones.
    pub associated: Vec<Associated>,
}

/// Per sensor sums.
#[derive(Debug, Clone, Default)]
struct SensorTally {
    dimension: usize,
    measurements: usize,
    associated: usize,
    squares: Vec<f64>,
    nis: f64,
}

/// The run's tally of associations and MAP labels.
#[derive(Debug, Clone, Default)]
pub struct Judge {
    sensors: BTreeMap<String, SensorTally>,
    labels: BTreeSet<u32>,
    previous: BTreeSet<u32>,
    started: usize,
    ended: usize,
}

/// What the summary says of the run's consistency.
#[derive(Debug, Clone, PartialEq)]
pub struct Judgement {
    /// Per sensor.
    pub residuals: BTreeMap<String, SensorResiduals>,
    /// MAP labels appearing over the run.
    pub tracks_started: usize,
    /// MAP labels disappearing over the run.
    pub tracks_ended: usize,
    /// Associated measurements per MAP label seen (the prior's included); 0 without labels.
    pub measurements_per_track: f64,
    /// Sensors whose mean NIS lies outside its band.
    pub consistency_warnings: Vec<String>,
}

impl Judge {
    /// A tally starting from the prior's MAP labels.
    pub fn new(prior: impl IntoIterator<Item = u32>) -> Self {
        let previous: BTreeSet<u32> = prior.into_iter().collect();
        Self { labels: previous.clone(), previous, ..Self::default() }
    }

    /// Records the associations of a scan the tracker took.
    pub fn scan(&mut self, scan: &ScanAssociations) {
        let tally = self.sensors.entry(scan.sensor.clone()).or_default();
        tally.dimension = scan.dimension;
        tally.measurements += scan.measurements;
        tally.squares.resize(scan.dimension, 0.0);
        for a in &scan.associated {
            tally.associated += 1;
            tally.nis += a.nis;
            for (sum, r) in tally.squares.iter_mut().zip(&a.residual) {
                *sum += r * r;
            }
        }
    }

    /// Records the MAP labels after a scan: those new are started, those gone ended.
    pub fn labels(&mut self, map: impl IntoIterator<Item = u32>) {
        let now: BTreeSet<u32> = map.into_iter().collect();
        self.started += now.difference(&self.previous).count();
        self.ended += self.previous.difference(&now).count();
        self.labels.extend(now.iter().copied());
        self.previous = now;
    }

    /// The run's judgement.
    pub fn finish(&self) -> Judgement {
        let residuals: BTreeMap<String, SensorResiduals> =
            self.sensors.iter().map(|(name, t)| (name.clone(), residuals(t))).collect();
        let consistency_warnings =
            residuals.iter().filter(|(_, r)| inconsistent(r)).map(|(name, _)| name.clone()).collect();
        let associated: usize = self.sensors.values().map(|t| t.associated).sum();
        Judgement {
            residuals,
            tracks_started: self.started,
            tracks_ended: self.ended,
            measurements_per_track: if self.labels.is_empty() {
                0.0
            } else {
                associated as f64 / self.labels.len() as f64
            },
            consistency_warnings,
        }
    }
}

/// Whether a sensor's statistics fall outside their band: its mean NIS outside the 95 % band, or
/// measurements of which none lies within a MAP track's gate (a bias far beyond the gate leaves no NIS to
/// average; every measurement of such a sensor is beyond the 99.9 % gate of every track).
pub fn inconsistent(r: &SensorResiduals) -> bool {
    match (r.mean_nis, r.nis_band) {
        (Some(mean), Some([low, high])) => mean < low || mean > high,
        _ => r.measurements > 0,
    }
}

/// A sensor's figures from its sums (`null` RMS, NIS and band without associated measurements).
fn residuals(t: &SensorTally) -> SensorResiduals {
    let n = t.associated;
    let associated = n > 0;
    SensorResiduals {
        rms: associated.then(|| t.squares.iter().map(|s| (s / n as f64).sqrt()).collect()),
        mean_nis: associated.then(|| t.nis / n as f64),
        nis_band: associated.then(|| nis_band(n, t.dimension)),
        associated_fraction: if t.measurements > 0 { n as f64 / t.measurements as f64 } else { 0.0 },
        measurements: t.measurements,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wilson_hilferty_is_close_to_the_tables() {
        // χ² tables: χ²_{0.975}(10) = 20.483, χ²_{0.025}(10) = 3.247, χ²_{0.999}(3) = 16.266, χ²_{0.999}(2) = 13.816.
        assert!((chi2_quantile(Z_975, 10.0) - 20.483).abs() < 0.05);
        assert!((chi2_quantile(-Z_975, 10.0) - 3.247).abs() < 0.05);
        assert!((gate(3) - 16.266).abs() < 0.3, "{}", gate(3));
        assert!((gate(2) - 13.816).abs() < 0.5, "{}", gate(2));
        let [low, high] = nis_band(100, 3);
        assert!(low < 3.0 && high > 3.0 && (high - low - 2.0 * 1.96 * (6.0f64 / 100.0).sqrt()).abs() < 0.05);
    }

    #[test]
    fn a_biased_sensor_is_flagged_and_labels_are_counted() {
        let mut judge = Judge::new([1]);
        for k in 0..50 {
            let unit = Associated { label: 1, residual: vec![1.0, 0.0], nis: if k % 2 == 0 { 1.0 } else { 3.0 } };
            let biased = Associated { label: 1, residual: vec![5.0, 0.0], nis: 25.0 };
            judge.scan(&ScanAssociations { sensor: "a".into(), dimension: 2, measurements: 2, associated: vec![unit] });
            judge.scan(&ScanAssociations {
                sensor: "b".into(),
                dimension: 2,
                measurements: 1,
                associated: vec![biased],
            });
        }
        judge.scan(&ScanAssociations { sensor: "c".into(), dimension: 2, measurements: 3, associated: vec![] });
        judge.scan(&ScanAssociations { sensor: "d".into(), dimension: 2, measurements: 0, associated: vec![] });
        judge.labels([1, 2]);
        judge.labels([2]);
        let j = judge.finish();
        assert_eq!(j.consistency_warnings, ["b", "c"], "c: measurements, none associated; d: none");
        assert_eq!((j.tracks_started, j.tracks_ended), (1, 1));
        assert_eq!(j.measurements_per_track, 50.0);
        let a = &j.residuals["a"];
        assert_eq!((a.mean_nis, a.associated_fraction, a.measurements), (Some(2.0), 0.5, 100));
        assert_eq!(a.rms, Some(vec![1.0, 0.0]));
    }
}
