//! Status codes: what every function of the C interface returns, with a static message per code
//! (`rfisst_status_message`); the handle keeps the detailed text of its last failure
//! (`rfisst_tracker_last_error`), and [`Failure`] is that pair on the Rust side.

use core::fmt;
use tracker_core::{ConfigError, StepError};

/// The outcome of a call. Every value but `RFISST_OK` leaves the tracker as it was.
#[repr(u32)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RfisstStatus {
    /// Success.
    RfisstOk = 0,
    /// A pointer argument was null.
    RfisstNullPointer = 1,
    /// A size or count argument is wrong: storage smaller than `rfisst_tracker_size`, a measurement
    /// dimension that is not the tracker's, a count whose product overflows.
    RfisstBadSize = 2,
    /// The storage is not aligned to `rfisst_tracker_align`.
    RfisstMisaligned = 3,
    /// The kind is not one of `RfisstKind`.
    RfisstUnknownKind = 4,
    /// The handle was not initialised (or its initialisation failed).
    RfisstInvalidHandle = 5,
    /// A field of the C configuration or prior is out of range (an unknown code, a count above its
    /// capacity, a sensor kind the tracker does not take).
    RfisstInvalidConfig = 6,
    /// tracker-core rejected the configuration or the prior (its `ConfigError`).
    RfisstConfigRejected = 7,
    /// tracker-core rejected the scan (its `StepError`); the tracker is unchanged.
    RfisstStepRejected = 8,
    /// The scenario JSON does not parse, or does not fit the kind asked for.
    RfisstScenario = 9,
    /// Not available in this build (the JSON path needs the `std` feature).
    RfisstUnsupported = 10,
    /// An output array is smaller than what there is to write; `written` says how many are needed.
    RfisstBufferTooSmall = 11,
    /// An index (hypothesis) is past the end.
    RfisstOutOfRange = 12,
}

/// Every status, in code order.
pub const STATUSES: [RfisstStatus; 13] = [
    RfisstStatus::RfisstOk,
    RfisstStatus::RfisstNullPointer,
    RfisstStatus::RfisstBadSize,
    RfisstStatus::RfisstMisaligned,
    RfisstStatus::RfisstUnknownKind,
    RfisstStatus::RfisstInvalidHandle,
    RfisstStatus::RfisstInvalidConfig,
    RfisstStatus::RfisstConfigRejected,
    RfisstStatus::RfisstStepRejected,
    RfisstStatus::RfisstScenario,
    RfisstStatus::RfisstUnsupported,
    RfisstStatus::RfisstBufferTooSmall,
    RfisstStatus::RfisstOutOfRange,
];

impl RfisstStatus {
    /// The static message, NUL-terminated for C.
    pub const fn message(self) -> &'static str {
        match self {
            RfisstStatus::RfisstOk => "ok\0",
            RfisstStatus::RfisstNullPointer => "a pointer argument is null\0",
            RfisstStatus::RfisstBadSize => "a size or count argument is wrong\0",
            RfisstStatus::RfisstMisaligned => "the storage is not aligned to rfisst_tracker_align(kind)\0",
            RfisstStatus::RfisstUnknownKind => "unknown tracker kind\0",
            RfisstStatus::RfisstInvalidHandle => "the handle is not an initialised tracker\0",
            RfisstStatus::RfisstInvalidConfig => "a configuration or prior field is out of range\0",
            RfisstStatus::RfisstConfigRejected => "the tracker rejected its configuration or prior\0",
            RfisstStatus::RfisstStepRejected => "the tracker rejected the scan (the tracker is unchanged)\0",
            RfisstStatus::RfisstScenario => "the scenario JSON is invalid or does not fit the tracker kind\0",
            RfisstStatus::RfisstUnsupported => "not available in this build\0",
            RfisstStatus::RfisstBufferTooSmall => "an output array is too small\0",
            RfisstStatus::RfisstOutOfRange => "an index is out of range\0",
        }
    }
}

/// A failed call: its status and what to write as the handle's last error.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Failure {
    /// A status whose static message says it all, or with a static detail.
    Plain(RfisstStatus, &'static str),
    /// A detail naming an index.
    Indexed(RfisstStatus, &'static str, usize),
    /// tracker-core's configuration error.
    Config(ConfigError),
    /// tracker-core's step error (its text is the one `host-sim digest` prints).
    Step(StepError),
}

impl Failure {
    /// Its status code.
    pub fn status(&self) -> RfisstStatus {
        match self {
            Failure::Plain(status, _) | Failure::Indexed(status, _, _) => *status,
            Failure::Config(_) => RfisstStatus::RfisstConfigRejected,
            Failure::Step(_) => RfisstStatus::RfisstStepRejected,
        }
    }

    /// An invalid C configuration field.
    pub const fn invalid(what: &'static str) -> Self {
        Failure::Plain(RfisstStatus::RfisstInvalidConfig, what)
    }
}

impl fmt::Display for Failure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Failure::Plain(status, "") => f.write_str(status.message().trim_end_matches('\0')),
            Failure::Plain(_, detail) => f.write_str(detail),
            Failure::Indexed(_, detail, index) => write!(f, "{detail} {index}"),
            Failure::Config(error) => write!(f, "tracker configuration: {error}"),
            Failure::Step(error) => write!(f, "{error}"),
        }
    }
}

impl From<ConfigError> for Failure {
    fn from(error: ConfigError) -> Self {
        Failure::Config(error)
    }
}

impl From<StepError> for Failure {
    fn from(error: StepError) -> Self {
        Failure::Step(error)
    }
}
