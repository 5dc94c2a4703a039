//! The bounded Metropolis sampler of child hypotheses (R-FISST, paper 003 §III, paper 004 §III-B).
//!
//! Heads up: read docs/maths.md §7.6 before changing anything here. The chain only *searches*; it never
//! estimates weights. Every child it offers carries its exact log-weight, recomputed from the
//! association matrix, and the tracker renormalises over all offered children of all parents.
//!
//! One chain runs on one [`AssociationMatrix`] (a parent and a birth/death event):
//!
//! - **State**: an association vector a (one column or clutter per measurement, no column twice) and its
//!   running log-score Σ δ. Required columns (p_D = 1, or a birth that must be detected) that are left
//!   unassigned cost a penalty of [`REQUIRED_PENALTY`] nats in the chain's target, so the chain can cross
//!   infeasible states; only feasible states are recorded.
//! - **Start**: the mode of the target, found exactly by a shortest augmenting path assignment
//!   ([`crate::optimal`], at most R (M + 1) M reduced costs for R rows and M columns), and recorded:
//!   every chain offers its matrix's best child, whatever its mixing. Then every move-or-swap neighbour
//!   of the mode (at most R (M + 1)) is recorded, the likeliest candidates for the next best children,
//!   and the chain starts from the mode. Should that search fail (only a NaN entry can make it),
//!   greedy (repeatedly the best remaining measurement-object pair that beats clutter, then each
//!   unassigned required column takes its best free measurement) and hill climbing by improving
//!   move-or-swap moves take its place.
//! - **Proposals** (each O(1): one random number picks a row and a column):
//!   - [`Proposal::Paper`]: paper 003's move. The row takes the column; a measurement that held the
//!     column goes to clutter. Not symmetric (undoing a conflict needs two moves), which is harmless
//!     because weights are exact.
//!   - [`Proposal::MoveOrSwap`]: the row takes the column; a measurement that held it takes the row's
//!     old column (or clutter) instead. Symmetric, so Metropolis acceptance is exact detailed balance; it
//!     moves along ridges of good associations instead of falling into clutter.
//!   - [`Proposal::Informed`] (default): as `MoveOrSwap`, but every other step (the chain's even-numbered
//!     moves, in a fixed alternation) draws the column from the row's own distribution q_j(c) ∝ e^{δ_jc}
//!     (clutter e⁰) through a per-row cumulative table built once per matrix (a guide table starts the
//!     search: usually one comparison per step). Such a move to a free column is always accepted, so the
//!     chain rarely wastes a step on an impossible or poor column; the uniform steps in between keep
//!     columns of small weight reachable. Each kind of step leaves the target invariant, so the
//!     alternation does too (docs/maths.md §7.5).
//! - **Acceptance**: Metropolis–Hastings, min(1, e^Δ q_reverse / q_forward), with Δ the O(1) change of
//!   the log-score; the uniform of the test comes from the step's one random draw (the row's
//!   multiply-shift remainder).
//! - **Budget**: `burn_in` steps unrecorded, then `steps` recorded steps; every feasible state visited
//!   after burn-in (and the greedy start) goes to a [`BestChildren`] set that keeps the best `C`
//!   distinct children, with duplicates found in O(1) through an incremental Zobrist-style hash.
//!   At the end the set's children are offered, each once, with exact weights.

mod best;
mod chain;

pub use best::{BestChildren, association_hash};
pub use chain::MetropolisSampler;

/// Penalty (nats) per unassigned required column in the chain's target.
pub const REQUIRED_PENALTY: f64 = 64.0;

/// The proposal of the Metropolis chain.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Proposal {
    /// Paper 003: a random row takes a random column; a conflicting measurement goes to clutter.
    Paper,
    /// A random row takes a random column; a conflicting measurement takes the row's old column.
    MoveOrSwap,
    /// As `MoveOrSwap`, but every other step (in a fixed alternation) draws the column in proportion to
    /// the row's entries e^δ (clutter e⁰), so good associations are proposed often; the
    /// Metropolis–Hastings ratio corrects for it exactly.
    #[default]
    Informed,
}

/// Budget and moves of the sampler.
///
/// # Examples
/// A smaller budget and every cluster sampled, in a `const`; the tracker reports the steps its chains took:
/// ```
/// # use nalgebra::SVector;
/// # use tracker_core::{Config, LinearTracker};
/// # let (config, object) = (tracker_core::examples::config(), tracker_core::examples::object());
/// use tracker_core::ChildGeneration;
/// use tracker_core::sampler::SamplerConfig;
/// const QUICK: SamplerConfig =
///     SamplerConfig { burn_in: 10, steps: 200, exhaustive_limit: 0, ..SamplerConfig::DEFAULT };
/// assert_eq!(SamplerConfig::default(), SamplerConfig::DEFAULT);
///
/// let config = Config { children: ChildGeneration::Sampled(QUICK), ..config };
/// let mut tracker = LinearTracker::<f64, 8, 4, 4, 16, 1>::with_objects(config, &[object], 0.0)?;
/// let report = tracker.step(1.0, &[SVector::from([1.0, 0.0]), SVector::from([-3.0, 2.0])])?;
/// assert_eq!(report.sampler_steps, 10 + 200); // one matrix, one cluster, one chain
/// assert_eq!(report.hypotheses, 3); // all three children were found
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SamplerConfig {
    /// Steps per chain before recording.
    pub burn_in: u32,
    /// Recorded steps per chain.
    pub steps: u32,
    /// The proposal.
    pub proposal: Proposal,
    /// Split each matrix into independent clusters by gating and combine the clusters' best children.
    pub clusters: bool,
    /// With `clusters`, enumerate a cluster exhaustively when A_n(m) of its n columns and m rows is at most
    /// this; sample larger ones. 0 samples every cluster.
    pub exhaustive_limit: u64,
    /// Start each chain at the exact mode of its target and record the mode's neighbours
    /// ([`crate::optimal`]); `false` starts greedily and climbs, as without it.
    pub exact_start: bool,
}

impl Default for SamplerConfig {
    fn default() -> Self {
        Self::DEFAULT
    }
}

impl SamplerConfig {
    /// The largest accepted `burn_in + steps` of one chain (10⁶; the papers use 10⁵). A scan runs at most
    /// H (1 + B + N) chains (one per parent and event), so this bounds its moves.
    pub const MAX_CHAIN_STEPS: u32 = 1_000_000;

    /// The largest accepted `exhaustive_limit` (10⁶ associations enumerated per cluster).
    pub const MAX_EXHAUSTIVE_LIMIT: u64 = 1_000_000;

    /// The burn-in and recorded moves of a chain allowed at most `max_moves` moves: the configured ones
    /// when they fit, else both scaled down in proportion (burn-in rounded down).
    ///
    /// # Examples
    /// ```
    /// use tracker_core::sampler::SamplerConfig;
    /// let config = SamplerConfig { burn_in: 100, steps: 2_000, ..SamplerConfig::DEFAULT };
    /// assert_eq!(config.moves_within(u64::MAX), (100, 2_000));
    /// assert_eq!(config.moves_within(210), (10, 200));
    /// assert_eq!(config.moves_within(0), (0, 0));
    /// ```
    pub fn moves_within(&self, max_moves: u64) -> (u32, u32) {
        let total = u64::from(self.burn_in) + u64::from(self.steps);
        if total <= max_moves {
            return (self.burn_in, self.steps);
        }
        // max_moves < total ≤ 2³³, so the product fits in u64 and both parts fit in u32.
        let burn_in = u64::from(self.burn_in) * max_moves / total;
        (burn_in as u32, (max_moves - burn_in) as u32)
    }

    /// Checks the work limits: at least one recorded step, `burn_in + steps` ≤
    /// [`SamplerConfig::MAX_CHAIN_STEPS`], `exhaustive_limit` ≤ [`SamplerConfig::MAX_EXHAUSTIVE_LIMIT`].
    ///
    /// # Errors
    /// [`crate::ConfigError::ChildBudget`] for zero steps, [`crate::ConfigError::AboveLimit`] naming the
    /// parameter above its limit.
    ///
    /// # Examples
    /// ```
    /// use tracker_core::{ConfigError, sampler::SamplerConfig};
    /// assert_eq!(SamplerConfig::DEFAULT.check(), Ok(()));
    /// let endless = SamplerConfig { steps: u32::MAX, ..SamplerConfig::DEFAULT };
    /// assert!(matches!(endless.check(), Err(ConfigError::AboveLimit { parameter: "sampler burn_in + steps", .. })));
    /// ```
    pub fn check(&self) -> Result<(), crate::ConfigError> {
        if self.steps == 0 {
            return Err(crate::ConfigError::ChildBudget);
        }
        if u64::from(self.burn_in) + u64::from(self.steps) > u64::from(Self::MAX_CHAIN_STEPS) {
            let limit = u64::from(Self::MAX_CHAIN_STEPS);
            return Err(crate::ConfigError::AboveLimit { parameter: "sampler burn_in + steps", limit });
        }
        if self.exhaustive_limit > Self::MAX_EXHAUSTIVE_LIMIT {
            let limit = Self::MAX_EXHAUSTIVE_LIMIT;
            return Err(crate::ConfigError::AboveLimit { parameter: "sampler exhaustive_limit", limit });
        }
        Ok(())
    }

    /// The default budget and moves (also usable in a `const` context).
    pub const DEFAULT: Self = Self {
        burn_in: 100,
        steps: 2_000,
        proposal: Proposal::Informed,
        clusters: true,
        exhaustive_limit: 1_000,
        exact_start: true,
    };
}
