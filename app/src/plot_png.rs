//! Benchmark plots as PNG, drawn in Rust: panels of x-y charts with lines, markers, axes, ticks
//! and labels, rasterised by vello_cpu (antialiased paths and glyphs) with egui's embedded Ubuntu
//! font (the same crates egui already brings). `rouge bench translucency --plot F.png` uses it.

use anyhow::{Context, Result};
use skrifa::instance::{LocationRef, Size};
use skrifa::{FontRef, MetadataProvider};
use vello_cpu::color::{AlphaColor, Srgb};
use vello_cpu::kurbo::{Affine, BezPath, Circle, Rect, Shape, Stroke};
use vello_cpu::peniko::{Blob, FontData};
use vello_cpu::{Glyph, Pixmap, RenderContext, Resources};

/// How a series marks its points.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Marker {
    /// A filled dot.
    Dot,
    /// A cross.
    Cross,
    /// A filled diamond.
    Diamond,
    /// A filled square.
    Square,
}

/// One series: points joined by a line (or not), each with a marker and an optional label.
#[derive(Clone, Debug)]
pub struct Series {
    pub label: String,
    pub rgb: [u8; 3],
    pub points: Vec<(f64, f64, Option<String>)>,
    pub line: bool,
    pub marker: Marker,
}

/// One panel.
#[derive(Clone, Debug)]
pub struct Chart {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<Series>,
}

const PANEL_W: f64 = 420.0;
const PANEL_H: f64 = 320.0;
const MARGIN: (f64, f64, f64, f64) = (58.0, 16.0, 30.0, 44.0); // left, right, top, bottom

struct Canvas {
    ctx: RenderContext,
    resources: Resources,
    font: FontData,
    bytes: &'static [u8],
}

fn colour(rgb: [u8; 3]) -> AlphaColor<Srgb> {
    AlphaColor::from_rgba8(rgb[0], rgb[1], rgb[2], 255)
}

impl Canvas {
    fn text_width(&self, text: &str, px: f32) -> f64 {
        let Ok(font) = FontRef::new(self.bytes) else { return 0.0 };
        let (cmap, metrics) = (font.charmap(), font.glyph_metrics(Size::new(px), LocationRef::default()));
        text.chars().filter_map(|c| cmap.map(c)).map(|g| f64::from(metrics.advance_width(g).unwrap_or(0.0))).sum()
    }

    /// Draws `text` with its baseline at `y`, starting at `x` (anchor 0), centred (0.5) or ending
    /// there (1); `vertical` turns it a quarter anticlockwise about (x, y).
    fn text(&mut self, text: &str, (x, y): (f64, f64), px: f32, anchor: f64, vertical: bool, rgb: [u8; 3]) {
        let Ok(font) = FontRef::new(self.bytes) else { return };
        let (cmap, metrics) = (font.charmap(), font.glyph_metrics(Size::new(px), LocationRef::default()));
        let mut pen = 0.0f32;
        let glyphs: Vec<Glyph> = text
            .chars()
            .filter_map(|c| cmap.map(c))
            .map(|g| {
                let glyph = Glyph { id: g.to_u32(), x: pen, y: 0.0 };
                pen += metrics.advance_width(g).unwrap_or(0.0);
                glyph
            })
            .collect();
        let shift = -anchor * f64::from(pen);
        let rotate = if vertical { Affine::rotate(-std::f64::consts::FRAC_PI_2) } else { Affine::IDENTITY };
        self.ctx.set_transform(Affine::translate((x, y)) * rotate * Affine::translate((shift, 0.0)));
        self.ctx.set_paint(colour(rgb));
        let font = self.font.clone();
        self.ctx.glyph_run(&mut self.resources, &font).font_size(px).fill_glyphs(glyphs.into_iter());
        self.ctx.reset_transform();
    }

    fn stroke(&mut self, path: &BezPath, width: f64, rgb: [u8; 3]) {
        self.ctx.set_stroke(Stroke::new(width));
        self.ctx.set_paint(colour(rgb));
        self.ctx.stroke_path(path);
    }

    fn fill(&mut self, path: &BezPath, rgb: [u8; 3]) {
        self.ctx.set_paint(colour(rgb));
        self.ctx.fill_path(path);
    }
}

/// Tick positions: 1, 2 or 5 times a power of ten, about `n` of them over [lo, hi].
fn ticks(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    let span = (hi - lo).max(1e-12);
    let raw = span / n as f64;
    let p = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0].iter().map(|m| m * p).find(|s| *s >= raw).unwrap_or(10.0 * p);
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    (first..=last).map(|k| k as f64 * step).collect()
}

fn tick_label(v: f64, step: f64) -> String {
    let decimals = if step >= 1.0 { 0 } else { (-step.log10().floor()) as usize };
    format!("{v:.decimals$}")
}

fn draw_chart(c: &mut Canvas, chart: &Chart, (ox, oy): (f64, f64)) {
    let (l, r, t, b) = MARGIN;
    let plot = Rect::new(ox + l, oy + t, ox + PANEL_W - r, oy + PANEL_H - b);
    let pts = chart.series.iter().flat_map(|s| s.points.iter().map(|p| (p.0, p.1)));
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
    for (x, y) in pts.filter(|(x, y)| x.is_finite() && y.is_finite()) {
        (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
    }
    if !x0.is_finite() {
        (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
    }
    let pad = |a: f64, b: f64| {
        let d = ((b - a) * 0.08).max(b.abs() * 0.02).max(1e-6);
        (a - d, b + d)
    };
    let ((x0, x1), (y0, y1)) = (pad(x0, x1), pad(y0, y1));
    let sx = |x: f64| plot.x0 + (x - x0) / (x1 - x0) * plot.width();
    let sy = |y: f64| plot.y1 - (y - y0) / (y1 - y0) * plot.height();
    let grey = [200, 200, 200];
    for (axis, lo, hi) in [(0, x0, x1), (1, y0, y1)] {
        let ts = ticks(lo, hi, 5);
        let step = if ts.len() > 1 { ts[1] - ts[0] } else { hi - lo };
        for v in ts {
            let mut grid = BezPath::new();
            if axis == 0 {
                grid.move_to((sx(v), plot.y0));
                grid.line_to((sx(v), plot.y1));
                c.text(&tick_label(v, step), (sx(v), plot.y1 + 14.0), 10.0, 0.5, false, [60, 60, 60]);
            } else {
                grid.move_to((plot.x0, sy(v)));
                grid.line_to((plot.x1, sy(v)));
                c.text(&tick_label(v, step), (plot.x0 - 5.0, sy(v) + 3.5), 10.0, 1.0, false, [60, 60, 60]);
            }
            c.stroke(&grid, 0.6, grey);
        }
    }
    c.stroke(&plot.to_path(0.1), 1.0, [90, 90, 90]);
    for s in &chart.series {
        let points: Vec<(f64, f64, Option<String>)> =
            s.points.iter().filter(|p| p.0.is_finite() && p.1.is_finite()).cloned().collect();
        if s.line && points.len() > 1 {
            let mut path = BezPath::new();
            path.move_to((sx(points[0].0), sy(points[0].1)));
            for p in &points[1..] {
                path.line_to((sx(p.0), sy(p.1)));
            }
            c.stroke(&path, 1.6, s.rgb);
        }
        for (x, y, label) in &points {
            let (px, py) = (sx(*x), sy(*y));
            draw_marker(c, s.marker, (px, py), s.rgb);
            if let Some(label) = label {
                c.text(label, (px + 4.0, py - 4.0), 9.0, 0.0, false, [40, 40, 40]);
            }
        }
    }
    c.text(&chart.title, (ox + PANEL_W / 2.0, oy + 18.0), 12.0, 0.5, false, [20, 20, 20]);
    c.text(&chart.x_label, (plot.x0 + plot.width() / 2.0, oy + PANEL_H - 10.0), 11.0, 0.5, false, [20, 20, 20]);
    c.text(&chart.y_label, (ox + 14.0, plot.y0 + plot.height() / 2.0), 11.0, 0.5, true, [20, 20, 20]);
}

/// Draws `marker` centred on `at`.
fn draw_marker(c: &mut Canvas, marker: Marker, (px, py): (f64, f64), rgb: [u8; 3]) {
    match marker {
        Marker::Dot => c.fill(&Circle::new((px, py), 3.5).to_path(0.1), rgb),
        Marker::Square => c.fill(&Rect::new(px - 4.0, py - 4.0, px + 4.0, py + 4.0).to_path(0.1), rgb),
        Marker::Diamond => {
            let mut d = BezPath::new();
            d.move_to((px, py - 6.0));
            d.line_to((px + 5.0, py));
            d.line_to((px, py + 6.0));
            d.line_to((px - 5.0, py));
            d.close_path();
            c.fill(&d, rgb);
        }
        Marker::Cross => {
            let mut x = BezPath::new();
            x.move_to((px - 5.0, py - 5.0));
            x.line_to((px + 5.0, py + 5.0));
            x.move_to((px - 5.0, py + 5.0));
            x.line_to((px + 5.0, py - 5.0));
            c.stroke(&x, 2.0, rgb);
        }
    }
}

/// Draws `charts` in a grid of `columns`, with a title and one legend of every series label,
/// and encodes the image as PNG.
///
/// # Errors
/// When the font cannot be read or the PNG cannot be encoded.
pub fn render(title: &str, charts: &[Chart], columns: usize) -> Result<Vec<u8>> {
    let columns = columns.clamp(1, charts.len().max(1));
    let rows = charts.len().div_ceil(columns).max(1);
    let (head, legend) = (36.0, 34.0);
    let width = (PANEL_W * columns as f64).ceil() as u16;
    let height = (head + PANEL_H * rows as f64 + legend).ceil() as u16;
    let bytes: &'static [u8] = epaint_default_fonts::UBUNTU_LIGHT;
    FontRef::new(bytes).context("the embedded Ubuntu font")?;
    let mut c = Canvas {
        ctx: RenderContext::new(width, height),
        resources: Resources::new(),
        font: FontData::new(Blob::from(bytes.to_vec()), 0),
        bytes,
    };
    c.fill(&Rect::new(0.0, 0.0, f64::from(width), f64::from(height)).to_path(0.1), [255, 255, 255]);
    // The title shrinks to fit the width.
    let title_px = (14.0 * (f64::from(width) - 24.0) / c.text_width(title, 14.0).max(1.0)).min(14.0) as f32;
    c.text(title, (f64::from(width) / 2.0, 24.0), title_px, 0.5, false, [0, 0, 0]);
    for (i, chart) in charts.iter().enumerate() {
        let (col, row) = (i % columns, i / columns);
        draw_chart(&mut c, chart, (PANEL_W * col as f64, head + PANEL_H * row as f64));
    }
    // Legend: every distinct label once, in order of appearance.
    let mut seen: Vec<(String, [u8; 3], Marker)> = Vec::new();
    for s in charts.iter().flat_map(|c| &c.series) {
        if !seen.iter().any(|(l, _, _)| *l == s.label) {
            seen.push((s.label.clone(), s.rgb, s.marker));
        }
    }
    let total: f64 = seen.iter().map(|(l, _, _)| 24.0 + c.text_width(l, 11.0)).sum();
    let (mut x, y) = ((f64::from(width) - total) / 2.0, f64::from(height) - legend / 2.0);
    for (label, rgb, marker) in seen {
        draw_marker(&mut c, marker, (x + 4.0, y - 4.0), rgb);
        c.text(&label, (x + 12.0, y), 11.0, 0.0, false, [20, 20, 20]);
        x += 24.0 + c.text_width(&label, 11.0);
    }
    let mut pixmap = Pixmap::new(width, height);
    c.ctx.flush();
    c.ctx.render(&mut pixmap, &mut c.resources);
    pixmap.into_png().context("cannot encode the plot as PNG")
}
