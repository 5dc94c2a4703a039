//! Seeds of the scan's random streams: each one is derived from the configured seed with SplitMix64, so
//! a chain's draws depend only on (seed, scan, parent, event), never on what other chains drew.

use rand_core::{Rng, SeedableRng};
use rand_xoshiro::SplitMix64;

/// The first SplitMix64 output from state `value`: a well-mixed 64-bit function of it (also the cell hash
/// of a chain's association hash).
#[inline]
pub(crate) fn mix(value: u64) -> u64 {
    SplitMix64::seed_from_u64(value).next_u64()
}

/// The seed of scan number `scan` (1 for the first scan).
pub(crate) fn scan_seed(seed: u64, scan: u64) -> u64 {
    mix(seed ^ mix(scan))
}

/// The seed of the chain of one (parent, event) in a scan; `event_code` numbers the parent's events.
pub(crate) fn chain_seed(scan_seed: u64, parent: u16, event_code: u64) -> u64 {
    mix(scan_seed ^ mix((u64::from(parent) << 32) | event_code))
}

/// The seed of one cluster's chain within a matrix whose seed is `matrix_seed`.
pub(crate) fn cluster_seed(matrix_seed: u64, cluster: usize) -> u64 {
    mix(matrix_seed ^ mix(cluster as u64 + 1))
}

/// The seed of the Gumbel perturbations of a scan's selection by weight.
pub(crate) fn selection_seed(scan_seed: u64) -> u64 {
    mix(scan_seed ^ 0x5e1e_c7ed)
}

/// A SplitMix64 stream for the crate's tests: the stream their random matrices were drawn from.
#[cfg(test)]
pub(crate) fn test_stream(seed: u64) -> SplitMix64 {
    SplitMix64::seed_from_u64(seed.wrapping_add(0x9e37_79b9_7f4a_7c15))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mix_is_the_splitmix64_finaliser_of_the_advanced_state() {
        // The published SplitMix64 outputs from state 0 (the first two).
        assert_eq!(mix(0), 0xe220_a839_7b1d_cdaf);
        assert_eq!(mix(0x9e37_79b9_7f4a_7c15), 0x6e78_9e6a_a1b9_65f4);
    }
}
