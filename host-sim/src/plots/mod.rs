//! Result figures for the tracker simulator: truth-vs-estimate snapshots, hypothesis-weight bar charts, line
//! charts (linear or log10 axes) and per-sensor sky plots (azimuth/elevation or right ascension/declination). Every
//! function writes both `<stem>.png` and `<stem>.svg`.
//!
//! Text is rendered with a vendored DejaVu Sans font (registered with plotters' `ab_glyph` backend), so no system
//! font libraries are needed. In snapshots, bar and line charts, points that cannot be drawn are skipped: non-finite
//! values, magnitudes above 1e300, and on log axes values outside [1e-150, 1e150] (including non-positive ones). Sky
//! plots instead refuse a non-finite angle with an error naming the series. Empty or degenerate data still yields a
//! valid, labelled figure.
//!
//! A file per figure type: `snapshots`, `weights` (hypothesis-weight bars), `line_chart`, `sky` (az/el and
//! RA/Dec), `ground_tracks`, `scatter` and `histogram`; what they share is in `figure` (font, files, axes) and `legend` (markers and
//! legends). The public names are re-exported here.

mod clip;
mod figure;
mod ground_tracks;
mod histogram;
mod legend;
mod line_chart;
mod scatter;
mod sky;
mod snapshots;
mod weights;

#[cfg(test)]
mod tests;

pub use figure::{PlotError, Scale};
pub use ground_tracks::ground_tracks;
pub use histogram::histogram;
pub use line_chart::{Series, plot_series};
pub use scatter::scatter;
pub use sky::{SkySeries, sky_plot_az_el, sky_plot_ra_dec};
pub use snapshots::{FovLines, SnapshotPanel, plot_snapshots};
pub use weights::plot_hypothesis_weights;
