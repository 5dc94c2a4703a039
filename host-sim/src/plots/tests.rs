//! Tests of the figures.

use super::clip::{clip_polyline, clip_segment};
use super::figure::{
    Bounds, Scale, ensure_font_registered, format_scientific, format_tick, linear_axis, log_axis, path_with_extension,
};
use super::ground_tracks::{GroundTrackFigure, ground_tracks};
use super::line_chart::{LINE_CHART_SIZE, Series, plot_series};
use super::sky::{
    PolarSkyFigure, RaDecView, SKY_POLAR_SIDE, SkySeries, clip_to_horizon, format_ra_tick, polar_projection,
    sky_plot_az_el, sky_plot_ra_dec,
};
use super::snapshots::{FovLines, SNAPSHOT_PANEL_SIDE, SnapshotPanel, equal_aspect_ranges, plot_snapshots};
use super::weights::{WEIGHT_PANEL_SIZE, format_rank_tick, plot_hypothesis_weights, ranked_bars};
use crate::sim::vector::wrap_angle;
use std::path::{Path, PathBuf};

const PNG_SIGNATURE: [u8; 8] = [0x89, b'P', b'N', b'G', b'\r', b'\n', 0x1a, b'\n'];

/// A fresh directory under the system temp dir, removed when dropped.
struct TestDir(PathBuf);

impl TestDir {
    fn new(test_name: &str) -> Self {
        let path = std::env::temp_dir().join(format!("plots-test-{}-{test_name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&path);
        std::fs::create_dir_all(&path).expect("create test dir");
        Self(path)
    }

    fn stem(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }
}

impl Drop for TestDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Checks both files exist and look like a PNG and an SVG; returns the PNG's (width, height).
fn assert_png_and_svg(stem: &Path) -> (u32, u32) {
    let png = std::fs::read(path_with_extension(stem, "png")).expect("png written");
    assert!(png.len() > 100, "png too small");
    assert_eq!(png[..8], PNG_SIGNATURE);
    let svg = std::fs::read_to_string(path_with_extension(stem, "svg")).expect("svg written");
    assert!(svg.contains("<svg"));
    let be_u32 = |at: usize| u32::from_be_bytes(png[at..at + 4].try_into().expect("4 bytes"));
    (be_u32(16), be_u32(20))
}

fn example_panel(title: &str) -> SnapshotPanel {
    let truth: Vec<[f64; 2]> =
        (0..5).map(|i| f64::from(i) * 0.6).map(|a| [42_164.0 * a.cos(), 42_164.0 * a.sin()]).collect();
    SnapshotPanel {
        title: title.to_string(),
        estimates_within_bound: truth.iter().take(3).map(|p| [p[0] + 300.0, p[1] - 200.0]).collect(),
        estimates_outside_bound: truth.iter().skip(3).map(|p| [p[0] + 5_000.0, p[1]]).collect(),
        truth,
        fov: Some(FovLines { origin: [6_378.137, 0.0], look_direction: 0.8, half_angle: 0.25, max_range: 60_000.0 }),
        unit: "km".to_string(),
        central_body_radius: Some(6_378.137),
    }
}

fn series(name: &str, points: Vec<(f64, f64)>, markers: bool) -> Series {
    Series { name: name.to_string(), points, markers }
}

#[test]
fn snapshots_normal_data() {
    let dir = TestDir::new("snapshots-normal");
    let stem = dir.stem("snapshots");
    plot_snapshots(&stem, &[example_panel("k = 1"), example_panel("k = 2")]).unwrap();
    let (width, height) = assert_png_and_svg(&stem);
    assert_eq!(width, 2 * SNAPSHOT_PANEL_SIDE);
    assert!(height > SNAPSHOT_PANEL_SIDE, "legend strip below the panels");
}

#[test]
fn snapshots_wrap_after_four_panels() {
    let dir = TestDir::new("snapshots-wrap");
    let stem = dir.stem("wrapped");
    let panels: Vec<_> = (0..5).map(|k| example_panel(&format!("k = {k}"))).collect();
    plot_snapshots(&stem, &panels).unwrap();
    let (width, height) = assert_png_and_svg(&stem);
    assert_eq!(width, 4 * SNAPSHOT_PANEL_SIDE);
    assert!(height > 2 * SNAPSHOT_PANEL_SIDE);
}

#[test]
fn snapshots_empty_data() {
    let dir = TestDir::new("snapshots-empty");
    plot_snapshots(&dir.stem("no_panels"), &[]).unwrap();
    assert_png_and_svg(&dir.stem("no_panels"));
    plot_snapshots(&dir.stem("empty_panel"), &[SnapshotPanel::default()]).unwrap();
    assert_png_and_svg(&dir.stem("empty_panel"));
    let fov_only = SnapshotPanel { fov: example_panel("").fov, ..SnapshotPanel::default() };
    plot_snapshots(&dir.stem("fov_only"), &[fov_only]).unwrap();
    assert_png_and_svg(&dir.stem("fov_only"));
}

#[test]
fn snapshots_single_point() {
    let dir = TestDir::new("snapshots-single");
    let at_origin = SnapshotPanel { truth: vec![[0.0, 0.0]], ..SnapshotPanel::default() };
    let far_away = SnapshotPanel { estimates_outside_bound: vec![[4.2e4, -1.0e3]], ..SnapshotPanel::default() };
    plot_snapshots(&dir.stem("single"), &[at_origin, far_away]).unwrap();
    assert_png_and_svg(&dir.stem("single"));
}

#[test]
fn snapshots_skip_nan_and_inf() {
    let dir = TestDir::new("snapshots-nan");
    let mut panel = example_panel("with NaN");
    panel.truth.push([f64::NAN, 1.0]);
    panel.estimates_within_bound.push([f64::INFINITY, 0.0]);
    panel.estimates_outside_bound.push([1.0, f64::NEG_INFINITY]);
    let broken_fov = SnapshotPanel {
        truth: vec![[f64::NAN, f64::NAN]],
        fov: Some(FovLines { origin: [0.0, 0.0], look_direction: f64::NAN, half_angle: 0.1, max_range: 1.0 }),
        central_body_radius: Some(f64::NAN),
        ..SnapshotPanel::default()
    };
    plot_snapshots(&dir.stem("nan"), &[panel, broken_fov]).unwrap();
    assert_png_and_svg(&dir.stem("nan"));
}

#[test]
fn weights_normal_data() {
    let dir = TestDir::new("weights-normal");
    let panels = vec![
        ("k = 1".to_string(), vec![0.7, 0.2, 0.1]),
        ("k = 2".to_string(), (1..=40).map(|i| 0.5_f64.powi(i)).collect()),
    ];
    plot_hypothesis_weights(&dir.stem("weights"), &panels).unwrap();
    let (width, _) = assert_png_and_svg(&dir.stem("weights"));
    assert_eq!(width, 2 * WEIGHT_PANEL_SIZE.0);
}

#[test]
fn weights_are_ranked_in_descending_order() {
    let bars = ranked_bars(&[0.1, f64::NAN, 0.6, 0.3, f64::INFINITY]);
    assert_eq!(bars, vec![(1.0, 0.6), (2.0, 0.3), (3.0, 0.1)]);
    assert!(ranked_bars(&[]).is_empty());
}

#[test]
fn weights_empty_single_and_nan() {
    let dir = TestDir::new("weights-edge");
    plot_hypothesis_weights(&dir.stem("no_panels"), &[]).unwrap();
    assert_png_and_svg(&dir.stem("no_panels"));
    plot_hypothesis_weights(&dir.stem("no_weights"), &[("empty".to_string(), vec![])]).unwrap();
    assert_png_and_svg(&dir.stem("no_weights"));
    plot_hypothesis_weights(&dir.stem("single"), &[("one".to_string(), vec![1.0])]).unwrap();
    assert_png_and_svg(&dir.stem("single"));
    let odd = vec![f64::NAN, 0.5, f64::INFINITY, 1.7, -0.2];
    plot_hypothesis_weights(&dir.stem("nan"), &[("odd".to_string(), odd), ("all NaN".to_string(), vec![f64::NAN])])
        .unwrap();
    assert_png_and_svg(&dir.stem("nan"));
}

#[test]
fn series_normal_data() {
    let dir = TestDir::new("series-normal");
    let truth = series("Truth", (0..50).map(|k| (f64::from(k), if k < 20 { 3.0 } else { 5.0 })).collect(), false);
    let estimate = series("Estimate", (0..50).map(|k| (f64::from(k), 3.0 + f64::from(k) / 25.0)).collect(), true);
    plot_series(&dir.stem("series"), "Objects", "Time [s]", "Count", Scale::Linear, Scale::Linear, &[truth, estimate])
        .unwrap();
    assert_eq!(assert_png_and_svg(&dir.stem("series")), LINE_CHART_SIZE);
}

#[test]
fn series_empty_data() {
    let dir = TestDir::new("series-empty");
    for (x_scale, y_scale) in [(Scale::Linear, Scale::Linear), (Scale::Log10, Scale::Log10)] {
        let stem = dir.stem(&format!("empty_{x_scale:?}_{y_scale:?}"));
        plot_series(&stem, "No series", "x", "y", x_scale, y_scale, &[]).unwrap();
        assert_png_and_svg(&stem);
        let stem = dir.stem(&format!("empty_points_{x_scale:?}_{y_scale:?}"));
        plot_series(&stem, "Empty series", "x", "y", x_scale, y_scale, &[series("nothing", vec![], true)]).unwrap();
        assert_png_and_svg(&stem);
    }
}

#[test]
fn series_single_point() {
    let dir = TestDir::new("series-single");
    for (x_scale, y_scale) in [(Scale::Linear, Scale::Linear), (Scale::Log10, Scale::Log10)] {
        let stem = dir.stem(&format!("single_{x_scale:?}"));
        plot_series(&stem, "One point", "x", "y", x_scale, y_scale, &[series("one", vec![(5.0, 5.0)], false)]).unwrap();
        assert_png_and_svg(&stem);
    }
    let stem = dir.stem("constant");
    let flat = series("flat", vec![(1.0, 0.0), (2.0, 0.0), (3.0, 0.0)], false);
    plot_series(&stem, "Flat zero", "x", "y", Scale::Linear, Scale::Linear, &[flat]).unwrap();
    assert_png_and_svg(&stem);
}

#[test]
fn series_skip_nan_inf_and_non_positive_on_log_axes() {
    let dir = TestDir::new("series-nan");
    let points = vec![(0.0, 1.0), (1.0, f64::NAN), (2.0, 3.0), (f64::INFINITY, 4.0), (4.0, -5.0), (5.0, 6.0)];
    let noisy = series("noisy", points, true);
    let all_nan = series("all NaN", vec![(f64::NAN, f64::NAN); 3], false);
    for (x_scale, y_scale) in [(Scale::Linear, Scale::Linear), (Scale::Log10, Scale::Log10)] {
        let stem = dir.stem(&format!("nan_{x_scale:?}"));
        plot_series(&stem, "NaN", "x", "y", x_scale, y_scale, &[noisy.clone(), all_nan.clone()]).unwrap();
        assert_png_and_svg(&stem);
    }
    let only_non_positive = series("negative", vec![(-1.0, -1.0), (0.0, 0.0)], false);
    let stem = dir.stem("non_positive_log");
    plot_series(&stem, "Nothing positive", "x", "y", Scale::Log10, Scale::Log10, &[only_non_positive]).unwrap();
    assert_png_and_svg(&stem);
}

#[test]
fn series_log_scales_with_wide_range() {
    let dir = TestDir::new("series-log");
    let children: Vec<f64> = (1..=33).map(|e| 10_f64.powi(e)).collect();
    let timing = series("time", children.iter().map(|&n| (n, 1e-6 * n.powf(0.05))).collect(), true);
    let linear = series("linear", children.iter().map(|&n| (n, 1e-9 * n)).collect(), false);
    let stem = dir.stem("loglog");
    plot_series(&stem, "Timing", "Possible children", "Time [s]", Scale::Log10, Scale::Log10, &[timing, linear])
        .unwrap();
    assert_png_and_svg(&stem);
    let stem = dir.stem("semilog");
    let decay = series("decay", (0..20).map(|k| (f64::from(k), 10_f64.powi(-k))).collect(), false);
    plot_series(&stem, "Semi-log", "k", "value", Scale::Linear, Scale::Log10, &[decay]).unwrap();
    assert_png_and_svg(&stem);
}

#[test]
fn series_extreme_magnitudes_do_not_hang_or_panic() {
    let dir = TestDir::new("series-extreme");
    let extreme = series("extreme", vec![(-1e300, 1e-300), (1e300, 1e300), (f64::MAX, f64::MIN_POSITIVE)], false);
    let near = series("near", vec![(1e9, 1.0), (1e9 + 1e-7, 1.0 + 1e-12)], false);
    let log_limits = series("log limits", vec![(1e-150, 1e150), (1e150, 1e-150), (1e-300, 1e300)], true);
    for (x_scale, y_scale) in
        [(Scale::Linear, Scale::Linear), (Scale::Linear, Scale::Log10), (Scale::Log10, Scale::Log10)]
    {
        let stem = dir.stem(&format!("extreme_{x_scale:?}_{y_scale:?}"));
        plot_series(&stem, "Extreme", "x", "y", x_scale, y_scale, &[extreme.clone(), near.clone(), log_limits.clone()])
            .unwrap();
        assert_png_and_svg(&stem);
    }
}

#[test]
fn unwritable_destination_is_an_error() {
    let dir = TestDir::new("unwritable");
    let blocker = dir.stem("blocker");
    std::fs::write(&blocker, b"a file, not a directory").unwrap();
    let error = plot_series(&blocker.join("chart"), "t", "x", "y", Scale::Linear, Scale::Linear, &[]).unwrap_err();
    assert!(error.0.contains("blocker"), "message names the path: {error}");
    assert!(plot_hypothesis_weights(Path::new(""), &[]).is_err());
}

#[test]
fn absurd_panel_counts_are_refused() {
    let dir = TestDir::new("too-many");
    let panels = vec![SnapshotPanel::default(); 400];
    let error = plot_snapshots(&dir.stem("huge"), &panels).unwrap_err();
    assert!(error.0.contains("px"), "{error}");
}

#[test]
fn output_paths_append_extensions() {
    assert_eq!(path_with_extension(Path::new("out/run.v2/gospa"), "png"), PathBuf::from("out/run.v2/gospa.png"));
    assert_eq!(path_with_extension(Path::new("fig.final"), "svg"), PathBuf::from("fig.final.svg"));
}

#[test]
fn tick_labels_are_short() {
    assert_eq!(format_tick(&0.0), "0");
    assert_eq!(format_tick(&0.30000000000000004), "0.3");
    assert_eq!(format_tick(&-20_000.0), "-20000");
    assert_eq!(format_tick(&1.0000000000000001e7), "1e7");
    assert_eq!(format_tick(&2.5e-4), "2.5e-4");
    assert_eq!(format_scientific(&1000.0), "1e3");
    assert_eq!(format_rank_tick(&3.0), "3");
    assert_eq!(format_rank_tick(&2.5), "");
}

#[test]
fn axes_are_widened_and_padded() {
    let single = linear_axis(Some(5.0..5.0));
    assert!(single.start < 5.0 && single.end > 5.0);
    let zero = linear_axis(Some(0.0..0.0));
    assert!(zero.start < 0.0 && zero.end > 0.0);
    let padded = linear_axis(Some(0.0..10.0));
    assert!(padded.start < 0.0 && padded.end > 10.0);
    assert_eq!(linear_axis(None), 0.0..1.0);

    // Log axes always contain a power of ten.
    for data in [2.0..8.0, 3.0..3.0, 1e1..1e33, 0.02..0.03] {
        let axis = log_axis(Some(data.clone()));
        assert!(axis.start < data.start && axis.end > data.end, "{axis:?} frames {data:?}");
        assert!(axis.end.log10().floor() >= axis.start.log10().ceil(), "{axis:?} holds a power of ten");
    }
}

#[test]
fn snapshot_axes_have_equal_units_per_pixel() {
    let bounds = Bounds { x: -10.0..30.0, y: 0.0..5.0 };
    let (x, y) = equal_aspect_ranges(Some(bounds), (500, 400));
    let (x_per_pixel, y_per_pixel) = ((x.end - x.start) / 500.0, (y.end - y.start) / 400.0);
    assert!((x_per_pixel - y_per_pixel).abs() < 1e-12 * x_per_pixel);
    assert!(x.start < -10.0 && x.end > 30.0 && y.start < 0.0 && y.end > 5.0);
    let (x, y) = equal_aspect_ranges(Some(Bounds::around(7.0, 7.0)), (500, 500));
    assert!(x.start < 7.0 && x.end > 7.0 && y.start < 7.0 && y.end > 7.0);
}

#[test]
fn segments_and_polylines_are_clipped_to_the_view() {
    let (x, y) = (0.0..10.0, 0.0..10.0);
    assert_eq!(clip_segment((-5.0, 5.0), (15.0, 5.0), &x, &y), Some(((0.0, 5.0), (10.0, 5.0))));
    assert_eq!(clip_segment((1.0, 1.0), (2.0, 2.0), &x, &y), Some(((1.0, 1.0), (2.0, 2.0))));
    assert_eq!(clip_segment((-5.0, -5.0), (-1.0, 20.0), &x, &y), None);
    let pieces = clip_polyline(&[(-1.0, 5.0), (2.0, 5.0), (4.0, 6.0), (20.0, 6.0), (20.0, 8.0), (5.0, 8.0)], &x, &y);
    assert_eq!(pieces, vec![vec![(0.0, 5.0), (2.0, 5.0), (4.0, 6.0), (10.0, 6.0)], vec![(10.0, 8.0), (5.0, 8.0)]]);
}

/// A LEO pass from NNE over a near-zenith point (88°) to SSW, its azimuth wrapping through ±π, with a gap.
fn leo_pass() -> SkySeries {
    let points = (0..=120)
        .map(|k| {
            let t = f64::from(k) / 120.0;
            let azimuth = wrap_angle(0.1 - t * (std::f64::consts::PI + 0.2));
            let elevation = 88_f64.to_radians() * (std::f64::consts::PI * t).sin();
            (!(40..45).contains(&k)).then_some((azimuth, elevation))
        })
        .collect();
    SkySeries { name: "leo 1".to_string(), points, color: None }
}

/// Every fifth point of `truth`, offset by `offset` radians in both angles.
fn estimates_of(truth: &SkySeries, offset: f64) -> SkySeries {
    let points = truth.points.iter().step_by(5).map(|p| p.map(|(a, b)| (a + offset, b - offset.abs()))).collect();
    SkySeries { name: format!("track of {}", truth.name), points, color: None }
}

/// Five GEO objects within 0.1° around RA = 180°, right ascensions given on both sides of ±180°.
fn geo_cluster() -> Vec<SkySeries> {
    (0..5)
        .map(|object| {
            let points = (0..60)
                .map(|k| {
                    let ra = (179.96 + 0.02 * f64::from(object) + 0.0005 * f64::from(k)).to_radians();
                    let ra = if object % 2 == 0 { wrap_angle(ra) } else { ra };
                    Some((ra, (-5.0 + 0.01 * f64::from(object)).to_radians()))
                })
                .collect();
            SkySeries { name: format!("geo {object}"), points, color: None }
        })
        .collect()
}

#[test]
fn polar_projection_puts_north_up_and_east_right() {
    let close = |a: (f64, f64), b: (f64, f64)| (a.0 - b.0).abs() < 1e-12 && (a.1 - b.1).abs() < 1e-12;
    assert!(close(polar_projection(0.0, 0.0), (0.0, 1.0)), "north on the rim, up");
    assert!(close(polar_projection(std::f64::consts::FRAC_PI_2, 0.0), (1.0, 0.0)), "east right");
    assert!(close(polar_projection(1.0, std::f64::consts::FRAC_PI_2), (0.0, 0.0)), "zenith at the centre");
    assert!(close(polar_projection(std::f64::consts::PI, std::f64::consts::FRAC_PI_6), (0.0, -2.0 / 3.0)));
    // Consecutive samples either side of azimuth ±π stay neighbours in the projection.
    let near_south = std::f64::consts::PI - 0.001;
    let (a, b) = (polar_projection(near_south, 0.2), polar_projection(-near_south, 0.2));
    assert!((a.0 - b.0).hypot(a.1 - b.1) < 0.01);
}

#[test]
fn lines_are_cut_at_the_horizon() {
    let (inside, outside) = ((0.0, 0.5), (0.0, 1.5));
    let (start, end) = clip_to_horizon(inside, outside).unwrap();
    assert_eq!(start, inside);
    assert!((end.1 - 1.0).abs() < 1e-12 && end.0.abs() < 1e-12);
    let (start, _) = clip_to_horizon(outside, inside).unwrap();
    assert!((start.1 - 1.0).abs() < 1e-12);
    // A chord between two points below the horizon is not drawn, even through the sky.
    assert_eq!(clip_to_horizon((0.0, 1.2), (0.0, -1.2)), None);
}

#[test]
fn sky_az_el_leo_pass_through_zenith() {
    let dir = TestDir::new("sky-az-el");
    let truth = vec![leo_pass(), SkySeries { color: Some(3), ..estimates_of(&leo_pass(), 0.3) }];
    let estimates = vec![estimates_of(&truth[0], 0.01), estimates_of(&truth[0], -0.2)];
    let box_outline = [(-0.6, 0.2), (0.6, 0.2), (0.6, 1.2), (-0.6, 1.2)];
    let stem = dir.stem("az_el");
    sky_plot_az_el(&stem, "Radar 1: azimuth/elevation", &truth, &estimates, Some(&box_outline)).unwrap();
    let (width, height) = assert_png_and_svg(&stem);
    assert_eq!(width, SKY_POLAR_SIDE);
    assert!(height > SKY_POLAR_SIDE);

    // The estimates 0.2 rad below the truth put some points under the horizon: counted, not drawn.
    let figure = PolarSkyFigure::new("t", &truth, &estimates, Some(&box_outline)).unwrap();
    assert!(figure.estimates_below_horizon > 0 && figure.footnote().is_some());
    // The gap and the cut at the horizon split the first truth series; no piece leaves the horizon circle.
    assert!(figure.truth[0].1.len() >= 2);
    for &(x, y) in figure.truth.iter().flat_map(|(_, pieces)| pieces.iter().flatten()) {
        assert!(x.hypot(y) <= 1.0 + 1e-12);
    }

    sky_plot_az_el(&dir.stem("empty"), "Nothing", &[], &[], None).unwrap();
    assert_png_and_svg(&dir.stem("empty"));
}

#[test]
fn sky_ra_dec_geo_cluster_near_180_zooms_in() {
    let dir = TestDir::new("sky-ra-dec");
    let truth = geo_cluster();
    let estimates: Vec<_> = truth.iter().map(|series| estimates_of(series, 1e-5)).collect();
    let stare = [(178.0_f64, -6.0_f64), (-178.0, -6.0), (-178.0, -4.0), (178.0, -4.0)]
        .map(|(ra, dec)| (ra.to_radians(), dec.to_radians()));
    let stem = dir.stem("ra_dec");
    sky_plot_ra_dec(&stem, "Telescope: RA/Dec", &truth, &estimates, Some(&stare)).unwrap();
    assert_png_and_svg(&stem);

    // The view spans the cluster (0.11° wide in RA) across ±180°, not the whole circle.
    let view = RaDecView::new(&truth, &estimates, Some(&stare));
    assert!(view.x.start < 179.96 && view.x.end > 180.07 && view.x.end - view.x.start < 0.3, "{:?}", view.x);
    assert!(view.y.start < -5.0 && view.y.end > -4.96 && view.y.end - view.y.start < 0.2, "{:?}", view.y);
    assert!(view.truth.iter().all(|(_, pieces)| pieces.len() == 1), "no line cut at ±180°");
    assert!(view.field_of_view.is_empty(), "the 4° field of view lies outside the zoomed view");

    // With no points the view frames the field of view, which straddles RA = 180° too.
    let empty = RaDecView::new(&[], &[], Some(&stare));
    assert!(empty.x.start < 178.0 && empty.x.end > 182.0 && empty.x.end - empty.x.start < 5.0, "{:?}", empty.x);
    assert_eq!(empty.field_of_view.len(), 1, "the whole closed outline, uncut at ±180°");
    sky_plot_ra_dec(&dir.stem("empty"), "Nothing", &[], &[], None).unwrap();
    assert_png_and_svg(&dir.stem("empty"));
}

#[test]
fn sky_ra_dec_wraps_at_zero_and_cuts_at_the_seam() {
    let near_zero = SkySeries {
        name: "near 0".to_string(),
        points: [359.9_f64, 359.95, 0.0, 0.05].iter().map(|ra| Some((ra.to_radians(), 0.0))).collect(),
        color: None,
    };
    let view = RaDecView::new(&[near_zero], &[], None);
    assert!(view.x.end - view.x.start < 1.0, "{:?}", view.x);
    assert_eq!(view.truth[0].1.len(), 1);
    assert_eq!(format_ra_tick(&360.02), "0.02");
    assert_eq!(format_ra_tick(&-0.5), "359.5");

    // A circumpolar path covers all right ascensions: the line is cut where it crosses the seam.
    let around = SkySeries {
        name: "around the pole".to_string(),
        points: (0..=36).map(|k| Some((f64::from(k * 10).to_radians(), 89_f64.to_radians()))).collect(),
        color: None,
    };
    let view = RaDecView::new(&[around], &[], None);
    assert!(view.truth[0].1.len() >= 2);
    for piece in &view.truth[0].1 {
        assert!(piece.windows(2).all(|pair| (pair[1].0 - pair[0].0).abs() <= 180.0));
    }
}

#[test]
fn sky_plots_refuse_bad_angles_and_unwritable_paths() {
    let dir = TestDir::new("sky-errors");
    let mut bad = leo_pass();
    bad.name = "leo 7".to_string();
    bad.points[3] = Some((f64::NAN, 0.3));
    for ra_dec in [false, true] {
        let plot = if ra_dec { sky_plot_ra_dec } else { sky_plot_az_el };
        let stem = dir.stem(&format!("bad_{ra_dec}"));
        let error = plot(&stem, "t", &[leo_pass()], std::slice::from_ref(&bad), None).unwrap_err();
        assert!(error.0.contains("estimate series \"leo 7\" point 3"), "{error}");
        assert!(!path_with_extension(&stem, "png").exists(), "nothing written on bad input");

        let too_high = SkySeries { points: vec![Some((0.0, 1.6))], ..SkySeries::default() };
        let error = plot(&stem, "t", &[too_high], &[], None).unwrap_err();
        assert!(error.0.contains("truth series #0 point 0") && error.0.contains("outside"), "{error}");

        let error = plot(&stem, "t", &[], &[], Some(&[(0.0, 0.1), (f64::INFINITY, 0.2)])).unwrap_err();
        assert!(error.0.contains("field of view outline point 1"), "{error}");

        let blocker = dir.stem(&format!("blocker_{ra_dec}"));
        std::fs::write(&blocker, b"a file, not a directory").unwrap();
        let error = plot(&blocker.join("sky"), "t", &[leo_pass()], &[], None).unwrap_err();
        assert!(error.0.contains("blocker"), "message names the path: {error}");
    }
}

#[test]
fn ground_tracks_cut_at_the_antimeridian_and_refuse_bad_latitudes() {
    let dir = TestDir::new("ground-tracks");
    // An inclined orbit's track over 1.5 revolutions: longitude drifting west, crossing ±180°.
    let track = SkySeries {
        name: "leo".to_string(),
        points: (0..=135)
            .map(|k| {
                let u = f64::from(k) * 4_f64.to_radians();
                Some((u - 0.02 * f64::from(k), (53_f64.to_radians().sin() * u.sin()).asin()))
            })
            .collect(),
        color: None,
    };
    ensure_font_registered().unwrap();
    let figure = GroundTrackFigure::new("t", std::slice::from_ref(&track), &[]).unwrap();
    assert!(figure.truth[0].1.len() >= 2, "cut at the antimeridian");
    for piece in &figure.truth[0].1 {
        assert!(piece.windows(2).all(|pair| (pair[1].0 - pair[0].0).abs() <= 180.0));
        assert!(piece.iter().all(|p| (-180.0..180.0).contains(&p.0) && p.1.abs() <= 53.0 + 1e-9));
    }
    let stem = dir.stem("ground");
    let estimates = [SkySeries { name: "map".into(), points: vec![Some((0.1, 0.2))], color: None }];
    ground_tracks(&stem, "ground tracks", &[track], &estimates).unwrap();
    assert_png_and_svg(&stem);
    let too_high = SkySeries { points: vec![Some((0.0, 1.6))], ..SkySeries::default() };
    let error = ground_tracks(&dir.stem("bad"), "t", &[too_high], &[]).unwrap_err();
    assert!(error.0.contains("latitude") && error.0.contains("outside"), "{error}");
}

#[test]
fn scatter_and_histogram_normal_and_empty() {
    let dir = TestDir::new("scatter-histogram");
    let dots = |name: &str, k: f64| Series {
        name: name.into(),
        points: (0..50).map(|i| (f64::from(i), k * f64::from(i) + 3.0)).chain([(f64::NAN, 1.0)]).collect(),
        markers: true,
    };
    super::scatter(&dir.stem("scatter"), "cost", "objects in view", "ms", &[dots("a", 0.5), dots("b", 1.0)]).unwrap();
    assert_eq!(assert_png_and_svg(&dir.stem("scatter")).0, LINE_CHART_SIZE.0);
    super::scatter(&dir.stem("scatter-empty"), "none", "x", "y", &[]).unwrap();
    assert_png_and_svg(&dir.stem("scatter-empty"));
    super::histogram(&dir.stem("histogram"), "sizes", "objects", "clusters", &[(1, 980), (2, 9), (5, 1)]).unwrap();
    assert_eq!(assert_png_and_svg(&dir.stem("histogram")).0, LINE_CHART_SIZE.0);
    super::histogram(&dir.stem("histogram-empty"), "none", "x", "y", &[]).unwrap();
    assert_png_and_svg(&dir.stem("histogram-empty"));
}
