//! The truth of the simulated objects: their initial states and groups, which are unknown to the prior, their tracks, and Keplerian orbit construction.

use super::error::SsaError;
use super::vector::{add, scale};
use crate::sim::orbit::Propagator;
use crate::sim::rng::{Random, Stream};
use core::f64::consts::PI;
use serde::{Deserialize, Serialize};

/// Earth's gravitational parameter used to build orbits (km³/s², as [`crate::sim::orbit::Gravity::EARTH`]).
pub(crate) const MU: f64 = 398_600.441_8;

/// One object's truth.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ObjectTruth {
    /// Inertial state at t = 0 (km, km/s); propagate with [`crate::sim::orbit::Propagator::EARTH`].
    pub initial_state: [f64; 6],
    /// The crossing pair, co-located cluster or break-up it belongs to (index into `groups`), if any.
    pub group: Option<usize>,
    /// Whether the prior knows the object.
    #[serde(default = "known")]
    pub in_prior: bool,
    /// When the object starts to exist (a break-up fragment); `None`: from the start.
    #[serde(default)]
    pub birth_time: Option<f64>,
}

pub(crate) fn known() -> bool {
    true
}

impl ObjectTruth {
    /// An object of the prior that exists from the start.
    pub fn known(initial_state: [f64; 6], group: Option<usize>) -> Self {
        ObjectTruth { initial_state, group, in_prior: true, birth_time: None }
    }

    /// Whether the object exists at `time`.
    pub fn exists_at(&self, time: f64) -> bool {
        self.birth_time.is_none_or(|b| b <= time)
    }
}

/// Objects unknown to the prior: a fraction of the objects missing from it, and a break-up.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Unknowns {
    /// Fraction of the objects (break-up fragments aside) left out of the prior, rounded to the nearest
    /// count; in [0, 1].
    pub missing_fraction: f64,
    /// Fragments of a break-up during the run (`radar-leo` only; 0: none).
    pub breakup: usize,
}

/// Leaves `round(fraction × n)` of the first `n` objects out of the prior, chosen by the seed's stream
/// [`Stream::Scenario`] 2,000,000 (no other draw moves).
pub(crate) fn mark_missing(seed: u64, objects: &mut [ObjectTruth], n: usize, fraction: f64) -> Result<(), SsaError> {
    if !(0.0..=1.0).contains(&fraction) {
        return Err(SsaError::BadUnknowns);
    }
    let mut order: Vec<usize> = (0..n).collect();
    Random::stream(seed, Stream::Scenario, 2_000_000).shuffle(&mut order);
    let missing = (fraction * n as f64).round() as usize;
    for &i in &order[..missing.min(n)] {
        objects[i].in_prior = false;
    }
    Ok(())
}

/// An object's truth at every scan time.
pub(crate) type Track = Vec<[f64; 6]>;

/// A deliberately close group of objects.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Group {
    /// "crossing-pair" or "cluster".
    pub kind: String,
    /// Object indices.
    pub objects: Vec<usize>,
}

/// The truth of one object that is inside the field of view at a scan.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TruthAt {
    /// Object index.
    pub object: usize,
    /// Inertial state at the scan time.
    pub state: [f64; 6],
    /// The index of its measurement in the scan, if detected.
    pub measurement: Option<usize>,
}

/// Truth states of one object at `times` (increasing, ≥ 0), propagated step by step from t = 0.
pub(crate) fn track(initial: [f64; 6], times: &[f64]) -> Result<Vec<[f64; 6]>, SsaError> {
    let mut state = initial;
    let mut t = 0.0;
    let mut out = Vec::with_capacity(times.len());
    for &ti in times {
        state = Propagator::EARTH.propagate(state, ti - t)?;
        t = ti;
        out.push(state);
    }
    Ok(out)
}

/// The inertial state of a Keplerian orbit (a km, e, angles rad, M mean anomaly).
pub fn kepler_state(a: f64, e: f64, i: f64, raan: f64, argp: f64, mean_anomaly: f64) -> [f64; 6] {
    let mut ea = mean_anomaly;
    for _ in 0..20 {
        ea -= (ea - e * ea.sin() - mean_anomaly) / (1.0 - e * ea.cos());
    }
    let (se, ce) = ea.sin_cos();
    let b = a * (1.0 - e * e).sqrt();
    let r = a * (1.0 - e * ce);
    let n = (MU / (a * a * a)).sqrt();
    // Perifocal position and velocity.
    let (xp, yp) = (a * (ce - e), b * se);
    let (vxp, vyp) = (-a * a * n * se / r, a * b * n * ce / r);
    let (so, co) = raan.sin_cos();
    let (sw, cw) = argp.sin_cos();
    let (si, ci) = i.sin_cos();
    let p = [co * cw - so * sw * ci, so * cw + co * sw * ci, sw * si];
    let q = [-co * sw - so * cw * ci, -so * sw + co * cw * ci, cw * si];
    let r_vec = add(scale(p, xp), scale(q, yp));
    let v_vec = add(scale(p, vxp), scale(q, vyp));
    [r_vec[0], r_vec[1], r_vec[2], v_vec[0], v_vec[1], v_vec[2]]
}

/// A circular orbit of `radius` and `inclination` passing through the inertial direction of
/// (right ascension, declination) `aim`, ascending or descending there; its state at that point.
pub(crate) fn aimed_circular(aim: [f64; 2], radius: f64, inclination: f64, ascending: bool) -> [f64; 6] {
    let [ra, dec] = aim;
    let s = (dec.sin() / inclination.sin()).clamp(-1.0, 1.0).asin();
    let u = if ascending { s } else { PI - s };
    let raan = ra - (inclination.cos() * u.sin()).atan2(u.cos());
    kepler_state(radius, 0.0, inclination, raan, 0.0, u)
}

/// Sidereal days over which [`geosynchronous`] measures the drift.
const DRIFT_DAYS: f64 = 5.0;

/// `state` with its speed scaled so that, under the truth's two-body + J2 gravity, it keeps its place
/// above the Earth: its right ascension after whole sidereal days gains exactly the Earth's turns.
///
/// A circular orbit at the two-body geosynchronous radius (μ/ω_E²)^(1/3) drifts under J2: J2 adds to
/// the pull of the Earth, so the mean motion exceeds ω_E (by about 0.007° a day at the equator, more from
/// the osculating speed). Over months such an object leaves a 3° field of view, which a station-kept
/// object does not. The drift rate λ̇ is measured over [`DRIFT_DAYS`] sidereal days (comparing the same
/// phase of the day cancels the daily terms) and removed by scaling the speed: for a near-circular orbit
/// δa/a = 2 δv/v and λ̇ = −(3/2) n δa/a, so δv/v = −λ̇ / (3 n). Three rounds leave below 10⁻⁸ rad a day.
///
/// # Errors
/// When the propagation fails.
pub(crate) fn geosynchronous(mut state: [f64; 6], earth_rate: f64) -> Result<[f64; 6], SsaError> {
    let span = DRIFT_DAYS * 2.0 * PI / earth_rate;
    for _ in 0..3 {
        let end = Propagator::EARTH.propagate(state, span)?;
        let turned = end[1].atan2(end[0]) - state[1].atan2(state[0]);
        let drift = (turned + PI).rem_euclid(2.0 * PI) - PI;
        let scale_by = 1.0 + drift / span / (3.0 * earth_rate);
        for v in &mut state[3..] {
            *v *= scale_by;
        }
    }
    Ok(state)
}
