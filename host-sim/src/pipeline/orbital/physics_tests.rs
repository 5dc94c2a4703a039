//! Measurement physics end to end (issue 29 item 4): a tiny-3d scenario simulated with a sensor bias,
//! light time or refraction ([`crate::sim::physics`]) and run with the matching sensor settings
//! ([`super::corrections`], tracker-core's light time) against the same run without them.

use super::run;
use crate::io::report::RunSummary;
use crate::pipeline::tracker::TrackerKind;
use crate::scenario::v2::{LightTimeSpec, NoiseSpec, RefractionSpec, Scenario3d};
use crate::sim::physics::{SensorPhysics, apply};
use crate::sim::refraction::Atmosphere;
use crate::sim::ssa::{SsaScenario, simulate_tracks};
use tracker_core::model::LightTime;

/// tiny-3d seed 1 with its radar's noise scaled by `noise` (the same truth, schedule and draws).
fn tiny(noise: f64) -> SsaScenario {
    let sim = crate::sim::presets::tiny_3d(1).expect("tiny-3d");
    let mut sensors = sim.sensors.clone();
    for s in &mut sensors {
        s.sigma.iter_mut().for_each(|v| *v *= noise);
    }
    let schedule: Vec<(f64, usize)> = sim.scans.iter().map(|s| (s.time, s.sensor)).collect();
    let tracks: Vec<Vec<[f64; 6]>> = (0..sim.objects.len()).map(|i| sim.object_states(i).expect("truth")).collect();
    let visible = vec![vec![true; schedule.len()]; tracks.len()];
    simulate_tracks("tiny-3d", 1, &sim.epoch, sim.duration, sensors, schedule, tracks, visible).expect("simulated")
}

fn scenario(sim: &SsaScenario) -> Scenario3d {
    crate::scenario::from_simulation::to_scenario(sim).expect("scenario").0
}

/// The run's summary, on a thread with the stack `main` gives the trackers.
fn summary(scenario: Scenario3d, tag: &str) -> RunSummary {
    let out = std::env::temp_dir().join(format!("host-sim-physics-{}-{tag}", std::process::id()));
    let summary = std::thread::Builder::new()
        .stack_size(512 << 20)
        .spawn(move || {
            let result = run(&scenario, TrackerKind::Rfisst, None, true, &out);
            let _ = std::fs::remove_dir_all(&out);
            result.expect("run").0
        })
        .expect("thread")
        .join()
        .expect("no panic");
    assert!(summary.rejected_scans.is_empty(), "{:?}", summary.rejected_scans);
    summary
}

fn gospa(s: &RunSummary) -> f64 {
    s.mean_gospa.expect("truth")
}

fn warnings(s: &RunSummary) -> Vec<String> {
    s.consistency_warnings.clone().unwrap_or_default()
}

#[test]
fn a_known_bias_configured_tracks_as_the_unbiased_run_and_unconfigured_it_is_flagged() {
    let plain = summary(scenario(&tiny(1.0)), "bias-plain");
    let mut sim = tiny(1.0);
    // 0.3 km (15 σ) on the range, 0.05° on the azimuth.
    let bias = vec![0.3, 0.05f64.to_radians(), 0.0];
    apply(&mut sim, &[SensorPhysics { bias, ..SensorPhysics::default() }]).expect("physics");
    let unconfigured = summary(scenario(&sim), "bias-absent");
    let mut configured = scenario(&sim);
    configured.sensors[0].bias =
        Some(NoiseSpec { range_km: Some(0.3), azimuth_arcsec: Some(180.0), ..NoiseSpec::default() });
    let configured = summary(configured, "bias-configured");
    // Removing the bias gives the plain measurements to rounding: the same estimates to 1e-9 km.
    assert!((gospa(&configured) - gospa(&plain)).abs() < 1e-9, "{} {}", gospa(&configured), gospa(&plain));
    assert_eq!(warnings(&plain), Vec::<String>::new());
    assert_eq!(warnings(&configured), Vec::<String>::new());
    assert_eq!(warnings(&unconfigured), vec!["radar-north".to_string()]);
}

#[test]
fn light_time_modelled_matches_the_truth_better_than_ignored() {
    // σ 2 m in range, 1.1″ in angle: light time (25–50 m along track) is well above the noise.
    let mut sim = tiny(0.1);
    let physics = SensorPhysics { light_time: LightTime::TwoWayReceive, ..SensorPhysics::default() };
    apply(&mut sim, &[physics]).expect("physics");
    let ignored = summary(scenario(&sim), "light-off");
    let mut modelled = scenario(&sim);
    modelled.sensors[0].light_time = Some(LightTimeSpec::TwoWayReceive);
    let modelled = summary(modelled, "light-on");
    let plain = summary(scenario(&tiny(0.1)), "light-plain");
    eprintln!("mean GOSPA: plain {} modelled {} ignored {}", gospa(&plain), gospa(&modelled), gospa(&ignored));
    let nis = |s: &RunSummary| s.residuals.as_ref().and_then(|r| r["radar-north"].mean_nis).expect("NIS");
    eprintln!("mean NIS: plain {} modelled {} ignored {}", nis(&plain), nis(&modelled), nis(&ignored));
    assert!(gospa(&modelled) < gospa(&ignored), "{} {}", gospa(&modelled), gospa(&ignored));
    // Modelled, the run is as good as one without light time at all (within 10 %).
    assert!((gospa(&modelled) - gospa(&plain)).abs() < 0.1 * gospa(&plain));
    assert_eq!(warnings(&modelled), Vec::<String>::new());
}

#[test]
fn refraction_removed_matches_the_unrefracted_run() {
    let plain = summary(scenario(&tiny(0.1)), "refraction-plain");
    let mut sim = tiny(0.1);
    let physics = SensorPhysics { refraction: Some(Atmosphere::STANDARD), ..SensorPhysics::default() };
    apply(&mut sim, &[physics]).expect("physics");
    let ignored = summary(scenario(&sim), "refraction-off");
    let mut removed = scenario(&sim);
    removed.sensors[0].refraction = Some(RefractionSpec::STANDARD);
    let removed = summary(removed, "refraction-on");
    eprintln!("mean GOSPA: plain {} removed {} ignored {}", gospa(&plain), gospa(&removed), gospa(&ignored));
    // Not bit-identical: refraction is removed at the noisy elevation, not the true one (R' σ_E ≈ 10⁻³ σ_E).
    assert!((gospa(&removed) - gospa(&plain)).abs() < 1e-3 * gospa(&plain), "{}", gospa(&removed));
    assert!(gospa(&removed) < gospa(&ignored));
    assert_eq!(warnings(&removed), Vec::<String>::new());
    assert_eq!(warnings(&ignored), vec!["radar-north".to_string()]);
}

#[test]
fn track_takes_light_time_and_refraction_from_the_tdm() {
    let mut sim = tiny(0.1);
    let physics = SensorPhysics {
        light_time: LightTime::TwoWayReceive,
        refraction: Some(Atmosphere::STANDARD),
        ..SensorPhysics::default()
    };
    apply(&mut sim, &[physics]).expect("physics");
    let mut stated = scenario(&sim);
    stated.sensors[0].light_time = Some(LightTimeSpec::TwoWayReceive);
    stated.sensors[0].refraction = Some(RefractionSpec::STANDARD);
    let dir = std::env::temp_dir().join(format!("host-sim-physics-{}-tdm", std::process::id()));
    let files = crate::io::tdm::export(&stated, &dir).expect("export");
    let text = std::fs::read_to_string(&files[0]).expect("read");
    assert!(text.contains("PATH = 1,2,1\n") && !text.contains("COMMENT LIGHT_TIME NONE"), "{text}");
    assert!(!text.contains("COMMENT REFRACTION NONE"));
    // The configuration states neither: the TDM's two-way path and AZEL angles turn both on.
    let config = scenario(&sim);
    let tracked = crate::io::tdm::scenario_from_tdms(&files, &config).expect("tracked");
    assert_eq!(tracked.sensors[0].light_time, Some(LightTimeSpec::TwoWayReceive));
    assert_eq!(tracked.sensors[0].refraction, Some(RefractionSpec::STANDARD));
    // Stated explicitly, the configuration wins.
    let mut off = config.clone();
    off.sensors[0].light_time = Some(LightTimeSpec::Off);
    off.sensors[0].refraction = Some(RefractionSpec::None);
    let kept = crate::io::tdm::scenario_from_tdms(&files, &off).expect("tracked");
    assert_eq!(
        (kept.sensors[0].light_time, kept.sensors[0].refraction),
        (off.sensors[0].light_time, off.sensors[0].refraction)
    );
    // A plain export says it has neither, and tracks back as before.
    let plain = scenario(&tiny(0.1));
    let plain_files = crate::io::tdm::export(&plain, &dir.join("plain")).expect("export");
    let back = crate::io::tdm::scenario_from_tdms(&plain_files, &plain).expect("tracked");
    assert_eq!(
        (back.sensors[0].light_time, back.sensors[0].refraction),
        (Some(LightTimeSpec::Off), Some(RefractionSpec::None))
    );
    let _ = std::fs::remove_dir_all(&dir);
    let mut truth = tracked.clone();
    truth.truth = stated.truth.clone();
    let modelled = summary(truth, "tdm-on");
    let reference = summary(stated, "tdm-stated");
    assert!((gospa(&modelled) - gospa(&reference)).abs() < 1e-9, "{} {}", gospa(&modelled), gospa(&reference));
}

#[test]
fn light_time_in_a_network_of_mixed_kinds_tracks_as_in_a_network_of_one_kind() {
    let mut sim = tiny(0.1);
    let physics = SensorPhysics { light_time: LightTime::TwoWayReceive, ..SensorPhysics::default() };
    apply(&mut sim, &[physics]).expect("physics");
    let mut single = scenario(&sim);
    single.sensors[0].light_time = Some(LightTimeSpec::TwoWayReceive);
    // The same radar as the one sensor of a `network` (tracker-core's MixedNetwork).
    let mut mixed = single.clone();
    mixed.measurement = crate::scenario::v2::Measurement3dSpec::Network;
    mixed.sensors[0].kind = Some(crate::scenario::v2::Measurement3dSpec::Radar);
    let ignored = {
        let mut off = mixed.clone();
        off.sensors[0].light_time = None;
        summary(off, "mixed-light-off")
    };
    let (single, mixed) = (summary(single, "single-light-on"), summary(mixed, "mixed-light-on"));
    eprintln!("mean GOSPA: one kind {} mixed {} mixed ignored {}", gospa(&single), gospa(&mixed), gospa(&ignored));
    // The core gives the bits of the network of one kind (model/mixed tests): the same run.
    assert_eq!(gospa(&mixed), gospa(&single));
    assert!(gospa(&mixed) < gospa(&ignored), "{} {}", gospa(&mixed), gospa(&ignored));
}
