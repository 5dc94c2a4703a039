//! The C interface called from Rust: bad input is a status code and a message, never a crash, and the
//! tracker is unchanged after a failed call; the JSON path gives the digests `host-sim digest` prints
//! (planar `SsaTracker<f32>` and radar `RadarTracker<f32>`, the QEMU firmware's trackers); every kind
//! initialises and steps.

use core::ffi::{CStr, c_void};
use host_sim::scenario::v2::Scenario3d;
use rfisst::scenario::{CScenario, from_json, rfisst_tracker_init_json};
use rfisst::*;
use std::ffi::CString;
use tracker_core::digest::Fnv1a;

/// Storage for one tracker of any kind, 16-byte aligned.
struct Storage {
    words: Vec<u128>,
}

impl Storage {
    fn new() -> Self {
        let size = RfisstKind::ALL.iter().map(|&k| rfisst_tracker_size(k as u32)).max().expect("kinds");
        Self { words: vec![0; size / 16 + 1] }
    }
    fn ptr(&mut self) -> *mut c_void {
        self.words.as_mut_ptr().cast()
    }
    fn size(&self) -> usize {
        self.words.len() * 16
    }
}

fn text(pointer: *const core::ffi::c_char) -> String {
    // SAFETY: the interface returns NUL-terminated strings.
    unsafe { CStr::from_ptr(pointer) }.to_string_lossy().into_owned()
}

fn last_error(tracker: *const RfisstTracker) -> String {
    // SAFETY: a handle or checked storage.
    text(unsafe { rfisst_tracker_last_error(tracker) })
}

fn with_big_stack(f: impl FnOnce() + Send + 'static) {
    std::thread::Builder::new().stack_size(256 << 20).spawn(f).expect("thread").join().expect("no panic");
}

fn planar_scenario(scans: usize) -> String {
    let mut simulation = host_sim::sim::planar::preset("fifty-birth-death", 1).expect("preset");
    simulation.scans = scans;
    serde_json::to_string(&simulation.run()).expect("JSON")
}

fn radar_scenario() -> (Scenario3d, String) {
    let simulation = host_sim::sim::presets::tiny_3d(1).expect("tiny-3d");
    let scenario = host_sim::scenario::from_simulation::to_scenario(&simulation).expect("scenario").0;
    let json = serde_json::to_string(&scenario).expect("JSON");
    (scenario, json)
}

/// Initialises `kind` from `scenario` in `storage`.
fn init(storage: &mut Storage, kind: RfisstKind, scenario: &CScenario) -> *mut RfisstTracker {
    let (status, tracker) = try_init(storage, kind, &scenario.config, scenario);
    assert_eq!(status, RfisstStatus::RfisstOk, "{}", last_error(storage.ptr().cast()));
    tracker
}

/// `rfisst_tracker_init` of `kind` with `config` and `scenario`'s prior in `storage`: its status and handle.
fn try_init(
    storage: &mut Storage,
    kind: RfisstKind,
    config: &RfisstConfig,
    scenario: &CScenario,
) -> (RfisstStatus, *mut RfisstTracker) {
    let hypotheses = scenario.hypotheses();
    let mut tracker = core::ptr::null_mut();
    // SAFETY: valid storage, configuration and prior.
    let status = unsafe {
        rfisst_tracker_init(
            storage.ptr(),
            storage.size(),
            kind as u32,
            config,
            hypotheses.as_ptr(),
            hypotheses.len(),
            scenario.prior_time,
            &mut tracker,
        )
    };
    (status, tracker)
}

/// The digest text of `host-sim digest`, through the C interface.
fn digest_text(tracker: *mut RfisstTracker, scenario: &CScenario, count: usize) -> String {
    let mut out = String::new();
    let mut running = Fnv1a::new();
    for (index, scan) in scenario.scans[..count].iter().enumerate() {
        let mut report = RfisstStepReport::default();
        let rows = scan.measurements.len() / scenario.dimension;
        // SAFETY: a handle and `rows × dimension` values.
        let status = unsafe {
            rfisst_tracker_step(
                tracker,
                scan.time,
                scan.sensor,
                core::ptr::null(),
                scan.measurements.as_ptr(),
                rows,
                scenario.dimension,
                &mut report,
            )
        };
        let mut digest = 0;
        // SAFETY: as above.
        assert_eq!(unsafe { rfisst_tracker_digest(tracker, &mut digest) }, RfisstStatus::RfisstOk);
        running.write(&digest.to_le_bytes());
        if status == RfisstStatus::RfisstOk {
            out += &format!(
                "scan {index} hypotheses {} tracks {} digest {digest:016x}\n",
                report.hypotheses, report.tracks
            );
        } else {
            assert_eq!(status, RfisstStatus::RfisstStepRejected);
            out += &format!("scan {index} error {} digest {digest:016x}\n", last_error(tracker));
        }
    }
    out + &format!("final scans {count} digest {:016x}", running.finish())
}

#[test]
fn json_path_gives_host_sim_digests_planar_f32() {
    with_big_stack(|| {
        let json = planar_scenario(12);
        let scenario = from_json(&json, RfisstKind::RfisstSsaF32, None).expect("planar");
        let mut storage = Storage::new();
        let tracker = init(&mut storage, RfisstKind::RfisstSsaF32, &scenario);
        let c = digest_text(tracker, &scenario, 12);
        let parsed = host_sim::scenario::Scenario::from_json(&json).expect("scenario");
        let host = host_sim::pipeline::digest::planar::run(&parsed, Some(12)).expect("host digest");
        assert_eq!(c, host);

        // The JSON entry point builds the same tracker.
        let cjson = CString::new(json).expect("no NUL");
        let mut again = Storage::new();
        let mut handle = core::ptr::null_mut();
        // SAFETY: valid storage and string.
        let status = unsafe { rfisst_tracker_init_json(again.ptr(), again.size(), 0, cjson.as_ptr(), &mut handle) };
        assert_eq!(status, RfisstStatus::RfisstOk, "{}", last_error(again.ptr().cast()));
        assert_eq!(digest_text(handle, &scenario, 12), host);
    });
}

#[test]
fn json_path_gives_host_sim_digests_radar_f32() {
    with_big_stack(|| {
        let (parsed, json) = radar_scenario();
        let count = parsed.scans.len();
        let scenario = from_json(&json, RfisstKind::RfisstRadarF32, Some(count)).expect("radar");
        let mut storage = Storage::new();
        let tracker = init(&mut storage, RfisstKind::RfisstRadarF32, &scenario);
        let host = host_sim::pipeline::digest::orbital::run(&parsed, Some(count)).expect("host digest");
        assert_eq!(digest_text(tracker, &scenario, count), host);
        assert!(host.lines().any(|line| line.contains(" tracks ")), "{host}");
    });
}

#[test]
fn the_lost_track_rule_is_configured_from_c_and_json_as_on_the_host() {
    with_big_stack(|| {
        let (mut parsed, _) = radar_scenario();
        let count = parsed.scans.len();
        let plain = host_sim::pipeline::digest::orbital::run(&parsed, Some(count)).expect("host digest");
        // A track unseen in one scan (in view, nothing in its gate) is dropped: the rule fires here.
        parsed.tracker.gate.get_or_insert(5.0);
        parsed.tracker.lost_after_unseen_scans = core::num::NonZeroU16::new(1);
        let json = serde_json::to_string(&parsed).expect("JSON");
        let host = host_sim::pipeline::digest::orbital::run(&parsed, Some(count)).expect("host digest");
        assert_ne!(host, plain, "the rule changes this run");
        let scenario = from_json(&json, RfisstKind::RfisstRadarF32, Some(count)).expect("radar");
        assert_eq!(scenario.config.lost_after_unseen_scans, 1);
        let mut storage = Storage::new();
        let tracker = init(&mut storage, RfisstKind::RfisstRadarF32, &scenario);
        assert_eq!(digest_text(tracker, &scenario, count), host);
        // The default is the exact recursion; a count beyond u16 is refused with its field named.
        let mut config = RfisstConfig::default_for(false);
        assert_eq!(config.lost_after_unseen_scans, 0);
        config = RfisstConfig { lost_after_unseen_scans: 70_000, ..scenario.config };
        let (status, handle) = try_init(&mut storage, RfisstKind::RfisstRadarF32, &config, &scenario);
        assert_eq!(status, RfisstStatus::RfisstInvalidConfig);
        assert!(handle.is_null());
        assert!(
            last_error(storage.ptr().cast()).contains("lost_after_unseen_scans"),
            "{}",
            last_error(storage.ptr().cast())
        );
    });
}

#[test]
fn a_floor_under_the_weights_is_configured_from_c_and_json_as_on_the_host() {
    with_big_stack(|| {
        let (mut parsed, _) = radar_scenario();
        let count = parsed.scans.len();
        let plain = host_sim::pipeline::digest::orbital::run(&parsed, Some(count)).expect("host digest");
        // One decade: every child under a tenth of the heaviest is dropped, which this run has.
        parsed.tracker.selection = host_sim::scenario::SelectionSpec::TopWeightWithin { decades: 1 };
        let json = serde_json::to_string(&parsed).expect("JSON");
        let host = host_sim::pipeline::digest::orbital::run(&parsed, Some(count)).expect("host digest");
        assert_ne!(host, plain, "the floor changes this run");
        let scenario = from_json(&json, RfisstKind::RfisstRadarF32, Some(count)).expect("radar");
        assert_eq!(
            (scenario.config.selection, scenario.config.selection_floor_decades),
            (choice::RFISST_SELECTION_TOP_WEIGHT_WITHIN, 1)
        );
        let mut storage = Storage::new();
        let tracker = init(&mut storage, RfisstKind::RfisstRadarF32, &scenario);
        assert_eq!(digest_text(tracker, &scenario, count), host);
        // A floor beyond 255 decades is refused with its field named.
        let config = RfisstConfig { selection_floor_decades: 256, ..scenario.config };
        let (status, handle) = try_init(&mut storage, RfisstKind::RfisstRadarF32, &config, &scenario);
        assert_eq!(status, RfisstStatus::RfisstInvalidConfig);
        assert!(handle.is_null());
        assert!(last_error(storage.ptr().cast()).contains("selection_floor_decades"));
    });
}

#[test]
fn every_kind_initialises_steps_and_reports() {
    with_big_stack(|| {
        let planar = planar_scenario(3);
        let (_, radar) = radar_scenario();
        let mut storage = Storage::new();
        for kind in RfisstKind::ALL {
            let json = if kind.is_planar() { &planar } else { &radar };
            let scenario = match kind {
                RfisstKind::RfisstOpticalF32 | RfisstKind::RfisstOpticalF64 => {
                    // A radar file does not fit the optical tracker: a clear message.
                    let error = from_json(json, kind, None).expect_err("radar file, optical tracker");
                    assert!(error.contains("does not fit"), "{error}");
                    optical_from_radar(from_json(json, RfisstKind::RfisstRadarF64, None).expect("radar"))
                }
                _ => from_json(json, kind, None).expect("scenario"),
            };
            let tracker = init(&mut storage, kind, &scenario);
            // SAFETY: a handle.
            unsafe {
                assert_eq!(rfisst_tracker_kind(tracker), kind as u32);
                assert_eq!(rfisst_tracker_dimension(tracker), scenario.dimension);
            }
            let mut expected = 0.0;
            // SAFETY: a handle.
            assert_eq!(unsafe { rfisst_tracker_expected_cardinality(tracker, &mut expected) }, RfisstStatus::RfisstOk);
            let prior_objects = scenario.prior[0].1.len() as f64;
            assert_eq!(expected, prior_objects, "{kind:?}: one prior hypothesis");
            let scans = if matches!(kind, RfisstKind::RfisstOpticalF32 | RfisstKind::RfisstOpticalF64) {
                0 // the radar's scans are not RA/Dec
            } else {
                scenario.scans.len().min(3)
            };
            let text = digest_text(tracker, &scenario, scans);
            assert!(!text.contains(" error "), "{kind:?}: {text}");
            let mut tracks = vec![RfisstTrack { label: 0, existence: 0.0, state: RfisstGaussian::ZERO }; 64];
            let mut written = 0;
            // SAFETY: a handle and room for 64 tracks.
            let status = unsafe { rfisst_tracker_map_tracks(tracker, tracks.as_mut_ptr(), 64, &mut written) };
            assert_eq!(status, RfisstStatus::RfisstOk, "{kind:?}");
            assert!(written > 0 && tracks[..written].iter().all(|t| t.state.mean[0].is_finite()), "{kind:?}");
        }
    });
}

/// The radar scenario's configuration with its sensor turned into a telescope (RA/Dec, no range window).
fn optical_from_radar(mut scenario: CScenario) -> CScenario {
    for sensor in &mut scenario.config.sensors[..scenario.config.sensor_count as usize] {
        sensor.kind = rfisst::config::sensor::RFISST_SENSOR_OPTICAL;
        sensor.sigma = [1e-5, 1e-5, 0.0, 0.0];
        sensor.detection.field_of_view.has_range = 0;
    }
    scenario.dimension = 2;
    scenario
}

#[test]
fn bad_arguments_are_statuses_with_messages() {
    with_big_stack(bad_arguments);
}

fn bad_arguments() {
    let json = planar_scenario(2);
    let scenario = from_json(&json, RfisstKind::RfisstSsaF64, None).expect("planar");
    let hypotheses = scenario.hypotheses();
    let kind = RfisstKind::RfisstSsaF64 as u32;
    let mut storage = Storage::new();
    let mut tracker = core::ptr::null_mut();
    let config = &scenario.config;
    let size = rfisst_tracker_size(kind);
    // SAFETY: every pointer is null, valid, or deliberately short/misaligned storage the function must
    // refuse before it writes.
    unsafe {
        let init = |storage: *mut c_void, size: usize, kind: u32, config: *const RfisstConfig, out| {
            rfisst_tracker_init(storage, size, kind, config, hypotheses.as_ptr(), hypotheses.len(), 0.0, out)
        };
        assert_eq!(init(core::ptr::null_mut(), size, kind, config, &mut tracker), RfisstStatus::RfisstNullPointer);
        assert_eq!(init(storage.ptr(), size - 1, kind, config, &mut tracker), RfisstStatus::RfisstBadSize);
        assert_eq!(init(storage.ptr().byte_add(4), size, kind, config, &mut tracker), RfisstStatus::RfisstMisaligned);
        assert_eq!(init(storage.ptr(), size, 8, config, &mut tracker), RfisstStatus::RfisstUnknownKind);
        assert_eq!(init(storage.ptr(), size, kind, config, core::ptr::null_mut()), RfisstStatus::RfisstNullPointer);
        assert_eq!(init(storage.ptr(), size, kind, core::ptr::null(), &mut tracker), RfisstStatus::RfisstNullPointer);
        assert!(tracker.is_null());
        assert_eq!(rfisst_tracker_size(8), 0);

        // An unknown code in the configuration, and a value the core rejects: the text says which.
        let mut bad = *config;
        bad.sensor.field_of_view.r#type = 9;
        assert_eq!(init(storage.ptr(), size, kind, &bad, &mut tracker), RfisstStatus::RfisstInvalidConfig);
        assert!(last_error(storage.ptr().cast()).contains("RFISST_REGION_"), "{}", last_error(storage.ptr().cast()));
        let mut bad = *config;
        bad.death_probability = 2.0;
        assert_eq!(init(storage.ptr(), size, kind, &bad, &mut tracker), RfisstStatus::RfisstConfigRejected);
        assert!(last_error(storage.ptr().cast()).contains("death probability"));
        // Storage whose initialisation failed is not a tracker.
        let mut digest = 0;
        assert_eq!(rfisst_tracker_digest(storage.ptr().cast(), &mut digest), RfisstStatus::RfisstInvalidHandle);
        // Nor is zeroed memory.
        let mut zeroed = Storage::new();
        assert_eq!(rfisst_tracker_digest(zeroed.ptr().cast(), &mut digest), RfisstStatus::RfisstInvalidHandle);
        assert_eq!(rfisst_tracker_digest(core::ptr::null_mut(), &mut digest), RfisstStatus::RfisstNullPointer);

        // A JSON text that does not parse, or does not fit the kind.
        let broken = CString::new("{\"format\": ").expect("no NUL");
        let status = rfisst_tracker_init_json(storage.ptr(), size, kind, broken.as_ptr(), &mut tracker);
        assert_eq!(status, RfisstStatus::RfisstScenario);
        assert!(last_error(storage.ptr().cast()).starts_with("scenario: "), "{}", last_error(storage.ptr().cast()));
        let planar = CString::new(json.clone()).expect("no NUL");
        let radar = RfisstKind::RfisstRadarF64 as u32;
        let status = rfisst_tracker_init_json(storage.ptr(), storage.size(), radar, planar.as_ptr(), &mut tracker);
        assert_eq!(status, RfisstStatus::RfisstScenario);
        assert!(last_error(storage.ptr().cast()).contains("planar"), "{}", last_error(storage.ptr().cast()));

        // A good tracker, then bad steps and queries: each a status, the tracker unchanged.
        assert_eq!(init(storage.ptr(), size, kind, config, &mut tracker), RfisstStatus::RfisstOk);
        let mut before = 0;
        assert_eq!(rfisst_tracker_digest(tracker, &mut before), RfisstStatus::RfisstOk);
        let z = [1.0, 2.0, 3.0, 4.0];
        let step = |time: f64, z: *const f64, count: usize, dimension: usize| {
            rfisst_tracker_step(tracker, time, 0, core::ptr::null(), z, count, dimension, core::ptr::null_mut())
        };
        assert_eq!(step(1.0, z.as_ptr(), 2, 3), RfisstStatus::RfisstBadSize);
        assert!(last_error(tracker).contains("dimension is 2"), "{}", last_error(tracker));
        assert_eq!(step(1.0, core::ptr::null(), 2, 2), RfisstStatus::RfisstNullPointer);
        assert_eq!(step(1.0, z.as_ptr(), usize::MAX, 2), RfisstStatus::RfisstBadSize);
        assert_eq!(step(f64::NAN, z.as_ptr(), 0, 2), RfisstStatus::RfisstStepRejected);
        assert_eq!(last_error(tracker), "scan time is not finite");
        let many = vec![0.0; 2 * 40];
        assert_eq!(step(1.0, many.as_ptr(), 40, 2), RfisstStatus::RfisstStepRejected);
        assert_eq!(last_error(tracker), "40 measurements exceed the capacity of 32");
        let nan = [f64::NAN, 0.0];
        assert_eq!(step(1.0, nan.as_ptr(), 1, 2), RfisstStatus::RfisstStepRejected);
        assert_eq!(last_error(tracker), "measurement 0 is not finite");
        assert_eq!(
            rfisst_tracker_step(
                core::ptr::null_mut(),
                1.0,
                0,
                core::ptr::null(),
                z.as_ptr(),
                1,
                2,
                core::ptr::null_mut()
            ),
            RfisstStatus::RfisstNullPointer
        );
        let mut after = 0;
        assert_eq!(rfisst_tracker_digest(tracker, &mut after), RfisstStatus::RfisstOk);
        assert_eq!(before, after, "failed steps leave the tracker unchanged");

        let mut written = 0;
        let mut weights = [0.0; 1];
        assert_eq!(
            rfisst_tracker_hypotheses(tracker, weights.as_mut_ptr(), core::ptr::null_mut(), 0, &mut written),
            RfisstStatus::RfisstBufferTooSmall
        );
        assert_eq!(written, 1, "the number needed");
        assert_eq!(
            rfisst_tracker_hypotheses(tracker, weights.as_mut_ptr(), core::ptr::null_mut(), 1, &mut written),
            RfisstStatus::RfisstOk
        );
        assert_eq!(weights[0], 1.0);
        let mut track = [RfisstTrack { label: 0, existence: 0.0, state: RfisstGaussian::ZERO }];
        assert_eq!(
            rfisst_tracker_map_tracks(tracker, track.as_mut_ptr(), 1, &mut written),
            RfisstStatus::RfisstBufferTooSmall
        );
        assert_eq!(written, scenario.prior[0].1.len());
        assert_eq!(
            rfisst_tracker_tracks(tracker, 5, track.as_mut_ptr(), 1, &mut written),
            RfisstStatus::RfisstOutOfRange
        );
        assert_eq!(
            rfisst_tracker_map_tracks(tracker, core::ptr::null_mut(), 3, &mut written),
            RfisstStatus::RfisstNullPointer
        );
        assert_eq!(
            rfisst_tracker_map_tracks(tracker, track.as_mut_ptr(), 1, core::ptr::null_mut()),
            RfisstStatus::RfisstNullPointer
        );
        assert_eq!(
            rfisst_tracker_expected_cardinality(tracker, core::ptr::null_mut()),
            RfisstStatus::RfisstNullPointer
        );
        assert_eq!(rfisst_tracker_hypothesis_count(tracker, core::ptr::null_mut()), RfisstStatus::RfisstNullPointer);

        // A bad reset leaves the tracker as it was.
        let bad_prior = [RfisstPriorHypothesis { weight: -1.0, objects: core::ptr::null(), object_count: 0 }];
        assert_eq!(rfisst_tracker_reset(tracker, bad_prior.as_ptr(), 1, 0.0), RfisstStatus::RfisstConfigRejected);
        assert!(last_error(tracker).contains("weight"), "{}", last_error(tracker));
        let null_objects = [RfisstPriorHypothesis { weight: 1.0, objects: core::ptr::null(), object_count: 3 }];
        assert_eq!(rfisst_tracker_reset(tracker, null_objects.as_ptr(), 1, 0.0), RfisstStatus::RfisstNullPointer);
        assert_eq!(rfisst_tracker_digest(tracker, &mut after), RfisstStatus::RfisstOk);
        assert_eq!(before, after);

        assert_eq!(text(rfisst_tracker_last_error(core::ptr::null())), "no tracker (null or misaligned handle)");
    }
    for code in 0..13 {
        assert!(!text(rfisst_status_message(code)).is_empty());
    }
    assert_eq!(text(rfisst_status_message(13)), "unknown status code");
}

/// A prior of several hypotheses sharing objects, read object by object from the C arrays
/// (`PriorSource`), is the tracker tracker-core's `reset` builds from the same objects converted first;
/// `rfisst_tracker_reset` reloads it; a label twice in a hypothesis is the core's error.
#[test]
fn a_prior_of_several_hypotheses_loads_as_the_core_loads_it() {
    with_big_stack(|| {
        let mut scenario = from_json(&planar_scenario(3), RfisstKind::RfisstSsaF32, None).expect("planar");
        let objects = scenario.prior[0].1.clone();
        assert!(objects.len() >= 3, "the preset's prior has objects");
        let (first, rest) = (objects[..objects.len() - 1].to_vec(), objects[1..].to_vec());
        scenario.prior = vec![(3.0, first), (1.0, rest), (0.0, objects[..1].to_vec())];
        let mut storage = Storage::new();
        let tracker = init(&mut storage, RfisstKind::RfisstSsaF32, &scenario);
        let c_digest = |tracker| {
            let mut digest = 0;
            // SAFETY: a handle.
            assert_eq!(unsafe { rfisst_tracker_digest(tracker, &mut digest) }, RfisstStatus::RfisstOk);
            digest
        };
        let digest = c_digest(tracker);

        let converted: Vec<Vec<tracker_core::PriorObject<f32, 4>>> = scenario
            .prior
            .iter()
            .map(|(_, objects)| {
                let object = |o: &RfisstPriorObject| tracker_core::PriorObject {
                    label: tracker_core::TrackLabel(o.label),
                    state: rfisst::convert::gaussian(&o.state),
                };
                objects.iter().map(object).collect()
            })
            .collect();
        let prior: Vec<tracker_core::PriorHypothesis<'_, f32, 4>> = scenario
            .prior
            .iter()
            .zip(&converted)
            .map(|((weight, _), objects)| tracker_core::PriorHypothesis { weight: *weight as f32, objects })
            .collect();
        let config = rfisst::convert::planar::<f32>(&scenario.config).expect("config");
        let core = tracker_core::SsaTracker::<f32>::new(config, &prior, scenario.prior_time).expect("core");
        assert_eq!(digest, core.digest(), "C prior and core prior");
        assert_eq!(core.hypotheses().len(), 2, "the zero-weight hypothesis is dropped");

        let hypotheses = scenario.hypotheses();
        // SAFETY: a handle and the prior's hypotheses.
        let status = unsafe { rfisst_tracker_reset(tracker, hypotheses.as_ptr(), hypotheses.len(), 0.0) };
        assert_eq!(status, RfisstStatus::RfisstOk);
        assert_eq!(c_digest(tracker), digest, "reset from the same prior at the same time");

        let mut twice = scenario.prior[1].1.clone();
        twice.push(twice[0]);
        let bad = [RfisstPriorHypothesis { weight: 1.0, objects: twice.as_ptr(), object_count: twice.len() }];
        // SAFETY: as above.
        let status = unsafe { rfisst_tracker_reset(tracker, bad.as_ptr(), 1, 0.0) };
        assert_eq!(status, RfisstStatus::RfisstConfigRejected);
        assert!(last_error(tracker).contains("a label appears twice"), "{}", last_error(tracker));
        assert_eq!(c_digest(tracker), digest, "a rejected prior leaves the tracker unchanged");
    });
}
