//! Small 3-vector maths on `[f64; 3]` and angles: the one copy host-sim uses.

use core::f64::consts::{PI, TAU};

/// Degrees to radians.
pub fn deg(x: f64) -> f64 {
    x.to_radians()
}

pub type V3 = [f64; 3];

pub fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

pub fn scale(a: V3, s: f64) -> V3 {
    [a[0] * s, a[1] * s, a[2] * s]
}

pub fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

pub fn cross(a: V3, b: V3) -> V3 {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

pub fn norm(a: V3) -> f64 {
    dot(a, a).sqrt()
}

pub fn pos(state: &[f64; 6]) -> V3 {
    [state[0], state[1], state[2]]
}

pub fn vel(state: &[f64; 6]) -> V3 {
    [state[3], state[4], state[5]]
}

/// The angle between two vectors (rad), by atan2 (accurate for small and large angles).
pub fn angle_between(a: V3, b: V3) -> f64 {
    norm(cross(a, b)).atan2(dot(a, b))
}

/// Wraps an angle into (−π, π].
pub fn wrap_angle(x: f64) -> f64 {
    let y = (x + PI).rem_euclid(TAU) - PI; // [−π, π)
    if y <= -PI { y + TAU } else { y }
}

/// Rodrigues rotation of `v` about unit `k` by `angle`.
pub fn rotate(v: V3, k: V3, angle: f64) -> V3 {
    let (s, c) = angle.sin_cos();
    add(add(scale(v, c), scale(cross(k, v), s)), scale(k, dot(k, v) * (1.0 - c)))
}
