//! The PNG charts of `rouge analyze` (drawn by `plot_png`): coverage against thickness, the
//! skins a product line serves, and `rouge qc`'s batch report with its tolerance ellipses.

use crate::plot_png::{Chart, Marker, Series, render};
use anyhow::Result;
use rouge_measure::analysis::coverage::{CoverageRow, HIDING_CONTRAST_RATIO};
use rouge_measure::analysis::matching::SkinCoverage;
use rouge_measure::analysis::qc::{AB_PLANE, Metric, lightness_chroma_plane, tolerance_contour};
use rouge_measure::analysis::{Layer, lab_of};
use rouge_measure::colorimetry::Colorimeter;
use rouge_measure::spectrum::Spectrum;

/// 61 thicknesses from 0 to the largest of `xs_mm` (at least 50 µm): a smooth curve.
pub fn curve_mm(xs_mm: &[f64]) -> Vec<f64> {
    let top = xs_mm.iter().copied().fold(0.05, f64::max);
    (0..=60).map(|i| top * f64::from(i) / 60.0).collect()
}

/// Names without the words every name starts with ("Foundation 03 Sand" → "03 Sand"), for legends.
fn short_names(names: &[&str]) -> Vec<String> {
    let words: Vec<Vec<&str>> = names.iter().map(|n| n.split_whitespace().collect()).collect();
    let min_len = words.iter().map(Vec::len).min().unwrap_or(0);
    let common = (0..min_len.saturating_sub(1)).take_while(|&i| words.iter().all(|w| w[i] == words[0][i])).count();
    let common = if names.len() > 1 { common } else { 0 };
    words.iter().map(|w| w[common..].join(" ")).collect()
}

/// Encoded sRGB of a reflectance, clipped, as 8-bit; darkened if too light to see on white.
fn swatch(c: &Colorimeter, r: &Spectrum) -> [u8; 3] {
    let rgb = c.srgb(&c.xyz(r)).map(|v| v.clamp(0.0, 1.0));
    let luma = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
    let k = if luma > 0.8 { 0.8 / luma } else { 1.0 };
    rgb.map(|v| (v * k * 255.0).round() as u8)
}

fn line(label: &str, rgb: [u8; 3], points: Vec<(f64, f64)>) -> Series {
    Series {
        label: label.into(),
        rgb,
        points: points.into_iter().map(|(x, y)| (x, y, None)).collect(),
        line: true,
        marker: Marker::Dot,
    }
}

/// Contrast ratio and ΔE2000 on each skin against thickness, the 0.98 line and the hiding point.
pub fn coverage(
    name: &str,
    rows: &[CoverageRow],
    hiding_mm: Option<f64>,
    skins: &[(String, Spectrum)],
    c: &Colorimeter,
) -> Result<Vec<u8>> {
    let top_um = rows.last().map_or(50.0, |r| r.thickness_mm * 1e3);
    let mut cr = vec![line(
        "contrast ratio",
        [40, 40, 40],
        rows.iter().map(|r| (r.thickness_mm * 1e3, r.contrast.contrast_ratio)).collect(),
    )];
    cr.push(line(
        "CR 0.98 (hiding)",
        [170, 170, 170],
        vec![(0.0, HIDING_CONTRAST_RATIO), (top_um, HIDING_CONTRAST_RATIO)],
    ));
    if let Some(x) = hiding_mm.filter(|x| x * 1e3 <= top_um) {
        cr.push(Series {
            label: "hiding thickness".into(),
            rgb: [200, 40, 40],
            points: vec![(x * 1e3, HIDING_CONTRAST_RATIO, Some(format!("{:.1} µm", x * 1e3)))],
            line: false,
            marker: Marker::Diamond,
        });
    }
    let de = skins
        .iter()
        .enumerate()
        .map(|(i, (skin, r))| {
            line(
                &format!("ΔE00 on {skin}"),
                swatch(c, r),
                rows.iter().map(|row| (row.thickness_mm * 1e3, row.delta_e_on_skin[i])).collect(),
            )
        })
        .collect();
    let charts = [
        Chart {
            title: "Contrast ratio (Y over black / Y over white)".into(),
            x_label: "thickness (µm)".into(),
            y_label: "contrast ratio".into(),
            series: cr,
        },
        Chart {
            title: "Colour change on skin".into(),
            x_label: "thickness (µm)".into(),
            y_label: "ΔE2000, bare against covered".into(),
            series: de,
        },
    ];
    render(&format!("{name}: coverage ({})", c.viewing()), &charts, 2)
}

/// The skins in L* against b*, each marked in the colour of its best shade (gaps crossed), the
/// shades' own opaque colours as diamonds; and the best ΔE2000 against the skin's L*.
pub fn shade_map(
    shades: &[Layer],
    skins: &[(String, Spectrum)],
    cover: &[SkinCoverage],
    gap_de: f64,
    target: &str,
    c: &Colorimeter,
) -> Result<Vec<u8>> {
    let mut gamut = Vec::new();
    let mut errors = Vec::new();
    let names = short_names(&shades.iter().map(|s| s.name.as_str()).collect::<Vec<_>>());
    for (i, (s, short)) in shades.iter().zip(&names).enumerate() {
        let rgb = swatch(c, &s.r_inf());
        let mine: Vec<&SkinCoverage> = cover.iter().filter(|sc| sc.best.shade == i && !sc.gap).collect();
        let pts = |f: &dyn Fn(&SkinCoverage) -> (f64, f64)| {
            mine.iter()
                .map(|sc| {
                    let (x, y) = f(sc);
                    (x, y, None)
                })
                .collect::<Vec<_>>()
        };
        gamut.push(Series {
            label: short.clone(),
            rgb,
            points: pts(&|sc| (sc.skin_lab[2], sc.skin_lab[0])),
            line: false,
            marker: Marker::Dot,
        });
        errors.push(Series {
            label: short.clone(),
            rgb,
            points: pts(&|sc| (sc.skin_lab[0], sc.best.delta_e)),
            line: false,
            marker: Marker::Dot,
        });
        // The shade itself (opaque), a labelled diamond under the same legend entry.
        let lab = lab_of(c, &s.r_inf());
        gamut.push(Series {
            label: short.clone(),
            rgb,
            points: vec![(lab[2], lab[0], Some(short.clone()))],
            line: false,
            marker: Marker::Diamond,
        });
    }
    // Gap skins: crosses in the colour of their best shade, under one legend entry.
    if cover.iter().any(|sc| sc.gap) {
        let label = format!("gap: best ΔE00 > {gap_de} (cross in its best shade's colour)");
        let empty =
            Series { label: label.clone(), rgb: [120, 30, 30], points: Vec::new(), line: false, marker: Marker::Cross };
        gamut.push(empty.clone());
        errors.push(empty);
        for (i, s) in shades.iter().enumerate() {
            let rgb = swatch(c, &s.r_inf());
            let gaps: Vec<&SkinCoverage> = cover.iter().filter(|sc| sc.gap && sc.best.shade == i).collect();
            let series = |points| Series { label: label.clone(), rgb, points, line: false, marker: Marker::Cross };
            gamut.push(series(gaps.iter().map(|sc| (sc.skin_lab[2], sc.skin_lab[0], None)).collect()));
            errors.push(series(gaps.iter().map(|sc| (sc.skin_lab[0], sc.best.delta_e, None)).collect()));
        }
    }
    let l_range = cover
        .iter()
        .map(|sc| sc.skin_lab[0])
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), l| (a.min(l), b.max(l)));
    if l_range.0.is_finite() {
        errors.push(line("gap threshold", [170, 170, 170], vec![(l_range.0, gap_de), (l_range.1, gap_de)]));
    }
    let charts = [
        Chart {
            title: format!("{} skins (dots) and the shades (diamonds, opaque)", skins.len()),
            x_label: "b* (skin)".into(),
            y_label: "L* (skin)".into(),
            series: gamut,
        },
        Chart {
            title: format!("Best ΔE2000 to {target}"),
            x_label: "L* (skin)".into(),
            y_label: "ΔE2000 of the best shade".into(),
            series: errors,
        },
    ];
    render(&format!("Shade matching ({})", c.viewing()), &charts, 2)
}

/// A batch judged for the QC plot: its name, CIELAB and verdict.
#[derive(Clone, Debug)]
pub struct QcPoint {
    pub name: String,
    pub lab: [f64; 3],
    pub pass: bool,
}

/// Widens `((x0, x1), (y0, y1))` so that a CIELAB unit is as long on both axes of a panel
/// (plot area 346 × 246 px): the contours keep their shape.
fn equal_aspect(points: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
    for &(x, y) in points {
        (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
    }
    let aspect = 346.0 / 246.0;
    let (w, h) = ((x1 - x0).max(1e-6), (y1 - y0).max(1e-6));
    let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
    let (w, h) = if w / h > aspect { (w, w / aspect) } else { (h * aspect, h) };
    vec![(cx - w / 2.0, cy - h / 2.0), (cx + w / 2.0, cy + h / 2.0)]
}

/// `rouge qc --png`: the batches around the standard in the a*b* plane (at the standard's L*)
/// and in the lightness-chroma plane through it, with the tolerance contours of ΔE2000,
/// CMC(l:c) and ΔE*ab at `tolerance` (traced numerically, [`tolerance_contour`]; the chosen
/// `metric`'s drawn heavier), passing batches as dots, failing ones as labelled crosses.
pub fn qc_report(
    title: &str,
    standard: [f64; 3],
    batches: &[QcPoint],
    metric: Metric,
    tolerance: f64,
) -> Result<Vec<u8>> {
    let cmc = match metric {
        Metric::Cmc { .. } => metric,
        _ => Metric::Cmc { l: 2.0, c: 1.0 },
    };
    let chroma = lightness_chroma_plane(standard);
    let c_std = standard[1].hypot(standard[2]);
    // (a*, b*) and (C* along the standard's hue, L*) of a colour.
    let ab = |p: [f64; 3]| (p[1], p[2]);
    let lc = |p: [f64; 3]| (c_std + (p[1] - standard[1]) * chroma[1][1] + (p[2] - standard[2]) * chroma[1][2], p[0]);
    let mut panels: Vec<Vec<Series>> = vec![Vec::new(), Vec::new()];
    let formulas = [(Metric::De2000, [31, 119, 180]), (cmc, [214, 39, 40]), (Metric::Ab, [120, 120, 120])];
    for (k, (plane, project)) in
        [(AB_PLANE, &ab as &dyn Fn([f64; 3]) -> (f64, f64)), (chroma, &lc)].into_iter().enumerate()
    {
        for (m, rgb) in formulas {
            let mut ring = tolerance_contour(m, standard, tolerance, plane, 144)?;
            ring.push(ring[0]);
            let chosen = m == metric;
            panels[k].push(Series {
                label: format!("{} = {tolerance}{}", m.name(), if chosen { " (the tolerance)" } else { "" }),
                rgb: if chosen { rgb } else { rgb.map(|v| (v as f64 * 0.5 + 110.0) as u8) },
                points: ring.into_iter().map(|p| (project(p).0, project(p).1, None)).collect(),
                line: true,
                marker: Marker::None,
            });
        }
        let (sx, sy) = project(standard);
        panels[k].push(Series {
            label: "standard".into(),
            rgb: [20, 20, 20],
            points: vec![(sx, sy, None)],
            line: false,
            marker: Marker::Diamond,
        });
        for (pass, label, rgb, marker) in
            [(true, "pass", [44, 160, 44], Marker::Dot), (false, "fail", [200, 30, 30], Marker::Cross)]
        {
            let points = batches
                .iter()
                .filter(|b| b.pass == pass)
                .map(|b| (project(b.lab).0, project(b.lab).1, (!pass).then(|| b.name.clone())))
                .collect();
            panels[k].push(Series { label: label.into(), rgb, points, line: false, marker });
        }
        let all: Vec<(f64, f64)> = panels[k].iter().flat_map(|s| s.points.iter().map(|p| (p.0, p.1))).collect();
        let corners = equal_aspect(&all).into_iter().map(|(x, y)| (x, y, None)).collect();
        // Invisible corners under the standard's legend entry: equal CIELAB units on both axes.
        panels[k].push(Series {
            label: "standard".into(),
            rgb: [20, 20, 20],
            points: corners,
            line: false,
            marker: Marker::None,
        });
    }
    let [ab_series, lc_series]: [Vec<Series>; 2] = panels.try_into().map_err(|_| anyhow::anyhow!("two panels"))?;
    let charts = [
        Chart {
            title: format!("a*b* plane at L* = {:.1}", standard[0]),
            x_label: "a*".into(),
            y_label: "b*".into(),
            series: ab_series,
        },
        Chart {
            title: format!(
                "lightness and chroma at hue {:.0}°",
                standard[2].atan2(standard[1]).to_degrees().rem_euclid(360.0)
            ),
            x_label: "C*ab (along the standard's hue)".into(),
            y_label: "L*".into(),
            series: lc_series,
        },
    ];
    render(title, &charts, 2)
}

/// `rouge analyze recipe --png`: the target's reflectance and the best recipes' (each recipe its
/// own colour), and each recipe's ΔE2000 under each light of the objective.
pub fn recipes(
    target_name: &str,
    target: &Spectrum,
    found: &[(String, Spectrum, Vec<f64>)],
    lights: &[String],
) -> Result<Vec<u8>> {
    const PALETTE: [[u8; 3]; 5] = [[214, 39, 40], [31, 119, 180], [44, 160, 44], [148, 103, 189], [255, 127, 14]];
    let spectrum = |r: &Spectrum| r.iter_nm().map(|(nm, v)| (nm, v, None)).collect::<Vec<_>>();
    let mut curves = vec![Series {
        label: format!("target: {target_name}"),
        rgb: [20, 20, 20],
        points: spectrum(target),
        line: true,
        marker: Marker::None,
    }];
    let mut errors = Vec::new();
    for (k, (label, r, de)) in found.iter().enumerate() {
        let rgb = PALETTE[k % PALETTE.len()];
        curves.push(Series { label: label.clone(), rgb, points: spectrum(r), line: true, marker: Marker::None });
        errors.push(Series {
            label: label.clone(),
            rgb,
            points: de
                .iter()
                .enumerate()
                .map(|(i, d)| (i as f64 + 1.0, *d, (k == 0).then(|| lights[i].clone())))
                .collect(),
            line: true,
            marker: Marker::Dot,
        });
    }
    let charts = [
        Chart {
            title: "Reflectance (R∞ or over the skin)".into(),
            x_label: "wavelength (nm)".into(),
            y_label: "R".into(),
            series: curves,
        },
        Chart {
            title: format!("ΔE2000 to the target under each light ({})", lights.join(", ")),
            x_label: "light (in the order given)".into(),
            y_label: "ΔE2000".into(),
            series: errors,
        },
    ];
    render(&format!("Recipe search: the best {} recipes for {target_name}", found.len()), &charts, 2)
}
