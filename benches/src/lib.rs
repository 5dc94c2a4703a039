//! Shared inputs of the benches: fixed association matrices and scenarios, built deterministically so that
//! every run measures the same work.

use tracker_core::association::AssociationMatrix;

/// SplitMix64 step, for deterministic bench inputs.
pub fn splitmix(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// A `rows × columns` association matrix like a dense crossing: each measurement is inside the gate of
/// `in_gate` objects around its own (entries from −2 to +8 nats), impossible elsewhere.
pub fn crossing_matrix<const N: usize, const Z: usize>(
    rows: usize,
    columns: usize,
    in_gate: usize,
    seed: u64,
) -> AssociationMatrix<f64, N, Z> {
    let mut state = seed;
    let mut m = AssociationMatrix::new(rows, columns, 0.0);
    let mut column_entries = vec![vec![f64::NEG_INFINITY; rows]; columns];
    for row in 0..rows {
        let centre = row * columns / rows.max(1);
        for k in 0..in_gate {
            let column = (centre + k).min(columns - 1);
            let u = (splitmix(&mut state) >> 11) as f64 / (1u64 << 53) as f64;
            if let Some(entry) = column_entries[column].get_mut(row) {
                *entry = -2.0 + 10.0 * u;
            }
        }
    }
    for (column, entries) in column_entries.iter().enumerate() {
        m.set_column(column, entries, false);
    }
    m
}
