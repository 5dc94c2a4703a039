//! The Python exceptions raised for the core's errors: the classes live in `rfisst.errors` (a base
//! `TrackerError` carrying `kind` and `message`, and `ScenarioError`, `InputError`, `StepError`); this
//! module makes one from a message and a kind.

use host_sim::scenario::cut_quotes;
use pyo3::prelude::*;
use tracker_core::StepError;

/// Which exception class of `rfisst.errors`.
#[derive(Clone, Copy)]
pub enum Class {
    /// The scenario (file, dict or JSON) does not parse, or the core refuses its configuration.
    Scenario,
    /// The scan is bad input (shape, non-finite values, unknown sensor, time, field of view, capacity); the
    /// tracker is unchanged.
    Input,
    /// The core could not process an otherwise valid scan (no viable child, a numerical failure, a full
    /// store); the tracker is unchanged.
    Step,
}

impl Class {
    fn name(self) -> &'static str {
        match self {
            Class::Scenario => "ScenarioError",
            Class::Input => "InputError",
            Class::Step => "StepError",
        }
    }
}

/// The exception `class(message, kind)`. The message is made one short line: line breaks become spaces
/// and long quoted input (a 100,000-character sensor name, numpy's repr of a huge array) is cut to an
/// excerpt, as the CLI's messages are (`host_sim::scenario::cut_quotes`).
pub fn error(py: Python<'_>, class: Class, kind: &str, message: impl Into<String>) -> PyErr {
    let message = cut_quotes(&message.into().replace(['\n', '\r'], " "));
    let made = py.import("rfisst.errors").and_then(|m| m.getattr(class.name())).and_then(|c| c.call1((message, kind)));
    match made {
        Ok(value) => PyErr::from_value(value),
        Err(e) => e,
    }
}

/// The name of a core error's variant (`NonFiniteMeasurement`, `NoViableChild`, ...).
pub fn variant_name(error: &StepError) -> String {
    format!("{error:?}").chars().take_while(char::is_ascii_alphanumeric).collect()
}

/// The exception of a core step error: [`Class::Input`] when the scan itself was refused, else
/// [`Class::Step`]; `kind` is the core's variant name.
pub fn step_error(py: Python<'_>, e: &StepError) -> PyErr {
    let class = match e {
        StepError::TooManyMeasurements { .. }
        | StepError::NonFiniteMeasurement { .. }
        | StepError::MeasurementOutsideFieldOfView { .. }
        | StepError::MeasurementOfWrongKind { .. }
        | StepError::NonFiniteTime
        | StepError::TimeNotAfterLastScan
        | StepError::TimeStepTooLong { .. }
        | StepError::Placement(_) => Class::Input,
        _ => Class::Step,
    };
    error(py, class, &variant_name(e), e.to_string())
}
