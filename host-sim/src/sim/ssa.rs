//! The 3-D SSA scenario and its simulation, independent of tracker-core: real SSA scans: ground radars (range, azimuth, elevation, optional
//! range-rate) and telescopes (topocentric right ascension, declination) looking at objects on two-body +
//! J2 orbits, with fields of view, detection and clutter in measurement coordinates.
//!
//! **Independence.** Nothing here calls tracker-core: the time scale, the Earth model, the frames, the
//! measurement functions and the field-of-view tests are written again, so that a test comparing the
//! tracker with this truth compares two implementations. Truth orbits come from [`super::orbit`]
//! (adaptive RKF7(8), two-body + J2), not from the tracker's fixed-step RK4.
//!
//! **Frames and time.** Inertial frame: Earth-centred, z along the pole, x at the equinox of the
//! scenario's epoch (the frame of SGP4's TEME up to the neglected terms below); km, km/s, radians,
//! seconds since the epoch. The Earth-fixed frame is the inertial one turned about z by the Earth
//! rotation angle θ(t) = GMST(epoch) + ω_E t, with GMST the IAU-82 polynomial (the one SGP4 uses),
//! UT1 = UTC, and ω_E = 7.292115e-5 rad/s. Neglected: polar motion (≲ 0.5″, ≲ 15 m at the site),
//! UT1 − UTC (≤ 0.9 s, ≲ 0.4 km of site motion along the parallel), precession-nutation between epoch
//! and scan (hours: ≪ 1″). Light-time is not modelled (truth and tracker share the instantaneous
//! geometry): for real LEO radar data it is ≲ 10 ms, up to ≈ 70 m of range and ≈ 0.001° of angle; for
//! GEO optical ≈ 0.12 s, ≈ 2″. Annual aberration (≈ 20″) is not modelled either.
//! Sunlight and night are ignored for the telescope.
//!
//! **Sites.** Geodetic latitude, longitude and height on WGS-84; the observer's inertial velocity is
//! ω_E × r. The local frame is East-North-Up.
//!
//! **Measurements.** Radar: ρ = |d|, A = atan2(d·e, d·n) ∈ (−π, π] (from North toward East),
//! E = atan2(d·u, √((d·e)² + (d·n)²)), optional ρ̇ = d·(v − v_s)/ρ, with d = r − r_s. Optical:
//! α = atan2(d_y, d_x) ∈ (−π, π], δ = asin(d_z/|d|). Noise is Gaussian per component; angles are wrapped
//! into (−π, π]; a noisy elevation (declination) above π/2 is reflected over the zenith (pole), turning
//! the azimuth (right ascension) by π, so every reported angle is in its range.
//!
//! **Fields of view** live in the site's local frame: a cone about a boresight (A₀, E₀) or an
//! azimuth/elevation box, always with an elevation mask and, for radar, a range window. An object is
//! detectable when its true (A, E, ρ) is inside; it is detected with probability p_D. Clutter is
//! Poisson per scan and uniform in measurement coordinates over the field of view: (ρ, A, E[, ρ̇]) for
//! radar, (α, δ) for optical (where membership of a sampled (α, δ) goes through the site's ENU basis
//! at the scan time), drawn by rejection from a bounding box in those coordinates.

use super::error::{MAX_MEASUREMENTS, SsaError};
use super::sensor::SensorSpec;
use super::site::Observer;
use super::time::{earth_rotation_angle, parse_iso8601};
use super::truth::{Group, ObjectTruth, TruthAt, track};
use super::vector::{V3, angle_between, pos, sub};
use crate::sim::rng::{Random, Stream};
use serde::{Deserialize, Serialize};

/// A visibility gap longer than this (s) between two in-view times of one sensor starts a new pass.
pub const PASS_GAP: f64 = 600.0;

/// One scan of one sensor.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Scan3 {
    /// Seconds since the epoch.
    pub time: f64,
    /// Index into `sensors`.
    pub sensor: usize,
    /// Measurements (detections and clutter in random order).
    pub measurements: Vec<Vec<f64>>,
    /// Objects inside the field of view (detected or not), by object index.
    pub truth: Vec<TruthAt>,
}

/// A simulated SSA scenario.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SsaScenario {
    /// Preset name.
    pub name: String,
    /// The seed.
    pub seed: u64,
    /// UTC epoch as written.
    pub epoch: String,
    /// UTC epoch as a Julian date (UT1 = UTC).
    pub epoch_jd: f64,
    /// Duration (s).
    pub duration: f64,
    /// Sensors.
    pub sensors: Vec<SensorSpec>,
    /// Objects (all exist for the whole scenario).
    pub objects: Vec<ObjectTruth>,
    /// Crossing pairs and clusters.
    pub groups: Vec<Group>,
    /// Scans in time order.
    pub scans: Vec<Scan3>,
}

/// Figures of a scenario.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stats {
    /// Number of scans.
    pub scans: usize,
    /// Most measurements in one scan.
    pub max_measurements: usize,
    /// Mean measurements per scan.
    pub mean_measurements: f64,
    /// Most objects in view in one scan.
    pub max_in_view: usize,
    /// Mean objects in view per scan.
    pub mean_in_view: f64,
    /// Scans with at least one object in view.
    pub scans_with_objects: usize,
}

impl SsaScenario {
    /// Scan statistics.
    pub fn stats(&self) -> Stats {
        let n = self.scans.len().max(1) as f64;
        Stats {
            scans: self.scans.len(),
            max_measurements: self.scans.iter().map(|s| s.measurements.len()).max().unwrap_or(0),
            mean_measurements: self.scans.iter().map(|s| s.measurements.len()).sum::<usize>() as f64 / n,
            max_in_view: self.scans.iter().map(|s| s.truth.len()).max().unwrap_or(0),
            mean_in_view: self.scans.iter().map(|s| s.truth.len()).sum::<usize>() as f64 / n,
            scans_with_objects: self.scans.iter().filter(|s| !s.truth.is_empty()).count(),
        }
    }

    /// Passes per object: maximal runs of in-view times of one sensor, split by gaps > [`PASS_GAP`],
    /// summed over the sensors.
    pub fn passes(&self) -> Vec<usize> {
        let mut last = vec![vec![f64::NEG_INFINITY; self.sensors.len()]; self.objects.len()];
        let mut passes = vec![0; self.objects.len()];
        for scan in &self.scans {
            for t in &scan.truth {
                if scan.time - last[t.object][scan.sensor] > PASS_GAP {
                    passes[t.object] += 1;
                }
                last[t.object][scan.sensor] = scan.time;
            }
        }
        passes
    }

    /// Per group, over the scans that see all its members: the smallest and the largest pairwise angle
    /// (rad) between members as seen from the sensor ((∞, 0) if no scan sees them all).
    pub fn group_separations(&self) -> Vec<(f64, f64)> {
        self.groups
            .iter()
            .map(|g| {
                let (mut lo, mut hi) = (f64::INFINITY, 0.0_f64);
                for scan in &self.scans {
                    let o = self.observer(scan);
                    let dirs: Option<Vec<V3>> = g
                        .objects
                        .iter()
                        .map(|&i| scan.truth.iter().find(|t| t.object == i).map(|t| sub(pos(&t.state), o.position)))
                        .collect();
                    let Some(dirs) = dirs else { continue };
                    for (k, x) in dirs.iter().enumerate() {
                        for y in &dirs[k + 1..] {
                            let angle = angle_between(*x, *y);
                            lo = lo.min(angle);
                            hi = hi.max(angle);
                        }
                    }
                }
                (lo, hi)
            })
            .collect()
    }

    /// An object's truth at every scan time (in view or not), propagated from its initial state the way
    /// the simulation did: the states of the scans' `truth` entries are reproduced bit for bit.
    ///
    /// # Errors
    /// [`SsaError::Orbit`] if propagation fails.
    pub fn object_states(&self, object: usize) -> Result<Vec<[f64; 6]>, SsaError> {
        let times: Vec<f64> = self.scans.iter().map(|s| s.time).collect();
        track(self.objects[object].initial_state, &times)
    }

    /// The observer of a scan.
    pub fn observer(&self, scan: &Scan3) -> Observer {
        self.sensors[scan.sensor].site.observer(earth_rotation_angle(self.epoch_jd, scan.time))
    }
}

/// Per scan, whether the object is inside the scan's field of view.
pub(crate) fn visibility(
    sensors: &[SensorSpec],
    schedule: &[(f64, usize)],
    observers: &[Observer],
    states: &[[f64; 6]],
) -> Vec<bool> {
    schedule.iter().zip(observers).zip(states).map(|((&(_, s), o), x)| sensors[s].sees(o, x)).collect()
}

/// The number of passes in a visibility sequence (see [`SsaScenario::passes`]).
pub(crate) fn count_passes(schedule: &[(f64, usize)], visible: &[bool], sensors: usize) -> usize {
    let mut last = vec![f64::NEG_INFINITY; sensors];
    let mut passes = 0;
    for (&(t, s), &v) in schedule.iter().zip(visible) {
        if v {
            if t - last[s] > PASS_GAP {
                passes += 1;
            }
            last[s] = t;
        }
    }
    passes
}

/// Everything a preset decides before the scans are drawn.
pub(super) struct Plan {
    pub(super) name: String,
    pub(super) seed: u64,
    pub(super) epoch: String,
    pub(super) duration: f64,
    pub(super) sensors: Vec<SensorSpec>,
    pub(super) objects: Vec<ObjectTruth>,
    pub(super) groups: Vec<Group>,
    /// (time, sensor) of every scan, in time order.
    pub(super) schedule: Vec<(f64, usize)>,
    /// Truth per object per scan, when the preset already propagated it.
    pub(super) tracks: Option<Vec<Vec<[f64; 6]>>>,
    /// Per object per scan, whether the object can be seen at all (a telescope sees only sunlit objects);
    /// `None`: always.
    pub(super) visible: Option<Vec<Vec<bool>>>,
}

pub(crate) fn observers(sensors: &[SensorSpec], epoch_jd: f64, schedule: &[(f64, usize)]) -> Vec<Observer> {
    schedule.iter().map(|&(t, s)| sensors[s].site.observer(earth_rotation_angle(epoch_jd, t))).collect()
}

/// Draws scan `k` of a plan with `seed`: the sensor `s` (`sensor`, seen from `observer`) at `time` looks at
/// the objects at `states` (`None`: object `i` cannot be seen at this scan; object `i` draws its detection and
/// noise from `detection[i]`); Poisson clutter
/// from stream [`Stream::Clutter`] `k`, the order shuffled by stream [`Stream::Scenario`] `k`.
///
/// # Errors
/// [`SsaError::TooManyMeasurements`] above [`MAX_MEASUREMENTS`]; [`SsaError::EmptyFieldOfView`] from clutter.
pub fn draw_scan(
    seed: u64,
    k: usize,
    scan: (f64, usize),
    sensor: &SensorSpec,
    observer: &Observer,
    states: impl Iterator<Item = Option<[f64; 6]>>,
    detection: &mut [Random],
) -> Result<Scan3, SsaError> {
    let scan = draw_scan_any_size(seed, k, scan, sensor, observer, states, detection)?;
    if scan.measurements.len() > MAX_MEASUREMENTS {
        return Err(SsaError::TooManyMeasurements { scan: k });
    }
    Ok(scan)
}

/// [`draw_scan`] without the cap on its measurements (`experiment catalogue-scale`'s wide-field radar sees
/// hundreds of objects at once; its tracker routes them to clusters).
///
/// # Errors
/// [`SsaError::EmptyFieldOfView`] from clutter.
pub fn draw_scan_any_size(
    seed: u64,
    k: usize,
    (time, s): (f64, usize),
    sensor: &SensorSpec,
    observer: &Observer,
    states: impl Iterator<Item = Option<[f64; 6]>>,
    detection: &mut [Random],
) -> Result<Scan3, SsaError> {
    // (measurement, origin)
    let mut items: Vec<(Vec<f64>, Option<usize>)> = Vec::new();
    let mut truth = Vec::new();
    for ((i, state), random) in states.enumerate().zip(detection.iter_mut()) {
        let Some(state) = state.filter(|state| sensor.sees(observer, state)) else { continue };
        truth.push(TruthAt { object: i, state, measurement: None });
        if random.uniform() < sensor.detection_probability {
            items.push((sensor.noisy(observer, &state, random), Some(i)));
        }
    }
    let mut clutter = Random::stream(seed, Stream::Clutter, k as u64);
    for _ in 0..clutter.poisson(sensor.clutter_rate) {
        items.push((sensor.clutter_point(observer, &mut clutter)?, None));
    }
    Random::stream(seed, Stream::Scenario, k as u64).shuffle(&mut items);
    for (j, (_, origin)) in items.iter().enumerate() {
        if let Some(i) = origin
            && let Some(t) = truth.iter_mut().find(|t| t.object == *i)
        {
            t.measurement = Some(j);
        }
    }
    Ok(Scan3 { time, sensor: s, measurements: items.into_iter().map(|(z, _)| z).collect(), truth })
}

/// Draws detections and clutter for every scan of a plan.
pub(super) fn simulate(plan: Plan) -> Result<SsaScenario, SsaError> {
    let epoch_jd = parse_iso8601(&plan.epoch)?;
    for s in &plan.sensors {
        s.check()?;
    }
    let times: Vec<f64> = plan.schedule.iter().map(|&(t, _)| t).collect();
    let observers = observers(&plan.sensors, epoch_jd, &plan.schedule);
    let tracks = match plan.tracks {
        Some(t) => t,
        None => plan.objects.iter().map(|o| track(o.initial_state, &times)).collect::<Result<_, _>>()?,
    };
    let mut detection: Vec<Random> =
        (0..plan.objects.len()).map(|i| Random::stream(plan.seed, Stream::Detection, i as u64)).collect();
    let mut scans = Vec::with_capacity(plan.schedule.len());
    for (k, (&(time, s), observer)) in plan.schedule.iter().zip(&observers).enumerate() {
        // An object that does not exist yet (a fragment before its break-up) or that the plan marks invisible
        // at this scan (a telescope's unlit object) is not seen.
        let visible = |i: usize| plan.objects[i].exists_at(time) && plan.visible.as_ref().is_none_or(|v| v[i][k]);
        let states = tracks.iter().enumerate().map(|(i, states)| visible(i).then_some(states[k]));
        scans.push(draw_scan(plan.seed, k, (time, s), &plan.sensors[s], observer, states, &mut detection)?);
    }
    Ok(SsaScenario {
        name: plan.name,
        seed: plan.seed,
        epoch: plan.epoch,
        epoch_jd,
        duration: plan.duration,
        sensors: plan.sensors,
        objects: plan.objects,
        groups: plan.groups,
        scans,
    })
}

/// A scenario whose truth the caller propagated (`tracks[object][scan]`, inertial km, km/s, at the
/// `schedule`'s times): detections and clutter drawn as for the presets, an object seen only where
/// `visible[object][scan]` (and inside the sensor's field of view). `objects[i].initial_state` is
/// `tracks`' first state (informative only).
///
/// # Errors
/// As [`radar_leo`].
#[allow(clippy::too_many_arguments)]
pub fn simulate_tracks(
    name: &str,
    seed: u64,
    epoch: &str,
    duration: f64,
    sensors: Vec<SensorSpec>,
    schedule: Vec<(f64, usize)>,
    tracks: Vec<Vec<[f64; 6]>>,
    visible: Vec<Vec<bool>>,
) -> Result<SsaScenario, SsaError> {
    let objects = tracks
        .iter()
        .map(|t| ObjectTruth {
            initial_state: t.first().copied().unwrap_or([0.0; 6]),
            group: None,
            in_prior: true,
            birth_time: None,
        })
        .collect();
    simulate(Plan {
        name: name.into(),
        seed,
        epoch: epoch.into(),
        duration,
        sensors,
        objects,
        groups: vec![],
        schedule,
        tracks: Some(tracks),
        visible: Some(visible),
    })
}
