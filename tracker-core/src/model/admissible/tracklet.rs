//! Tracklets: short arcs of angles from one optical sensor, linked across frames, and the birth density of
//! their admissible region in (range, range-rate) (docs/maths.md §5.10).
//!
//! One frame of a telescope gives two angles; the object's range and all of its velocity are unknown, so a
//! single-frame birth density ([`super::optical_births`]) spans a 4-D region and needs hundreds of cells.
//! A few frames of the same object give the angles *and their rates* at a mid time: an *attributable*
//! (α, δ, α̇, δ̇). Only range ρ and range-rate ρ̇ remain unknown, and the state is
//!
//! ```text
//! r = q + ρ ê(α, δ),    v = q̇ + ρ̇ ê + ρ (α̇ ê_α + δ̇ ê_δ)
//! ```
//!
//! (q, q̇ the observer's inertial state, ê_α = ∂ê/∂α, ê_δ = ∂ê/∂δ). The admissible region is the set of
//! (ρ, ρ̇) whose orbit has a perigee of at least `min_perigee_radius`, an apogee of at most
//! `max_apogee_radius` (so it is bound) and an inclination of at most `max_inclination`: the region of
//! Milani et al. restricted as DeMars and Jah's constrained admissible region. A coarse pass finds the
//! span of ranges with an admissible range-rate; that span is cut into `range_cells` cells uniform in
//! ln ρ (so LEO and GEO ranges are resolved alike) times `rate_cells` cells across each range cell's
//! admissible range-rates (the perigee and apogee conditions solved in closed form: a GEO region's are
//! metres per second wide); each cell with an admissible part gives a
//! component weighted by its admissible area (a density uniform in (ln ρ, ρ̇)), with the attributable's
//! covariance and the cell's width carried through the map above.
//!
//! **Linking.** The frames' angles are fitted by a quadratic per angle in time (least squares, equal
//! weights; the angle, rate and acceleration at the mean time). A set of measurements is a tracklet when
//! the fit passes [`LinkLimits`]: its χ² with 2 (n − 3) degrees of freedom (from 4 frames on), its
//! angular rate and its angular acceleration. Three frames fit exactly, so only the rate and acceleration
//! bounds test them: the false-link rate of 3-frame tracklets in clutter is the fraction of random triples
//! within those bounds (docs/maths.md §5.10); from 4 frames on the χ² test removes almost all of them.

use super::{AdmissibleRegion, CELL_SIGMA};
use super::{BirthComponent, BirthError, Cell, Lens, V3, cell, finish, inclination_ok, norm, push, real};
use crate::real::{Real, c, cos, exp, ln, sin, sqrt};
use nalgebra::{SMatrix, SVector};

/// Frames a tracklet holds at most.
pub const MAX_TRACKLET_FRAMES: usize = 8;
/// Scan points per cell, per axis, of the coarse pass that finds the admissible ranges.
const SCAN: usize = 8;

/// One frame of a candidate tracklet: its time (s) and its angles (right ascension, declination; rad).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrackletFrame<T> {
    /// Time of the frame (s).
    pub time: f64,
    /// Right ascension and declination (rad).
    pub angles: [T; 2],
}

/// One measurement as a direction on the sky, for tracklets: what a sensor that measures angles gives the
/// birth pool ([`crate::model::BirthGeometry::sky_point`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SkyPoint<T> {
    /// Topocentric right ascension and declination (rad).
    pub angles: [T; 2],
    /// Their noise σ (rad).
    pub sigma: [T; 2],
    /// The observer's inertial state (km, km/s) at the measurement.
    pub observer: [T; 6],
}

/// Angles and angle rates of one object at a reference time, with their covariance, from a linked short
/// arc.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Attributable<T: Real> {
    /// The reference time (s): the frames' mean time ([`Attributable::fit`]) or the caller's.
    pub time: f64,
    /// (α, δ, α̇, δ̇): rad and rad/s.
    pub values: [T; 4],
    /// Their covariance (the fit's, with the measurement noise).
    pub covariance: SMatrix<T, 4, 4>,
    /// The fit's χ² (2 (n − 3) degrees of freedom).
    pub chi_squared: T,
    /// The fitted accelerations on the sky, α̈ cos δ and δ̈ (rad/s²).
    pub accelerations: [T; 2],
    /// Frames fitted.
    pub frames: usize,
}

/// The link test of [`Attributable::fit`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct LinkLimits<T> {
    /// The largest χ² of the fit (2 (n − 3) degrees of freedom; no test with 3 frames).
    pub max_chi_squared: T,
    /// The largest angular rate √(α̇² cos²δ + δ̇²) (rad/s).
    pub max_rate: T,
    /// The largest angular acceleration per axis, δ̈ and α̈ cos δ (rad/s²), beyond 3 σ of its estimate.
    pub max_acceleration: T,
    /// The largest angular jerk per axis (rad/s³) the quadratic neglects: the bias it can cause in the
    /// angles and rates is added to their variances (a LEO pass seen from the ground: ~1e-5).
    pub max_jerk: T,
}

/// Why frames do not make a tracklet.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum TrackletError {
    /// Fewer than 3 or more than [`MAX_TRACKLET_FRAMES`] frames, or two frames at the same time.
    Frames,
    /// An angle, a time or σ is not finite (or σ ≤ 0).
    NonFinite,
    /// The fit's χ², rate or acceleration is beyond the [`LinkLimits`].
    NotLinked,
}

impl core::fmt::Display for TrackletError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            TrackletError::Frames => f.write_str("a tracklet needs 3 to 8 frames at distinct times"),
            TrackletError::NonFinite => f.write_str("non-finite tracklet angle, time or noise"),
            TrackletError::NotLinked => f.write_str("the frames are not one object's short arc"),
        }
    }
}

/// `a − b` wrapped to (−π, π].
fn angle_difference<T: Real>(a: T, b: T) -> T {
    let two_pi = T::pi() + T::pi();
    let mut d = a - b;
    if d > T::pi() {
        d -= two_pi;
    } else if d <= -T::pi() {
        d += two_pi;
    }
    d
}

impl<T: Real> Attributable<T> {
    /// Fits `frames` (in any order) with a quadratic in time per angle about their mean time; `sigma` is
    /// the noise of (α, δ) per frame. The frames are a tracklet when the fit passes `limits`.
    ///
    /// # Errors
    /// [`TrackletError`].
    pub fn fit(frames: &[TrackletFrame<T>], sigma: [T; 2], limits: &LinkLimits<T>) -> Result<Self, TrackletError> {
        let mean = frames.iter().map(|f| f.time).sum::<f64>() / frames.len().max(1) as f64;
        Self::fit_at(frames, mean, sigma, limits)
    }

    /// As [`Attributable::fit`], with the attributable at `time` (the birth pool takes the latest frame's,
    /// where its observer is placed).
    ///
    /// # Errors
    /// [`TrackletError`]; a non-finite `time` is [`TrackletError::NonFinite`].
    pub fn fit_at(
        frames: &[TrackletFrame<T>],
        time: f64,
        sigma: [T; 2],
        limits: &LinkLimits<T>,
    ) -> Result<Self, TrackletError> {
        let n = frames.len();
        if !(3..=MAX_TRACKLET_FRAMES).contains(&n) {
            return Err(TrackletError::Frames);
        }
        let finite = frames.iter().all(|f| f.time.is_finite() && f.angles.iter().all(|a| a.is_finite_value()));
        if !finite || !time.is_finite() || !sigma.iter().all(|s| s.is_finite_value() && *s > T::zero()) {
            return Err(TrackletError::NonFinite);
        }
        if frames.iter().enumerate().any(|(i, a)| frames.iter().take(i).any(|b| b.time == a.time)) {
            return Err(TrackletError::Frames);
        }
        let row = |f: &TrackletFrame<T>| {
            let dt = T::of_f64(f.time - time);
            SVector::<T, 3>::from([T::one(), dt, dt * dt * c(0.5)])
        };
        let normal = frames.iter().fold(SMatrix::<T, 3, 3>::zeros(), |m, f| m + row(f) * row(f).transpose());
        let inverse = normal.try_inverse().ok_or(TrackletError::Frames)?;
        let reference = frames[0].angles[0];
        let mut values = [T::zero(); 4];
        let mut acceleration = [T::zero(); 2];
        let mut chi_squared = T::zero();
        for axis in 0..2 {
            // Right ascension relative to the first frame's, so an arc across 0/2π stays continuous.
            let y =
                |f: &TrackletFrame<T>| if axis == 0 { angle_difference(f.angles[0], reference) } else { f.angles[1] };
            let rhs = frames.iter().fold(SVector::<T, 3>::zeros(), |s, f| s + row(f) * y(f));
            let p = inverse * rhs;
            chi_squared += frames.iter().fold(T::zero(), |s, f| {
                let r = y(f) - row(f).dot(&p);
                s + r * r
            }) / (sigma[axis] * sigma[axis]);
            values[axis] = if axis == 0 { reference + p[0] } else { p[0] };
            values[axis + 2] = p[1];
            acceleration[axis] = p[2];
        }
        let cos_dec = cos(values[1]);
        let rate = sqrt(values[2] * values[2] * cos_dec * cos_dec + values[3] * values[3]);
        let accelerations = [acceleration[0] * cos_dec, acceleration[1]];
        let spread = [sigma[0] * cos_dec, sigma[1]].map(|s| c::<T>(3.0) * s * sqrt(inverse[(2, 2)]));
        let steady = accelerations.iter().zip(&spread).all(|(a, s)| a.abs() <= limits.max_acceleration + *s);
        if !(chi_squared <= limits.max_chi_squared && rate <= limits.max_rate && steady) {
            return Err(TrackletError::NotLinked);
        }
        // The fit's bias from a cubic term j t³ / 6: j · inverse · Σ row t³ / 6, at most max_jerk per axis.
        let cubic = frames.iter().fold(SVector::<T, 3>::zeros(), |s, f| {
            let dt = T::of_f64(f.time - time);
            s + row(f) * (dt * dt * dt / c(6.0))
        });
        let bias = inverse * cubic * limits.max_jerk;
        let mut covariance = SMatrix::<T, 4, 4>::zeros();
        for axis in 0..2 {
            let s2 = sigma[axis] * sigma[axis];
            covariance[(axis, axis)] = s2 * inverse[(0, 0)];
            covariance[(axis, axis + 2)] = s2 * inverse[(0, 1)];
            covariance[(axis + 2, axis)] = s2 * inverse[(1, 0)];
            covariance[(axis + 2, axis + 2)] = s2 * inverse[(1, 1)];
            // The bias bound, with α's scaled to the sky (a jerk of the sky's motion is 1/cos δ in α).
            let scale = if axis == 0 { T::one() / cos_dec.abs().max(c(1e-3)) } else { T::one() };
            let (b0, b1) = (bias[0] * scale, bias[1] * scale);
            covariance[(axis, axis)] += b0 * b0;
            covariance[(axis, axis + 2)] += b0 * b1;
            covariance[(axis + 2, axis)] += b0 * b1;
            covariance[(axis + 2, axis + 2)] += b1 * b1;
        }
        Ok(Self { time, values, covariance, chi_squared, accelerations, frames: n })
    }
}

/// ê, ê_α, ê_δ and the second derivatives ê_αα, ê_αδ (ê_δδ = −ê) at (α, δ).
fn directions<T: Real>(alpha: T, delta: T) -> [V3<T>; 5] {
    let (sa, ca, sd, cd) = (sin(alpha), cos(alpha), sin(delta), cos(delta));
    let z = T::zero();
    [
        V3::from([cd * ca, cd * sa, sd]),
        V3::from([-cd * sa, cd * ca, z]),
        V3::from([-sd * ca, -sd * sa, cd]),
        V3::from([-cd * ca, -cd * sa, z]),
        V3::from([sd * sa, -sd * ca, z]),
    ]
}

/// The state (r, v) at (ρ, ρ̇) and its Jacobian over (α, δ, α̇, δ̇, ρ, ρ̇).
fn state_and_jacobian<T: Real>(
    attributable: &[T; 4],
    observer: &[T; 6],
    range: T,
    rate: T,
) -> (SVector<T, 6>, SMatrix<T, 6, 6>) {
    let [alpha, delta, alpha_dot, delta_dot] = *attributable;
    let [e, ea, ed, eaa, ead] = directions(alpha, delta);
    let q = V3::from([observer[0], observer[1], observer[2]]);
    let q_dot = V3::from([observer[3], observer[4], observer[5]]);
    let turn = ea * alpha_dot + ed * delta_dot;
    let r = q + e * range;
    let v = q_dot + e * rate + turn * range;
    let columns: [(V3<T>, V3<T>); 6] = [
        (ea * range, ea * rate + (eaa * alpha_dot + ead * delta_dot) * range),
        (ed * range, ed * rate + (ead * alpha_dot - e * delta_dot) * range),
        (V3::zeros(), ea * range),
        (V3::zeros(), ed * range),
        (e, turn),
        (V3::zeros(), e),
    ];
    let mut jacobian = SMatrix::<T, 6, 6>::zeros();
    for (j, (dr, dv)) in columns.iter().enumerate() {
        for i in 0..3 {
            jacobian[(i, j)] = dr[i];
            jacobian[(i + 3, j)] = dv[i];
        }
    }
    (SVector::from([r[0], r[1], r[2], v[0], v[1], v[2]]), jacobian)
}

/// Whether (r, v) is admissible: perigee, apogee ([`Lens`]) and inclination.
fn admissible<T: Real>(region: &AdmissibleRegion<T>, state: &SVector<T, 6>) -> bool {
    let r = V3::from([state[0], state[1], state[2]]);
    let v = V3::from([state[3], state[4], state[5]]);
    let radius = norm(&r);
    let Some(lens) = Lens::at(region, radius) else {
        return false;
    };
    let radial = v.dot(&r) / radius;
    let horizontal = norm(&(v - r * (radial / radius)));
    lens.admits(radial, horizontal) && inclination_ok(region, &r, &v)
}

/// The ranges ρ where the line of sight from `site` along `los` is between the perigee and apogee radii
/// (the far intersections; an observer inside the perigee sphere, as a ground site is).
fn range_interval<T: Real>(region: &AdmissibleRegion<T>, site: &V3<T>, los: &V3<T>) -> Option<[T; 2]> {
    let (b, s2) = (site.dot(los), site.dot(site));
    let far = |radius: T| {
        let disc = b * b - s2 + radius * radius;
        (disc > T::zero()).then(|| -b + sqrt(disc))
    };
    let low = if s2 < region.min_perigee_radius * region.min_perigee_radius {
        far(region.min_perigee_radius)?
    } else {
        T::zero()
    };
    let high = far(region.max_apogee_radius)?;
    (low > T::zero() && high > low).then_some([low, high])
}

/// The real roots of k₂ x² + k₁ x + k₀ (none, one for a linear polynomial or a double root, two in order).
fn real_roots<T: Real>(k2: T, k1: T, k0: T) -> [Option<T>; 2] {
    let scale = k2.abs().max(k1.abs()).max(k0.abs());
    if !(scale > T::zero()) {
        return [None, None];
    }
    if k2.abs() <= scale * c(1e-12) {
        return [(k1 != T::zero()).then(|| -k0 / k1), None];
    }
    let disc = k1 * k1 - c::<T>(4.0) * k2 * k0;
    if disc < T::zero() {
        return [None, None];
    }
    // The root of larger magnitude first (no cancellation), then the other from the product k₀/k₂.
    let q = -(k1 + if k1 < T::zero() { -sqrt(disc) } else { sqrt(disc) }) * c(0.5);
    let big = q / k2;
    let small = if q != T::zero() { k0 / q } else { big };
    [Some(big.min(small)), Some(big.max(small))]
}

/// The range-rates ρ̇ at range ρ whose orbit meets the perigee and apogee limits (the [`Lens`] at
/// |r|; inclination not tested): the hull of the set, `None` when it is empty. With v = w + ρ̇ ê
/// (w = q̇ + ρ (α̇ ê_α + δ̇ ê_δ)) and v_r = v · r̂ linear in ρ̇, both conditions are quadratic in ρ̇
/// (docs/maths.md §5.10): apogee (1 − A_a) v_r² + A_a |v|² ≤ B_a, an interval; perigee
/// (1 + A_p) v_r² − A_p |v|² + B_p ≤ 0, whose roots cut that interval into at most three pieces, each
/// admissible or not as a whole (tested at its midpoint).
fn lens_rate_interval<T: Real>(
    region: &AdmissibleRegion<T>,
    attributable: &[T; 4],
    observer: &[T; 6],
    range: T,
) -> Option<[T; 2]> {
    let [alpha, delta, alpha_dot, delta_dot] = *attributable;
    let [e, ea, ed, _, _] = directions(alpha, delta);
    let q = V3::from([observer[0], observer[1], observer[2]]);
    let q_dot = V3::from([observer[3], observer[4], observer[5]]);
    let r = q + e * range;
    let radius = norm(&r);
    let lens = Lens::at(region, radius)?;
    let up = r / radius;
    let w = q_dot + (ea * alpha_dot + ed * delta_dot) * range;
    let (a0, a1, b, w2) = (w.dot(&up), e.dot(&up), w.dot(&e), w.dot(&w));
    let two = c::<T>(2.0);
    let ka = T::one() - lens.aa;
    let [Some(low), Some(high)] =
        real_roots(ka * a1 * a1 + lens.aa, two * (ka * a0 * a1 + lens.aa * b), ka * a0 * a0 + lens.aa * w2 - lens.ba)
    else {
        return None;
    };
    let kp = T::one() + lens.ap;
    let cuts =
        real_roots(kp * a1 * a1 - lens.ap, two * (kp * a0 * a1 - lens.ap * b), kp * a0 * a0 - lens.ap * w2 + lens.bp);
    let mut ends = [low, high, high, high];
    for (slot, cut) in ends[1..3].iter_mut().zip(cuts) {
        *slot = cut.map_or(high, |x| x.max(low).min(high));
    }
    if ends[2] < ends[1] {
        ends.swap(1, 2);
    }
    let admits = |rate: T| {
        let v = w + e * rate;
        let radial = v.dot(&up);
        lens.admits(radial, norm(&(v - up * radial)))
    };
    let mut hull: Option<[T; 2]> = None;
    for piece in ends.windows(2) {
        let (from, to) = (piece[0], piece[1]);
        if to >= from && admits((from + to) * c(0.5)) {
            hull = Some(hull.map_or([from, to], |[a, _]| [a, to]));
        }
    }
    hull
}

/// Coarse to fine: the span of ln ρ in `[low, high]` where some range-rate is admissible, found on
/// `SCAN` × `cells[0]` ranges and `SCAN` × `cells[1]` range-rates each, widened by one scan step either
/// side (and clipped), so the `cells[0]` range cells cover the admissible region only.
fn admissible_span<T: Real>(
    region: &AdmissibleRegion<T>,
    values: &[T; 4],
    observer: &[T; 6],
    [low, high]: [T; 2],
    cells: [usize; 2],
) -> Result<[T; 2], BirthError> {
    let ranges = SCAN.saturating_mul(cells[0]);
    let rates = SCAN.saturating_mul(cells[1]);
    let step = (high - low) / real(ranges);
    let mut span: Option<[T; 2]> = None;
    for i in 0..=ranges {
        let x = low + real::<T>(i) * step;
        let Some([rate_low, rate_high]) = lens_rate_interval(region, values, observer, exp(x)) else {
            continue;
        };
        let any = (0..=rates).any(|j| {
            let rate = rate_low + (rate_high - rate_low) * real::<T>(j) / real::<T>(rates);
            admissible(region, &state_and_jacobian(values, observer, exp(x), rate).0)
        });
        if any {
            span = Some(span.map_or([x, x], |[a, b]| [a.min(x), b.max(x)]));
        }
    }
    let [a, b] = span.ok_or(BirthError::Degenerate)?;
    Ok([(a - step).max(low), (b + step).min(high)])
}

/// The birth density of a tracklet's attributable seen from `observer` (its inertial state at the
/// attributable's time): `range_cells` × `rate_cells` cells of the admissible region in (ln ρ, ρ̇).
///
/// # Errors
/// [`BirthError::InvalidRegion`] for a region that fails validation or zero cells,
/// [`BirthError::NonFinite`], [`BirthError::Degenerate`] when no cell is admissible,
/// [`BirthError::TooManyComponents`] when `out` is shorter than the admissible cells.
pub fn tracklet_births<T: Real>(
    attributable: &Attributable<T>,
    observer: &[T; 6],
    region: &AdmissibleRegion<T>,
    cells: [usize; 2],
    out: &mut [BirthComponent<T, 6>],
) -> Result<usize, BirthError> {
    region.validate().map_err(|_| BirthError::InvalidRegion)?;
    if cells[0] == 0 || cells[1] == 0 {
        return Err(BirthError::InvalidRegion);
    }
    let finite = attributable.values.iter().chain(observer.iter()).chain(attributable.covariance.iter());
    if !finite.into_iter().all(|v| v.is_finite_value()) {
        return Err(BirthError::NonFinite);
    }
    let values = attributable.values;
    let site = V3::from([observer[0], observer[1], observer[2]]);
    let los = directions(values[0], values[1])[0];
    let [low, high] = range_interval(region, &site, &los).ok_or(BirthError::Degenerate)?;
    let [ln_low, ln_high] = admissible_span(region, &values, observer, [ln(low), ln(high)], cells)?;
    let ln_width = (ln_high - ln_low) / real(cells[0]);
    let mut count = 0;
    for i in 0..cells[0] {
        // The range-rates admissible somewhere in the cell: the hull of the lens intervals at SCAN + 1 ranges.
        let hull = (0..=SCAN).fold(None, |hull: Option<[T; 2]>, k| {
            let x = ln_low + (real::<T>(i) + real::<T>(k) / real::<T>(SCAN)) * ln_width;
            match (hull, lens_rate_interval(region, &values, observer, exp(x))) {
                (Some([a, b]), Some([lo, hi])) => Some([a.min(lo), b.max(hi)]),
                (hull, None) => hull,
                (None, interval) => interval,
            }
        });
        let Some([rate_low, rate_high]) = hull else { continue };
        // Widened by a sub-sample either side, so a range-rate between the sampled ranges stays inside.
        let pad = ((rate_high - rate_low) / real::<T>(SCAN)).max(c(1e-6));
        let (rate_low, rate_high) = (rate_low - pad, rate_high + pad);
        let rate_width = (rate_high - rate_low) / real(cells[1]);
        for j in 0..cells[1] {
            let low_corner = [ln_low + real::<T>(i) * ln_width, rate_low + real::<T>(j) * rate_width];
            let admits = |x: T, y: T| admissible(region, &state_and_jacobian(&values, observer, exp(x), y).0);
            let Some(Cell { volume, mean, extent }) = cell(low_corner, [ln_width, rate_width], admits, |_, _| T::one())
            else {
                continue;
            };
            let range = exp(mean[0]);
            let (state, jacobian) = state_and_jacobian(&values, observer, range, mean[1]);
            let mut input = SMatrix::<T, 6, 6>::zeros();
            input.fixed_view_mut::<4, 4>(0, 0).copy_from(&attributable.covariance);
            let sigma_range = c::<T>(CELL_SIGMA) * extent[0] * range;
            let sigma_rate = c::<T>(CELL_SIGMA) * extent[1];
            input[(4, 4)] = sigma_range * sigma_range;
            input[(5, 5)] = sigma_rate * sigma_rate;
            let covariance = jacobian * input * jacobian.transpose();
            let covariance = (covariance + covariance.transpose()) * c::<T>(0.5);
            push(out, &mut count, volume, state, covariance)?;
        }
    }
    finish(out, count)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::model::{EARTH_MU, EARTH_RADIUS};
    use crate::sensor::EARTH_ROTATION_RATE;
    use rand_core::Rng;
    use rand_xoshiro::Xoshiro256PlusPlus;
    use rand_xoshiro::rand_core::SeedableRng;

    pub(crate) type S6 = SVector<f64, 6>;

    /// Two-body acceleration and an RK4 step of `h` seconds.
    pub(crate) fn step(x: &S6, h: f64) -> S6 {
        let f = |x: &S6| {
            let r = V3::from([x[0], x[1], x[2]]);
            let a = r * (-EARTH_MU / r.norm().powi(3));
            S6::from([x[3], x[4], x[5], a[0], a[1], a[2]])
        };
        let k1 = f(x);
        let k2 = f(&(x + k1 * (h / 2.0)));
        let k3 = f(&(x + k2 * (h / 2.0)));
        let k4 = f(&(x + k3 * h));
        x + (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (h / 6.0)
    }

    /// The state at `t` s from `x` at 0 (1 s steps, then the rest).
    pub(crate) fn propagate(x: &S6, t: f64) -> S6 {
        let mut state = *x;
        let whole = t.floor();
        for _ in 0..whole as usize {
            state = step(&state, 1.0);
        }
        if t > whole { step(&state, t - whole) } else { state }
    }

    /// A ground site's inertial state at `t` (latitude, longitude at t = 0, rad).
    pub(crate) fn site(latitude: f64, longitude: f64, t: f64) -> [f64; 6] {
        let theta = longitude + EARTH_ROTATION_RATE * t;
        let r = V3::from([latitude.cos() * theta.cos(), latitude.cos() * theta.sin(), latitude.sin()]) * EARTH_RADIUS;
        let v = V3::from([0.0, 0.0, EARTH_ROTATION_RATE]).cross(&r);
        [r[0], r[1], r[2], v[0], v[1], v[2]]
    }

    /// An orbit's state at perifocal anomaly `nu` (rad): semi-major axis, eccentricity, inclination, RAAN.
    pub(crate) fn orbit(a: f64, e: f64, inclination: f64, raan: f64, nu: f64) -> S6 {
        let p = a * (1.0 - e * e);
        let r = p / (1.0 + e * nu.cos());
        let (pos, vel) = (
            V3::from([r * nu.cos(), r * nu.sin(), 0.0]),
            V3::from([-nu.sin(), e + nu.cos(), 0.0]) * (EARTH_MU / p).sqrt(),
        );
        let rot = |v: V3<f64>| {
            let (ci, si, co, so) = (inclination.cos(), inclination.sin(), raan.cos(), raan.sin());
            let v1 = V3::from([v[0], v[1] * ci - v[2] * si, v[1] * si + v[2] * ci]);
            V3::from([v1[0] * co - v1[1] * so, v1[0] * so + v1[1] * co, v1[2]])
        };
        let (r, v) = (rot(pos), rot(vel));
        S6::from([r[0], r[1], r[2], v[0], v[1], v[2]])
    }

    /// Topocentric right ascension and declination of `x` from the site state `q`.
    pub(crate) fn angles(x: &S6, q: &[f64; 6]) -> [f64; 2] {
        let d = V3::from([x[0] - q[0], x[1] - q[1], x[2] - q[2]]);
        [d[1].atan2(d[0]), (d[2] / d.norm()).asin()]
    }

    pub(crate) fn normal(rng: &mut Xoshiro256PlusPlus) -> f64 {
        // Box–Muller from two uniforms in (0, 1].
        let u = |rng: &mut Xoshiro256PlusPlus| ((rng.next_u64() >> 11) as f64 + 1.0) / (1u64 << 53) as f64;
        let (u1, u2) = (u(rng), u(rng));
        (-2.0 * u1.ln()).sqrt() * (2.0 * core::f64::consts::PI * u2).cos()
    }

    /// The site latitude and longitude (rad) under which `x` is at its highest, for the test geometry.
    pub(crate) fn site_below(x: &S6) -> (f64, f64) {
        let r = V3::from([x[0], x[1], x[2]]);
        ((r[2] / r.norm()).asin() * 0.9, r[1].atan2(r[0]) + 0.05)
    }

    /// Every bound orbit from LEO to beyond GEO: perigee ≥ R_E + 150 km, apogee ≤ 50,000 km.
    pub(crate) fn bound() -> AdmissibleRegion<f64> {
        AdmissibleRegion::bound()
    }

    pub(crate) const SIGMA: f64 = 2.4e-5; // 5″
    pub(crate) const CELLS: [usize; 2] = [24, 4];
    pub(crate) const LIMITS: LinkLimits<f64> =
        LinkLimits { max_chi_squared: 18.5, max_rate: 0.05, max_acceleration: 1e-3, max_jerk: 2e-5 };

    /// Four noisy frames of `x0` `spacing` s apart from a site under it; the attributable, the site's
    /// state and the true state at the attributable's time.
    fn tracklet(x0: &S6, spacing: f64, seed: u64) -> (Attributable<f64>, [f64; 6], S6) {
        let (latitude, longitude) = site_below(x0);
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
        let frames: [TrackletFrame<f64>; 4] = core::array::from_fn(|k| {
            let t = spacing * k as f64;
            let [ra, dec] = angles(&propagate(x0, t), &site(latitude, longitude, t));
            TrackletFrame { time: t, angles: [ra + SIGMA * normal(&mut rng), dec + SIGMA * normal(&mut rng)] }
        });
        let attributable = Attributable::fit(&frames, [SIGMA; 2], &LIMITS).expect("linked");
        let t = attributable.time;
        (attributable, site(latitude, longitude, t), propagate(x0, t))
    }

    /// The smallest Mahalanobis distance² of `truth` to a component, and the components' count.
    pub(crate) fn nearest(attributable: &Attributable<f64>, observer: &[f64; 6], truth: &S6) -> (f64, usize) {
        let mut out = [BirthComponent::<f64, 6>::ZERO; 96];
        let n = tracklet_births(attributable, observer, &bound(), CELLS, &mut out).expect("births");
        let total: f64 = out[..n].iter().map(|c| c.weight).sum();
        assert!((total - 1.0).abs() < 1e-12);
        for component in &out[..n] {
            assert!(admissible(&bound(), &component.state.mean), "{:?}", component.state.mean);
        }
        let best = out[..n]
            .iter()
            .map(|c| {
                let d = truth - c.state.mean;
                let inverse = c.state.covariance.try_inverse().expect("invertible");
                (d.transpose() * inverse * d)[0]
            })
            .fold(f64::INFINITY, f64::min);
        (best, n)
    }

    #[test]
    fn leo_geo_and_molniya_arcs_link_and_their_mixture_covers_the_truth() {
        let cases = [
            ("LEO", orbit(EARTH_RADIUS + 600.0, 0.001, 0.9, 0.3, 1.0), 2.0),
            ("GEO", orbit(42_164.0, 0.0002, 0.01, 1.2, 0.4), 30.0),
            ("Molniya near perigee", orbit(26_600.0, 0.72, 1.1, 2.0, 0.3), 2.0),
            ("Molniya near apogee", orbit(26_600.0, 0.72, 1.1, 2.0, 3.0), 30.0),
            ("GTO", orbit(24_400.0, 0.73, 0.1, 0.5, 2.5), 30.0),
        ];
        // 10 noise draws per orbit: the truth within χ²₆ 99.9 % (22.5) of a component in at least 9.
        for (name, x0, spacing) in &cases {
            let mut covered = 0;
            for seed in 0..10 {
                let (attributable, observer, truth) = tracklet(x0, *spacing, seed);
                let (distance, n) = nearest(&attributable, &observer, &truth);
                assert!(n <= CELLS[0] * CELLS[1]);
                covered += usize::from(distance < 22.5);
            }
            assert!(covered >= 9, "{name}: covered {covered} of 10");
        }
    }

    #[test]
    fn the_lens_interval_in_closed_form_is_the_hull_of_the_sampled_admissible_range_rates() {
        // LEO to GEO arcs, the bound and the GEO belt's regions, ranges along each line of sight: every
        // sampled range-rate the lens admits lies in the closed-form interval, and its ends are admitted
        // range-rates (to a millimetre per second).
        let cases = [
            (orbit(EARTH_RADIUS + 600.0, 0.001, 0.9, 0.3, 1.0), 2.0, bound()),
            (orbit(42_164.0, 0.0002, 0.01, 1.2, 0.4), 30.0, bound()),
            (orbit(42_164.0, 0.0002, 0.01, 1.2, 0.4), 90.0, AdmissibleRegion::geo()),
            (orbit(26_600.0, 0.72, 1.1, 2.0, 3.0), 30.0, bound()),
        ];
        let lens_admits = |region: &AdmissibleRegion<f64>, a: &Attributable<f64>, q: &[f64; 6], range, rate| {
            let state = state_and_jacobian(&a.values, q, range, rate).0;
            let (r, v) = (V3::from([state[0], state[1], state[2]]), V3::from([state[3], state[4], state[5]]));
            let radial = v.dot(&r) / r.norm();
            Lens::at(region, r.norm()).is_some_and(|lens| lens.admits(radial, (v - r * (radial / r.norm())).norm()))
        };
        let mut admitted = 0;
        for (x0, spacing, region) in &cases {
            let (a, q, truth) = tracklet(x0, *spacing, 3);
            let true_range = (V3::from([truth[0] - q[0], truth[1] - q[1], truth[2] - q[2]])).norm();
            for k in 0..41 {
                let range = true_range * (0.9 + 0.005 * k as f64);
                let interval = lens_rate_interval(region, &a.values, &q, range);
                for j in 0..=4000 {
                    let rate = -8.0 + 16.0 * j as f64 / 4000.0;
                    if lens_admits(region, &a, &q, range, rate) {
                        admitted += 1;
                        let [low, high] = interval.expect("an admitted range-rate, an interval");
                        assert!(rate >= low - 1e-9 && rate <= high + 1e-9, "{rate} outside [{low}, {high}]");
                    }
                }
                if let Some([low, high]) = interval {
                    assert!(low <= high);
                    for end in [low + 1e-6, high - 1e-6].map(|x| x.clamp(low, high)) {
                        let near = [end - 1e-6, end, end + 1e-6];
                        assert!(near.iter().any(|&x| lens_admits(region, &a, &q, range, x)), "{end} not admitted");
                    }
                }
            }
        }
        assert!(admitted > 1000, "{admitted}");
    }

    #[test]
    fn a_geo_arc_in_the_geo_belts_region_gives_a_mixture_that_covers_the_truth() {
        // Four frames 90 s apart of a GEO object (the optical-geo cadence), the GEO belt's region (its
        // admissible range-rates are metres per second wide): the truth within χ²₆ 99.9 % of a component in
        // at least 9 of 10 noise draws.
        let x0 = orbit(42_164.0, 0.0002, 0.01, 1.2, 0.4);
        let region = AdmissibleRegion::geo();
        let mut covered = 0;
        for seed in 0..10 {
            let (a, q, truth) = tracklet(&x0, 90.0, seed);
            let mut out = [BirthComponent::<f64, 6>::ZERO; 96];
            let n = tracklet_births(&a, &q, &region, CELLS, &mut out).expect("a GEO arc has admissible cells");
            let best = out[..n]
                .iter()
                .map(|c| {
                    assert!(admissible(&region, &c.state.mean));
                    let d = truth - c.state.mean;
                    (d.transpose() * c.state.covariance.try_inverse().expect("invertible") * d)[0]
                })
                .fold(f64::INFINITY, f64::min);
            covered += usize::from(best < 22.5);
        }
        assert!(covered >= 9, "covered {covered} of 10");
    }

    /// The fraction of 10,000 random triples uniform in a square field that link.
    fn three_frame_links(field_deg: f64, spacing: f64) -> f64 {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(7);
        let field = field_deg.to_radians();
        let mut uniform = || rng.next_u64() as f64 / u64::MAX as f64;
        let linked = (0..10_000)
            .filter(|_| {
                let frames: [TrackletFrame<f64>; 3] = core::array::from_fn(|k| TrackletFrame {
                    time: spacing * k as f64,
                    angles: [1.0 + field * uniform(), 0.2 + field * uniform()],
                });
                Attributable::fit(&frames, [SIGMA; 2], &LIMITS).is_ok()
            })
            .count();
        linked as f64 / 1e4
    }

    #[test]
    fn three_frame_links_in_clutter_depend_on_the_rate_and_acceleration_bounds_only() {
        // Three frames fit exactly: with LEO bounds slow clutter links (docs/maths.md §5.10).
        assert!(three_frame_links(2.0, 10.0) > 0.99);
        assert!(three_frame_links(5.0, 1.0) < 0.001);
    }

    #[test]
    fn random_triples_of_clutter_do_not_link() {
        // Clutter uniform in a 2° × 2° field, four frames: a quadratic through four random points misses
        // the fourth by far more than 5″, so none of 10,000 quadruples links.
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(7);
        let field = 2.0_f64.to_radians();
        let mut linked = 0;
        for _ in 0..10_000 {
            let frames: [TrackletFrame<f64>; 4] = core::array::from_fn(|k| TrackletFrame {
                time: 10.0 * k as f64,
                angles: [
                    1.0 + field * (rng.next_u64() as f64 / u64::MAX as f64),
                    0.2 + field * (rng.next_u64() as f64 / u64::MAX as f64),
                ],
            });
            linked += usize::from(Attributable::fit(&frames, [SIGMA; 2], &LIMITS).is_ok());
        }
        assert_eq!(linked, 0);
    }

    #[test]
    fn the_fit_ignores_frame_order_and_the_zero_meridian() {
        let frames = [0.0, 10.0, 20.0].map(|t| TrackletFrame { time: t, angles: [-0.001 + 1e-4 * t, 0.3 - 2e-5 * t] });
        let wrapped = frames
            .map(|f| TrackletFrame { angles: [f.angles[0].rem_euclid(2.0 * core::f64::consts::PI), f.angles[1]], ..f });
        let shuffled = [wrapped[2], wrapped[0], wrapped[1]];
        let a = Attributable::fit(&frames, [SIGMA; 2], &LIMITS).expect("linked");
        let b = Attributable::fit(&shuffled, [SIGMA; 2], &LIMITS).expect("linked");
        assert!((a.values[2] - 1e-4).abs() < 1e-12 && (a.values[3] + 2e-5).abs() < 1e-12);
        assert!((a.values[2] - b.values[2]).abs() < 1e-12);
        assert!(angle_difference(a.values[0], b.values[0]).abs() < 1e-12);
    }

    #[test]
    fn bad_frames_are_refused() {
        let frame = |t: f64| TrackletFrame { time: t, angles: [0.1, 0.2] };
        let fit = |frames: &[TrackletFrame<f64>]| Attributable::fit(frames, [SIGMA; 2], &LIMITS);
        assert_eq!(fit(&[frame(0.0), frame(1.0)]), Err(TrackletError::Frames));
        assert_eq!(fit(&[frame(0.0), frame(1.0), frame(1.0)]), Err(TrackletError::Frames));
        assert_eq!(fit(&[frame(0.0), frame(1.0), frame(f64::NAN)]), Err(TrackletError::NonFinite));
        let fast = [0.0, 1.0, 2.0].map(|t| TrackletFrame { time: t, angles: [0.1 * t, 0.2] });
        assert_eq!(fit(&fast), Err(TrackletError::NotLinked));
        let bent = [0.0, 1.0, 2.0].map(|t| TrackletFrame { time: t, angles: [0.1 + 0.01 * t * t, 0.2] });
        assert_eq!(fit(&bent), Err(TrackletError::NotLinked));
        let (a, observer, _) = tracklet(&orbit(42_164.0, 0.0002, 0.01, 1.2, 0.4), 30.0, 1);
        let mut out = [BirthComponent::<f64, 6>::ZERO; 4];
        assert_eq!(tracklet_births(&a, &observer, &bound(), [0, 4], &mut out), Err(BirthError::InvalidRegion));
        assert_eq!(tracklet_births(&a, &observer, &bound(), CELLS, &mut out), Err(BirthError::TooManyComponents));
    }
}
