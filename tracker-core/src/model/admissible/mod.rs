//! Birth densities from one measurement: the admissible region of a new object's state, discretised
//! into a fixed-size weighted Gaussian mixture (docs/maths.md §5.7).
//!
//! One measurement leaves some of a new object's state unobserved: the velocity (radar), the velocity
//! across the line of sight (radar with range-rate), the range and the velocity (optical). The
//! unobserved part is restricted to an *admissible region* ([`AdmissibleRegion`]): bound orbits whose
//! perigee is at least `min_perigee_radius` and whose apogee is at most `max_apogee_radius`, with an
//! inclination of at most `max_inclination`, and (optical) a geocentric radius in the `shell` band.
//! The region is cut into cells; each cell with an admissible part gives one [`BirthComponent`]: weight
//! ∝ the admissible volume of the cell (a uniform density over the region), mean at an admissible point
//! near the cell's admissible centroid, covariance σ = half the cell's width along each cell axis plus
//! the measurement noise carried through the geometry (J R Jᵀ), with its position-velocity blocks.
//!
//! - Radar (range, azimuth, elevation): position r = r_s + ρ û; velocity in the local horizontal frame
//!   at r: `headings` × `speeds` × `climbs` cells of heading ψ, horizontal speed v_t and radial speed v_r.
//! - Radar with range-rate: v · û = ρ̇ + v_s · û is fixed; the velocity across the line of sight is
//!   gridded `headings` × `speeds` in the plane perpendicular to û.
//! - Optical (right ascension, declination): the line of sight meets `ranges` shells of radii across the
//!   `shell` band (twice for an observer outside a shell); at each, the velocity cells of the radar.
//!   This is the one-measurement admissible region, not a short-arc initiation, because the birth pool
//!   makes its cells from single measurements; for the GEO belt ([`AdmissibleRegion::geo`]) the headings
//!   are limited to the prograde arc of inclination ≤ `max_inclination` (15°), not weighted.
//!
//! A measurement without an admissible state (a radius outside the perigee/apogee limits, a line of sight
//! that misses the shell, a range-rate too large for a bound orbit, a latitude above the largest
//! inclination) is [`BirthError::Degenerate`]: nothing is written and the caller keeps the measurement.

pub mod tracklet;

use super::{EARTH_MU, EARTH_RADIUS};
use crate::gaussian::Gaussian;
use crate::real::{Real, atan2, c, cos, sin, sqrt};
use nalgebra::{SMatrix, SVector};

type V3<T> = SVector<T, 3>;

/// The largest [`AdmissibleRegion::max_components`] a region may have (checked by
/// [`AdmissibleRegion::validate`]).
pub const MAX_BIRTH_COMPONENTS: usize = 1024;
/// The radius of the geostationary orbit (km): (μ / ω²)^(1/3) with ω one turn per sidereal day.
pub const GEO_RADIUS: f64 = 42_164.0;
/// Sub-samples per cell axis for a cell's admissible volume and centroid.
const SUBSAMPLES: usize = 4;
/// A cell's σ along each of its axes, as a fraction of the cell's width.
const CELL_SIGMA: f64 = 0.5;

/// One weighted Gaussian of a birth density; the weights of one measurement's components sum to 1.
///
/// # Examples
/// The birth density of a radar measurement 900 km away at 40° elevation, for a LEO object.
/// ```
/// use nalgebra::SVector;
/// use tracker_core::model::{AdmissibleRegion, BirthComponent, BirthGeometry, MAX_BIRTH_COMPONENTS, RadarRangeAzEl};
/// use tracker_core::sensor::{EarthRotation, GroundSite};
/// let site = GroundSite { latitude: 0.7_f64, longitude: -1.8, height: 1.6 };
/// let radar = RadarRangeAzEl::at_site(&site, &EarthRotation::new(0.3), 120.0, [0.02, 1e-3, 1e-3]);
/// let region = AdmissibleRegion::leo();
/// let mut out = [BirthComponent::ZERO; MAX_BIRTH_COMPONENTS];
/// let n = radar.birth_components(&SVector::from([900.0, 1.0, 0.7]), &region, &mut out)?;
/// assert!(n > 0 && n <= region.max_components());
/// let total: f64 = out[..n].iter().map(|component| component.weight).sum();
/// assert!((total - 1.0).abs() < 1e-12);
/// // Every component is centred on the measured position.
/// assert!(out[..n].windows(2).all(|pair| pair[0].state.mean.fixed_rows::<3>(0) == pair[1].state.mean.fixed_rows::<3>(0)));
/// # Ok::<(), tracker_core::model::BirthError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BirthComponent<T: Real, const S: usize> {
    /// The component's weight.
    pub weight: T,
    /// The component's state density.
    pub state: Gaussian<T, S>,
}

impl<T: Real, const S: usize> BirthComponent<T, S> {
    /// Zero weight, zero mean and covariance (a placeholder in fixed storage).
    pub const ZERO: Self = Self { weight: T::ZERO, state: Gaussian::ZERO };
}

impl<T: Real, const S: usize> Default for BirthComponent<T, S> {
    fn default() -> Self {
        Self::ZERO
    }
}

/// Why a measurement gave no birth density.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum BirthError {
    /// The measurement model has no birth geometry.
    Unsupported,
    /// The region fails [`AdmissibleRegion::validate`].
    InvalidRegion,
    /// No admissible state: the radius is outside the perigee/apogee limits, the line of sight misses
    /// the shell, the range-rate is too large for a bound orbit, or the latitude is above the largest
    /// inclination.
    Degenerate,
    /// The measurement, the observer or a result has a NaN or an infinity.
    NonFinite,
    /// The output slice is shorter than the number of components.
    TooManyComponents,
}

impl core::fmt::Display for BirthError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            BirthError::Unsupported => f.write_str("measurement model has no birth geometry"),
            BirthError::InvalidRegion => f.write_str("invalid admissible region"),
            BirthError::Degenerate => f.write_str("measurement has no admissible state (empty admissible region)"),
            BirthError::NonFinite => f.write_str("non-finite measurement, observer or birth density"),
            BirthError::TooManyComponents => f.write_str("more birth components than the output slice holds"),
        }
    }
}

impl core::error::Error for BirthError {}

/// The admissible region of a new object and its discretisation (docs/maths.md §5.7).
///
/// # Examples
/// ```
/// use tracker_core::model::AdmissibleRegion;
/// let leo = AdmissibleRegion::<f64>::leo();
/// assert!(leo.validate().is_ok());
/// assert_eq!(leo.max_components(), 768);
/// let bad = AdmissibleRegion { min_perigee_radius: 9000.0, ..leo };
/// assert!(bad.validate().is_err()); // perigee limit above the apogee limit
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct AdmissibleRegion<T> {
    /// Gravitational parameter μ (km³/s²).
    pub mu: T,
    /// Smallest perigee radius (km): above the atmosphere.
    pub min_perigee_radius: T,
    /// Largest apogee radius (km).
    pub max_apogee_radius: T,
    /// Largest inclination (rad, in (0, π]; π admits every orbit plane).
    pub max_inclination: T,
    /// Optical: the band of geocentric radii (km) the line of sight is intersected with, inside
    /// [`min_perigee_radius`, `max_apogee_radius`].
    pub shell: [T; 2],
    /// Cells of heading in the local horizontal plane (radar with range-rate: across the line of sight).
    pub headings: usize,
    /// Cells of horizontal speed (radar with range-rate: along the plane's radial axis).
    pub speeds: usize,
    /// Cells of radial speed (not used with range-rate).
    pub climbs: usize,
    /// Optical: cells of radius across `shell`.
    pub ranges: usize,
    /// Planar position models: the standard deviation of each velocity component (mean 0).
    pub velocity_sigma: T,
}

impl<T: Real> AdmissibleRegion<T> {
    /// Low Earth orbit: perigee ≥ R_E + 200 km, apogee ≤ R_E + 2000 km, any inclination; optical shell
    /// R_E + 200 … R_E + 2000 km; 8 headings, 4 speeds, 3 climbs, 4 ranges.
    pub fn leo() -> Self {
        let (low, high) = (c(EARTH_RADIUS + 200.0), c(EARTH_RADIUS + 2000.0));
        Self {
            mu: c(EARTH_MU),
            min_perigee_radius: low,
            max_apogee_radius: high,
            max_inclination: T::pi(),
            shell: [low, high],
            headings: 8,
            speeds: 4,
            climbs: 3,
            ranges: 4,
            velocity_sigma: T::one(),
        }
    }

    /// The GEO belt: perigee ≥ 42164 − 300 km, apogee ≤ 42164 + 300 km (eccentricity ≲ 0.007),
    /// inclination ≤ 15°, shell 42164 ± 200 km; 6 headings, 3 speeds, 3 climbs, 4 ranges.
    pub fn geo() -> Self {
        Self {
            mu: c(EARTH_MU),
            min_perigee_radius: c(GEO_RADIUS - 300.0),
            max_apogee_radius: c(GEO_RADIUS + 300.0),
            max_inclination: c(15.0_f64.to_radians()),
            shell: [c(GEO_RADIUS - 200.0), c(GEO_RADIUS + 200.0)],
            headings: 6,
            speeds: 3,
            climbs: 3,
            ranges: 4,
            velocity_sigma: T::one(),
        }
    }

    /// Geosynchronous orbits, near-circular: perigee ≥ 42164 − 25 km, apogee ≤ 42164 + 25 km (so
    /// |a − 42164| ≤ 25 km and e ≤ 5.9·10⁻⁴), inclination ≤ 15°, shell the same ±25 km; the cells of
    /// [`AdmissibleRegion::geo`]. A station-kept satellite (longitude drift ≲ 0.05°/day: |Δa| ≲ 4 km;
    /// e ≲ 5·10⁻⁴) and one whose inclination is no longer controlled are inside; a drifting object
    /// (|Δa| of tens of km and more) is not: its births need [`AdmissibleRegion::geo`] (docs/maths.md §5.7).
    pub fn geosynchronous() -> Self {
        let (low, high) = (c(GEO_RADIUS - 25.0), c(GEO_RADIUS + 25.0));
        Self { min_perigee_radius: low, max_apogee_radius: high, shell: [low, high], ..Self::geo() }
    }

    /// Every bound orbit from LEO to beyond GEO, GTO and Molniya included: perigee ≥ R_E + 150 km, apogee
    /// ≤ 50,000 km, any inclination; single-frame cells as [`AdmissibleRegion::leo`], shell the whole band.
    /// The region of tracklet births (docs/maths.md §5.10).
    pub fn bound() -> Self {
        let (low, high) = (c(EARTH_RADIUS + 150.0), c(50_000.0));
        Self { min_perigee_radius: low, max_apogee_radius: high, shell: [low, high], ..Self::leo() }
    }

    /// For planar position models: velocity N(0, `velocity_sigma`² I) (the orbital fields are those of
    /// [`AdmissibleRegion::leo`]).
    pub fn planar(velocity_sigma: T) -> Self {
        Self { velocity_sigma, ..Self::leo() }
    }

    /// The most components one measurement can give: 2 · ranges · headings · speeds · climbs (saturating).
    pub fn max_components(&self) -> usize {
        [self.ranges, self.headings, self.speeds, self.climbs].iter().fold(2_usize, |n, &k| n.saturating_mul(k))
    }

    /// Checks the region.
    ///
    /// # Errors
    /// A static description of the first invalid field.
    pub fn validate(&self) -> Result<(), &'static str> {
        let positive = |x: T| x.is_finite_value() && x > T::zero();
        if !positive(self.mu) {
            return Err("admissible region: mu must be finite and > 0");
        }
        if !(positive(self.min_perigee_radius)
            && self.max_apogee_radius.is_finite_value()
            && self.max_apogee_radius > self.min_perigee_radius)
        {
            return Err("admissible region: need 0 < min_perigee_radius < max_apogee_radius, finite");
        }
        if !(positive(self.max_inclination) && self.max_inclination <= T::pi()) {
            return Err("admissible region: max_inclination must be in (0, pi]");
        }
        let [low, high] = self.shell;
        if !(low.is_finite_value() && high.is_finite_value() && low < high)
            || low < self.min_perigee_radius
            || high > self.max_apogee_radius
        {
            return Err("admissible region: shell must be [low, high], low < high, inside the perigee/apogee limits");
        }
        if self.headings == 0 || self.speeds == 0 || self.climbs == 0 || self.ranges == 0 {
            return Err("admissible region: every cell count must be >= 1");
        }
        if self.max_components() > MAX_BIRTH_COMPONENTS {
            return Err("admissible region: 2 * ranges * headings * speeds * climbs exceeds MAX_BIRTH_COMPONENTS");
        }
        if !positive(self.velocity_sigma) {
            return Err("admissible region: velocity_sigma must be finite and > 0");
        }
        Ok(())
    }
}

/// The admissible (radial, horizontal) speeds at one radius r (docs/maths.md §5.7): v_r² ≤ A_p v_t² − B_p
/// (perigee ≥ R_p) and v_r² ≤ B_a − A_a v_t² (apogee ≤ R_a), a convex lens in (v_t, v_r).
struct Lens<T> {
    ap: T,
    bp: T,
    aa: T,
    ba: T,
    /// Horizontal speeds [v_t,min, v_t,max].
    vt: [T; 2],
    /// The largest |v_r|.
    vr: T,
}

impl<T: Real> Lens<T> {
    /// The lens at radius `r`; `None` unless R_p < r < R_a.
    fn at(region: &AdmissibleRegion<T>, r: T) -> Option<Self> {
        let (rp, ra) = (region.min_perigee_radius, region.max_apogee_radius);
        if !(r > rp && r < ra) {
            return None;
        }
        let two_mu = c::<T>(2.0) * region.mu;
        let ap = (r - rp) * (r + rp) / (rp * rp);
        let bp = two_mu * (r - rp) / (rp * r);
        let aa = (ra - r) * (ra + r) / (ra * ra);
        let ba = two_mu * (ra - r) / (ra * r);
        let vt = [sqrt(two_mu * rp / (r * (r + rp))), sqrt(two_mu * ra / (r * (r + ra)))];
        let vt_star2 = (ba + bp) / (aa + ap);
        let vr2 = ba - aa * vt_star2;
        let vr = if vr2 > T::zero() { sqrt(vr2) } else { T::zero() };
        Some(Self { ap, bp, aa, ba, vt, vr })
    }

    fn admits(&self, vr: T, vt: T) -> bool {
        let (vr2, vt2) = (vr * vr, vt * vt);
        vt >= T::zero() && vr2 <= self.ap * vt2 - self.bp && vr2 <= self.ba - self.aa * vt2
    }
}

/// One column g of a covariance Σ σ² g gᵀ: a position change `dr`, a rotation `omega` of the velocity
/// frame (δv = ω × v) and a change `dc` of the velocity along the line of sight û (δv += dc û).
#[derive(Clone, Copy)]
struct Column<T: Real> {
    dr: V3<T>,
    omega: V3<T>,
    dc: T,
    sigma: T,
}

impl<T: Real> Column<T> {
    fn add_to(&self, covariance: &mut SMatrix<T, 6, 6>, velocity: &V3<T>, los: &V3<T>) {
        let dv = self.omega.cross(velocity) + los * self.dc;
        let g = SVector::<T, 6>::from([self.dr[0], self.dr[1], self.dr[2], dv[0], dv[1], dv[2]]);
        *covariance += g * g.transpose() * (self.sigma * self.sigma);
    }
}

/// Adds σ² g gᵀ for a velocity-only column g = (0, dv).
fn add_velocity<T: Real>(covariance: &mut SMatrix<T, 6, 6>, dv: V3<T>, sigma: T) {
    let z = T::zero();
    let g = SVector::<T, 6>::from([z, z, z, dv[0], dv[1], dv[2]]);
    *covariance += g * g.transpose() * (sigma * sigma);
}

fn norm<T: Real>(v: &V3<T>) -> T {
    sqrt(v.dot(v))
}

/// arccos x for x ∈ [−1, 1].
fn acos<T: Real>(x: T) -> T {
    atan2(sqrt((T::one() - x * x).max(T::zero())), x)
}

/// The index `i` as a real.
fn real<T: Real>(i: usize) -> T {
    T::of_f64(i as f64)
}

/// The rotation of the geocentric horizontal frame for a position change `dr`: ω = r̂ × δr / r (its twist
/// about r̂ neglected, docs/maths.md §5.7).
fn geocentric_omega<T: Real>(position: &V3<T>, dr: &V3<T>) -> V3<T> {
    let r2 = position.dot(position);
    position.cross(dr) / r2
}

/// r̂, East ê = ẑ × r̂ / |ẑ × r̂| (ŷ on the pole), North n̂ = r̂ × ê, and cos φ = |ẑ × r̂|.
fn horizontal<T: Real>(position: &V3<T>, r: T) -> (V3<T>, V3<T>, V3<T>, T) {
    let up = position / r;
    let east_raw = V3::from([-up[1], up[0], T::zero()]);
    let cos_lat = norm(&east_raw);
    let east = if cos_lat > c(1e-6) { east_raw / cos_lat } else { V3::from([T::zero(), T::one(), T::zero()]) };
    let north = up.cross(&east);
    (up, east, north, cos_lat)
}

/// The half-width ψ_m of the headings (from East towards North) with inclination ≤ i_max:
/// cos i = cos ψ cos φ ≥ cos i_max. `None` when no heading qualifies.
fn heading_half_width<T: Real>(region: &AdmissibleRegion<T>, cos_lat: T) -> Option<T> {
    let ci = cos(region.max_inclination);
    if ci <= -cos_lat {
        return Some(T::pi());
    }
    if !(cos_lat > ci) {
        return None;
    }
    Some(acos(ci / cos_lat))
}

/// Writes `component` into the next slot.
fn push<T: Real>(
    out: &mut [BirthComponent<T, 6>],
    count: &mut usize,
    weight: T,
    mean: SVector<T, 6>,
    covariance: SMatrix<T, 6, 6>,
) -> Result<(), BirthError> {
    let slot = out.get_mut(*count).ok_or(BirthError::TooManyComponents)?;
    *slot = BirthComponent { weight, state: Gaussian { mean, covariance } };
    *count += 1;
    Ok(())
}

fn state<T: Real>(position: &V3<T>, velocity: &V3<T>) -> SVector<T, 6> {
    SVector::from([position[0], position[1], position[2], velocity[0], velocity[1], velocity[2]])
}

/// The admissible part of one cell of a 2-D grid.
struct Cell<T> {
    /// Admissible volume (∫ density over the admissible part).
    volume: T,
    /// An admissible point near the centroid.
    mean: [T; 2],
    /// The admissible part's extent along each axis (at most the cell's width).
    extent: [T; 2],
}

/// `admits(x, y)` on SUBSAMPLES² midpoints of the cell `low + [0, width]`, each weighted by `density(x, y)`:
/// the admissible volume, the weighted centroid when it is admissible (else the admissible sub-sample
/// nearest to it, in cell widths) and the admissible extent (the sub-samples' span plus one spacing).
fn cell<T: Real>(
    low: [T; 2],
    width: [T; 2],
    admits: impl Fn(T, T) -> bool,
    density: impl Fn(T, T) -> T,
) -> Option<Cell<T>> {
    let q = real::<T>(SUBSAMPLES);
    let half = c::<T>(0.5);
    let at = |i: usize, axis: usize| low[axis] + (real::<T>(i) + half) * width[axis] / q;
    let (mut total, mut sx, mut sy) = (T::zero(), T::zero(), T::zero());
    let (mut first, mut last) = ([SUBSAMPLES; 2], [0; 2]);
    for i in 0..SUBSAMPLES {
        for j in 0..SUBSAMPLES {
            let (x, y) = (at(i, 0), at(j, 1));
            if admits(x, y) {
                let w = density(x, y);
                total += w;
                sx += w * x;
                sy += w * y;
                first = [first[0].min(i), first[1].min(j)];
                last = [last[0].max(i), last[1].max(j)];
            }
        }
    }
    if !(total > T::zero()) {
        return None;
    }
    let volume = total * width[0] * width[1] / (q * q);
    let extent = [0, 1].map(|axis| (real::<T>(last[axis].saturating_sub(first[axis])) + T::one()) * width[axis] / q);
    let (mx, my) = (sx / total, sy / total);
    if admits(mx, my) {
        return Some(Cell { volume, mean: [mx, my], extent });
    }
    let mut best: Option<(T, T, T)> = None;
    for i in 0..SUBSAMPLES {
        for j in 0..SUBSAMPLES {
            let (x, y) = (at(i, 0), at(j, 1));
            if admits(x, y) {
                let (dx, dy) = ((x - mx) / width[0], (y - my) / width[1]);
                let d = dx * dx + dy * dy;
                if best.is_none_or(|(b, _, _)| d < b) {
                    best = Some((d, x, y));
                }
            }
        }
    }
    best.map(|(_, x, y)| Cell { volume, mean: [x, y], extent })
}

/// The components of an unobserved velocity at `position` (radar without range-rate, optical): cells of
/// heading × horizontal speed × radial speed in the local horizontal frame, each weighted by its admissible
/// velocity volume times `scale`. `columns` carry the position noise (their ω is set here).
fn geocentric_cells<T: Real>(
    region: &AdmissibleRegion<T>,
    position: &V3<T>,
    columns: &[Column<T>],
    scale: T,
    out: &mut [BirthComponent<T, 6>],
    count: &mut usize,
) -> Result<(), BirthError> {
    let r = norm(position);
    let Some(lens) = Lens::at(region, r) else {
        return Ok(());
    };
    let (up, east, north, cos_lat) = horizontal(position, r);
    let Some(psi_m) = heading_half_width(region, cos_lat) else {
        return Ok(());
    };
    let (headings, speeds, climbs) = (region.headings, region.speeds, region.climbs);
    let dpsi = c::<T>(2.0) * psi_m / real(headings);
    let dvt = (lens.vt[1] - lens.vt[0]) / real(speeds);
    let dvr = c::<T>(2.0) * lens.vr / real(climbs);
    let sigma_psi = c::<T>(CELL_SIGMA) * dpsi;
    for iv in 0..speeds {
        for ir in 0..climbs {
            let low = [lens.vt[0] + real::<T>(iv) * dvt, -lens.vr + real::<T>(ir) * dvr];
            // Volume element v_t dv_t dv_r dψ of the velocity in cylindrical coordinates.
            let Some(part) = cell(low, [dvt, dvr], |x, y| lens.admits(y, x), |x, _| x) else {
                continue;
            };
            let ([vt, vr], volume) = (part.mean, part.volume);
            let [sigma_vt, sigma_vr] = part.extent.map(|e| c::<T>(CELL_SIGMA) * e);
            for j in 0..headings {
                let psi = -psi_m + (real::<T>(j) + c(0.5)) * dpsi;
                let (cp, sp) = (cos(psi), sin(psi));
                let heading = east * cp + north * sp;
                let turn = north * cp - east * sp;
                let velocity = heading * vt + up * vr;
                let mut covariance = SMatrix::<T, 6, 6>::zeros();
                for column in columns {
                    let column = Column { omega: geocentric_omega(position, &column.dr), ..*column };
                    column.add_to(&mut covariance, &velocity, &up);
                }
                add_velocity(&mut covariance, turn * vt, sigma_psi);
                add_velocity(&mut covariance, heading, sigma_vt);
                // The cell is an arc: its points lie up to v_t (1 − cos(Δψ/2)) inside the heading's chord.
                add_velocity(&mut covariance, heading, vt * (T::one() - cos(c::<T>(0.5) * dpsi)));
                add_velocity(&mut covariance, up, sigma_vr);
                push(out, count, volume * dpsi * scale, state(position, &velocity), covariance)?;
            }
        }
    }
    Ok(())
}

/// A unit vector perpendicular to `u`.
fn perpendicular<T: Real>(u: &V3<T>) -> V3<T> {
    let (ax, ay, az) = (u[0].abs(), u[1].abs(), u[2].abs());
    let axis = if ax <= ay && ax <= az {
        V3::from([T::one(), T::zero(), T::zero()])
    } else if ay <= az {
        V3::from([T::zero(), T::one(), T::zero()])
    } else {
        V3::from([T::zero(), T::zero(), T::one()])
    };
    let p = u.cross(&axis);
    p / norm(&p)
}

/// Whether the orbit through `position` with `velocity` has inclination ≤ i_max.
fn inclination_ok<T: Real>(region: &AdmissibleRegion<T>, position: &V3<T>, velocity: &V3<T>) -> bool {
    let h = position.cross(velocity);
    h[2] >= norm(&h) * cos(region.max_inclination)
}

/// The components of a velocity whose component along the line of sight `los` is `along` (radar with
/// range-rate): a `speeds` × `headings` grid of (a, b) in the plane v = along û + a p̂ + b q̂, p̂ the
/// direction of r̂ across û, q̂ = û × p̂ (horizontal), bounded by the apogee ellipsoid.
#[allow(clippy::too_many_arguments)]
fn plane_cells<T: Real>(
    region: &AdmissibleRegion<T>,
    position: &V3<T>,
    los: &V3<T>,
    along: T,
    columns: &[Column<T>],
    out: &mut [BirthComponent<T, 6>],
    count: &mut usize,
) -> Result<(), BirthError> {
    let r = norm(position);
    let Some(lens) = Lens::at(region, r) else {
        return Ok(());
    };
    let up = position / r;
    let ur = los.dot(&up);
    let across = up - los * ur;
    let p = if norm(&across) > c(1e-6) { across / norm(&across) } else { perpendicular(los) };
    let q = los.cross(&p);
    let pr = p.dot(&up);
    // Apogee ellipsoid at b = 0: α a² + β a + γ ≤ 0; its largest |b|² is (β²/4α − γ) / A_a.
    let one = T::one();
    let alpha = (one - lens.aa) * pr * pr + lens.aa;
    let beta = c::<T>(2.0) * (one - lens.aa) * along * ur * pr;
    let gamma = (one - lens.aa) * along * along * ur * ur + lens.aa * along * along - lens.ba;
    let disc = beta * beta - c::<T>(4.0) * alpha * gamma;
    if !(disc > T::zero() && alpha > T::zero() && lens.aa > T::zero()) {
        return Ok(());
    }
    let root = sqrt(disc);
    let a_low = (-beta - root) / (c::<T>(2.0) * alpha);
    let a_width = root / alpha / real(region.speeds);
    let b_max = sqrt(disc / (c::<T>(4.0) * alpha * lens.aa));
    let b_width = c::<T>(2.0) * b_max / real(region.headings);
    let velocity_at = |a: T, b: T| los * along + p * a + q * b;
    let admits = |a: T, b: T| {
        let v = velocity_at(a, b);
        let vr = v.dot(&up);
        let vt2 = v.dot(&v) - vr * vr;
        let vt = if vt2 > T::zero() { sqrt(vt2) } else { T::zero() };
        lens.admits(vr, vt) && inclination_ok(region, position, &v)
    };
    for ia in 0..region.speeds {
        for ib in 0..region.headings {
            let low = [a_low + real::<T>(ia) * a_width, -b_max + real::<T>(ib) * b_width];
            let Some(part) = cell(low, [a_width, b_width], admits, |_, _| one) else {
                continue;
            };
            let ([a, b], volume) = (part.mean, part.volume);
            let [sigma_a, sigma_b] = part.extent.map(|e| c::<T>(CELL_SIGMA) * e);
            let velocity = velocity_at(a, b);
            let mut covariance = SMatrix::<T, 6, 6>::zeros();
            for column in columns {
                column.add_to(&mut covariance, &velocity, los);
                // The truth's offset ξ from the mean across the cell turns with the angle too: v · û moves by
                // −ξ · ∂û δθ, a product of independent terms, as large as the range-rate noise or larger.
                let turn = column.omega.cross(los);
                for (axis, sigma) in [(&p, sigma_a), (&q, sigma_b)] {
                    add_velocity(&mut covariance, *los * axis.dot(&turn), column.sigma * sigma);
                }
            }
            add_velocity(&mut covariance, p, sigma_a);
            add_velocity(&mut covariance, q, sigma_b);
            push(out, count, volume, state(position, &velocity), covariance)?;
        }
    }
    Ok(())
}

/// Normalises the weights of `out[..count]` and checks that everything is finite.
fn finish<T: Real, const S: usize>(out: &mut [BirthComponent<T, S>], count: usize) -> Result<usize, BirthError> {
    let written = out.get_mut(..count).ok_or(BirthError::TooManyComponents)?;
    if written.is_empty() {
        return Err(BirthError::Degenerate);
    }
    let total = written.iter().fold(T::zero(), |sum, component| sum + component.weight);
    if !(total.is_finite_value() && total > T::zero()) {
        return Err(BirthError::NonFinite);
    }
    for component in written.iter_mut() {
        component.weight /= total;
        let finite = component.state.mean.iter().chain(component.state.covariance.iter()).all(|v| v.is_finite_value());
        if !finite {
            return Err(BirthError::NonFinite);
        }
    }
    Ok(count)
}

fn check_inputs<T: Real>(region: &AdmissibleRegion<T>, values: &[T], observer: &[T; 6]) -> Result<(), BirthError> {
    region.validate().map_err(|_| BirthError::InvalidRegion)?;
    if !(values.iter().chain(observer.iter()).all(|v| v.is_finite_value())) {
        return Err(BirthError::NonFinite);
    }
    Ok(())
}

/// Look direction û = sin A cos E ê + cos A cos E n̂ + sin E û_up in a frame given by its rows, and its
/// derivatives over A and E.
fn look<T: Real>(frame: &[[T; 3]; 3], azimuth: T, elevation: T) -> (V3<T>, V3<T>, V3<T>) {
    let [e, n, u] = frame.map(V3::from);
    let (sa, ca, se, ce) = (sin(azimuth), cos(azimuth), sin(elevation), cos(elevation));
    let los = e * (sa * ce) + n * (ca * ce) + u * se;
    let d_azimuth = e * (ca * ce) - n * (sa * ce);
    let d_elevation = -(e * (sa * se)) - n * (ca * se) + u * ce;
    (los, d_azimuth, d_elevation)
}

/// The birth density of a radar measurement (range, azimuth, elevation[, range-rate]) from `observer`
/// with local frame `frame` (rows East, North, Up) and noise `sigma` (range, azimuth, elevation
/// [, range-rate]).
pub(crate) fn radar_births<T: Real>(
    observer: &[T; 6],
    frame: &[[T; 3]; 3],
    z: [T; 3],
    range_rate: Option<(T, T)>,
    sigma: [T; 3],
    region: &AdmissibleRegion<T>,
    out: &mut [BirthComponent<T, 6>],
) -> Result<usize, BirthError> {
    let [range, azimuth, elevation] = z;
    let (rate, sigma_rate) = range_rate.unwrap_or((T::zero(), T::zero()));
    check_inputs(region, &[range, azimuth, elevation, rate, sigma_rate], observer)?;
    if !(range > T::zero()) {
        return Err(BirthError::Degenerate);
    }
    let [ox, oy, oz, ovx, ovy, ovz] = *observer;
    let (site, site_velocity) = (V3::from([ox, oy, oz]), V3::from([ovx, ovy, ovz]));
    let (los, d_azimuth, d_elevation) = look(frame, azimuth, elevation);
    let position = site + los * range;
    let zero = V3::zeros();
    let mut count = 0;
    match range_rate {
        None => {
            let columns = [
                Column { dr: los, omega: zero, dc: T::zero(), sigma: sigma[0] },
                Column { dr: d_azimuth * range, omega: zero, dc: T::zero(), sigma: sigma[1] },
                Column { dr: d_elevation * range, omega: zero, dc: T::zero(), sigma: sigma[2] },
            ];
            geocentric_cells(region, &position, &columns, T::one(), out, &mut count)?;
        }
        Some((rate, sigma_rate)) => {
            // v · û = ρ̇ + v_s · û; an angle turns the plane's frame rigidly (ω = û × ∂û) and moves v_s · û.
            let along = rate + site_velocity.dot(&los);
            let columns = [
                Column { dr: los, omega: zero, dc: T::zero(), sigma: sigma[0] },
                Column {
                    dr: d_azimuth * range,
                    omega: los.cross(&d_azimuth),
                    dc: site_velocity.dot(&d_azimuth),
                    sigma: sigma[1],
                },
                Column {
                    dr: d_elevation * range,
                    omega: los.cross(&d_elevation),
                    dc: site_velocity.dot(&d_elevation),
                    sigma: sigma[2],
                },
                Column { dr: zero, omega: zero, dc: T::one(), sigma: sigma_rate },
            ];
            plane_cells(region, &position, &los, along, &columns, out, &mut count)?;
        }
    }
    finish(out, count)
}

/// The birth density of an optical measurement (right ascension, declination) from `observer` with noise
/// `sigma`: the line of sight against `ranges` shells across the region's band.
pub(crate) fn optical_births<T: Real>(
    observer: &[T; 6],
    z: [T; 2],
    sigma: [T; 2],
    region: &AdmissibleRegion<T>,
    out: &mut [BirthComponent<T, 6>],
) -> Result<usize, BirthError> {
    check_inputs(region, &z, observer)?;
    let [ra, dec] = z;
    // The inertial axes as a frame with azimuth = right ascension, elevation = declination.
    let (o, l) = (T::zero(), T::one());
    let (los, d_ra, d_dec) = look(&[[o, l, o], [l, o, o], [o, o, l]], ra, dec);
    let site = V3::from([observer[0], observer[1], observer[2]]);
    let (b, s2) = (site.dot(&los), site.dot(&site));
    let [low, high] = region.shell;
    let width = (high - low) / real(region.ranges);
    let zero = V3::zeros();
    let mut count = 0;
    for k in 0..region.ranges {
        let radius = low + (real::<T>(k) + c(0.5)) * width;
        // |r_s + ρ û| = R: ρ² + 2 b ρ + |r_s|² − R² = 0.
        let disc = b * b - s2 + radius * radius;
        if !(disc > T::zero()) {
            continue;
        }
        let root = sqrt(disc);
        let far = -b + root;
        let near = if s2 > radius * radius { -b - root } else { -T::one() };
        for range in [near, far] {
            if !(range > T::zero()) {
                continue;
            }
            let position = site + los * range;
            // dR/dρ = û · r̂; the cell's extent in range, bounded by the grazing chord √(2 R ΔR).
            let slope = ((range + b) / radius).abs();
            let grazing = sqrt(c::<T>(2.0) * radius * width);
            let extent = if slope * grazing > width { width / slope } else { grazing };
            let columns = [
                Column { dr: los, omega: zero, dc: T::zero(), sigma: c::<T>(CELL_SIGMA) * extent },
                Column { dr: d_ra * range, omega: zero, dc: T::zero(), sigma: sigma[0] },
                Column { dr: d_dec * range, omega: zero, dc: T::zero(), sigma: sigma[1] },
            ];
            geocentric_cells(region, &position, &columns, range * range * extent, out, &mut count)?;
        }
    }
    finish(out, count)
}

/// The birth density of a planar position measurement: mean (z, 0), covariance diag(R, σ_v² I).
pub(crate) fn planar_birth<T: Real>(
    z: &SVector<T, 2>,
    noise: &SMatrix<T, 2, 2>,
    region: &AdmissibleRegion<T>,
    out: &mut [BirthComponent<T, 4>],
) -> Result<usize, BirthError> {
    region.validate().map_err(|_| BirthError::InvalidRegion)?;
    if !z.iter().chain(noise.iter()).all(|v| v.is_finite_value()) {
        return Err(BirthError::NonFinite);
    }
    let mut covariance = SMatrix::<T, 4, 4>::zeros();
    covariance.fixed_view_mut::<2, 2>(0, 0).copy_from(noise);
    let v2 = region.velocity_sigma * region.velocity_sigma;
    covariance[(2, 2)] = v2;
    covariance[(3, 3)] = v2;
    let slot = out.get_mut(0).ok_or(BirthError::TooManyComponents)?;
    *slot = BirthComponent {
        weight: T::one(),
        state: Gaussian { mean: SVector::from([z[0], z[1], T::zero(), T::zero()]), covariance },
    };
    Ok(1)
}

#[cfg(test)]
mod tests;
