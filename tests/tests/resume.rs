//! A tracker's state between scans read out and loaded back (`Tracker::state`, `Tracker::resume`): one
//! tracker reused for two independent trackers, loading each one's state before each of its scans, gives
//! the bits of each tracker held on its own, with sampled children, births, deaths and unseen-scan counts.

use conformance::*;
use tracker_core::config::ChildGeneration;
use tracker_core::hypothesis::Hypothesis;
use tracker_core::sampler::SamplerConfig;
use tracker_core::{BirthModel, ConfigError, LinearConfig, LinearTracker, Track, TrackLoss, TrackerState};

type Small = LinearTracker<f64, 24, 8, 6, 96, 2>;

/// What a tracker carries between scans, owned.
#[derive(Debug, Clone, PartialEq)]
struct Owned {
    time: f64,
    scans: u64,
    next_label: u32,
    tracks: Vec<Track<f64, 4>>,
    hypotheses: Vec<Hypothesis<f64, 8>>,
}

impl Owned {
    fn of(tracker: &Small) -> Self {
        let s = tracker.state().expect("no birth pool");
        Owned {
            time: s.time,
            scans: s.scans,
            next_label: s.next_label,
            tracks: s.tracks.to_vec(),
            hypotheses: s.hypotheses.to_vec(),
        }
    }

    fn view(&self) -> TrackerState<'_, f64, 4, 8> {
        TrackerState {
            time: self.time,
            scans: self.scans,
            next_label: self.next_label,
            tracks: &self.tracks,
            hypotheses: &self.hypotheses,
        }
    }
}

fn config() -> LinearConfig<f64, 2> {
    let mut config = linear_config::<2>(0.85, 2.0, 400.0);
    config.birth = BirthModel {
        events: Default::default(),
        measured: None,
        probability: 0.05,
        cells: [gaussian([5.0, 5.0, 0.0, 0.0], 9.0)].into_iter().collect(),
        detection: Default::default(),
    };
    config.death_probability = 0.05;
    config.children = ChildGeneration::Sampled(SamplerConfig { exhaustive_limit: 0, ..SamplerConfig::default() });
    config.gate = Some(16.0);
    config.track_loss = TrackLoss::AfterUnseenScans(core::num::NonZeroU16::new(4).unwrap());
    config
}

/// Scan `k` of a tracker whose objects start at `x0`: the objects seen (most scans), clutter, a birth.
fn scan(k: usize, x0: f64) -> Vec<V2> {
    let t = k as f64;
    let mut zs = vec![];
    if k % 3 != 2 {
        zs.push(V2::new(x0 + t + 0.1 * (t * 1.3).sin(), 0.1 * (t * 0.7).cos()));
    }
    if k % 4 != 1 {
        zs.push(V2::new(x0 + 0.8 + 0.9 * t, 0.4 + 0.1 * t.sin()));
    }
    if k >= 5 {
        zs.push(V2::new(5.0 + 0.2 * (t - 5.0), 5.1));
    }
    zs.push(V2::new(x0 - 7.0 + (t * 2.1).sin() * 3.0, -6.0 + (t * 1.7).cos() * 3.0));
    zs
}

#[test]
fn a_reused_tracker_resumed_before_each_scan_gives_each_trackers_own_bits() {
    let objects = |x0: f64| [gaussian([x0, 0.0, 1.0, 0.0], 0.5), gaussian([x0 + 0.8, 0.4, 0.9, 0.1], 0.5)];
    let mut alone = [
        Box::new(Small::with_objects(config(), &objects(0.0), 0.0).unwrap()),
        Box::new(Small::with_objects(config(), &objects(3.0), 0.0).unwrap()),
    ];
    let mut rests = [Owned::of(&alone[0]), Owned::of(&alone[1])];
    let mut shared = Box::new(Small::empty(config()));
    let (mut hypotheses, mut unseen) = (0, 0);
    for k in 1..=14 {
        for (i, x0) in [0.0, 3.0].into_iter().enumerate() {
            let zs = scan(k, x0);
            shared.resume(&rests[i].view()).unwrap();
            assert_eq!(shared.digest(), alone[i].digest());
            alone[i].step(k as f64, &zs).unwrap();
            shared.step(k as f64, &zs).unwrap();
            rests[i] = Owned::of(&shared);
            assert_eq!(rests[i], Owned::of(&alone[i]), "tracker {i}, scan {k}");
            assert_eq!(shared.digest(), alone[i].digest());
            hypotheses = hypotheses.max(alone[i].hypotheses().len());
            unseen = unseen.max(alone[i].tracks().iter().map(|t| t.unseen_scans).max().unwrap_or(0));
        }
    }
    // The run exercised what the state must carry: several hypotheses, births, unseen scans.
    assert!(hypotheses > 1, "{hypotheses}");
    assert!(rests.iter().any(|r| r.next_label > 2), "a birth");
    assert!(unseen > 0, "an unseen scan counted");
}

#[test]
fn a_state_that_does_not_fit_is_refused_and_changes_nothing() {
    let two =
        Small::with_objects(config(), &[gaussian([0.0; 4], 1.0), gaussian([9.0, 0.0, 0.0, 0.0], 1.0)], 0.0).unwrap();
    let mut other = Small::with_objects(config(), &[gaussian([1.0; 4], 1.0)], 3.0).unwrap();
    let before = other.digest();
    let mut bad = Owned::of(&two);
    bad.tracks.truncate(1);
    assert_eq!(other.resume(&bad.view()), Err(ConfigError::PriorObject { hypothesis: 0, object: 1 }));
    let mut bad = Owned::of(&two);
    bad.time = f64::NAN;
    assert_eq!(other.resume(&bad.view()), Err(ConfigError::PriorTime));
    let mut bad = Owned::of(&two);
    bad.hypotheses.clear();
    assert_eq!(other.resume(&bad.view()), Err(ConfigError::PriorEmpty));
    assert_eq!(other.digest(), before);
    assert!(Small::empty(config()).state().is_none(), "no prior, no state");
}
