//! Benchmark plots as PNG, drawn in Rust: panels of x-y charts with lines, markers, axes, ticks
//! and labels, rasterised by vello_cpu (antialiased paths and glyphs) with egui's embedded Ubuntu
//! font (the same crates egui already brings). `rouge bench translucency --plot F.png` uses it, and
//! `rouge import --plot F.png` draws the app's material panels with it.

use anyhow::{Context, Result};
use rouge_app::material_plots::Panel;
use rouge_app::ticks;
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
    /// No marker: a line series drawn as a plain line (a short line stands for it in the legend).
    None,
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
        self.stroke_styled(path, width, false, rgb);
    }

    /// A solid or dashed (6 on, 4 off) line.
    fn stroke_styled(&mut self, path: &BezPath, width: f64, dashed: bool, rgb: [u8; 3]) {
        let stroke = if dashed { Stroke::new(width).with_dashes(0.0, [6.0, 4.0]) } else { Stroke::new(width) };
        self.ctx.set_stroke(stroke);
        self.ctx.set_paint(colour(rgb));
        self.ctx.stroke_path(path);
    }

    fn fill(&mut self, path: &BezPath, rgb: [u8; 3]) {
        self.ctx.set_paint(colour(rgb));
        self.ctx.fill_path(path);
    }
}

/// A panel's plot area and the data range it shows.
struct Axes {
    plot: Rect,
    x: (f64, f64),
    y: (f64, f64),
}

impl Axes {
    fn sx(&self, x: f64) -> f64 {
        self.plot.x0 + (x - self.x.0) / (self.x.1 - self.x.0) * self.plot.width()
    }

    fn sy(&self, y: f64) -> f64 {
        self.plot.y1 - (y - self.y.0) / (self.y.1 - self.y.0) * self.plot.height()
    }
}

/// The range of the finite `points` and of `y_include`, padded by 8 % each way.
fn data_range(points: impl Iterator<Item = (f64, f64)>, y_include: &[f64]) -> ((f64, f64), (f64, f64)) {
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
    for (x, y) in points.filter(|(x, y)| x.is_finite() && y.is_finite()) {
        (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
    }
    if !x0.is_finite() {
        (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
    }
    for &y in y_include {
        (y0, y1) = (y0.min(y), y1.max(y));
    }
    let pad = |a: f64, b: f64| {
        let d = ((b - a) * 0.08).max(b.abs() * 0.02).max(1e-6);
        (a - d, b + d)
    };
    (pad(x0, x1), pad(y0, y1))
}

/// A panel's frame at (`ox`, `oy`) of `height`: grid, ticks and labels on both axes
/// ([`rouge_app::ticks`]), the box, the title and both axis labels.
fn draw_axes(
    c: &mut Canvas,
    (ox, oy): (f64, f64),
    height: f64,
    labels: [&str; 3],
    range: ((f64, f64), (f64, f64)),
) -> Axes {
    let (l, r, t, b) = MARGIN;
    let axes = Axes { plot: Rect::new(ox + l, oy + t, ox + PANEL_W - r, oy + height - b), x: range.0, y: range.1 };
    let grey = [200, 200, 200];
    for (axis, (lo, hi)) in [(0, axes.x), (1, axes.y)] {
        let step = ticks::nice_step(hi - lo, 5);
        for v in ticks::ticks_with_step(lo, hi, step) {
            let mut grid = BezPath::new();
            if axis == 0 {
                grid.move_to((axes.sx(v), axes.plot.y0));
                grid.line_to((axes.sx(v), axes.plot.y1));
                c.text(&ticks::label(v, step), (axes.sx(v), axes.plot.y1 + 14.0), 10.0, 0.5, false, [60, 60, 60]);
            } else {
                grid.move_to((axes.plot.x0, axes.sy(v)));
                grid.line_to((axes.plot.x1, axes.sy(v)));
                c.text(&ticks::label(v, step), (axes.plot.x0 - 5.0, axes.sy(v) + 3.5), 10.0, 1.0, false, [60, 60, 60]);
            }
            c.stroke(&grid, 0.6, grey);
        }
    }
    c.stroke(&axes.plot.to_path(0.1), 1.0, [90, 90, 90]);
    let [title, x_label, y_label] = labels;
    let plot = axes.plot;
    c.text(title, (ox + PANEL_W / 2.0, oy + 18.0), 12.0, 0.5, false, [20, 20, 20]);
    c.text(x_label, (plot.x0 + plot.width() / 2.0, oy + height - 10.0), 11.0, 0.5, false, [20, 20, 20]);
    c.text(y_label, (ox + 14.0, plot.y0 + plot.height() / 2.0), 11.0, 0.5, true, [20, 20, 20]);
    axes
}

fn draw_chart(c: &mut Canvas, chart: &Chart, origin: (f64, f64)) {
    let range = data_range(chart.series.iter().flat_map(|s| s.points.iter().map(|p| (p.0, p.1))), &[]);
    let axes = draw_axes(c, origin, PANEL_H, [&chart.title, &chart.x_label, &chart.y_label], range);
    for s in &chart.series {
        let points: Vec<(f64, f64, Option<String>)> =
            s.points.iter().filter(|p| p.0.is_finite() && p.1.is_finite()).cloned().collect();
        if s.line && points.len() > 1 {
            let mut path = BezPath::new();
            path.move_to((axes.sx(points[0].0), axes.sy(points[0].1)));
            for p in &points[1..] {
                path.line_to((axes.sx(p.0), axes.sy(p.1)));
            }
            c.stroke(&path, 1.6, s.rgb);
        }
        for (x, y, label) in &points {
            let (px, py) = (axes.sx(*x), axes.sy(*y));
            draw_marker(c, s.marker, (px, py), s.rgb);
            if let Some(label) = label {
                c.text(label, (px + 4.0, py - 4.0), 9.0, 0.0, false, [40, 40, 40]);
            }
        }
    }
}

/// Draws `marker` centred on `at`.
fn draw_marker(c: &mut Canvas, marker: Marker, (px, py): (f64, f64), rgb: [u8; 3]) {
    match marker {
        Marker::None => {}
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

impl Canvas {
    /// A white `width` × `height` canvas with `title` centred on top (shrunk to fit).
    fn new(width: u16, height: u16, title: &str) -> Result<Canvas> {
        let bytes: &'static [u8] = epaint_default_fonts::UBUNTU_LIGHT;
        FontRef::new(bytes).context("the embedded Ubuntu font")?;
        let mut c = Canvas {
            ctx: RenderContext::new(width, height),
            resources: Resources::new(),
            font: FontData::new(Blob::from(bytes.to_vec()), 0),
            bytes,
        };
        c.fill(&Rect::new(0.0, 0.0, f64::from(width), f64::from(height)).to_path(0.1), [255, 255, 255]);
        let title_px = (14.0 * (f64::from(width) - 24.0) / c.text_width(title, 14.0).max(1.0)).min(14.0) as f32;
        c.text(title, (f64::from(width) / 2.0, 24.0), title_px, 0.5, false, [0, 0, 0]);
        Ok(c)
    }

    /// Rasterises what was drawn and encodes it as PNG.
    fn into_png(mut self, width: u16, height: u16) -> Result<Vec<u8>> {
        let mut pixmap = Pixmap::new(width, height);
        self.ctx.flush();
        self.ctx.render(&mut pixmap, &mut self.resources);
        pixmap.into_png().context("cannot encode the plot as PNG")
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
    let width = (PANEL_W * columns as f64).ceil() as u16;
    // Legend: every distinct label once, in order of appearance, in centred lines that fit the
    // width (broken on a generous estimate of 7 px a character, drawn with the font's widths).
    let mut seen: Vec<(String, [u8; 3], Marker)> = Vec::new();
    for s in charts.iter().flat_map(|c| &c.series) {
        if !seen.iter().any(|(l, _, _)| *l == s.label) {
            seen.push((s.label.clone(), s.rgb, s.marker));
        }
    }
    let mut lines: Vec<Vec<(String, [u8; 3], Marker)>> = vec![Vec::new()];
    let mut used = 0.0;
    for entry in seen {
        let w = 24.0 + 7.0 * entry.0.chars().count() as f64;
        if used + w > f64::from(width) - 40.0 && !lines.last().is_some_and(Vec::is_empty) {
            lines.push(Vec::new());
            used = 0.0;
        }
        used += w;
        if let Some(line) = lines.last_mut() {
            line.push(entry);
        }
    }
    let (head, line_h) = (36.0, 18.0);
    let legend = 16.0 + line_h * lines.len() as f64;
    let height = (head + PANEL_H * rows as f64 + legend).ceil() as u16;
    let mut c = Canvas::new(width, height, title)?;
    for (i, chart) in charts.iter().enumerate() {
        let (col, row) = (i % columns, i / columns);
        draw_chart(&mut c, chart, (PANEL_W * col as f64, head + PANEL_H * row as f64));
    }
    for (k, line) in lines.into_iter().enumerate() {
        let total: f64 = line.iter().map(|(l, _, _)| 24.0 + c.text_width(l, 11.0)).sum();
        let y = head + PANEL_H * rows as f64 + 14.0 + line_h * k as f64;
        let mut x = (f64::from(width) - total) / 2.0;
        for (label, rgb, marker) in line {
            if marker == Marker::None {
                let mut stroke = BezPath::new();
                stroke.move_to((x - 2.0, y - 4.0));
                stroke.line_to((x + 10.0, y - 4.0));
                c.stroke(&stroke, 2.0, rgb);
            } else {
                draw_marker(&mut c, marker, (x + 4.0, y - 4.0), rgb);
            }
            c.text(&label, (x + 12.0, y), 11.0, 0.0, false, [20, 20, 20]);
            x += 24.0 + c.text_width(&label, 11.0);
        }
    }
    c.into_png(width, height)
}

/// Height of the legend rows under each material panel.
const PANEL_LEGEND_H: f64 = 40.0;

/// The material plots of [`rouge_app::material_plots`] (the app's material panel draws the same
/// panels) as one PNG: `title` with an `swatch` of the material's colour, the panels two to a
/// row, each with ticks and labels on both axes and its own legend in rows under its box, where
/// it covers no curve; dashed curves dashed.
///
/// # Errors
/// When the font cannot be read or the PNG cannot be encoded.
pub fn render_panels(title: &str, swatch: Option<[u8; 3]>, panels: &[Panel]) -> Result<Vec<u8>> {
    let columns = 2.min(panels.len().max(1));
    let rows = panels.len().div_ceil(columns).max(1);
    let (head, cell_h) = (44.0, PANEL_H + PANEL_LEGEND_H);
    let width = (PANEL_W * columns as f64).ceil() as u16;
    let height = (head + cell_h * rows as f64).ceil() as u16;
    let mut c = Canvas::new(width, height, title)?;
    if let Some(rgb) = swatch {
        c.fill(&Rect::new(12.0, 8.0, 52.0, 32.0).to_path(0.1), rgb);
        c.stroke(&Rect::new(12.0, 8.0, 52.0, 32.0).to_path(0.1), 1.0, [60, 60, 60]);
    }
    for (i, panel) in panels.iter().enumerate() {
        let (ox, oy) = (PANEL_W * (i % columns) as f64, head + cell_h * (i / columns) as f64);
        let points = panel.curves.iter().flat_map(|c| c.points.iter().map(|p| (p[0], p[1])));
        let range = data_range(points, &panel.y_include);
        let axes = draw_axes(&mut c, (ox, oy), PANEL_H, [panel.title, panel.x_label, panel.y_label], range);
        for curve in &panel.curves {
            let mut path = BezPath::new();
            for (k, p) in curve.points.iter().filter(|p| p[0].is_finite() && p[1].is_finite()).enumerate() {
                let at = (axes.sx(p[0]), axes.sy(p[1]));
                if k == 0 { path.move_to(at) } else { path.line_to(at) }
            }
            c.stroke_styled(&path, 1.6, curve.dashed, curve.rgb);
        }
        // The legend: a line sample and the label per curve, wrapped within the panel.
        let (x0, x_end) = (ox + MARGIN.0, ox + PANEL_W - MARGIN.1);
        let (mut x, mut y) = (x0, oy + PANEL_H + 6.0);
        for curve in panel.curves.iter().filter(|c| !c.name.is_empty()) {
            let w = 30.0 + c.text_width(&curve.name, 11.0);
            if x + w > x_end && x > x0 {
                (x, y) = (x0, y + 16.0);
            }
            let mut sample = BezPath::new();
            sample.move_to((x, y - 4.0));
            sample.line_to((x + 20.0, y - 4.0));
            c.stroke_styled(&sample, 2.0, curve.dashed, curve.rgb);
            c.text(&curve.name, (x + 24.0, y), 11.0, 0.0, false, [20, 20, 20]);
            x += w + 8.0;
        }
    }
    c.into_png(width, height)
}
