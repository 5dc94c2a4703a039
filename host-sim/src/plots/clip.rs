//! Plane geometry of the figures: polylines clipped to the plotting area, circles as polygons.

use std::ops::Range;

pub(crate) fn circle_polygon(radius: f64) -> Vec<(f64, f64)> {
    const SEGMENTS: usize = 180;
    (0..SEGMENTS)
        .map(|i| {
            let angle = std::f64::consts::TAU * i as f64 / SEGMENTS as f64;
            (radius * angle.cos(), radius * angle.sin())
        })
        .collect()
}

/// Clips segment `a`-`b` to the view rectangle (Liang–Barsky); None if it lies entirely outside.
pub(crate) fn clip_segment(
    a: (f64, f64),
    b: (f64, f64),
    x: &Range<f64>,
    y: &Range<f64>,
) -> Option<((f64, f64), (f64, f64))> {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
    for (p, q) in [(-dx, a.0 - x.start), (dx, x.end - a.0), (-dy, a.1 - y.start), (dy, y.end - a.1)] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
            if t0 > t1 {
                return None;
            }
        }
    }
    // Unclipped ends are returned exactly, so consecutive pieces of a polyline can be rejoined.
    let start = if t0 == 0.0 { a } else { (a.0 + t0 * dx, a.1 + t0 * dy) };
    let end = if t1 == 1.0 { b } else { (a.0 + t1 * dx, a.1 + t1 * dy) };
    Some((start, end))
}

/// The visible pieces of a polyline, each still a polyline (so joins stay smooth).
pub(crate) fn clip_polyline(points: &[(f64, f64)], x: &Range<f64>, y: &Range<f64>) -> Vec<Vec<(f64, f64)>> {
    clip_polyline_with(points, |a, b| clip_segment(a, b, x, y))
}

/// A line segment's two ends.
pub(crate) type Segment = ((f64, f64), (f64, f64));

/// The pieces of a polyline that `clip` keeps of each segment, rejoined where a kept segment starts exactly where the
/// previous one ended.
pub(crate) fn clip_polyline_with(
    points: &[(f64, f64)],
    clip: impl Fn((f64, f64), (f64, f64)) -> Option<Segment>,
) -> Vec<Vec<(f64, f64)>> {
    let mut pieces: Vec<Vec<(f64, f64)>> = Vec::new();
    for pair in points.windows(2) {
        let Some((start, end)) = clip(pair[0], pair[1]) else { continue };
        match pieces.last_mut() {
            Some(piece) if piece.last() == Some(&start) => piece.push(end),
            _ => pieces.push(vec![start, end]),
        }
    }
    pieces
}
