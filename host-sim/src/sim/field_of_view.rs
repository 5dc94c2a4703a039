//! Fields of view in a site's local frame: a cone or an azimuth/elevation box, an elevation mask and, for radar, a range window.

use super::vector::{angle_between, wrap_angle};
use core::f64::consts::{FRAC_PI_2, PI};
use serde::{Deserialize, Serialize};

/// The shape of a field of view in the site's local frame (radians).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum LookShape {
    /// Lines of sight within `half_angle` of the boresight (azimuth, elevation).
    Cone {
        /// Boresight azimuth.
        azimuth: f64,
        /// Boresight elevation.
        elevation: f64,
        /// Half-angle of the cone.
        half_angle: f64,
    },
    /// wrap(A − azimuth_centre) within ±azimuth_half_width and E in [elevation_min, elevation_max].
    Box {
        /// Centre azimuth.
        azimuth_centre: f64,
        /// Half width in azimuth (π: all azimuths).
        azimuth_half_width: f64,
        /// Lowest elevation.
        elevation_min: f64,
        /// Highest elevation.
        elevation_max: f64,
    },
}

/// A field of view: a shape, an elevation mask and (radar) a range window.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FieldOfView {
    /// The look shape.
    pub shape: LookShape,
    /// Elevation mask (rad): nothing below it is seen.
    pub min_elevation: f64,
    /// Range window [min, max] (km); radar only.
    pub range: Option<[f64; 2]>,
}

impl FieldOfView {
    /// Whether (azimuth, elevation, range) is inside; `range` None skips the range window (optical).
    pub fn contains(&self, azimuth: f64, elevation: f64, range: Option<f64>) -> bool {
        if !(elevation >= self.min_elevation) {
            return false;
        }
        if let (Some([lo, hi]), Some(r)) = (self.range, range)
            && !(r >= lo && r <= hi)
        {
            return false;
        }
        match self.shape {
            LookShape::Cone { azimuth: a0, elevation: e0, half_angle } => {
                // cos of the angle between the two directions, by the spherical law of cosines.
                let to_unit = |a: f64, e: f64| {
                    let (sa, ca) = a.sin_cos();
                    let (se, ce) = e.sin_cos();
                    [ce * sa, ce * ca, se]
                };
                angle_between(to_unit(azimuth, elevation), to_unit(a0, e0)) <= half_angle
            }
            LookShape::Box { azimuth_centre, azimuth_half_width, elevation_min, elevation_max } => {
                wrap_angle(azimuth - azimuth_centre).abs() <= azimuth_half_width
                    && elevation >= elevation_min
                    && elevation <= elevation_max
            }
        }
    }

    /// Bounding intervals of (azimuth, elevation) of the shape with the mask: azimuth as
    /// (centre, half width), elevation as [lo, hi].
    pub(super) fn az_el_bounds(&self) -> (f64, f64, f64, f64) {
        const MARGIN: f64 = 1e-6;
        match self.shape {
            LookShape::Cone { azimuth, elevation, half_angle } => {
                let lo = (elevation - half_angle).max(self.min_elevation).max(-FRAC_PI_2);
                let hi = (elevation + half_angle).min(FRAC_PI_2);
                let width = if elevation.abs() + half_angle >= FRAC_PI_2 - MARGIN {
                    PI
                } else {
                    ((half_angle.sin() / elevation.cos()).min(1.0).asin() + MARGIN).min(PI)
                };
                (azimuth, width, lo - MARGIN, hi)
            }
            LookShape::Box { azimuth_centre, azimuth_half_width, elevation_min, elevation_max } => {
                (azimuth_centre, azimuth_half_width.min(PI), elevation_min.max(self.min_elevation), elevation_max)
            }
        }
    }
}
