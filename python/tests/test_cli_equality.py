"""The Python tracker's MAP estimates equal ``host-sim run``'s (estimates.csv) bit for bit, on planar
(version 1) and 3-D (version 2: radar, optical, a network of mixed kinds) presets, scan by scan; scans the CLI refused are refused
from Python with an InputError of the same kind, and the tracker goes on unchanged."""

from __future__ import annotations

from collections import defaultdict

import numpy as np
import pytest
import rfisst
from conftest import load

PLANAR = ["x", "y", "vx", "vy"]
ORBITAL = ["x", "y", "z", "vx", "vy", "vz"]


@pytest.mark.parametrize("preset", ["linear-small", "crossings", "tiny-3d", "optical-geo", "tiny-network"])
def test_map_estimates_equal_the_cli(host_sim, preset: str) -> None:
    path = host_sim.scenario(preset)
    scenario = load(path)
    rows = host_sim.estimates(preset)
    expected: dict[int, list[dict[str, str]]] = defaultdict(list)
    for row in rows:
        expected[int(row["scan"])].append(row)

    tracker = rfisst.Tracker.from_file(path)
    version = scenario.get("version", 1)
    assert tracker.version == version
    columns = PLANAR if version == 1 else ORBITAL
    compared = 0
    for k, scan in enumerate(scenario["scans"]):
        # A network's sensors have their own kinds: each scan's rows have its sensor's components.
        rows_of_scan = scan["measurements"]
        width = len(rows_of_scan[0]) if rows_of_scan else tracker.measurement_dim
        measurements = np.asarray(rows_of_scan, dtype=float).reshape(-1, width)
        try:
            tracker.step(scan["time"], measurements, scan.get("sensor"))
        except rfisst.InputError:
            pass  # refused: the CLI goes on too, its estimates those of the last accepted scan
        tracks = tracker.map_tracks()
        want = expected.get(k, [])
        assert [int(r["label"]) for r in want] == tracks["labels"].tolist(), f"scan {k}: labels"
        for row, mean, existence in zip(want, tracks["means"], tracks["existence"]):
            # float(repr) round-trips: equality is bit-identity.
            assert [float(row[c]) for c in columns] == mean.tolist(), f"scan {k}, label {row['label']}: mean"
            assert float(row["existence"]) == existence, f"scan {k}, label {row['label']}: existence"
            compared += 1
    assert compared == len(rows) and compared > 0


def test_dict_and_file_give_the_same_tracker(host_sim) -> None:
    path = host_sim.scenario("linear-small")
    scenario = load(path)
    from_file = rfisst.Tracker.from_file(path)
    from_dict = rfisst.Tracker.from_dict(scenario)
    for scan in scenario["scans"]:
        a = from_file.step(scan["time"], scan["measurements"])
        b = from_dict.step(scan["time"], np.asarray(scan["measurements"]))
        assert a == b
    assert from_file.map_tracks()["means"].tolist() == from_dict.map_tracks()["means"].tolist()
    assert from_file.expected_cardinality() == from_dict.expected_cardinality()
