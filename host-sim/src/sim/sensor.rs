//! A simulated sensor: its kind (radar, optical), site, field of view, p_D, clutter and noise; it measures, draws clutter and adds noise.

use super::error::SsaError;
use super::field_of_view::{FieldOfView, LookShape};
use super::frames::{radec, radec_direction};
use super::site::{Observer, Site};
use super::vector::{pos, wrap_angle};
use crate::sim::rng::Random;
use core::f64::consts::{FRAC_PI_2, PI};
use serde::{Deserialize, Serialize};

/// What a sensor measures.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum SensorKind {
    /// Radar: [ρ (km), A, E].
    Radar,
    /// Radar with range-rate: [ρ, A, E, ρ̇ (km/s)]; clutter ρ̇ uniform in ±`max_range_rate`.
    RadarRangeRate {
        /// Largest |ρ̇| of clutter (km/s).
        max_range_rate: f64,
    },
    /// Telescope: [α, δ].
    Optical,
    /// A ground station's mount angles only: [A, E].
    AzEl,
    /// Range only: [ρ].
    Range,
    /// Range and range-rate: [ρ, ρ̇]; clutter ρ̇ uniform in ±`max_range_rate`.
    RangeRangeRate {
        /// Largest |ρ̇| of clutter and of what is in view (km/s).
        max_range_rate: f64,
    },
}

impl SensorKind {
    /// The measurement dimension.
    pub fn dimension(&self) -> usize {
        match self {
            SensorKind::Radar => 3,
            SensorKind::RadarRangeRate { .. } => 4,
            SensorKind::Optical | SensorKind::AzEl | SensorKind::RangeRangeRate { .. } => 2,
            SensorKind::Range => 1,
        }
    }

    /// Whether it measures range.
    pub fn has_range(&self) -> bool {
        !matches!(self, SensorKind::Optical | SensorKind::AzEl)
    }

    /// The components of its azimuth (or right ascension) and elevation (or declination), if it measures
    /// angles.
    fn angles(&self) -> Option<(usize, usize)> {
        match self {
            SensorKind::Radar | SensorKind::RadarRangeRate { .. } => Some((1, 2)),
            SensorKind::Optical | SensorKind::AzEl => Some((0, 1)),
            SensorKind::Range | SensorKind::RangeRangeRate { .. } => None,
        }
    }
}

/// A sensor: site, measurement type, field of view, noise, detection and clutter.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SensorSpec {
    /// A label.
    pub name: String,
    /// Where it stands.
    pub site: Site,
    /// What it measures.
    pub kind: SensorKind,
    /// Where it looks.
    pub fov: FieldOfView,
    /// Noise standard deviation per measurement component (km, rad, km/s).
    pub sigma: Vec<f64>,
    /// Probability of detecting an object inside the field of view.
    pub detection_probability: f64,
    /// Mean number of clutter measurements per scan.
    pub clutter_rate: f64,
}

impl SensorSpec {
    pub(crate) fn check(&self) -> Result<(), SsaError> {
        let radar = self.kind.has_range();
        let ok = self.sigma.len() == self.kind.dimension()
            && self.sigma.iter().all(|s| s.is_finite() && *s >= 0.0)
            && (0.0..=1.0).contains(&self.detection_probability)
            && self.clutter_rate.is_finite()
            && self.clutter_rate >= 0.0
            && (!radar || matches!(self.fov.range, Some([lo, hi]) if lo >= 0.0 && hi > lo));
        if ok { Ok(()) } else { Err(SsaError::BadSensor) }
    }

    /// The noiseless measurement of `state` by this sensor seen from `observer`.
    pub fn measure(&self, observer: &Observer, state: &[f64; 6]) -> Vec<f64> {
        match self.kind {
            SensorKind::Radar => observer.radar(state, false),
            SensorKind::RadarRangeRate { .. } => observer.radar(state, true),
            SensorKind::Optical => observer.optical(pos(state)).to_vec(),
            SensorKind::AzEl => observer.radar(state, false)[1..].to_vec(),
            SensorKind::Range => observer.radar(state, false)[..1].to_vec(),
            SensorKind::RangeRangeRate { .. } => {
                let z = observer.radar(state, true);
                vec![z[0], z[3]]
            }
        }
    }

    /// Whether a true state is inside the field of view (a range and range-rate sensor: its range-rate
    /// within ±`max_range_rate` too).
    pub fn sees(&self, observer: &Observer, state: &[f64; 6]) -> bool {
        let (rho, a, e) = observer.range_az_el(pos(state));
        let rate_ok = match self.kind {
            SensorKind::RangeRangeRate { max_range_rate } => observer.radar(state, true)[3].abs() <= max_range_rate,
            _ => true,
        };
        rate_ok && self.fov.contains(a, e, Some(rho))
    }

    fn in_range_window(&self, range: f64) -> bool {
        self.fov.range.is_none_or(|[low, high]| range >= low && range <= high)
    }

    /// Whether a measurement-space point is inside the field of view (its look angles and range).
    pub fn contains_measurement(&self, observer: &Observer, z: &[f64]) -> bool {
        match self.kind {
            SensorKind::Radar | SensorKind::RadarRangeRate { .. } => self.fov.contains(z[1], z[2], Some(z[0])),
            SensorKind::Optical => {
                let (a, e) = observer.look(radec_direction(z[0], z[1]));
                self.fov.contains(a, e, None)
            }
            SensorKind::AzEl => self.fov.contains(z[0], z[1], None),
            // No angles: the range (and range-rate) windows.
            SensorKind::Range => self.in_range_window(z[0]),
            SensorKind::RangeRangeRate { max_range_rate } => self.in_range_window(z[0]) && z[1].abs() <= max_range_rate,
        }
    }

    /// A bounding box of the field of view in measurement coordinates: per component (centre, half
    /// width); angles may extend past ±π and are wrapped after sampling.
    fn measurement_box(&self, observer: &Observer) -> Vec<(f64, f64)> {
        let (az_c, az_w, el_lo, el_hi) = self.fov.az_el_bounds();
        let el = ((el_lo + el_hi) * 0.5, ((el_hi - el_lo) * 0.5).max(0.0));
        match self.kind {
            SensorKind::Radar | SensorKind::RadarRangeRate { .. } => {
                let [lo, hi] = self.fov.range.unwrap_or([0.0, 0.0]);
                let mut b = vec![((lo + hi) * 0.5, (hi - lo) * 0.5), (az_c, az_w), el];
                if let SensorKind::RadarRangeRate { max_range_rate } = self.kind {
                    b.push((0.0, max_range_rate));
                }
                b
            }
            SensorKind::Optical => match self.fov.shape {
                LookShape::Cone { azimuth, elevation, half_angle } => {
                    let [a0, d0] = radec(observer.direction(azimuth, elevation));
                    let d_lo = (d0 - half_angle).max(-FRAC_PI_2);
                    let d_hi = (d0 + half_angle).min(FRAC_PI_2);
                    let width = if d0.abs() + half_angle >= FRAC_PI_2 - 1e-6 {
                        PI
                    } else {
                        ((half_angle.sin() / d0.cos()).min(1.0).asin() + 1e-6).min(PI)
                    };
                    vec![(a0, width), ((d_lo + d_hi) * 0.5, (d_hi - d_lo) * 0.5)]
                }
                // No tight (α, δ) image of a box is computed: the whole sky bounds it.
                LookShape::Box { .. } => vec![(0.0, PI), (0.0, FRAC_PI_2)],
            },
            SensorKind::AzEl => vec![(az_c, az_w), el],
            SensorKind::Range | SensorKind::RangeRangeRate { .. } => {
                let [lo, hi] = self.fov.range.unwrap_or([0.0, 0.0]);
                let mut b = vec![((lo + hi) * 0.5, (hi - lo) * 0.5)];
                if let SensorKind::RangeRangeRate { max_range_rate } = self.kind {
                    b.push((0.0, max_range_rate));
                }
                b
            }
        }
    }

    fn angle_components(&self) -> &'static [usize] {
        match self.kind.angles() {
            Some((0, _)) => &[0],
            Some(_) => &[1],
            None => &[],
        }
    }

    /// One clutter point, uniform in measurement coordinates over the field of view.
    ///
    /// # Errors
    /// [`SsaError::EmptyFieldOfView`] when 10⁶ draws from the bounding box all fall outside.
    pub fn clutter_point(&self, observer: &Observer, random: &mut Random) -> Result<Vec<f64>, SsaError> {
        let bounds = self.measurement_box(observer);
        for _ in 0..1_000_000 {
            let mut z: Vec<f64> = bounds.iter().map(|&(c, w)| random.between(c - w, c + w)).collect();
            for &i in self.angle_components() {
                z[i] = wrap_angle(z[i]);
            }
            if self.contains_measurement(observer, &z) {
                return Ok(z);
            }
        }
        Err(SsaError::EmptyFieldOfView)
    }

    /// The field-of-view volume in measurement coordinates (km·rad², rad², ...) by Monte Carlo:
    /// the bounding box's volume times the fraction of `samples` uniform draws inside.
    pub fn fov_volume_monte_carlo(&self, observer: &Observer, samples: usize, random: &mut Random) -> f64 {
        let bounds = self.measurement_box(observer);
        let box_volume: f64 = bounds.iter().map(|&(_, w)| 2.0 * w).product();
        let mut inside = 0usize;
        for _ in 0..samples {
            let mut z: Vec<f64> = bounds.iter().map(|&(c, w)| random.between(c - w, c + w)).collect();
            for &i in self.angle_components() {
                z[i] = wrap_angle(z[i]);
            }
            inside += usize::from(self.contains_measurement(observer, &z));
        }
        box_volume * inside as f64 / samples.max(1) as f64
    }

    /// A noisy measurement of `state`: Gaussian noise per component, angles wrapped, an elevation
    /// (declination) above π/2 reflected over the zenith (pole).
    pub(super) fn noisy(&self, observer: &Observer, state: &[f64; 6], random: &mut Random) -> Vec<f64> {
        let mut z = self.measure(observer, state);
        for (zi, s) in z.iter_mut().zip(&self.sigma) {
            *zi += s * random.normal();
        }
        let Some((a, e)) = self.kind.angles() else { return z };
        if z[e] > FRAC_PI_2 {
            z[e] = PI - z[e];
            z[a] += PI;
        } else if z[e] < -FRAC_PI_2 {
            z[e] = -PI - z[e];
            z[a] += PI;
        }
        z[a] = wrap_angle(z[a]);
        z
    }
}
