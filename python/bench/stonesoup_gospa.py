"""R-FISST (the Stone Soup plugin) against Stone Soup's GNN and JPDA trackers on the same detections of
Stone Soup's own multi-target simulation (constant velocity, clutter, births and deaths), scored by Stone
Soup's GOSPA metric (positions, p = 1, c = 10, alpha = 2), with the wall-clock time per step of each.

Usage: python python/bench/stonesoup_gospa.py [SEED ...]     (default seeds 1 to 5)
Also imported by python/tests/test_stonesoup.py.
"""

from __future__ import annotations

import datetime
import sys
import time

import numpy as np
from stonesoup.dataassociator.neighbour import GNNWith2DAssignment
from stonesoup.dataassociator.probability import JPDA
from stonesoup.deleter.error import CovarianceBasedDeleter
from stonesoup.hypothesiser.distance import DistanceHypothesiser
from stonesoup.hypothesiser.probability import PDAHypothesiser
from stonesoup.initiator.simple import MultiMeasurementInitiator
from stonesoup.measures import Euclidean, Mahalanobis
from stonesoup.metricgenerator.ospametric import GOSPAMetric
from stonesoup.models.measurement.linear import LinearGaussian
from stonesoup.models.transition.linear import CombinedLinearGaussianTransitionModel, ConstantVelocity
from stonesoup.predictor.kalman import KalmanPredictor
from stonesoup.simulator.simple import MultiTargetGroundTruthSimulator, SimpleDetectionSimulator
from stonesoup.tracker.simple import MultiTargetMixtureTracker, MultiTargetTracker
from stonesoup.types.state import GaussianState
from stonesoup.updater.kalman import KalmanUpdater

START = datetime.datetime(2026, 1, 1)
FOV = ((-60.0, 60.0), (-60.0, 60.0))
P_D, CLUTTER, Q, R = 0.9, 2.0, 0.05, 0.25


def scenario(seed: int, steps: int = 40):
    """(models, birth density, truth paths by time, detections per scan) of one simulation."""
    transition = CombinedLinearGaussianTransitionModel([ConstantVelocity(Q), ConstantVelocity(Q)])
    measurement = LinearGaussian(ndim_state=4, mapping=(0, 2), noise_covar=np.diag([R, R]))
    birth = GaussianState([[0.0], [0.0], [0.0], [0.0]], np.diag([100.0, 1.0, 100.0, 1.0]), timestamp=START)
    truth = MultiTargetGroundTruthSimulator(
        transition_model=transition, initial_state=birth, timestep=datetime.timedelta(seconds=1),
        number_steps=steps, birth_rate=0.1, death_probability=0.01, initial_number_targets=4, seed=seed,
    )
    detector = SimpleDetectionSimulator(
        groundtruth=truth, measurement_model=measurement, meas_range=np.array(FOV),
        detection_probability=P_D, clutter_rate=CLUTTER, seed=seed,
    )
    scans, truths = [], {}
    for t, detections in detector:
        inside = {d for d in detections if FOV[0][0] <= d.state_vector[0] <= FOV[0][1]
                  and FOV[1][0] <= d.state_vector[1] <= FOV[1][1]}
        scans.append((t, inside))
        truths[t] = [s for s in (p[t] for p in truth.groundtruth_paths if t in {x.timestamp for x in p.states})
                     if FOV[0][0] <= s.state_vector[0] <= FOV[0][1] and FOV[1][0] <= s.state_vector[2] <= FOV[1][1]]
    return transition, measurement, birth, truths, scans


def stone_soup_trackers(transition, measurement, scans):
    """Stone Soup's GNN and JPDA trackers as its tutorials set them up."""
    predictor, updater = KalmanPredictor(transition), KalmanUpdater(measurement)
    distance = DistanceHypothesiser(predictor, updater, measure=Mahalanobis(), missed_distance=3)
    gnn = GNNWith2DAssignment(distance)
    deleter = CovarianceBasedDeleter(covar_trace_thresh=4)

    def initiator():
        return MultiMeasurementInitiator(
            prior_state=GaussianState([[0], [0], [0], [0]], np.diag([0, 1, 0, 1])),
            measurement_model=measurement, deleter=deleter, data_associator=gnn, updater=updater, min_points=2,
        )

    area = (FOV[0][1] - FOV[0][0]) * (FOV[1][1] - FOV[1][0])
    pda = PDAHypothesiser(predictor=predictor, updater=updater, clutter_spatial_density=CLUTTER / area,
                          prob_detect=P_D)
    return {
        "GNN": MultiTargetTracker(initiator=initiator(), deleter=deleter, detector=scans, data_associator=gnn,
                                  updater=updater),
        "JPDA": MultiTargetMixtureTracker(initiator=initiator(), deleter=deleter, detector=scans,
                                          data_associator=JPDA(hypothesiser=pda), updater=updater),
    }


def birth_cells() -> list[GaussianState]:
    """The simulator's birth density N(0, diag(100, 1, 100, 1)) as four cells (a quadrant each), so that
    independent births can start several objects in one scan."""
    return [
        GaussianState([[x], [0.0], [y], [0.0]], np.diag([50.0, 1.0, 50.0, 1.0]))
        for x in (-7.0, 7.0) for y in (-7.0, 7.0)
    ]


def rfisst_tracker(transition, measurement, birth, scans, events="independent"):
    from stonesoup.plugins.rfisst import RFISSTTracker

    cells = birth_cells() if events == "independent" else birth
    return RFISSTTracker(
        detector=scans, transition_model=transition, measurement_model=measurement, detection_probability=P_D,
        clutter_rate=CLUTTER, field_of_view=FOV, birth_density=cells, birth_probability=0.05, birth_events=events,
        death_probability=0.01, start_time=START - datetime.timedelta(seconds=1),
    )


def inside(state) -> bool:
    x, y = float(state.state_vector[0, 0]), float(state.state_vector[2, 0])
    return FOV[0][0] <= x <= FOV[0][1] and FOV[1][0] <= y <= FOV[1][1]


def run(tracker, truths) -> tuple[float, float]:
    """(mean GOSPA over the scans, mean ms per step)."""
    metric = GOSPAMetric(c=10.0, p=1.0, measure=Euclidean(mapping=[0, 2]))
    gospa, elapsed = [], []
    iterator = iter(tracker)
    while True:
        start = time.perf_counter()
        try:
            t, tracks = next(iterator)
        except StopIteration:
            break
        elapsed.append(time.perf_counter() - start)
        # Scored in the field of view, truth and estimates alike (the tracks R-FISST keeps of objects that
        # left it are not false tracks there, nor are its truths missed).
        estimates = [track.state for track in tracks if track.state.timestamp == t and inside(track.state)]
        if estimates or truths[t]:
            gospa.append(metric.compute_gospa_metric(estimates, truths[t])[0].value["distance"])
        else:
            gospa.append(0.0)
    return float(np.mean(gospa)), 1e3 * float(np.mean(elapsed))


def compare(seed: int, first_order: bool = True) -> dict[str, tuple[float, float]]:
    """Per tracker, (mean GOSPA, ms per step) on the same detections of simulation `seed`. Stone Soup's
    simulator iterates sets, so a seed's detections differ from process to process; within one call every
    tracker sees the same ones."""
    transition, measurement, birth, truths, scans = scenario(seed)
    results = {"R-FISST": run(rfisst_tracker(transition, measurement, birth, scans), truths)}
    if first_order:
        results["R-FISST first-order"] = run(rfisst_tracker(transition, measurement, birth, scans, "first-order"), truths)
    for name, tracker in stone_soup_trackers(transition, measurement, scans).items():
        results[name] = run(tracker, truths)
    return results


if __name__ == "__main__":
    for seed in [int(s) for s in sys.argv[1:]] or [1, 2, 3, 4, 5]:
        results = compare(seed)
        print(f"seed {seed}: " + ", ".join(f"{k} GOSPA {g:.3f} ({ms:.2f} ms/step)" for k, (g, ms) in results.items()))
