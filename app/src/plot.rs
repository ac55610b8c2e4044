//! Spectral plots as standalone SVG (no dependencies): what a colour scientist looks at after an
//! import — the measured reflectances and the inverted S and K per wavelength.

use rouge_measure::preset::Preset;
use std::fmt::Write;

/// One curve: label, colour, dash pattern, values on the working grid.
struct Curve<'a> {
    label: &'a str,
    colour: &'a str,
    dash: &'a str,
    values: &'a [f64],
}

const W: f64 = 720.0;
const PANEL_H: f64 = 260.0;
const LEFT: f64 = 64.0;
const RIGHT: f64 = 150.0;
const TOP: f64 = 40.0;

/// A "nice" upper bound for an axis: 1, 2 or 5 times a power of ten at or above `max`.
fn nice_max(max: f64) -> f64 {
    if !(max > 0.0 && max.is_finite()) {
        return 1.0;
    }
    let p = 10f64.powf(max.log10().floor());
    [1.0, 2.0, 5.0, 10.0].iter().map(|m| m * p).find(|v| *v >= max * 0.999_999).unwrap_or(10.0 * p)
}

fn panel(svg: &mut String, y0: f64, title: &str, y_label: &str, wavelengths: &[f64], curves: &[Curve]) {
    let (x_min, x_max) = (wavelengths[0], wavelengths[wavelengths.len() - 1]);
    let y_max = nice_max(curves.iter().flat_map(|c| c.values.iter().copied()).fold(0.0, f64::max));
    let pw = W - LEFT - RIGHT;
    let ph = PANEL_H - 60.0;
    let x = |nm: f64| LEFT + (nm - x_min) / (x_max - x_min) * pw;
    let y = |v: f64| y0 + ph - (v / y_max).clamp(0.0, 1.05) * ph;
    let _ = writeln!(svg, r#"<text x="{LEFT}" y="{}" font-size="15" font-weight="bold">{title}</text>"#, y0 - 12.0);
    let _ = writeln!(svg, r##"<rect x="{LEFT}" y="{y0}" width="{pw}" height="{ph}" fill="none" stroke="#444"/>"##);
    for i in 0..=5 {
        let v = y_max * i as f64 / 5.0;
        let yy = y(v);
        let _ = writeln!(
            svg,
            r##"<line x1="{LEFT}" y1="{yy}" x2="{}" y2="{yy}" stroke="#ddd"/><text x="{}" y="{}" font-size="11" text-anchor="end">{}</text>"##,
            LEFT + pw,
            LEFT - 6.0,
            yy + 4.0,
            format_tick(v)
        );
    }
    for nm in (400..=750).step_by(50) {
        let xx = x(nm as f64);
        let _ = writeln!(
            svg,
            r##"<line x1="{xx}" y1="{y0}" x2="{xx}" y2="{}" stroke="#eee"/><text x="{xx}" y="{}" font-size="11" text-anchor="middle">{nm}</text>"##,
            y0 + ph,
            y0 + ph + 16.0
        );
    }
    let _ = writeln!(
        svg,
        r#"<text x="{}" y="{}" font-size="12" text-anchor="middle">wavelength (nm)</text>"#,
        LEFT + pw / 2.0,
        y0 + ph + 34.0
    );
    let _ = writeln!(
        svg,
        r#"<text x="16" y="{}" font-size="12" text-anchor="middle" transform="rotate(-90 16 {})">{y_label}</text>"#,
        y0 + ph / 2.0,
        y0 + ph / 2.0
    );
    for (k, c) in curves.iter().enumerate() {
        let mut points = String::new();
        for (nm, v) in wavelengths.iter().zip(c.values) {
            let _ = write!(points, "{:.2},{:.2} ", x(*nm), y(*v));
        }
        let _ = writeln!(
            svg,
            r#"<polyline points="{}" fill="none" stroke="{}" stroke-width="2" stroke-dasharray="{}"/>"#,
            points.trim_end(),
            c.colour,
            c.dash
        );
        let ly = y0 + 14.0 + 20.0 * k as f64;
        let lx = LEFT + pw + 14.0;
        let _ = writeln!(
            svg,
            r#"<line x1="{lx}" y1="{ly}" x2="{}" y2="{ly}" stroke="{}" stroke-width="2" stroke-dasharray="{}"/><text x="{}" y="{}" font-size="12">{}</text>"#,
            lx + 26.0,
            c.colour,
            c.dash,
            lx + 32.0,
            ly + 4.0,
            c.label
        );
    }
}

fn format_tick(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else if v.abs() >= 100.0 {
        format!("{v:.0}")
    } else if v.abs() >= 1.0 {
        format!("{v:.1}")
    } else {
        format!("{v:.2}")
    }
}

/// Two panels: measured R∞, R, Rg and R re-computed from S and K; then S and K per mm. With a
/// swatch of the measured R∞ (sRGB, D65).
pub fn preset_svg(preset: &Preset, r_recomputed: &[f64]) -> String {
    let wl = &preset.wavelengths_nm;
    let mut svg = String::new();
    let height = TOP + 2.0 * PANEL_H + 20.0;
    let _ = writeln!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{height}" viewBox="0 0 {W} {height}" font-family="sans-serif">"#
    );
    let _ = writeln!(svg, r#"<rect width="100%" height="100%" fill="white"/>"#);
    let name = escape(&preset.name);
    let _ = writeln!(
        svg,
        r#"<text x="{LEFT}" y="22" font-size="17" font-weight="bold">{name} ({}, D = {} mm)</text>"#,
        preset.kind.name(),
        preset.thickness_mm
    );
    let hex = &preset.derived.r_inf_srgb_hex;
    let _ = writeln!(
        svg,
        r##"<rect x="{}" y="8" width="110" height="22" fill="{hex}" stroke="#444"/><text x="{}" y="44" font-size="11" text-anchor="middle">R∞ {hex}</text>"##,
        W - RIGHT + 14.0,
        W - RIGHT + 69.0
    );
    if let Some(m) = &preset.measurement {
        panel(
            &mut svg,
            TOP + 30.0,
            "Reflectance",
            "reflectance",
            wl,
            &[
                Curve { label: "R∞ measured", colour: "#c0392b", dash: "none", values: &m.r_inf },
                Curve { label: "R measured", colour: "#2471a3", dash: "none", values: &m.r },
                Curve { label: "R from S, K", colour: "#f39c12", dash: "6 4", values: r_recomputed },
                Curve { label: "Rg background", colour: "#555", dash: "2 3", values: &m.rg },
            ],
        );
    }
    panel(
        &mut svg,
        TOP + PANEL_H + 30.0,
        "Kubelka-Munk coefficients",
        "per mm",
        wl,
        &[
            Curve { label: "S scattering", colour: "#1e8449", dash: "none", values: &preset.s_per_mm },
            Curve { label: "K absorption", colour: "#7d3c98", dash: "none", values: &preset.k_per_mm },
        ],
    );
    svg.push_str("</svg>\n");
    svg
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;")
}
