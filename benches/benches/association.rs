//! The per-parent gather of the association matrix, as `Tracker::step` does it: for each of the parent's
//! N = 64 objects (all in the field of view) copy its column of δ (Z = 32 measurements) from the scan's
//! K × Z entry table (K = 256 tracks) into a fresh `AssociationMatrix` (the SSA caps, `ssa_caps`).
//! Throughput is in columns.
//!
//! `cargo bench -p benches --bench association`
use benches::{splitmix, uniform};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;
use tracker_core::association::AssociationMatrix;
use tracker_core::ssa_caps::{MEASUREMENTS as Z, OBJECTS as N, TRACKS as K};

fn association(c: &mut Criterion) {
    let mut state = 3u64;
    // The scan's entry table: δ for every (track, measurement), some outside the gate.
    let entries: Vec<[f64; Z]> = (0..K)
        .map(|_| {
            std::array::from_fn(|_| {
                let u = uniform(&mut state);
                if u < 0.5 { f64::NEG_INFINITY } else { 20.0 * u - 5.0 }
            })
        })
        .collect();
    // A parent: N distinct slots of the store.
    let mut slots: Vec<u16> = (0..K as u16).collect();
    for i in (1..slots.len()).rev() {
        slots.swap(i, (splitmix(&mut state) % (i as u64 + 1)) as usize);
    }
    slots.truncate(N);
    let mut group = c.benchmark_group("association");
    group.throughput(Throughput::Elements(N as u64));
    group.bench_function(format!("gather/{Z}x{N}"), |b| {
        let mut column_position = [0u16; N];
        b.iter(|| {
            let mut matrix = AssociationMatrix::<f64, N, Z>::new(Z, 0, 0.0);
            for (position, &slot) in black_box(&slots).iter().enumerate() {
                if let Some(column) = matrix.push_column(&entries[slot as usize][..Z], false) {
                    column_position[column] = position as u16;
                }
            }
            black_box((&matrix, &column_position));
        })
    });
    group.finish();
}

criterion_group!(benches, association);
criterion_main!(benches);
