//! Two- and three-line element sets: columns, checksums, Alpha-5 catalogue numbers, assumed exponents and epochs.

use super::entry::err;
use super::entry::{CatalogueEntry, CatalogueError, MAX_NAME_CHARS};
use sgp4::chrono::{NaiveDate, NaiveDateTime, NaiveTime};

/// Parses two-line (and three-line, with a name line, optionally "0 NAME") element sets. Blank lines and
/// lines starting with `#` are skipped; lines 1 and 2 must follow each other.
pub fn parse_tle(file: &str, text: &str) -> Result<Vec<CatalogueEntry>, CatalogueError> {
    let lines: Vec<&str> = text.lines().collect();
    let mut entries = vec![];
    let mut name: Option<(usize, String)> = None;
    let mut i = 0;
    while i < lines.len() {
        let number = i + 1;
        let line = lines[i].trim_end();
        i += 1;
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        tabs_refused(file, number, line)?;
        if line.starts_with("1 ") {
            let Some(next) = lines.get(i).map(|l| l.trim_end()) else {
                return Err(err(file, number, "line 2", "missing after line 1"));
            };
            tabs_refused(file, number + 1, next)?;
            if !next.starts_with("2 ") {
                return Err(err(file, number + 1, "line 2", "expected \"2 \" right after line 1"));
            }
            i += 1;
            let mut entry = tle_pair(file, number, line, next)?;
            if let Some((name_line, text)) = name.take() {
                entry.name = Some(text);
                entry.line = name_line;
            }
            entries.push(entry);
        } else if line.starts_with("2 ") {
            return Err(err(file, number, "line 2", "without a line 1 before it"));
        } else {
            if let Some((name_line, _)) = name {
                let why = format!("not followed by a line 1: line {number} does not start with \"1 \"");
                return Err(err(file, name_line, "name line", why));
            }
            let text = line.strip_prefix("0 ").unwrap_or(line).trim();
            if text.chars().count() > MAX_NAME_CHARS {
                return Err(err(file, number, "name line", format!("longer than {MAX_NAME_CHARS} characters")));
            }
            name = Some((number, text.to_string()));
        }
    }
    if let Some((name_line, _)) = name {
        return Err(err(file, name_line, "name line", "not followed by a line 1"));
    }
    Ok(entries)
}

/// A line that starts as a TLE line 1 or 2 ("1" or "2" and a blank) but holds a tab is refused as such (not
/// taken for a name line).
fn tabs_refused(file: &str, number: usize, line: &str) -> Result<(), CatalogueError> {
    let b = line.as_bytes();
    if b.len() >= 2 && matches!(b[0], b'1' | b'2') && b[1].is_ascii_whitespace() && line.contains('\t') {
        let which = format!("line {}", b[0] as char);
        return Err(err(file, number, which, "contains a tab: the columns of a TLE line are blanks, not tabs"));
    }
    Ok(())
}

/// The TLE modulo-10 checksum of the first 68 columns: digits count their value, '-' counts 1.
pub fn tle_checksum(line: &[u8]) -> u32 {
    line.iter()
        .take(68)
        .map(|&b| match b {
            b'0'..=b'9' => u32::from(b - b'0'),
            b'-' => 1,
            _ => 0,
        })
        .sum::<u32>()
        % 10
}

/// A catalogue number of 5 columns: digits (leading blanks allowed) or Alpha-5, a letter (A-Z without I
/// and O, A = 10) followed by 4 digits: "A0001" = 100001, "Z9999" = 339999.
pub fn parse_catalogue_number(field: &str) -> Option<u64> {
    let bytes = field.as_bytes();
    if bytes.len() != 5 {
        return None;
    }
    let first = bytes[0];
    if first == b' ' {
        let t = field.trim_start();
        return (!t.is_empty() && t.bytes().all(|b| b.is_ascii_digit())).then(|| t.parse().ok()).flatten();
    }
    let rest = &field[1..];
    if !rest.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    let rest: u64 = rest.parse().ok()?;
    let lead = match first {
        b'0'..=b'9' => u64::from(first - b'0'),
        b'A'..=b'H' => u64::from(first - b'A') + 10,
        b'J'..=b'N' => u64::from(first - b'J') + 18,
        b'P'..=b'Z' => u64::from(first - b'P') + 23,
        _ => return None,
    };
    Some(lead * 10_000 + rest)
}

/// A decimal field (`-.00000084`, `15.56387291`): optional sign, digits and at most one point, blanks around.
fn decimal(field: &str) -> Option<f64> {
    let t = field.trim();
    let body = t.strip_prefix(['-', '+']).unwrap_or(t);
    let valid = !body.is_empty()
        && body.bytes().all(|b| b.is_ascii_digit() || b == b'.')
        && body.bytes().filter(|&b| b == b'.').count() <= 1
        && body.bytes().any(|b| b.is_ascii_digit());
    if !valid {
        return None;
    }
    t.parse::<f64>().ok().filter(|v| v.is_finite())
}

/// An 8-column field with an assumed leading decimal point and an exponent: " 12345-3" = 0.12345e-3.
fn assumed_exponent(field: &str) -> Option<f64> {
    let b = field.as_bytes();
    if b.len() != 8 {
        return None;
    }
    let sign = match b[0] {
        b' ' | b'+' => 1.0,
        b'-' => -1.0,
        _ => return None,
    };
    if !b[1..6].iter().all(u8::is_ascii_digit) || !b[7].is_ascii_digit() {
        return None;
    }
    let exponent_sign = match b[6] {
        b' ' | b'+' => 1,
        b'-' => -1,
        _ => return None,
    };
    let mantissa: f64 = field[1..6].parse::<u32>().ok()? as f64 / 1e5;
    let exponent = exponent_sign * i32::from(b[7] - b'0');
    Some(sign * mantissa * 10f64.powi(exponent))
}

/// An unsigned integer field, blanks around; a blank field is `blank`.
pub(crate) fn unsigned(field: &str, blank: Option<u64>) -> Option<u64> {
    let t = field.trim();
    if t.is_empty() {
        return blank;
    }
    if !t.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    t.parse().ok()
}

/// The epoch of TLE columns 19-32: two-digit year (57-99 → 19xx, 00-56 → 20xx) and day of the year with
/// its fraction (day 1.0 is 1 January 0h).
fn tle_epoch(year: &str, day: &str) -> Option<NaiveDateTime> {
    if !year.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    let yy: i32 = year.parse().ok()?;
    let year = if yy < 57 { 2000 + yy } else { 1900 + yy };
    let day = decimal(day).filter(|d| *d >= 1.0 && !day.trim().starts_with(['-', '+']))?;
    let ordinal = day.floor();
    let nanos = ((day - ordinal) * 86_400e9).round() as u64;
    let (ordinal, nanos) = if nanos >= 86_400_000_000_000 { (ordinal + 1.0, 0) } else { (ordinal, nanos) };
    let date = NaiveDate::from_yo_opt(year, ordinal as u32)?;
    let time =
        NaiveTime::from_num_seconds_from_midnight_opt((nanos / 1_000_000_000) as u32, (nanos % 1_000_000_000) as u32)?;
    Some(date.and_time(time))
}

/// Lines 1 and 2 of one element set (line 1 at `number`).
fn tle_pair(file: &str, number: usize, line1: &str, line2: &str) -> Result<CatalogueEntry, CatalogueError> {
    for (k, line) in [(1, line1), (2, line2)] {
        let at = number + k - 1;
        if !line.is_ascii() {
            return Err(err(file, at, format!("line {k}"), "not ASCII"));
        }
        if line.len() != 69 {
            return Err(err(file, at, format!("line {k}"), format!("{} columns, expected 69", line.len())));
        }
        let b = line.as_bytes();
        if !b[68].is_ascii_digit() {
            return Err(err(file, at, format!("line {k} column 69 (checksum)"), "not a digit"));
        }
        let sum = tle_checksum(b);
        if sum != u32::from(b[68] - b'0') {
            return Err(err(
                file,
                at,
                format!("line {k} column 69 (checksum)"),
                format!("is {}, the columns 1-68 give {sum}", b[68] - b'0'),
            ));
        }
        let blanks: &[usize] = if k == 1 { &[2, 9, 18, 33, 44, 53, 62, 64] } else { &[2, 8, 17, 26, 34, 43, 52] };
        if let Some(&c) = blanks.iter().find(|&&c| b[c - 1] != b' ') {
            return Err(err(file, at, format!("line {k} column {c}"), "expected a blank"));
        }
    }
    let l2 = number + 1;
    let f1 = |a: usize, b: usize| &line1[a - 1..b];
    let f2 = |a: usize, b: usize| &line2[a - 1..b];
    let bad = |line: usize, cols: &str, what: &str, expected: &str, value: &str| {
        err(file, line, format!("line {} columns {cols} ({what})", line + 1 - number), format!("{value:?}: {expected}"))
    };
    let norad_id = parse_catalogue_number(f1(3, 7))
        .ok_or_else(|| bad(number, "3-7", "catalogue number", "expected 5 digits or Alpha-5", f1(3, 7)))?;
    let norad_2 = parse_catalogue_number(f2(3, 7))
        .ok_or_else(|| bad(l2, "3-7", "catalogue number", "expected 5 digits or Alpha-5", f2(3, 7)))?;
    if norad_2 != norad_id {
        return Err(bad(l2, "3-7", "catalogue number", &format!("differs from line 1's {norad_id}"), f2(3, 7)));
    }
    let classification = match line1.as_bytes()[7] {
        c @ (b'U' | b'C' | b'S') => c as char,
        _ => return Err(bad(number, "8-8", "classification", "expected U, C or S", f1(8, 8))),
    };
    let designator = f1(10, 17).trim();
    let epoch = tle_epoch(f1(19, 20), f1(21, 32))
        .ok_or_else(|| bad(number, "19-32", "epoch", "expected YYDDD.DDDDDDDD with a day of the year", f1(19, 32)))?;
    let mean_motion_dot =
        decimal(f1(34, 43)).ok_or_else(|| bad(number, "34-43", "mean motion dot", "expected a decimal", f1(34, 43)))?;
    let mean_motion_ddot = assumed_exponent(f1(45, 52))
        .ok_or_else(|| bad(number, "45-52", "mean motion ddot", "expected [sign]DDDDD[sign]D", f1(45, 52)))?;
    let bstar = assumed_exponent(f1(54, 61))
        .ok_or_else(|| bad(number, "54-61", "B*", "expected [sign]DDDDD[sign]D", f1(54, 61)))?;
    let ephemeris_type = unsigned(f1(63, 63), Some(0))
        .ok_or_else(|| bad(number, "63-63", "ephemeris type", "expected a digit", f1(63, 63)))?
        as u8;
    let element_set_number = unsigned(f1(65, 68), Some(0))
        .ok_or_else(|| bad(number, "65-68", "element set number", "expected digits", f1(65, 68)))?;
    let angle = |a, b, what| {
        decimal(f2(a, b)).ok_or_else(|| bad(l2, &format!("{a}-{b}"), what, "expected a decimal", f2(a, b)))
    };
    let inclination = angle(9, 16, "inclination")?;
    let right_ascension = angle(18, 25, "right ascension")?;
    let ecc = f2(27, 33);
    if !ecc.bytes().all(|b| b.is_ascii_digit()) {
        return Err(bad(l2, "27-33", "eccentricity", "expected 7 digits after an assumed \"0.\" (0 <= e < 1)", ecc));
    }
    let eccentricity =
        ecc.parse::<u32>().map_err(|_| bad(l2, "27-33", "eccentricity", "expected 7 digits", ecc))? as f64 / 1e7;
    let argument_of_perigee = angle(35, 42, "argument of perigee")?;
    let mean_anomaly = angle(44, 51, "mean anomaly")?;
    let mean_motion = angle(53, 63, "mean motion")?;
    let revolution_number = unsigned(f2(64, 68), Some(0))
        .ok_or_else(|| bad(l2, "64-68", "revolution number", "expected digits", f2(64, 68)))?;
    let entry = CatalogueEntry {
        name: None,
        norad_id,
        international_designator: (!designator.is_empty()).then(|| designator.to_string()),
        classification,
        epoch,
        mean_motion_dot,
        mean_motion_ddot,
        bstar,
        inclination,
        right_ascension,
        eccentricity,
        argument_of_perigee,
        mean_anomaly,
        mean_motion,
        element_set_number,
        revolution_number,
        ephemeris_type,
        line: number,
    };
    entry.check_ranges().map_err(|(field, message)| err(file, l2, field.tle(), message))?;
    Ok(entry)
}
