//! Which element sets a catalogue run keeps: an orbit that enters the Earth (by its mean elements, or at a
//! time of the run), SGP4 failing at a time of the run, or an element set given twice (same catalogue number
//! and epoch) is dropped with a warning and listed in `catalogue_dropped`; elements far from the run's
//! times (SGP4 extrapolated over more than [`MAX_EXTRAPOLATION_DAYS`]) are kept with a warning.

use super::entry::CatalogueEntry;
use super::propagation::Satellite;
use crate::scenario::Readable;
use serde::{Deserialize, Serialize};
use sgp4::chrono::NaiveDateTime;
use std::collections::HashMap;

/// The Earth's equatorial radius (km, WGS-84; WGS-72's is 6378.135).
pub const EARTH_RADIUS_KM: f64 = 6378.137;

/// The least perigee height kept (km above [`EARTH_RADIUS_KM`]): below 100 km an orbit decays within a
/// revolution or two.
pub const MIN_PERIGEE_HEIGHT_KM: f64 = 100.0;

/// Elements farther than this from the run's start or end (days) give a warning: SGP4's errors grow with
/// the time from the epoch (a few km a day for LEO).
pub const MAX_EXTRAPOLATION_DAYS: f64 = 30.0;

/// WGS-72's gravitational parameter (km³/s²), SGP4's.
const MU_WGS72: f64 = 398_600.8;

/// The most warning lines of each kind printed; the rest are counted in one line.
pub const MAX_WARNING_LINES: usize = 100;

/// An element set left out of the run, and why.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DroppedElementSet {
    /// Catalogue number.
    pub norad_id: u64,
    /// Name, if the file gives one.
    pub name: Option<String>,
    /// The line of the catalogue file where its element set starts.
    pub line: usize,
    /// Why it was dropped.
    pub reason: String,
}

/// `catalogue_dropped` of `generate catalogue --json` and of `run-catalogue`'s `summary.json`.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CatalogueDropped {
    /// Element sets dropped.
    pub count: usize,
    /// Each, in file order.
    pub objects: Vec<DroppedElementSet>,
    /// Element sets kept with a warning: elements more than [`MAX_EXTRAPOLATION_DAYS`] from the run.
    #[serde(default)]
    pub extrapolated: usize,
}

/// The element sets a run keeps (as SGP4 propagators, in file order), those it drops, and the warning lines
/// (drops and long extrapolations, each naming the file, line and object).
#[derive(Debug, Clone)]
pub struct Screened {
    /// The propagators of the element sets kept.
    pub satellites: Vec<Satellite>,
    /// The element sets dropped.
    pub dropped: CatalogueDropped,
    /// One line per drop and per long extrapolation.
    pub warnings: Vec<String>,
}

/// The perigee radius (km) of the mean elements: a (1 − e), a from the Kozai mean motion and WGS-72's μ.
pub fn perigee_radius_km(entry: &CatalogueEntry) -> f64 {
    let n = entry.mean_motion * std::f64::consts::TAU / 86_400.0;
    (MU_WGS72 / (n * n)).cbrt() * (1.0 - entry.eccentricity)
}

/// Why `entry` cannot be part of a run at `times` (s after `start`): its mean perigee is below
/// [`MIN_PERIGEE_HEIGHT_KM`], SGP4 refuses it or fails at one of the times, or its radius there is below
/// the same height. `None` when it can.
pub fn orbit_problem(entry: &CatalogueEntry, start: NaiveDateTime, times: &[f64]) -> Option<String> {
    checked(entry.clone(), start, times).err()
}

/// The propagator of `entry` when it can be part of a run at `times`, else why not ([`orbit_problem`]).
fn checked(entry: CatalogueEntry, start: NaiveDateTime, times: &[f64]) -> Result<Satellite, String> {
    let floor = EARTH_RADIUS_KM + MIN_PERIGEE_HEIGHT_KM;
    let perigee = perigee_radius_km(&entry);
    if !(perigee >= floor) {
        return Err(format!(
            "the orbit enters the Earth: perigee radius {} km (mean elements) is below {floor} km \
             ({EARTH_RADIUS_KM} + {MIN_PERIGEE_HEIGHT_KM})",
            Readable((perigee * 10.0).round() / 10.0)
        ));
    }
    let satellite = Satellite::new(entry).map_err(|e| e.to_string())?;
    for &t in times {
        state_in_orbit(&satellite, start, t)?;
    }
    Ok(satellite)
}

/// The tracker-frame state (km, km/s) of `satellite` at `t` s after `start`, or why it decays there (SGP4
/// fails, or the radius is below [`EARTH_RADIUS_KM`] + [`MIN_PERIGEE_HEIGHT_KM`]).
///
/// # Errors
/// The reason, as `catalogue_dropped` gives it.
pub fn state_in_orbit(satellite: &Satellite, start: NaiveDateTime, t: f64) -> Result<[f64; 6], String> {
    let floor = EARTH_RADIUS_KM + MIN_PERIGEE_HEIGHT_KM;
    let (r, v) = satellite
        .tracker_state(start, t)
        .map_err(|e| format!("decays during the run: at start + {} s: {e}", Readable(t)))?;
    let radius = (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
    if !(radius >= floor) {
        return Err(format!(
            "decays during the run: radius {} km at start + {} s is below {floor} km",
            Readable((radius * 10.0).round() / 10.0),
            Readable(t)
        ));
    }
    Ok([r[0], r[1], r[2], v[0], v[1], v[2]])
}

/// The days from `entry`'s epoch to the farther of `start` and `start + last` s.
fn extrapolation_days(entry: &CatalogueEntry, start: NaiveDateTime, last: f64) -> f64 {
    let to_start = (start - entry.epoch).num_milliseconds() as f64 / 86_400e3;
    to_start.abs().max((to_start + last / 86_400.0).abs())
}

/// "file:line: object ID (NAME)".
fn object(file: &str, entry: &CatalogueEntry) -> String {
    let name = entry.name.as_deref().map_or_else(String::new, |n| format!(" ({})", crate::scenario::excerpt(n, 40)));
    format!("{file}:{}: object {}{name}", entry.line, entry.norad_id)
}

/// Screens `entries` of `file` for a run starting at `start` whose truth is wanted at `times` (s after
/// `start`, the prior's time included).
pub fn screen_for_run(file: &str, entries: Vec<CatalogueEntry>, start: NaiveDateTime, times: &[f64]) -> Screened {
    let mut screened = Screened { satellites: vec![], dropped: CatalogueDropped::default(), warnings: vec![] };
    let mut first_of: HashMap<(u64, NaiveDateTime), usize> = HashMap::new();
    let (first, last) = times.iter().fold((0.0f64, 0.0f64), |(lo, hi), &t| (lo.min(t), hi.max(t)));
    for entry in entries {
        let key = (entry.norad_id, entry.epoch);
        let days = extrapolation_days(&entry, start, last).max(extrapolation_days(&entry, start, first));
        let label = object(file, &entry);
        let (id, name, line) = (entry.norad_id, entry.name.clone(), entry.line);
        let kept = match first_of.get(&key) {
            Some(first) => Err(format!("the element set of line {first} again (same catalogue number and epoch)")),
            None => checked(entry, start, times),
        };
        first_of.entry(key).or_insert(line);
        match kept {
            Ok(satellite) => {
                if days > MAX_EXTRAPOLATION_DAYS {
                    screened.dropped.extrapolated += 1;
                    let days = Readable((days * 10.0).round() / 10.0);
                    screened.warnings.push(format!(
                        "{label}: elements {days} days from the run: SGP4 extrapolated beyond \
                         {MAX_EXTRAPOLATION_DAYS} days"
                    ));
                }
                screened.satellites.push(satellite);
            }
            Err(reason) => {
                screened.warnings.push(format!("{label}: dropped: {reason}"));
                screened.dropped.objects.push(DroppedElementSet { norad_id: id, name, line, reason });
            }
        }
    }
    screened.dropped.count = screened.dropped.objects.len();
    screened
}

/// [`screen_for_run`] at the scan times `scans` (s after `start`) and the prior's (1 s before the first
/// scan or the start, as [`crate::scenario::from_simulation`] places it), the warnings printed
/// ([`print_warnings`]).
///
/// # Errors
/// [`crate::Error::Input`] when every element set is dropped.
pub fn screen_scans(
    file: &str,
    entries: Vec<CatalogueEntry>,
    start: NaiveDateTime,
    scans: &[f64],
) -> Result<Screened, crate::Error> {
    let prior_time = scans.first().map_or(0.0, |&t| t.min(0.0)) - 1.0;
    let times: Vec<f64> = std::iter::once(prior_time).chain(scans.iter().copied()).collect();
    let screened = screen_for_run(file, entries, start, &times);
    print_warnings(&screened.warnings);
    if screened.satellites.is_empty() {
        return Err(crate::Error::input(format!("{file}: every element set is dropped (see the warnings)")));
    }
    Ok(screened)
}

/// Prints `warnings` on stderr, one `warning:` line each, at most [`MAX_WARNING_LINES`] and then their count.
pub fn print_warnings(warnings: &[String]) {
    for line in warnings.iter().take(MAX_WARNING_LINES) {
        eprintln!("warning: {}", crate::scenario::one_line(line));
    }
    if warnings.len() > MAX_WARNING_LINES {
        eprintln!("warning: {} more catalogue warnings not shown", warnings.len() - MAX_WARNING_LINES);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::catalogue::parse;

    const L1: &str = "1 00005U 58002B   00179.78495062  .00000023  00000-0  28098-4 0  4753";
    const L2: &str = "2 00005  34.2682 348.7242 1859667 331.7664  19.3264 10.82419157413667";

    fn entry() -> CatalogueEntry {
        parse("t", &format!("{L1}\n{L2}\n")).unwrap().remove(0)
    }

    fn at_epoch(entry: &CatalogueEntry) -> NaiveDateTime {
        entry.epoch
    }

    #[test]
    fn orbits_inside_the_earth_are_dropped() {
        // Issue 33 item 4: mean motions of 17 and 99 rev/day were accepted (truth radius down to 1,947 km).
        let good = entry();
        let start = at_epoch(&good);
        let times = [-1.0, 0.0, 600.0, 3600.0];
        assert_eq!(orbit_problem(&good, start, &times), None);
        for (mean_motion, eccentricity) in [(17.0, 0.0), (99.0, 0.0), (10.8, 0.5)] {
            let bad = CatalogueEntry { mean_motion, eccentricity, ..good.clone() };
            let why = orbit_problem(&bad, start, &times).expect("dropped");
            assert!(why.contains("enters the Earth"), "{why}");
        }
        // Vanguard 1: perigee height about 650 km.
        assert!((perigee_radius_km(&good) - 7_027.0).abs() < 1.0, "{}", perigee_radius_km(&good));
    }

    #[test]
    fn orbits_that_decay_during_the_run_are_dropped() {
        // A low orbit (perigee height about 280 km) with a large drag term: kept for an hour, dropped over
        // ten days, when SGP4 takes it below 100 km or fails.
        let low = CatalogueEntry { mean_motion: 16.0, eccentricity: 0.0001, bstar: 0.01, ..entry() };
        let start = at_epoch(&low);
        assert_eq!(orbit_problem(&low, start, &[-1.0, 0.0, 3600.0]), None);
        let days: Vec<f64> = (0..=240).map(|h| 3600.0 * f64::from(h)).collect();
        let why = orbit_problem(&low, start, &days).expect("dropped");
        assert!(why.starts_with("decays during the run"), "{why}");
    }

    #[test]
    fn duplicates_are_dropped_and_old_elements_warned() {
        let good = entry();
        let renamed = CatalogueEntry { line: 3, ..good.clone() };
        let later = CatalogueEntry { line: 5, epoch: good.epoch + sgp4::chrono::Duration::days(1), ..good.clone() };
        let start = good.epoch + sgp4::chrono::Duration::days(40);
        let screened = screen_for_run("t", vec![good, renamed, later], start, &[-1.0, 0.0, 60.0]);
        assert_eq!(screened.satellites.len(), 2);
        assert_eq!(screened.dropped.count, 1);
        assert_eq!(screened.dropped.objects[0].line, 3);
        assert!(screened.dropped.objects[0].reason.contains("line 1 again"), "{:?}", screened.dropped);
        let old: Vec<&String> = screened.warnings.iter().filter(|w| w.contains("days from the run")).collect();
        assert_eq!(old.len(), 2, "{:?}", screened.warnings);
        assert_eq!(screened.dropped.extrapolated, 2);
        assert!(old[0].starts_with("t:1: object 5: elements 40 days"), "{}", old[0]);
        assert!(old[1].starts_with("t:5: object 5: elements 39 days"), "{}", old[1]);
    }
}
