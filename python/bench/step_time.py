"""Mean wall-clock ms per scan of ``rfisst.Tracker.step`` over a scenario's scans (numpy conversion
included; best of 3 runs), to set against ``host-sim run``'s ``mean_ms_per_scan`` (summary.json).

Usage: python python/bench/step_time.py SCENARIO.json
"""

import json
import sys
import time

import numpy as np
import rfisst


def main(path: str) -> None:
    with open(path) as f:
        scenario = json.load(f)
    scans = [(s["time"], np.asarray(s["measurements"], dtype=float), s.get("sensor")) for s in scenario["scans"]]
    best = None
    for repeat in range(3):
        tracker = rfisst.Tracker.from_file(path)
        times = []
        for t, measurements, sensor in scans:
            measurements = measurements.reshape(-1, tracker.measurement_dim)
            start = time.perf_counter()
            try:
                tracker.step(t, measurements, sensor)
            except rfisst.InputError:
                pass  # refused, as host-sim run refuses it
            times.append(time.perf_counter() - start)
        mean = 1e3 * sum(times) / len(times)
        print(f"run {repeat}: mean {mean:.3f} ms/scan, max {1e3 * max(times):.3f} ms")
        best = mean if best is None else min(best, mean)
    print(f"best mean {best:.3f} ms/scan over {len(scans)} scans")


if __name__ == "__main__":
    main(sys.argv[1])
