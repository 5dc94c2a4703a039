//! Ground sites on WGS-84 and their observers at a time: East-North-Up frame, look angles, radar and optical measurements.

use super::frames::{fixed_to_inertial, radec};
use super::time::EARTH_ROTATION_RATE;
use super::vector::{V3, add, dot, norm, pos, scale, sub, vel};
use serde::{Deserialize, Serialize};

/// WGS-84 equatorial radius (km).
pub const WGS84_A: f64 = 6378.137;

/// WGS-84 flattening.
pub const WGS84_F: f64 = 1.0 / 298.257_223_563;

/// A ground site on WGS-84.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Site {
    /// Geodetic latitude (rad).
    pub latitude: f64,
    /// Longitude, east positive (rad).
    pub longitude: f64,
    /// Height above the ellipsoid (km).
    pub height: f64,
}

impl Site {
    /// The site's Earth-fixed position (km).
    pub fn earth_fixed(&self) -> V3 {
        let e2 = WGS84_F * (2.0 - WGS84_F);
        let (sp, cp) = self.latitude.sin_cos();
        let (sl, cl) = self.longitude.sin_cos();
        let n = WGS84_A / (1.0 - e2 * sp * sp).sqrt();
        [(n + self.height) * cp * cl, (n + self.height) * cp * sl, (n * (1.0 - e2) + self.height) * sp]
    }

    /// The site's East, North, Up unit vectors in the Earth-fixed frame.
    pub fn enu_fixed(&self) -> [V3; 3] {
        let (sp, cp) = self.latitude.sin_cos();
        let (sl, cl) = self.longitude.sin_cos();
        [[-sl, cl, 0.0], [-sp * cl, -sp * sl, cp], [cp * cl, cp * sl, sp]]
    }

    /// The observer at Earth rotation angle `theta`.
    pub fn observer(&self, theta: f64) -> Observer {
        let position = fixed_to_inertial(self.earth_fixed(), theta);
        let velocity = [-EARTH_ROTATION_RATE * position[1], EARTH_ROTATION_RATE * position[0], 0.0];
        let [e, n, u] = self.enu_fixed().map(|v| fixed_to_inertial(v, theta));
        Observer { position, velocity, east: e, north: n, up: u }
    }
}

/// A site at one instant, in the inertial frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Observer {
    /// Position (km).
    pub position: V3,
    /// Velocity ω_E × r (km/s).
    pub velocity: V3,
    /// East unit vector.
    pub east: V3,
    /// North unit vector.
    pub north: V3,
    /// Up unit vector (the geodetic normal).
    pub up: V3,
}

impl Observer {
    /// (azimuth, elevation) of an inertial line of sight `d` (any length > 0).
    pub fn look(&self, d: V3) -> (f64, f64) {
        let (e, n, u) = (dot(d, self.east), dot(d, self.north), dot(d, self.up));
        (e.atan2(n), u.atan2((e * e + n * n).sqrt()))
    }

    /// The inertial unit line of sight of (azimuth, elevation).
    pub fn direction(&self, azimuth: f64, elevation: f64) -> V3 {
        let (sa, ca) = azimuth.sin_cos();
        let (se, ce) = elevation.sin_cos();
        add(add(scale(self.east, ce * sa), scale(self.north, ce * ca)), scale(self.up, se))
    }

    /// Where the line of sight along the unit vector `d` meets the sphere of `radius` (km) about the Earth's
    /// centre: the far root, the one ahead of a site inside the sphere.
    pub fn sphere_crossing(&self, d: V3, radius: f64) -> V3 {
        let b = dot(self.position, d);
        let rho = -b + (b * b - dot(self.position, self.position) + radius * radius).sqrt();
        add(self.position, scale(d, rho))
    }

    /// (range, azimuth, elevation) of an inertial position.
    pub fn range_az_el(&self, position: V3) -> (f64, f64, f64) {
        let d = sub(position, self.position);
        let (a, e) = self.look(d);
        (norm(d), a, e)
    }

    /// The radar measurement of a state: [ρ, A, E] or, `with_rate`, [ρ, A, E, ρ̇].
    pub fn radar(&self, state: &[f64; 6], with_rate: bool) -> Vec<f64> {
        let d = sub(pos(state), self.position);
        let rho = norm(d);
        let (a, e) = self.look(d);
        let mut z = vec![rho, a, e];
        if with_rate {
            z.push(dot(d, sub(vel(state), self.velocity)) / rho);
        }
        z
    }

    /// The optical measurement [α, δ] of an inertial position.
    pub fn optical(&self, position: V3) -> [f64; 2] {
        radec(sub(position, self.position))
    }
}
