//! What the plots of a material show, shared by the app's material panel (egui_plot) and `rouge
//! import --plot` (PNG): four panels, each with its own axes, so K (which falls by orders of
//! magnitude past 600 nm) does not lie flat under S; R0 and T coloured by channel, T dashed.
//! No drawing here: each front end draws these panels with the ticks of [`crate::ticks`] and
//! its legend outside the curves.

use rouge_measure::km::r_inf_from_s_k;
use rouge_measure::preset::{Preset, table_thicknesses_mm};

/// One curve of a panel.
#[derive(Clone, Debug, PartialEq)]
pub struct Curve {
    /// The legend's label.
    pub name: String,
    /// sRGB colour.
    pub rgb: [u8; 3],
    /// Dashed (derived or second quantity) rather than solid.
    pub dashed: bool,
    /// (x, y) points.
    pub points: Vec<[f64; 2]>,
}

/// One panel: a title, axis labels, its curves and a y range it must show.
#[derive(Clone, Debug, PartialEq)]
pub struct Panel {
    /// Title.
    pub title: &'static str,
    /// The x axis's label, with its unit.
    pub x_label: &'static str,
    /// The y axis's label, with its unit.
    pub y_label: &'static str,
    /// The curves.
    pub curves: Vec<Curve>,
    /// Values the y axis includes besides the curves' (reflectances show 0 to 1).
    pub y_include: [f64; 2],
}

/// Colours of the series (tab10), then the R, G and B channels.
const SERIES: [[u8; 3]; 6] =
    [[31, 119, 180], [255, 127, 14], [120, 120, 120], [214, 39, 140], [44, 160, 44], [200, 60, 40]];
const CHANNELS: [(&str, [u8; 3]); 3] = [("R", [220, 60, 50]), ("G", [60, 170, 70]), ("B", [70, 110, 230])];

fn curve(name: &str, rgb: [u8; 3], points: Vec<[f64; 2]>) -> Curve {
    Curve { name: name.to_string(), rgb, dashed: false, points }
}

/// A panel of one Kubelka-Munk coefficient per wavelength, 1/mm, from 0; with its standard
/// uncertainty, the band ±2u (a 95 % interval for a normal distribution) as two dashed edges
/// (the lower one held at 0).
fn coefficient(
    title: &'static str,
    name: &str,
    y_label: &'static str,
    rgb: [u8; 3],
    points: Vec<[f64; 2]>,
    u: Option<&[f64]>,
) -> Panel {
    let mut curves = vec![curve(name, rgb, points.clone())];
    if let Some(u) = u {
        let edge = |sign: f64| points.iter().zip(u).map(|(p, u)| [p[0], (p[1] + sign * 2.0 * u).max(0.0)]).collect();
        curves.push(Curve { dashed: true, ..curve(&format!("{name} ± 2u"), rgb, edge(1.0)) });
        curves.push(Curve { dashed: true, ..curve("", rgb, edge(-1.0)) });
    }
    Panel { title, x_label: "wavelength (nm)", y_label, curves, y_include: [0.0, 0.0] }
}

/// The panels of `preset`: reflectances (measured R∞, R and Rg when the preset keeps its
/// measurement, R∞ from S and K, and `r_from_s_k`, R re-computed over the background, when
/// given), S and K (with their ±2u band when the preset carries its uncertainty), and R0(X), T(X) of the renderer's tables in linear sRGB.
pub fn material_panels(preset: &Preset, r_from_s_k: Option<&[f64]>) -> Vec<Panel> {
    let wl = &preset.wavelengths_nm;
    let series = |v: &[f64]| -> Vec<[f64; 2]> { wl.iter().zip(v).map(|(&x, &y)| [x, y]).collect() };
    let r_inf: Vec<f64> = preset.s_per_mm.iter().zip(&preset.k_per_mm).map(|(&s, &k)| r_inf_from_s_k(s, k)).collect();
    let mut reflectance = Vec::new();
    if let Some(m) = &preset.measurement {
        reflectance.push(curve("R∞ measured", SERIES[0], series(&m.r_inf)));
        reflectance.push(curve("R measured", SERIES[1], series(&m.r)));
        reflectance.push(curve("Rg background", SERIES[2], series(&m.rg)));
    }
    reflectance.push(Curve { dashed: true, ..curve("R∞ from S, K", SERIES[3], series(&r_inf)) });
    if let Some(r) = r_from_s_k {
        reflectance.push(Curve { dashed: true, ..curve("R from S, K", SERIES[1], series(r)) });
    }
    let u = preset.uncertainty.as_ref();
    let xs = table_thicknesses_mm();
    let mut rt = Vec::new();
    for (c, (name, rgb)) in CHANNELS.into_iter().enumerate() {
        let r0 = xs.iter().zip(&preset.derived.r0_linear_srgb).map(|(&x, v)| [x, v[c]]).collect();
        let t = xs.iter().zip(&preset.derived.t_linear_srgb).map(|(&x, v)| [x, v[c]]).collect();
        rt.push(curve(&format!("R0 {name}"), rgb, r0));
        rt.push(Curve { dashed: true, ..curve(&format!("T {name}"), rgb, t) });
    }
    vec![
        Panel {
            title: "Reflectance",
            x_label: "wavelength (nm)",
            y_label: "reflectance",
            curves: reflectance,
            y_include: [0.0, 1.0],
        },
        coefficient(
            "S, scattering",
            "S",
            "S (1/mm)",
            SERIES[4],
            series(&preset.s_per_mm),
            u.map(|u| &u.u_s_per_mm[..]),
        ),
        coefficient(
            "K, absorption",
            "K",
            "K (1/mm)",
            SERIES[5],
            series(&preset.k_per_mm),
            u.map(|u| &u.u_k_per_mm[..]),
        ),
        Panel {
            title: "R0(X) solid, T(X) dashed, linear sRGB",
            x_label: "thickness X (mm)",
            y_label: "R0, T",
            curves: rt,
            y_include: [0.0, 1.0],
        },
    ]
}

/// `#rrggbb` (a preset's `r_inf_srgb_hex`) as sRGB bytes; `None` if it is not that.
pub fn hex_rgb(hex: &str) -> Option<[u8; 3]> {
    let digits = hex.strip_prefix('#').unwrap_or(hex);
    let v = u32::from_str_radix(digits, 16).ok().filter(|_| digits.len() == 6)?;
    Some([(v >> 16) as u8, (v >> 8) as u8, v as u8])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn four_panels_every_curve_and_channels_coloured_alike() {
        let p = rouge_model::look::builtin_preset("blush_01_petal").expect("a built-in preset");
        let r = vec![0.3; p.wavelengths_nm.len()];
        let panels = material_panels(&p, Some(&r));
        let names: Vec<Vec<&str>> = panels.iter().map(|p| p.curves.iter().map(|c| c.name.as_str()).collect()).collect();
        let measured = p.measurement.is_some();
        assert_eq!(names[0].len(), if measured { 5 } else { 2 });
        assert_eq!((names[1].clone(), names[2].clone()), (vec!["S"], vec!["K"]));
        assert_eq!(names[3], ["R0 R", "T R", "R0 G", "T G", "R0 B", "T B"]);
        for pair in panels[3].curves.chunks(2) {
            assert_eq!(pair[0].rgb, pair[1].rgb);
            assert!(!pair[0].dashed && pair[1].dashed);
        }
        assert_eq!(hex_rgb("#c0392b"), Some([0xc0, 0x39, 0x2b]));
        assert_eq!(hex_rgb("#c0392"), None);
        assert!(
            panels
                .iter()
                .flat_map(|p| &p.curves)
                .all(|c| c.points.iter().all(|q| q[0].is_finite() && q[1].is_finite()))
        );
    }
}
