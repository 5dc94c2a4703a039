//! Markers (truth dots, within-bound circles, estimate stars) and the legends that name them.

use super::figure::{FONT, PALETTE, PlotError, to_message};
use plotters::coord::Shift;
use plotters::element::ComposedElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

const TRUTH_COLOR: RGBColor = RGBColor(20, 80, 220);

const WITHIN_BOUND_COLOR: RGBColor = RGBColor(0, 150, 40);

const OUTSIDE_BOUND_COLOR: RGBColor = RGBColor(220, 20, 20);

pub(crate) const FOV_COLOR: RGBColor = BLACK;

pub(crate) const BODY_FILL: RGBColor = RGBColor(215, 225, 235);

pub(crate) const BODY_EDGE: RGBColor = RGBColor(120, 130, 145);

const TRUTH_DOT_RADIUS: i32 = 4;

const WITHIN_CIRCLE_RADIUS: i32 = 8;

const STAR_OUTER_RADIUS: f64 = 10.0;

/// Filled five-pointed star (pixel offsets from its centre, y down), to be placed with `EmptyElement::at(..) +`.
pub(crate) fn star_marker() -> Polygon<(i32, i32)> {
    let vertices: Vec<(i32, i32)> = (0..10)
        .map(|i| {
            let radius = if i % 2 == 0 { STAR_OUTER_RADIUS } else { STAR_OUTER_RADIUS * 0.42 };
            let angle = -std::f64::consts::FRAC_PI_2 + f64::from(i) * std::f64::consts::PI / 5.0;
            ((radius * angle.cos()).round() as i32, (radius * angle.sin()).round() as i32)
        })
        .collect();
    Polygon::new(vertices, OUTSIDE_BOUND_COLOR.filled())
}

pub(crate) fn truth_marker<C>(at: C) -> Circle<C, i32> {
    Circle::new(at, TRUTH_DOT_RADIUS, TRUTH_COLOR.filled())
}

/// A circle positioned in pixel offsets from a composed element's anchor.
type PixelCircle = Circle<(i32, i32), i32>;

/// A 2 px ring; two 1 px circles, because plotters' bitmap backend leaves gaps in thick circle outlines.
pub(crate) fn within_bound_marker<C, DB: DrawingBackend>(at: C) -> ComposedElement<C, DB, PixelCircle, PixelCircle> {
    let ring = |radius| Circle::new((0, 0), radius, WITHIN_BOUND_COLOR.stroke_width(1));
    EmptyElement::at(at) + ring(WITHIN_CIRCLE_RADIUS) + ring(WITHIN_CIRCLE_RADIUS - 1)
}

const LEGEND_FONT_SIZE: u32 = 18;

pub(crate) const LEGEND_LINE_HEIGHT: u32 = 32;

const LEGEND_SYMBOL_WIDTH: u32 = 34;

const LEGEND_ENTRY_GAP: u32 = 34;

const LEGEND_TEXT_GAP: u32 = 8;

pub(crate) const LEGEND_PADDING: u32 = 12;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum LegendSymbol {
    Truth,
    WithinBound,
    OutsideBound,
    Fov,
    CentralBody,
    /// Sky plots: truth tracks, one colour per object.
    TruthTracks,
    /// Sky plots: MAP estimate markers.
    MapEstimate,
}

impl LegendSymbol {
    fn label(self) -> &'static str {
        match self {
            Self::Truth => "Truth",
            Self::WithinBound => "Estimate within bound",
            Self::OutsideBound => "Estimate outside bound",
            Self::Fov => "Sensor FOV",
            Self::CentralBody => "Central body",
            Self::TruthTracks => "Truth (one colour per object)",
            Self::MapEstimate => "MAP estimate",
        }
    }
}

/// A legend entry placed at pixel offset `x` within its line.
pub(crate) struct PlacedLegendEntry {
    symbol: LegendSymbol,
    x: u32,
}

/// Flows legend entries into lines no wider than `width`.
pub(crate) fn layout_legend(symbols: &[LegendSymbol], width: u32) -> Result<Vec<Vec<PlacedLegendEntry>>, PlotError> {
    let font = (FONT, LEGEND_FONT_SIZE).into_font();
    let mut lines = Vec::new();
    let mut line: Vec<PlacedLegendEntry> = Vec::new();
    let mut x = LEGEND_PADDING;
    for &symbol in symbols {
        let (text_width, _) = font.box_size(symbol.label()).map_err(to_message)?;
        let entry_width = LEGEND_SYMBOL_WIDTH + LEGEND_TEXT_GAP + text_width;
        if !line.is_empty() && x + entry_width > width.saturating_sub(LEGEND_PADDING) {
            lines.push(std::mem::take(&mut line));
            x = LEGEND_PADDING;
        }
        line.push(PlacedLegendEntry { symbol, x });
        x += entry_width + LEGEND_ENTRY_GAP;
    }
    lines.push(line);
    Ok(lines)
}

pub(crate) fn draw_snapshot_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    lines: &[Vec<PlacedLegendEntry>],
) -> Result<(), PlotError> {
    let text_style = TextStyle::from((FONT, LEGEND_FONT_SIZE).into_font()).pos(Pos::new(HPos::Left, VPos::Center));
    for (row, line) in lines.iter().enumerate() {
        let y = (LEGEND_PADDING + row as u32 * LEGEND_LINE_HEIGHT + LEGEND_LINE_HEIGHT / 2) as i32;
        for entry in line {
            let x = entry.x as i32;
            draw_legend_symbol(area, entry.symbol, x, y).map_err(to_message)?;
            // +2 px: plotters' ab_glyph text sits a little high in PNGs (SVG is centred by the viewer).
            let text_x = x + (LEGEND_SYMBOL_WIDTH + LEGEND_TEXT_GAP) as i32;
            area.draw(&Text::new(entry.symbol.label(), (text_x, y + 2), text_style.clone())).map_err(to_message)?;
        }
    }
    Ok(())
}

/// Draws `symbol` in the legend slot starting at `x`, vertically centred on `y`.
fn draw_legend_symbol<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    symbol: LegendSymbol,
    x: i32,
    y: i32,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let width = LEGEND_SYMBOL_WIDTH as i32;
    let center = (x + width / 2, y);
    match symbol {
        LegendSymbol::Truth => area.draw(&truth_marker(center)),
        LegendSymbol::WithinBound => area.draw(&within_bound_marker(center)),
        LegendSymbol::OutsideBound => area.draw(&(EmptyElement::at(center) + star_marker())),
        LegendSymbol::Fov => area.draw(&PathElement::new(vec![(x, y), (x + width, y)], FOV_COLOR.stroke_width(2))),
        LegendSymbol::TruthTracks => {
            let third = width / 3;
            for (piece, color) in PALETTE.iter().take(3).enumerate() {
                let from = x + piece as i32 * third;
                area.draw(&PathElement::new(vec![(from, y), (from + third, y)], color.stroke_width(SKY_TRUTH_WIDTH)))?;
            }
            Ok(())
        }
        LegendSymbol::MapEstimate => area.draw(&estimate_marker((x + width / 2, y), ESTIMATE_COLOR)),
        LegendSymbol::CentralBody => {
            let swatch = [(x + 4, y - 9), (x + width - 4, y + 9)];
            area.draw(&Rectangle::new(swatch, BODY_FILL.filled()))?;
            area.draw(&Rectangle::new(swatch, BODY_EDGE.stroke_width(1)))
        }
    }
}

pub(crate) const SKY_TRUTH_WIDTH: u32 = 2;

pub(crate) const ESTIMATE_COLOR: RGBColor = BLACK;

const ESTIMATE_CROSS_SIZE: i32 = 4;

pub(crate) fn estimate_marker<C>(at: C, color: RGBColor) -> Cross<C, i32> {
    Cross::new(at, ESTIMATE_CROSS_SIZE, color.stroke_width(2))
}
