//! Tracklet births in the pool (docs/maths.md §5.10): the directions of the last frames' unexplained
//! measurements, per sensor, and the link that turns a measurement and one direction from each of the
//! sensor's previous frames into an attributable whose admissible region gives its birth cells.
//!
//! Everything is fixed-size: [`TRACKLET_FRAMES`] earlier frames (of any sensors), [`TRACKLET_POINTS`]
//! directions each (those of largest r_U), so linking one measurement tries at most
//! `TRACKLET_POINTS^(frames − 1)` combinations.

use crate::model::{AdmissibleRegion, Attributable, LinkLimits, MAX_BIRTH_COMPONENTS, SkyPoint, TrackletFrame};
use crate::real::Real;

/// Earlier frames kept, of any sensors.
pub const TRACKLET_FRAMES: usize = 16;
/// Directions kept per frame: the unexplained measurements of largest r_U.
pub const TRACKLET_POINTS: usize = 8;
/// The most frames one tracklet links (the current one included).
pub const MAX_LINKED_FRAMES: usize = 4;

/// The settings of tracklet births.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TrackletBirths<T> {
    /// Frames per tracklet, the current one included: 3 or 4 ([`MAX_LINKED_FRAMES`]).
    pub frames: usize,
    /// The longest time from a tracklet's first frame to its last (s).
    pub max_span: f64,
    /// The link test.
    pub limits: LinkLimits<T>,
    /// The admissible region of a tracklet's range and range-rate.
    pub region: AdmissibleRegion<T>,
    /// Cells of the region: in ln ρ, in ρ̇.
    pub cells: [usize; 2],
    /// Whether a direction that links with nothing yet makes its own single-frame cells (§5.7). Without
    /// them an object's first frames stay unexplained until they link, and its births are one tracklet's.
    #[cfg_attr(feature = "serde", serde(default))]
    pub single_frame: bool,
}

impl<T: Real> TrackletBirths<T> {
    /// Checks the settings.
    ///
    /// # Errors
    /// A static description of the first invalid field.
    pub fn validate(&self) -> Result<(), &'static str> {
        if !(3..=MAX_LINKED_FRAMES).contains(&self.frames) {
            return Err("tracklet births: frames must be 3 or 4");
        }
        if !(self.max_span.is_finite() && self.max_span > 0.0) {
            return Err("tracklet births: max_span must be finite and > 0");
        }
        let LinkLimits { max_chi_squared, max_rate, max_acceleration, max_jerk } = self.limits;
        let positive = |x: T| x.is_finite_value() && x > T::zero();
        let jerk = max_jerk.is_finite_value() && max_jerk >= T::zero();
        if !(positive(max_chi_squared) && positive(max_rate) && positive(max_acceleration) && jerk) {
            return Err("tracklet births: the link limits must be finite, > 0 (max_jerk >= 0)");
        }
        self.region.validate()?;
        let [ranges, rates] = self.cells;
        if ranges == 0 || rates == 0 || ranges.saturating_mul(rates) > MAX_BIRTH_COMPONENTS {
            return Err("tracklet births: cells must be >= 1 each, their product at most MAX_BIRTH_COMPONENTS");
        }
        Ok(())
    }
}

/// One earlier frame: its sensor, time, noise and the directions of its unexplained measurements.
#[derive(Debug, Clone, PartialEq)]
struct SkyFrame<T> {
    sensor: usize,
    time: f64,
    sigma: [T; 2],
    /// (direction, r_U), largest r_U kept.
    points: heapless::Vec<([T; 2], T), TRACKLET_POINTS>,
}

/// The earlier frames, oldest first.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct TrackletBuffer<T> {
    frames: heapless::Vec<SkyFrame<T>, TRACKLET_FRAMES>,
}

impl<T: Real> TrackletBuffer<T> {
    /// An empty buffer.
    pub const fn new() -> Self {
        Self { frames: heapless::Vec::new() }
    }

    /// Forgets every frame.
    pub fn clear(&mut self) {
        self.frames.clear();
    }

    /// Frames held.
    pub fn len(&self) -> usize {
        self.frames.len()
    }

    /// Whether no frame is held.
    pub fn is_empty(&self) -> bool {
        self.frames.is_empty()
    }

    /// Records a frame of `sensor` at `time`: `points` are (direction, r_U) of its unexplained
    /// measurements; the largest r_U are kept, the oldest frame gives way when the buffer is full.
    pub fn record(&mut self, sensor: usize, time: f64, sigma: [T; 2], points: impl Iterator<Item = ([T; 2], T)>) {
        let mut kept: heapless::Vec<([T; 2], T), TRACKLET_POINTS> = heapless::Vec::new();
        for point in points {
            if kept.push(point).is_err() {
                let smallest = kept.iter().enumerate().fold(None, |low: Option<(usize, T)>, (i, p)| match low {
                    Some((_, r)) if r <= p.1 => low,
                    _ => Some((i, p.1)),
                });
                if let Some((index, r)) = smallest
                    && point.1 > r
                    && let Some(slot) = kept.get_mut(index)
                {
                    *slot = point;
                }
            }
        }
        if kept.is_empty() {
            return;
        }
        if self.frames.is_full() {
            self.frames.remove(0);
        }
        let _ = self.frames.push(SkyFrame { sensor, time, sigma, points: kept });
    }

    /// Forgets the frames older than `time − max_span`.
    pub fn expire(&mut self, time: f64, max_span: f64) {
        self.frames.retain(|frame| time - frame.time <= max_span);
    }

    /// The best tracklet through `point` (of `sensor`, at `time`) and one direction of each of the
    /// sensor's latest `settings.frames − 1` earlier frames within `max_span`: the attributable at `time`
    /// with the smallest link score (χ² plus the accelerations squared in units of their bound), or
    /// `None` when there are too few frames or no combination links.
    pub fn link(
        &self,
        sensor: usize,
        time: f64,
        point: &SkyPoint<T>,
        settings: &TrackletBirths<T>,
    ) -> Option<Attributable<T>> {
        let earlier = settings.frames.clamp(3, MAX_LINKED_FRAMES) - 1;
        let mut chosen: [usize; MAX_LINKED_FRAMES - 1] = [0; MAX_LINKED_FRAMES - 1];
        let mut found = 0;
        for (index, frame) in self.frames.iter().enumerate().rev() {
            if found == earlier {
                break;
            }
            if frame.sensor == sensor && frame.time < time && time - frame.time <= settings.max_span {
                let Some(slot) = chosen.get_mut(found) else { break };
                *slot = index;
                found += 1;
            }
        }
        if found < earlier {
            return None;
        }
        let frames = chosen.get(..earlier)?;
        let mut digits = [0_usize; MAX_LINKED_FRAMES - 1];
        let mut best: Option<(T, Attributable<T>)> = None;
        loop {
            let mut arc = [TrackletFrame { time, angles: point.angles }; MAX_LINKED_FRAMES];
            for (slot, (&frame, &digit)) in frames.iter().zip(&digits).enumerate() {
                let earlier = self.frames.get(frame)?;
                let (angles, _) = *earlier.points.get(digit)?;
                arc[slot + 1] = TrackletFrame { time: earlier.time, angles };
            }
            if let Ok(attributable) = Attributable::fit_at(arc.get(..=earlier)?, time, point.sigma, &settings.limits) {
                let score = link_score(&attributable, &settings.limits);
                if best.as_ref().is_none_or(|(low, _)| score < *low) {
                    best = Some((score, attributable));
                }
            }
            // Next combination (odometer over the chosen frames' points).
            let mut position = 0;
            loop {
                let Some(&frame) = frames.get(position) else {
                    return best.map(|(_, attributable)| attributable);
                };
                let size = self.frames.get(frame).map_or(0, |f| f.points.len());
                digits[position] += 1;
                if digits[position] < size {
                    break;
                }
                digits[position] = 0;
                position += 1;
            }
        }
    }
}

/// χ² plus Σ (acceleration / bound)²: smaller for a straighter, better-fitting arc.
fn link_score<T: Real>(attributable: &Attributable<T>, limits: &LinkLimits<T>) -> T {
    attributable.accelerations.iter().fold(attributable.chi_squared, |sum, &a| {
        let ratio = a / limits.max_acceleration;
        sum + ratio * ratio
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::OpticalRaDec;
    use crate::model::admissible::tracklet::tests::{
        LIMITS, S6, SIGMA, angles, bound, normal, orbit, propagate, site, site_below,
    };
    use crate::pool::{BirthPool, MeasuredBirths, ScanUse};
    use nalgebra::SVector;
    use rand_xoshiro::Xoshiro256PlusPlus;
    use rand_xoshiro::rand_core::SeedableRng;

    const B: usize = 128;

    /// One frame: its time, the observer's state and the measurements.
    type Frame = (f64, [f64; 6], std::vec::Vec<SVector<f64, 2>>);

    fn settings(frames: usize) -> MeasuredBirths<f64> {
        MeasuredBirths {
            min_unexplained: 0.5,
            tracklets: Some(TrackletBirths {
                frames,
                max_span: 300.0,
                limits: LIMITS,
                region: bound(),
                cells: [24, 4],
                single_frame: true,
            }),
            ..MeasuredBirths::new(AdmissibleRegion::geo())
        }
    }

    /// Frames of a GEO object 30 s apart from a site under it, each with `clutter` extra directions.
    fn frames(count: usize, clutter: usize) -> ([f64; 6], S6, std::vec::Vec<Frame>) {
        let x0 = orbit(42_164.0, 0.0002, 0.01, 1.2, 0.4);
        let (latitude, longitude) = site_below(&x0);
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(3);
        let scans = (0..count)
            .map(|k| {
                let t = 30.0 * k as f64;
                let q = site(latitude, longitude, t);
                let [ra, dec] = angles(&propagate(&x0, t), &q);
                let mut zs = std::vec![SVector::from([ra + SIGMA * normal(&mut rng), dec + SIGMA * normal(&mut rng)])];
                for c in 0..clutter {
                    zs.push(SVector::from([
                        ra + 0.01 * (c as f64 + 1.0) * normal(&mut rng),
                        dec + 0.01 * normal(&mut rng),
                    ]));
                }
                (t, q, zs)
            })
            .collect::<std::vec::Vec<_>>();
        let last = scans.last().map(|s| s.0).unwrap_or(0.0);
        (scans.last().map(|s| s.1).unwrap_or([0.0; 6]), propagate(&x0, last), scans)
    }

    /// Runs the pool over the frames (every measurement unexplained) and returns the last update.
    fn run(
        pool: &mut BirthPool<f64, 6, B>,
        settings: &MeasuredBirths<f64>,
        scans: &[Frame],
    ) -> crate::pool::PoolUpdate {
        let mut update = Default::default();
        for (t, q, zs) in scans {
            let model = OpticalRaDec { observer: *q, sigma: [SIGMA; 2] };
            let r_u = std::vec![1.0; zs.len()];
            let scan = ScanUse {
                time: *t,
                sensor: 0,
                measurements: zs,
                unexplained: &r_u,
                born: &[],
                detection: &[],
                labels: &[],
            };
            let motion =
                crate::model::TwoBodyJ2::<f64>::earth(crate::model::ProcessNoise::Isotropic(1e-10), 20.0, 2000);
            let sensor = crate::Sensor {
                detection_probability: 0.9,
                clutter_rate: 1.0,
                field_of_view: crate::Region::Everywhere { volume: 1.0 },
            };
            let weights =
                crate::weight::WeightModel::new(&sensor, None, 0.0, 0, crate::BirthDetection::AllDetected, 0.0);
            let field_of_view = crate::Region::Everywhere { volume: 1.0 };
            let linking = crate::pool::Linking {
                motion: &motion,
                field_of_view: &field_of_view,
                weights: &weights,
                detection_probability: 0.9,
            };
            update = pool.update(settings, B, &model, &linking, &scan);
        }
        update
    }

    #[test]
    fn the_fourth_frame_of_a_geo_object_gives_the_cells_of_its_tracklet() {
        let (_, truth, scans) = frames(4, 2);
        let mut pool = BirthPool::<f64, 6, B>::new();
        let settings = settings(4);
        let update = run(&mut pool, &settings, &scans[..3]);
        assert_eq!(update.tracklets, 0, "three frames are not enough for a 4-frame tracklet");
        pool.clear();
        let update = run(&mut pool, &settings, &scans);
        assert!(update.tracklets >= 1, "{update:?}");
        // The newest cells (this scan's) include one within χ²₆ 99.9 % of the truth.
        let newest: std::vec::Vec<_> = pool.cells().iter().filter(|c| c.time == scans[3].0).collect();
        let best = newest
            .iter()
            .map(|c| {
                let d = truth - c.state.mean;
                (d.transpose() * c.state.covariance.try_inverse().expect("invertible") * d)[0]
            })
            .fold(f64::INFINITY, f64::min);
        assert!(best < 22.5, "nearest tracklet cell at Mahalanobis² {best}");
    }

    #[test]
    fn without_tracklets_the_pool_is_unchanged_and_keeps_no_frames() {
        let (_, _, scans) = frames(4, 2);
        let mut with = BirthPool::<f64, 6, B>::new();
        let mut without = BirthPool::<f64, 6, B>::new();
        let off = MeasuredBirths { tracklets: None, ..settings(4) };
        run(&mut without, &off, &scans);
        assert!(without.tracklet_frames().is_empty());
        run(&mut with, &settings(4), &scans[..1]);
        let mut plain = BirthPool::<f64, 6, B>::new();
        run(&mut plain, &off, &scans[..1]);
        // One frame links nothing: the same single-frame cells either way.
        assert_eq!(with.cells(), plain.cells());
        assert_eq!(with.tracklet_frames().len(), 1);
    }

    #[test]
    fn frames_expire_and_a_full_frame_keeps_the_largest_r_u() {
        let mut buffer = TrackletBuffer::<f64>::new();
        let points = (0..12).map(|i| ([i as f64, 0.0], i as f64 / 12.0));
        buffer.record(0, 0.0, [SIGMA; 2], points);
        let kept: std::vec::Vec<f64> = buffer.frames[0].points.iter().map(|p| p.1).collect();
        assert_eq!(kept.len(), TRACKLET_POINTS);
        assert!(kept.iter().all(|&r| r >= 4.0 / 12.0), "{kept:?}");
        for k in 1..=TRACKLET_FRAMES {
            buffer.record(1, k as f64, [SIGMA; 2], core::iter::once(([0.0, 0.0], 1.0)));
        }
        assert_eq!(buffer.len(), TRACKLET_FRAMES);
        assert!(buffer.frames.iter().all(|f| f.sensor == 1), "the oldest frame gave way");
        buffer.expire(100.0, 90.0);
        assert_eq!(buffer.len(), 7, "the frames at 10 s to 16 s are within 90 s of 100 s");
        buffer.expire(200.0, 90.0);
        assert_eq!(buffer.len(), 0);
    }

    #[test]
    fn invalid_settings_are_refused() {
        let good = settings(4);
        assert!(good.validate().is_ok());
        let with = |t: TrackletBirths<f64>| MeasuredBirths { tracklets: Some(t), ..good };
        let base = good.tracklets.expect("set");
        assert!(with(TrackletBirths { frames: 2, ..base }).validate().is_err());
        assert!(with(TrackletBirths { frames: 5, ..base }).validate().is_err());
        assert!(with(TrackletBirths { max_span: f64::NAN, ..base }).validate().is_err());
        assert!(with(TrackletBirths { cells: [0, 4], ..base }).validate().is_err());
        assert!(with(TrackletBirths { cells: [1024, 2], ..base }).validate().is_err());
        let limits = LinkLimits { max_rate: -1.0, ..base.limits };
        assert!(with(TrackletBirths { limits, ..base }).validate().is_err());
    }
}
