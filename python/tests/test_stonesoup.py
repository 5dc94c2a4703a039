"""The Stone Soup plugin: found through the ``stonesoup.plugins`` entry point, fed by Stone Soup's own
multi-target simulator (constant velocity, clutter, births and deaths; python/bench/stonesoup_gospa.py),
yielding tracks near the truth with a GOSPA at most that of Stone Soup's GNN and JPDA; refusing the models
the core has no equivalent for."""

from __future__ import annotations

import datetime

import numpy as np
import pytest
from stonesoup.models.measurement.linear import LinearGaussian
from stonesoup.models.measurement.nonlinear import CartesianToBearingRange
from stonesoup.models.transition.linear import (
    CombinedLinearGaussianTransitionModel,
    ConstantAcceleration,
    ConstantVelocity,
    KnownTurnRate,
)

START = datetime.datetime(2026, 1, 1)
FOV = ((-60.0, 60.0), (-60.0, 60.0))


def models(q: float = 0.05):
    transition = CombinedLinearGaussianTransitionModel([ConstantVelocity(q), ConstantVelocity(q)])
    measurement = LinearGaussian(ndim_state=4, mapping=(0, 2), noise_covar=np.diag([0.25, 0.25]))
    return transition, measurement


def plugin_class():
    from stonesoup.plugins.rfisst import RFISSTTracker  # the entry point, as a Stone Soup user imports it

    return RFISSTTracker


def test_plugin_is_registered_through_the_entry_point() -> None:
    from importlib.metadata import entry_points

    import rfisst.stonesoup

    names = {e.name: e.value for e in entry_points(group="stonesoup.plugins")}
    assert names.get("rfisst") == "rfisst.stonesoup"
    assert plugin_class() is rfisst.stonesoup.RFISSTTracker


def test_tracks_a_stone_soup_simulation_near_the_truth() -> None:
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "bench"))
    import stonesoup_gospa

    errors, misses, false_tracks, judged_scans = [], 0, 0, 0
    for seed in (1, 2, 3):
        transition, measurement, birth, truths, scans = stonesoup_gospa.scenario(seed)
        tracker = stonesoup_gospa.rfisst_tracker(transition, measurement, birth, scans)
        for k, (time, tracks) in enumerate(tracker):
            estimates = [t.state for t in tracks]
            assert all(e.timestamp == time for e in estimates)
            assert all(e.state_vector.shape == (4, 1) and e.covar.shape == (4, 4) for e in estimates)
            if k < 3:
                continue  # births need a scan or two to be confirmed
            judged_scans += 1
            estimates = [e for e in estimates if stonesoup_gospa.inside(e)]
            used = set()
            for s in truths[time]:
                distances = [
                    (np.hypot(*(np.asarray(e.state_vector)[[0, 2], 0] - np.asarray(s.state_vector)[[0, 2], 0])), i)
                    for i, e in enumerate(estimates)
                    if i not in used
                ]
                d, i = min(distances, default=(np.inf, -1))
                if d < 3.0:
                    used.add(i)
                    errors.append(d)
                else:
                    misses += 1
            false_tracks += len(estimates) - len(used)
        # The tracks are Stone Soup Tracks of GaussianStates, one per label, that grow scan by scan.
        assert all(len(t) >= 1 and t.id.startswith("rfisst-") for t in tracker.tracks)
    judged = len(errors) + misses
    print(f"{judged_scans} scans, {judged} true objects in view: {misses} without a track within 3, "
          f"{false_tracks} false tracks, mean error {np.mean(errors):.3f}")
    assert judged > 300
    # Near the truth: most true objects in view have a MAP track within 3 (measurement sigma 0.5).
    assert misses <= 0.1 * judged, (misses, judged)
    assert false_tracks <= 0.1 * judged, (false_tracks, judged)
    assert np.mean(errors) < 1.0, np.mean(errors)


def refused(**overrides):
    transition, measurement = models()
    arguments = dict(detector=[], transition_model=transition, measurement_model=measurement, field_of_view=FOV)
    arguments.update(overrides)
    return plugin_class()(**arguments)


@pytest.mark.parametrize(
    "overrides, error, named",
    [
        (dict(transition_model=ConstantVelocity(0.1)), TypeError, "ConstantVelocity"),
        (
            dict(transition_model=CombinedLinearGaussianTransitionModel([ConstantAcceleration(0.1)] * 2)),
            TypeError,
            "ConstantAcceleration",
        ),
        (
            dict(transition_model=CombinedLinearGaussianTransitionModel([ConstantVelocity(0.1)] * 3)),
            TypeError,
            "ConstantVelocity",
        ),
        (dict(transition_model=KnownTurnRate([0.1, 0.1], 0.1)), TypeError, "KnownTurnRate"),
        (
            dict(transition_model=CombinedLinearGaussianTransitionModel([ConstantVelocity(0.1), ConstantVelocity(0.2)])),
            ValueError,
            "noise_diff_coeff",
        ),
        (
            dict(measurement_model=CartesianToBearingRange(ndim_state=4, mapping=(0, 2), noise_covar=np.eye(2))),
            TypeError,
            "CartesianToBearingRange",
        ),
        (
            dict(measurement_model=LinearGaussian(ndim_state=4, mapping=(2, 0), noise_covar=np.eye(2))),
            ValueError,
            "mapping",
        ),
        (dict(field_of_view=None), ValueError, "field_of_view"),
        (dict(scenario={"format": "rfisst-scenario/1"}), ValueError, "either a scenario or Stone Soup models"),
    ],
)
def test_refuses_models_without_an_equivalent(overrides, error, named) -> None:
    with pytest.raises(error, match=named):
        refused(**overrides)


def test_ssa_scenario_through_the_plugin(host_sim) -> None:
    """A 3-D radar scenario (the project's SSA models) run through the plugin gives the same MAP tracks as
    the Tracker class on the same scans."""
    import rfisst
    from conftest import load
    from stonesoup.types.detection import Detection

    path = host_sim.scenario("tiny-3d")
    scenario = load(path)
    epoch = START
    scans = [
        (epoch + datetime.timedelta(seconds=s["time"]), {Detection(np.array(z).reshape(-1, 1), metadata={"sensor": s["sensor"]}) for z in s["measurements"]})
        for s in scenario["scans"]
    ]
    tracker = plugin_class()(detector=scans, scenario=str(path), start_time=epoch)
    direct = rfisst.Tracker.from_file(path)
    for (time, tracks), scan in zip(tracker, scenario["scans"]):
        # Detections are a set: the plugin's measurement order may differ from the file's.
        direct.step(scan["time"], scan["measurements"], scan["sensor"])
        assert len(tracks) == len(direct.map_tracks()["labels"])
    final = {t.id: t.state.state_vector.ravel() for t in tracker.tracks}
    for label, mean in zip(direct.map_tracks()["labels"], direct.map_tracks()["means"]):
        assert np.allclose(final[f"rfisst-{label}"], mean, rtol=0, atol=1e-3)
    with pytest.raises(ValueError, match="start_time"):
        plugin_class()(detector=scans, scenario=str(path))


def test_gospa_at_most_stone_soups_gnn_and_jpda() -> None:
    """On Stone Soup's simulation (5 seeds, the same detections for every tracker), R-FISST's GOSPA
    (Stone Soup's GOSPAMetric, p = 1, c = 10, in the field of view) averaged over the seeds is at most that
    of Stone Soup's GNN and JPDA trackers set up as in its tutorials."""
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "bench"))
    import stonesoup_gospa

    runs = [stonesoup_gospa.compare(seed, first_order=False) for seed in range(1, 6)]
    mean = {name: float(np.mean([r[name][0] for r in runs])) for name in runs[0]}
    print("mean GOSPA over 5 seeds:", mean)
    assert mean["R-FISST"] <= mean["GNN"], mean
    assert mean["R-FISST"] <= mean["JPDA"], mean
