//! The reused cores of a partitioned tracker: a pool of boxed core trackers of the clusters' configuration,
//! leased for one step (or a few) and handed back, so that a scan allocates no core and the memory held is
//! one core per concurrent task, not one per cluster. A leased core is always loaded before it is read
//! ([`Tracker::resume`] or [`Tracker::reset`]), so what it held before leaves no trace.

use super::cluster::Rest;
use super::error::{ClusterId, PartitionError};
use super::hypotheses::{self, Hypothesis};
use std::ops::{Deref, DerefMut};
use std::sync::Mutex;
use tracker_core::model::{MeasurementModel, MotionModel};
use tracker_core::{Config, Tracker};

type Core<
    M,
    G,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
> = Tracker<f64, M, G, S, D, H, N, Z, K, B>;

/// The pool: the configuration every cluster's core has, and the cores not leased.
pub struct Cores<
    M,
    G,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
> {
    config: Config<f64, M, G, S, B>,
    free: Mutex<Vec<Box<Core<M, G, S, D, H, N, Z, K, B>>>>,
}

impl<
    M: Clone,
    G: Clone,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
> Clone for Cores<M, G, S, D, H, N, Z, K, B>
{
    /// A pool of the same configuration, with no core yet.
    fn clone(&self) -> Self {
        Self { config: self.config.clone(), free: Mutex::new(vec![]) }
    }
}

/// A core on loan from a [`Cores`], handed back when dropped.
pub struct Lease<
    'a,
    M,
    G,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
> {
    core: Option<Box<Core<M, G, S, D, H, N, Z, K, B>>>,
    free: &'a Mutex<Vec<Box<Core<M, G, S, D, H, N, Z, K, B>>>>,
}

impl<
    M,
    G,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
> Drop for Lease<'_, M, G, S, D, H, N, Z, K, B>
{
    fn drop(&mut self) {
        if let Some(core) = self.core.take() {
            self.free.lock().unwrap_or_else(|poisoned| poisoned.into_inner()).push(core);
        }
    }
}

impl<
    M,
    G,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
> Deref for Lease<'_, M, G, S, D, H, N, Z, K, B>
{
    type Target = Core<M, G, S, D, H, N, Z, K, B>;
    fn deref(&self) -> &Self::Target {
        self.core.as_deref().expect("a lease holds its core until dropped")
    }
}

impl<
    M,
    G,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
> DerefMut for Lease<'_, M, G, S, D, H, N, Z, K, B>
{
    fn deref_mut(&mut self) -> &mut Self::Target {
        self.core.as_deref_mut().expect("a lease holds its core until dropped")
    }
}

impl<
    M,
    G,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
> Cores<M, G, S, D, H, N, Z, K, B>
where
    M: MotionModel<f64, S> + Clone,
    G: MeasurementModel<f64, S, D> + Clone,
{
    /// An empty pool of cores of `config`.
    pub fn new(config: Config<f64, M, G, S, B>) -> Self {
        Self { config, free: Mutex::new(vec![]) }
    }

    /// The configuration of every core of the pool.
    pub fn config(&self) -> &Config<f64, M, G, S, B> {
        &self.config
    }

    /// How many cores the pool has made so far (all handed back between scans).
    pub fn made(&self) -> usize {
        self.free.lock().unwrap_or_else(|poisoned| poisoned.into_inner()).len()
    }

    /// A core on loan: a free one, or a new one when every core is out.
    pub fn lease(&self) -> Lease<'_, M, G, S, D, H, N, Z, K, B> {
        let free = self.free.lock().unwrap_or_else(|poisoned| poisoned.into_inner()).pop();
        let core = free.unwrap_or_else(|| Box::new(Core::empty(self.config.clone())));
        Lease { core: Some(core), free: &self.free }
    }
}

/// Loads cluster `id`'s `rest` into `core`.
///
/// # Errors
/// [`PartitionError::Rebuild`] when the core refuses it (not for a rest read from a core of the pool).
pub fn load<
    M,
    G,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
>(
    core: &mut Core<M, G, S, D, H, N, Z, K, B>,
    id: ClusterId,
    rest: &Rest<S, N>,
) -> Result<(), PartitionError>
where
    M: MotionModel<f64, S>,
    G: MeasurementModel<f64, S, D>,
{
    core.resume(&rest.view()).map_err(|error| PartitionError::Rebuild { cluster: id, error })
}

/// The rest of a cluster `id` holding `set` at `time` (the core's prior of it), loaded through `core`,
/// which then holds it.
///
/// # Errors
/// [`PartitionError::Rebuild`] when the core refuses the set (its capacities).
pub fn build<
    M,
    G,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
>(
    core: &mut Core<M, G, S, D, H, N, Z, K, B>,
    id: ClusterId,
    set: &[Hypothesis<S>],
    time: f64,
) -> Result<Rest<S, N>, PartitionError>
where
    M: MotionModel<f64, S>,
    G: MeasurementModel<f64, S, D>,
{
    core.reset(&hypotheses::as_prior(set), time).map_err(|error| PartitionError::Rebuild { cluster: id, error })?;
    Rest::of(id, core)
}
