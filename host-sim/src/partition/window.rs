//! A scan's measurements indexed for the gate (docs/maths.md §13.2): sorted by the distance of their first
//! component from a reference measurement's, so that a track in view is compared only with the measurements
//! whose distance lies within the gate's bound of its predicted measurement's. The window is a superset of
//! what the gate's first-component test accepts, never a cut of it.

use nalgebra::SVector;

/// Relative slack added to a window's half-width, far above the rounding of the distances it compares.
const SLACK: f64 = 1e-9;

/// A scan's measurements and their order by distance from the reference in the first component.
#[derive(Debug, Clone)]
pub struct Indexed<'a, const D: usize> {
    /// The scan's measurements, in scan order.
    pub measurements: &'a [SVector<f64, D>],
    /// Measurement indices by increasing key (ties by index); every index.
    order: Vec<usize>,
    /// The keys in `order`'s order; empty when no window can be used (a key not finite, no measurement).
    keys: Vec<f64>,
    /// The reference measurement: the one of the smallest first component (ties: the first).
    reference: usize,
    /// The largest key, for the slack.
    largest: f64,
}

impl<'a, const D: usize> Indexed<'a, D> {
    /// Indexes `measurements` by `distance(z, z_ref)`, `distance` the absolute first component of the
    /// residual (a metric on the first component: a plain or a wrapped difference, §13.2).
    pub fn new(
        measurements: &'a [SVector<f64, D>],
        distance: impl Fn(&SVector<f64, D>, &SVector<f64, D>) -> f64,
    ) -> Self {
        let mut order: Vec<usize> = (0..measurements.len()).collect();
        let reference = order.iter().copied().min_by(|&a, &b| measurements[a][0].total_cmp(&measurements[b][0]));
        let mut index = Self { measurements, order: order.clone(), keys: vec![], reference: 0, largest: 0.0 };
        let Some(reference) = reference else { return index };
        let keys: Vec<f64> = measurements.iter().map(|z| distance(z, &measurements[reference])).collect();
        if !keys.iter().all(|k| k.is_finite()) {
            return index;
        }
        order.sort_by(|&a, &b| keys[a].total_cmp(&keys[b]).then(a.cmp(&b)));
        index.keys = order.iter().map(|&i| keys[i]).collect();
        index.largest = index.keys.last().copied().unwrap_or(0.0);
        (index.order, index.reference) = (order, reference);
        index
    }

    /// The indices of the measurements z that can have `distance(z, predicted) ≤ radius`: those whose key is
    /// within `radius` (and a slack) of `distance(predicted, z_ref)`, by the triangle inequality; every
    /// measurement when `radius` is `None` or any of it is not finite.
    pub fn candidates(
        &self,
        predicted: &SVector<f64, D>,
        radius: Option<f64>,
        distance: impl Fn(&SVector<f64, D>, &SVector<f64, D>) -> f64,
    ) -> &[usize] {
        let Some(radius) = radius.filter(|r| r.is_finite() && *r >= 0.0 && !self.keys.is_empty()) else {
            return &self.order;
        };
        let t = distance(predicted, &self.measurements[self.reference]);
        if !t.is_finite() {
            return &self.order;
        }
        let half = radius * (1.0 + SLACK) + SLACK * (1.0 + t + radius + self.largest);
        let low = self.keys.partition_point(|&k| k < t - half);
        let high = self.keys.partition_point(|&k| k <= t + half);
        &self.order[low..high.max(low)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn wrap(a: f64) -> f64 {
        let w = a - 2.0 * PI * (a / (2.0 * PI)).round();
        if w <= -PI { w + 2.0 * PI } else { w }
    }

    #[test]
    fn every_measurement_within_the_radius_is_a_candidate_with_a_plain_or_a_wrapped_first_component() {
        // A deterministic spread of measurements and predictions, with first components as ranges (plain)
        // and as angles near ±π (wrapped); every measurement within the radius must be a candidate, and
        // the window must leave out most of the others.
        let plain = |a: &SVector<f64, 2>, b: &SVector<f64, 2>| (a[0] - b[0]).abs();
        let wrapped = |a: &SVector<f64, 2>, b: &SVector<f64, 2>| wrap(a[0] - b[0]).abs();
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut uniform = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let (mut inside, mut left_out) = (0, 0);
        for wrapped_first in [false, true] {
            let distance = |a: &SVector<f64, 2>, b: &SVector<f64, 2>| {
                if wrapped_first { wrapped(a, b) } else { plain(a, b) }
            };
            let spread = |u: f64| if wrapped_first { wrap(PI * (2.0 * u - 1.0) * 1.2) } else { 200.0 + 3800.0 * u };
            let zs: Vec<SVector<f64, 2>> = (0..400).map(|_| SVector::from([spread(uniform()), uniform()])).collect();
            let index = Indexed::new(&zs, distance);
            for _ in 0..300 {
                let predicted = SVector::from([spread(uniform()), 0.0]);
                let radius = if wrapped_first { 0.05 * uniform() } else { 40.0 * uniform() };
                let candidates = index.candidates(&predicted, Some(radius), distance);
                for (m, z) in zs.iter().enumerate() {
                    if distance(z, &predicted) <= radius {
                        inside += 1;
                        assert!(candidates.contains(&m), "{m} within {radius} of {predicted:?} left out");
                    } else if !candidates.contains(&m) {
                        left_out += 1;
                    }
                }
                assert_eq!(index.candidates(&predicted, None, distance).len(), zs.len());
            }
        }
        assert!(inside > 1000, "{inside} pairs inside");
        assert!(left_out > 2 * 300 * 400 * 9 / 10, "{left_out} pairs left out");
    }
}
