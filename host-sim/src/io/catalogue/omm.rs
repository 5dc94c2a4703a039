//! CCSDS OMM mean elements as CelesTrak writes them, in JSON and in CSV.

use super::entry::err;
use super::entry::{CatalogueEntry, CatalogueError, MAX_NAME_CHARS};
use super::tle::unsigned;
use crate::sim::time::CalendarTime;
use sgp4::chrono::{NaiveDate, NaiveDateTime};

/// One OMM value before conversion.
enum Raw<'a> {
    Text(&'a str),
    Number(&'a serde_json::Number),
    /// A JSON value of another type (its name).
    Other(&'static str),
}

/// An OMM ISO-8601 epoch `YYYY-MM-DDTHH:MM:SS[.fraction of up to 9 digits][Z]`, year in 1900-2099.
pub fn parse_omm_epoch(text: &str) -> Option<NaiveDateTime> {
    let time = CalendarTime::parse(text)?;
    if time.fraction.len() > 9 || !(1900..=2099).contains(&time.year) {
        return None;
    }
    let nanos: u32 = if time.fraction.is_empty() { 0 } else { format!("{:0<9}", time.fraction).parse().ok()? };
    NaiveDate::from_ymd_opt(time.year, time.month, time.day)?.and_hms_nano_opt(
        time.hour,
        time.minute,
        time.second,
        nanos,
    )
}

/// One OMM record: its values by keyword and the line of each.
fn omm_entry<'a>(
    file: &str,
    start: usize,
    get: &dyn Fn(&str) -> Option<Raw<'a>>,
    line_of: &dyn Fn(&str) -> usize,
) -> Result<CatalogueEntry, CatalogueError> {
    let fail = |key: &str, message: String| err(file, line_of(key), key, message);
    let text = |key: &str| -> Result<Option<String>, CatalogueError> {
        match get(key) {
            None => Ok(None),
            Some(Raw::Text(s)) => Ok(Some(s.to_string())),
            Some(Raw::Number(n)) => Err(fail(key, format!("expected a string, found the number {n}"))),
            Some(Raw::Other(t)) => Err(fail(key, format!("expected a string, found {t}"))),
        }
    };
    let number = |key: &str, required: bool| -> Result<Option<f64>, CatalogueError> {
        let value = match get(key) {
            None if required => return Err(fail(key, "missing".into())),
            None => return Ok(None),
            Some(Raw::Number(n)) => n.as_f64(),
            Some(Raw::Text(s)) if s.trim().is_empty() && !required => return Ok(None),
            Some(Raw::Text(s)) => {
                let t = s.trim();
                let ok = !t.is_empty() && t.bytes().all(|b| b.is_ascii_digit() || b"+-.eE".contains(&b));
                if ok { t.parse::<f64>().ok() } else { None }
            }
            Some(Raw::Other(t)) => return Err(fail(key, format!("expected a number, found {t}"))),
        };
        match value {
            Some(v) if v.is_finite() => Ok(Some(v)),
            _ => Err(fail(key, "expected a finite number".into())),
        }
    };
    let integer = |key: &str, required: bool, max: u64| -> Result<Option<u64>, CatalogueError> {
        let value = match get(key) {
            None if required => return Err(fail(key, "missing".into())),
            None => return Ok(None),
            Some(Raw::Number(n)) => n.as_u64(),
            Some(Raw::Text(s)) if s.trim().is_empty() && !required => return Ok(None),
            Some(Raw::Text(s)) => unsigned(s, None),
            Some(Raw::Other(t)) => return Err(fail(key, format!("expected an integer, found {t}"))),
        };
        match value {
            Some(v) if v <= max => Ok(Some(v)),
            _ => Err(fail(key, format!("expected an integer in [0, {max}]"))),
        }
    };
    if let Some(theory) = text("MEAN_ELEMENT_THEORY")?
        && theory.trim() != "SGP4"
    {
        return Err(fail("MEAN_ELEMENT_THEORY", format!("{theory:?} is not SGP4")));
    }
    let epoch_text = text("EPOCH")?.ok_or_else(|| fail("EPOCH", "missing".into()))?;
    let epoch = parse_omm_epoch(epoch_text.trim())
        .ok_or_else(|| fail("EPOCH", format!("{epoch_text:?} is not YYYY-MM-DDTHH:MM:SS[.ffffff] (1900-2099)")))?;
    let classification = match text("CLASSIFICATION_TYPE")?.as_deref().map(str::trim) {
        None | Some("") | Some("U") => 'U',
        Some("C") => 'C',
        Some("S") => 'S',
        Some(other) => return Err(fail("CLASSIFICATION_TYPE", format!("{other:?} is not U, C or S"))),
    };
    let required = |key: &str| number(key, true).map(|v| v.unwrap_or(0.0));
    let name = text("OBJECT_NAME")?.map(|s| s.trim().to_string());
    if name.as_ref().is_some_and(|n| n.chars().count() > MAX_NAME_CHARS) {
        return Err(fail("OBJECT_NAME", format!("longer than {MAX_NAME_CHARS} characters")));
    }
    let entry = CatalogueEntry {
        name,
        norad_id: integer("NORAD_CAT_ID", true, 999_999_999)?.unwrap_or(0),
        international_designator: text("OBJECT_ID")?.map(|s| s.trim().to_string()).filter(|s| !s.is_empty()),
        classification,
        epoch,
        mean_motion_dot: required("MEAN_MOTION_DOT")?,
        mean_motion_ddot: required("MEAN_MOTION_DDOT")?,
        bstar: required("BSTAR")?,
        inclination: required("INCLINATION")?,
        right_ascension: required("RA_OF_ASC_NODE")?,
        eccentricity: required("ECCENTRICITY")?,
        argument_of_perigee: required("ARG_OF_PERICENTER")?,
        mean_anomaly: required("MEAN_ANOMALY")?,
        mean_motion: required("MEAN_MOTION")?,
        element_set_number: integer("ELEMENT_SET_NO", false, u64::from(u32::MAX))?.unwrap_or(0),
        revolution_number: integer("REV_AT_EPOCH", false, u64::from(u32::MAX))?.unwrap_or(0),
        ephemeris_type: integer("EPHEMERIS_TYPE", false, 9)?.unwrap_or(0) as u8,
        line: start,
    };
    entry.check_ranges().map_err(|(field, message)| fail(field.omm(), message))?;
    Ok(entry)
}

/// The byte spans of the top-level objects of a JSON text (of an array's elements, or the text's one
/// object), found outside strings.
fn object_spans(text: &str) -> Vec<(usize, usize)> {
    let (mut depth, mut in_string, mut escaped) = (0usize, false, false);
    let mut start = 0;
    let mut spans = vec![];
    let top = usize::from(text.trim_start().starts_with('['));
    for (i, c) in text.char_indices() {
        if in_string {
            match c {
                _ if escaped => escaped = false,
                '\\' => escaped = true,
                '"' => in_string = false,
                _ => {}
            }
            continue;
        }
        match c {
            '"' => in_string = true,
            '{' | '[' => {
                if c == '{' && depth == top {
                    start = i;
                }
                depth += 1;
            }
            '}' | ']' => {
                depth = depth.saturating_sub(1);
                if c == '}' && depth == top {
                    spans.push((start, i + 1));
                }
            }
            _ => {}
        }
    }
    spans
}

/// The line numbers of a text's bytes, for byte offsets that mostly grow: each call counts the line breaks
/// from the previous offset only, so the records of a file are numbered in one pass (counting from the start
/// for every record was quadratic: 10,000 records took 9.3 s).
struct LineCounter<'a> {
    text: &'a str,
    byte: usize,
    line: usize,
}

impl<'a> LineCounter<'a> {
    fn new(text: &'a str) -> Self {
        LineCounter { text, byte: 0, line: 1 }
    }

    /// The line (from 1) of byte `byte`.
    fn at(&mut self, byte: usize) -> usize {
        let byte = byte.min(self.text.len());
        if byte < self.byte {
            *self = LineCounter::new(self.text);
        }
        self.line += newlines(&self.text.as_bytes()[self.byte..byte]);
        self.byte = byte;
        self.line
    }
}

fn newlines(bytes: &[u8]) -> usize {
    bytes.iter().filter(|&&b| b == b'\n').count()
}

/// Parses OMM records in JSON: an array of objects with CelesTrak's keywords (numbers as JSON numbers or
/// strings), or one object.
pub fn parse_omm_json(file: &str, text: &str) -> Result<Vec<CatalogueEntry>, CatalogueError> {
    let value: serde_json::Value =
        serde_json::from_str(text).map_err(|e| err(file, e.line(), "JSON", e.to_string()))?;
    let objects: Vec<&serde_json::Value> = match &value {
        serde_json::Value::Array(items) => items.iter().collect(),
        object @ serde_json::Value::Object(_) => vec![object],
        _ => return Err(err(file, 1, "JSON", "expected an array of OMM objects or one object")),
    };
    let spans = object_spans(text);
    let mut lines = LineCounter::new(text);
    let mut entries = Vec::with_capacity(objects.len());
    for (k, object) in objects.into_iter().enumerate() {
        let (from, to) = spans.get(k).copied().unwrap_or((0, 0));
        let start = lines.at(from);
        let Some(map) = object.as_object() else {
            return Err(err(file, start, format!("element {k}"), "expected an OMM object"));
        };
        let get = |key: &str| -> Option<Raw<'_>> {
            map.get(key).map(|v| match v {
                serde_json::Value::String(s) => Raw::Text(s),
                serde_json::Value::Number(n) => Raw::Number(n),
                serde_json::Value::Null => Raw::Other("null"),
                serde_json::Value::Bool(_) => Raw::Other("a boolean"),
                serde_json::Value::Array(_) => Raw::Other("an array"),
                serde_json::Value::Object(_) => Raw::Other("an object"),
            })
        };
        let span = &text[from..to];
        let line_of =
            |key: &str| span.find(&format!("\"{key}\"")).map_or(start, |at| start + newlines(&span.as_bytes()[..at]));
        entries.push(omm_entry(file, start, &get, &line_of)?);
    }
    Ok(entries)
}

/// `entries` as OMM JSON in CelesTrak's keywords, one record a line; numbers written exactly (shortest
/// round-trip form) and the epoch to the microsecond, so that [`parse_omm_json`] reads back the same
/// elements when the epochs are whole microseconds.
pub fn to_omm_json(entries: &[CatalogueEntry]) -> String {
    let mut text = String::with_capacity(entries.len() * 560 + 4);
    text.push('[');
    for (k, e) in entries.iter().enumerate() {
        let record = serde_json::json!({
            "OBJECT_NAME": e.name.clone().unwrap_or_default(),
            "OBJECT_ID": e.international_designator.clone().unwrap_or_default(),
            "EPOCH": e.epoch.format("%Y-%m-%dT%H:%M:%S%.6f").to_string(),
            "MEAN_MOTION": e.mean_motion,
            "ECCENTRICITY": e.eccentricity,
            "INCLINATION": e.inclination,
            "RA_OF_ASC_NODE": e.right_ascension,
            "ARG_OF_PERICENTER": e.argument_of_perigee,
            "MEAN_ANOMALY": e.mean_anomaly,
            "EPHEMERIS_TYPE": e.ephemeris_type,
            "CLASSIFICATION_TYPE": e.classification.to_string(),
            "NORAD_CAT_ID": e.norad_id,
            "ELEMENT_SET_NO": e.element_set_number,
            "REV_AT_EPOCH": e.revolution_number,
            "BSTAR": e.bstar,
            "MEAN_MOTION_DOT": e.mean_motion_dot,
            "MEAN_MOTION_DDOT": e.mean_motion_ddot,
        });
        text.push_str(if k == 0 { "\n" } else { ",\n" });
        text.push_str(&record.to_string());
    }
    text.push_str("\n]\n");
    text
}

/// The fields of one CSV line: separated by commas, a field in double quotes may hold commas and `""`.
fn csv_fields(line: &str) -> Option<Vec<String>> {
    let mut fields = vec![];
    let mut field = String::new();
    let mut chars = line.chars().peekable();
    let mut quoted = false;
    while let Some(c) = chars.next() {
        match c {
            '"' if quoted && chars.peek() == Some(&'"') => {
                chars.next();
                field.push('"');
            }
            '"' if quoted => quoted = false,
            '"' if field.is_empty() => quoted = true,
            ',' if !quoted => fields.push(std::mem::take(&mut field)),
            _ => field.push(c),
        }
    }
    if quoted {
        return None;
    }
    fields.push(field);
    Some(fields)
}

/// Parses OMM records in CSV: a header line of keywords, then one record a line (blank lines skipped).
pub fn parse_omm_csv(file: &str, text: &str) -> Result<Vec<CatalogueEntry>, CatalogueError> {
    let mut lines = text.lines().enumerate().filter(|(_, l)| !l.trim().is_empty());
    let Some((h, header)) = lines.next() else { return Ok(vec![]) };
    let header: Vec<String> = csv_fields(header.trim_end())
        .ok_or_else(|| err(file, h + 1, "header", "unterminated quote"))?
        .into_iter()
        .map(|s| s.trim().to_string())
        .collect();
    let mut seen = std::collections::HashSet::with_capacity(header.len());
    if let Some(key) = header.iter().find(|k| !seen.insert(k.as_str())) {
        return Err(err(file, h + 1, key.as_str(), "appears twice in the header"));
    }
    let mut entries = vec![];
    for (i, line) in lines {
        let number = i + 1;
        let fields = csv_fields(line.trim_end()).ok_or_else(|| err(file, number, "record", "unterminated quote"))?;
        if fields.len() != header.len() {
            return Err(err(
                file,
                number,
                "record",
                format!("{} fields, the header has {}", fields.len(), header.len()),
            ));
        }
        let get = |key: &str| header.iter().position(|k| k == key).map(|p| Raw::Text(fields[p].as_str()));
        entries.push(omm_entry(file, number, &get, &|_| number)?);
    }
    Ok(entries)
}
