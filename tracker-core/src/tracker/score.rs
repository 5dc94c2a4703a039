//! Stage 1 of a scan: predict every track of the shared store once, and score it against every measurement
//! once. The entries δ of docs/maths.md §4.2 computed here serve every parent hypothesis that holds the
//! track; birth cells are scored the same way.

use super::scan::PlacedScan;
use crate::config::{Config, NumericalFailure};
use crate::ekf::{self, Innovation, NumericalError};
use crate::error::StepError;
use crate::gaussian::Gaussian;
use crate::index::{At, NONE};
use crate::model::{MeasurementModel, MotionModel};
use crate::pool::BirthPool;
use crate::real::Real;
use crate::real::ln;
use crate::report::NumericalDrops;
use crate::sensor::Region;
use crate::store::{Track, TrackLabel};
use nalgebra::SVector;

/// A track after prediction to the current scan.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(super) struct Predicted<T: Real, const S: usize, const D: usize> {
    pub(super) state: Gaussian<T, S>,
    pub(super) innovation: Innovation<T, D>,
    pub(super) in_field_of_view: bool,
    /// Dropped for a numerical failure ([`NumericalFailure::DropTrack`]) or lost
    /// ([`crate::TrackLoss`]): in no child of this scan.
    pub(super) dropped: bool,
    /// The track's unseen scans, this one counted ([`crate::TrackLoss`]).
    pub(super) unseen_scans: u16,
}

/// The scan's birth cells as its sensor sees them: the configuration's cells, then the pool's cells
/// predicted to the scan (docs/maths.md §5.8); each one's density, α, predicted measurement and whether
/// it lies in the field of view.
#[derive(Debug, Clone, Copy)]
pub(super) struct BirthCells<T: Real, const S: usize, const D: usize, const B: usize> {
    pub(super) states: [Gaussian<T, S>; B],
    pub(super) innovations: [Innovation<T, D>; B],
    pub(super) in_field_of_view: [bool; B],
    /// α of each cell.
    pub(super) probabilities: [T; B],
    /// The pool cell each cell was predicted from (`NONE`: a cell of the configuration).
    pub(super) pool_cell: [u16; B],
    /// Each pool cell's candidate (group) and the label its first birth was given (§5.8).
    pub(super) candidate: [Option<(u32, Option<TrackLabel>)>; B],
    pub(super) count: usize,
}

impl<T: Real, const S: usize, const D: usize, const B: usize> BirthCells<T, S, D, B> {
    pub(super) const EMPTY: Self = Self {
        states: [Gaussian::ZERO; B],
        innovations: [Innovation::EMPTY; B],
        in_field_of_view: [false; B],
        probabilities: [T::ZERO; B],
        pool_cell: [NONE; B],
        candidate: [None; B],
        count: 0,
    };

    /// Whether cell `cell` lies in the field of view (`None`: no such cell).
    pub(super) fn in_field_of_view(&self, cell: usize) -> Option<bool> {
        self.in_field_of_view.get(cell).copied()
    }
}

/// Predictions and entries of one scan. Nothing in it outlives a `step` call.
#[derive(Debug, Clone)]
pub(super) struct Scores<T: Real, const S: usize, const D: usize, const Z: usize, const K: usize, const B: usize> {
    predicted: [Predicted<T, S, D>; K],
    /// δ for every (track slot, measurement).
    entries: [[T; Z]; K],
    /// δ for every (birth cell, measurement).
    birth_entries: [[T; Z]; B],
}

impl<T: Real, const S: usize, const D: usize, const Z: usize, const K: usize, const B: usize> Scores<T, S, D, Z, K, B> {
    pub(super) const fn new() -> Self {
        Self {
            predicted: [Predicted {
                state: Gaussian::ZERO,
                innovation: Innovation::EMPTY,
                in_field_of_view: false,
                dropped: false,
                unseen_scans: 0,
            }; K],
            entries: [[T::NEG_INFINITY; Z]; K],
            birth_entries: [[T::NEG_INFINITY; Z]; B],
        }
    }

    /// Predicts every track in `tracks` by `dt` and scores it, and every birth cell, against every
    /// measurement (`-inf` outside the gate or the field of view). A track whose prediction, innovation
    /// or (in view) update gain fails is dropped from the scan or fails it, as `config.numerical_failure`
    /// says; the dropped ones are returned, with the number of tracks lost by `config.track_loss`.
    ///
    /// # Errors
    /// With [`NumericalFailure::Error`], [`StepError::Numerical`] naming the first track that fails.
    pub(super) fn run<M, G>(
        &mut self,
        config: &Config<T, M, G, S, B>,
        placed: &PlacedScan<T, G>,
        birth_cells: &BirthCells<T, S, D, B>,
        tracks: &[Track<T, S>],
        dt: T,
        measurements: &[SVector<T, D>],
    ) -> Result<(NumericalDrops, usize), StepError>
    where
        M: MotionModel<T, S>,
        G: MeasurementModel<T, S, D>,
    {
        let mut drops = NumericalDrops::default();
        let mut lost = 0;
        let slots = self.predicted.iter_mut().zip(self.entries.iter_mut());
        for (track, (predicted, entries)) in tracks.iter().zip(slots) {
            *predicted = match predict_track(&config.motion, placed, track, dt) {
                Ok(prediction) => prediction,
                Err(error) if config.numerical_failure == NumericalFailure::Error => {
                    return Err(StepError::Numerical { label: track.label, error });
                }
                Err(error) => {
                    drops.count += 1;
                    drops.first = drops.first.or(Some((track.label, error)));
                    Predicted {
                        state: track.state,
                        innovation: Innovation::EMPTY,
                        in_field_of_view: false,
                        dropped: true,
                        unseen_scans: track.unseen_scans,
                    }
                }
            };
            score_row(entries, placed, &predicted.innovation, predicted.in_field_of_view, measurements);
            let rows = measurements.len().min(Z);
            predicted.unseen_scans = unseen_scans(track.unseen_scans, predicted.in_field_of_view, &entries[..rows]);
            if !predicted.dropped && config.track_loss.is_lost(predicted.unseen_scans) {
                lost += 1;
                predicted.dropped = true;
                predicted.in_field_of_view = false;
                entries.fill(T::NEG_INFINITY);
            }
        }
        let cells = birth_cells.innovations.iter().zip(&birth_cells.in_field_of_view).zip(&birth_cells.probabilities);
        for (entries, ((innovation, &in_field_of_view), &alpha)) in
            self.birth_entries.iter_mut().zip(cells).take(birth_cells.count)
        {
            score_row(entries, placed, innovation, in_field_of_view, measurements);
            for entry in entries.iter_mut() {
                *entry = placed.weights.birth_entry_with(*entry, alpha);
            }
        }
        Ok((drops, lost))
    }

    /// The prediction of the track in `slot`.
    #[inline]
    pub(super) fn predicted(&self, slot: usize) -> &Predicted<T, S, D> {
        self.predicted.at(slot)
    }

    /// The entries of the track in `slot` for the first `rows` measurements.
    #[inline]
    pub(super) fn entries(&self, slot: usize, rows: usize) -> &[T] {
        &self.entries.at(slot)[..rows.min(Z)]
    }

    /// The entries of birth cell `cell` for the first `rows` measurements (`None`: no such cell).
    #[inline]
    pub(super) fn birth_entries(&self, cell: usize, rows: usize) -> Option<&[T]> {
        self.birth_entries.get(cell).map(|entries| &entries[..rows.min(Z)])
    }
}

/// Whether an object at `state`, whose measurement by the placed sensor `model` is predicted at
/// `predicted`, lies in `region`: read from the predicted measurement ([`Region::sees`]), or from the
/// state's look direction for a sensor that measures no angles ([`Measure::look_of_state`](crate::Measure::look_of_state)). The tracker and the
/// host's reference decide every missed detection here.
pub fn in_field_of_view<T: Real, G: MeasurementModel<T, S, D>, const S: usize, const D: usize>(
    region: &Region<T>,
    model: &G,
    state: &Gaussian<T, S>,
    predicted: &SVector<T, D>,
) -> bool {
    match model.look_of_state(&state.mean) {
        Some(look) => region.contains_look(&look),
        None => region.sees(model, predicted),
    }
}

/// A track's unseen scans after this scan ([`crate::TrackLoss`]): one more when it is in view and no
/// entry of its row is possible (no measurement in its gate), none when some is, as before out of view.
/// The tracker and the host's reference count them here.
pub fn unseen_scans<T: Real>(before: u16, in_field_of_view: bool, entries: &[T]) -> u16 {
    if !in_field_of_view {
        before
    } else if entries.iter().any(|&e| e > T::NEG_INFINITY) {
        0
    } else {
        before.saturating_add(1)
    }
}

/// Predicts `track` by `dt`: its state, innovation and whether it is in view; for a track in view, also
/// checks that an update is possible (its gain and posterior covariance), so that a failure drops or fails
/// the track before any child holds it.
fn predict_track<T: Real, M, G, const S: usize, const D: usize>(
    motion: &M,
    placed: &PlacedScan<T, G>,
    track: &Track<T, S>,
    dt: T,
) -> Result<Predicted<T, S, D>, NumericalError>
where
    M: MotionModel<T, S>,
    G: MeasurementModel<T, S, D>,
{
    let state = ekf::predict(motion, &track.state, dt)?;
    let innovation = ekf::innovation(&placed.model, &state)?;
    let in_field_of_view =
        in_field_of_view(&placed.detection.field_of_view, &placed.model, &state, &innovation.predicted);
    if in_field_of_view {
        ekf::correction(&placed.model, &state, &innovation)?;
    }
    Ok(Predicted { state, innovation, in_field_of_view, dropped: false, unseen_scans: track.unseen_scans })
}

/// The scan's birth cells as its sensor sees them (the configuration's, then `pool`'s predicted to `time`),
/// and `placed`'s weight model set to them (docs/maths.md §5.6, §5.8). A pool cell whose prediction or
/// innovation fails is left out of this scan.
///
/// # Errors
/// [`StepError::BirthCell`] when the innovation of a cell of the configuration cannot be formed.
pub(super) fn birth_cells<T: Real, M, G, const S: usize, const D: usize, const B: usize>(
    config: &Config<T, M, G, S, B>,
    pool: &BirthPool<T, S, B>,
    placed: &mut PlacedScan<T, G>,
    time: f64,
    cells: &mut BirthCells<T, S, D, B>,
) -> Result<(), StepError>
where
    M: MotionModel<T, S>,
    G: MeasurementModel<T, S, D>,
{
    // In place (the tracker's scratch, a few KiB that would otherwise sit on the stack): the entries past
    // `count` are never read; the small tables are reset to their empty values.
    cells.count = 0;
    cells.in_field_of_view = [false; B];
    cells.probabilities = [T::ZERO; B];
    cells.pool_cell = [NONE; B];
    cells.candidate = [None; B];
    let fixed =
        config.birth.cells.iter().enumerate().map(|(cell, state)| (NONE, cell, *state, config.birth.probability));
    let from_pool =
        pool.predicted(&config.motion, time).map(|(index, state, alpha)| (index as u16, usize::MAX, state, alpha));
    let mut no_birth = T::zero();
    for (pool_cell, fixed_cell, state, alpha) in fixed.chain(from_pool) {
        if cells.count >= B {
            break;
        }
        let innovation = match ekf::innovation(&placed.model, &state) {
            Ok(innovation) => innovation,
            Err(_) if pool_cell == NONE => return Err(StepError::BirthCell { cell: fixed_cell }),
            Err(_) => continue,
        };
        let cell = cells.count;
        *cells.states.at_mut(cell) = state;
        *cells.innovations.at_mut(cell) = innovation;
        *cells.in_field_of_view.at_mut(cell) =
            in_field_of_view(&placed.detection.field_of_view, &placed.model, &state, &innovation.predicted);
        *cells.probabilities.at_mut(cell) = alpha;
        *cells.pool_cell.at_mut(cell) = pool_cell;
        *cells.candidate.at_mut(cell) =
            pool.cells().get(usize::from(pool_cell)).map(|pooled| (pooled.group, pooled.label));
        cells.count += 1;
        no_birth += ln(T::one() - alpha);
    }
    if config.birth.measured.is_some() {
        placed.weights.set_birth_cells(cells.count, no_birth);
    }
    Ok(())
}

/// δ of one track or birth cell against every measurement, `-inf` everywhere when it is out of view; the
/// residuals formed by the scan's measurement model (angles wrapped).
fn score_row<T: Real, G: MeasurementModel<T, S, D>, const S: usize, const D: usize>(
    entries: &mut [T],
    placed: &PlacedScan<T, G>,
    innovation: &Innovation<T, D>,
    in_field_of_view: bool,
    measurements: &[SVector<T, D>],
) {
    for (entry, z) in entries.iter_mut().zip(measurements) {
        *entry = if in_field_of_view {
            placed.weights.entry_of_residual(innovation, &placed.model.residual(z, &innovation.predicted))
        } else {
            T::NEG_INFINITY
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::{BirthModel, ChildGeneration, Selection, StoreOverflow, TrackLoss};
    use crate::model::{ConstantVelocity, PositionMeasurement};
    use crate::sensor::{Region, Sensor};
    use crate::store::TrackLabel;
    use nalgebra::SMatrix;

    type Cv = Config<f64, ConstantVelocity<f64>, PositionMeasurement<f64>, 4, 1>;

    fn config(numerical_failure: NumericalFailure) -> Cv {
        Config {
            motion: ConstantVelocity { acceleration_noise: 0.01 },
            measurement: PositionMeasurement::isotropic(0.5),
            sensor: Sensor {
                detection_probability: 0.9,
                clutter_rate: 1.0,
                field_of_view: Region::Rectangle { min: [-10.0, -10.0], max: [10.0, 10.0] },
            },
            birth: BirthModel::none(),
            death_probability: 0.0,
            gate: Some(16.0),
            children: ChildGeneration::default(),
            selection: Selection::default(),
            store_overflow: StoreOverflow::default(),
            numerical_failure,
            track_loss: TrackLoss::Never,
            seed: 1,
        }
    }

    fn placed(config: &Cv) -> PlacedScan<f64, PositionMeasurement<f64>> {
        PlacedScan {
            model: config.measurement,
            detection: config.sensor,
            weights: crate::weight::WeightModel::from_config(config),
        }
    }

    fn track(label: u32, x: f64, variance: f64) -> Track<f64, 4> {
        let state = Gaussian { mean: SVector::from([x, 0.0, 1.0, 0.0]), covariance: SMatrix::identity() * variance };
        Track { label: TrackLabel(label), state, existence: 1.0, unseen_scans: 0 }
    }

    #[test]
    fn entries_are_scored_in_view_and_impossible_out_of_view_or_outside_the_gate() {
        let config = config(NumericalFailure::Error);
        let model = placed(&config);
        let mut scores = Scores::<f64, 4, 2, 2, 4, 1>::new();
        let tracks = [track(0, 0.0, 1.0), track(1, 50.0, 1.0)];
        let zs = [SVector::from([1.0, 0.0]), SVector::from([-9.0, 9.0])];
        let (drops, lost) = scores.run(&config, &model, &BirthCells::EMPTY, &tracks, 1.0, &zs).unwrap();
        assert_eq!((drops.count, lost), (0, 0));
        assert!(scores.predicted(0).in_field_of_view && !scores.predicted(1).in_field_of_view);
        let near = scores.entries(0, 2);
        assert!(near[0].is_finite() && near[1] == f64::NEG_INFINITY, "{near:?}: the second is outside the gate");
        assert!(scores.entries(1, 2).iter().all(|&e| e == f64::NEG_INFINITY));
    }

    #[test]
    fn a_failing_track_is_dropped_or_fails_the_scan_as_configured() {
        let tracks = [track(0, 0.0, 1.0), track(7, 3.0, 1e308)];
        let zs = [SVector::from([1.0, 0.0])];
        let strict = config(NumericalFailure::Error);
        let mut scores = Scores::<f64, 4, 2, 1, 4, 1>::new();
        let result = scores.run(&strict, &placed(&strict), &BirthCells::EMPTY, &tracks, 1.0, &zs);
        assert!(matches!(result, Err(StepError::Numerical { label: TrackLabel(7), .. })), "{result:?}");

        let lenient = config(NumericalFailure::DropTrack);
        let model = placed(&lenient);
        let (drops, _) = scores.run(&lenient, &model, &BirthCells::EMPTY, &tracks, 1.0, &zs).unwrap();
        assert_eq!(drops.count, 1);
        assert_eq!(drops.first.map(|(label, _)| label), Some(TrackLabel(7)));
        assert!(scores.predicted(1).dropped && !scores.predicted(1).in_field_of_view);
        assert!(!scores.predicted(0).dropped && scores.entries(0, 1)[0].is_finite());
    }

    #[test]
    fn a_track_in_view_without_a_measurement_in_its_gate_is_unseen_and_lost_after_the_configured_scans() {
        // Track 0 has a measurement in its gate, track 1 (at x = 50, out of the sector) is out of view,
        // track 2 (at x = 8) is in view and no measurement is in its gate; each has been unseen twice.
        let rule = TrackLoss::AfterUnseenScans(core::num::NonZeroU16::new(3).unwrap());
        let managed = Cv { track_loss: rule, ..config(NumericalFailure::Error) };
        let model = placed(&managed);
        let mut scores = Scores::<f64, 4, 2, 2, 4, 1>::new();
        let mut tracks = [track(0, 0.0, 1.0), track(1, 50.0, 1.0), track(2, 8.0, 1.0)];
        for t in &mut tracks {
            t.unseen_scans = 2;
        }
        let zs = [SVector::from([1.0, 0.0])];
        let (_, lost) = scores.run(&managed, &model, &BirthCells::EMPTY, &tracks, 1.0, &zs).unwrap();
        let unseen: Vec<u16> = (0..3).map(|slot| scores.predicted(slot).unseen_scans).collect();
        assert_eq!(unseen, [0, 2, 3]);
        assert_eq!(lost, 1);
        assert!(scores.predicted(2).dropped && !scores.predicted(2).in_field_of_view);
        assert!(scores.entries(2, 1).iter().all(|&e| e == f64::NEG_INFINITY));
        assert!(!scores.predicted(0).dropped && !scores.predicted(1).dropped);
        // Never: the same track is counted but kept.
        let exact = config(NumericalFailure::Error);
        let (_, lost) = scores.run(&exact, &placed(&exact), &BirthCells::EMPTY, &tracks, 1.0, &zs).unwrap();
        assert_eq!((lost, scores.predicted(2).unseen_scans, scores.predicted(2).dropped), (0, 3, false));
        // A stale entry beyond this scan's measurements does not count as a measurement in the gate.
        assert_eq!(unseen_scans(4, true, &[f64::NEG_INFINITY]), 5);
        assert_eq!(unseen_scans(4, false, &[f64::NEG_INFINITY]), 4);
    }
}
