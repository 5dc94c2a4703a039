//! Catalogue input: two- and three-line element sets (TLE, with Alpha-5 catalogue numbers) and CCSDS OMM
//! mean elements (CelesTrak's JSON and CSV) read into one [`CatalogueEntry`], then into the `sgp4` crate's
//! elements and propagated in AFSPC-compatibility mode (WGS-72), the mode of the Vallado et al. (2006)
//! verification cases (`sgp4_check`).
//!
//! Every parser is ours: each field is checked (columns, checksums, ranges) and a bad file is a
//! [`CatalogueError`] naming the file, the line and the keyword (TLE: the line and columns of the field),
//! printed by the CLI as one line with exit code 2. Files are read through [`crate::scenario::MAX_FILE_BYTES`].
//!
//! Frame (docs/maths.md §6.8, "Catalogue objects"): SGP4's TEME is taken as the tracker's inertial frame;
//! [`Satellite::tracker_state`] converts the tracker time t (s since the scenario epoch) into minutes since
//! the element set's epoch and returns SGP4's TEME position and velocity (km, km/s) unchanged.
//!
//! The entry and its errors are in `entry`, reading a file in `files`, the formats in `tle` and `omm`, SGP4 in
//! `propagation`, which element sets a run keeps in `screen`; [`sgp4_check`] runs the published verification cases. The public names are re-exported here.

mod entry;
mod files;
mod omm;
mod propagation;
pub mod screen;
pub mod sgp4_check;
#[cfg(test)]
mod tests;
mod tle;

pub use entry::{CatalogueEntry, CatalogueError, MAX_NAME_CHARS};
pub use files::{Format, detect, load, parse};
pub use omm::{parse_omm_csv, parse_omm_epoch, parse_omm_json, to_omm_json};
pub use propagation::{ObjectReport, PropagationError, Satellite, State, report};
pub use screen::{CatalogueDropped, DroppedElementSet, Screened, orbit_problem, screen_for_run};
pub use tle::{parse_catalogue_number, parse_tle, tle_checksum};
