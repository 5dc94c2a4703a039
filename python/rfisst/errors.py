"""The exceptions of the R-FISST tracker.

Every error is a :class:`TrackerError` with ``kind`` (a short name: the core's error variant such as
``NonFiniteMeasurement`` or ``NoViableChild``, or one of the package's own checks such as ``WrongShape``
or ``UnknownSensor``) and ``message`` (one line). After an :class:`InputError` or a :class:`StepError`
the tracker is unchanged.
"""

from __future__ import annotations


class TrackerError(Exception):
    """Base class of every error the tracker raises."""

    kind: str
    message: str

    def __init__(self, message: str, kind: str = "TrackerError") -> None:
        super().__init__(message)
        self.message = message
        self.kind = kind

    def __str__(self) -> str:
        return f"{self.kind}: {self.message}"


class ScenarioError(TrackerError, ValueError):
    """The scenario (file, JSON text or dict) does not parse or check, or the core refuses its
    configuration (for example more birth cells than the capacity profile holds)."""


class InputError(TrackerError, ValueError):
    """The scan is bad input: wrong measurement shape, non-numeric or non-finite values, unknown sensor,
    a time not after the last scan, a measurement outside the field of view, more measurements than the
    capacity. The tracker is unchanged."""


class StepError(TrackerError):
    """The core could not process a well-formed scan (no viable child, a numerical failure, a full
    track store). The tracker is unchanged."""


__all__ = ["TrackerError", "ScenarioError", "InputError", "StepError"]
