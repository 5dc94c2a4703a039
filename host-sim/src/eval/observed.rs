//! Catalogue figures a user can read (issue 30 item 5): the error of the objects observed so far apart from
//! the prediction error of the objects no sensor has observed yet.
//!
//! One GOSPA over a whole catalogue mixes two things: how well the tracker holds what its sensors saw, and
//! how far the prior's unobserved objects drift (which no tracker can correct). [`observed_errors`] splits
//! them at one time: each true object is *observed* once a measurement of it has been taken (its latest
//! observation time is known), else *unobserved*; each object's error is the distance from its true position
//! to its track, and each group reports its median.
//!
//! An object's track: the MAP track carrying the object's prior label when there is one (host-sim's
//! generated scenarios label object i's prior track i), else, among the tracks left, the nearest within
//! `cutoff_km` (closest pairs first, one track per object: births have labels of their own). An object
//! with no track is counted as `unmatched` and enters its median at `cutoff_km`, as GOSPA saturates a
//! missed object at its cut-off. The nearest pairs are found on a grid of `cutoff_km` cells, so the cost
//! grows with the objects and tracks, not their product.

use std::collections::HashMap;

/// The cut-off (km) of the distance matching that `run` and `run-catalogue` use: far beyond the error of a
/// track that follows its object, short of the distance between neighbouring catalogue objects' tracks.
pub const MATCH_CUTOFF_KM: f64 = 100.0;

/// One true object at the time of the figures.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ObjectAt<const P: usize> {
    /// Truth id.
    pub id: u64,
    /// Position.
    pub position: [f64; P],
    /// The label of its prior track, when it has one.
    pub prior_label: Option<u32>,
    /// The time of its latest observation (`None`: never observed).
    pub last_observed: Option<f64>,
}

/// The errors of the observed and the unobserved objects at one time.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ObservedErrors {
    /// Objects observed at least once.
    pub observed_objects: usize,
    /// Objects never observed.
    pub unobserved_objects: usize,
    /// Median error (km) of the observed objects (`None`: none).
    pub observed_median_error_km: Option<f64>,
    /// Median prediction error (km) of the unobserved objects (`None`: none).
    pub unobserved_median_error_km: Option<f64>,
    /// Median time (s) since the observed objects' latest observation.
    pub observed_median_age_s: Option<f64>,
    /// Observed objects without a track (their error counted at the cut-off).
    pub observed_unmatched: usize,
    /// Unobserved objects without a track.
    pub unobserved_unmatched: usize,
}

fn distance<const P: usize>(a: &[f64; P], b: &[f64; P]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum::<f64>().sqrt()
}

/// The median of `values` (sorted in place); `None` when empty.
pub fn median(values: &mut [f64]) -> Option<f64> {
    values.sort_by(f64::total_cmp);
    let n = values.len();
    match n {
        0 => None,
        _ if n % 2 == 1 => Some(values[n / 2]),
        _ => Some((values[n / 2 - 1] + values[n / 2]) / 2.0),
    }
}

/// The grid cell of `position` for cells of `size`.
fn cell<const P: usize>(position: &[f64; P], size: f64) -> [i64; P] {
    core::array::from_fn(|i| (position[i] / size).floor() as i64)
}

/// The cells next to `c` and `c` itself (3^P of them).
fn neighbours<const P: usize>(c: [i64; P]) -> impl Iterator<Item = [i64; P]> {
    (0..3usize.pow(P as u32)).map(move |k| core::array::from_fn(|i| c[i] + (k / 3usize.pow(i as u32) % 3) as i64 - 1))
}

/// Each object's error (km; `None`: no track), objects matched by prior label first, then by distance.
fn errors<const P: usize>(objects: &[ObjectAt<P>], tracks: &[(u32, [f64; P])], cutoff_km: f64) -> Vec<Option<f64>> {
    let by_label: HashMap<u32, usize> = tracks.iter().enumerate().map(|(j, t)| (t.0, j)).collect();
    let mut taken = vec![false; tracks.len()];
    let mut error = vec![None; objects.len()];
    for (i, o) in objects.iter().enumerate() {
        if let Some(&j) = o.prior_label.and_then(|l| by_label.get(&l)) {
            taken[j] = true;
            error[i] = Some(distance(&o.position, &tracks[j].1));
        }
    }
    if !(cutoff_km > 0.0 && cutoff_km.is_finite()) {
        return error;
    }
    let mut grid: HashMap<[i64; P], Vec<usize>> = HashMap::new();
    for (j, t) in tracks.iter().enumerate().filter(|(j, _)| !taken[*j]) {
        grid.entry(cell(&t.1, cutoff_km)).or_default().push(j);
    }
    let mut pairs = vec![];
    for (i, o) in objects.iter().enumerate().filter(|(i, _)| error[*i].is_none()) {
        for c in neighbours(cell(&o.position, cutoff_km)) {
            for &j in grid.get(&c).map_or(&[][..], Vec::as_slice) {
                let d = distance(&o.position, &tracks[j].1);
                if d <= cutoff_km {
                    pairs.push((d, i, j));
                }
            }
        }
    }
    // Closest pairs first; ties in object then track order, so the result is deterministic.
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
    for (d, i, j) in pairs {
        if error[i].is_none() && !taken[j] {
            taken[j] = true;
            error[i] = Some(d);
        }
    }
    error
}

/// The observed and unobserved objects' errors at time `now` (see the module's text), the MAP tracks being
/// `tracks` (label, position).
pub fn observed_errors<const P: usize>(
    now: f64,
    objects: &[ObjectAt<P>],
    tracks: &[(u32, [f64; P])],
    cutoff_km: f64,
) -> ObservedErrors {
    let errors = errors(objects, tracks, cutoff_km);
    let (mut seen, mut unseen, mut ages) = (vec![], vec![], vec![]);
    let mut figures = ObservedErrors::default();
    for (o, e) in objects.iter().zip(&errors) {
        let value = e.unwrap_or(cutoff_km);
        match o.last_observed {
            Some(t) => {
                figures.observed_objects += 1;
                figures.observed_unmatched += usize::from(e.is_none());
                seen.push(value);
                ages.push(now - t);
            }
            None => {
                figures.unobserved_objects += 1;
                figures.unobserved_unmatched += usize::from(e.is_none());
                unseen.push(value);
            }
        }
    }
    figures.observed_median_error_km = median(&mut seen);
    figures.unobserved_median_error_km = median(&mut unseen);
    figures.observed_median_age_s = median(&mut ages);
    figures
}

#[cfg(test)]
mod tests {
    use super::*;

    fn object(id: u64, x: f64, prior: bool, seen: Option<f64>) -> ObjectAt<3> {
        ObjectAt { id, position: [x, 0.0, 0.0], prior_label: prior.then_some(id as u32), last_observed: seen }
    }

    #[test]
    fn observed_and_unobserved_objects_are_apart() {
        // Objects 0-2 observed (errors 0.1, 0.3, 0.2 km), 3-4 not (errors 40 and 60 km), object 5 observed
        // and born (no prior label, its track 0.5 km away with label 100), object 6 unobserved and without a
        // track.
        let objects = [
            object(0, 0.0, true, Some(10.0)),
            object(1, 1000.0, true, Some(20.0)),
            object(2, 2000.0, true, Some(30.0)),
            object(3, 3000.0, true, None),
            object(4, 4000.0, true, None),
            object(5, 5000.0, false, Some(40.0)),
            object(6, 9000.0, true, None),
        ];
        let tracks = [
            (0, [0.1, 0.0, 0.0]),
            (1, [1000.0, 0.3, 0.0]),
            (2, [2000.0, 0.0, 0.2]),
            (3, [3040.0, 0.0, 0.0]),
            (4, [4000.0, 60.0, 0.0]),
            (100, [5000.5, 0.0, 0.0]),
        ];
        let f = observed_errors(50.0, &objects, &tracks, MATCH_CUTOFF_KM);
        assert_eq!((f.observed_objects, f.unobserved_objects), (4, 3));
        let close = |a: Option<f64>, b: f64| a.is_some_and(|a| (a - b).abs() < 1e-9);
        assert!(close(f.observed_median_error_km, 0.25), "{f:?}");
        // 40, 60 and the cut-off (100) for object 6.
        assert!(close(f.unobserved_median_error_km, 60.0), "{f:?}");
        assert_eq!((f.observed_unmatched, f.unobserved_unmatched), (0, 1));
        // Ages 40, 30, 20, 10 s.
        assert!(close(f.observed_median_age_s, 25.0), "{f:?}");
    }

    #[test]
    fn the_label_wins_over_distance_and_each_track_serves_one_object() {
        // Object 0's prior track drifted 80 km; object 1 (born) sits 1 km from it and has its own track 5 km
        // away: object 0 keeps its label's track, object 1 takes the other.
        let objects = [object(0, 0.0, true, Some(1.0)), object(1, 79.0, false, Some(1.0))];
        let tracks = [(0, [80.0, 0.0, 0.0]), (7, [84.0, 0.0, 0.0])];
        let f = observed_errors(1.0, &objects, &tracks, MATCH_CUTOFF_KM);
        assert!(f.observed_median_error_km.is_some_and(|m| (m - 42.5).abs() < 1e-9), "{f:?}");
        // Without the distance matching, the born object has no track.
        let f = observed_errors(1.0, &objects, &tracks, 0.0);
        assert_eq!(f.observed_unmatched, 1);
        assert_eq!(observed_errors::<3>(0.0, &[], &tracks, 100.0).observed_median_error_km, None);
    }

    #[test]
    fn the_grid_finds_what_all_pairs_find() {
        // Random objects and tracks: the grid's greedy matching equals a brute-force greedy matching.
        let mut random = crate::sim::rng::Random::stream(4, crate::sim::rng::Stream::Scenario, 0);
        let objects: Vec<ObjectAt<3>> = (0..300)
            .map(|i| ObjectAt {
                id: i,
                position: [0.0; 3].map(|_: f64| random.between(-2000.0, 2000.0)),
                prior_label: None,
                last_observed: (i % 2 == 0).then_some(0.0),
            })
            .collect();
        let tracks: Vec<(u32, [f64; 3])> =
            (0..250).map(|j| (j, [0.0; 3].map(|_: f64| random.between(-2000.0, 2000.0)))).collect();
        let grid = errors(&objects, &tracks, 300.0);
        let mut pairs = vec![];
        for (i, o) in objects.iter().enumerate() {
            for (j, t) in tracks.iter().enumerate() {
                let d = distance(&o.position, &t.1);
                if d <= 300.0 {
                    pairs.push((d, i, j));
                }
            }
        }
        pairs.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
        let (mut brute, mut taken) = (vec![None; objects.len()], vec![false; tracks.len()]);
        for (d, i, j) in pairs {
            if brute[i].is_none() && !taken[j] {
                (brute[i], taken[j]) = (Some(d), true);
            }
        }
        assert_eq!(grid, brute);
        assert!(grid.iter().filter(|e| e.is_some()).count() > 50);
    }
}
