//! Seeded random streams for the simulator.
//!
//! Every random quantity comes from its own stream, seeded from (scenario seed, stream kind, index): an
//! object's motion noise, detections and measurement noise depend only on that object's id, and the
//! clutter of a scan only on the scan index. Adding an object therefore does not change the noise of any
//! other object. Normal variates use Box–Muller through `libm`, so a seed gives the same numbers on every
//! platform.

use nalgebra::{SMatrix, SVector};
use rand_core::{Rng, SeedableRng};
use rand_xoshiro::{SplitMix64, Xoshiro256PlusPlus};

/// What a stream is used for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stream {
    /// An object's orbit or initial state.
    Orbit = 1,
    /// An object's process noise.
    Motion = 2,
    /// An object's detections and measurement noise.
    Detection = 3,
    /// A scan's clutter.
    Clutter = 4,
    /// An object's prior estimate error.
    Prior = 5,
    /// Scenario-level choices (which objects are births, measurement order).
    Scenario = 6,
}

/// SplitMix64's first output from state `z` (its finaliser of `z` + the golden-ratio increment): spreads
/// a 64-bit key over the seed space.
fn mix(z: u64) -> u64 {
    SplitMix64::seed_from_u64(z).next_u64()
}

/// A seeded random stream.
#[derive(Debug, Clone)]
pub struct Random(Xoshiro256PlusPlus);

impl Random {
    /// The stream `kind` number `index` of scenario seed `seed`.
    pub fn stream(seed: u64, kind: Stream, index: u64) -> Self {
        Random(Xoshiro256PlusPlus::seed_from_u64(mix(mix(seed ^ mix(kind as u64)) ^ index)))
    }

    /// Uniform in [0, 1).
    pub fn uniform(&mut self) -> f64 {
        (self.0.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// Uniform in [low, high).
    pub fn between(&mut self, low: f64, high: f64) -> f64 {
        low + (high - low) * self.uniform()
    }

    /// Uniform integer in [0, n) (n > 0).
    pub fn below(&mut self, n: usize) -> usize {
        ((self.uniform() * n as f64) as usize).min(n - 1)
    }

    /// Standard normal (Box–Muller).
    pub fn normal(&mut self) -> f64 {
        let u1 = 1.0 - self.uniform(); // (0, 1]
        let u2 = self.uniform();
        libm::sqrt(-2.0 * libm::log(u1)) * libm::cos(2.0 * std::f64::consts::PI * u2)
    }

    /// A sample of N(0, covariance) (covariance symmetric positive semi-definite).
    pub fn gaussian<const D: usize>(&mut self, covariance: &SMatrix<f64, D, D>) -> SVector<f64, D> {
        let white = SVector::<f64, D>::from_fn(|_, _| self.normal());
        // Scenario validation makes every covariance here positive definite; a tiny diagonal jitter keeps
        // a semi-definite one (rounding) factorable.
        let jitter = covariance.diagonal().max().abs() * 1e-12;
        let factor =
            covariance.cholesky().or_else(|| (covariance + SMatrix::<f64, D, D>::identity() * jitter).cholesky());
        factor.map_or_else(SVector::zeros, |c| c.l() * white)
    }

    /// A Poisson variate of mean `mean` (Knuth's method; means here are small).
    pub fn poisson(&mut self, mean: f64) -> usize {
        if mean <= 0.0 {
            return 0;
        }
        let limit = libm::exp(-mean);
        let mut product = self.uniform();
        let mut count = 0;
        while product > limit && count < 10_000 {
            count += 1;
            product *= self.uniform();
        }
        count
    }

    /// Shuffles `items` (Fisher–Yates).
    pub fn shuffle<T>(&mut self, items: &mut [T]) {
        for i in (1..items.len()).rev() {
            let j = self.below(i + 1);
            items.swap(i, j);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The classic SplitMix64 of one step, written out: `mix` must give the same bits, so every stream (and
    /// every simulated scenario) is unchanged by the switch to `rand_xoshiro::SplitMix64`.
    fn classic_mix(mut z: u64) -> u64 {
        z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    #[test]
    fn mix_is_the_classic_splitmix64() {
        for z in [0, 1, 2, 6, 0x9e37_79b9_7f4a_7c15, u64::MAX - 1, u64::MAX] {
            assert_eq!(mix(z), classic_mix(z), "{z}");
        }
        let mut state = 12_345u64;
        for _ in 0..1000 {
            state = classic_mix(state);
            assert_eq!(mix(state), classic_mix(state));
        }
        // Known value: the first output of SplitMix64 seeded with 0.
        assert_eq!(mix(0), 0xe220_a839_7b1d_cdaf);
    }

    #[test]
    fn streams_are_reproducible_and_independent() {
        let a: Vec<f64> = (0..5).map(|_| Random::stream(1, Stream::Motion, 3).normal()).collect();
        assert!(a.windows(2).all(|w| w[0] == w[1]));
        let mut x = Random::stream(1, Stream::Motion, 3);
        let mut y = Random::stream(1, Stream::Motion, 4);
        assert_ne!(x.normal(), y.normal());
    }

    #[test]
    fn normal_and_poisson_moments() {
        let mut r = Random::stream(9, Stream::Scenario, 0);
        let n = 100_000;
        let samples: Vec<f64> = (0..n).map(|_| r.normal()).collect();
        let mean = samples.iter().sum::<f64>() / n as f64;
        let var = samples.iter().map(|s| (s - mean).powi(2)).sum::<f64>() / n as f64;
        assert!(mean.abs() < 0.02 && (var - 1.0).abs() < 0.02, "mean {mean} var {var}");
        let counts: Vec<usize> = (0..n).map(|_| r.poisson(2.5)).collect();
        let pmean = counts.iter().sum::<usize>() as f64 / n as f64;
        assert!((pmean - 2.5).abs() < 0.03, "poisson mean {pmean}");
    }
}
