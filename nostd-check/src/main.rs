//! Links tracker-core into a `#![no_std]`, `#![no_main]` binary with no global allocator (any use of
//! `alloc` would fail to link) and tracks two objects through a few scans, in one tracker and in a pool of
//! clusters. Exits 0 when both find both objects, 1 otherwise.
#![no_std]
#![no_main]

use core::fmt::Write;
use nalgebra::{SMatrix, SVector};
use tracker_core::config::{ChildGeneration, StoreOverflow};
use tracker_core::partition::ClusterPool;
use tracker_core::sensor::ScanGeometry;
use tracker_core::{
    BirthModel, Config, ConstantVelocity, Gaussian, LinearTracker, PositionMeasurement, PriorObject, Region, Sensor,
    TrackLabel,
};

#[link(name = "c")]
unsafe extern "C" {
    fn write(fd: i32, buf: *const u8, count: usize) -> isize;
}

/// A fixed buffer that implements `fmt::Write`, flushed to stdout.
struct Out {
    buf: [u8; 256],
    len: usize,
}

impl Write for Out {
    fn write_str(&mut self, s: &str) -> core::fmt::Result {
        let bytes = s.as_bytes();
        let end = (self.len + bytes.len()).min(self.buf.len());
        self.buf[self.len..end].copy_from_slice(&bytes[..end - self.len]);
        self.len = end;
        Ok(())
    }
}

impl Out {
    fn flush(&mut self) {
        // SAFETY: the pointer and length describe initialised bytes of `self.buf`.
        unsafe { write(1, self.buf.as_ptr(), self.len) };
        self.len = 0;
    }
}

/// The precompiled `core` for this host target was built with unwinding and references this symbol;
/// with `panic = "abort"` it is never called.
#[unsafe(no_mangle)]
extern "C" fn rust_eh_personality() {}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {}
}

type Tracker = LinearTracker<f64, 16, 4, 4, 32, 1>;
/// A pool of at most 4 clusters of the same capacities, scans of at most 8 measurements.
type Pool = ClusterPool<f64, ConstantVelocity<f64>, PositionMeasurement<f64>, 4, 2, 16, 4, 4, 32, 1, 4, 8>;

fn run() -> Result<(f64, f64), tracker_core::StepError> {
    let config = Config {
        motion: ConstantVelocity { acceleration_noise: 0.01 },
        measurement: PositionMeasurement::isotropic(0.3),
        sensor: Sensor {
            detection_probability: 0.9,
            clutter_rate: 1.0,
            field_of_view: Region::Rectangle { min: [-50.0, -50.0], max: [50.0, 50.0] },
        },
        birth: BirthModel::none(),
        death_probability: 0.01,
        gate: Some(16.0),
        children: ChildGeneration::Exhaustive { max_children_per_scan: 100_000 },
        selection: tracker_core::config::Selection::TopWeight,
        store_overflow: StoreOverflow::PruneChildren,
        numerical_failure: Default::default(),
        track_loss: Default::default(),
        seed: 1,
    };
    let objects = [
        Gaussian { mean: SVector::from([0.0, 0.0, 1.0, 0.0]), covariance: SMatrix::identity() },
        Gaussian { mean: SVector::from([0.0, 5.0, 1.0, -0.5]), covariance: SMatrix::identity() },
    ];
    let mut tracker =
        Tracker::with_objects(config.clone(), &objects, 0.0).map_err(|_| tracker_core::StepError::NoViableChild)?;
    // The same objects and scans in a pool of clusters (the partitioned tracker in fixed memory).
    let labelled = [0, 1].map(|i| PriorObject { label: TrackLabel(i), state: objects[i as usize] });
    let mut pool = Pool::new(config, &labelled, 0.0, 0.0).map_err(|_| tracker_core::StepError::NoViableChild)?;
    for k in 1..=6 {
        let t = k as f64;
        let zs =
            [SVector::from([t + 0.1, 0.05]), SVector::from([t - 0.05, 5.0 - 0.5 * t]), SVector::from([-20.0, 30.0])];
        tracker.step(t, &zs)?;
        pool.step(&ScanGeometry::single(t), &zs).map_err(|_| tracker_core::StepError::NoViableChild)?;
    }
    let mut pooled = 0.0;
    for i in 0..pool.clusters().len() {
        if let Ok(Some(cluster)) = pool.load(i) {
            pooled += cluster.expected_cardinality();
        }
    }
    Ok((tracker.expected_cardinality(), pooled))
}

#[unsafe(no_mangle)]
pub extern "C" fn main(_argc: i32, _argv: *const *const u8) -> i32 {
    let mut out = Out { buf: [0; 256], len: 0 };
    let (size, pool_size) = (core::mem::size_of::<Tracker>(), core::mem::size_of::<Pool>());
    match run() {
        Ok((cardinality, pooled)) if (cardinality - 2.0).abs() < 0.1 && (pooled - 2.0).abs() < 0.1 => {
            let _ = writeln!(
                out,
                "nostd-check: ok, expected cardinality {cardinality:.4} (pool {pooled:.4}), size_of tracker {size} \
                 bytes, pool {pool_size} bytes"
            );
            out.flush();
            0
        }
        Ok((cardinality, pooled)) => {
            let _ = writeln!(out, "nostd-check: FAILED, expected cardinality {cardinality:.4} (pool {pooled:.4})");
            out.flush();
            1
        }
        Err(_) => {
            let _ = writeln!(out, "nostd-check: FAILED, step error");
            out.flush();
            1
        }
    }
}
