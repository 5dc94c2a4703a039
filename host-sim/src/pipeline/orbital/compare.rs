//! `host-sim compare` on a version 2 file: the bounded tracker and the unbounded reference on the same
//! scans ([`crate::eval::exactness::compare_scans`]).

use super::tracker::{ScenarioNetwork, choose_profile, config3d, padded};
use crate::error::Error;
use crate::eval::exactness::{CompareFigures, Scan, compare_scans_with_budget};
use crate::pipeline::profile::ORBITAL;
use crate::pipeline::profile::Profile;
use crate::pipeline::tracker::{ReferenceBudget, TrackerKind};
use crate::scenario::v2::Scenario3d;
use crate::{with_capacities, with_measurement};
use tracker_core::sensor::ScanGeometry;

/// The scans of `scenario` as the trackers take them (angles in radians, corrections removed).
fn scans3d<const D: usize>(scenario: &Scenario3d) -> Vec<Scan<D>> {
    scenario
        .scans
        .iter()
        .map(|scan| {
            let zs =
                super::corrections::corrected_measurements(scenario, scan).iter().map(|z| padded::<D>(z)).collect();
            (ScanGeometry { sensor: scan.sensor, time: scan.time, observer: None }, zs)
        })
        .collect()
}

fn compare_with<G, const D: usize, const H: usize, const N: usize, const Z: usize, const K: usize, const B: usize>(
    scenario: &Scenario3d,
    kind: TrackerKind,
    budget: ReferenceBudget,
) -> Result<CompareFigures, Error>
where
    G: ScenarioNetwork<D>,
{
    let (config, prior) = config3d::<G, D, B>(scenario, kind)?;
    compare_scans_with_budget::<_, _, 6, D, H, N, Z, K, B>(
        &config,
        &prior,
        scenario.prior.time,
        budget,
        &scans3d::<D>(scenario),
    )
    .map_err(Error::input)
}

/// [`compare3d`] for the network `G`.
fn compare_for<G: ScenarioNetwork<D>, const D: usize>(
    scenario: &Scenario3d,
    kind: TrackerKind,
    profile: Profile,
    budget: ReferenceBudget,
) -> Result<CompareFigures, Error> {
    with_capacities!(profile, ORBITAL, compare_with, [G, D], (scenario, kind, budget))
}

/// `host-sim compare` on a version 2 file: the bounded tracker `kind` (homht or rfisst) and the unbounded
/// reference (memory budget `budget_bytes`, no children bound, the default work bound) on the same scans,
/// placed per sensor by the core's `place_scan` in both ([`crate::eval::exactness::compare_scans`]).
///
/// # Errors
/// Bad input: the configuration, or the reference tracker as bounded tracker.
pub fn compare3d(
    scenario: &Scenario3d,
    kind: TrackerKind,
    profile: Option<Profile>,
    budget_bytes: usize,
) -> Result<CompareFigures, Error> {
    let budget = ReferenceBudget { bytes: budget_bytes, children: u64::MAX, ..ReferenceBudget::default() };
    compare3d_with_budget(scenario, kind, profile, budget)
}

/// [`compare3d`] with every budget of the reference given (`compare`'s options).
///
/// # Errors
/// As [`compare3d`].
pub fn compare3d_with_budget(
    scenario: &Scenario3d,
    kind: TrackerKind,
    profile: Option<Profile>,
    budget: ReferenceBudget,
) -> Result<CompareFigures, Error> {
    if kind == TrackerKind::Reference {
        return Err(Error::input("--tracker: the bounded tracker must be homht or rfisst"));
    }
    let profile = choose_profile(scenario, profile);
    with_measurement!(scenario.measurement, compare_for, (scenario, kind, profile, budget))
}

/// The figures `compare` writes for a version 2 file ([`compare3d`] with the profile it chooses).
///
/// # Errors
/// As [`compare3d`].
pub fn summary(
    scenario: &Scenario3d,
    kind: TrackerKind,
    profile: Option<Profile>,
    reference: crate::pipeline::tracker::ReferenceBudget,
) -> Result<crate::io::report::Compare3dSummary, Error> {
    let profile = choose_profile(scenario, profile);
    let figures = compare3d_with_budget(scenario, kind, Some(profile), reference)?;
    for scan in &figures.scans {
        if let Some(error) = &scan.reference_error {
            eprintln!("warning: scan {} (t = {}): the reference rejected it: {error}", scan.scan, scan.time);
        }
    }
    Ok(crate::io::report::Compare3dSummary {
        tracker: kind.name().to_string(),
        profile: profile.name().to_string(),
        sensors: scenario.sensors.len(),
        scans: figures.scans.len(),
        map_agreement: figures.map_agreement,
        min_captured_mass: figures.min_captured_mass,
        mean_captured_mass: figures.mean_captured_mass,
        max_weight_l1: figures.max_weight_l1,
        max_map_weight_difference: figures.max_map_weight_difference,
        min_core_captured_mass: figures.min_core_captured_mass,
        core_rejected_scans: figures.scans.iter().filter(|s| s.core_error.is_some()).count(),
        reference_rejected_scans: figures.scans.iter().filter(|s| s.reference_error.is_some()).count(),
    })
}
