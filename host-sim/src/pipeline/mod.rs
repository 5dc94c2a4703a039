//! One pipeline over every world: replay a scenario through a tracker, score it against the truth, write
//! the outputs; soak and digest.

pub mod digest;
pub mod orbital;
pub mod planar;
pub mod snapshot;
pub mod soak;
