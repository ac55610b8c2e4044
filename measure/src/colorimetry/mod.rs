//! CIE colorimetry on the working grid: spectrum → XYZ by summation, xyY, CIELAB, linear and
//! encoded sRGB, and CIEDE2000.
//!
//! Tables (CIE 1931 2° and CIE 1964 10° colour-matching functions; illuminants D65, D55, D50, A,
//! E, the fluorescent lamps FL2, FL7, FL11 and the white LED LED-B3 of \[CIE15\]) are in `data/cie/`, written by `python/gen_cie.py` from colour-science 0.4.7 exactly as its
//! `sd_to_XYZ(..., method="Integration", shape=SpectralShape(380, 780, 5))` aligns them, and
//! embedded at compile time. `python/test_colorimetry.py` checks XYZ, Lab and sRGB against
//! colour-science to 1e-6 for every illuminant and observer.
//!
//! # Conventions
//! * **XYZ** (\[CIE15\] §7.1, summation): `X = k Σ x̄(λ) S(λ) R(λ)` with
//!   `k = 100 / Σ ȳ(λ) S(λ)`, so the perfect reflector has `Y = 100`. The 5 nm interval cancels.
//! * **CIELAB** (\[CIE15\] §8.2.1) relative to the white of the same illuminant and observer,
//!   computed from the same tables (the perfect reflector's XYZ), so a non-selective grey has
//!   exactly `a* = b* = 0`.
//! * **sRGB** (\[IEC61966\], IEC 61966-2-1:1999): its published XYZ→RGB matrix applied to `XYZ/100`. For D65 no
//!   adaptation is applied (the XYZ are already relative to D65). For any other illuminant the
//!   XYZ are first adapted with the **Bradford** transform (\[Lam1985\], von Kries scaling in the
//!   Bradford cone space) from the computed white to the sRGB white point (x, y) = (0.3127,
//!   0.3290): the colour the sample would have if the eye were adapted to the illuminant, shown on a
//!   D65 display. With the 1964 10° observer the same matrix is used, an approximation (sRGB is
//!   defined for the 2° observer) that is customary and documented here.
//! * **Encoded sRGB** is not clipped: `12.92 L` for `L ≤ 0.0031308` (also for negative `L`),
//!   `1.055 L^{1/2.4} − 0.055` above, as colour-science's `eotf_inverse_sRGB`.

mod difference;

pub use difference::{delta_e_1976_raw, delta_e_2000, delta_e_2000_raw, delta_e_cmc_raw};

use crate::spectrum::{Spectrum, WORKING_LEN};
use std::borrow::Borrow;
use std::fmt;
use std::sync::OnceLock;

/// CIE standard illuminants available on the working grid.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum Illuminant {
    /// CIE D65, average daylight (6504 K); the sRGB white.
    D65,
    /// CIE D55.
    D55,
    /// CIE D50, the graphic-arts viewing illuminant.
    D50,
    /// CIE A, incandescent tungsten (2856 K).
    A,
    /// Equal-energy illuminant E.
    E,
    /// CIE FL2, cool-white standard fluorescent lamp (4230 K).
    Fl2,
    /// CIE FL7, broad-band daylight fluorescent lamp (6500 K).
    Fl7,
    /// CIE FL11, three-band (narrow tri-phosphor) fluorescent lamp (4000 K): the usual test
    /// illuminant of metamerism indices.
    Fl11,
    /// CIE LED-B3, phosphor-converted white LED (4103 K) of \[CIE15\] (2018) table 12.
    LedB3,
}

impl Illuminant {
    /// All illuminants, in table order.
    pub const ALL: [Illuminant; 9] = [
        Illuminant::D65,
        Illuminant::D55,
        Illuminant::D50,
        Illuminant::A,
        Illuminant::E,
        Illuminant::Fl2,
        Illuminant::Fl7,
        Illuminant::Fl11,
        Illuminant::LedB3,
    ];

    /// The name used in tables and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Illuminant::D65 => "D65",
            Illuminant::D55 => "D55",
            Illuminant::D50 => "D50",
            Illuminant::A => "A",
            Illuminant::E => "E",
            Illuminant::Fl2 => "FL2",
            Illuminant::Fl7 => "FL7",
            Illuminant::Fl11 => "FL11",
            Illuminant::LedB3 => "LED-B3",
        }
    }

    /// Parses `D65`, `d50`, `A`, `FL11` (or `F11`), `LED-B3`, ... (case-insensitive; the names
    /// are colour-science's keys of `SDS_ILLUMINANTS`).
    pub fn parse(s: &str) -> Option<Self> {
        let upper = s.trim().to_ascii_uppercase();
        // CIE 15 writes the fluorescent lamps F1-F12; colour-science keys them FL1-FL12.
        let name = match upper.strip_prefix('F') {
            Some(n) if !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()) => format!("FL{n}"),
            _ => upper,
        };
        Self::ALL.into_iter().find(|i| i.name() == name)
    }

    /// Relative spectral power on the working grid (as tabulated; the scale cancels).
    pub fn spd(self) -> &'static Spectrum {
        &tables().illuminants[self as usize]
    }
}

/// CIE standard colorimetric observers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum Observer {
    /// CIE 1931 2° standard observer.
    Cie1931,
    /// CIE 1964 10° standard observer.
    Cie1964,
}

impl Observer {
    /// Both observers.
    pub const ALL: [Observer; 2] = [Observer::Cie1931, Observer::Cie1964];

    /// The year used on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Observer::Cie1931 => "1931",
            Observer::Cie1964 => "1964",
        }
    }

    /// Parses `1931`, `2`, `1964`, `10` (also with a trailing `°`).
    pub fn parse(s: &str) -> Option<Self> {
        match s.trim().trim_end_matches('°') {
            "1931" | "2" => Some(Observer::Cie1931),
            "1964" | "10" => Some(Observer::Cie1964),
            _ => None,
        }
    }

    /// Colour-matching functions x̄, ȳ, z̄ on the working grid.
    pub fn cmfs(self) -> &'static [Spectrum; 3] {
        &tables().cmfs[self as usize]
    }
}

/// An illuminant seen by an observer: the reference every XYZ and Lab value is relative to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub struct Viewing {
    /// Illuminant.
    pub illuminant: Illuminant,
    /// Observer.
    pub observer: Observer,
}

impl Viewing {
    /// D65 and the 1931 2° observer: the default everywhere in Rouge.
    pub const D65_1931: Viewing = Viewing { illuminant: Illuminant::D65, observer: Observer::Cie1931 };
}

impl Default for Viewing {
    fn default() -> Self {
        Viewing::D65_1931
    }
}

impl fmt::Display for Viewing {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} / CIE {}", self.illuminant.name(), self.observer.name())
    }
}

/// Tristimulus values, scaled so the perfect reflector has `Y = 100`, under a [`Viewing`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Xyz {
    /// X, Y, Z.
    pub xyz: [f64; 3],
    /// The illuminant and observer they are relative to.
    pub viewing: Viewing,
}

impl Xyz {
    /// Chromaticity and luminance `[x, y, Y]`. A black (X+Y+Z = 0) gets the chromaticity of
    /// the white, as colour-science does.
    pub fn xyy(&self) -> [f64; 3] {
        let [x, y, z] = self.xyz;
        let sum = x + y + z;
        if sum == 0.0 {
            let w = Colorimeter::get(self.viewing).white().xyz;
            let ws = w[0] + w[1] + w[2];
            return [w[0] / ws, w[1] / ws, 0.0];
        }
        [x / sum, y / sum, y]
    }
}

/// CIELAB coordinates under a [`Viewing`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lab {
    /// L*, a*, b*.
    pub lab: [f64; 3],
    /// The illuminant and observer of the white they are relative to.
    pub viewing: Viewing,
}

/// Errors of colour computations.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ColorError {
    /// Two colours relative to different whites cannot be compared.
    #[error("cannot compare a colour under {0} with one under {1}: convert one of them first")]
    MixedViewing(Viewing, Viewing),
}

struct Tables {
    /// Indexed by `Observer as usize`: [x̄, ȳ, z̄].
    cmfs: [[Spectrum; 3]; 2],
    /// Indexed by `Illuminant as usize`.
    illuminants: [Spectrum; Illuminant::ALL.len()],
}

const CMFS_1931_CSV: &str = include_str!("../../../data/cie/cmfs_cie1931_2.csv");
const CMFS_1964_CSV: &str = include_str!("../../../data/cie/cmfs_cie1964_10.csv");
const ILLUMINANTS_CSV: &str = include_str!("../../../data/cie/illuminants.csv");

/// Parses an embedded table: `#` comments, a header with `wavelength_nm` first, 81 rows on the
/// working grid. The tables are part of the build, so a malformed one is a bug caught by the tests
/// (`tables_are_on_the_working_grid`), never a user error.
fn parse_table(text: &str, columns: &[&str]) -> Vec<Spectrum> {
    let mut lines = text.lines().map(str::trim).filter(|l| !l.is_empty() && !l.starts_with('#'));
    let header: Vec<&str> = lines.next().unwrap_or_default().split(',').collect();
    let index: Vec<usize> =
        columns.iter().map(|c| header.iter().position(|h| h.trim() == *c).unwrap_or(usize::MAX)).collect();
    let mut out = vec![[f64::NAN; WORKING_LEN]; columns.len()];
    for (row, line) in lines.enumerate().take(WORKING_LEN) {
        let cells: Vec<&str> = line.split(',').collect();
        for (c, &i) in index.iter().enumerate() {
            out[c][row] = cells.get(i).and_then(|v| v.trim().parse().ok()).unwrap_or(f64::NAN);
        }
    }
    out.into_iter().map(Spectrum).collect()
}

fn tables() -> &'static Tables {
    static TABLES: OnceLock<Tables> = OnceLock::new();
    TABLES.get_or_init(|| {
        let cmf = |text| -> [Spectrum; 3] {
            let v = parse_table(text, &["x_bar", "y_bar", "z_bar"]);
            [v[0], v[1], v[2]]
        };
        let names = Illuminant::ALL.map(Illuminant::name);
        let ill = parse_table(ILLUMINANTS_CSV, &names);
        Tables { cmfs: [cmf(CMFS_1931_CSV), cmf(CMFS_1964_CSV)], illuminants: std::array::from_fn(|i| ill[i]) }
    })
}

/// A 3×3 matrix, rows first.
pub(crate) type Mat3 = [[f64; 3]; 3];

/// XYZ → linear sRGB, IEC 61966-2-1:1999 (the published 4-decimal matrix).
pub const XYZ_TO_SRGB: Mat3 = [[3.2406, -1.5372, -0.4986], [-0.9689, 1.8758, 0.0415], [0.0557, -0.2040, 1.0570]];

/// sRGB reference white chromaticity (D65 as IEC 61966-2-1 rounds it).
pub const SRGB_WHITE_XY: [f64; 2] = [0.3127, 0.3290];

/// Bradford cone-response matrix (\[Lam1985\]).
pub const BRADFORD: Mat3 = [[0.8951, 0.2664, -0.1614], [-0.7502, 1.7135, 0.0367], [0.0389, -0.0685, 1.0296]];

pub(crate) fn mat_vec(m: &Mat3, v: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2])
}

fn mat_mul(a: &Mat3, b: &Mat3) -> Mat3 {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}

/// Inverse of a 3×3 matrix by the adjugate (the matrices here are well conditioned).
pub(crate) fn mat_inv(m: &Mat3) -> Mat3 {
    let c = |r0: usize, r1: usize, c0: usize, c1: usize| m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0];
    let cof: Mat3 = [
        [c(1, 2, 1, 2), -c(1, 2, 0, 2), c(1, 2, 0, 1)],
        [-c(0, 2, 1, 2), c(0, 2, 0, 2), -c(0, 2, 0, 1)],
        [c(0, 1, 1, 2), -c(0, 1, 0, 2), c(0, 1, 0, 1)],
    ];
    let det = m[0][0] * cof[0][0] + m[0][1] * cof[0][1] + m[0][2] * cof[0][2];
    std::array::from_fn(|i| std::array::from_fn(|j| cof[j][i] / det))
}

fn xy_to_xyz_unit(xy: [f64; 2]) -> [f64; 3] {
    [xy[0] / xy[1], 1.0, (1.0 - xy[0] - xy[1]) / xy[1]]
}

/// Bradford adaptation matrix from white `src` to white `dst` (both XYZ with Y = 1).
pub fn bradford_adaptation(src: [f64; 3], dst: [f64; 3]) -> Mat3 {
    let s = mat_vec(&BRADFORD, src);
    let d = mat_vec(&BRADFORD, dst);
    let scale: Mat3 = [[d[0] / s[0], 0.0, 0.0], [0.0, d[1] / s[1], 0.0], [0.0, 0.0, d[2] / s[2]]];
    mat_mul(&mat_inv(&BRADFORD), &mat_mul(&scale, &BRADFORD))
}

/// Precomputed weights for one [`Viewing`]: spectrum → XYZ → Lab / sRGB.
#[derive(Clone, Debug)]
pub struct Colorimeter {
    viewing: Viewing,
    /// `k x̄ S`, `k ȳ S`, `k z̄ S` on the working grid.
    weights: [[f64; WORKING_LEN]; 3],
    white: [f64; 3],
    /// XYZ/100 → linear sRGB, adaptation included.
    to_srgb: Mat3,
}

impl Colorimeter {
    /// Builds the weights for `viewing` (a few hundred flops; [`Colorimeter::get`] caches them).
    pub fn new(viewing: Viewing) -> Self {
        let cmfs = viewing.observer.cmfs();
        let spd = viewing.illuminant.spd();
        let norm: f64 = (0..WORKING_LEN).map(|i| cmfs[1].0[i] * spd.0[i]).sum();
        let k = 100.0 / norm;
        let weights: [[f64; WORKING_LEN]; 3] =
            std::array::from_fn(|c| std::array::from_fn(|i| k * cmfs[c].0[i] * spd.0[i]));
        let white: [f64; 3] = std::array::from_fn(|c| weights[c].iter().sum());
        let to_srgb = if viewing.illuminant == Illuminant::D65 {
            XYZ_TO_SRGB
        } else {
            let ws = white[0] + white[1] + white[2];
            let src = xy_to_xyz_unit([white[0] / ws, white[1] / ws]);
            let dst = xy_to_xyz_unit(SRGB_WHITE_XY);
            mat_mul(&XYZ_TO_SRGB, &bradford_adaptation(src, dst))
        };
        Colorimeter { viewing, weights, white, to_srgb }
    }

    /// A shared colorimeter for `viewing`, built once.
    pub fn get(viewing: Viewing) -> &'static Colorimeter {
        static ALL: OnceLock<Vec<Colorimeter>> = OnceLock::new();
        let all = ALL.get_or_init(|| {
            Observer::ALL
                .into_iter()
                .flat_map(|observer| {
                    Illuminant::ALL
                        .into_iter()
                        .map(move |illuminant| Colorimeter::new(Viewing { illuminant, observer }))
                })
                .collect()
        });
        &all[viewing.observer as usize * Illuminant::ALL.len() + viewing.illuminant as usize]
    }

    /// The viewing conditions.
    pub fn viewing(&self) -> Viewing {
        self.viewing
    }

    /// The weights `k·cmf·S` (rows X, Y, Z) over the working grid.
    pub fn weights(&self) -> &[[f64; WORKING_LEN]; 3] {
        &self.weights
    }

    /// XYZ of the perfect reflector (Y = 100).
    pub fn white(&self) -> Xyz {
        Xyz { xyz: self.white, viewing: self.viewing }
    }

    /// Tristimulus values of a reflectance (or transmittance) spectrum, by summation
    /// (\[CIE15\] §7.1; `k` makes the perfect reflector's Y = 100).
    ///
    /// # Examples
    ///
    /// The perfect reflector under D65 with the 1931 observer is the computed white,
    /// XYZ = (95.0430, 100, 108.8801) as colour-science 0.4.7 gives it (`sd_to_XYZ`,
    /// integration, 380-780 nm / 5 nm); an 18 % grey is 0.18 of it.
    ///
    /// ```
    /// use rouge_measure::{Colorimeter, Spectrum, Viewing};
    ///
    /// let c = Colorimeter::get(Viewing::D65_1931);
    /// let white = c.xyz(&Spectrum::constant(1.0)).xyz;
    /// for (got, want) in white.iter().zip([95.042_966_94, 100.0, 108.880_054_7]) {
    ///     assert!((got - want).abs() < 1e-6, "{white:?}");
    /// }
    /// let grey = c.xyz(&Spectrum::constant(0.18)).xyz;
    /// assert!((grey[1] - 18.0).abs() < 1e-12);
    /// ```
    pub fn xyz(&self, spectrum: &Spectrum) -> Xyz {
        let xyz = std::array::from_fn(|c| self.weights[c].iter().zip(&spectrum.0).map(|(w, r)| w * r).sum());
        Xyz { xyz, viewing: self.viewing }
    }

    /// Tristimulus values of many spectra at once (the same sums as [`Colorimeter::xyz`] in
    /// another order: eight partial sums per channel, so the compiler vectorises them; results
    /// agree to a few ulps). `out` must be as long as `spectra`.
    pub fn xyz_many(&self, spectra: &[Spectrum], out: &mut [[f64; 3]]) {
        let n = spectra.len().min(out.len());
        let (spectra, out) = (&spectra[..n], &mut out[..n]);
        dispatch!(xyz_many_generic, xyz_many_avx2, xyz_many_avx512, (&self.weights, spectra, out))
    }

    /// [`Colorimeter::xyz_many`] on bare rows of working-grid values (a C-ordered
    /// `spectra × 81` buffer, as numpy hands it over, read in place).
    pub fn xyz_many_rows(&self, rows: &[[f64; WORKING_LEN]], out: &mut [[f64; 3]]) {
        let n = rows.len().min(out.len());
        let (rows, out) = (&rows[..n], &mut out[..n]);
        dispatch!(xyz_many_generic, xyz_many_avx2, xyz_many_avx512, (&self.weights, rows, out))
    }

    /// CIELAB of `xyz` relative to this viewing's white (\[CIE15\] §8.2.1, eq. 8.1-8.3).
    ///
    /// # Examples
    ///
    /// An 18 % grey is neutral under any illuminant, with L* = 116·∛0.18 − 16 = 49.4961.
    ///
    /// ```
    /// use rouge_measure::{Colorimeter, Illuminant, Observer, Spectrum, Viewing};
    ///
    /// let c = Colorimeter::get(Viewing { illuminant: Illuminant::A, observer: Observer::Cie1964 });
    /// let [l, a, b] = c.lab(&c.xyz(&Spectrum::constant(0.18))).lab;
    /// assert!((l - 49.496_107_6).abs() < 1e-6, "{l}");
    /// assert!(a.abs() < 1e-12 && b.abs() < 1e-12, "{a} {b}");
    /// ```
    ///
    /// # Panics
    /// Never; an `xyz` of another viewing is a logic error caught in debug builds.
    pub fn lab(&self, xyz: &Xyz) -> Lab {
        debug_assert_eq!(xyz.viewing, self.viewing);
        Lab { lab: xyz_to_lab_raw(xyz.xyz, self.white), viewing: self.viewing }
    }

    /// Linear sRGB (white = 1) of `xyz`; adapted to D65 by Bradford when the illuminant is not D65.
    pub fn srgb_linear(&self, xyz: &Xyz) -> [f64; 3] {
        debug_assert_eq!(xyz.viewing, self.viewing);
        mat_vec(&self.to_srgb, xyz.xyz.map(|v| v / 100.0))
    }

    /// Encoded (gamma) sRGB, not clipped.
    pub fn srgb(&self, xyz: &Xyz) -> [f64; 3] {
        self.srgb_linear(xyz).map(srgb_encode)
    }
}

#[inline(always)]
fn xyz_many_loop<S: Borrow<[f64; WORKING_LEN]>>(w: &[[f64; WORKING_LEN]; 3], spectra: &[S], out: &mut [[f64; 3]]) {
    const LANES: usize = 8;
    const FULL: usize = WORKING_LEN / LANES * LANES;
    for (s, o) in spectra.iter().zip(out.iter_mut()) {
        let s: &[f64; WORKING_LEN] = s.borrow();
        for c in 0..3 {
            let mut acc = [0.0f64; LANES];
            for base in (0..FULL).step_by(LANES) {
                for l in 0..LANES {
                    acc[l] += w[c][base + l] * s[base + l];
                }
            }
            let tail: f64 = w[c][FULL..].iter().zip(&s[FULL..]).map(|(a, b)| a * b).sum();
            o[c] = ((acc[0] + acc[1]) + (acc[2] + acc[3])) + ((acc[4] + acc[5]) + (acc[6] + acc[7])) + tail;
        }
    }
}

fn xyz_many_generic<S: Borrow<[f64; WORKING_LEN]>>(w: &[[f64; WORKING_LEN]; 3], spectra: &[S], out: &mut [[f64; 3]]) {
    xyz_many_loop(w, spectra, out)
}
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn xyz_many_avx2<S: Borrow<[f64; WORKING_LEN]>>(w: &[[f64; WORKING_LEN]; 3], spectra: &[S], out: &mut [[f64; 3]]) {
    xyz_many_loop(w, spectra, out)
}
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,avx512dq,avx512vl,fma")]
fn xyz_many_avx512<S: Borrow<[f64; WORKING_LEN]>>(w: &[[f64; WORKING_LEN]; 3], spectra: &[S], out: &mut [[f64; 3]]) {
    xyz_many_loop(w, spectra, out)
}

/// CIELAB of tristimulus values `xyz` relative to the white `white` (\[CIE15\] eq. 8.1-8.3,
/// with the linear segment below (24/116)³).
pub fn xyz_to_lab_raw(xyz: [f64; 3], white: [f64; 3]) -> [f64; 3] {
    let f = |t: f64| {
        if t > (24.0f64 / 116.0).powi(3) { t.cbrt() } else { 841.0 / 108.0 * t + 16.0 / 116.0 }
    };
    let [fx, fy, fz] = std::array::from_fn(|c| f(xyz[c] / white[c]));
    [116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)]
}

/// The IEC 61966-2-1 linear sRGB → XYZ matrix (white = Y 1).
const SRGB_TO_XYZ: [[f64; 3]; 3] = [[0.4124, 0.3576, 0.1805], [0.2126, 0.7152, 0.0722], [0.0193, 0.1192, 0.9505]];

/// CIELAB of a linear sRGB colour, against the sRGB primaries' own D65 white (linear RGB
/// 1, 1, 1): how the renderer's outputs are compared with each other (golden images, studies),
/// where the display's white is the reference rather than a measured illuminant.
pub fn linear_srgb_to_lab(rgb: [f64; 3]) -> [f64; 3] {
    let white = std::array::from_fn(|i| SRGB_TO_XYZ[i].iter().sum());
    xyz_to_lab_raw(mat_vec(&SRGB_TO_XYZ, rgb), white)
}

/// sRGB transfer function (IEC 61966-2-1), applied as colour-science's `eotf_inverse_sRGB`:
/// linear below 0.0031308 (negative values included), power law above; not clipped.
#[inline]
pub fn srgb_encode(linear: f64) -> f64 {
    if linear <= 0.003_130_8 { 12.92 * linear } else { 1.055 * linear.powf(1.0 / 2.4) - 0.055 }
}

/// Inverse of [`srgb_encode`].
#[inline]
pub fn srgb_decode(encoded: f64) -> f64 {
    if encoded <= 0.040_45 { encoded / 12.92 } else { ((encoded + 0.055) / 1.055).powf(2.4) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tables_are_on_the_working_grid() {
        for obs in Observer::ALL {
            for c in obs.cmfs() {
                // The 10° functions dip slightly below zero in places; only finiteness is universal.
                assert!(c.0.iter().all(|v| v.is_finite() && *v > -1e-3), "{obs:?}");
            }
        }
        for ill in Illuminant::ALL {
            // LED-B3 emits nothing at 380 nm; every SPD is finite, ≥ 0 and somewhere positive.
            assert!(ill.spd().0.iter().all(|v| v.is_finite() && *v >= 0.0), "{ill:?}");
            assert!(ill.spd().0.iter().sum::<f64>() > 0.0, "{ill:?}");
        }
        assert_eq!(Illuminant::parse("f11"), Some(Illuminant::Fl11));
        assert_eq!(Illuminant::parse("led-b3"), Some(Illuminant::LedB3));
        assert_eq!(Illuminant::parse("F"), None);
        let w = crate::spectrum::working_wavelengths_nm();
        let first_rows: Vec<f64> = CMFS_1931_CSV
            .lines()
            .filter(|l| !l.starts_with('#'))
            .skip(1)
            .filter_map(|l| l.split(',').next()?.trim().parse().ok())
            .collect();
        assert_eq!(first_rows, w.to_vec());
    }
}
