"""A complete Stone Soup run with the R-FISST plugin: Stone Soup's own multi-target simulator (constant
velocity, clutter, targets born and dying), the plugin as its tracker, Stone Soup's GOSPA metric.

Run: python python/examples/stonesoup_quickstart.py   (after `pip install ./python[test]`)
python/tests/test_examples.py runs it.
"""

import datetime

import numpy as np
from stonesoup.models.measurement.linear import LinearGaussian
from stonesoup.models.transition.linear import CombinedLinearGaussianTransitionModel, ConstantVelocity
from stonesoup.plugins.rfisst import RFISSTTracker  # found through the stonesoup.plugins entry point
from stonesoup.simulator.simple import MultiTargetGroundTruthSimulator, SimpleDetectionSimulator
from stonesoup.types.state import GaussianState

start = datetime.datetime(2026, 1, 1)
transition = CombinedLinearGaussianTransitionModel([ConstantVelocity(0.05), ConstantVelocity(0.05)])
measurement = LinearGaussian(ndim_state=4, mapping=(0, 2), noise_covar=np.diag([0.25, 0.25]))
birth = GaussianState([[0.0], [0.0], [0.0], [0.0]], np.diag([400.0, 1.0, 400.0, 1.0]), timestamp=start)
truths = MultiTargetGroundTruthSimulator(
    transition_model=transition,
    initial_state=birth,
    timestep=datetime.timedelta(seconds=1),
    number_steps=40,
    birth_rate=0.15,
    death_probability=0.01,
    seed=7,
)
detector = SimpleDetectionSimulator(
    groundtruth=truths,
    measurement_model=measurement,
    meas_range=np.array([[-60.0, 60.0], [-60.0, 60.0]]),
    detection_probability=0.9,
    clutter_rate=2.0,
    seed=7,
)
tracker = RFISSTTracker(
    detector=detector,
    transition_model=transition,
    measurement_model=measurement,
    detection_probability=0.9,
    clutter_rate=2.0,
    field_of_view=((-60.0, 60.0), (-60.0, 60.0)),
    birth_density=birth,
    birth_probability=0.05,
    death_probability=0.01,
    start_time=start - datetime.timedelta(seconds=1),
    outside_field_of_view="drop",  # targets that wander out of the window are no longer seen
)
scans, tracks = 0, set()
for time, current in tracker:  # each scan: the MAP hypothesis's tracks (Stone Soup Tracks)
    scans += 1
    tracks |= current
    print(time.time(), len(current), "tracks")
print(f"scans {scans} tracks {len(tracks)}")
