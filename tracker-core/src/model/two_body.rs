//! Planar two-body (Keplerian) motion: state (x, y, vx, vy) with r̈ = −μ r / |r|³.
//!
//! The state and its transition matrix Φ are integrated together by classical fixed-step RK4 on the
//! variational equations Φ̇ = A(x) Φ, with A = [[0, I], [G, 0]] and the gravity gradient
//! G = μ (3 r rᵀ / |r|⁵ − I / |r|³). A time step `dt` is split into `ceil(dt / max_step)` equal sub-steps;
//! more than `max_substeps` is an error, which bounds the cost of one prediction. Process noise is white
//! acceleration noise, as for constant velocity.
//!
//! Guards: a propagation is an error, never an absurd state, when
//! - the object is at the centre (|r| = 0): [`ModelError::Singular`];
//! - a state, or any RK4 stage, is closer to the centre than `min_radius` (inside the central body):
//!   [`ModelError::InsideBody`];
//! - a sub-step h is too long for the local gravity, h² μ / |r|³ > 1 at some stage (h longer than
//!   1/(2π) of the period of a circular orbit at that radius: RK4 cannot follow a close approach, and
//!   a start at |r| = 10⁻³ km from the Earth's centre would otherwise come out at 10¹⁴ km):
//!   [`ModelError::Unresolved`];
//! - the specific energy E = |v|²/2 − μ/|r| changed by more than its scale |v₀|²/2 + μ/|r₀| over the
//!   propagation (exact motion conserves it; the integrator blew up): [`ModelError::Unresolved`].
//!
//! The guards only reject: an accepted propagation is the same bits as without them.

use super::{ModelError, MotionModel, Propagation, white_acceleration_noise};
use crate::real::{Real, c, sqrt};
use nalgebra::{SMatrix, SVector};

/// The planar two-body motion model.
///
/// # Examples
/// A circular orbit returns to its start after one period:
/// ```
/// use tracker_core::model::{MotionModel, TwoBody};
/// use nalgebra::SVector;
/// let mu = 398_600.441_8_f64; // km³/s²
/// let r = 7000.0;
/// let v = (mu / r).sqrt();
/// let period = 2.0 * core::f64::consts::PI * (r * r * r / mu).sqrt();
/// let model = TwoBody { mu, acceleration_noise: 1e-9, max_step: 10.0, max_substeps: 10_000, min_radius: 6378.137 };
/// let p = model.propagate(&SVector::from([r, 0.0, 0.0, v]), period).unwrap();
/// assert!((p.state[0] - r).abs() < 1e-3 && p.state[1].abs() < 1e-3);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TwoBody<T> {
    /// Gravitational parameter μ (length³ / s²; 398600.4418 km³/s² for the Earth).
    pub mu: T,
    /// Power spectral density q of the white acceleration noise (length² / s³).
    pub acceleration_noise: T,
    /// Largest RK4 sub-step (s).
    pub max_step: T,
    /// Most sub-steps one propagation may take; a longer `dt` is [`ModelError::TimeStepTooLarge`].
    pub max_substeps: u32,
    /// Smallest allowed distance from the centre (length; the central body's radius, 6378.137 km for
    /// the Earth). A state or an RK4 stage closer is [`ModelError::InsideBody`]. 0
    /// ([`TwoBody::DEFAULT_MIN_RADIUS`], the default when the field is absent from a serialised
    /// configuration) treats the body as a point mass.
    #[cfg_attr(feature = "serde", serde(default))]
    pub min_radius: T,
}

impl<T: Real> TwoBody<T> {
    /// The default `min_radius`: 0, a point mass (only the centre itself and unresolved close approaches
    /// are errors).
    pub const DEFAULT_MIN_RADIUS: T = T::ZERO;

    /// Time derivative of the state and of Φ: (ẋ, Φ̇) = (f(x), A(x) Φ), at a stage of a sub-step with
    /// h² μ = `h2_mu`, after the guards of the module documentation.
    fn derivative(
        &self,
        state: &SVector<T, 4>,
        phi: &SMatrix<T, 4, 4>,
        h2_mu: T,
    ) -> Result<(SVector<T, 4>, SMatrix<T, 4, 4>), ModelError> {
        let (x, y) = (state[0], state[1]);
        let r2 = x * x + y * y;
        if !(r2 > T::zero()) || !r2.is_finite_value() {
            return Err(ModelError::Singular);
        }
        if r2 < self.min_radius * self.min_radius {
            return Err(ModelError::InsideBody);
        }
        let r = sqrt(r2);
        let inv_r3 = T::one() / (r2 * r);
        // h² μ / |r|³ ≤ 1: the sub-step resolves the local dynamics.
        if !(h2_mu * inv_r3 <= T::one()) {
            return Err(ModelError::Unresolved);
        }
        let inv_r5 = inv_r3 / r2;
        // a = −μ r / |r|³
        let derivative = SVector::from([state[2], state[3], -self.mu * x * inv_r3, -self.mu * y * inv_r3]);
        // G = μ (3 r rᵀ / |r|⁵ − I / |r|³)
        let three = c::<T>(3.0);
        let gxx = self.mu * (three * x * x * inv_r5 - inv_r3);
        let gxy = self.mu * (three * x * y * inv_r5);
        let gyy = self.mu * (three * y * y * inv_r5 - inv_r3);
        let mut phi_dot = SMatrix::<T, 4, 4>::zeros();
        for col in 0..4 {
            // Rows 0-1: velocity rows of Φ; rows 2-3: G times the position rows of Φ.
            phi_dot[(0, col)] = phi[(2, col)];
            phi_dot[(1, col)] = phi[(3, col)];
            phi_dot[(2, col)] = gxx * phi[(0, col)] + gxy * phi[(1, col)];
            phi_dot[(3, col)] = gxy * phi[(0, col)] + gyy * phi[(1, col)];
        }
        Ok((derivative, phi_dot))
    }
}

impl<T: Real> TwoBody<T> {
    /// (|v|²/2, μ/|r|): the specific energy is their difference.
    fn energy_terms(&self, state: &SVector<T, 4>) -> (T, T) {
        let r = sqrt(state[0] * state[0] + state[1] * state[1]);
        (c::<T>(0.5) * (state[2] * state[2] + state[3] * state[3]), self.mu / r)
    }
}

impl<T: Real> MotionModel<T, 4> for TwoBody<T> {
    fn propagate(&self, state: &SVector<T, 4>, dt: T) -> Result<Propagation<T, 4>, ModelError> {
        let (steps, h) = super::rk4_substeps(dt, self.max_step, self.max_substeps)?;
        let half = c::<T>(0.5);
        let sixth = T::one() / c(6.0);
        let two = c::<T>(2.0);

        let h2_mu = h * h * self.mu;

        let mut x = *state;
        let mut phi = SMatrix::<T, 4, 4>::identity();
        for _ in 0..steps {
            let (k1x, k1p) = self.derivative(&x, &phi, h2_mu)?;
            let (k2x, k2p) = self.derivative(&(x + k1x * (h * half)), &(phi + k1p * (h * half)), h2_mu)?;
            let (k3x, k3p) = self.derivative(&(x + k2x * (h * half)), &(phi + k2p * (h * half)), h2_mu)?;
            let (k4x, k4p) = self.derivative(&(x + k3x * h), &(phi + k3p * h), h2_mu)?;
            x += (k1x + k2x * two + k3x * two + k4x) * (h * sixth);
            phi += (k1p + k2p * two + k3p * two + k4p) * (h * sixth);
        }
        if !x.iter().chain(phi.iter()).all(|v| v.is_finite_value()) {
            return Err(ModelError::NonFinite);
        }
        // The first stage accepted both states' radii (|r| > 0), so the energies are finite or the
        // comparison fails.
        let (kinetic, potential) = self.energy_terms(state);
        let (kinetic_after, potential_after) = self.energy_terms(&x);
        let change = (kinetic_after - potential_after) - (kinetic - potential);
        if !(change.abs() <= kinetic + potential) {
            return Err(ModelError::Unresolved);
        }
        if x[0] * x[0] + x[1] * x[1] < self.min_radius * self.min_radius {
            return Err(ModelError::InsideBody);
        }
        Ok(Propagation { state: x, transition: phi })
    }

    fn process_noise(&self, _state: &SVector<T, 4>, dt: T) -> SMatrix<T, 4, 4> {
        white_acceleration_noise(self.acceleration_noise, dt)
    }

    fn validate(&self) -> Result<(), &'static str> {
        if !(self.mu.is_finite_value() && self.mu > T::zero()) {
            return Err("two-body: mu must be finite and > 0");
        }
        if !(self.acceleration_noise.is_finite_value() && self.acceleration_noise > T::zero()) {
            return Err("two-body: acceleration_noise must be finite and > 0 (Q positive definite)");
        }
        if !(self.max_step.is_finite_value() && self.max_step > T::zero()) {
            return Err("two-body: max_step must be finite and > 0");
        }
        if self.max_substeps == 0 || self.max_substeps > super::MAX_RK4_SUBSTEPS {
            return Err("two-body: max_substeps must be in 1..=1,000,000");
        }
        if !(self.min_radius.is_finite_value() && self.min_radius >= T::zero()) {
            return Err("two-body: min_radius must be finite and >= 0");
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

    fn leo() -> (TwoBody<f64>, SVector<f64, 4>) {
        let mu = 398_600.441_8;
        let r: f64 = 7000.0;
        let v = (mu / r).sqrt();
        (
            TwoBody { mu, acceleration_noise: 1e-9, max_step: 10.0, max_substeps: 1000, min_radius: 6378.137 },
            SVector::from([r, 0.0, 0.0, v * 1.05]),
        )
    }

    #[test]
    fn transition_matrix_matches_finite_differences() {
        let (model, x0) = leo();
        let dt = 120.0;
        let base = model.propagate(&x0, dt).unwrap();
        for j in 0..4 {
            let eps = if j < 2 { 1e-3 } else { 1e-6 };
            let mut plus = x0;
            plus[j] += eps;
            let mut minus = x0;
            minus[j] -= eps;
            let column =
                (model.propagate(&plus, dt).unwrap().state - model.propagate(&minus, dt).unwrap().state) / (2.0 * eps);
            for i in 0..4 {
                let expected = column[i];
                let got = base.transition[(i, j)];
                assert!(
                    (got - expected).abs() <= 1e-6 * (1.0 + expected.abs()),
                    "Φ[{i},{j}] = {got}, finite difference {expected}"
                );
            }
        }
    }

    #[test]
    fn energy_is_conserved_over_an_hour() {
        let (model, x0) = leo();
        let energy =
            |x: &SVector<f64, 4>| 0.5 * (x[2] * x[2] + x[3] * x[3]) - model.mu / (x[0] * x[0] + x[1] * x[1]).sqrt();
        let x1 = model.propagate(&x0, 3600.0).unwrap().state;
        assert!((energy(&x1) - energy(&x0)).abs() < 1e-8 * energy(&x0).abs());
    }

    #[test]
    fn too_long_a_step_is_an_error() {
        let (model, x0) = leo();
        assert_eq!(model.propagate(&x0, 10.0 * 1001.0), Err(ModelError::TimeStepTooLarge));
        assert!(model.propagate(&x0, 10.0 * 1000.0).is_ok());
    }

    #[test]
    fn origin_is_singular() {
        let (model, _) = leo();
        assert_eq!(model.propagate(&SVector::from([0.0, 0.0, 1.0, 0.0]), 1.0), Err(ModelError::Singular));
    }

    fn point_mass() -> TwoBody<f64> {
        TwoBody { min_radius: TwoBody::DEFAULT_MIN_RADIUS, ..leo().0 }
    }

    /// Issue 17: a start at 10⁻³ km from the centre used to come out at x = −2·10¹⁴ with no error.
    #[test]
    fn start_next_to_the_centre_is_an_error() {
        for dt in [1.0, 10.0, 60.0] {
            for speed in [0.0, 1.0, 7.5] {
                let x0 = SVector::from([1e-3, 0.0, 0.0, speed]);
                assert_eq!(point_mass().propagate(&x0, dt), Err(ModelError::Unresolved), "dt {dt}, speed {speed}");
                assert_eq!(leo().0.propagate(&x0, dt), Err(ModelError::InsideBody));
                let centre = SVector::from([0.0, 0.0, speed, 0.0]);
                assert_eq!(point_mass().propagate(&centre, dt), Err(ModelError::Singular));
            }
        }
        let f32_model = TwoBody::<f32> {
            mu: 398_600.44,
            acceleration_noise: 1e-9,
            max_step: 20.0,
            max_substeps: 100,
            min_radius: 0.0,
        };
        assert_eq!(f32_model.propagate(&SVector::from([1e-3, 0.0, 0.0, 0.0]), 60.0), Err(ModelError::Unresolved));
    }

    #[test]
    fn entering_the_body_is_an_error() {
        let (model, _) = leo();
        // Falling straight down from 7000 km: inside 6378 km within about 5 minutes.
        let falling = SVector::from([7000.0, 0.0, -2.0, 0.0]);
        assert!(model.propagate(&falling, 60.0).is_ok());
        assert_eq!(model.propagate(&falling, 600.0), Err(ModelError::InsideBody));
        assert_eq!(model.propagate(&SVector::from([6000.0, 0.0, 0.0, 8.0]), 1.0), Err(ModelError::InsideBody));
    }

    /// Seeded random states between 10⁻⁶ km and 10⁸ km with random velocities, with and without a
    /// body: every `Ok` propagation is finite, outside the body and conserves energy to within its
    /// scale; every failure is typed.
    #[test]
    fn random_states_propagate_or_fail_typed() {
        use rand_core::{Rng, SeedableRng};
        let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1);
        let mut uniform = || (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        let mut accepted = 0;
        for draw in 0..600 {
            let model = if draw % 2 == 0 { point_mass() } else { leo().0 };
            let (r, angle) = (10f64.powf(-6.0 + 14.0 * uniform()), core::f64::consts::TAU * uniform());
            let speed = (model.mu / r).sqrt() * 2.0 * uniform();
            let heading = core::f64::consts::TAU * uniform();
            let x0 = SVector::from([r * angle.cos(), r * angle.sin(), speed * heading.cos(), speed * heading.sin()]);
            let dt = 10f64.powf(-1.0 + 4.0 * uniform());
            match model.propagate(&x0, dt) {
                Ok(p) => {
                    accepted += 1;
                    let (k0, u0) = model.energy_terms(&x0);
                    let (k1, u1) = model.energy_terms(&p.state);
                    assert!(((k1 - u1) - (k0 - u0)).abs() <= k0 + u0, "{x0:?} -> {:?}", p.state);
                    assert!(p.state.iter().chain(p.transition.iter()).all(|v| v.is_finite()));
                    assert!(p.state.xy().norm() >= model.min_radius);
                }
                Err(e) => {
                    assert!(matches!(e, ModelError::Unresolved | ModelError::InsideBody | ModelError::TimeStepTooLarge))
                }
            }
        }
        assert!(accepted > 100, "{accepted}");
    }

    #[test]
    fn min_radius_is_validated() {
        for bad in [-1.0, f64::NAN, f64::INFINITY] {
            assert!(TwoBody { min_radius: bad, ..leo().0 }.validate().is_err());
        }
        assert_eq!(point_mass().validate(), Ok(()));
        assert_eq!(leo().0.validate(), Ok(()));
    }

    #[cfg(feature = "serde")]
    #[test]
    fn min_radius_defaults_to_a_point_mass() {
        let text = r#"{"mu":398600.0,"acceleration_noise":1e-13,"max_step":20.0,"max_substeps":100}"#;
        let model: TwoBody<f64> = serde_json::from_str(text).unwrap();
        assert_eq!(model.min_radius, TwoBody::<f64>::DEFAULT_MIN_RADIUS);
    }
}
