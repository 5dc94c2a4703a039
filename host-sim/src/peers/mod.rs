//! The peers R-FISST is checked and compared against, on the host: the unbounded [`reference`] tracker, the
//! [`murty`] k-best assignment and the [`gibbs`] association sampler (both over the linear [`assignment`]
//! solver), and [`sampler_check`], which scores the core's sampler against the reference's exact posterior.

pub mod assignment;
pub mod gibbs;
pub mod murty;
pub mod reference;
pub mod sampler_check;
