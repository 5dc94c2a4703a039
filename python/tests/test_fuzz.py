"""Hostile input to the Python package, generated from a seeded stream (a fuzz test that runs in pytest).

Each case drives a fresh tracker (planar, radar, mixed network) through a sequence of calls whose
arguments are drawn from hostile families: arrays of every dtype, shape and memory layout, NaN, infinities
and extreme magnitudes, ragged lists, times that go back or jump by 1e300 s, sensors that do not exist or
are 100,000-character names. The contract checked on every call:

- it returns a step report, or raises a :class:`rfisst.TrackerError` (never another exception, never a
  crash of the interpreter) whose message is one short line;
- a call that raises leaves the tracker exactly as it was (times, weights, labels, means, covariances);
- the same seed gives the same outcomes and the same final state (the stream replays).

Scenario dicts are fuzzed the same way: one leaf replaced by a hostile value gives a tracker or a
:class:`rfisst.ScenarioError`. ``RFISST_FUZZ_CASES`` (calls per tracker, default 120) and
``RFISST_FUZZ_SEED`` make it a longer fuzz run (docs/robustness.md).
"""

from __future__ import annotations

import copy
import math
import os

import numpy as np
import pytest
import rfisst
from conftest import load

CASES = int(os.environ.get("RFISST_FUZZ_CASES", "120"))
SEED = int(os.environ.get("RFISST_FUZZ_SEED", "1"))
MESSAGE_LIMIT = 1100  # host_sim::scenario::quote::MAX_MESSAGE_CHARS (1000) and its "… (n bytes)"
PRESETS = ["linear-small", "tiny-3d", "tiny-network"]

SPECIAL = [math.nan, math.inf, -math.inf, 1e308, -1e308, 5e-324, -0.0, 0.0, 1e-300, 2.0**63, -(2.0**63)]
DTYPES = [np.float64, np.float32, np.float16, np.int64, np.int8, np.uint64, np.bool_, np.complex128, object, "U4"]


def state(tracker: rfisst.Tracker):
    """Everything a caller can read of the posterior, as plain lists (bit-exact comparisons, NaN-safe)."""
    h = tracker.hypotheses()
    t = tracker.tracks()
    bits = lambda a: np.ascontiguousarray(a, dtype=np.float64).view(np.uint64).tolist()  # noqa: E731
    return (
        repr(tracker.time),
        bits(h["weights"]),
        [labels.tolist() for labels in h["labels"]],
        bits(t["means"]),
        bits(t["covariances"]),
    )


def hostile_measurements(rng: np.random.Generator, scan: list, dim: int):
    """One measurement argument: a real scan, a perturbed one, or something hostile."""
    rows = np.array(scan, dtype=np.float64).reshape(-1, dim) if len(scan) else np.zeros((0, dim))
    family = int(rng.integers(0, 11))
    if family == 0:
        return rows
    if family == 1:  # a real scan with one entry replaced by a special value
        bad = rows.copy() if len(rows) else np.zeros((1, dim))
        bad[rng.integers(0, len(bad)), rng.integers(0, dim)] = SPECIAL[rng.integers(0, len(SPECIAL))]
        return bad
    if family == 2:  # any shape and dtype
        shape = tuple(int(s) for s in rng.integers(0, 5, size=int(rng.integers(0, 4))))
        dtype = DTYPES[rng.integers(0, len(DTYPES))]
        values = rng.normal(0.0, 10.0 ** float(rng.integers(-3, 9)), size=shape)
        return values.astype(dtype) if dtype != "U4" else values.astype(str)
    if family == 3:  # the right width in another dtype
        return rows.astype(DTYPES[rng.integers(0, len(DTYPES))])
    if family == 4:  # ragged lists
        return [list(r) for r in rows] + [[0.0] * int(rng.integers(0, dim + 3))]
    if family == 5:  # not an array at all
        return [None, "scan", {"a": 1}, 3.5, b"\x00\x01", [[None] * dim], object()][rng.integers(0, 7)]
    if family == 6:  # more rows than any capacity
        return np.tile(rows if len(rows) else np.zeros((1, dim)), (int(rng.integers(33, 2000)), 1))
    if family == 7:  # non-contiguous and Fortran-ordered views of the same numbers
        wide = np.repeat(rows, 2, axis=1)
        return [wide[:, ::2], np.asfortranarray(rows), rows[::-1]][rng.integers(0, 3)]
    if family == 8:  # a real scan scaled by a huge or tiny factor
        return rows * 10.0 ** float(rng.integers(-300, 300))
    if family == 9:  # the transpose
        return rows.T
    return rows + rng.normal(0.0, 1e-3, size=rows.shape)


def hostile_time(rng: np.random.Generator, last: float, nominal: float):
    if int(rng.integers(0, 12)) < 9:
        return nominal
    hostile = [math.nan, math.inf, -math.inf, last, last - 1.0, last + 1e300, 1e308, np.float32(nominal), None,
               "10", [nominal]]
    return hostile[rng.integers(0, len(hostile))]


def hostile_sensor(rng: np.random.Generator, sensors: list[str], own):
    """The scan's own sensor most of the time, else another one or something that is no sensor."""
    family = int(rng.integers(0, 12))
    if family < 6 or (family < 8 and not sensors):
        return own
    if family < 8:
        return [int(rng.integers(0, len(sensors))), sensors[rng.integers(0, len(sensors))]][rng.integers(0, 2)]
    return [-1, len(sensors) + 1, 2**70, 0.5, "x" * 100_000, "", "\n", True, [0], None][rng.integers(0, 10)]


def drive(tracker: rfisst.Tracker, scenario: dict, seed: int):
    """Runs CASES hostile calls; returns what each call gave and the final state."""
    rng = np.random.default_rng(seed)
    scans = scenario["scans"]
    outcomes = []
    for case in range(CASES):
        scan = scans[case % len(scans)]
        nominal = scan["time"] + (case // len(scans)) * 1.0e4
        time = hostile_time(rng, tracker.time, nominal)
        # A network's scan has its own sensor kind's width.
        dim = len(scan["measurements"][0]) if scan["measurements"] else tracker.measurement_dim
        measurements = hostile_measurements(rng, scan["measurements"], dim)
        sensor = hostile_sensor(rng, tracker.sensors, scan.get("sensor"))
        before = state(tracker)
        try:
            report = tracker.step(time, measurements, sensor)
        except rfisst.TrackerError as e:
            assert e.message and "\n" not in e.message, f"case {case}: {e!r}"
            assert len(e.message) <= MESSAGE_LIMIT, f"case {case}: {len(e.message)}-character message"
            assert state(tracker) == before, f"case {case}: {e.kind} changed the tracker"
            outcomes.append(e.kind)
        else:
            assert report["scan"] >= 1
            outcomes.append("ok")
    return outcomes, state(tracker)


@pytest.mark.parametrize("preset", PRESETS)
def test_hostile_steps_raise_typed_errors_and_change_nothing(host_sim, preset) -> None:
    path = host_sim.scenario(preset)
    scenario = load(path)
    outcomes, final = drive(rfisst.Tracker.from_file(path), scenario, SEED)
    assert "ok" in outcomes, "the stream reached no valid scan"
    assert len(set(outcomes)) > 3, f"the stream hit few error kinds: {sorted(set(outcomes))}"
    replay, replay_final = drive(rfisst.Tracker.from_file(path), scenario, SEED)
    assert (replay, replay_final) == (outcomes, final)


def leaves(value, path=()):
    """Every (path, leaf) of a JSON value."""
    if isinstance(value, dict):
        for key, inner in value.items():
            yield from leaves(inner, (*path, key))
    elif isinstance(value, list):
        for index, inner in enumerate(value[:4]):
            yield from leaves(inner, (*path, index))
    else:
        yield path, value


HOSTILE_LEAVES = [math.nan, math.inf, -1.0, 0.0, 1e308, -1e308, 2**64, "", "x" * 100_000, None, [], {}, True,
                  [math.nan] * 3, "\n"]


@pytest.mark.parametrize("preset", PRESETS)
def test_hostile_scenarios_give_a_tracker_or_a_scenario_error(host_sim, preset) -> None:
    scenario = load(host_sim.scenario(preset))
    paths = [p for p, _ in leaves(scenario) if p and p[0] != "scans" and p[0] != "truth"]
    rng = np.random.default_rng(SEED)
    kinds = set()
    for case in range(max(CASES // 2, 20)):
        bad = copy.deepcopy(scenario)
        path = paths[rng.integers(0, len(paths))]
        target = bad
        for key in path[:-1]:
            target = target[key]
        target[path[-1]] = HOSTILE_LEAVES[rng.integers(0, len(HOSTILE_LEAVES))]
        try:
            tracker = rfisst.Tracker.from_dict(bad)
        except rfisst.ScenarioError as e:
            assert e.message and "\n" not in e.message, f"case {case} {path}: {e!r}"
            assert len(e.message) <= MESSAGE_LIMIT, f"case {case} {path}: {len(e.message)}-character message"
            kinds.add(e.kind)
            continue
        scan = scenario["scans"][0]
        try:
            tracker.step(scan["time"], scan["measurements"], scan.get("sensor"))
        except rfisst.TrackerError as e:
            assert "\n" not in e.message and len(e.message) <= MESSAGE_LIMIT, f"case {case} {path}: {e!r}"
    assert kinds, "no hostile scenario was refused"
