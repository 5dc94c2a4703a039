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
use crate::io::catalogue::screen::CatalogueDropped;
use crate::io::report::RunSummary;
use crate::pipeline::profile::ORBITAL;
use crate::pipeline::profile::Profile;
use crate::pipeline::tracker::{StepInfo, TrackerKind, is_refused_input};
use crate::pipeline::world::{Estimate, Heading, Posterior, ScanRecord, StepFailure, TruthObject, World};
use crate::scenario::catalogue_stream::{CatalogueStream, DrawnScan};
use crate::scenario::v2::{Scan3dSpec, Scenario3d, TruthScan3dSpec};
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

/// Where an orbital run's scans and truth come from.
enum Scans {
    /// The scenario's own.
    Held,
    /// Drawn as the run goes (a catalogue too large to hold, [`CatalogueStream`]): the scan being replayed,
    /// and every scan drawn so far without its truth (for `scenario.json`).
    Streamed { stream: Box<CatalogueStream>, current: Box<DrawnScan>, drawn: Vec<Scan3dSpec> },
}

impl Scans {
    /// The truth at scan `k` of `scenario`'s run, when it has truth.
    fn truth<'s>(&'s self, scenario: &'s Scenario3d, k: usize) -> Option<&'s TruthScan3dSpec> {
        match self {
            Scans::Held => scenario.truth.as_ref().map(|t| &t.scans[k]),
            Scans::Streamed { current, .. } => Some(&current.1),
        }
    }
}

/// Simulated seconds between two snapshots of a streamed run's `estimates.csv` and `tracks.oem`.
pub const STREAMED_SNAPSHOT_S: f64 = 3600.0;

/// The orbital world's adapter: a scenario, its tracker, its sensors' geometry and its own outputs (the
/// OEM, the sky plots).
pub struct OrbitalWorld<'a> {
    scenario: &'a Scenario3d,
    scans: Scans,
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
            scans: Scans::Held,
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

    /// The world of a catalogue drawn as the run goes: `scenario` is `stream`'s configuration and prior
    /// ([`CatalogueStream::scenario`]). Its `estimates.csv` and `tracks.oem` hold the MAP tracks once every
    /// [`STREAMED_SNAPSHOT_S`] and at the last scan; it writes `scenario.json` with the scans drawn and no
    /// truth.
    ///
    /// # Errors
    /// As [`OrbitalWorld::new`].
    pub fn streamed(
        scenario: &'a Scenario3d,
        stream: CatalogueStream,
        kind: TrackerKind,
        profile: Profile,
        out: &Path,
    ) -> Result<Self, Error> {
        let mut world = Self::new(scenario, kind, profile, out)?;
        let empty = (
            Scan3dSpec { time: 0.0, sensor: 0, measurements: vec![] },
            TruthScan3dSpec { objects: vec![], origins: None },
        );
        world.scans = Scans::Streamed { stream: Box::new(stream), current: Box::new(empty), drawn: vec![] };
        Ok(world)
    }

    fn state(state: &[f64]) -> &[f64; 6] {
        state.try_into().expect("orbital states have 6 entries")
    }

    /// Scan `k` (a streamed world holds only the scan being replayed: [`World::begin`] drew it).
    fn scan(&self, k: usize) -> &Scan3dSpec {
        match &self.scans {
            Scans::Held => &self.scenario.scans[k],
            Scans::Streamed { current, .. } => &current.0,
        }
    }

    /// The truth at scan `k`, when the scenario has truth.
    fn truth_scan(&self, k: usize) -> Option<&TruthScan3dSpec> {
        self.scans.truth(self.scenario, k)
    }

    /// Whether scan `k` is a snapshot of a streamed run (the first scan at or after each multiple of
    /// [`STREAMED_SNAPSHOT_S`], and the last scan); every scan of a held one.
    fn snapshot(&self, k: usize) -> bool {
        let Scans::Streamed { stream, .. } = &self.scans else { return true };
        let hour = |k: usize| (stream.time(k) / STREAMED_SNAPSHOT_S).floor();
        k == 0 || k + 1 == stream.scans() || hour(k) > hour(k - 1)
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
        match &self.scans {
            Scans::Held => self.scenario.scans.len(),
            Scans::Streamed { stream, .. } => stream.scans(),
        }
    }

    fn time(&self, k: usize) -> f64 {
        match &self.scans {
            Scans::Held => self.scenario.scans[k].time,
            Scans::Streamed { stream, .. } => stream.time(k),
        }
    }

    fn begin(&mut self, k: usize) -> Result<(), Error> {
        if let Scans::Streamed { stream, current, drawn } = &mut self.scans {
            **current = stream.scan(k)?;
            drawn.push(current.0.clone());
        }
        Ok(())
    }

    fn step(&mut self, k: usize) -> Result<StepInfo, StepFailure> {
        let scan = self.scan(k);
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
        let truth = self.truth_scan(k)?;
        Some(truth.objects.iter().map(|o| TruthObject { id: o.id, state: &o.state }).collect())
    }

    fn detected(&self, k: usize) -> Vec<u64> {
        let origins = self.truth_scan(k).and_then(|t| t.origins.as_ref());
        origins.into_iter().flatten().flatten().copied().collect()
    }

    fn sensor_name(&self, k: usize) -> Option<String> {
        self.scenario.sensors.get(self.scan(k).sensor).map(|s| s.name.clone())
    }

    fn judged(&self) -> bool {
        true
    }

    fn associate(&self, k: usize) -> Option<ScanAssociations> {
        let scan = self.scan(k);
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
        let scan = self.scan(k);
        self.geometry.in_view(scan.sensor, scan.time, Self::state(state))
    }

    fn csv_header(&self) -> &'static str {
        "scan,time,sensor,label,x,y,z,vx,vy,vz,existence,within_error_bound"
    }

    fn estimates_due(&self, k: usize) -> bool {
        self.snapshot(k)
    }

    fn csv_scan_columns(&self, k: usize) -> String {
        let scan = self.scan(k);
        format!("{k},{},{}", scan.time, scan.sensor)
    }

    fn record(&mut self, k: usize, accepted: bool, posterior: &Posterior, _: &[Option<bool>]) -> Result<(), Error> {
        let (time, sensor) = (self.scan(k).time, self.scan(k).sensor);
        if accepted && self.snapshot(k) {
            self.oem.record(time, &self.last.map);
        }
        let geometry = &self.geometry;
        let sky =
            |state: &[f64; 6]| geometry.in_view(sensor, time, state).then(|| geometry.sky_point(sensor, time, state));
        if let Some(truth) = self.scans.truth(self.scenario, k) {
            // Sky plot truth: each object's points in view, a break (one `None`) where it leaves the view.
            let series = &mut self.sky_truth[sensor];
            for t in &truth.objects {
                match sky(&t.state) {
                    Some(point) => series.entry(t.id).or_default().push(Some(point)),
                    None => {
                        if let Some(points) = series.get_mut(&t.id)
                            && points.last().is_some_and(Option::is_some)
                        {
                            points.push(None);
                        }
                    }
                }
            }
        }
        for t in &posterior.map {
            if let Some(point) = sky(Self::state(&t.mean)) {
                self.sky_estimates[sensor].push(Some(point));
            }
        }
        Ok(())
    }

    fn finish(&mut self, records: &[ScanRecord]) -> Result<(), Error> {
        plots::write_plots(self.scenario, records, &self.sky_truth, &self.sky_estimates, &self.out)?;
        self.oem.write(&self.out.join("tracks.oem"))?;
        if let Scans::Streamed { drawn, .. } = &mut self.scans {
            // The scans as drawn, without truth: `run` replays them as a run on real data.
            let scenario = Scenario3d { scans: std::mem::take(drawn), truth: None, ..self.scenario.clone() };
            scenario.save(&self.out.join("scenario.json"))?;
        }
        Ok(())
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
    let profile = choose_profile(scenario, profile);
    check_birth_components(scenario, profile)?;
    std::fs::create_dir_all(out).map_err(|e| Error::output(out, e))?;
    let mut world = OrbitalWorld::new(scenario, kind, profile, out)?;
    crate::pipeline::replay::run(&mut world, quiet, out)
}

/// [`run`] on a catalogue drawn as the run goes ([`OrbitalWorld::streamed`]; `profile` chosen from its
/// configuration and prior); also returns the element sets dropped, before the run and during it.
///
/// # Errors
/// As [`run`], and a scan the stream cannot draw (bad input).
pub fn run_streamed(
    stream: CatalogueStream,
    kind: TrackerKind,
    profile: Option<Profile>,
    quiet: bool,
    out: &Path,
) -> Result<(RunSummary, bool, CatalogueDropped), Error> {
    let scenario = stream.scenario().clone();
    let profile = choose_profile(&scenario, profile);
    check_birth_components(&scenario, profile)?;
    std::fs::create_dir_all(out).map_err(|e| Error::output(out, e))?;
    let mut world = OrbitalWorld::streamed(&scenario, stream, kind, profile, out)?;
    let (summary, clean) = crate::pipeline::replay::run(&mut world, quiet, out)?;
    let Scans::Streamed { stream, .. } = world.scans else { return Err(Error::internal("streamed world")) };
    Ok((summary, clean, stream.dropped().clone()))
}

/// The warning that some measurements of `scenario` give more birth components than the free birth cells
/// of the tracker `run` builds for `profile` (the partitioned tracker's clusters when the prior is beyond
/// the profile's N); an error, saying how to size them, when its tracklets' cells do not fit them (the core
/// refuses such a pool: no tracklet of it could give a birth).
///
/// # Errors
/// Bad input: tracklet cells beyond the profile's free birth cells.
fn check_birth_components(scenario: &Scenario3d, profile: Profile) -> Result<(), Error> {
    let components = birth_components_per_measurement(scenario);
    // A prior beyond the profile's N runs the partitioned tracker, whose birth cluster has a cluster's B.
    let (cells, holder) = if scenario.max_prior_objects() > ORBITAL.of(profile).objects {
        (crate::partition::runner::CLUSTER.birth_cells, "a cluster of the partitioned tracker".to_string())
    } else {
        (ORBITAL.of(profile).birth_cells, format!("the {} profile", profile.name()))
    };
    let free = cells.saturating_sub(scenario.birth.cells.len());
    if let Some([ranges, rates]) = scenario.birth.measured.and_then(|m| m.tracklets).map(|t| t.cells)
        && ranges.saturating_mul(rates) > free
    {
        // An example that fits: the same range-rate cells (as many as fit), as many ranges as then fit.
        let fit_rates = rates.min(free).max(1);
        let fit_ranges = (free / fit_rates).max(1);
        return Err(Error::input(format!(
            "birth.measured.tracklets.cells [{ranges}, {rates}] makes {} birth cells a tracklet, more than the {free} \
             free birth cells of {holder}: give the tracklets at most {free} cells (for example \"cells\": \
             [{fit_ranges}, {fit_rates}], docs/results.md \"optical-leo\") or run with --profile host",
            ranges.saturating_mul(rates),
        )));
    }
    if components > free {
        eprintln!(
            "warning: birth.measured gives up to {components} birth components per measurement, more than the \
             {free} free birth cells of {holder}: measurements that need more give no birth (--profile host)"
        );
    }
    Ok(())
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
