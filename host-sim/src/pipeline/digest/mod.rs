//! `host-sim digest`: the QEMU firmware's digest, replayed on the host.

pub mod orbital;
pub mod planar;
