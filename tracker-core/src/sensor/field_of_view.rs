//! A sensor's field of view: the region of measurement space it sees ([`Region`]: planar rectangles and
//! sectors, or look directions in the sensor's own frame), whether a point lies in it, and its volume.

use crate::real::{Real, atan2, c, cos, sin, sqrt};
use nalgebra::SVector;

/// The region of measurement space the sensor sees.
///
/// `Rectangle` and `Sector` read the first two components of a measurement as a planar position.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Region<T> {
    /// No boundary: every object is detectable and clutter spreads over an abstract `volume`
    /// (for exactness tests that follow the papers' single-volume examples).
    Everywhere {
        /// The measurement-space volume V over which clutter is uniform.
        volume: T,
    },
    /// An axis-aligned rectangle `min ≤ (z₀, z₁) ≤ max`.
    Rectangle {
        /// Lower corner.
        min: [T; 2],
        /// Upper corner.
        max: [T; 2],
    },
    /// A field of view in the sensor's own frame (East, North, Up of a ground site; the inertial axes for a
    /// spacecraft), read through the placed sensor's [`look`](super::Placement::look): a cone or
    /// an azimuth/elevation box, above an elevation mask, and for a radar inside a range window (and a
    /// range-rate window when it measures range-rate). Angles in radians, azimuth from North towards East.
    Look {
        /// The cone or box of look directions.
        shape: LookShape<T>,
        /// The elevation mask: nothing lower is seen.
        min_elevation: T,
        /// `[min, max]` range (km) seen; required exactly when the model measures range.
        range: Option<[T; 2]>,
        /// `[min, max]` range-rate (km/s) seen; required exactly when the model measures range-rate.
        range_rate: Option<[T; 2]>,
    },
    /// A circular sector: the sensor at `origin` looking along `look_direction` (radians from +x),
    /// seeing `half_angle` radians either side, out to `max_range`.
    Sector {
        /// Sensor position.
        origin: [T; 2],
        /// Boresight direction in radians, counter-clockwise from +x.
        look_direction: T,
        /// Half of the field-of-view angle, in radians (0, π].
        half_angle: T,
        /// Largest range seen.
        max_range: T,
    },
}

/// The look directions of a [`Region::Look`] field of view.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum LookShape<T> {
    /// Every direction within `half_angle` of the boresight (`azimuth`, `elevation`).
    Cone {
        /// Boresight azimuth.
        azimuth: T,
        /// Boresight elevation.
        elevation: T,
        /// Half of the cone's opening angle, in (0, π].
        half_angle: T,
    },
    /// Azimuths within `half_width` of `azimuth` (across ±π too) and elevations in `elevation`.
    Box {
        /// Centre azimuth.
        azimuth: T,
        /// Half of the azimuth extent, in (0, π].
        half_width: T,
        /// `[min, max]` elevation.
        elevation: [T; 2],
    },
}

/// Which coordinates besides azimuth and elevation a model's measurements carry.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct LookAxes {
    /// Range.
    pub range: bool,
    /// Range-rate.
    pub range_rate: bool,
}

/// A measurement as a look direction in the sensor's frame.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Look<T> {
    /// Azimuth from North towards East, (−π, π].
    pub azimuth: T,
    /// Elevation above the horizontal plane, [−π/2, π/2].
    pub elevation: T,
    /// Range (km), when measured.
    pub range: Option<T>,
    /// Range-rate (km/s), when measured.
    pub range_rate: Option<T>,
}

/// Rows of the elevation quadrature of [`LookShape::area`]: for a cone a midpoint rule in φ with elevation
/// E = centre + half·sin φ, which removes the square-root behaviour of its width at its top and bottom; for
/// a box plain midpoints in E.
const LOOK_ROWS: usize = 256;

impl<T: Real> LookShape<T> {
    /// Whether the direction (`azimuth`, `elevation`) lies in the shape (boundary included).
    pub fn contains(&self, azimuth: T, elevation: T) -> bool {
        match *self {
            LookShape::Cone { azimuth: a0, elevation: e0, half_angle } => {
                // cos γ = sin E sin E₀ + cos E cos E₀ cos(A − A₀), γ the angle from the boresight.
                let cos_gamma = sin(elevation) * sin(e0) + cos(elevation) * cos(e0) * cos(azimuth - a0);
                cos_gamma >= cos(half_angle)
            }
            LookShape::Box { azimuth: a0, half_width, elevation: [low, high] } => {
                let offset = super::frames::wrap_angle(azimuth - a0);
                elevation >= low && elevation <= high && offset >= -half_width && offset <= half_width
            }
        }
    }

    /// The elevation span `[low, high]` of the shape above `mask`; `None` when empty.
    fn elevation_span(&self, mask: T) -> Option<(T, T)> {
        let half_pi = T::frac_pi_2();
        let (low, high) = match *self {
            LookShape::Cone { elevation, half_angle, .. } => (elevation - half_angle, elevation + half_angle),
            LookShape::Box { elevation: [low, high], .. } => (low, high),
        };
        let (low, high) = (max(max(low, mask), -half_pi), min(high, half_pi));
        if high > low { Some((low, high)) } else { None }
    }

    /// The azimuth half-width of the shape's row at `elevation` (its centre is the shape's azimuth).
    fn row_half_width(&self, elevation: T) -> T {
        match *self {
            LookShape::Box { half_width, .. } => half_width,
            LookShape::Cone { elevation: e0, half_angle, .. } => {
                // cos ΔA ≥ q = (cos θ − sin E sin E₀) / (cos E cos E₀).
                let denominator = cos(elevation) * cos(e0);
                let numerator = cos(half_angle) - sin(elevation) * sin(e0);
                if !(denominator > T::zero()) {
                    return if numerator <= T::zero() { T::pi() } else { T::zero() };
                }
                let q = numerator / denominator;
                if q <= -T::one() {
                    T::pi()
                } else if q >= T::one() {
                    T::zero()
                } else {
                    atan2(sqrt(T::one() - q * q), q)
                }
            }
        }
    }

    /// The centre azimuth of every row.
    fn azimuth(&self) -> T {
        match *self {
            LookShape::Cone { azimuth, .. } | LookShape::Box { azimuth, .. } => azimuth,
        }
    }

    /// ∫∫ density(A, E) dA dE over the shape above the elevation `mask`, by a fixed quadrature:
    /// [`LOOK_ROWS`] elevation rows, `azimuth_points` midpoints across each row's azimuth interval
    /// (one is exact when the density does not depend on the azimuth).
    pub fn area<F: Fn(T, T) -> T>(&self, mask: T, azimuth_points: usize, density: F) -> T {
        let Some((low, high)) = self.elevation_span(mask) else {
            return T::zero();
        };
        let (centre, half) = ((low + high) * c(0.5), (high - low) * c(0.5));
        let rows = T::of_f64(LOOK_ROWS as f64);
        let columns = azimuth_points.clamp(1, 1024);
        let mut total = T::zero();
        let cone = matches!(self, LookShape::Cone { .. });
        for row in 0..LOOK_ROWS {
            let midpoint = (T::of_f64(row as f64) + c(0.5)) / rows;
            let (elevation, weight) = if cone {
                // φ ∈ (−π/2, π/2) at the midpoints; dE = half cos φ dφ.
                let phi = midpoint * T::pi() - T::frac_pi_2();
                (centre + half * sin(phi), half * cos(phi) * T::pi() / rows)
            } else {
                // A box's rows all have the same width: plain midpoints are exact for a constant density.
                (low + midpoint * (high - low), (high - low) / rows)
            };
            let width = self.row_half_width(elevation);
            let step = c::<T>(2.0) * width / T::of_f64(columns as f64);
            let mut row_sum = T::zero();
            for column in 0..columns {
                let azimuth = self.azimuth() - width + (T::of_f64(column as f64) + c(0.5)) * step;
                row_sum += density(azimuth, elevation);
            }
            total += weight * row_sum * step;
        }
        total
    }
}

fn max<T: Real>(a: T, b: T) -> T {
    if a >= b { a } else { b }
}

fn min<T: Real>(a: T, b: T) -> T {
    if a <= b { a } else { b }
}

/// Whether `value` is in the closed window `[low, high]` (an absent window admits everything).
fn in_window<T: Real>(window: Option<[T; 2]>, value: Option<T>) -> bool {
    match (window, value) {
        (Some([low, high]), Some(v)) => v >= low && v <= high,
        (Some(_), None) => false,
        (None, _) => true,
    }
}

fn window_extent<T: Real>(window: Option<[T; 2]>) -> T {
    window.map_or(T::one(), |[low, high]| high - low)
}

impl<T: Real> Region<T> {
    /// Whether the look direction `look` lies in a [`Region::Look`] field of view (`false` for the planar
    /// regions, which are not in look coordinates).
    pub fn contains_look(&self, look: &Look<T>) -> bool {
        match *self {
            Region::Look { shape, min_elevation, range, range_rate } => {
                // Angles outside their ranges are no direction the sensor sees.
                let half_pi = T::frac_pi_2();
                look.azimuth >= -T::pi()
                    && look.azimuth <= T::pi()
                    && look.elevation >= -half_pi
                    && look.elevation <= half_pi
                    && look.elevation >= min_elevation
                    && shape.contains(look.azimuth, look.elevation)
                    && in_window(range, look.range)
                    && in_window(range_rate, look.range_rate)
            }
            _ => false,
        }
    }

    /// The measurement-space volume V (an area for planar regions).
    ///
    /// # Examples
    /// ```
    /// use tracker_core::Region;
    /// assert_eq!(Region::Rectangle { min: [-1.0, 0.0], max: [3.0, 5.0] }.volume(), 20.0);
    /// let sector = Region::Sector { origin: [0.0, 0.0], look_direction: 0.0, half_angle: 0.5, max_range: 10.0 };
    /// assert_eq!(sector.volume(), 50.0); // θ R²
    /// ```
    pub fn volume(&self) -> T {
        match *self {
            Region::Everywhere { volume } => volume,
            Region::Rectangle { min, max } => (max[0] - min[0]) * (max[1] - min[1]),
            // Area of a sector of angle 2θ: θ R².
            Region::Sector { half_angle, max_range, .. } => half_angle * max_range * max_range,
            // Look coordinates: ∫∫ dA dE over the angles, times the range and range-rate extents.
            Region::Look { shape, min_elevation, range, range_rate } => {
                shape.area(min_elevation, 1, |_, _| T::one()) * window_extent(range) * window_extent(range_rate)
            }
        }
    }

    /// Whether the measurement-space point `z` lies in the region (boundary included).
    ///
    /// # Examples
    /// ```
    /// use nalgebra::SVector;
    /// use tracker_core::Region;
    /// let rectangle = Region::Rectangle { min: [0.0, 0.0], max: [10.0, 5.0] };
    /// assert!(rectangle.contains(&SVector::from([10.0, 5.0]))); // the boundary is inside
    /// assert!(!rectangle.contains(&SVector::from([10.5, 1.0])));
    ///
    /// // Looking along +y, 30° either side, out to 100.
    /// let sector = Region::Sector {
    ///     origin: [0.0, 0.0],
    ///     look_direction: core::f64::consts::FRAC_PI_2,
    ///     half_angle: 30f64.to_radians(),
    ///     max_range: 100.0,
    /// };
    /// assert!(sector.contains(&SVector::from([10.0, 50.0])));
    /// assert!(!sector.contains(&SVector::from([50.0, 10.0]))); // 79° off the boresight
    /// assert!(!sector.contains(&SVector::from([0.0, 101.0]))); // out of range
    /// ```
    pub fn contains<const D: usize>(&self, z: &SVector<T, D>) -> bool {
        match *self {
            Region::Everywhere { .. } => true,
            // Look coordinates need the measurement model: see `sees`.
            Region::Look { .. } => false,
            Region::Rectangle { min, max } => {
                D >= 2 && z[0] >= min[0] && z[0] <= max[0] && z[1] >= min[1] && z[1] <= max[1]
            }
            Region::Sector { origin, look_direction, half_angle, max_range } => {
                if D < 2 {
                    return false;
                }
                let dx = z[0] - origin[0];
                let dy = z[1] - origin[1];
                if dx * dx + dy * dy > max_range * max_range {
                    return false;
                }
                // Rotate into the boresight frame and compare the bearing with the half angle.
                let (s, c) = (sin(look_direction), cos(look_direction));
                let along = dx * c + dy * s;
                let across = dy * c - dx * s;
                let bearing = atan2(across, along);
                bearing <= half_angle && bearing >= -half_angle
            }
        }
    }

    pub(crate) fn validate(&self, measurement_dimension: usize) -> Result<(), &'static str> {
        let finite = |v: T| v.is_finite_value();
        match *self {
            Region::Everywhere { volume } => {
                if !(finite(volume) && volume > T::zero()) {
                    return Err("field of view: volume must be finite and > 0");
                }
            }
            Region::Rectangle { min, max } => {
                if measurement_dimension < 2 {
                    return Err("field of view: a rectangle needs measurements of dimension >= 2");
                }
                if !(min.iter().chain(max.iter()).all(|&v| finite(v)) && max[0] > min[0] && max[1] > min[1]) {
                    return Err("field of view: rectangle corners must be finite with max > min");
                }
            }
            Region::Look { shape, min_elevation, range, range_rate } => {
                let half_pi = T::frac_pi_2();
                let angle = |v: T| finite(v) && v >= -half_pi && v <= half_pi;
                if !angle(min_elevation) {
                    return Err("field of view: elevation mask must be in [-pi/2, pi/2]");
                }
                match shape {
                    LookShape::Cone { azimuth, elevation, half_angle } => {
                        if !(finite(azimuth) && angle(elevation)) {
                            return Err("field of view: cone boresight must be finite with elevation in [-pi/2, pi/2]");
                        }
                        if !(finite(half_angle) && half_angle > T::zero() && half_angle <= T::pi()) {
                            return Err("field of view: cone half angle must be in (0, pi]");
                        }
                    }
                    LookShape::Box { azimuth, half_width, elevation: [low, high] } => {
                        if !finite(azimuth) {
                            return Err("field of view: box azimuth must be finite");
                        }
                        if !(finite(half_width) && half_width > T::zero() && half_width <= T::pi()) {
                            return Err("field of view: box azimuth half width must be in (0, pi]");
                        }
                        if !(angle(low) && angle(high) && high > low) {
                            return Err("field of view: box elevations must be in [-pi/2, pi/2] with max > min");
                        }
                    }
                }
                for window in [range, range_rate].into_iter().flatten() {
                    if !(finite(window[0]) && finite(window[1]) && window[1] > window[0]) {
                        return Err(
                            "field of view: zero volume or worse: range and range-rate windows must be finite with max > min",
                        );
                    }
                }
                if let Some([low, _]) = range
                    && low < T::zero()
                {
                    return Err("field of view: the range window must start at >= 0");
                }
                if shape.elevation_span(min_elevation).is_none() {
                    return Err("field of view: zero volume: nothing of the look shape is above the elevation mask");
                }
            }
            Region::Sector { origin, look_direction, half_angle, max_range } => {
                if measurement_dimension < 2 {
                    return Err("field of view: a sector needs measurements of dimension >= 2");
                }
                if !(origin.iter().all(|&v| finite(v)) && finite(look_direction)) {
                    return Err("field of view: sector origin and look direction must be finite");
                }
                if !(finite(half_angle) && half_angle > T::zero() && half_angle <= T::pi()) {
                    return Err("field of view: sector half angle must be in (0, pi]");
                }
                if !(finite(max_range) && max_range > T::zero()) {
                    return Err("field of view: sector max range must be finite and > 0");
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand_core::Rng;

    /// A uniform draw in [low, high) from 53 random bits.
    pub(crate) fn uniform(rng: &mut impl Rng, low: f64, high: f64) -> f64 {
        low + (high - low) * ((rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64)
    }

    /// The look-angle area of `region` by Monte Carlo over the whole (A, E) rectangle, with its standard
    /// error.
    fn monte_carlo_area(region: &Region<f64>, samples: usize) -> (f64, f64) {
        let mut rng = crate::random::test_stream(7);
        let half_pi = core::f64::consts::FRAC_PI_2;
        let box_area = 2.0 * core::f64::consts::PI * 2.0 * half_pi;
        let mut inside = 0usize;
        for _ in 0..samples {
            let azimuth = uniform(&mut rng, -core::f64::consts::PI, core::f64::consts::PI);
            let elevation = uniform(&mut rng, -half_pi, half_pi);
            let look = Look { azimuth, elevation, range: None, range_rate: None };
            let angles_only = match *region {
                Region::Look { shape, min_elevation, .. } => {
                    Region::Look { shape, min_elevation, range: None, range_rate: None }
                }
                other => other,
            };
            inside += usize::from(angles_only.contains_look(&look));
        }
        let fraction = inside as f64 / samples as f64;
        (fraction * box_area, box_area * (fraction * (1.0 - fraction) / samples as f64).sqrt())
    }

    #[test]
    fn look_volumes_match_monte_carlo_in_measurement_coordinates() {
        let degree = 1f64.to_radians();
        let cases = [
            // A radar cone at 50° elevation above a 10° mask, with a range window.
            Region::Look {
                shape: LookShape::Cone { azimuth: 2.0, elevation: 50.0 * degree, half_angle: 30.0 * degree },
                min_elevation: 10.0 * degree,
                range: Some([200.0, 2200.0]),
                range_rate: None,
            },
            // A cone holding the zenith, cut by a 30° mask.
            Region::Look {
                shape: LookShape::Cone { azimuth: -3.0, elevation: 80.0 * degree, half_angle: 60.0 * degree },
                min_elevation: 30.0 * degree,
                range: None,
                range_rate: None,
            },
            // A box across azimuth ±180°.
            Region::Look {
                shape: LookShape::Box { azimuth: 3.0, half_width: 0.5, elevation: [5.0 * degree, 40.0 * degree] },
                min_elevation: 10.0 * degree,
                range: Some([0.0, 3000.0]),
                range_rate: Some([-8.0, 8.0]),
            },
        ];
        for region in cases {
            assert_eq!(region.validate(3), Ok(()));
            let (estimate, error) = monte_carlo_area(&region, 400_000);
            let extent = match region {
                Region::Look { range, range_rate, .. } => {
                    window_extent(range).max(1.0) * window_extent(range_rate).max(1.0)
                }
                _ => 1.0,
            };
            let area = region.volume() / extent;
            eprintln!("look area {area:.6} sr-coordinates, Monte Carlo {estimate:.6} ± {error:.6}");
            assert!((area - estimate).abs() < 4.0 * error, "{area} vs {estimate} ± {error}");
        }
        // The box's area is exact: 2 · 0.5 rad of azimuth × 30° of elevation above the mask.
        let exact = 1.0 * 30.0 * degree * 3000.0 * 16.0;
        assert!((cases[2].volume() - exact).abs() < 1e-9 * exact);
    }

    #[test]
    fn look_regions_test_every_coordinate_and_reject_bad_parameters() {
        let degree = 1f64.to_radians();
        let region = Region::Look {
            shape: LookShape::Box { azimuth: core::f64::consts::PI, half_width: 0.2, elevation: [0.0, 0.5] },
            min_elevation: 0.1,
            range: Some([100.0, 1000.0]),
            range_rate: None,
        };
        let look = |azimuth: f64, elevation: f64, range: f64| Look {
            azimuth,
            elevation,
            range: Some(range),
            range_rate: None,
        };
        assert!(region.contains_look(&look(-3.1, 0.3, 500.0))); // across ±π
        assert!(!region.contains_look(&look(-3.1, 0.05, 500.0))); // under the mask
        assert!(!region.contains_look(&look(-3.1, 0.3, 1500.0))); // beyond the range window
        assert!(!region.contains_look(&Look { range: None, ..look(-3.1, 0.3, 500.0) })); // no range given
        assert!(!region.contains_look(&look(2.0, 0.3, 500.0)));
        let bad = [
            Region::Look {
                shape: LookShape::Cone { azimuth: 0.0, elevation: 100.0 * degree, half_angle: 0.1 },
                min_elevation: 0.0,
                range: None,
                range_rate: None,
            },
            Region::Look {
                shape: LookShape::Cone { azimuth: 0.0, elevation: 0.5, half_angle: 0.0 },
                min_elevation: 0.0,
                range: None,
                range_rate: None,
            },
            // Zero volume: an empty range window, or everything under the mask.
            Region::Look {
                shape: LookShape::Cone { azimuth: 0.0, elevation: 0.5, half_angle: 0.1 },
                min_elevation: 0.0,
                range: Some([500.0, 500.0]),
                range_rate: None,
            },
            Region::Look {
                shape: LookShape::Box { azimuth: 0.0, half_width: 0.1, elevation: [0.0, 0.2] },
                min_elevation: 0.3,
                range: None,
                range_rate: None,
            },
            Region::Look {
                shape: LookShape::Box { azimuth: f64::NAN, half_width: 0.1, elevation: [0.0, 0.2] },
                min_elevation: 0.0,
                range: None,
                range_rate: None,
            },
        ];
        for region in bad {
            assert!(region.validate(3).is_err(), "{region:?}");
        }
    }

    #[test]
    fn sector_contains_points_inside_only() {
        let fov = Region::Sector {
            origin: [0.0, 0.0],
            look_direction: 15f64.to_radians(),
            half_angle: 15f64.to_radians(),
            max_range: 10.0,
        };
        let at = |deg: f64, r: f64| SVector::from([r * deg.to_radians().cos(), r * deg.to_radians().sin()]);
        assert!(fov.contains(&at(15.0, 5.0)));
        assert!(fov.contains(&at(1.0, 9.9)));
        assert!(fov.contains(&at(29.0, 1.0)));
        assert!(!fov.contains(&at(31.0, 5.0)));
        assert!(!fov.contains(&at(-1.0, 5.0)));
        assert!(!fov.contains(&at(15.0, 10.1)));
        assert!(!fov.contains(&at(195.0, 5.0)));
        // θ R² with θ = 15°.
        assert!((fov.volume() - 15f64.to_radians() * 100.0).abs() < 1e-12);
    }

    #[test]
    fn rectangle_volume_and_membership() {
        let fov = Region::Rectangle { min: [-1.0, 0.0], max: [3.0, 5.0] };
        assert_eq!(fov.volume(), 20.0);
        assert!(fov.contains(&SVector::from([0.0, 0.0])));
        assert!(!fov.contains(&SVector::from([3.5, 1.0])));
    }
}
