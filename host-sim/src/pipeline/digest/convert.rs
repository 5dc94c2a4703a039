//! `f64` → `T` converters shared by the digests: every value of the host's configuration rounded once
//! (`T::of_f64`), so that the host replay and the firmware start from the same bits.

use crate::scenario::v2::{Motion3dSpec, ProcessNoiseSpec, Scenario3d};
use tracker_core::model::{AdmissibleRegion, ProcessNoise, SensorBirths};
use tracker_core::pool::MeasuredBirths;
use tracker_core::sensor::{GroundSite, LookShape, Platform};
use tracker_core::{Gaussian, Real, Region, Sensor, TwoBodyJ2};

/// An `f64` region in scalar `T`.
pub fn region<T: Real>(region: &Region<f64>) -> Region<T> {
    let of = T::of_f64;
    match *region {
        Region::Everywhere { volume } => Region::Everywhere { volume: of(volume) },
        Region::Rectangle { min, max } => Region::Rectangle { min: min.map(of), max: max.map(of) },
        Region::Sector { origin, look_direction, half_angle, max_range } => Region::Sector {
            origin: origin.map(of),
            look_direction: of(look_direction),
            half_angle: of(half_angle),
            max_range: of(max_range),
        },
        Region::Look { shape, min_elevation, range, range_rate } => Region::Look {
            shape: match shape {
                LookShape::Cone { azimuth, elevation, half_angle } => {
                    LookShape::Cone { azimuth: of(azimuth), elevation: of(elevation), half_angle: of(half_angle) }
                }
                LookShape::Box { azimuth, half_width, elevation } => {
                    LookShape::Box { azimuth: of(azimuth), half_width: of(half_width), elevation: elevation.map(of) }
                }
            },
            min_elevation: of(min_elevation),
            range: range.map(|window| window.map(of)),
            range_rate: range_rate.map(|window| window.map(of)),
        },
    }
}

/// An `f64` Gaussian in scalar `T`.
pub fn gaussian<T: Real, const S: usize>(gaussian: &Gaussian<f64, S>) -> Gaussian<T, S> {
    Gaussian { mean: gaussian.mean.map(T::of_f64), covariance: gaussian.covariance.map(T::of_f64) }
}

/// A sensor's detection model in scalar `T`.
pub fn sensor<T: Real>(sensor: &Sensor<f64>) -> Sensor<T> {
    Sensor {
        detection_probability: T::of_f64(sensor.detection_probability),
        clutter_rate: T::of_f64(sensor.clutter_rate),
        field_of_view: region(&sensor.field_of_view),
    }
}

/// A sensor's platform in scalar `T` (a ground site's angles already in radians).
pub fn platform<T: Real>(platform: Platform<f64>) -> Platform<T> {
    let of = T::of_f64;
    match platform {
        Platform::Ground(site) => Platform::Ground(GroundSite {
            latitude: of(site.latitude),
            longitude: of(site.longitude),
            height: of(site.height),
        }),
        Platform::Spacecraft => Platform::Spacecraft,
    }
}

/// The scenario's motion model in `f32`: the `f32` Earth constants, its noise and steps rounded once.
pub fn motion(scenario: &Scenario3d) -> TwoBodyJ2<f32> {
    let of = f32::of_f64;
    let Motion3dSpec::TwoBodyJ2 { process_noise, max_step, max_substeps } = scenario.motion;
    let noise = match process_noise {
        ProcessNoiseSpec::Isotropic { q } => ProcessNoise::Isotropic(of(q)),
        ProcessNoiseSpec::Ric { radial, in_track, cross_track } => {
            ProcessNoise::Ric { radial: of(radial), in_track: of(in_track), cross_track: of(cross_track) }
        }
    };
    TwoBodyJ2::<f32>::earth(noise, of(max_step), max_substeps)
}

/// An admissible region in scalar `T`.
pub fn admissible<T: Real>(region: &AdmissibleRegion<f64>) -> AdmissibleRegion<T> {
    let of = T::of_f64;
    AdmissibleRegion {
        mu: of(region.mu),
        min_perigee_radius: of(region.min_perigee_radius),
        max_apogee_radius: of(region.max_apogee_radius),
        max_inclination: of(region.max_inclination),
        shell: region.shell.map(of),
        headings: region.headings,
        speeds: region.speeds,
        climbs: region.climbs,
        ranges: region.ranges,
        velocity_sigma: of(region.velocity_sigma),
    }
}

/// Where a sensor's births come from, in scalar `T`.
pub fn sensor_births<T: Real>(births: SensorBirths<f64>) -> SensorBirths<T> {
    match births {
        SensorBirths::FromModel => SensorBirths::FromModel,
        SensorBirths::Region(region) => SensorBirths::Region(admissible(&region)),
        SensorBirths::Off => SensorBirths::Off,
    }
}

/// Measurement-driven birth settings in scalar `T`.
pub fn measured<T: Real>(measured: &MeasuredBirths<f64>) -> MeasuredBirths<T> {
    let of = T::of_f64;
    MeasuredBirths {
        region: admissible(&measured.region),
        expected_births: of(measured.expected_births),
        max_probability: of(measured.max_probability),
        min_unexplained: of(measured.min_unexplained),
        lifetime: measured.lifetime,
        tracklets: measured.tracklets.map(|t| tracker_core::pool::TrackletBirths {
            frames: t.frames,
            max_span: t.max_span,
            limits: tracker_core::model::LinkLimits {
                max_chi_squared: of(t.limits.max_chi_squared),
                max_rate: of(t.limits.max_rate),
                max_acceleration: of(t.limits.max_acceleration),
                max_jerk: of(t.limits.max_jerk),
            },
            region: admissible(&t.region),
            cells: t.cells,
            single_frame: t.single_frame,
        }),
        link_waiting: measured.link_waiting,
    }
}
