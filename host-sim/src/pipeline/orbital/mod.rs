//! The orbital world (version 2 scenario files: ground radars and telescopes, two-body + J2): its trackers
//! ([`tracker`]), its sensors' look geometry ([`geometry`]), its adapter to the one replay
//! ([`OrbitalWorld`]), `compare` against the unbounded reference ([`compare`]) and its figures ([`plots`]).
//!
//! Every scan is stepped with its sensor and time ([`tracker_core::Tracker::step_scan`]); the replay scores
//! 3-D positions (km), and an estimate is *in view* when it lies in the field of view of the scan's sensor
//! (look angles, range and range-rate of [`SiteGeometry::look`]). Besides what every world writes, an
//! orbital run writes the MAP tracks as a CCSDS OEM (`tracks.oem`, [`crate::io::oem`]) and a sky plot per
//! sensor.
//!
//! The measurement kind of a version 2 file meets the core's measurement models in one place,
//! [`with_measurement!`](crate::with_measurement).

pub mod associate;
pub mod compare;
pub mod corrections;
pub mod geometry;
#[cfg(test)]
mod physics_tests;
pub mod plots;
pub mod prior_oem;
pub mod tracker;

pub use compare::compare3d;
pub use geometry::{FieldOfViewCheck, SiteGeometry};
pub use tracker::{
    C, Posterior6, Runner3d, ScenarioNetwork, birth_components_per_measurement, build3d, choose_profile, config3d,
    measurements_in_radians, network, padded,
};

use crate::error::Error;
use crate::eval::consistency::{Associated, ScanAssociations};
use crate::io::report::RunSummary;
use crate::pipeline::profile::ORBITAL;
use crate::pipeline::profile::Profile;
use crate::pipeline::tracker::{StepInfo, TrackerKind, is_refused_input};
use crate::pipeline::world::{Estimate, Heading, Posterior, ScanRecord, StepFailure, TruthObject, World};
use crate::scenario::v2::Scenario3d;
use plots::SkyTruth;
use std::path::{Path, PathBuf};
use tracker_core::StepError;

/// Calls `$f::<G, D>($args..)` with the core's measurement model `G` (of `D` coordinates) of the
/// measurement type `$kind` of a version 2 file ([`ScenarioNetwork`]): the one place the two meet. Radar,
/// radar with range-rate and optical are a [`SensorNetwork`](tracker_core::model::SensorNetwork) of their
/// model; every other type (`network`, az/el, range, range and range-rate) a
/// [`MixedNetwork`](tracker_core::model::MixedNetwork).
#[macro_export]
macro_rules! with_measurement {
    ($kind:expr, $f:ident, ($($arg:expr),* $(,)?)) => {
        match $kind {
            $crate::scenario::v2::Measurement3dSpec::Radar => $f::<
                ::tracker_core::model::SensorNetwork<
                    f64,
                    ::tracker_core::model::RadarRangeAzEl<f64>,
                    3,
                    { $crate::pipeline::orbital::C },
                >,
                3,
            >($($arg),*),
            $crate::scenario::v2::Measurement3dSpec::RadarRangeRate => $f::<
                ::tracker_core::model::SensorNetwork<
                    f64,
                    ::tracker_core::model::RadarRangeRate<f64>,
                    4,
                    { $crate::pipeline::orbital::C },
                >,
                4,
            >($($arg),*),
            $crate::scenario::v2::Measurement3dSpec::Optical => $f::<
                ::tracker_core::model::SensorNetwork<
                    f64,
                    ::tracker_core::model::OpticalRaDec<f64>,
                    2,
                    { $crate::pipeline::orbital::C },
                >,
                2,
            >($($arg),*),
            $crate::scenario::v2::Measurement3dSpec::AzEl
            | $crate::scenario::v2::Measurement3dSpec::Range
            | $crate::scenario::v2::Measurement3dSpec::RangeRangeRate
            | $crate::scenario::v2::Measurement3dSpec::Network => $f::<
                ::tracker_core::model::MixedNetwork<f64, { $crate::pipeline::orbital::C }>,
                { ::tracker_core::model::MIXED_DIMENSION },
            >($($arg),*),
        }
    };
}

/// The orbital world's adapter: a scenario, its tracker, its sensors' geometry and its own outputs (the
/// OEM, the sky plots).
pub struct OrbitalWorld<'a> {
    scenario: &'a Scenario3d,
    kind: TrackerKind,
    profile: Profile,
    runner: Box<dyn Runner3d>,
    geometry: SiteGeometry,
    /// The posterior after the last step (its MAP tracks with covariances, for the OEM).
    last: Posterior6,
    /// Sky plots: per sensor, per truth object, a point per scan of that sensor (None out of view).
    sky_truth: Vec<SkyTruth>,
    /// Sky plots: per sensor, the MAP estimates in view.
    sky_estimates: Vec<Vec<Option<(f64, f64)>>>,
    oem: crate::io::oem::OemTracks,
    out: PathBuf,
}

impl<'a> OrbitalWorld<'a> {
    /// The world of `scenario` with the tracker `kind` and capacities `profile`, writing into `out`.
    ///
    /// # Errors
    /// Bad input when the tracker cannot be built.
    pub fn new(scenario: &'a Scenario3d, kind: TrackerKind, profile: Profile, out: &Path) -> Result<Self, Error> {
        let sensors = scenario.sensors.len();
        Ok(Self {
            scenario,
            kind,
            profile,
            runner: build3d(kind, profile, scenario)?,
            geometry: SiteGeometry::new(scenario),
            last: Posterior6::default(),
            sky_truth: vec![SkyTruth::new(); sensors],
            sky_estimates: vec![vec![]; sensors],
            oem: crate::io::oem::OemTracks::new(scenario),
            out: out.to_path_buf(),
        })
    }

    fn state(state: &[f64]) -> &[f64; 6] {
        state.try_into().expect("orbital states have 6 entries")
    }
}

impl World<3> for OrbitalWorld<'_> {
    fn heading(&self) -> Heading {
        let scenario = self.scenario;
        Heading {
            scenario: scenario.name.clone(),
            tracker: self.kind.name(),
            profile: self.profile.name(),
            sensors: Some(scenario.sensors.len()),
            sensor_kinds: Some(scenario.sensor_kinds().iter().map(|k| k.name().to_string()).collect()),
            evaluation: scenario.evaluation,
            has_truth: scenario.truth.is_some(),
            births: scenario
                .truth
                .iter()
                .flat_map(|t| t.objects.iter().filter(|o| !o.in_prior).map(|o| o.id))
                .collect(),
            peak_counts_prior: true,
            reference: false,
            births_from_tracklets_only: scenario.births_from_tracklets_only(),
        }
    }

    fn scans(&self) -> usize {
        self.scenario.scans.len()
    }

    fn time(&self, k: usize) -> f64 {
        self.scenario.scans[k].time
    }

    fn step(&mut self, k: usize) -> Result<StepInfo, StepFailure> {
        let scan = &self.scenario.scans[k];
        let zs = corrections::corrected_measurements(self.scenario, scan);
        self.runner.step_or_failure(scan.sensor, scan.time, &zs)
    }

    fn posterior(&mut self) -> Posterior {
        self.last = self.runner.posterior();
        let map = self
            .last
            .map
            .iter()
            .map(|t| Estimate { label: t.label, mean: t.mean.to_vec(), existence: t.existence })
            .collect();
        Posterior { map, expected_cardinality: self.last.expected_cardinality, hypotheses: self.last.hypotheses }
    }

    fn truth(&self, k: usize) -> Option<Vec<TruthObject<'_>>> {
        let truth = self.scenario.truth.as_ref()?;
        Some(truth.scans[k].objects.iter().map(|o| TruthObject { id: o.id, state: &o.state }).collect())
    }

    fn detected(&self, k: usize) -> Vec<u64> {
        let origins = self.scenario.truth.as_ref().and_then(|t| t.scans[k].origins.as_ref());
        origins.into_iter().flatten().flatten().copied().collect()
    }

    fn sensor_name(&self, k: usize) -> Option<String> {
        self.scenario.sensors.get(self.scenario.scans[k].sensor).map(|s| s.name.clone())
    }

    fn judged(&self) -> bool {
        true
    }

    fn associate(&self, k: usize) -> Option<ScanAssociations> {
        let scan = &self.scenario.scans[k];
        let kind = self.scenario.kind(scan.sensor);
        let zs = corrections::corrected_measurements(self.scenario, scan);
        let (dimension, associations) = self.runner.associate(scan.sensor, scan.time, &zs);
        let in_file_units = |i: usize, v: f64| if kind.is_angle(i) { v.to_degrees() } else { v };
        let associated = associations
            .into_iter()
            .flatten()
            .map(|(label, residual, nis)| Associated {
                label,
                residual: residual.iter().enumerate().map(|(i, &v)| in_file_units(i, v)).collect(),
                nis,
            })
            .collect();
        Some(ScanAssociations {
            sensor: self.sensor_name(k)?,
            dimension,
            measurements: scan.measurements.len(),
            associated,
        })
    }

    fn residual_axes(&self, sensor: &str) -> Option<Vec<crate::pipeline::residual_plots::Axis>> {
        let index = self.scenario.sensors.iter().position(|s| s.name == sensor)?;
        let (kind, spec) = (self.scenario.kind(index), &self.scenario.sensors[index]);
        let sigma = spec.noise.sigma(kind);
        let in_file_units = |i: usize, v: f64| if kind.is_angle(i) { v.to_degrees() } else { v };
        Some(
            plots::component_names(kind)
                .iter()
                .zip(&sigma)
                .enumerate()
                .map(|(i, (n, &s))| (*n, in_file_units(i, s)))
                .collect(),
        )
    }

    fn in_view(&self, k: usize, state: &[f64]) -> bool {
        let scan = &self.scenario.scans[k];
        self.geometry.in_view(scan.sensor, scan.time, Self::state(state))
    }

    fn csv_header(&self) -> &'static str {
        "scan,time,sensor,label,x,y,z,vx,vy,vz,existence,within_error_bound"
    }

    fn csv_scan_columns(&self, k: usize) -> String {
        let scan = &self.scenario.scans[k];
        format!("{k},{},{}", scan.time, scan.sensor)
    }

    fn record(&mut self, k: usize, accepted: bool, posterior: &Posterior, _: &[Option<bool>]) -> Result<(), Error> {
        let scan = &self.scenario.scans[k];
        if accepted {
            self.oem.record(scan.time, &self.last.map);
        }
        let geometry = &self.geometry;
        let sky = |state: &[f64; 6]| {
            geometry.in_view(scan.sensor, scan.time, state).then(|| geometry.sky_point(scan.sensor, scan.time, state))
        };
        if let Some(truth) = &self.scenario.truth {
            // Sky plot truth: every object, in view or a break.
            let series = &mut self.sky_truth[scan.sensor];
            for t in &truth.scans[k].objects {
                series.entry(t.id).or_default().push(sky(&t.state));
            }
        }
        for t in &posterior.map {
            if let Some(point) = sky(Self::state(&t.mean)) {
                self.sky_estimates[scan.sensor].push(Some(point));
            }
        }
        Ok(())
    }

    fn finish(&mut self, records: &[ScanRecord]) -> Result<(), Error> {
        plots::write_plots(self.scenario, records, &self.sky_truth, &self.sky_estimates, &self.out)?;
        self.oem.write(&self.out.join("tracks.oem"))
    }
}

/// What a run does with a core error of a scan: bad input (one line, exit code 2) for a gap beyond the
/// motion model's bound or an unknown sensor, a refused scan for the scan's own input, else a rejection.
pub fn step_failure(e: StepError) -> StepFailure {
    match e {
        StepError::TimeStepTooLong { .. } | StepError::Placement(_) => StepFailure::BadInput(e.to_string()),
        e if is_refused_input(&e) => StepFailure::Refused(e.to_string()),
        e => StepFailure::Rejected(e.to_string()),
    }
}

/// `host-sim run` on a version 2 scenario: runs `kind` with `profile` (chosen by [`choose_profile`] when
/// `None`), writes `summary.json`, `estimates.csv`, `tracks.oem` and the plots into `out`, and returns the
/// summary and whether every scan was accepted.
///
/// # Errors
/// Bad input (exit code 2): a tracker that cannot be built, a scan gap beyond the motion model's bound or a
/// scan naming an unknown sensor; [`Error::Output`] when a file cannot be written.
pub fn run(
    scenario: &Scenario3d,
    kind: TrackerKind,
    profile: Option<Profile>,
    quiet: bool,
    out: &Path,
) -> Result<(RunSummary, bool), Error> {
    std::fs::create_dir_all(out).map_err(|e| Error::output(out, e))?;
    let profile = choose_profile(scenario, profile);
    let components = birth_components_per_measurement(scenario);
    let pool = ORBITAL.of(profile).birth_cells.saturating_sub(scenario.birth.cells.len());
    if components > pool {
        eprintln!(
            "warning: birth.measured gives up to {components} birth components per measurement, more than the \
             {pool} free birth cells of the {} profile: measurements that need more give no birth (--profile host)",
            profile.name()
        );
    }
    let mut world = OrbitalWorld::new(scenario, kind, profile, out)?;
    crate::pipeline::replay::run(&mut world, quiet, out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::SVector;
    use tracker_core::model::RadarRangeAzEl;
    use tracker_core::sensor::ScanGeometry;

    fn tiny() -> Scenario3d {
        let simulation = crate::sim::presets::tiny_3d(1).expect("tiny-3d");
        crate::scenario::from_simulation::to_scenario(&simulation).expect("scenario").0
    }

    fn temp(tag: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("host-sim-run3d-{}-{tag}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        dir
    }

    /// The core's own errors for bad input (an unvalidated scenario) are bad input at the command line:
    /// `Error::Input` (exit code 2) with one line naming the scan.
    /// Runs `f` on a thread with the stack `main` gives the trackers.
    fn on_large_stack(f: impl FnOnce() + Send + 'static) {
        std::thread::Builder::new().stack_size(512 << 20).spawn(f).expect("thread").join().expect("no panic");
    }

    #[test]
    fn core_gap_and_placement_errors_are_bad_input() {
        on_large_stack(core_gap_and_placement_errors);
    }

    fn core_gap_and_placement_errors() {
        let mut gap = tiny();
        gap.motion = Motion3dSpecFor::short();
        let out = temp("gap");
        match run(&gap, TrackerKind::Rfisst, None, true, &out) {
            Err(Error::Input(e)) => {
                assert!(e.0.starts_with("scans[1]: scan is more than 5 s after the last one"), "{e}");
                assert!(!e.0.contains('\n'));
            }
            other => panic!("{:?}", other.map(|s| s.0.scans)),
        }
        let mut unknown = tiny();
        unknown.scans[2].sensor = 3;
        match run(&unknown, TrackerKind::Rfisst, None, true, &out) {
            Err(Error::Input(e)) => assert!(e.0.starts_with("scans[2]: scan geometry: scan names sensor 3"), "{e}"),
            other => panic!("{:?}", other.map(|s| s.0.scans)),
        }
        let _ = std::fs::remove_dir_all(&out);
    }

    struct Motion3dSpecFor;

    impl Motion3dSpecFor {
        /// Gaps of at most 5 s: the 10 s between tiny-3d's scans are too long.
        fn short() -> crate::scenario::v2::Motion3dSpec {
            crate::scenario::v2::Motion3dSpec::TwoBodyJ2 {
                process_noise: crate::scenario::v2::ProcessNoiseSpec::Isotropic { q: 1e-12 },
                max_step: 5.0,
                max_substeps: 1,
            }
        }
    }

    #[test]
    fn look_angles_match_the_core_radar_model() {
        use tracker_core::{Measure, Placement};
        let scenario = tiny();
        let geometry = SiteGeometry::new(&scenario);
        let network = network::<tracker_core::model::SensorNetwork<f64, RadarRangeAzEl<f64>, 3, C>, 3>(&scenario)
            .expect("network");
        let truth = &scenario.truth.as_ref().expect("truth").scans[4].objects[0];
        let time = scenario.scans[4].time;
        let placed = network.place(&ScanGeometry { sensor: 0, time, observer: None }).expect("placed");
        let z = placed.measure(&SVector::from(truth.state));
        let look = geometry.look(0, time, &truth.state);
        assert!((look.range.expect("range") - z[0]).abs() < 1e-9, "{look:?} {z}");
        assert!((look.azimuth - z[1]).abs() < 1e-12 && (look.elevation - z[2]).abs() < 1e-12, "{look:?} {z}");
    }
}
