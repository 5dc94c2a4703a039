//! Frames: Earth-fixed to inertial, and topocentric right ascension / declination of a direction.

use super::vector::{V3, norm};

/// Rotates an Earth-fixed vector into the inertial frame: about z by θ.
pub fn fixed_to_inertial(v: V3, theta: f64) -> V3 {
    let (s, c) = theta.sin_cos();
    [c * v[0] - s * v[1], s * v[0] + c * v[1], v[2]]
}

/// (right ascension, declination) of an inertial direction.
pub fn radec(d: V3) -> [f64; 2] {
    [d[1].atan2(d[0]), (d[2] / norm(d)).clamp(-1.0, 1.0).asin()]
}

/// The inertial unit vector of (right ascension, declination).
pub fn radec_direction(alpha: f64, delta: f64) -> V3 {
    let (sa, ca) = alpha.sin_cos();
    let (sd, cd) = delta.sin_cos();
    [cd * ca, cd * sa, sd]
}
