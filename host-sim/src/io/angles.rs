//! Azimuth and right ascension in any convention: a value in [−360°, 720°] ([`ACCEPTED_TURN`]) is wrapped
//! once, on the way in, to the core's (−180°, 180°]; the fields of view and residuals see only that.
//!
//! A TDM's value is wrapped in decimal, exactly, before its one rounding to binary ([`wrap_decimal`]): an
//! angle written as 350.87654321 reads as the same `f64` as −9.12345679 written directly. A scenario file's
//! value, already a binary `f64`, is wrapped in binary ([`wrap`]): whole turns of 360° subtracted, exact
//! whenever the result is within a factor 2 of 360° (Sterbenz), else rounded once.

/// The accepted range of an azimuth or a right ascension (deg): [−360°, 720°], a turn either side of the
/// two usual conventions [0°, 360°) and (−180°, 180°].
pub const ACCEPTED_TURN: (f64, f64) = (-360.0, 720.0);

/// Whole turns to subtract from `degrees` to bring it into (−180°, 180°].
fn turns(degrees: f64) -> i64 {
    if degrees > 180.0 {
        ((degrees - 180.0) / 360.0).ceil() as i64
    } else if degrees <= -180.0 {
        -(((-180.0 - degrees) / 360.0).floor() as i64 + 1)
    } else {
        0
    }
}

/// `degrees` (finite, within [`ACCEPTED_TURN`]) in (−180°, 180°]: unchanged there, else whole turns
/// subtracted.
pub fn wrap(degrees: f64) -> f64 {
    match turns(degrees) {
        0 => degrees,
        k => degrees - 360.0 * k as f64,
    }
}

/// The decimal number `text` (as `f64::from_str` reads it) in (−180°, 180°], the whole turns subtracted
/// in decimal before the one rounding to `f64`; `None` when `text` is not a finite number or lies outside
/// [`ACCEPTED_TURN`].
pub fn wrap_decimal(text: &str) -> Option<f64> {
    let value: f64 = text.parse().ok().filter(|v: &f64| v.is_finite())?;
    if !(ACCEPTED_TURN.0..=ACCEPTED_TURN.1).contains(&value) {
        return None;
    }
    let k = turns(value);
    if k == 0 {
        return Some(value);
    }
    // value = digits × 10^exponent exactly; subtract 360 k × 10^-exponent in integers.
    let exact = decimal(text).and_then(|(digits, exponent)| {
        let scale = 10i128.checked_pow(u32::try_from(-exponent).ok()?)?;
        let turns = i128::from(360 * k).checked_mul(scale)?;
        format!("{}e{exponent}", digits.checked_sub(turns)?).parse::<f64>().ok()
    });
    Some(exact.unwrap_or_else(|| wrap(value)))
}

/// `text` as an integer and a power of ten (`-12.5e1` is (−125, 0)), when it is a plain decimal whose
/// digits fit an `i128` and whose exponent is ≤ 0 after the fraction; `None` otherwise.
fn decimal(text: &str) -> Option<(i128, i32)> {
    let text = text.trim();
    let (mantissa, exponent) = match text.find(['e', 'E']) {
        Some(at) => (&text[..at], text[at + 1..].parse::<i32>().ok()?),
        None => (text, 0),
    };
    let (negative, unsigned) = match mantissa.strip_prefix('-') {
        Some(rest) => (true, rest),
        None => (false, mantissa.strip_prefix('+').unwrap_or(mantissa)),
    };
    let (whole, fraction) = unsigned.split_once('.').unwrap_or((unsigned, ""));
    if whole.is_empty() && fraction.is_empty() || !whole.chars().chain(fraction.chars()).all(|c| c.is_ascii_digit()) {
        return None;
    }
    let mut digits: i128 = 0;
    for c in whole.chars().chain(fraction.chars()) {
        digits = digits.checked_mul(10)?.checked_add(i128::from(c as u8 - b'0'))?;
    }
    let exponent = exponent.checked_sub(i32::try_from(fraction.len()).ok()?)?;
    if exponent > 0 {
        // A whole number of degrees times a power of ten: an integer.
        return Some((digits.checked_mul(10i128.checked_pow(exponent as u32)?)? * if negative { -1 } else { 1 }, 0));
    }
    Some((if negative { -digits } else { digits }, exponent))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_conventions_meet_in_the_cores() {
        for (given, expected) in
            [(0.0, 0.0), (180.0, 180.0), (180.5, -179.5), (359.0, -1.0), (-180.0, 180.0), (-360.0, 0.0), (720.0, 0.0)]
        {
            assert_eq!(wrap(given), expected, "{given}");
        }
        assert_eq!(wrap(-179.999), -179.999);
        assert_eq!(wrap(540.25), 180.25 - 360.0);
    }

    #[test]
    fn a_decimal_angle_wraps_exactly_before_rounding() {
        // The decimal 360 + v written out reads as the very f64 of v.
        for (shifted, plain) in [
            ("350.876543210987654", "-9.123456789012346"),
            ("359.99999999999999", "-0.00000000000001"),
            ("180.000000000000057", "-179.999999999999943"),
            ("-180", "180"),
            ("3.5e2", "-10"),
            ("-200.125", "159.875"),
            ("719.5", "-0.5"),
            ("10.25", "10.25"),
        ] {
            assert_eq!(wrap_decimal(shifted), plain.parse().ok(), "{shifted}");
        }
        // In binary the same shift is not exact: the decimal wrap is what makes the conventions bit-equal.
        let v: f64 = -9.123456789012346;
        assert_ne!(wrap(v + 360.0), v);
        for refused in ["720.5", "-360.5", "nan", "inf", "1e400", "x"] {
            assert_eq!(wrap_decimal(refused), None, "{refused}");
        }
    }
}
