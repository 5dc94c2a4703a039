//! Prints `core::mem::size_of` of the default configurations' trackers.
//!
//! `cargo run -p tracker-core --example sizes`
use tracker_core::{NetworkTracker, OpticalTracker, RadarTracker, SsaTracker, ssa_caps};

fn main() {
    println!(
        "SsaTracker caps: H = {}, N = {}, Z = {}, K = {}, B = {}",
        ssa_caps::HYPOTHESES,
        ssa_caps::OBJECTS,
        ssa_caps::MEASUREMENTS,
        ssa_caps::TRACKS,
        ssa_caps::BIRTH_CELLS
    );
    println!("size_of::<SsaTracker<f64>>() = {} bytes", core::mem::size_of::<SsaTracker<f64>>());
    println!("size_of::<SsaTracker<f32>>() = {} bytes", core::mem::size_of::<SsaTracker<f32>>());
    println!("3-D trackers: the same caps with K = {} and C = {} sensors", ssa_caps::TRACKS_3D, ssa_caps::SENSORS);
    println!("size_of::<RadarTracker<f64>>() = {} bytes", core::mem::size_of::<RadarTracker<f64>>());
    println!("size_of::<RadarTracker<f32>>() = {} bytes", core::mem::size_of::<RadarTracker<f32>>());
    println!("size_of::<OpticalTracker<f64>>() = {} bytes", core::mem::size_of::<OpticalTracker<f64>>());
    println!("size_of::<OpticalTracker<f32>>() = {} bytes", core::mem::size_of::<OpticalTracker<f32>>());
    println!("NetworkTracker: the 3-D caps with C = {} sensors of mixed kinds, D = 4", ssa_caps::NETWORK_SENSORS);
    println!("size_of::<NetworkTracker<f64>>() = {} bytes", core::mem::size_of::<NetworkTracker<f64>>());
    println!("size_of::<NetworkTracker<f32>>() = {} bytes", core::mem::size_of::<NetworkTracker<f32>>());
}
