//! Fuzz target `ilrs`: arbitrary bytes into host-sim's laser ranging readers (`host_sim::io::ilrs`: CRD
//! normal points, CPF predictions, SINEX stations), and an accepted CRD file through the reduction and the
//! TDM and configuration `track-ilrs` writes, with the committed CPF and stations of LAGEOS-2.
//!
//! Checked on every input:
//! - nothing panics;
//! - a refused file gets a one-line message naming a line of the file (or the line after the last);
//! - an accepted CPF interpolates to finite states within its span and to none outside it;
//! - accepted normal points reduce to finite ranges, and the TDM written of them parses and gives every
//!   point back.
#![no_main]

use host_sim::io::ilrs::{IlrsError, cpf, crd, import, sinex};
use libfuzzer_sys::fuzz_target;
use std::path::Path;
use std::sync::OnceLock;

/// The committed CPF and stations, read once.
fn reference() -> &'static (cpf::Cpf, Vec<sinex::Station>) {
    static DATA: OnceLock<(cpf::Cpf, Vec<sinex::Station>)> = OnceLock::new();
    DATA.get_or_init(|| {
        let cpf = cpf::parse(include_str!("../../host-sim/data/ilrs/lageos2_cpf_160213_5441.sgf")).expect("CPF");
        let stations = sinex::parse(include_str!("../../host-sim/data/ilrs/slrf2014_stations.snx")).expect("SINEX");
        (cpf, stations)
    })
}

fn check_error(text: &str, e: &IlrsError) {
    let message = e.to_string();
    assert!(!message.contains(['\n', '\r']), "multi-line error message: {message}");
    assert!(message.chars().count() < 400, "long error message: {message}");
    assert!(e.line >= 1 && e.line <= text.lines().count() + 1, "line {} of {} lines", e.line, text.lines().count());
}

fn check_cpf(cpf: &cpf::Cpf) {
    let day = cpf.records[0].0.day;
    let (first, last) = cpf.span(day);
    for k in 0..=8 {
        let t = first + (last - first) * f64::from(k) / 8.0;
        if let Some((r, v)) = cpf.state_at(t, day) {
            assert!(r.iter().chain(&v).all(|x| x.is_finite()), "state at {t}: {r:?} {v:?}");
        } else {
            panic!("no state at {t} within [{first}, {last}]");
        }
    }
    assert!(cpf.state_at(last + 1.0, day).is_none(), "a state after the span");
}

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    match cpf::parse(text) {
        Ok(cpf) => check_cpf(&cpf),
        Err(e) => check_error(text, &e),
    }
    if let Err(e) = sinex::parse(text) {
        check_error(text, &e);
    }
    let passes = match crd::parse(text) {
        Ok(passes) => passes,
        Err(e) => return check_error(text, &e),
    };
    let (cpf, stations) = reference();
    let Ok(imported) = import::import(Path::new("fuzz.npt"), &passes, cpf, stations, 0.251) else { return };
    for p in &imported.points {
        assert!(p.reduced.range_km.is_finite() && p.reduced.time.is_finite(), "{p:?}");
    }
    let tdm = imported.tdm("fuzz.npt").expect("a TDM of points within the CPF's span");
    let parsed = host_sim::io::tdm::parse(&tdm).expect("the TDM written parses");
    let records: usize = parsed.segments.iter().map(|s| s.records.len()).sum();
    assert_eq!(records, imported.points.len(), "every point is in the TDM");
});
