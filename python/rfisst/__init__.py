"""R-FISST: a bounded, deterministic multi-object tracker for Space Situational Awareness (Rust core).

Build a :class:`Tracker` from a scenario file, JSON text or dict (the format ``host-sim`` reads, version 1
planar or version 2 3-D), step it with ``(time, measurements, sensor)`` and read the MAP tracks,
hypotheses and expected cardinality as numpy arrays. Errors are :class:`TrackerError` subclasses.
The Stone Soup plugin is :mod:`rfisst.stonesoup` (``stonesoup.plugins.rfisst``).
"""

from ._rfisst import Tracker, __version__
from .errors import InputError, ScenarioError, StepError, TrackerError

__all__ = ["Tracker", "TrackerError", "ScenarioError", "InputError", "StepError", "__version__"]
