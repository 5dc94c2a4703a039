//! `host-sim experiment network`: the `ssa-network` preset tracked by one fused tracker, and by the same
//! tracker on each single-kind subset of its sensors (the radars alone, the radar with range-rate alone,
//! the telescopes alone, the az/el station alone, the ranging station alone), on the same truth
//! (docs/results.md, "One tracker for the whole network"). Writes `network.json` and each run's
//! directory (`fused/`, `subset-<kind>/`).

use crate::error::Error;
use crate::io::report::RunSummary;
use crate::pipeline::output::write_json;
use crate::pipeline::tracker::TrackerKind;
use crate::scenario::from_simulation::{Preset3d, to_scenario};
use crate::scenario::v2::{Measurement3dSpec, Scenario3d};
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::Path;

/// What one run gives.
#[derive(Debug, Clone, Serialize)]
pub struct NetworkRun {
    /// Scans tracked.
    pub scans: usize,
    /// Objects unknown to the prior and detected.
    pub births_total: usize,
    /// Of them, confirmed.
    pub births_confirmed: usize,
    /// Confirmed tracks that are no object.
    pub false_tracks: Option<usize>,
    /// Mean GOSPA (km).
    pub mean_gospa: Option<f64>,
    /// Tracks declared lost (`tracker.lost_after_unseen_scans`).
    pub lost_tracks: usize,
}

impl NetworkRun {
    fn of(summary: &RunSummary) -> Self {
        Self {
            scans: summary.scans,
            births_total: summary.births.births_total,
            births_confirmed: summary.births.births_confirmed,
            false_tracks: summary.births.false_tracks,
            mean_gospa: summary.mean_gospa,
            lost_tracks: summary.lost_tracks,
        }
    }
}

/// `network.json`.
#[derive(Debug, Clone, Serialize)]
pub struct NetworkFigures {
    /// The seed.
    pub seed: u64,
    /// The kinds of the sensors.
    pub sensor_kinds: Vec<String>,
    /// Objects.
    pub objects: usize,
    /// The fused tracker's figures (flattened: `births_total`, `births_confirmed`, `false_tracks`,
    /// `mean_gospa`, `lost_tracks`, `scans`).
    #[serde(flatten)]
    pub fused: NetworkRun,
    /// False tracks per 1,000 scans of the fused tracker.
    pub false_tracks_per_1000_scans: Option<f64>,
    /// The same tracker on each single-kind subset of the sensors, by kind.
    pub subsets: BTreeMap<String, NetworkRun>,
    /// The lowest mean GOSPA of a subset.
    pub best_subset_gospa: Option<f64>,
    /// Whether the fused tracker's mean GOSPA is below every subset's.
    pub fused_below_every_subset: bool,
}

/// `scenario` with only the sensors of `kind` and their scans (their truth kept).
pub fn subset(scenario: &Scenario3d, kind: Measurement3dSpec) -> Scenario3d {
    let kept: Vec<usize> = (0..scenario.sensors.len()).filter(|&i| scenario.kind(i) == kind).collect();
    let mut out = scenario.clone();
    out.name = format!("{} ({} only)", scenario.name, kind.name());
    out.sensors = kept.iter().map(|&i| scenario.sensors[i].clone()).collect();
    let scans: Vec<usize> = (0..scenario.scans.len()).filter(|&k| kept.contains(&scenario.scans[k].sensor)).collect();
    out.scans = scans
        .iter()
        .map(|&k| {
            let mut scan = scenario.scans[k].clone();
            scan.sensor = kept.iter().position(|&i| i == scan.sensor).unwrap_or(0);
            scan
        })
        .collect();
    if let (Some(truth), Some(source)) = (out.truth.as_mut(), scenario.truth.as_ref()) {
        truth.scans = scans.iter().map(|&k| source.scans[k].clone()).collect();
    }
    out
}

/// Runs the experiment for `seed` into `dir`.
///
/// # Errors
/// The simulation's or a run's error; [`Error::Output`] when a file cannot be written.
pub fn network(dir: &Path, seed: u64, quiet: bool) -> Result<NetworkFigures, Error> {
    let (scenario, _) = to_scenario(&Preset3d::SsaNetwork.simulate(seed)?)?;
    scenario.save(&dir.join("scenario.json"))?;
    let run = |scenario: &Scenario3d, name: &str| -> Result<NetworkRun, Error> {
        let (summary, _) = crate::pipeline::orbital::run(scenario, TrackerKind::Rfisst, None, quiet, &dir.join(name))?;
        Ok(NetworkRun::of(&summary))
    };
    let fused = run(&scenario, "fused")?;
    let mut subsets = BTreeMap::new();
    for kind in scenario.sensor_kinds() {
        subsets.insert(kind.name().to_string(), run(&subset(&scenario, kind), &format!("subset-{}", kind.name()))?);
    }
    let best_subset_gospa = subsets.values().filter_map(|s| s.mean_gospa).min_by(f64::total_cmp);
    let fused_below_every_subset = match (fused.mean_gospa, best_subset_gospa) {
        (Some(fused), Some(best)) => fused < best,
        _ => false,
    };
    let figures = NetworkFigures {
        seed,
        sensor_kinds: scenario.sensor_kinds().iter().map(|k| k.name().to_string()).collect(),
        objects: scenario.truth.as_ref().map_or(0, |t| t.objects.len()),
        false_tracks_per_1000_scans: fused.false_tracks.map(|f| f as f64 * 1000.0 / fused.scans.max(1) as f64),
        fused,
        subsets,
        best_subset_gospa,
        fused_below_every_subset,
    };
    write_json(&dir.join("network.json"), &figures)?;
    Ok(figures)
}
