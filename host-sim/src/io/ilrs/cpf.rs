//! A reader of ILRS predictions in the Consolidated Prediction Format (CPF v1 and v2, ILRS "Consolidated
//! Laser Ranging Prediction Format Version 2.00", 2018), and their interpolation.
//!
//! Read: H1 (format `CPF`, version 1 or 2, target name), H2 (the reference frame must be 0, geocentric
//! true body-fixed: the ITRF; predictions of the centre of mass, not the retroreflector array), H5 (the
//! centre-of-mass offset, m, optional), H9, and the position records 10 (direction flag 0, common epoch;
//! MJD and seconds of day in UTC; x, y, z in m) increasing in time (1 ms apart at least), at least [`LAGRANGE_POINTS`];
//! 99 ends the file. Checked for their place and ignored: H3, H4, 00 (comments) and the records 20–70.
//!
//! Interpolation: Lagrange polynomials of degree 9 on the [`LAGRANGE_POINTS`] records nearest the time (the
//! CPF documentation's recommendation for its 10-point tables), and their derivative for the velocity; no
//! extrapolation beyond the first and last records.

use super::{DayTime, Fields, IlrsError, fail};

/// Records per interpolation.
pub const LAGRANGE_POINTS: usize = 10;

/// A parsed CPF file.
#[derive(Debug, Clone, PartialEq)]
pub struct Cpf {
    /// The target's name (H1).
    pub target: String,
    /// The centre-of-mass offset (m, H5), when given.
    pub centre_of_mass_m: Option<f64>,
    /// The position records: times and ITRF positions (m).
    pub records: Vec<(DayTime, [f64; 3])>,
}

/// Record types checked for their place and not used.
const IGNORED: &[&str] = &["h3", "h4", "20", "30", "40", "50", "60", "70"];

/// Parses a CPF file.
///
/// # Errors
/// The first problem: a malformed or misplaced record, an unknown record type, a frame other than the
/// ITRF, predictions of the retroreflector array, a direction flag other than 0, times not increasing,
/// fewer than [`LAGRANGE_POINTS`] records, a file without 99.
pub fn parse(text: &str) -> Result<Cpf, IlrsError> {
    let mut target = None;
    let mut frame_checked = false;
    let mut header_done = false;
    let mut cpf = Cpf { target: String::new(), centre_of_mass_m: None, records: vec![] };
    let mut last = 0;
    for (index, raw) in text.lines().enumerate() {
        let line = index + 1;
        last = line;
        let f = Fields::of(line, raw);
        let record = f.record().to_string();
        if record.is_empty() || record == "00" {
            continue;
        }
        let header = record.starts_with('h');
        if header == header_done && record != "99" {
            let place = if header { "a header record after H9" } else { "a data record before H9" };
            return f.fail("record", place);
        }
        match record.as_str() {
            "h1" => target = Some(header_h1(&f)?),
            "h2" => {
                header_h2(&f)?;
                frame_checked = true;
            }
            "h5" => cpf.centre_of_mass_m = Some(centre_of_mass(&f)?),
            "h9" => {
                let Some(name) = target.take() else { return f.fail("record", "H9 before H1") };
                if !frame_checked {
                    return f.fail("record", "H9 before H2");
                }
                cpf.target = name;
                header_done = true;
            }
            "10" => position(&f, &mut cpf.records)?,
            "99" if !header_done => return f.fail("record", "end of file before H9"),
            "99" if cpf.records.len() < LAGRANGE_POINTS => {
                return f
                    .fail("record", format!("{} position records, fewer than {LAGRANGE_POINTS}", cpf.records.len()));
            }
            "99" => return Ok(cpf),
            _ if IGNORED.contains(&record.as_str()) => {}
            _ => return f.fail("record", "unknown record type"),
        }
    }
    fail(last + 1, "99", "the file ends without its end-of-file record 99")
}

/// H1: the format, version and target.
fn header_h1(f: &Fields) -> Result<String, IlrsError> {
    if !f.text(1, "format")?.eq_ignore_ascii_case("CPF") {
        return f.fail("format", "not a CPF file (H1 must say CPF)");
    }
    let version = f.integer(2, "version", 1..=2)?;
    // v2 adds the sub-daily sequence number before the target's name.
    Ok(f.text(if version == 1 { 9 } else { 10 }, "target name")?.to_string())
}

/// H2: the frame must be the ITRF and the positions those of the centre of mass.
fn header_h2(f: &Fields) -> Result<(), IlrsError> {
    if f.integer(19, "reference frame", 0..=2)? != 0 {
        return f.fail("reference frame", "not geocentric true body-fixed (0, the ITRF)");
    }
    if f.integer(21, "centre of mass correction", 0..=1)? != 0 {
        return f.fail("centre of mass correction", "predictions of the retroreflector array, not the centre of mass");
    }
    Ok(())
}

/// H5: the centre-of-mass offset (m).
fn centre_of_mass(f: &Fields) -> Result<f64, IlrsError> {
    let offset = f.number(1, "centre of mass offset")?;
    if !(0.0..=10.0).contains(&offset) {
        return f.fail("centre of mass offset", format!("{offset} m is not in [0, 10]"));
    }
    Ok(offset)
}

/// Record 10, appended after checking its time follows the previous record's.
fn position(f: &Fields, records: &mut Vec<(DayTime, [f64; 3])>) -> Result<(), IlrsError> {
    if f.integer(1, "direction flag", 0..=2)? != 0 {
        return f.fail("direction flag", "not a common epoch (0): transmit and receive tables are not supported");
    }
    let mjd = f.integer(2, "modified julian date", 33_282..=88_068)?;
    let seconds = f.number(3, "seconds of day")?;
    if !(0.0..86_400.0).contains(&seconds) {
        return f.fail("seconds of day", format!("{seconds} is not in [0, 86400)"));
    }
    let time = DayTime { day: mjd - 40_587, seconds };
    let mut r = [0.0; 3];
    for (k, name) in ["x", "y", "z"].iter().enumerate() {
        r[k] = f.number(5 + k, name)?;
        if r[k].abs() > 1e9 {
            return f.fail(name, format!("{} m is beyond 1e9 m", r[k]));
        }
    }
    // 1 ms apart at least: the interpolation's weights stay finite (CPF steps are seconds to minutes).
    if let Some((previous, _)) = records.last()
        && time.since(previous.day) - previous.seconds < 1e-3
    {
        return f.fail("seconds of day", "not at least 1 ms after the previous record's time");
    }
    records.push((time, r));
    Ok(())
}

impl Cpf {
    /// The first and last record times, in seconds since `epoch_day`.
    pub fn span(&self, epoch_day: i64) -> (f64, f64) {
        let first = self.records.first().map_or(f64::NAN, |(t, _)| t.since(epoch_day));
        let last = self.records.last().map_or(f64::NAN, |(t, _)| t.since(epoch_day));
        (first, last)
    }

    /// Position (m) and velocity (m/s) in the ITRF at `t` seconds since `epoch_day`; `None` outside the
    /// records' span.
    pub fn state_at(&self, t: f64, epoch_day: i64) -> Option<([f64; 3], [f64; 3])> {
        let (first, last) = self.span(epoch_day);
        if !(t >= first && t <= last) || self.records.len() < LAGRANGE_POINTS {
            return None;
        }
        let times: Vec<f64> = self.records.iter().map(|(time, _)| time.since(epoch_day)).collect();
        let after = times.partition_point(|&x| x <= t);
        let start = after.saturating_sub(LAGRANGE_POINTS / 2).min(times.len() - LAGRANGE_POINTS);
        let nodes = &times[start..start + LAGRANGE_POINTS];
        let (weights, slopes) = lagrange(nodes, t);
        let mut r = [0.0; 3];
        let mut v = [0.0; 3];
        for (j, (_, p)) in self.records[start..start + LAGRANGE_POINTS].iter().enumerate() {
            for k in 0..3 {
                r[k] += weights[j] * p[k];
                v[k] += slopes[j] * p[k];
            }
        }
        Some((r, v))
    }
}

/// The Lagrange basis polynomials of `nodes` at `t` and their derivatives.
fn lagrange(nodes: &[f64], t: f64) -> (Vec<f64>, Vec<f64>) {
    let n = nodes.len();
    let mut weights = vec![0.0; n];
    let mut slopes = vec![0.0; n];
    for j in 0..n {
        let mut w = 1.0;
        for m in (0..n).filter(|&m| m != j) {
            w *= (t - nodes[m]) / (nodes[j] - nodes[m]);
        }
        weights[j] = w;
        // d/dt Π_{m≠j} (t − t_m)/(t_j − t_m) = Σ_{i≠j} 1/(t_j − t_i) Π_{m≠i,j} (t − t_m)/(t_j − t_m).
        let mut slope = 0.0;
        for i in (0..n).filter(|&i| i != j) {
            let mut term = 1.0 / (nodes[j] - nodes[i]);
            for m in (0..n).filter(|&m| m != j && m != i) {
                term *= (t - nodes[m]) / (nodes[j] - nodes[m]);
            }
            slope += term;
        }
        slopes[j] = slope;
    }
    (weights, slopes)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A CPF v1 of a point moving on a circle of radius 7000 km with period 13 500 s (LAGEOS), records every 300 s.
    fn circle() -> String {
        let mut text = String::from(
            "H1 CPF  1  SGF 2016  2 13  2  5441 circle\n\
             H2  9207002 5986    22195 2016  2 13  0  0  0 2016  2 13 23 54  0   300 1 1  0 0 0\n\
             H9\n",
        );
        for k in 0..20 {
            let s = 300.0 * f64::from(k);
            let a = std::f64::consts::TAU * s / 13_500.0;
            text.push_str(&format!("10 0 57431 {s:.5} 0 {:.3} {:.3} 0.0\n", 7e6 * a.cos(), 7e6 * a.sin()));
        }
        text.push_str("99\n");
        text
    }

    #[test]
    fn interpolation_recovers_a_circle_and_its_velocity() {
        let cpf = parse(&circle()).expect("valid");
        let day = 57_431 - 40_587;
        assert_eq!(cpf.target, "circle");
        for t in [0.0, 150.0, 1234.5, 2850.0, 5700.0] {
            let (r, v) = cpf.state_at(t, day).expect("inside");
            let a = std::f64::consts::TAU * t / 13_500.0;
            let w = std::f64::consts::TAU / 13_500.0;
            assert!((r[0] - 7e6 * a.cos()).abs() < 0.01 && (r[1] - 7e6 * a.sin()).abs() < 0.01, "{t}: {r:?}");
            assert!((v[0] + 7e6 * w * a.sin()).abs() < 0.05 && (v[1] - 7e6 * w * a.cos()).abs() < 0.05, "{t}: {v:?}");
        }
        assert!(cpf.state_at(-1.0, day).is_none());
        assert!(cpf.state_at(5700.5, day).is_none());
    }

    #[test]
    fn malformed_records_name_their_line_and_field() {
        let sample = circle();
        let cases = [
            ("H1 CPF  1", "H1 CRD  1", 1, "h1 format", "not a CPF file"),
            ("0   300 1 1  0 0 0", "0   300 1 1  1 0 0", 2, "h2 reference frame", "ITRF"),
            ("0   300 1 1  0 0 0", "0   300 1 1  0 0 1", 2, "h2 centre of mass correction", "retroreflector"),
            ("10 0 57431 300.00000", "10 1 57431 300.00000", 5, "10 direction flag", "common epoch"),
            ("10 0 57431 300.00000", "10 0 57431 0.00000", 5, "10 seconds of day", "not at least 1 ms after"),
            ("10 0 57431 600.00000 0 ", "10 0 57431 600.00000 0 x", 6, "10 x", "not a finite number"),
            ("H9\n", "H9\nH5 0.25\n", 4, "h5 record", "after H9"),
            ("99\n", "77 x\n99\n", 24, "77 record", "unknown record type"),
        ];
        for (from, to, line, field, message) in cases {
            let text = sample.replacen(from, to, 1);
            assert_ne!(text, sample, "{from}");
            let e = parse(&text).expect_err(to);
            assert_eq!((e.line, e.field.as_str()), (line, field), "{to}: {e}");
            assert!(e.message.contains(message), "{to}: {}", e.message);
        }
        let cut = parse(&sample.replace("99\n", "")).unwrap_err();
        assert!(cut.message.contains("without its end-of-file record"), "{cut}");
        let few: String = sample.lines().take(8).chain(["99"]).map(|l| format!("{l}\n")).collect();
        assert!(parse(&few).unwrap_err().message.contains("fewer than 10"));
        let com = parse(&sample.replace("H9\n", "H5 0.2510\nH9\n")).expect("valid");
        assert_eq!(com.centre_of_mass_m, Some(0.251));
    }
}
