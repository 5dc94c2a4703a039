//! The OEM reader and the prior made from it: what `tracks.oem` writes reads back bit for bit, and every
//! bad OEM is one [`OemError`] naming its line and keyword.

use super::*;
use crate::io::oem::OemTracks;
use crate::pipeline::orbital::prior_oem::prior_from_oem;
use crate::pipeline::snapshot::Track6;

fn tiny() -> crate::scenario::v2::Scenario3d {
    let simulation = crate::sim::presets::tiny_3d(1).expect("tiny-3d");
    crate::scenario::from_simulation::to_scenario(&simulation).expect("scenario").0
}

fn track(label: u32, t: f64) -> Track6 {
    let mut covariance = [[0.0; 6]; 6];
    for (i, row) in covariance.iter_mut().enumerate() {
        row[i] = if i < 3 { 0.25 + t * 1e-3 } else { 1e-6 };
    }
    covariance[0][3] = 1e-5;
    covariance[3][0] = 1e-5;
    Track6 { label, mean: [7000.0 + t, -12.5, 0.1 / 3.0, 0.001, 7.5 + t * 1e-4, -0.2], existence: 1.0, covariance }
}

/// A `tracks.oem` of two confirmed tracks over three scans with noisy times (2169.6898 s and others).
fn written() -> (String, crate::scenario::v2::Scenario3d) {
    let scenario = tiny();
    let mut tracks = OemTracks::new(&scenario);
    for t in [10.1, 2169.6898, 2229.6898 + 1e-4] {
        tracks.record(t, &[track(3, t), track(7, t)]);
    }
    (tracks.text(), scenario)
}

#[test]
fn a_written_oem_reads_back_bit_for_bit_with_exact_epochs() {
    let (text, scenario) = written();
    assert!(text.contains("T00:36:09.6898 ") || text.contains(":09.6898 "), "{text}");
    assert!(!text.contains("999999") && !text.contains("000000000"), "no float noise in the epochs:\n{text}");
    let oem = parse(&text).expect("parses");
    assert_eq!(oem.segments.len(), 2);
    let epoch = Instant::epoch_of(&scenario);
    for (segment, label) in oem.segments.iter().zip([3, 7]) {
        assert_eq!(segment.object_id.0, label.to_string());
        let t: f64 = 2229.6898 + 1e-4;
        assert_eq!(segment.last.epoch.since(&epoch).map(f64::to_bits), Some(t.to_bits()));
        assert_eq!(segment.last.epoch, epoch.after(t).expect("after"));
        let expected = track(label, t);
        assert_eq!(segment.last.state.map(f64::to_bits), expected.mean.map(f64::to_bits));
        let covariance = segment.covariance.as_ref().expect("covariance at the last epoch");
        assert_eq!(covariance.matrix.map(|r| r.map(f64::to_bits)), expected.covariance.map(|r| r.map(f64::to_bits)));
    }
    let prior = prior_from_oem(&oem, &epoch, 64, "embedded").expect("prior");
    assert_eq!(prior.prior.time.to_bits(), (2229.6898 + 1e-4_f64).to_bits());
    let labels: Vec<u32> = prior.prior.hypotheses[0].objects.iter().map(|o| o.label).collect();
    assert_eq!((labels, prior.renumbered), (vec![3, 7], false));
}

/// `edit` applied to the written OEM gives an error at the line of the first line containing `at` (the
/// one after the last for `None`) with `keyword`, whose message contains `message`.
fn assert_refused(edit: impl Fn(&str) -> String, at: Option<&str>, keyword: &str, message: &str) {
    let (text, scenario) = written();
    let text = edit(&text);
    let line = at.map_or(text.lines().count() + 1, |at| text.lines().position(|l| l.contains(at)).expect(at) + 1);
    let error = match parse(&text) {
        Err(e) => e,
        Ok(oem) => prior_from_oem(&oem, &Instant::epoch_of(&scenario), 1, "test").expect_err("refused"),
    };
    assert_eq!((error.line, error.keyword.as_str()), (line, keyword), "{error}");
    assert!(error.message.contains(message), "{error}");
    assert!(error.to_string().len() < 200 && !error.to_string().contains('\n'), "{error}");
}

/// Only the first segment (the prior tests use a capacity of 1).
fn first_segment(text: &str) -> String {
    let second = text.match_indices("META_START").nth(1).map_or(text.len(), |(i, _)| i);
    text[..second].to_string()
}

#[test]
fn bad_frames_time_systems_and_centres_are_refused() {
    let frame = |t: &str| t.replacen("REF_FRAME = TEME", "REF_FRAME = MOD", 1);
    assert_refused(frame, Some("REF_FRAME = MOD"), "REF_FRAME", "\"MOD\" is not supported (TEME, EME2000");
    let time = |t: &str| t.replacen("TIME_SYSTEM = UTC", "TIME_SYSTEM = UT1", 1);
    assert_refused(time, Some("TIME_SYSTEM = UT1"), "TIME_SYSTEM", "\"UT1\" is not supported (UTC, TAI, GPS or TT)");
    let centre = |t: &str| t.replacen("CENTER_NAME = EARTH", "CENTER_NAME = MOON", 1);
    assert_refused(centre, Some("CENTER_NAME = MOON"), "CENTER_NAME", "MOON");
    let cov_frame = |t: &str| t.replacen("COV_REF_FRAME = TEME", "COV_REF_FRAME = ITRF", 1);
    assert_refused(cov_frame, Some("COV_REF_FRAME = ITRF"), "COV_REF_FRAME", "not the segment's REF_FRAME TEME");
    let missing = |t: &str| t.replacen("REF_FRAME = TEME\n", "", 1);
    assert_refused(missing, Some("META_STOP"), "REF_FRAME", "required in the metadata, missing");
    let long = |t: &str| t.replacen("REF_FRAME = TEME", &format!("REF_FRAME = {}", "X".repeat(5000)), 1);
    assert_refused(long, Some("REF_FRAME = XXX"), "REF_FRAME", "…\" is not supported");
}

#[test]
fn non_finite_and_malformed_numbers_are_refused() {
    let (text, _) = written();
    let data = text.lines().find(|l| l.starts_with(|c: char| c.is_ascii_digit())).expect("ephemeris").to_string();
    let x = data.split_whitespace().nth(1).expect("x").to_string();
    for bad in ["NaN", "inf", "-infinity", "1e999", "7000,5"] {
        let edit = |t: &str| t.replacen(&data, &data.replacen(&x, bad, 1), 1);
        assert_refused(edit, Some(bad), "EPHEMERIS", "is not a finite number");
    }
    let short = |t: &str| t.replacen(&data, &data[..data.rfind(' ').expect("space")], 1);
    assert_refused(short, Some(&data[..data.rfind(' ').expect("space")]), "EPHEMERIS", "6 or 9 numbers");
    let row = text.lines().skip_while(|l| !l.starts_with("COV_REF_FRAME")).nth(1).expect("row").to_string();
    let nan = |t: &str| t.replacen(&format!("\n{row}\n"), "\nNaN\n", 1);
    assert_refused(nan, Some("NaN"), "COVARIANCE", "is not a finite number");
    let two = |t: &str| t.replacen(&format!("\n{row}\n"), &format!("\n{row} 0\n"), 1);
    assert_refused(two, Some(&format!("{row} 0")), "COVARIANCE", "row 1 of the lower triangle needs 1 numbers");
}

#[test]
fn malformed_structure_is_refused() {
    assert_refused(|_| String::new(), None, "CCSDS_OEM_VERS", "empty file");
    assert_refused(|t| t.replacen("2.0", "9.0", 1), Some("CCSDS_OEM_VERS"), "CCSDS_OEM_VERS", "9.0");
    let no_meta = |t: &str| t[..t.find("\nMETA_START").expect("meta")].to_string();
    assert_refused(no_meta, None, "META_START", "no META block");
    let unknown = |t: &str| t.replacen("CENTER_NAME", "CENTRE_NAME", 1);
    assert_refused(unknown, Some("CENTRE_NAME"), "CENTRE_NAME", "unknown keyword in the metadata");
    let (text, _) = written();
    let lines: Vec<&str> = text.lines().filter(|l| l.starts_with(|c: char| c.is_ascii_digit())).collect();
    let swapped = |t: &str| t.replacen(lines[0], "@", 1).replacen(lines[1], lines[0], 1).replacen('@', lines[1], 1);
    assert_refused(swapped, Some(lines[0]), "EPHEMERIS", "is not after the previous epoch");
    let truncated = |t: &str| t[..t.find("COVARIANCE_STOP").expect("stop")].to_string();
    assert_refused(truncated, None, "COVARIANCE_STOP", "the file ends inside the covariance section");
    let cut = |t: &str| {
        let stop = t.find("COVARIANCE_STOP").expect("stop");
        let row = t[..stop - 1].rfind('\n').expect("row");
        format!("{}\n{}", &t[..row], &t[stop..])
    };
    assert_refused(cut, Some("COVARIANCE_STOP"), "COVARIANCE_STOP", "has 5 of its 6 rows");
}

#[test]
fn priors_the_tracker_cannot_take_are_refused() {
    // Two segments, a capacity of one.
    let (text, _) = written();
    let second = text.match_indices("META_START").nth(1).expect("second").0;
    let line = text[..second].lines().count() + 1;
    let error = prior_from_oem(&parse(&text).expect("parses"), &Instant::epoch_of(&tiny()), 1, "test").expect_err("N");
    assert_eq!((error.line, error.keyword.as_str()), (line, "META_START"), "{error}");
    assert!(error.message.contains("2 objects, more than the 1 a hypothesis of the test profile holds"), "{error}");
    // No covariance.
    let none = |t: &str| {
        let t = first_segment(t);
        t[..t.find("COVARIANCE_START").expect("cov")].to_string()
    };
    let (text, _) = written();
    let last_line = first_segment(&text)[..first_segment(&text).find("\nCOVARIANCE_START").expect("cov")]
        .trim_end()
        .lines()
        .last()
        .expect("last state")
        .to_string();
    assert_refused(none, Some(&last_line), "COVARIANCE", "no covariance at the segment's last epoch");
    // Not positive definite: a variance of −1.
    let (text, _) = written();
    let last_epoch_line = text.lines().filter(|l| l.starts_with("EPOCH = ")).nth(2).expect("third epoch").to_string();
    let negative = |t: &str| {
        let t = first_segment(t);
        let at = t.find(&last_epoch_line).expect("epoch");
        let row = at + t[at..].find("COV_REF_FRAME = TEME\n").expect("frame") + "COV_REF_FRAME = TEME\n".len();
        let end = row + t[row..].find('\n').expect("row end");
        format!("{}-1{}", &t[..row], &t[end..])
    };
    assert_refused(negative, Some(&last_epoch_line), "COVARIANCE", "is not positive definite");
}

#[test]
fn another_tools_form_is_read_and_labelled_in_file_order() {
    let text = include_str!("../../../../../fuzz/seeds/oem/external-9-values.oem");
    let oem = parse(text).expect("parses");
    assert_eq!(oem.segments.len(), 1);
    let segment = &oem.segments[0];
    assert_eq!((segment.object_name.as_str(), segment.object_id.0.as_str()), ("ISS (ZARYA)", "1998-067A"));
    assert_eq!(segment.last.epoch.to_string(), "2026-03-20T00:02:00.25");
    assert_eq!(segment.last.state, [-4570.1, -1025.5, 5330.2, 4.35, -5.56, 2.60], "accelerations dropped");
    let covariance = segment.covariance.as_ref().expect("covariance");
    assert_eq!((covariance.matrix[1][0], covariance.matrix[0][1], covariance.matrix[5][5]), (0.1, 0.1, 1e-6));
    let prior = prior_from_oem(&oem, &Instant::epoch_of(&tiny()), 64, "embedded").expect("prior");
    assert_eq!(prior.prior.time, 120.25);
    assert_eq!((prior.prior.hypotheses[0].objects[0].label, prior.renumbered), (1, true));
}
