"""The R-FISST tracker as a Stone Soup :class:`~stonesoup.tracker.base.Tracker`.

Registered through the ``stonesoup.plugins`` entry point, so that after ``pip install rfisst``::

    from stonesoup.plugins.rfisst import RFISSTTracker

It consumes a Stone Soup detector (``(time, detections)`` per scan) and yields ``(time, tracks)``: the
tracks of the MAP hypothesis, one :class:`~stonesoup.types.track.Track` per label, each a sequence of
:class:`~stonesoup.types.state.GaussianState`.

Two ways to give it its models:

* **Stone Soup models, planar tracker**: ``transition_model`` a
  :class:`~stonesoup.models.transition.linear.CombinedLinearGaussianTransitionModel` of two
  :class:`~stonesoup.models.transition.linear.ConstantVelocity` with the same ``noise_diff_coeff`` (state
  ``(x, vx, y, vy)``), and ``measurement_model`` a
  :class:`~stonesoup.models.measurement.linear.LinearGaussian` with ``ndim_state=4`` and ``mapping=(0, 2)``;
  plus the sensor (``detection_probability``, ``clutter_rate``, a rectangular ``field_of_view``), the birth
  model and the death probability, which Stone Soup's models do not carry.
* **A scenario** (``scenario``: a dict or a path in the format ``host-sim`` reads, version 1 or 2): the
  project's own models, among them the SSA ones (two-body + J2 with ground radars or telescopes); a
  detection's ``state_vector`` is then a measurement in the scenario's units (km, degrees, km/s) and its
  ``metadata["sensor"]`` names the sensor (index or name) when the scenario has several.

Any other model is refused with a :class:`TypeError` or :class:`ValueError` naming it.
"""

from __future__ import annotations

import datetime
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import Any

import numpy as np
from stonesoup.base import Property
from stonesoup.models.measurement.base import MeasurementModel
from stonesoup.models.measurement.linear import LinearGaussian
from stonesoup.models.transition.base import TransitionModel
from stonesoup.models.transition.linear import CombinedLinearGaussianTransitionModel, ConstantVelocity
from stonesoup.tracker.base import Tracker
from stonesoup.types.state import GaussianState
from stonesoup.types.track import Track

from ._rfisst import Tracker as CoreTracker

#: Stone Soup's planar CV state (x, vx, y, vy) from the core's (x, y, vx, vy): core = state[TO_CORE].
TO_CORE = np.array([0, 2, 1, 3])
#: The core's state to Stone Soup's: ss = core[FROM_CORE].
FROM_CORE = np.array([0, 2, 1, 3])


def _name(model: object) -> str:
    return type(model).__name__


def constant_velocity_noise(model: TransitionModel) -> float:
    """The acceleration noise q of a planar constant-velocity model, or a TypeError/ValueError naming
    what the core has no equivalent for."""
    if not isinstance(model, CombinedLinearGaussianTransitionModel):
        raise TypeError(
            f"transition_model: {_name(model)} has no equivalent in the R-FISST core; use "
            "CombinedLinearGaussianTransitionModel([ConstantVelocity(q), ConstantVelocity(q)]) or a scenario"
        )
    components = list(model.model_list)
    kinds = [_name(m) for m in components]
    if len(components) != 2 or not all(type(m) is ConstantVelocity for m in components):
        raise TypeError(
            f"transition_model: CombinedLinearGaussianTransitionModel of {kinds} has no equivalent in the "
            "R-FISST core; it takes exactly two ConstantVelocity components (planar x, y)"
        )
    q = [float(m.noise_diff_coeff) for m in components]
    if q[0] != q[1]:
        raise ValueError(
            f"transition_model: ConstantVelocity noise_diff_coeff {q[0]} and {q[1]} differ; the core's "
            "constant-velocity model has one acceleration noise for both axes"
        )
    if not (np.isfinite(q[0]) and q[0] > 0):
        raise ValueError(f"transition_model: ConstantVelocity noise_diff_coeff {q[0]} must be finite and > 0")
    return q[0]


def position_noise(model: MeasurementModel) -> list[list[float]]:
    """The 2 x 2 noise covariance of a linear (x, y) position measurement model, or a TypeError/ValueError
    naming what the core has no equivalent for."""
    if type(model) is not LinearGaussian:
        raise TypeError(
            f"measurement_model: {_name(model)} has no equivalent in the R-FISST planar core; use "
            "LinearGaussian(ndim_state=4, mapping=(0, 2), noise_covar=R) or a scenario"
        )
    mapping = tuple(int(i) for i in model.mapping)
    if model.ndim_state != 4 or mapping != (0, 2):
        raise ValueError(
            f"measurement_model: LinearGaussian with ndim_state={model.ndim_state}, mapping={mapping}; the "
            "core measures the position (x, y) of a state (x, vx, y, vy): ndim_state=4, mapping=(0, 2)"
        )
    noise = np.asarray(model.noise_covar, dtype=float)
    if noise.shape != (2, 2):
        raise ValueError(f"measurement_model: noise_covar of shape {noise.shape}, expected (2, 2)")
    return noise.tolist()


def _gaussian(state: GaussianState, what: str) -> tuple[list[float], list[list[float]]]:
    """(mean, covariance) in the core's order of a Stone Soup planar GaussianState."""
    mean = np.asarray(state.state_vector, dtype=float).reshape(-1)
    covar = np.asarray(state.covar, dtype=float)
    if mean.shape != (4,) or covar.shape != (4, 4):
        raise ValueError(f"{what}: a GaussianState of (x, vx, y, vy), got mean {mean.shape} covar {covar.shape}")
    return mean[TO_CORE].tolist(), covar[np.ix_(TO_CORE, TO_CORE)].tolist()


class RFISSTTracker(Tracker):
    """The R-FISST multi-object tracker (Rust core) fed by a Stone Soup detector."""

    detector: Any = Property(doc="Detector: yields (time, set of Detection) per scan")
    transition_model: TransitionModel = Property(
        default=None, doc="Two ConstantVelocity components with one noise_diff_coeff (planar); None with a scenario")
    measurement_model: MeasurementModel = Property(
        default=None, doc="LinearGaussian(ndim_state=4, mapping=(0, 2)) (planar); None with a scenario")
    detection_probability: float = Property(default=0.9, doc="p_D inside the field of view")
    clutter_rate: float = Property(default=1.0, doc="Expected clutter detections per scan")
    field_of_view: Sequence = Property(
        default=None, doc="((x_min, x_max), (y_min, y_max)): where the sensor sees (planar; required)")
    birth_density: Any = Property(
        default=None, doc="GaussianState or list of GaussianStates (x, vx, y, vy): where objects are born")
    birth_probability: float = Property(default=0.01, doc="alpha: probability of a birth per cell and scan")
    birth_events: str = Property(
        default="first-order",
        doc="'first-order' (at most one birth per scan, R-FISST's model) or 'independent' (each cell gives "
        "birth independently: several births per scan with several cells)",
    )
    death_probability: float = Property(default=0.005, doc="beta: probability of a death per object and scan")
    prior: Sequence = Property(default=(), doc="GaussianStates (x, vx, y, vy) of the objects known at the start")
    start_time: datetime.datetime = Property(
        default=None,
        doc="Time 0 of the core's clock (the prior's time); required with a scenario; with Stone Soup models "
        "default the prior's earliest timestamp, else 1 s before the first scan",
    )
    gate: float = Property(default=16.0, doc="Chi-square gate on the squared Mahalanobis distance")
    seed: int = Property(default=1, doc="Seed of the sampler")
    tracker: str = Property(default="rfisst", doc="'rfisst' (sampled children) or 'homht' (exhaustive)")
    profile: str = Property(default=None, doc="Capacities: 'embedded' (default) or 'host'")
    scenario: Any = Property(
        default=None, doc="Instead of Stone Soup models: a scenario dict or path (host-sim's format, v1 or v2)")
    outside_field_of_view: str = Property(
        default="error", doc="A detection outside the field of view: 'error' (InputError) or 'drop'")

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        if self.outside_field_of_view not in ("error", "drop"):
            raise ValueError(f"outside_field_of_view: {self.outside_field_of_view!r} is not 'error' or 'drop'")
        self._core: CoreTracker | None = None
        self._epoch: datetime.datetime | None = self.start_time
        self._tracks: dict[int, Track] = {}
        self._live: set[Track] = set()
        self._detector_iter: Iterator | None = None
        self.dropped_detections = 0
        self.last_report: dict | None = None
        if self.scenario is not None:
            if self.transition_model is not None or self.measurement_model is not None:
                raise ValueError("scenario: give either a scenario or Stone Soup models, not both")
            if self.start_time is None:
                raise ValueError("start_time: required with a scenario (the datetime of the scenario's time 0)")
        else:
            constant_velocity_noise(self.transition_model)
            position_noise(self.measurement_model)
            if self.field_of_view is None:
                raise ValueError("field_of_view: required with Stone Soup models: ((x_min, x_max), (y_min, y_max))")

    @property
    def tracks(self) -> set[Track]:
        return set(self._live)

    def __iter__(self):
        self._detector_iter = iter(self.detector)
        return self

    def __next__(self) -> tuple[datetime.datetime, set[Track]]:
        if self._detector_iter is None:
            self._detector_iter = iter(self.detector)
        time, detections = next(self._detector_iter)
        return self.update(time, detections)

    # --- building the core tracker ---

    def _prior_time(self, first_scan: datetime.datetime) -> datetime.datetime:
        if self._epoch is not None:
            return self._epoch
        # Stone Soup models: the core's prior is at time 0.
        stamps = [s.timestamp for s in self.prior if getattr(s, "timestamp", None) is not None]
        return min(stamps) if stamps else first_scan - datetime.timedelta(seconds=1)

    def scenario_dict(self) -> dict:
        """The version 1 scenario (without scans) these Stone Soup models and settings make."""
        (x_min, x_max), (y_min, y_max) = self.field_of_view
        births = self.birth_density
        if births is None:
            births = []
        elif isinstance(births, GaussianState):
            births = [births]
        cells = [dict(zip(("mean", "covariance"), _gaussian(b, "birth_density"))) for b in births]
        objects = [
            dict(label=i, **dict(zip(("mean", "covariance"), _gaussian(s, "prior")))) for i, s in enumerate(self.prior)
        ]
        return {
            "format": "rfisst-scenario/1",
            "name": "stonesoup",
            "motion": {"type": "constant-velocity", "acceleration_noise": constant_velocity_noise(self.transition_model)},
            "measurement": {"type": "position", "noise_covariance": position_noise(self.measurement_model)},
            "sensor": {
                "detection_probability": float(self.detection_probability),
                "clutter_rate": float(self.clutter_rate),
                "field_of_view": {
                    "type": "rectangle",
                    "min": [float(x_min), float(y_min)],
                    "max": [float(x_max), float(y_max)],
                },
            },
            "birth": {"probability": float(self.birth_probability), "events": self.birth_events, "cells": cells},
            "death_probability": float(self.death_probability),
            "tracker": {"gate": float(self.gate), "max_children_per_scan": 1_000_000, "seed": int(self.seed)},
            "prior": {"time": 0.0, "hypotheses": [{"weight": 1.0, "objects": objects}]},
            "scans": [],
        }

    def _build(self, first_scan: datetime.datetime) -> CoreTracker:
        self._epoch = self._prior_time(first_scan)
        if self.scenario is None:
            return CoreTracker.from_dict(self.scenario_dict(), tracker=self.tracker, profile=self.profile)
        if isinstance(self.scenario, (str, Path)):
            return CoreTracker.from_file(self.scenario, tracker=self.tracker, profile=self.profile)
        return CoreTracker.from_dict(self.scenario, tracker=self.tracker, profile=self.profile)

    # --- one scan ---

    def _inside(self, z: np.ndarray) -> bool:
        (x_min, x_max), (y_min, y_max) = self.field_of_view
        return bool(x_min <= z[0] <= x_max and y_min <= z[1] <= y_max)

    def _measurements(self, detections) -> tuple[np.ndarray, Any]:
        """The scan's measurements (n, D) and its sensor (None, or the detections' common sensor)."""
        # Sorted: a set's order changes from run to run, and the tracker's result depends on the order.
        rows = sorted((np.asarray(d.state_vector, dtype=float).reshape(-1) for d in detections), key=tuple)
        sensors = {d.metadata.get("sensor") for d in detections if d.metadata}
        sensors.discard(None)
        if len(sensors) > 1:
            raise ValueError(f"detections: one scan holds detections of several sensors {sorted(map(str, sensors))}")
        sensor = next(iter(sensors), None)
        if self.scenario is None and self.outside_field_of_view == "drop":
            kept = [z for z in rows if z.shape != (2,) or self._inside(z)]
            self.dropped_detections += len(rows) - len(kept)
            rows = kept
        dim = self._core.measurement_dim if self._core is not None else 2
        return (np.vstack(rows) if rows else np.zeros((0, dim))), sensor

    def _state(self, mean: np.ndarray, covar: np.ndarray, time: datetime.datetime) -> GaussianState:
        if self._core is not None and self._core.version == 1:
            return GaussianState(mean[FROM_CORE].reshape(-1, 1), covar[np.ix_(FROM_CORE, FROM_CORE)], timestamp=time)
        return GaussianState(mean.reshape(-1, 1), covar, timestamp=time)

    def update(self, time: datetime.datetime, detections) -> tuple[datetime.datetime, set[Track]]:
        """Steps the tracker with one scan (as iterating does); returns the time and the MAP tracks."""
        if self._core is None:
            self._core = self._build(time)
        measurements, sensor = self._measurements(detections)
        if sensor is None and self._core.version == 2 and len(self._core.sensors) > 1 and len(measurements) == 0:
            # A scan without detections says nothing of which sensor looked: nothing to step.
            return time, self.tracks
        seconds = (time - self._epoch).total_seconds()
        self.last_report = self._core.step(seconds, measurements, sensor)
        map_tracks = self._core.map_tracks()
        live = set()
        for label, mean, covar in zip(map_tracks["labels"], map_tracks["means"], map_tracks["covariances"]):
            label = int(label)
            track = self._tracks.get(label)
            if track is None:
                track = self._tracks[label] = Track(id=f"rfisst-{label}")
            track.append(self._state(mean, covar, time))
            live.add(track)
        self._live = live
        return time, self.tracks

    @property
    def core(self) -> CoreTracker | None:
        """The core tracker (None before the first scan)."""
        return self._core
