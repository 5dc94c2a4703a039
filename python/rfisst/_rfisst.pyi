"""Type stubs of the extension module ``rfisst._rfisst``."""

from os import PathLike
from typing import Any, Literal, Mapping, TypedDict

import numpy as np
import numpy.typing as npt

__version__: str

class Tracks(TypedDict):
    labels: npt.NDArray[np.uint32]  # (n,)
    means: npt.NDArray[np.float64]  # (n, state_dim)
    covariances: npt.NDArray[np.float64]  # (n, state_dim, state_dim)
    existence: npt.NDArray[np.float64]  # (n,)

class Hypotheses(TypedDict):
    weights: npt.NDArray[np.float64]  # (h,), best first
    log_weights: npt.NDArray[np.float64]  # (h,)
    labels: list[npt.NDArray[np.uint32]]  # per hypothesis, its labels
    track_indices: list[npt.NDArray[np.uint64]]  # per hypothesis, indices into tracks()

class BirthPool(TypedDict):
    added: int
    evicted: int
    expired: int
    without_density: int
    tracklets: int
    linked: int
    waiting: int

class StepReport(TypedDict):
    scan: int
    measurements: int
    hypotheses: int
    tracks: int
    children: int
    captured_mass: float
    merged_children: int
    children_dropped_for_store: int
    births_beyond_object_capacity: int
    sampler_steps: int
    numerical_drops: int
    numerical_drop_first: str | None
    lost_tracks: int
    expected_cardinality: float
    birth_pool: BirthPool

TrackerKind = Literal["rfisst", "homht"]
ProfileName = Literal["embedded", "host"]

class Tracker:
    """An R-FISST tracker (tracker-core) built from a scenario in the format host-sim reads."""

    @staticmethod
    def from_file(
        path: str | PathLike[str], tracker: TrackerKind = "rfisst", profile: ProfileName | None = None
    ) -> Tracker: ...
    @staticmethod
    def from_json(text: str, tracker: TrackerKind = "rfisst", profile: ProfileName | None = None) -> Tracker: ...
    @staticmethod
    def from_dict(
        scenario: Mapping[str, Any], tracker: TrackerKind = "rfisst", profile: ProfileName | None = None
    ) -> Tracker: ...
    def step(self, time: float, measurements: npt.ArrayLike, sensor: int | str | None = None) -> StepReport: ...
    def map_tracks(self) -> Tracks: ...
    def tracks(self) -> Tracks: ...
    def hypotheses(self) -> Hypotheses: ...
    def expected_cardinality(self) -> float: ...
    @property
    def version(self) -> Literal[1, 2]: ...
    @property
    def name(self) -> str: ...
    @property
    def tracker(self) -> TrackerKind: ...
    @property
    def profile(self) -> ProfileName: ...
    @property
    def state_dim(self) -> int: ...
    @property
    def measurement_dim(self) -> int: ...
    @property
    def measurement_kind(self) -> str: ...
    @property
    def sensors(self) -> list[str]: ...
    @property
    def time(self) -> float: ...
