//! What an error message quotes of its input: a short excerpt of any text the user gave ([`excerpt`],
//! [`cut_quotes`]), and numbers in a readable form ([`Readable`]), so a message stays one short line
//! whatever the file holds (a 10 MB key or value, `1e308`).

use std::fmt;

/// The most characters of user text a message quotes.
pub const EXCERPT_CHARS: usize = 60;

/// The longest message (characters) kept whole; a longer one is cut as [`excerpt`] does.
pub const MAX_MESSAGE_CHARS: usize = 1000;

/// `text` as it is when it has at most `max_chars` characters; else its first `max_chars` characters (cut
/// on a character boundary), then `…` and the length of the whole, e.g. `AAAA… (10485760 bytes)`.
pub fn excerpt(text: &str, max_chars: usize) -> String {
    match text.char_indices().nth(max_chars) {
        None => text.to_string(),
        Some((end, _)) => format!("{}… ({} bytes)", &text[..end], text.len()),
    }
}

/// `message` with every part between backticks or double quotes longer than [`EXCERPT_CHARS`] cut to an
/// [`excerpt`] (serde's "unknown field `…`" and "invalid type: string \"…\"" quote the input whole), then
/// the whole cut to [`MAX_MESSAGE_CHARS`].
pub fn cut_quotes(message: &str) -> String {
    let mut out = String::with_capacity(message.len().min(4 * MAX_MESSAGE_CHARS));
    let mut rest = message;
    while let Some(open) = rest.find(['`', '"']) {
        let quote = rest.as_bytes()[open] as char;
        let body_start = open + 1;
        let Some(close) = closing_quote(&rest[body_start..], quote) else { break };
        let body = &rest[body_start..body_start + close];
        out.push_str(&rest[..body_start]);
        out.push_str(&excerpt(body, EXCERPT_CHARS));
        out.push(quote);
        rest = &rest[body_start + close + 1..];
        if out.len() > 4 * MAX_MESSAGE_CHARS {
            break;
        }
    }
    out.push_str(rest);
    excerpt(&out, MAX_MESSAGE_CHARS)
}

/// The offset of the quote closing a quoted text (`\` escapes the next character).
fn closing_quote(body: &str, quote: char) -> Option<usize> {
    let mut escaped = false;
    for (i, c) in body.char_indices() {
        match c {
            _ if escaped => escaped = false,
            '\\' => escaped = true,
            c if c == quote => return Some(i),
            _ => {}
        }
    }
    None
}

/// A number as a message prints it: Rust's shortest round-trip form between 10⁻⁴ and 10¹⁵ in magnitude
/// (`0.5`, `744`), scientific beyond (`1e308`, `-2.5e-7`), so `1e308` is not 309 digits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Readable(pub f64);

impl fmt::Display for Readable {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v = self.0;
        if v == 0.0 || !v.is_finite() || (1e-4..1e15).contains(&v.abs()) {
            write!(f, "{v}")
        } else {
            write!(f, "{v:e}")
        }
    }
}

/// A seed: an integer in 0..=u64::MAX, anything else refused with that range (serde's own message for
/// `1e30` or 18446744073709551616 is "invalid type: floating point …, expected u64").
pub(crate) fn seed<'de, D: serde::Deserializer<'de>>(deserializer: D) -> Result<u64, D::Error> {
    struct Seed;
    impl serde::de::Visitor<'_> for Seed {
        type Value = u64;
        fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
            write!(f, "an integer in 0..={}", u64::MAX)
        }
        fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<u64, E> {
            Ok(v)
        }
        fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<u64, E> {
            u64::try_from(v).map_err(|_| E::custom(SEED_RANGE))
        }
        fn visit_f64<E: serde::de::Error>(self, _: f64) -> Result<u64, E> {
            Err(E::custom(SEED_RANGE))
        }
        fn visit_str<E: serde::de::Error>(self, _: &str) -> Result<u64, E> {
            Err(E::custom(SEED_RANGE))
        }
        fn visit_bool<E: serde::de::Error>(self, _: bool) -> Result<u64, E> {
            Err(E::custom(SEED_RANGE))
        }
        fn visit_unit<E: serde::de::Error>(self) -> Result<u64, E> {
            Err(E::custom(SEED_RANGE))
        }
    }
    deserializer.deserialize_u64(Seed)
}

/// What a seed must be.
const SEED_RANGE: &str = "must be an integer in 0..=18446744073709551615";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_text_is_cut_on_a_character_boundary_and_says_its_length() {
        assert_eq!(excerpt("short", 60), "short");
        assert_eq!(excerpt("ééé", 2), "éé… (6 bytes)");
        let long = "A".repeat(10 << 20);
        let cut = excerpt(&long, 60);
        assert_eq!(cut, format!("{}… (10485760 bytes)", "A".repeat(60)));
    }

    #[test]
    fn quoted_inputs_are_cut_and_the_rest_kept() {
        let key = "K".repeat(1 << 20);
        let message = format!("unknown field `{key}`, expected one of `format`, `version`");
        let cut = cut_quotes(&message);
        assert!(cut.len() < 200, "{cut}");
        assert!(
            cut.starts_with("unknown field `KKKK")
                && cut.ends_with("(1048576 bytes)`, expected one of `format`, `version`")
        );
        let value = format!("invalid type: string \"{}\\\"{}\", expected f64", "v".repeat(100), "w".repeat(100));
        let cut = cut_quotes(&value);
        assert!(cut.ends_with("bytes)\", expected f64") && cut.len() < 120, "{cut}");
        assert_eq!(cut_quotes("expected \"2 \" right after line 1"), "expected \"2 \" right after line 1");
        assert_eq!(cut_quotes("a lone \" quote"), "a lone \" quote");
        let unquoted = "x".repeat(5000);
        assert!(cut_quotes(&unquoted).chars().count() < MAX_MESSAGE_CHARS + 30);
    }

    #[test]
    fn numbers_are_readable() {
        assert_eq!(Readable(1e308).to_string(), "1e308");
        assert_eq!(Readable(744.0).to_string(), "744");
        assert_eq!(Readable(0.5).to_string(), "0.5");
        assert_eq!(Readable(-2.5e-7).to_string(), "-2.5e-7");
        assert_eq!(Readable(0.0).to_string(), "0");
        assert_eq!(Readable(f64::NAN).to_string(), "NaN");
        assert_eq!(Readable(f64::NEG_INFINITY).to_string(), "-inf");
    }
}
