"""The Tracker's API: hypotheses, cardinality, the step report, and typed exceptions for bad input that
leave the tracker unchanged."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import rfisst
from conftest import load


@pytest.fixture()
def planar(host_sim):
    path = host_sim.scenario("linear-small")
    return rfisst.Tracker.from_file(path), load(path)


@pytest.fixture()
def orbital(host_sim):
    path = host_sim.scenario("tiny-3d")
    return rfisst.Tracker.from_file(path), load(path)


def state(tracker: rfisst.Tracker):
    """Everything a caller can read of the posterior, as plain lists (bit-exact comparisons)."""
    h = tracker.hypotheses()
    t = tracker.tracks()
    return (
        tracker.time,
        h["weights"].tolist(),
        [labels.tolist() for labels in h["labels"]],
        t["means"].tolist(),
        t["covariances"].tolist(),
    )


def test_hypotheses_cardinality_and_report(planar) -> None:
    tracker, scenario = planar
    assert (tracker.state_dim, tracker.measurement_dim, tracker.measurement_kind) == (4, 2, "position")
    for scan in scenario["scans"]:
        report = tracker.step(scan["time"], scan["measurements"])
    h = tracker.hypotheses()
    weights = h["weights"]
    assert report["hypotheses"] == len(weights) == len(h["labels"]) > 1
    assert np.all(np.diff(weights) <= 0), "best first"
    assert math.isclose(weights.sum(), 1.0, rel_tol=1e-12)
    assert np.allclose(np.exp(h["log_weights"]), weights, rtol=1e-12)
    expected = sum(w * len(labels) for w, labels in zip(weights, h["labels"]))
    assert math.isclose(tracker.expected_cardinality(), expected, rel_tol=1e-12)
    assert math.isclose(report["expected_cardinality"], expected, rel_tol=1e-12)
    assert report["scan"] == len(scenario["scans"])
    assert report["measurements"] == len(scenario["scans"][-1]["measurements"])
    map_tracks = tracker.map_tracks()
    assert map_tracks["labels"].tolist() == h["labels"][0].tolist()
    covariances = map_tracks["covariances"]
    assert covariances.shape == (len(map_tracks["labels"]), 4, 4)
    assert np.allclose(covariances, np.transpose(covariances, (0, 2, 1)))
    tracks = tracker.tracks()
    for labels, indices in zip(h["labels"], h["track_indices"]):
        assert tracks["labels"][indices].tolist() == labels.tolist()


BAD_PLANAR = [
    ("wrong shape", lambda t: t.step(100.0, np.zeros((2, 3))), rfisst.InputError, "WrongShape"),
    ("1-D", lambda t: t.step(100.0, np.zeros(2)), rfisst.InputError, "WrongShape"),
    ("not numbers", lambda t: t.step(100.0, [["a", "b"]]), rfisst.InputError, "NotNumeric"),
    ("NaN", lambda t: t.step(100.0, [[0.0, math.nan]]), rfisst.InputError, "NonFiniteMeasurement"),
    ("infinite", lambda t: t.step(100.0, [[math.inf, 0.0]]), rfisst.InputError, "NonFiniteMeasurement"),
    ("NaN time", lambda t: t.step(math.nan, [[0.0, 0.0]]), rfisst.InputError, "NonFiniteTime"),
    ("time going back", lambda t: t.step(-1.0, [[0.0, 0.0]]), rfisst.InputError, "TimeNotAfterLastScan"),
    ("outside the field of view", lambda t: t.step(100.0, [[1e6, 0.0]]), rfisst.InputError,
     "MeasurementOutsideFieldOfView"),
    ("too many", lambda t: t.step(100.0, np.zeros((1000, 2))), rfisst.InputError, "TooManyMeasurements"),
    ("unknown sensor", lambda t: t.step(100.0, [[0.0, 0.0]], sensor=1), rfisst.InputError, "UnknownSensor"),
    ("sensor name", lambda t: t.step(100.0, [[0.0, 0.0]], sensor="radar"), rfisst.InputError, "UnknownSensor"),
]


@pytest.mark.parametrize("case", BAD_PLANAR, ids=[c[0] for c in BAD_PLANAR])
def test_bad_scan_raises_and_leaves_the_tracker_unchanged(planar, case) -> None:
    tracker, scenario = planar
    first = scenario["scans"][0]
    tracker.step(first["time"], first["measurements"])
    before = state(tracker)
    _, call, error, kind = case
    with pytest.raises(error) as raised:
        call(tracker)
    assert raised.value.kind == kind
    assert isinstance(raised.value, rfisst.TrackerError) and isinstance(raised.value, ValueError)
    assert raised.value.message and "\n" not in raised.value.message
    assert state(tracker) == before
    # And it goes on as if nothing happened.
    second = scenario["scans"][1]
    tracker.step(second["time"], second["measurements"])


def test_orbital_sensor_by_name_or_index(orbital) -> None:
    tracker, scenario = orbital
    assert (tracker.state_dim, tracker.measurement_dim, tracker.measurement_kind) == (6, 3, "radar")
    name = tracker.sensors[0]
    scan = scenario["scans"][0]
    by_name = rfisst.Tracker.from_dict(scenario)
    assert tracker.step(scan["time"], scan["measurements"], 0) == by_name.step(scan["time"], scan["measurements"], name)
    for sensor in (1, -1, "nowhere", 0.5):
        with pytest.raises(rfisst.InputError) as raised:
            tracker.step(scan["time"] + 10.0, scan["measurements"], sensor)
        assert raised.value.kind == "UnknownSensor"
    with pytest.raises(rfisst.InputError) as raised:
        tracker.step(scan["time"] + 10.0, np.zeros((1, 2)), 0)
    assert raised.value.kind == "WrongShape"


def test_bad_scenarios(tmp_path, host_sim) -> None:
    scenario = load(host_sim.scenario("linear-small"))
    cases = {
        "not a scenario": {"format": "x"},
        "NaN noise": {**scenario, "motion": {"type": "constant-velocity", "acceleration_noise": math.nan}},
        "negative noise": {**scenario, "motion": {"type": "constant-velocity", "acceleration_noise": -1.0}},
        "unknown version": {**scenario, "version": 7},
        "not JSON data": {**scenario, "name": object()},
    }
    for what, bad in cases.items():
        with pytest.raises(rfisst.ScenarioError, match=".") as raised:
            rfisst.Tracker.from_dict(bad)
        assert raised.value.kind, what
    with pytest.raises(rfisst.ScenarioError):
        rfisst.Tracker.from_file(tmp_path / "missing.json")
    (tmp_path / "broken.json").write_text("{")
    with pytest.raises(rfisst.ScenarioError):
        rfisst.Tracker.from_file(tmp_path / "broken.json")
    with pytest.raises(rfisst.ScenarioError):
        rfisst.Tracker.from_json(json.dumps(scenario), tracker="reference")
    with pytest.raises(rfisst.ScenarioError):
        rfisst.Tracker.from_json(json.dumps(scenario), profile="huge")
    # More birth cells than the embedded profile holds (B = 8): refused by the core's configuration.
    cells = scenario["birth"]["cells"] * 9
    with pytest.raises(rfisst.ScenarioError) as raised:
        rfisst.Tracker.from_dict({**scenario, "birth": {**scenario["birth"], "cells": cells}})
    assert raised.value.kind == "Configuration"
    assert rfisst.Tracker.from_dict({**scenario, "birth": {**scenario["birth"], "cells": cells}}, profile="host")
