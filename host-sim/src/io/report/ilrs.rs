//! `ilrs.json` of `host-sim track-ilrs`: what was read and left out, the settings chosen, and the
//! accuracy of the tracked laser ranges against the CPF's independent predictions (docs/results.md,
//! "Real data: laser ranging"). Lengths in m for ranges, km for positions.

use serde::{Deserialize, Serialize};

/// The whole file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IlrsReport {
    /// The target (the CPF's name).
    pub target: String,
    /// The epoch every time counts from.
    pub epoch: String,
    /// Normal points read from the CRD file.
    pub normal_points_read: usize,
    /// Of them, outside the CPF's span and left out.
    pub normal_points_outside_cpf: usize,
    /// Of them, tracked (scans the tracker took with the MAP track updated).
    pub normal_points_tracked: usize,
    /// The stations that ranged, as sensors (`<pad>-<name>`).
    pub stations: Vec<String>,
    /// The prior: its time (s), offset from the CPF (km, radial, in-track, cross-track) and σ.
    pub prior: IlrsPrior,
    /// σ of a range in the configuration (km).
    pub range_sigma_km: f64,
    /// Process noise q of the configuration (km²/s³).
    pub process_noise_km2_s3: f64,
    /// Measured range − the CPF's geometric range, per point (m): the data reduction against the
    /// predictions, independent of the tracker.
    pub range_minus_cpf_m: Stats,
    /// Measured range − the range of the tracker's updated state (m).
    pub range_minus_tracker_m: Stats,
    /// |tracker position − CPF position| (km), over every tracked point.
    pub position_vs_cpf_km: Stats,
    /// The same at the first and the last tracked point (km).
    pub position_vs_cpf_first_last_km: [f64; 2],
    /// Per pass (a station's run of consecutive points): the error at its last point.
    pub passes: Vec<IlrsPass>,
    /// Every tracked point.
    pub points: Vec<IlrsPoint>,
}

/// The prior's settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IlrsPrior {
    /// Its time (s since the epoch): the CPF's last record before the first point.
    pub time: f64,
    /// Offset from the CPF (km): radial, in-track, cross-track.
    pub offset_km: [f64; 3],
    /// σ per position axis (km).
    pub sigma_km: f64,
    /// σ per velocity axis (km/s).
    pub sigma_km_s: f64,
}

/// Count, mean, RMS and largest magnitude of a set of values.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Stats {
    /// How many.
    pub count: usize,
    /// Mean.
    pub mean: f64,
    /// Root mean square.
    pub rms: f64,
    /// Largest |value|.
    pub max_abs: f64,
}

impl Stats {
    /// The statistics of `values` (zeros when empty).
    pub fn of(values: &[f64]) -> Self {
        let n = values.len().max(1) as f64;
        Stats {
            count: values.len(),
            mean: values.iter().sum::<f64>() / n,
            rms: (values.iter().map(|v| v * v).sum::<f64>() / n).sqrt(),
            max_abs: values.iter().fold(0.0, |m, v| m.max(v.abs())),
        }
    }
}

/// One pass.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IlrsPass {
    /// The station.
    pub station: String,
    /// Its first and last point's time (s since the epoch).
    pub span: [f64; 2],
    /// Points tracked.
    pub points: usize,
    /// RMS of measured − tracker range over the pass (m).
    pub range_minus_tracker_rms_m: f64,
    /// Tracker − CPF position at the pass's last point (km): radial, in-track, cross-track, and its norm.
    pub position_vs_cpf_ric_km: [f64; 4],
}

/// One tracked point.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IlrsPoint {
    /// The bounce time (s since the epoch).
    pub time: f64,
    /// The station.
    pub station: String,
    /// Its CRD line.
    pub line: usize,
    /// The range given to the tracker (km).
    pub range_km: f64,
    /// Elevation (deg, from the CPF).
    pub elevation_deg: f64,
    /// The tropospheric delay removed (m).
    pub troposphere_m: f64,
    /// Range − CPF range (m).
    pub range_minus_cpf_m: f64,
    /// Range − tracker range (m).
    pub range_minus_tracker_m: f64,
    /// Tracker − CPF position (km): radial, in-track, cross-track, and its norm.
    pub position_vs_cpf_ric_km: [f64; 4],
}
