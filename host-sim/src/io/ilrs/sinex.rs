//! Station positions from a SINEX file (Solution INdependent EXchange format 2.02): the `STAX`, `STAY`,
//! `STAZ` (m) and `VELX`, `VELY`, `VELZ` (m/y) estimates of its `SOLUTION/ESTIMATE` block, per site code,
//! at their reference epoch `YY:DDD:SSSSS`; a station's position at a date is the linear propagation the
//! ILRS's SLRF files prescribe, p + v (t − t_ref) with years of 365.25 days.
//!
//! Every other block is skipped. Refused: an estimate line of another form, a site with two solutions
//! (keep, in the file given, the one valid at the data's dates), a site without all three coordinates, a
//! block that does not end.

use super::{DayTime, Fields, IlrsError, day_number, fail};

/// One station's position and velocity in the file's frame (ITRF for the SLRF).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Station {
    /// Its site code, e.g. 7090 (the CDP pad number of an SLR station).
    pub code: u32,
    /// Position at `epoch` (m).
    pub position: [f64; 3],
    /// Velocity (m/y; zero when the file gives none).
    pub velocity: [f64; 3],
    /// The reference epoch of the estimates.
    pub epoch: DayTime,
    /// Line of its first estimate.
    pub line: usize,
}

impl Station {
    /// Position (m) at `time`.
    pub fn position_at(&self, time: DayTime) -> [f64; 3] {
        let years = time.since(self.epoch.day) - self.epoch.seconds;
        let years = years / (365.25 * 86_400.0);
        std::array::from_fn(|k| self.position[k] + self.velocity[k] * years)
    }
}

/// The estimate types read: position then velocity components.
const TYPES: [&str; 6] = ["STAX", "STAY", "STAZ", "VELX", "VELY", "VELZ"];

/// A partly read station: its estimates so far and their solution number.
struct Partial {
    station: Station,
    solution: String,
    seen: [bool; 6],
}

/// Parses the `SOLUTION/ESTIMATE` block of a SINEX file.
///
/// # Errors
/// The first problem: a malformed estimate line, a unit that is not the type's (m, m/y), two solutions of
/// one site, a site without its three coordinates, no block or a block that does not end.
pub fn parse(text: &str) -> Result<Vec<Station>, IlrsError> {
    let mut partial: Vec<Partial> = vec![];
    let mut inside = false;
    let mut ended = false;
    let mut last = 0;
    for (index, raw) in text.lines().enumerate() {
        let line = index + 1;
        last = line;
        if raw.starts_with("+SOLUTION/ESTIMATE") {
            inside = true;
            continue;
        }
        if raw.starts_with("-SOLUTION/ESTIMATE") {
            if !inside {
                return fail(line, "-SOLUTION/ESTIMATE", "the block's end before its start");
            }
            inside = false;
            ended = true;
            continue;
        }
        if inside && raw.starts_with(['%', '+', '-']) {
            return fail(line, "-SOLUTION/ESTIMATE", "the block is not ended before this line");
        }
        if !inside || raw.starts_with('*') || raw.trim().is_empty() {
            continue;
        }
        estimate(&Fields::of(line, raw), &mut partial)?;
    }
    if inside {
        return fail(last + 1, "-SOLUTION/ESTIMATE", "the file ends inside the block");
    }
    if !ended {
        return fail(last + 1, "+SOLUTION/ESTIMATE", "no SOLUTION/ESTIMATE block");
    }
    partial
        .into_iter()
        .map(|p| match p.seen[..3].iter().all(|&s| s) {
            true => Ok(p.station),
            false => {
                fail(p.station.line, "STAX", format!("site {} lacks a coordinate (STAX, STAY, STAZ)", p.station.code))
            }
        })
        .collect()
}

/// One estimate line: `index type code point solution epoch unit constraint value sigma`.
fn estimate(f: &Fields, partial: &mut Vec<Partial>) -> Result<(), IlrsError> {
    let kind = f.text(1, "type")?;
    let Some(k) = TYPES.iter().position(|t| *t == kind) else { return Ok(()) };
    let code = f.integer(2, "site code", 0..=9999)? as u32;
    let solution = f.text(4, "solution")?.to_string();
    let epoch = sinex_epoch(f, 5)?;
    let unit = if k < 3 { "m" } else { "m/y" };
    if f.text(6, "unit")? != unit {
        return f.fail("unit", format!("{kind} must be in {unit}"));
    }
    let value = f.number(8, "estimated value")?;
    if value.abs() > 1e8 {
        return f.fail("estimated value", format!("{value} is beyond 1e8"));
    }
    let i = match partial.iter().position(|p| p.station.code == code) {
        Some(i) => i,
        None => {
            let station = Station { code, position: [0.0; 3], velocity: [0.0; 3], epoch, line: f.line };
            partial.push(Partial { station, solution: solution.clone(), seen: [false; 6] });
            partial.len() - 1
        }
    };
    let p = &mut partial[i];
    if p.solution != solution || p.seen[k] {
        return f
            .fail("solution", format!("site {code} has several solutions: keep the one valid at the data's dates"));
    }
    if p.station.epoch != epoch {
        return f.fail("reference epoch", format!("site {code}'s estimates have different epochs"));
    }
    p.seen[k] = true;
    if k < 3 {
        p.station.position[k] = value;
    } else {
        p.station.velocity[k - 3] = value;
    }
    Ok(())
}

/// A SINEX epoch `YY:DDD:SSSSS` (YY ≤ 50: 20YY, else 19YY).
fn sinex_epoch(f: &Fields, index: usize) -> Result<DayTime, IlrsError> {
    let text = f.text(index, "reference epoch")?;
    let parts: Vec<&str> = text.split(':').collect();
    let parsed: Option<Vec<i64>> = parts.iter().map(|p| p.parse::<i64>().ok()).collect();
    let Some([yy, doy, seconds]) = parsed.and_then(|v| <[i64; 3]>::try_from(v).ok()) else {
        return f.fail("reference epoch", "not YY:DDD:SSSSS");
    };
    let year = if yy <= 50 { 2000 + yy } else { 1900 + yy };
    match day_number(year, 1, 1) {
        Some(jan1) if (0..=99).contains(&yy) && (1..=366).contains(&doy) && (0..86_400).contains(&seconds) => {
            Ok(DayTime { day: jan1 + doy - 1, seconds: seconds as f64 })
        }
        _ => f.fail("reference epoch", format!("{text} is not a time YY:DDD:SSSSS")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SAMPLE: &str = "\
%=SNX 2.01 JCT 20:119:43200 JCT 79:215:00000 20:119:43200 C 01338 2 X V
+SITE/ID
 7090  A 50107M001 L Yarragadee MOBLAS-5    115 20 48.2 -29 -2-47.3   242.0     70900501
-SITE/ID
+SOLUTION/ESTIMATE
*INDEX TYPE__ CODE PT SOLN _REF_EPOCH__ UNIT S __ESTIMATED VALUE____ _STD_DEV___
   205 STAX   7090  A    1 10:001:00000 m    2 -.238900753398029E+07 0.51901E-03
   206 STAY   7090  A    1 10:001:00000 m    2 0.504332944749889E+07 0.30033E-03
   207 STAZ   7090  A    1 10:001:00000 m    2 -.307852422322662E+07 0.22901E-03
   208 VELX   7090  A    1 10:001:00000 m/y  2 -.468389138240797E-01 0.34434E-04
   209 VELY   7090  A    1 10:001:00000 m/y  2 0.839461295243685E-02 0.22507E-04
   210 VELZ   7090  A    1 10:001:00000 m/y  2 0.509471988578335E-01 0.25057E-04
-SOLUTION/ESTIMATE
%ENDSNX
";

    #[test]
    fn a_station_is_read_and_propagated_with_its_velocity() {
        let stations = parse(SAMPLE).expect("valid");
        assert_eq!(stations.len(), 1);
        let s = &stations[0];
        assert_eq!((s.code, s.line), (7090, 7));
        assert_eq!(s.position[0], -2_389_007.533_980_29);
        assert_eq!(s.epoch.day, day_number(2010, 1, 1).expect("date"));
        // 365.25 days later: one year of velocity.
        let later = s.position_at(s.epoch.plus(365.25 * 86_400.0));
        assert!((later[0] - (s.position[0] + s.velocity[0])).abs() < 1e-9, "{later:?}");
    }

    #[test]
    fn malformed_estimates_name_their_line_and_field() {
        let cases = [
            ("m    2 -.2389", "km   2 -.2389", 7, "205 unit", "must be in m"),
            ("-.238900753398029E+07", "x.2389", 7, "205 estimated value", "not a finite number"),
            ("10:001:00000 m    2 0.5043", "10:400:00000 m    2 0.5043", 8, "206 reference epoch", "not a time"),
            (
                "7090  A    1 10:001:00000 m    2 0.5043",
                "7090  A    2 10:001:00000 m    2 0.5043",
                8,
                "206 solution",
                "several solutions",
            ),
            ("-SOLUTION/ESTIMATE\n", "", 13, "-SOLUTION/ESTIMATE", "not ended"),
        ];
        for (from, to, line, field, message) in cases {
            let text = SAMPLE.replacen(from, to, 1);
            assert_ne!(text, SAMPLE, "{from}");
            let e = parse(&text).expect_err(to);
            assert_eq!((e.line, e.field.as_str()), (line, field), "{to}: {e}");
            assert!(e.message.contains(message), "{to}: {}", e.message);
        }
        let no_z = parse(&SAMPLE.replace("STAZ", "STAQ")).unwrap_err();
        assert!(no_z.message.contains("lacks a coordinate"), "{no_z}");
        assert!(parse("%=SNX\n").unwrap_err().message.contains("no SOLUTION/ESTIMATE"));
    }
}
