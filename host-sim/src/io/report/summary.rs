//! `summary.json` of `run` (and of `experiment fifty`): the run's figures, its births and its rejected scans.

use serde::{Deserialize, Serialize};

/// `summary.json` of `host-sim run` (and `experiment fifty`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RunSummary {
    /// Scenario name.
    pub scenario: String,
    /// Tracker (`rfisst`, `homht` or `reference`).
    pub tracker: String,
    /// Capacity profile, `unbounded` for the reference.
    pub profile: String,
    /// Number of scans.
    pub scans: usize,
    /// Mean GOSPA of the MAP estimates; `null` without truth.
    pub mean_gospa: Option<f64>,
    /// Mean OSPA of the MAP estimates; `null` without truth.
    pub mean_ospa: Option<f64>,
    /// GOSPA cut-off c.
    pub gospa_cutoff: f64,
    /// GOSPA order p.
    pub gospa_order: f64,
    /// Error bound.
    pub error_bound: f64,
    /// Expected number of objects after the last scan (of the prior when there is no scan).
    pub final_expected_cardinality: f64,
    /// Objects of the MAP hypothesis after the last scan (of the prior when there is no scan).
    pub final_map_cardinality: usize,
    /// True number of objects at the last scan.
    pub true_final_cardinality: Option<usize>,
    /// Births: their confirmation, detections to confirmation and false tracks.
    #[serde(flatten)]
    pub births: BirthsSummary,
    /// Label switches along GOSPA's assignment.
    pub label_switches: usize,
    /// Confirmed objects in view without a MAP estimate within the error bound, summed over scans.
    pub in_view_misses_after_confirmation: usize,
    /// MAP estimates in view outside the error bound of every object, summed over scans.
    pub in_view_red_stars: usize,
    /// The same out of view.
    pub out_of_view_red_stars: usize,
    /// Mean time of an accepted scan (ms).
    pub mean_ms_per_scan: f64,
    /// Largest time of an accepted scan (ms).
    pub max_ms_per_scan: f64,
    /// Largest number of hypotheses.
    pub peak_hypotheses: usize,
    /// Mean captured mass of the accepted scans.
    pub mean_captured_mass: f64,
    /// Smallest captured mass of the accepted scans.
    pub min_captured_mass: f64,
    /// The scans the tracker did not take: those it rejected and those it refused for their input (listed
    /// again, with their sensor and time, in `refused_scans`).
    pub rejected_scans: Vec<RejectedScan>,
    /// Scans at which the reference's memory budget forced pruning.
    pub reference_budget_reached_scans: Vec<usize>,
    /// The process's peak resident memory (VmHWM, KiB) when the summary was written, where the OS tells it.
    pub peak_resident_kib: Option<u64>,
    /// Version 2 (3-D) scenarios only: the number of sensors. Absent from version 1 runs.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sensors: Option<usize>,
    /// Version 2 (3-D) scenarios only: the kinds of the sensors, each once (`radar`, `radar-range-rate`,
    /// `optical`, `az-el`, `range`, `range-range-rate`). Absent from version 1 runs.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sensor_kinds: Option<Vec<String>>,
    /// Tracks the core dropped for a numerical failure (issue 33).
    #[serde(default)]
    pub numerical_drops: super::NumericalDropsSummary,
    /// Tracks the core declared lost and dropped (`tracker.lost_after_unseen_scans`, docs/maths.md §5.9).
    /// Absent when none.
    #[serde(default, skip_serializing_if = "crate::scenario::is_default")]
    pub lost_tracks: usize,
    /// Tracklets linked: unexplained measurements whose birth cells came from a tracklet
    /// (`birth.measured.tracklets`, docs/maths.md §5.10), summed over the scans. Absent when none.
    #[serde(default, skip_serializing_if = "crate::scenario::is_default")]
    pub tracklets_formed: usize,
    /// Born labels (not the prior's) that the MAP hypothesis held with existence ≥ `confirmation_existence`
    /// at some scan, when every birth cell comes from a tracklet (`birth.measured.tracklets` with
    /// `single_frame` false, no `link_waiting`, no fixed cells, only sensors of directions); counted whether
    /// or not the track is near a true object (those that are not are also `false_tracks`). Absent
    /// otherwise: a born label's cells are not traced to their tracklet.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tracklet_births: Option<usize>,
    /// Scans the core refused for their input; the run went on (issue 29).
    #[serde(default)]
    pub refused_scans: super::RefusedScans,
    /// `run-catalogue` only: the element sets its scenario left out (inside the Earth, decaying or failing
    /// SGP4 during the run, given twice). Absent from other runs.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub catalogue_dropped: Option<crate::io::catalogue::CatalogueDropped>,
    /// Runs of the core trackers: per sensor, the residuals and NIS of the MAP tracks' associated
    /// measurements ([`crate::eval::consistency`], issue 29). Absent from the reference's runs, like the four
    /// keys below.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub residuals: Option<std::collections::BTreeMap<String, super::SensorResiduals>>,
    /// MAP labels appearing over the run.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tracks_started: Option<usize>,
    /// MAP labels disappearing over the run.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tracks_ended: Option<usize>,
    /// Associated measurements per MAP label seen over the run (the prior's included).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub measurements_per_track: Option<f64>,
    /// Sensors whose `mean_nis` lies outside its `nis_band`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub consistency_warnings: Option<Vec<String>>,
    /// Version 2 (3-D) runs with truth: objects observed (measured at least once) by the last scan
    /// ([`crate::eval::observed`]). Absent from other runs, like the three keys below.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub observed_objects: Option<usize>,
    /// Objects never observed by the last scan.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub unobserved_objects: Option<usize>,
    /// Median error (km) at the last scan of the objects observed so far: true position to its MAP track
    /// (the prior label's, else the nearest within 100 km; none counts as 100 km). Absent when none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub observed_median_error_km: Option<f64>,
    /// Median prediction error (km) at the last scan of the objects never observed. Absent when none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub unobserved_median_error_km: Option<f64>,
}

/// The summary figures of a birth tally (`births::BirthTally::figures`), from which [`BirthsSummary`] is made.
#[derive(Debug, Clone, PartialEq)]
pub struct BirthFigures {
    /// Births in the truth.
    pub births_total: usize,
    /// Births confirmed.
    pub births_confirmed: usize,
    /// Per birth, in id order.
    pub records: Vec<BirthRecord>,
    /// Mean detections to confirmation of the confirmed births (`None`: none confirmed).
    pub mean_detections_to_confirm: Option<f64>,
    /// Largest detections to confirmation (`None`: none confirmed).
    pub max_detections_to_confirm: Option<usize>,
    /// Most confirmed labels that took one confirmed birth (`None`: none confirmed).
    pub max_labels_per_birth: Option<usize>,
    /// False tracks over the run.
    pub false_tracks: usize,
}

/// The births of a run, flattened into its summary (docs/scenario-format.md, summary keys).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
pub struct BirthsSummary {
    /// Born objects in the truth.
    pub births_total: usize,
    /// Born objects confirmed.
    pub births_confirmed: usize,
    /// Per born object, the scan of its confirmation.
    pub birth_confirmation_scans: Vec<BirthConfirmation>,
    /// Per born object, detections and scans from its first detection to its confirmation.
    #[serde(default)]
    pub birth_confirmations: Vec<BirthRecord>,
    /// Mean detections to confirmation of the confirmed births; `null` when none is.
    #[serde(default)]
    pub mean_detections_to_confirm: Option<f64>,
    /// Largest detections to confirmation; `null` when no birth is confirmed.
    #[serde(default)]
    pub max_detections_to_confirm: Option<usize>,
    /// Over the confirmed births, the most distinct confirmed labels GOSPA assigned to one of them (1: each
    /// confirmed under one label); `null` when no birth is confirmed.
    #[serde(default)]
    pub max_labels_per_birth: Option<usize>,
    /// MAP labels confirmed at some scan and never within the error bound of an object; `null` without
    /// truth.
    #[serde(default)]
    pub false_tracks: Option<usize>,
}

impl BirthsSummary {
    /// The summary of `figures`; false tracks only with a truth to compare with.
    pub fn new(figures: BirthFigures, has_truth: bool) -> Self {
        BirthsSummary {
            births_total: figures.births_total,
            births_confirmed: figures.births_confirmed,
            birth_confirmation_scans: figures
                .records
                .iter()
                .map(|r| BirthConfirmation { object: r.object, scan: r.confirmation_scan })
                .collect(),
            mean_detections_to_confirm: figures.mean_detections_to_confirm,
            max_detections_to_confirm: figures.max_detections_to_confirm,
            max_labels_per_birth: figures.max_labels_per_birth,
            false_tracks: has_truth.then_some(figures.false_tracks),
            birth_confirmations: figures.records,
        }
    }
}

/// A born object and the scan at which it was confirmed (`null`: never).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BirthConfirmation {
    /// Truth id.
    pub object: u64,
    /// Scan index.
    pub scan: Option<usize>,
}

/// A born object's way to confirmation ([`crate::eval::births`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BirthRecord {
    /// Truth id.
    pub object: u64,
    /// Scan of its first measurement (`null`: never detected).
    pub first_detection_scan: Option<usize>,
    /// Scan of its confirmation (`null`: never).
    pub confirmation_scan: Option<usize>,
    /// Its measurements up to and including the confirmation scan (`null`: never confirmed).
    pub detections_to_confirm: Option<usize>,
    /// Scans from the first detection to the confirmation, both counted (`null`: never confirmed).
    pub scans_to_confirm: Option<usize>,
    /// Distinct confirmed labels GOSPA assigned to it from its first detection on (0: never confirmed).
    #[serde(default)]
    pub confirmed_labels: usize,
}

/// A scan the tracker rejected.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RejectedScan {
    /// Scan index.
    pub scan: usize,
    /// The tracker's message.
    pub error: String,
}
