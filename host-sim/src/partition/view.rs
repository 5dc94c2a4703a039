//! The view skip's geometry (docs/maths.md §13.2): the network's ground sensors placed at a scan's time
//! ([`sights`]), and for a track's predicted mean how long it certainly stays out of each one's field of
//! view ([`clear_for`]): its distance from the region of space that field of view lies in (the range
//! window's ball, cut by the elevation mask and a cone's opening) over a bound on how fast it closes in.

use nalgebra::SVector;
use std::f64::consts::{FRAC_PI_2, PI};
use tracker_core::Config;
use tracker_core::model::{MeasurementModel, MotionModel};
use tracker_core::sensor::{Look, LookShape, Region, ScanGeometry};

/// A bound (km/s) on how fast an object of state `x` closes in on any point fixed to the ground within
/// `reach` km of a ground sensor of the network (docs/maths.md §13.2).
pub type SpeedBound<const S: usize> = fn(&SVector<f64, S>, f64) -> f64;

/// Distance (km) taken off every gap before it is turned into time: it covers the difference between the
/// prediction the gap is measured on and the longer one made when the cluster is next due (RK4's error,
/// metres over hours at 20 s sub-steps).
pub const MARGIN_KM: f64 = 1.0;

/// One ground sensor of the network placed at a scan's time.
#[derive(Debug, Clone)]
pub struct Sight<G> {
    /// Its index in the network.
    pub sensor: usize,
    /// The measurement model placed at the scan's time.
    pub model: G,
    /// Its field of view.
    pub field_of_view: Region<f64>,
}

/// Every sensor of `config`'s network that a scan without an observer places (the ground sensors), at
/// `time`.
pub fn sights<M, G, const S: usize, const D: usize, const B: usize>(
    config: &Config<f64, M, G, S, B>,
    time: f64,
) -> Vec<Sight<G>>
where
    M: MotionModel<f64, S>,
    G: MeasurementModel<f64, S, D> + Clone,
{
    (0..config.measurement.sensor_count())
        .filter_map(|sensor| {
            let model = config.measurement.place(&ScanGeometry { sensor, time, observer: None }).ok()?;
            let field_of_view = config.detection(&model).field_of_view;
            Some(Sight { sensor, model, field_of_view })
        })
        .collect()
}

/// Seconds from the scan during which an object whose predicted mean is `mean` certainly stays out of
/// `sight`'s field of view, `speed` bounding how fast it closes in; 0 when none can be given (a field of
/// view without a range window, a look without a range, a gap within [`MARGIN_KM`]). The larger of two
/// bounds (docs/maths.md §13.2): its distance beyond the range window's ball, whose centre (the site)
/// moves at `speed(x, 0)`'s site term; and its distance from the sector the field of view lies in, which
/// turns with the Earth, every point of it within the range window of the site (`speed(x, ρ_max)`).
pub fn clear_for<G, const S: usize, const D: usize>(
    sight: &Sight<G>,
    mean: &SVector<f64, S>,
    speed: SpeedBound<S>,
) -> f64
where
    G: MeasurementModel<f64, S, D>,
{
    gaps(sight, mean).map_or(0.0, |gaps| gaps.clear_for(mean, speed, 0.0))
}

/// Tracks whose means are within this distance (km, over all the state's components) of a track whose
/// [`Gaps`] were measured take that track's gaps less the distance ([`clear_near`]).
pub const NEAR_KM: f64 = 10.0;

/// [`clear_for`], from `near`'s gaps when its mean is within [`NEAR_KM`] of `mean`, or measured (and kept
/// in `near`) otherwise. Never longer than [`clear_for`] up to rounding (docs/maths.md §13.2): each gap is a
/// distance from a region, so it changes by at most the distance between the positions, and that is at
/// most the distance between the states (the position is three of the state's components, in km).
pub fn clear_near<G, const S: usize, const D: usize>(
    sight: &Sight<G>,
    mean: &SVector<f64, S>,
    speed: SpeedBound<S>,
    near: &mut Option<(Gaps, SVector<f64, S>)>,
) -> f64
where
    G: MeasurementModel<f64, S, D>,
{
    if let Some((gaps, at)) = near {
        let shift = (mean - *at).norm();
        if shift <= NEAR_KM {
            return gaps.clear_for(mean, speed, shift);
        }
    }
    let Some(gaps) = gaps(sight, mean) else { return 0.0 };
    *near = Some((gaps, *mean));
    gaps.clear_for(mean, speed, 0.0)
}

/// A point's distances (km) from a sight's field of view: beyond the range window's ball and from the
/// sector it lies in (docs/maths.md §13.2).
#[derive(Debug, Clone, Copy)]
pub struct Gaps {
    /// ρ − ρ_max.
    pub ball: f64,
    /// The distance from the sector ([`sector_gap`]).
    pub sector: f64,
    /// ρ_max, the sector's reach.
    pub reach: f64,
}

impl Gaps {
    /// The clearance (s) of an object of state `x` whose position is within `shift` km of the point these
    /// gaps were measured at: each gap less `shift` and [`MARGIN_KM`], over `speed`'s bound.
    pub fn clear_for<const S: usize>(&self, x: &SVector<f64, S>, speed: SpeedBound<S>, shift: f64) -> f64 {
        let over = |gap: f64, closing: f64| {
            let t = (gap - shift - MARGIN_KM) / closing;
            if t.is_finite() && closing > 0.0 { t.max(0.0) } else { 0.0 }
        };
        let ball = over(self.ball, speed(x, 0.0));
        let sector = over(self.sector, speed(x, self.reach));
        ball.max(sector)
    }
}

/// The [`Gaps`] of the object whose predicted mean is `mean` from `sight`'s field of view; `None` for a
/// field of view without a range window or a look without a range.
pub fn gaps<G, const S: usize, const D: usize>(sight: &Sight<G>, mean: &SVector<f64, S>) -> Option<Gaps>
where
    G: MeasurementModel<f64, S, D>,
{
    let Region::Look { shape, min_elevation, range: Some([_, max]), .. } = sight.field_of_view else {
        return None;
    };
    let look = sight.model.look_of_state(mean).or_else(|| sight.model.look(&sight.model.measure(mean)));
    let (look, range) = look.and_then(|l| l.range.map(|r| (l, r)))?;
    Some(Gaps { ball: range - max, sector: sector_gap(&look, range, &shape, min_elevation, max), reach: max })
}

/// The distance (km) from the point at `range` in the direction of `look` to the region the field of view
/// (`shape` above `mask`, out to `max`) lies in: the largest of its distances to the sector of directions
/// above the lowest elevation seen and, for a cone, to the cone's sector.
pub fn sector_gap(look: &Look<f64>, range: f64, shape: &LookShape<f64>, mask: f64, max: f64) -> f64 {
    let lowest = match *shape {
        LookShape::Cone { elevation, half_angle, .. } => elevation - half_angle,
        LookShape::Box { elevation: [low, _], .. } => low,
    }
    .max(mask);
    // Directions within π/2 − lowest of the zenith.
    let above = sector_distance(range, FRAC_PI_2 - look.elevation, (FRAC_PI_2 - lowest).clamp(0.0, PI), max);
    let cone = match *shape {
        LookShape::Cone { azimuth, elevation, half_angle } => {
            let (e, e0) = (look.elevation, elevation);
            let cos_gamma = e.sin() * e0.sin() + e.cos() * e0.cos() * (look.azimuth - azimuth).cos();
            sector_distance(range, cos_gamma.clamp(-1.0, 1.0).acos(), half_angle, max)
        }
        LookShape::Box { .. } => 0.0,
    };
    above.max(cone)
}

/// The distance (km) from a point at `range` from the apex, at angle `gamma` from the axis, to the sector of
/// the points within `radius` of the apex and within `alpha` of the axis. The nearest direction of the
/// sector is at angle δ = max(0, γ − α) from the point's (on the sphere, the axis between them), and the
/// distance to the segment along it grows with δ: ρ sin δ while the foot ρ cos δ is on the segment, the
/// distance to its far end beyond it, ρ (the apex) for δ ≥ π/2.
pub fn sector_distance(range: f64, gamma: f64, alpha: f64, radius: f64) -> f64 {
    let delta = gamma - alpha;
    if delta <= 0.0 {
        (range - radius).max(0.0)
    } else if delta >= FRAC_PI_2 {
        range
    } else if range * delta.cos() <= radius {
        range * delta.sin()
    } else {
        (range * range + radius * radius - 2.0 * range * radius * delta.cos()).max(0.0).sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The distance to the sector by brute force: the nearest of many points of it.
    fn brute(range: f64, gamma: f64, alpha: f64, radius: f64) -> f64 {
        let p = [range * gamma.sin(), 0.0, range * gamma.cos()];
        let mut best = f64::INFINITY;
        for i in 0..=200 {
            let a = alpha * f64::from(i) / 200.0;
            for j in 0..=36 {
                let phi = 2.0 * PI * f64::from(j) / 36.0;
                for k in 0..=100 {
                    let r = radius * f64::from(k) / 100.0;
                    let q = [r * a.sin() * phi.cos(), r * a.sin() * phi.sin(), r * a.cos()];
                    let d = ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt();
                    best = best.min(d);
                }
            }
        }
        best
    }

    #[test]
    fn the_sector_distance_is_the_nearest_point_of_the_sector() {
        // Inside, beyond the cap, beside the cone with the foot on the segment and beyond it, behind the apex;
        // a sector narrower and one wider than a half-space.
        for &(range, gamma, alpha) in &[
            (500.0, 0.3, 0.5),
            (5000.0, 0.3, 0.5),
            (3000.0, 0.9, 0.5),
            (9000.0, 0.7, 0.5),
            (2000.0, 2.5, 0.5),
            (3000.0, 2.0, 1.75),
            (6000.0, 2.9, 1.75),
        ] {
            let exact = sector_distance(range, gamma, alpha, 4000.0);
            let sampled = brute(range, gamma, alpha, 4000.0);
            // The samples are at most a grid step (≈ 40 km along, ≈ 0.01 rad across) from the nearest point.
            assert!(exact <= sampled + 1e-9, "{range} {gamma} {alpha}: {exact} > {sampled}");
            assert!(sampled - exact < 0.015 * range.max(4000.0), "{range} {gamma} {alpha}: {exact} ≪ {sampled}");
        }
    }
}
