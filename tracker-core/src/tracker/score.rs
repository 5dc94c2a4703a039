//! Stage 1 of a scan: predict every track of the shared store once, and score it against every measurement
//! once. The entries δ of docs/maths.md §4.2 computed here serve every parent hypothesis that holds the
//! track; birth cells are scored the same way.

use crate::config::{Config, NumericalFailure};
use crate::ekf::{self, Gaussian, Innovation, NumericalError};
use crate::error::StepError;
use crate::index::At;
use crate::model::{MeasurementModel, MotionModel};
use crate::real::Real;
use crate::report::NumericalDrops;
use crate::store::Track;
use crate::weight::WeightModel;
use nalgebra::SVector;

/// A track after prediction to the current scan.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(super) struct Predicted<T: Real, const S: usize, const D: usize> {
    pub(super) state: Gaussian<T, S>,
    pub(super) innovation: Innovation<T, D>,
    pub(super) in_field_of_view: bool,
    /// Dropped for a numerical failure ([`NumericalFailure::DropTrack`]): in no child of this scan.
    pub(super) dropped: bool,
}

/// The birth cells as the sensor sees them, fixed by the configuration: each cell's predicted
/// measurement and whether it lies in the field of view.
#[derive(Debug, Clone, Copy)]
pub(super) struct BirthCells<T: Real, const D: usize, const B: usize> {
    pub(super) innovations: [Innovation<T, D>; B],
    pub(super) in_field_of_view: [bool; B],
}

impl<T: Real, const D: usize, const B: usize> BirthCells<T, D, B> {
    pub(super) const EMPTY: Self = Self { innovations: [Innovation::EMPTY; B], in_field_of_view: [false; B] };

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
            }; K],
            entries: [[T::NEG_INFINITY; Z]; K],
            birth_entries: [[T::NEG_INFINITY; Z]; B],
        }
    }

    /// Predicts every track in `tracks` by `dt` and scores it, and every birth cell, against every
    /// measurement (`-inf` outside the gate or the field of view). A track whose prediction, innovation
    /// or (in view) update gain fails is dropped from the scan or fails it, as `config.numerical_failure`
    /// says; the dropped ones are returned.
    ///
    /// # Errors
    /// With [`NumericalFailure::Error`], [`StepError::Numerical`] naming the first track that fails.
    pub(super) fn run<M, G>(
        &mut self,
        config: &Config<T, M, G, S, B>,
        weight_model: &WeightModel<T>,
        birth_cells: &BirthCells<T, D, B>,
        tracks: &[Track<T, S>],
        dt: T,
        measurements: &[SVector<T, D>],
    ) -> Result<NumericalDrops, StepError>
    where
        M: MotionModel<T, S>,
        G: MeasurementModel<T, S, D>,
    {
        let mut drops = NumericalDrops::default();
        let slots = self.predicted.iter_mut().zip(self.entries.iter_mut());
        for (track, (predicted, entries)) in tracks.iter().zip(slots) {
            *predicted = match predict_track(config, track, dt) {
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
                    }
                }
            };
            score_row(entries, weight_model, &predicted.innovation, predicted.in_field_of_view, measurements);
        }
        let cells =
            self.birth_entries.iter_mut().zip(birth_cells.innovations.iter().zip(&birth_cells.in_field_of_view));
        for (entries, (innovation, &in_field_of_view)) in cells.take(config.birth.cells.len()) {
            score_row(entries, weight_model, innovation, in_field_of_view, measurements);
        }
        Ok(drops)
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

/// Predicts `track` by `dt`: its state, innovation and whether it is in view; for a track in view, also
/// checks that an update is possible (its gain and posterior covariance), so that a failure drops or fails
/// the track before any child holds it.
fn predict_track<T: Real, M, G, const S: usize, const D: usize, const B: usize>(
    config: &Config<T, M, G, S, B>,
    track: &Track<T, S>,
    dt: T,
) -> Result<Predicted<T, S, D>, NumericalError>
where
    M: MotionModel<T, S>,
    G: MeasurementModel<T, S, D>,
{
    let state = ekf::predict(&config.motion, &track.state, dt)?;
    let innovation = ekf::innovation(&config.measurement, &state)?;
    let in_field_of_view = config.sensor.field_of_view.contains(&innovation.predicted);
    if in_field_of_view {
        ekf::correction(&config.measurement, &state, &innovation)?;
    }
    Ok(Predicted { state, innovation, in_field_of_view, dropped: false })
}

/// δ of one track or birth cell against every measurement, `-inf` everywhere when it is out of view.
fn score_row<T: Real, const D: usize>(
    entries: &mut [T],
    weight_model: &WeightModel<T>,
    innovation: &Innovation<T, D>,
    in_field_of_view: bool,
    measurements: &[SVector<T, D>],
) {
    for (entry, z) in entries.iter_mut().zip(measurements) {
        *entry = if in_field_of_view { weight_model.entry(innovation, z) } else { T::NEG_INFINITY };
    }
}
