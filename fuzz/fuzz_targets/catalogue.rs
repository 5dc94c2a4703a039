//! Fuzz target `catalogue`: arbitrary bytes into host-sim's TLE and OMM parsers (issue 15).
//!
//! Checked on every input, for each of the three parsers (`parse_tle`, `parse_omm_json`, `parse_omm_csv`)
//! and for `parse`, which picks one:
//! - nothing panics;
//! - a rejected file gets a one-line message;
//! - every accepted entry is within the documented ranges (0 ≤ e < 1, angles in degrees, mean motion > 0);
//! - SGP4 from an accepted entry (initialisation and a propagation at the epoch and a day later) returns a
//!   state or an SGP4 error, never a panic, and a state is finite.
#![no_main]

use host_sim::io::catalogue::{self, CatalogueEntry, CatalogueError, Satellite};
use libfuzzer_sys::fuzz_target;

fn check(result: Result<Vec<CatalogueEntry>, CatalogueError>) {
    let entries = match result {
        Ok(entries) => entries,
        Err(error) => {
            let message = error.to_string();
            assert!(!message.contains(['\n', '\r']), "multi-line error message: {message}");
            // Quoted input is cut to an excerpt (issue 33): a message never echoes a long value whole.
            assert!(message.len() <= 32 << 10, "a message of {} bytes", message.len());
            return;
        }
    };
    for entry in entries.into_iter().take(8) {
        assert!((0.0..1.0).contains(&entry.eccentricity), "{entry:?}");
        assert!((0.0..=180.0).contains(&entry.inclination), "{entry:?}");
        for angle in [entry.right_ascension, entry.argument_of_perigee, entry.mean_anomaly] {
            assert!((0.0..=360.0).contains(&angle), "{entry:?}");
        }
        assert!(entry.mean_motion > 0.0 && entry.mean_motion.is_finite(), "{entry:?}");
        let Ok(satellite) = Satellite::new(entry) else { continue };
        for minutes in [0.0, 1440.0] {
            if let Ok((r, v)) = satellite.teme(minutes) {
                assert!(r.iter().chain(&v).all(|x| x.is_finite()), "non-finite state {r:?} {v:?}");
            }
        }
    }
}

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    check(catalogue::parse("fuzz", text));
    check(catalogue::parse_tle("fuzz", text));
    check(catalogue::parse_omm_json("fuzz", text));
    check(catalogue::parse_omm_csv("fuzz", text));
});
