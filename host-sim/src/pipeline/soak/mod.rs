//! `host-sim soak`: long runs with objects entering and leaving.

pub mod orbital;
pub mod planar;
