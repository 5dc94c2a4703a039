//! Two-body + J2 motion in 3-D: state (x, y, z, vx, vy, vz) in km and km/s, with
//! r̈ = −μ r / |r|³ + a_J2(r), the Earth's oblateness as its zonal term J2 (docs/maths.md §6.7).
//!
//! **Frame.** Inertial, Earth-centred, with z along the Earth's rotation pole: J2 is symmetric about
//! the inertial z axis, which is the pole in TEME, and in GCRF up to precession and nutation (GCRF's z
//! is ≈ 0.14° from the pole of date in 2025, 20″ a year since J2000). The truth and the tracker must
//! share the frame: SGP4 output is TEME, so feed TEME states and TEME-derived measurements.
//!
//! **Neglected.** Higher zonals and tesserals (J3 ≈ −2.5e-6, J4 ≈ −1.6e-6: about 1/400 of J2),
//! atmospheric drag, solar radiation pressure and lunisolar third-body gravity. For LEO these reach
//! tens of metres to kilometres over hours (drag the largest below ≈ 600 km; estimates in docs/maths.md
//! §6.7); they are what the process noise must cover.
//!
//! **Integration.** State and transition matrix Φ are integrated together by classical fixed-step RK4 on
//! the variational equations Φ̇ = A(x) Φ, A = [[0, I], [G, 0]], with the gravity gradient G = ∂a/∂r
//! written out analytically (no finite differences). A time step `dt` is split into
//! `ceil(dt / max_step)` equal sub-steps; more than `max_substeps` is [`ModelError::TimeStepTooLarge`],
//! so the longest gap a configuration can bridge is `max_step × max_substeps` (20 s × 1100 = 22 000 s
//! ≈ 6.1 h). Any position closer to the centre than `min_radius` at any RK4 stage is
//! [`ModelError::Singular`] (inside the Earth the field expansion is not valid and at r → 0 it diverges);
//! a non-finite input or result is [`ModelError::NonFinite`].
//!
//! **Process noise.** White acceleration noise, either isotropic or with separate spectral densities
//! along the radial, in-track and cross-track (RIC) axes of the state it is applied at
//! ([`ProcessNoise`]).

use super::{ModelError, MotionModel, Propagation};
use crate::real::{Real, c, sqrt};
use crate::sensor::EARTH_RADIUS;
use nalgebra::{SMatrix, SVector};

/// The Earth's gravitational parameter μ (km³/s²): the WGS-84 value (EGM-96's own, 398600.4415, differs by
/// 8e-10 relative).
pub const EARTH_MU: f64 = 398_600.441_8;
/// The Earth's second zonal harmonic J2 (dimensionless): the EGM-96 value, −√5 C̄20 with
/// C̄20 = −4.841 653 717 36e-4.
pub const EARTH_J2: f64 = 1.082_626_68e-3;
/// The default `min_radius` (km): R_E − 78.137 km, 56.6 km below the WGS-84 polar radius (6356.752 km),
/// so no object above the ground anywhere is rejected and anything below is inside the Earth.
pub const EARTH_MIN_RADIUS: f64 = 6300.0;

/// White acceleration noise of a [`TwoBodyJ2`] model: spectral densities in km²/s³.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum ProcessNoise<T> {
    /// The same density `q` along every inertial axis.
    Isotropic(T),
    /// Densities along the radial (r̂), in-track (ĉ × r̂) and cross-track (ĉ = r × v / |r × v|) axes of the
    /// state the noise is applied at.
    Ric {
        /// Radial density.
        radial: T,
        /// In-track density.
        in_track: T,
        /// Cross-track density.
        cross_track: T,
    },
}

/// The two-body + J2 motion model (see the module documentation for the frame and what is neglected).
///
/// # Examples
/// J2 turns the orbit plane: the ascending node of an inclined LEO orbit regresses at the secular rate
/// Ω̇ = −(3/2) n J2 (R_E / a)² cos i, while h_z, the pole-wise angular momentum, is conserved.
/// ```
/// use nalgebra::SVector;
/// use tracker_core::TwoBodyJ2;
/// use tracker_core::model::{EARTH_J2, EARTH_MU, EARTH_RADIUS, MotionModel, ProcessNoise};
///
/// // 20 s RK4 steps, at most 1100 of them: gaps up to 6.1 h.
/// static MODEL: TwoBodyJ2<f64> = TwoBodyJ2::<f64>::earth(ProcessNoise::Isotropic(1e-12), 20.0, 1100);
/// let (r, inclination) = (7000.0_f64, 51.6_f64.to_radians());
/// let v = (EARTH_MU / r).sqrt();
/// let x0 = SVector::from([r, 0.0, 0.0, 0.0, v * inclination.cos(), v * inclination.sin()]);
/// let node = |x: &SVector<f64, 6>| {
///     let h = x.fixed_rows::<3>(0).cross(&x.fixed_rows::<3>(3));
///     (h[0].atan2(-h[1]), h[2])
/// };
/// let dt = 6.0 * 3600.0;
/// let x1 = MODEL.propagate(&x0, dt)?.state;
/// let ((node0, hz0), (node1, hz1)) = (node(&x0), node(&x1));
/// let n = (EARTH_MU / (r * r * r)).sqrt();
/// let secular = -1.5 * n * EARTH_J2 * (EARTH_RADIUS / r).powi(2) * inclination.cos() * dt; // −1.12°
/// assert!(((node1 - node0) - secular).abs() < 0.02 * secular.abs()); // measured: 0.54 %
/// assert!((hz1 - hz0).abs() < 1e-8 * hz0); // measured: 1.5e-9 (RK4 truncation)
/// # Ok::<(), tracker_core::model::ModelError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TwoBodyJ2<T> {
    /// Gravitational parameter μ (km³/s²).
    pub mu: T,
    /// Second zonal harmonic J2 (0 gives pure two-body motion).
    pub j2: T,
    /// Reference radius of J2 (km).
    pub radius: T,
    /// Smallest distance from the centre a state may have (km); below it is [`ModelError::Singular`].
    pub min_radius: T,
    /// White acceleration noise.
    pub noise: ProcessNoise<T>,
    /// Largest RK4 sub-step (s).
    pub max_step: T,
    /// Most sub-steps one propagation may take; a longer `dt` is [`ModelError::TimeStepTooLarge`].
    pub max_substeps: u32,
}

macro_rules! earth_constructor {
    ($t:ty) => {
        impl TwoBodyJ2<$t> {
            /// The Earth ([`EARTH_MU`], [`EARTH_J2`], [`EARTH_RADIUS`], [`EARTH_MIN_RADIUS`]) with the given
            /// noise and step bounds; `const`, so usable in a `static`.
            pub const fn earth(noise: ProcessNoise<$t>, max_step: $t, max_substeps: u32) -> Self {
                Self {
                    mu: EARTH_MU as $t,
                    j2: EARTH_J2 as $t,
                    radius: EARTH_RADIUS as $t,
                    min_radius: EARTH_MIN_RADIUS as $t,
                    noise,
                    max_step,
                    max_substeps,
                }
            }
        }
    };
}

earth_constructor!(f64);
earth_constructor!(f32);

/// Point-mass acceleration and gradient at `p` (|p| = `r`, `g` = μ / r³):
/// a = −g p, G = g (3 u uᵀ − I) with u = p / r.
fn central_terms<T: Real>(p: &SVector<T, 3>, r: T, g: T) -> (SVector<T, 3>, SMatrix<T, 3, 3>) {
    let u = p / r;
    let gradient = (u * u.transpose() * c::<T>(3.0) - SMatrix::<T, 3, 3>::identity()) * g;
    (p * -g, gradient)
}

impl<T: Real> TwoBodyJ2<T> {
    /// |p|, or the error of a position the model cannot take.
    fn radius_of(&self, p: &SVector<T, 3>) -> Result<T, ModelError> {
        let r2 = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
        if !r2.is_finite_value() {
            return Err(ModelError::NonFinite);
        }
        let r = sqrt(r2);
        if !(r >= self.min_radius) {
            return Err(ModelError::Singular);
        }
        Ok(r)
    }

    /// J2 acceleration and its gradient at `p` (|p| = `r`, `g` = μ / r³). With s = z / r, u = p / r and
    /// k = g · (3/2) J2 (R / r)² (= (3/2) μ J2 R² / r⁵):
    ///
    /// a_J2 = −k (x (1 − 5s²), y (1 − 5s²), z (3 − 5s²))
    /// G_J2 = −k [diag(1 − 5s², 1 − 5s², 3 − 5s²) + (35s² − 5) u uᵀ − 10 s (e_z uᵀ + u e_zᵀ)]
    ///
    /// Everything is written with u and s, not with powers of r, so that f32 does not overflow
    /// (r⁹ at GEO is 4e41).
    fn j2_terms(&self, p: &SVector<T, 3>, r: T, g: T) -> (SVector<T, 3>, SMatrix<T, 3, 3>) {
        let rho = self.radius / r;
        let k = g * c::<T>(1.5) * self.j2 * rho * rho;
        let u = p / r;
        let s = u[2];
        let five_s2 = c::<T>(5.0) * s * s;
        let equatorial = T::one() - five_s2;
        let polar = c::<T>(3.0) - five_s2;
        let acceleration = SVector::<T, 3>::new(p[0] * equatorial, p[1] * equatorial, p[2] * polar) * -k;
        let outer = c::<T>(7.0) * five_s2 - c::<T>(5.0);
        let ten_s = c::<T>(10.0) * s;
        let mut gradient = u * u.transpose() * outer;
        for i in 0..3 {
            // −10 s (e_z uᵀ + u e_zᵀ): row z and column z.
            gradient[(2, i)] -= ten_s * u[i];
            gradient[(i, 2)] -= ten_s * u[i];
        }
        gradient[(0, 0)] += equatorial;
        gradient[(1, 1)] += equatorial;
        gradient[(2, 2)] += polar;
        (acceleration, gradient * -k)
    }

    /// The J2 acceleration of [`Self::j2_terms`] alone, with the same operations (so the same bits).
    fn j2_acceleration(&self, p: &SVector<T, 3>, r: T, g: T) -> SVector<T, 3> {
        let rho = self.radius / r;
        let k = g * c::<T>(1.5) * self.j2 * rho * rho;
        let s = (p / r)[2];
        let five_s2 = c::<T>(5.0) * s * s;
        let equatorial = T::one() - five_s2;
        let polar = c::<T>(3.0) - five_s2;
        SVector::<T, 3>::new(p[0] * equatorial, p[1] * equatorial, p[2] * polar) * -k
    }

    /// The state's time derivative f(x) of [`Self::derivative`] alone, with the same operations.
    fn velocity_and_acceleration(&self, state: &SVector<T, 6>) -> Result<SVector<T, 6>, ModelError> {
        let p = SVector::<T, 3>::new(state[0], state[1], state[2]);
        let r = self.radius_of(&p)?;
        let g = self.mu / (r * r * r);
        let a = p * -g + self.j2_acceleration(&p, r, g);
        Ok(SVector::from([state[3], state[4], state[5], a[0], a[1], a[2]]))
    }

    /// Total acceleration a(r) and gravity gradient G = ∂a/∂r.
    fn gravity(&self, p: &SVector<T, 3>) -> Result<(SVector<T, 3>, SMatrix<T, 3, 3>), ModelError> {
        let r = self.radius_of(p)?;
        let g = self.mu / (r * r * r);
        let (a_central, g_central) = central_terms(p, r, g);
        let (a_j2, g_j2) = self.j2_terms(p, r, g);
        Ok((a_central + a_j2, g_central + g_j2))
    }

    /// Time derivative of the state and of Φ: (ẋ, Φ̇) = (f(x), A(x) Φ), A = [[0, I], [G, 0]].
    fn derivative(
        &self,
        state: &SVector<T, 6>,
        phi: &SMatrix<T, 6, 6>,
    ) -> Result<(SVector<T, 6>, SMatrix<T, 6, 6>), ModelError> {
        let (a, g) = self.gravity(&SVector::<T, 3>::new(state[0], state[1], state[2]))?;
        let derivative = SVector::from([state[3], state[4], state[5], a[0], a[1], a[2]]);
        let mut phi_dot = SMatrix::<T, 6, 6>::zeros();
        for col in 0..6 {
            for i in 0..3 {
                // Rows 0-2: the velocity rows of Φ; rows 3-5: G times the position rows of Φ.
                phi_dot[(i, col)] = phi[(i + 3, col)];
                phi_dot[(i + 3, col)] =
                    g[(i, 0)] * phi[(0, col)] + g[(i, 1)] * phi[(1, col)] + g[(i, 2)] * phi[(2, col)];
            }
        }
        Ok((derivative, phi_dot))
    }

    /// The 3 × 3 spectral density matrix of the acceleration noise in the inertial frame at `state`.
    ///
    /// With the RIC unit vectors r̂ = r / |r|, ĉ = (r × v) / |r × v|, î = ĉ × r̂ as the columns of the
    /// rotation R (RIC → inertial), a noise w_ric with density diag(q_R, q_I, q_C) is w = R w_ric in the
    /// inertial frame, with density R diag(q_R, q_I, q_C) Rᵀ = q_R r̂ r̂ᵀ + q_I î îᵀ + q_C ĉ ĉᵀ.
    /// Where the RIC frame is undefined (r or r × v zero or not finite) the largest density is used on
    /// every axis, which covers each of the three.
    fn acceleration_density(&self, state: &SVector<T, 6>) -> SMatrix<T, 3, 3> {
        let (radial, in_track, cross_track) = match self.noise {
            ProcessNoise::Isotropic(q) => return SMatrix::<T, 3, 3>::identity() * q,
            ProcessNoise::Ric { radial, in_track, cross_track } => (radial, in_track, cross_track),
        };
        let r = SVector::<T, 3>::new(state[0], state[1], state[2]);
        let v = SVector::<T, 3>::new(state[3], state[4], state[5]);
        let h = r.cross(&v);
        let (r_norm, h_norm) = (sqrt(r.dot(&r)), sqrt(h.dot(&h)));
        let defined = r_norm > T::zero() && h_norm > T::zero() && r_norm.is_finite_value() && h_norm.is_finite_value();
        if !defined {
            let largest = radial.max(in_track).max(cross_track);
            return SMatrix::<T, 3, 3>::identity() * largest;
        }
        let r_hat = r / r_norm;
        let c_hat = h / h_norm;
        let i_hat = c_hat.cross(&r_hat);
        r_hat * r_hat.transpose() * radial
            + i_hat * i_hat.transpose() * in_track
            + c_hat * c_hat.transpose() * cross_track
    }
}

/// The sub-steps and constants of one RK4 propagation over `dt`, shared by [`TwoBodyJ2::propagate`] and
/// its mean-only twin so that both take the same steps with the same operations.
struct Rk4<T> {
    steps: u32,
    h: T,
    half: T,
    sixth: T,
    two: T,
}

impl<T: Real> TwoBodyJ2<T> {
    /// Checks that `state` is finite and splits `dt` into the RK4 sub-steps (§6.7).
    fn rk4(&self, state: &SVector<T, 6>, dt: T) -> Result<Rk4<T>, ModelError> {
        if !state.iter().all(|v| v.is_finite_value()) {
            return Err(ModelError::NonFinite);
        }
        let (steps, h) = super::rk4_substeps(dt, self.max_step, self.max_substeps)?;
        Ok(Rk4 { steps, h, half: c(0.5), sixth: T::one() / c(6.0), two: c(2.0) })
    }
}

impl<T: Real> MotionModel<T, 6> for TwoBodyJ2<T> {
    fn propagate(&self, state: &SVector<T, 6>, dt: T) -> Result<Propagation<T, 6>, ModelError> {
        let Rk4 { steps, h, half, sixth, two } = self.rk4(state, dt)?;
        let mut x = *state;
        let mut phi = SMatrix::<T, 6, 6>::identity();
        for _ in 0..steps {
            let (k1x, k1p) = self.derivative(&x, &phi)?;
            let (k2x, k2p) = self.derivative(&(x + k1x * (h * half)), &(phi + k1p * (h * half)))?;
            let (k3x, k3p) = self.derivative(&(x + k2x * (h * half)), &(phi + k2p * (h * half)))?;
            let (k4x, k4p) = self.derivative(&(x + k3x * h), &(phi + k3p * h))?;
            x += (k1x + k2x * two + k3x * two + k4x) * (h * sixth);
            phi += (k1p + k2p * two + k3p * two + k4p) * (h * sixth);
        }
        if x.iter().chain(phi.iter()).all(|v| v.is_finite_value()) {
            Ok(Propagation { state: x, transition: phi })
        } else {
            Err(ModelError::NonFinite)
        }
    }

    /// The state of [`Self::propagate`]'s RK4, the same sub-steps and operations, without Φ.
    fn propagate_mean(&self, state: &SVector<T, 6>, dt: T) -> Result<SVector<T, 6>, ModelError> {
        let Rk4 { steps, h, half, sixth, two } = self.rk4(state, dt)?;
        let mut x = *state;
        for _ in 0..steps {
            let k1x = self.velocity_and_acceleration(&x)?;
            let k2x = self.velocity_and_acceleration(&(x + k1x * (h * half)))?;
            let k3x = self.velocity_and_acceleration(&(x + k2x * (h * half)))?;
            let k4x = self.velocity_and_acceleration(&(x + k3x * h))?;
            x += (k1x + k2x * two + k3x * two + k4x) * (h * sixth);
        }
        if x.iter().all(|v| v.is_finite_value()) { Ok(x) } else { Err(ModelError::NonFinite) }
    }

    /// Q = [[dt³/3 Q_a, dt²/2 Q_a], [dt²/2 Q_a, dt Q_a]], with Q_a the acceleration density at `state`
    /// (the RIC axes are frozen at the prior state over `dt`, and the gravity gradient's effect on the
    /// noise over one step is neglected, as for constant velocity).
    fn process_noise(&self, state: &SVector<T, 6>, dt: T) -> SMatrix<T, 6, 6> {
        let density = self.acceleration_density(state);
        let dt2 = dt * dt;
        let blocks = [dt2 * dt / c(3.0), dt2 / c(2.0), dt];
        let mut noise = SMatrix::<T, 6, 6>::zeros();
        for i in 0..3 {
            for j in 0..3 {
                let q = density[(i, j)];
                noise[(i, j)] = q * blocks[0];
                noise[(i, j + 3)] = q * blocks[1];
                noise[(i + 3, j)] = q * blocks[1];
                noise[(i + 3, j + 3)] = q * blocks[2];
            }
        }
        noise
    }

    fn validate(&self) -> Result<(), &'static str> {
        let positive = |v: T| v.is_finite_value() && v > T::zero();
        if !positive(self.mu) {
            return Err("two-body J2: mu must be finite and > 0");
        }
        if !(self.j2.is_finite_value() && self.j2 >= T::zero()) {
            return Err("two-body J2: j2 must be finite and >= 0");
        }
        if !positive(self.radius) {
            return Err("two-body J2: radius must be finite and > 0");
        }
        if !positive(self.min_radius) {
            return Err("two-body J2: min_radius must be finite and > 0");
        }
        let densities_positive = match self.noise {
            ProcessNoise::Isotropic(q) => positive(q),
            ProcessNoise::Ric { radial, in_track, cross_track } => {
                positive(radial) && positive(in_track) && positive(cross_track)
            }
        };
        if !densities_positive {
            return Err("two-body J2: every noise density must be finite and > 0 (Q positive definite)");
        }
        if !positive(self.max_step) {
            return Err("two-body J2: max_step must be finite and > 0");
        }
        if self.max_substeps == 0 || self.max_substeps > super::MAX_RK4_SUBSTEPS {
            return Err("two-body J2: max_substeps must be in 1..=1,000,000");
        }
        Ok(())
    }

    /// `max_step × max_substeps`: the longest gap one prediction bridges.
    fn max_time_step(&self) -> Option<f64> {
        Some(self.max_step.as_f64() * f64::from(self.max_substeps))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MODEL: TwoBodyJ2<f64> = TwoBodyJ2::<f64>::earth(ProcessNoise::Isotropic(1e-12), 20.0, 1100);

    /// Slightly eccentric LEO (perigee 622 km) at 51.6°, started off the equator so that z ≠ 0.
    fn leo() -> SVector<f64, 6> {
        let r = 7000.0_f64;
        let v = (EARTH_MU / r).sqrt() * 1.01;
        let (ci, si) = (51.6_f64.to_radians().cos(), 51.6_f64.to_radians().sin());
        // Position 30° along the orbit from the node.
        let (cu, su) = (30.0_f64.to_radians().cos(), 30.0_f64.to_radians().sin());
        SVector::from([r * cu, r * su * ci, r * su * si, -v * su, v * cu * ci, v * cu * si])
    }

    /// Near-circular GEO with 5° inclination, off the equator.
    fn geo() -> SVector<f64, 6> {
        let r = 42_164.0_f64;
        let v = (EARTH_MU / r).sqrt();
        let (ci, si) = (5.0_f64.to_radians().cos(), 5.0_f64.to_radians().sin());
        let (cu, su) = (0.5_f64.cos(), 0.5_f64.sin());
        SVector::from([r * cu, r * su * ci, r * su * si, -v * su, v * cu * ci, v * cu * si])
    }

    fn period(x: &SVector<f64, 6>) -> f64 {
        let r = x.fixed_rows::<3>(0).norm();
        let a = 1.0 / (2.0 / r - x.fixed_rows::<3>(3).norm_squared() / EARTH_MU);
        2.0 * core::f64::consts::PI * (a * a * a / EARTH_MU).sqrt()
    }

    /// Largest discrepancy between Φ and central differences of the propagation, in the dimensionless
    /// form D⁻¹ Φ D with D = diag(r, r, r, v, v, v), relative to max(1, |entry|).
    fn transition_error(model: &TwoBodyJ2<f64>, x0: &SVector<f64, 6>, dt: f64) -> f64 {
        let r = x0.fixed_rows::<3>(0).norm();
        let v = x0.fixed_rows::<3>(3).norm();
        let scale = [r, r, r, v, v, v];
        let base = model.propagate(x0, dt).unwrap();
        let mut worst = 0.0_f64;
        for j in 0..6 {
            let eps = scale[j] * 1e-7;
            let (mut plus, mut minus) = (*x0, *x0);
            plus[j] += eps;
            minus[j] -= eps;
            let column =
                (model.propagate(&plus, dt).unwrap().state - model.propagate(&minus, dt).unwrap().state) / (2.0 * eps);
            for i in 0..6 {
                let expected = column[i] * scale[j] / scale[i];
                let got = base.transition[(i, j)] * scale[j] / scale[i];
                worst = worst.max((got - expected).abs() / expected.abs().max(1.0));
            }
        }
        worst
    }

    // Measured (`cargo test -p tracker-core two_body_j2`, with a print): LEO 9.7e-10 over 60 s and
    // 1.5e-8 over one orbit; GEO 1.2e-9 and 1.3e-7.
    #[test]
    fn two_body_j2_transition_matrix_matches_finite_differences() {
        let model = TwoBodyJ2 { max_substeps: 5000, ..MODEL }; // one GEO orbit is 4309 steps of 20 s
        for x0 in [leo(), geo()] {
            for dt in [60.0, period(&x0)] {
                let error = transition_error(&model, &x0, dt);
                assert!(error < 1e-6, "dt = {dt}: scaled Φ differs from finite differences by {error:e}");
            }
        }
    }

    /// The mean-only propagation is the full one's state, bit for bit (the partitioned tracker's coasting
    /// relies on it, docs/maths.md §13.2).
    #[test]
    fn two_body_j2_mean_propagation_is_the_full_propagations_state_bit_for_bit() {
        let molniya = {
            let (rp, ra) = (6_900.0_f64, 46_000.0_f64);
            let v = (EARTH_MU * (2.0 / rp - 2.0 / (rp + ra))).sqrt();
            let (ci, si) = (63.4_f64.to_radians().cos(), 63.4_f64.to_radians().sin());
            SVector::from([rp, 0.0, 0.0, 0.0, v * ci, v * si])
        };
        for x0 in [leo(), geo(), molniya] {
            for dt in [0.5, 6.67, 20.0, 33.3, 600.0, 5_432.1] {
                let full = MODEL.propagate(&x0, dt).unwrap().state;
                let mean = MODEL.propagate_mean(&x0, dt).unwrap();
                assert!(full.iter().zip(&mean).all(|(a, b)| a.to_bits() == b.to_bits()), "dt {dt}: {full} ≠ {mean}");
            }
        }
        assert_eq!(MODEL.propagate_mean(&leo(), 1e9), Err(MODEL.propagate(&leo(), 1e9).unwrap_err()));
    }

    // Measured: relative errors 3e-12 to 1.7e-10 (finite-difference truncation and rounding).
    #[test]
    fn two_body_j2_gravity_gradient_matches_finite_differences() {
        let positions = [
            SVector::from([7000.0, 0.0, 0.0]),
            SVector::from([3000.0, -4000.0, 5000.0]),
            SVector::from([10.0, 20.0, -6600.0]), // near the pole
            geo().fixed_rows::<3>(0).into_owned(),
        ];
        for p in positions {
            let r = p.norm();
            let g = EARTH_MU / (r * r * r);
            let (_, j2_gradient) = MODEL.j2_terms(&p, r, g);
            let (_, gradient) = MODEL.gravity(&p).unwrap();
            let mut j2_fd = SMatrix::<f64, 3, 3>::zeros();
            let mut fd = SMatrix::<f64, 3, 3>::zeros();
            for j in 0..3 {
                let eps = r * 1e-6;
                let (mut plus, mut minus) = (p, p);
                plus[j] += eps;
                minus[j] -= eps;
                let j2_at = |q: &SVector<f64, 3>| {
                    let rq = q.norm();
                    MODEL.j2_terms(q, rq, EARTH_MU / (rq * rq * rq)).0
                };
                j2_fd.set_column(j, &((j2_at(&plus) - j2_at(&minus)) / (2.0 * eps)));
                fd.set_column(j, &((MODEL.gravity(&plus).unwrap().0 - MODEL.gravity(&minus).unwrap().0) / (2.0 * eps)));
            }
            let j2_error = (j2_gradient - j2_fd).amax() / j2_fd.amax();
            let error = (gradient - fd).amax() / fd.amax();
            assert!(j2_error < 1e-8, "J2 gradient at {p:?}: relative error {j2_error:e}");
            assert!(error < 1e-8, "gravity gradient at {p:?}: relative error {error:e}");
            // The gradient of a potential is symmetric.
            assert!((j2_gradient - j2_gradient.transpose()).amax() <= 1e-15 * j2_gradient.amax());
        }
    }

    /// Kepler energy v²/2 − μ/r and the J2-modified energy, which also subtracts the J2 potential
    /// U_J2 = (μ J2 R² / 2r³)(1 − 3 z²/r²).
    fn energies(x: &SVector<f64, 6>) -> (f64, f64) {
        let r = x.fixed_rows::<3>(0).norm();
        let kepler = 0.5 * x.fixed_rows::<3>(3).norm_squared() - EARTH_MU / r;
        let s = x[2] / r;
        let u_j2 = EARTH_MU * EARTH_J2 * EARTH_RADIUS * EARTH_RADIUS / (2.0 * r * r * r) * (1.0 - 3.0 * s * s);
        (kepler, kepler - u_j2)
    }

    /// Samples the state every 60 s over one orbit; returns the largest relative changes of the Kepler
    /// energy, the J2 energy, h_z and h_x.
    fn drifts_over_one_orbit(model: &TwoBodyJ2<f64>, x0: &SVector<f64, 6>) -> [f64; 4] {
        let (kepler0, j2_0) = energies(x0);
        let h0 = x0.fixed_rows::<3>(0).cross(&x0.fixed_rows::<3>(3));
        let mut worst = [0.0_f64; 4];
        let mut x = *x0;
        let samples = (period(x0) / 60.0).ceil() as usize;
        for _ in 0..samples {
            x = model.propagate(&x, 60.0).unwrap().state;
            let (kepler, j2) = energies(&x);
            let h = x.fixed_rows::<3>(0).cross(&x.fixed_rows::<3>(3));
            let changes = [
                (kepler - kepler0) / kepler0,
                (j2 - j2_0) / j2_0,
                (h[2] - h0[2]) / h0.norm(),
                (h[0] - h0[0]) / h0.norm(),
            ];
            for (w, change) in worst.iter_mut().zip(changes) {
                *w = w.max(change.abs());
            }
        }
        worst
    }

    // Measured over one orbit of `leo()` sampled every 60 s (relative changes): J2 energy 7.2e-10 with
    // 20 s steps, 2.7e-11 with 10 s, 1.3e-12 with 5 s; h_z 2.2e-10, 6.9e-12, 2.1e-13. The ratio of
    // ~20-30 per halving is RK4's truncation error, not a missing term (which would not shrink).
    #[test]
    fn two_body_j2_conserves_the_j2_energy_not_the_kepler_energy() {
        let [kepler, j2, _, _] = drifts_over_one_orbit(&MODEL, &leo());
        // J2 exchanges ~1e-3 of the energy with the orbit; RK4 with 20 s steps keeps the integral.
        assert!(kepler > 1e-4, "Kepler energy changed by only {kepler:e}");
        assert!(j2 < 2e-9, "J2 energy changed by {j2:e}");
        let [_, j2_fine, _, _] = drifts_over_one_orbit(&TwoBodyJ2 { max_step: 10.0, ..MODEL }, &leo());
        assert!(j2_fine < j2 / 10.0, "J2 energy drift {j2_fine:e} with 10 s steps, {j2:e} with 20 s");
    }

    #[test]
    fn two_body_j2_conserves_the_polar_angular_momentum() {
        let [_, _, hz, hx] = drifts_over_one_orbit(&MODEL, &leo());
        // J2 is symmetric about z: h_z is an integral; h_x is not (the plane precesses).
        assert!(hz < 1e-9, "h_z changed by {hz:e}");
        assert!(hx > 1e-3, "h_x changed by only {hx:e}");
        let [_, _, hz_fine, _] = drifts_over_one_orbit(&TwoBodyJ2 { max_step: 10.0, ..MODEL }, &leo());
        assert!(hz_fine < hz / 10.0, "h_z drift {hz_fine:e} with 10 s steps, {hz:e} with 20 s");
    }

    #[test]
    fn two_body_j2_errors() {
        let model = MODEL;
        let at = |p: [f64; 3]| SVector::from([p[0], p[1], p[2], 1.0, 7.0, 0.0]);
        assert_eq!(model.propagate(&at([1e-3, 0.0, 0.0]), 1.0), Err(ModelError::Singular));
        assert_eq!(model.propagate(&at([0.0, 0.0, 0.0]), 1.0), Err(ModelError::Singular));
        assert_eq!(model.propagate(&at([0.0, 0.0, 6299.0]), 1.0), Err(ModelError::Singular));
        // Above min_radius at the start, below it during the step: a re-entry is not silently kept.
        let falling = SVector::from([6400.0, 0.0, 0.0, -3.0, 0.0, 0.0]);
        assert!(model.propagate(&falling, 20.0).is_ok());
        assert_eq!(model.propagate(&falling, 60.0), Err(ModelError::Singular));
        // The longest gap is max_step × max_substeps = 22 000 s.
        assert!(model.propagate(&leo(), 22_000.0).is_ok());
        assert_eq!(model.propagate(&leo(), 22_000.5), Err(ModelError::TimeStepTooLarge));
        let mut nan = leo();
        nan[4] = f64::NAN;
        assert_eq!(model.propagate(&nan, 10.0), Err(ModelError::NonFinite));
        assert_eq!(model.propagate(&leo(), f64::NAN), Err(ModelError::NonFinite));
        assert_eq!(model.propagate(&leo(), -1.0), Err(ModelError::NonFinite));
        let mut inf = leo();
        inf[0] = f64::INFINITY;
        assert_eq!(model.propagate(&inf, 10.0), Err(ModelError::NonFinite));
    }

    #[test]
    fn two_body_j2_validate_checks_every_parameter() {
        assert_eq!(MODEL.validate(), Ok(()));
        let ric = ProcessNoise::Ric { radial: 1e-12, in_track: 1e-10, cross_track: 1e-12 };
        assert_eq!(TwoBodyJ2::<f64>::earth(ric, 20.0, 1100).validate(), Ok(()));
        assert_eq!(TwoBodyJ2 { j2: 0.0, ..MODEL }.validate(), Ok(()));
        let bad = [
            TwoBodyJ2 { mu: 0.0, ..MODEL },
            TwoBodyJ2 { mu: f64::INFINITY, ..MODEL },
            TwoBodyJ2 { j2: -1e-3, ..MODEL },
            TwoBodyJ2 { j2: f64::NAN, ..MODEL },
            TwoBodyJ2 { radius: 0.0, ..MODEL },
            TwoBodyJ2 { min_radius: -1.0, ..MODEL },
            TwoBodyJ2 { min_radius: f64::NAN, ..MODEL },
            TwoBodyJ2 { noise: ProcessNoise::Isotropic(0.0), ..MODEL },
            TwoBodyJ2 { noise: ProcessNoise::Ric { radial: 1.0, in_track: f64::NAN, cross_track: 1.0 }, ..MODEL },
            TwoBodyJ2 { noise: ProcessNoise::Ric { radial: 1.0, in_track: 1.0, cross_track: 0.0 }, ..MODEL },
            TwoBodyJ2 { max_step: 0.0, ..MODEL },
            TwoBodyJ2 { max_step: f64::INFINITY, ..MODEL },
            TwoBodyJ2 { max_substeps: 0, ..MODEL },
        ];
        for model in bad {
            assert!(model.validate().is_err(), "{model:?} passed validation");
        }
    }

    #[test]
    fn two_body_j2_ric_noise_is_rotated_to_the_state() {
        let (qr, qi, qc) = (1.0, 4.0, 9.0);
        let model = TwoBodyJ2 { noise: ProcessNoise::Ric { radial: qr, in_track: qi, cross_track: qc }, ..MODEL };
        let dt = 10.0;
        // On the x axis moving along y: radial = x, in-track = y, cross-track = z.
        let q = model.process_noise(&SVector::from([7000.0, 0.0, 0.0, 0.0, 7.5, 0.0]), dt);
        let expected = SMatrix::<f64, 3, 3>::from_diagonal(&SVector::from([qr, qi, qc]));
        assert!((q.fixed_view::<3, 3>(3, 3) - expected * dt).amax() < 1e-12);
        assert!((q.fixed_view::<3, 3>(0, 0) - expected * (dt * dt * dt / 3.0)).amax() < 1e-9);
        assert!((q.fixed_view::<3, 3>(0, 3) - expected * (dt * dt / 2.0)).amax() < 1e-10);
        // An inclined, eccentric state: the density along r̂, the in-track and the cross-track axes is
        // q_R, q_I, q_C, and the trace is invariant.
        let x = leo();
        let q = model.process_noise(&x, 1.0).fixed_view::<3, 3>(3, 3).into_owned();
        let r_hat = x.fixed_rows::<3>(0).normalize();
        let c_hat = x.fixed_rows::<3>(0).cross(&x.fixed_rows::<3>(3)).normalize();
        let i_hat = c_hat.cross(&r_hat);
        for (axis, density) in [(r_hat, qr), (i_hat, qi), (c_hat, qc)] {
            assert!(((axis.transpose() * q * axis)[0] - density).abs() < 1e-12);
        }
        assert!((q.trace() - (qr + qi + qc)).abs() < 1e-12);
        assert!((q - q.transpose()).amax() < 1e-15);
        // A radial trajectory has no cross-track axis: the largest density on every axis.
        let q = model.process_noise(&SVector::from([7000.0, 0.0, 0.0, 1.0, 0.0, 0.0]), 1.0);
        assert_eq!(q.fixed_view::<3, 3>(3, 3).into_owned(), SMatrix::<f64, 3, 3>::identity() * qc);
        // Isotropic noise is the same in every frame.
        let q = MODEL.process_noise(&x, 1.0);
        assert_eq!(q.fixed_view::<3, 3>(3, 3).into_owned(), SMatrix::<f64, 3, 3>::identity() * 1e-12);
    }

    // Measured: f32 against f64 after 600 s, 1.6 m (LEO) and 4.7 m (GEO).
    #[test]
    fn two_body_j2_runs_in_f32() {
        let model32 = TwoBodyJ2::<f32>::earth(ProcessNoise::Isotropic(1e-12), 20.0, 1100);
        assert_eq!(model32.validate(), Ok(()));
        for x0 in [leo(), geo()] {
            let dt = 600.0;
            let p32 = model32.propagate(&x0.map(|v| v as f32), dt as f32).unwrap();
            let p64 = MODEL.propagate(&x0, dt).unwrap();
            assert!(p32.state.iter().chain(p32.transition.iter()).all(|v| v.is_finite()));
            let error = (p32.state.fixed_rows::<3>(0).map(f64::from) - p64.state.fixed_rows::<3>(0)).norm();
            assert!(error < 0.05, "f32 position differs from f64 by {error} km after {dt} s");
        }
    }
}
