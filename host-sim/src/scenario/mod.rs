//! Scenario files: models, sensor, birth/death model, tracker configuration, prior, scans and optional
//! truth, as JSON (format `rfisst-scenario/1`, documented field by field in `docs/scenario-format.md`).
//!
//! [`Scenario::load`] parses a file and checks everything a tracker relies on; any problem is a
//! [`ScenarioError`] whose one-line message names the field (`scans[12].time: ...`). Unknown fields are
//! rejected so that a typo cannot silently fall back to a default.

pub mod any;
mod births;
pub mod catalogue_stream;
pub mod checks;
pub mod from_catalogue;
pub mod from_simulation;
pub mod quote;
pub mod v2;

use serde::{Deserialize, Serialize};
use std::path::Path;

pub use any::{AnyScenario, load_any, parse_any};
pub use births::{AdmissiblePresetSpec, BirthRegionSpec, MeasuredBirthsSpec, SensorRegionSpec, TrackletSpec};
pub use checks::{MAX_COVARIANCE_ENTRY, MAX_FILE_BYTES, ScenarioError, one_line, read_limited};
pub(crate) use checks::{check_covariance, error, finite, finite_all, positive};
pub use quote::{Readable, cut_quotes, excerpt};

/// The format tag every scenario file carries.
pub const FORMAT: &str = "rfisst-scenario/1";

/// The largest label of a prior object: the labels above it are kept for the births that follow.
pub const MAX_PRIOR_LABEL: u32 = i32::MAX as u32;

/// The largest GOSPA order p.
pub const MAX_GOSPA_ORDER: f64 = 100.0;

/// The range of c^p (GOSPA cut-off c to the order p) and of the error bound: the metrics sum terms of
/// that size, so inside it a distance can neither overflow nor vanish.
pub const GOSPA_POWER_RANGE: (f64, f64) = (1e-200, 1e200);

/// A complete scenario.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scenario {
    /// Must be [`FORMAT`].
    pub format: String,
    /// The format version: absent or 1 (version 2 files are [`crate::scenario::v2`]'s).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub version: Option<u32>,
    /// Short name.
    pub name: String,
    /// Free text.
    #[serde(default)]
    pub description: String,
    /// How objects move.
    pub motion: MotionSpec,
    /// How the sensor measures.
    pub measurement: MeasurementSpec,
    /// Detection, clutter and field of view.
    pub sensor: SensorSpec,
    /// Birth model.
    pub birth: BirthSpec,
    /// β: probability that an object in the field of view dies before a scan.
    pub death_probability: f64,
    /// Tracker settings.
    pub tracker: TrackerSpec,
    /// The prior hypotheses.
    pub prior: PriorSpec,
    /// The scans, in time order.
    pub scans: Vec<ScanSpec>,
    /// Ground truth, when known.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub truth: Option<TruthSpec>,
    /// How results are scored.
    #[serde(default)]
    pub evaluation: EvaluationSpec,
}

/// Motion model.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "kebab-case", deny_unknown_fields)]
pub enum MotionSpec {
    /// Planar two-body gravity.
    TwoBody {
        /// μ (length³/s²).
        mu: f64,
        /// White acceleration noise spectral density q (length²/s³).
        acceleration_noise: f64,
        /// Largest RK4 sub-step (s).
        max_step: f64,
        /// Most sub-steps per prediction.
        max_substeps: u32,
    },
    /// 2-D constant velocity.
    ConstantVelocity {
        /// White acceleration noise spectral density q (length²/s³).
        acceleration_noise: f64,
    },
}

/// Measurement model.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "kebab-case", deny_unknown_fields)]
pub enum MeasurementSpec {
    /// Position (x, y) with Gaussian noise.
    Position {
        /// R (length²), symmetric positive definite.
        noise_covariance: [[f64; 2]; 2],
    },
}

/// Field of view.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "kebab-case", deny_unknown_fields)]
pub enum FieldOfViewSpec {
    /// A sector seen from `origin`.
    Sector {
        /// Sensor position (length).
        origin: [f64; 2],
        /// Boresight, degrees counter-clockwise from +x.
        look_direction_deg: f64,
        /// Full field-of-view angle, degrees.
        field_of_view_deg: f64,
        /// Largest range (length).
        max_range: f64,
    },
    /// An axis-aligned rectangle.
    Rectangle {
        /// Lower corner (length).
        min: [f64; 2],
        /// Upper corner (length).
        max: [f64; 2],
    },
    /// No boundary; clutter over an abstract volume.
    Everywhere {
        /// Clutter volume V (length²).
        volume: f64,
    },
}

/// Sensor.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SensorSpec {
    /// p_D in (0, 1].
    pub detection_probability: f64,
    /// Expected clutter returns per scan Λ_C (> 0).
    pub clutter_rate: f64,
    /// What the sensor sees.
    pub field_of_view: FieldOfViewSpec,
}

/// A Gaussian over the state (x, y, vx, vy).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GaussianSpec {
    /// Mean (length, length, length/s, length/s).
    pub mean: [f64; 4],
    /// Covariance, symmetric positive definite.
    pub covariance: [[f64; 4]; 4],
}

/// Whether births must be detected at birth.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum BirthDetectionSpec {
    /// Paper 000's "all births detected" (the default).
    #[default]
    AllDetected,
    /// Births may be missed like any object.
    AllowUndetected,
}

/// Whether `value` is its type's default (left out of written files).
pub(crate) fn is_default<T: Default + PartialEq>(value: &T) -> bool {
    *value == T::default()
}

/// How births combine in a scan (`tracker_core::BirthEvents`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum BirthEventsSpec {
    /// At most one birth per scan (R-FISST's first-order model; the default).
    #[default]
    FirstOrder,
    /// Each cell gives birth independently: several births per scan (docs/maths.md §5.6).
    Independent,
}

impl BirthEventsSpec {
    /// The core's value.
    pub fn core(self) -> tracker_core::BirthEvents {
        match self {
            BirthEventsSpec::FirstOrder => tracker_core::BirthEvents::FirstOrder,
            BirthEventsSpec::Independent => tracker_core::BirthEvents::Independent,
        }
    }
}

/// Birth model.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BirthSpec {
    /// α per cell per scan.
    pub probability: f64,
    /// Detection rule.
    #[serde(default)]
    pub detection: BirthDetectionSpec,
    /// At most one birth per scan, or independent births in every cell.
    #[serde(default, skip_serializing_if = "is_default")]
    pub events: BirthEventsSpec,
    /// Birth cells made from the measurements (docs/maths.md §5.8).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub measured: Option<MeasuredBirthsSpec>,
    /// Birth pdf of each cell.
    pub cells: Vec<GaussianSpec>,
}

/// Track-store overflow policy.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum StoreOverflowSpec {
    /// Drop the children that do not fit (the default).
    #[default]
    PruneChildren,
    /// Fail the scan.
    Error,
}

/// What a numerical failure of one track does to the scan (`tracker_core::NumericalFailure`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum NumericalFailureSpec {
    /// Drop that track from every hypothesis and go on (the default).
    #[default]
    DropTrack,
    /// Fail the scan.
    Error,
}

/// The Metropolis proposal.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum ProposalSpec {
    /// Paper 003's move (conflicting measurement to clutter).
    Paper,
    /// Symmetric move-or-swap.
    MoveOrSwap,
    /// Move-or-swap with every other column drawn from the row's entries (the default).
    #[default]
    Informed,
}

/// Settings of the R-FISST sampler (`--tracker rfisst`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SamplerSpec {
    /// Unrecorded steps per chain.
    pub burn_in: u32,
    /// Recorded steps per chain.
    pub steps: u32,
    /// Proposal.
    pub proposal: ProposalSpec,
    /// Split each association matrix into independent clusters.
    pub clusters: bool,
    /// Enumerate clusters with at most this many associations; sample larger ones.
    pub exhaustive_limit: u64,
    /// Start each chain at the exact mode of its matrix (and record the mode's neighbours).
    pub exact_start: bool,
}

impl Default for SamplerSpec {
    fn default() -> Self {
        let d = tracker_core::sampler::SamplerConfig::default();
        Self {
            burn_in: d.burn_in,
            steps: d.steps,
            proposal: ProposalSpec::Informed,
            clusters: d.clusters,
            exhaustive_limit: d.exhaustive_limit,
            exact_start: d.exact_start,
        }
    }
}

/// How H∞ hypotheses are chosen among the children.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum SelectionSpec {
    /// The H∞ largest weights (the default).
    #[default]
    TopWeight,
    /// H∞ drawn by weight without replacement.
    SampledByWeight,
    /// The H∞ largest weights, less those below 10^−decades of the heaviest (docs/maths.md §8.1).
    TopWeightWithin {
        /// The floor in powers of ten below the heaviest child.
        decades: u8,
    },
}

/// Tracker settings.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TrackerSpec {
    /// Gate on the squared Mahalanobis distance; `null` for no gate.
    pub gate: Option<f64>,
    /// Bound on exhaustive enumeration per scan.
    pub max_children_per_scan: u64,
    /// Track-store overflow policy.
    #[serde(default)]
    pub store_overflow: StoreOverflowSpec,
    /// Numerical failure policy.
    #[serde(default)]
    pub numerical_failure: NumericalFailureSpec,
    /// Declare a track lost after this many consecutive scans in view with no measurement in its gate
    /// (`tracker_core::TrackLoss`); absent: never.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lost_after_unseen_scans: Option<core::num::NonZeroU16>,
    /// Seed of every random choice.
    #[serde(deserialize_with = "quote::seed")]
    pub seed: u64,
    /// R-FISST sampler settings.
    #[serde(default)]
    pub sampler: SamplerSpec,
    /// H∞ selection.
    #[serde(default)]
    pub selection: SelectionSpec,
}

/// One prior object.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PriorObjectSpec {
    /// Label.
    pub label: u32,
    /// Mean.
    pub mean: [f64; 4],
    /// Covariance.
    pub covariance: [[f64; 4]; 4],
}

/// One prior hypothesis.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PriorHypothesisSpec {
    /// Relative weight (≥ 0).
    pub weight: f64,
    /// Objects.
    pub objects: Vec<PriorObjectSpec>,
}

/// The prior.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PriorSpec {
    /// Time of the prior (s).
    pub time: f64,
    /// Hypotheses.
    pub hypotheses: Vec<PriorHypothesisSpec>,
}

/// One scan.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScanSpec {
    /// Time (s), strictly after the previous scan and the prior.
    pub time: f64,
    /// Measurements (length).
    pub measurements: Vec<[f64; 2]>,
}

/// One true object.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TruthObjectSpec {
    /// Identifier used by the truth scans.
    pub id: u64,
    /// Whether the prior knows it; `false` makes it a birth.
    pub in_prior: bool,
    /// When it starts to exist (s); `null` for "before the prior".
    #[serde(default)]
    pub birth_time: Option<f64>,
    /// When it stops existing (s); `null` for never.
    #[serde(default)]
    pub death_time: Option<f64>,
}

/// The true state of one object at a scan.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TruthStateSpec {
    /// Object id.
    pub id: u64,
    /// State (x, y, vx, vy).
    pub state: [f64; 4],
}

/// The truth of one scan.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TruthScanSpec {
    /// Every object that exists at the scan time.
    pub objects: Vec<TruthStateSpec>,
    /// Per measurement, the id of the object that produced it, or `null` for clutter.
    pub origins: Vec<Option<u64>>,
}

/// Ground truth.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TruthSpec {
    /// The objects.
    pub objects: Vec<TruthObjectSpec>,
    /// One entry per scan.
    pub scans: Vec<TruthScanSpec>,
}

/// How results are scored.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EvaluationSpec {
    /// An estimate within this distance of a true object is correct (length).
    pub error_bound: f64,
    /// GOSPA cut-off c (length).
    pub gospa_cutoff: f64,
    /// GOSPA order p.
    pub gospa_order: f64,
    /// Existence probability at which a born object counts as confirmed.
    pub confirmation_existence: f64,
}

impl Default for EvaluationSpec {
    fn default() -> Self {
        Self { error_bound: 10.0, gospa_cutoff: 50.0, gospa_order: 2.0, confirmation_existence: 0.9 }
    }
}

impl Scenario {
    /// Reads and checks a scenario file of at most [`MAX_FILE_BYTES`].
    ///
    /// # Errors
    /// A one-line [`ScenarioError`] naming the file's problem.
    pub fn load(path: &Path) -> Result<Self, ScenarioError> {
        Self::from_json(&read_limited(path)?)
    }

    /// Parses and checks a scenario from JSON text (a leading byte-order mark is skipped).
    ///
    /// # Errors
    /// A one-line [`ScenarioError`] naming the field.
    pub fn from_json(text: &str) -> Result<Self, ScenarioError> {
        // A UTF-8 byte-order mark is not JSON, but editors write one: skip it.
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let deserializer = &mut serde_json::Deserializer::from_str(text);
        let scenario: Scenario = serde_path_to_error::deserialize(&mut *deserializer).map_err(|e| {
            // One line (`error`, `one_line`): keys and values may hold escaped line breaks.
            let path = e.path().to_string();
            let message = e.into_inner().to_string();
            if path == "." { error("invalid scenario JSON", message) } else { error(path, message) }
        })?;
        // Nothing but whitespace may follow the scenario.
        deserializer.end().map_err(|e| error("invalid scenario JSON", e))?;
        scenario.validate()?;
        Ok(scenario)
    }

    /// Writes the scenario as pretty JSON.
    ///
    /// # Errors
    /// [`crate::Error::Output`] when the file cannot be written.
    pub fn save(&self, path: &Path) -> Result<(), crate::Error> {
        crate::io::atomic::write_with(path, |w| serde_json::to_writer_pretty(w, self).map_err(std::io::Error::other))
    }

    /// Checks everything the trackers rely on that the JSON types cannot express.
    ///
    /// # Errors
    /// The first problem found.
    pub fn validate(&self) -> Result<(), ScenarioError> {
        if self.format != FORMAT {
            return Err(error("format", format!("expected \"{FORMAT}\", found \"{}\"", self.format)));
        }
        if let Some(version) = self.version
            && version != 1
        {
            return Err(error("version", format!("{version} does not go with format \"{FORMAT}\" (version 1)")));
        }
        self.validate_models()?;
        self.validate_sensor()?;
        self.validate_births_and_tracker()?;
        self.prior.validate()?;
        self.validate_scans()?;
        if let Some(truth) = &self.truth {
            truth.validate(&self.scans)?;
        }
        self.evaluation.validate()
    }

    /// Motion and measurement models.
    fn validate_models(&self) -> Result<(), ScenarioError> {
        match self.motion {
            MotionSpec::TwoBody { mu, acceleration_noise, max_step, max_substeps } => {
                positive("motion.mu", mu)?;
                positive("motion.acceleration_noise", acceleration_noise)?;
                positive("motion.max_step", max_step)?;
                if max_substeps == 0 {
                    return Err(error("motion.max_substeps", "must be > 0"));
                }
            }
            MotionSpec::ConstantVelocity { acceleration_noise } => {
                positive("motion.acceleration_noise", acceleration_noise)?
            }
        }
        let MeasurementSpec::Position { noise_covariance } = self.measurement;
        covariance2("measurement.noise_covariance", &noise_covariance)
    }

    /// Detection, clutter and field of view.
    fn validate_sensor(&self) -> Result<(), ScenarioError> {
        let sensor = &self.sensor;
        let pd = sensor.detection_probability;
        if !(pd.is_finite() && pd > 0.0 && pd <= 1.0) {
            return Err(error(
                "sensor.detection_probability",
                format!("{} is not in (0, 1]", crate::scenario::Readable(pd)),
            ));
        }
        positive("sensor.clutter_rate", sensor.clutter_rate)?;
        match sensor.field_of_view {
            FieldOfViewSpec::Sector { origin, look_direction_deg, field_of_view_deg, max_range } => {
                finite_all("sensor.field_of_view.origin", &origin)?;
                finite("sensor.field_of_view.look_direction_deg", look_direction_deg)?;
                if !(field_of_view_deg > 0.0 && field_of_view_deg <= 360.0) {
                    return Err(error(
                        "sensor.field_of_view.field_of_view_deg",
                        format!("{} is not in (0, 360]", crate::scenario::Readable(field_of_view_deg)),
                    ));
                }
                positive("sensor.field_of_view.max_range", max_range)
            }
            FieldOfViewSpec::Rectangle { min, max } => {
                finite_all("sensor.field_of_view.min", &min)?;
                finite_all("sensor.field_of_view.max", &max)?;
                if !(max[0] > min[0] && max[1] > min[1]) {
                    return Err(error("sensor.field_of_view", "max must exceed min on both axes"));
                }
                Ok(())
            }
            FieldOfViewSpec::Everywhere { volume } => positive("sensor.field_of_view.volume", volume),
        }
    }

    /// Birth and death probabilities, birth cells and the tracker settings.
    fn validate_births_and_tracker(&self) -> Result<(), ScenarioError> {
        let alpha = self.birth.probability;
        if !(alpha.is_finite() && (0.0..=1.0).contains(&alpha)) {
            return Err(error("birth.probability", format!("{} is not in [0, 1]", crate::scenario::Readable(alpha))));
        }
        if let Some(measured) = &self.birth.measured {
            measured.validate(self.birth.events)?;
        }
        for (i, cell) in self.birth.cells.iter().enumerate() {
            finite_all(&format!("birth.cells[{i}].mean"), &cell.mean)?;
            covariance4(&format!("birth.cells[{i}].covariance"), &cell.covariance)?;
        }
        let beta = self.death_probability;
        if !(beta.is_finite() && (0.0..=1.0).contains(&beta)) {
            return Err(error("death_probability", format!("{} is not in [0, 1]", crate::scenario::Readable(beta))));
        }
        if let Some(gate) = self.tracker.gate {
            positive("tracker.gate", gate)?;
        }
        if self.tracker.max_children_per_scan == 0 {
            return Err(error("tracker.max_children_per_scan", "must be > 0"));
        }
        if self.tracker.sampler.steps == 0 {
            return Err(error("tracker.sampler.steps", "must be > 0"));
        }
        Ok(())
    }

    /// Scan times and measurements.
    fn validate_scans(&self) -> Result<(), ScenarioError> {
        let mut previous = self.prior.time;
        for (k, scan) in self.scans.iter().enumerate() {
            finite(&format!("scans[{k}].time"), scan.time)?;
            if scan.time <= previous {
                return Err(error(
                    format!("scans[{k}].time"),
                    format!("{} is not after the previous time {previous}", scan.time),
                ));
            }
            previous = scan.time;
            for (j, z) in scan.measurements.iter().enumerate() {
                finite_all(&format!("scans[{k}].measurements[{j}]"), z)?;
            }
        }
        Ok(())
    }

    /// The largest number of measurements in one scan.
    pub fn max_measurements(&self) -> usize {
        self.scans.iter().map(|s| s.measurements.len()).max().unwrap_or(0)
    }
}

impl PriorSpec {
    /// Time, weights (finite, ≥ 0, with a finite positive sum), objects and labels.
    fn validate(&self) -> Result<(), ScenarioError> {
        finite("prior.time", self.time)?;
        if self.hypotheses.is_empty() {
            return Err(error("prior.hypotheses", "needs at least one hypothesis"));
        }
        let mut total = 0.0;
        for (h, hypothesis) in self.hypotheses.iter().enumerate() {
            let w = hypothesis.weight;
            if !(w.is_finite() && w >= 0.0) {
                return Err(error(
                    format!("prior.hypotheses[{h}].weight"),
                    format!("{} is not finite and >= 0", crate::scenario::Readable(w)),
                ));
            }
            total += w;
            for (o, object) in hypothesis.objects.iter().enumerate() {
                let field = format!("prior.hypotheses[{h}].objects[{o}]");
                if object.label > MAX_PRIOR_LABEL {
                    return Err(error(
                        format!("{field}.label"),
                        format!("{} is above {MAX_PRIOR_LABEL} (labels above it are kept for births)", object.label),
                    ));
                }
                finite_all(&format!("{field}.mean"), &object.mean)?;
                covariance4(&format!("{field}.covariance"), &object.covariance)?;
                if hypothesis.objects[..o].iter().any(|other| other.label == object.label) {
                    return Err(error(
                        format!("{field}.label"),
                        format!("label {} appears twice in the hypothesis", object.label),
                    ));
                }
            }
        }
        if !total.is_finite() {
            return Err(error("prior.hypotheses", "the sum of the weights overflows (is not finite)"));
        }
        if total <= 0.0 {
            return Err(error("prior.hypotheses", "weights sum to zero"));
        }
        Ok(())
    }
}

impl TruthSpec {
    /// One truth entry per scan, unique ids, known ids, one origin per measurement.
    fn validate(&self, scans: &[ScanSpec]) -> Result<(), ScenarioError> {
        if self.scans.len() != scans.len() {
            return Err(error("truth.scans", format!("has {} entries for {} scans", self.scans.len(), scans.len())));
        }
        for (i, object) in self.objects.iter().enumerate() {
            if self.objects[..i].iter().any(|other| other.id == object.id) {
                return Err(error(format!("truth.objects[{i}].id"), format!("id {} appears twice", object.id)));
            }
        }
        for (k, (scan, truth_scan)) in scans.iter().zip(&self.scans).enumerate() {
            if truth_scan.origins.len() != scan.measurements.len() {
                return Err(error(
                    format!("truth.scans[{k}].origins"),
                    format!("has {} entries for {} measurements", truth_scan.origins.len(), scan.measurements.len()),
                ));
            }
            for (i, state) in truth_scan.objects.iter().enumerate() {
                finite_all(&format!("truth.scans[{k}].objects[{i}].state"), &state.state)?;
                if !self.objects.iter().any(|o| o.id == state.id) {
                    return Err(error(
                        format!("truth.scans[{k}].objects[{i}].id"),
                        format!("unknown object id {}", state.id),
                    ));
                }
            }
            truth_scan.validate_origins(k)?;
        }
        Ok(())
    }
}

impl TruthScanSpec {
    /// Each object produces at most one measurement, and only while it exists.
    fn validate_origins(&self, k: usize) -> Result<(), ScenarioError> {
        for (j, origin) in self.origins.iter().enumerate() {
            let Some(id) = origin else { continue };
            if self.origins[..j].contains(&Some(*id)) {
                return Err(error(
                    format!("truth.scans[{k}].origins[{j}]"),
                    format!("object {id} already produced a measurement in this scan"),
                ));
            }
            if !self.objects.iter().any(|o| o.id == *id) {
                return Err(error(
                    format!("truth.scans[{k}].origins[{j}]"),
                    format!("object {id} does not exist at this scan"),
                ));
            }
        }
        Ok(())
    }
}

fn covariance2(field: &str, m: &[[f64; 2]; 2]) -> Result<(), ScenarioError> {
    let matrix = nalgebra::SMatrix::<f64, 2, 2>::from_fn(|i, j| m[i][j]);
    check_covariance(field, matrix)
}

fn covariance4(field: &str, m: &[[f64; 4]; 4]) -> Result<(), ScenarioError> {
    let matrix = nalgebra::SMatrix::<f64, 4, 4>::from_fn(|i, j| m[i][j]);
    check_covariance(field, matrix)
}
