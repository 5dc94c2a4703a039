//! `host-sim sgp4-check`: the SGP4 verification cases of Vallado et al. (2006) ("Revisiting Spacetrack
//! Report #3", AIAA 2006-6753) through [`crate::io::catalogue`]'s parser and the `sgp4` crate in
//! AFSPC-compatibility mode, against the published TEME states (`host-sim/data/sgp4-verification/`).
//!
//! Every expected state is compared (position and velocity errors as Euclidean norms); a case whose expected
//! output ends in an SGP4 error must end in the same error at the same time.

use crate::Error;
use crate::io::catalogue::{self, PropagationError, Satellite};
use serde::Serialize;

/// The verification element sets, as bundled.
pub const VERIFICATION_TLE: &str = include_str!("../../../data/sgp4-verification/sgp4-ver.tle");
/// Their expected TEME states, as bundled.
pub const VERIFICATION_EXPECTED: &str = include_str!("../../../data/sgp4-verification/sgp4-ver-expected.txt");

/// One expected line: a state, or the error the propagation ends in.
#[derive(Debug, Clone, PartialEq)]
enum Expected {
    State { minutes: f64, position: [f64; 3], velocity: [f64; 3] },
    Error { minutes: f64, kind: String },
}

/// One case (element set) of the expected file.
#[derive(Debug, Clone, PartialEq)]
struct Case {
    norad_id: u64,
    expected: Vec<Expected>,
}

/// The outcome of one case.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CaseReport {
    /// Catalogue number.
    pub norad_id: u64,
    /// States compared.
    pub states: usize,
    /// Largest position error (km) over its states.
    pub max_position_error_km: f64,
    /// Largest velocity error (km/s) over its states.
    pub max_velocity_error_km_s: f64,
    /// The SGP4 error the case is expected to end in, if any.
    pub expected_error: Option<String>,
    /// Whether everything matched: every state computed, the expected error (if any) met at its time.
    pub matched: bool,
    /// The first mismatch, if any.
    pub mismatch: Option<String>,
}

/// `sgp4-check`'s report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Sgp4CheckReport {
    /// Verification cases (element sets).
    pub cases: usize,
    /// Largest position error (km) over every expected state of every case.
    pub max_position_error_km: f64,
    /// Largest velocity error (km/s) likewise.
    pub max_velocity_error_km_s: f64,
    /// Expected states compared.
    pub states: usize,
    /// Cases whose expected output ends in an SGP4 error.
    pub error_cases: usize,
    /// Of those, the cases that end in the same error at the same time.
    pub error_cases_matched: usize,
    /// Cases with any mismatch (0 when the check passes).
    pub mismatched_cases: usize,
    /// Geopotential and mode.
    pub mode: &'static str,
    /// Per case.
    pub per_case: Vec<CaseReport>,
}

fn parse_expected(file: &str, text: &str) -> Result<Vec<Case>, Error> {
    let mut cases: Vec<Case> = vec![];
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let bad = |what: &str| Error::input(format!("{file}:{}: {what}", i + 1));
        let words: Vec<&str> = line.split_whitespace().collect();
        if words[0] == "case" {
            let id = words.get(1).and_then(|w| catalogue::parse_catalogue_number(&format!("{w:>5}")));
            let id = id.filter(|_| words.len() == 2).ok_or_else(|| bad("case: expected \"case NORAD\""))?;
            cases.push(Case { norad_id: id, expected: vec![] });
            continue;
        }
        let case = cases.last_mut().ok_or_else(|| bad("a state before the first \"case\" line"))?;
        let number = |w: &str| w.parse::<f64>().ok().filter(|v| v.is_finite());
        let minutes = number(words[0]).ok_or_else(|| bad("time: expected a number"))?;
        if words.len() == 3 && words[1] == "error" {
            case.expected.push(Expected::Error { minutes, kind: words[2].to_string() });
        } else if words.len() == 7 {
            let v: Option<Vec<f64>> = words[1..].iter().map(|w| number(w)).collect();
            let v = v.ok_or_else(|| bad("state: expected 6 numbers"))?;
            case.expected.push(Expected::State { minutes, position: [v[0], v[1], v[2]], velocity: [v[3], v[4], v[5]] });
        } else {
            return Err(bad("expected \"t x y z vx vy vz\" or \"t error KIND\""));
        }
    }
    Ok(cases)
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// Checks one case; `satellite` is the case's SGP4 initialisation.
fn check_case(satellite: Result<Satellite, PropagationError>, case: &Case) -> CaseReport {
    let mut report = CaseReport {
        norad_id: case.norad_id,
        states: 0,
        max_position_error_km: 0.0,
        max_velocity_error_km_s: 0.0,
        expected_error: None,
        matched: true,
        mismatch: None,
    };
    let fail = |report: &mut CaseReport, why: String| {
        if report.mismatch.is_none() {
            report.mismatch = Some(why);
        }
        report.matched = false;
    };
    for (k, expected) in case.expected.iter().enumerate() {
        let minutes = match expected {
            Expected::State { minutes, .. } | Expected::Error { minutes, .. } => *minutes,
        };
        let got = satellite.as_ref().map_err(Clone::clone).and_then(|s| s.teme(minutes));
        match (expected, got) {
            (Expected::State { position, velocity, .. }, Ok((r, v))) => {
                report.states += 1;
                report.max_position_error_km = report.max_position_error_km.max(distance(r, *position));
                report.max_velocity_error_km_s = report.max_velocity_error_km_s.max(distance(v, *velocity));
            }
            (Expected::State { .. }, Err(e)) => fail(&mut report, format!("t = {minutes} min: {e}")),
            (Expected::Error { kind, .. }, got) => {
                report.expected_error = Some(kind.clone());
                if k + 1 != case.expected.len() {
                    fail(&mut report, format!("t = {minutes} min: the expected error is not the last line"));
                }
                match got {
                    Err(e) if e.kind() == kind => {}
                    Err(e) => fail(&mut report, format!("t = {minutes} min: {} instead of {kind}", e.kind())),
                    Ok(_) => fail(&mut report, format!("t = {minutes} min: a state instead of {kind}")),
                }
            }
        }
    }
    report
}

/// Runs the verification on `tle` (element sets) and `expected` (states), named `files` in errors.
pub fn run_on(files: (&str, &str), tle: &str, expected: &str) -> Result<Sgp4CheckReport, Error> {
    let entries = catalogue::parse(files.0, tle)?;
    let cases = parse_expected(files.1, expected)?;
    if entries.len() != cases.len() {
        return Err(Error::input(format!(
            "{}: {} element sets, but {} has {} cases",
            files.0,
            entries.len(),
            files.1,
            cases.len()
        )));
    }
    let mut per_case = vec![];
    for (entry, case) in entries.into_iter().zip(&cases) {
        if entry.norad_id != case.norad_id {
            return Err(Error::input(format!(
                "{}:{}: catalogue number {} where {} expects {}",
                files.0, entry.line, entry.norad_id, files.1, case.norad_id
            )));
        }
        per_case.push(check_case(Satellite::new(entry), case));
    }
    let max = |f: fn(&CaseReport) -> f64| per_case.iter().map(f).fold(0.0, f64::max);
    let errors = per_case.iter().filter(|c| c.expected_error.is_some());
    Ok(Sgp4CheckReport {
        cases: per_case.len(),
        max_position_error_km: max(|c| c.max_position_error_km),
        max_velocity_error_km_s: max(|c| c.max_velocity_error_km_s),
        states: per_case.iter().map(|c| c.states).sum(),
        error_cases: errors.clone().count(),
        error_cases_matched: errors.filter(|c| c.matched).count(),
        mismatched_cases: per_case.iter().filter(|c| !c.matched).count(),
        mode: "WGS-72, AFSPC compatibility",
        per_case,
    })
}

/// Runs the verification on the bundled data.
pub fn run() -> Result<Sgp4CheckReport, Error> {
    run_on(("sgp4-ver.tle", "sgp4-ver-expected.txt"), VERIFICATION_TLE, VERIFICATION_EXPECTED)
}
