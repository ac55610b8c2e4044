//! Finishes: how a cosmetic's surface reflects, beyond its colour. Makeup is chosen by finish as
//! much as by shade (matte, satin, dewy, gloss), and a formulator measures it with a gloss meter.
//!
//! A finish is the layer's specular lobe ([`Specular`]: roughness and index, the lobe of
//! [`crate::specular`]) and two properties of the film ([`Finish`]):
//! - **clarity**, the part of the light reflected specularly *below* the layer (by the skin or
//!   a lower layer) that a fully formed layer lets through specularly: 1 for a clear binder,
//!   less for a powder or a matte foundation whose fillers scatter it into the diffuse. This is
//!   how a powder takes away the shine of oily skin while a gloss over a lipstick does not.
//! - **levelling**, how much the film flattens the skin's relief: the residual depth of a pore
//!   of depth d under a film of thickness t is d·exp(−levelling·t/d) ([`pore_relief`]). 1 is a
//!   fluid that levels as it dries (a primer or a gloss), 0 a film that follows the relief.
//!
//! *Choice*: the defaults per kind ([`FinishKind::defaults`]) are the writer's, spread between a
//! powder and a gloss; measured products should carry their own roughness from gloss readings
//! ([`fit_gloss`]). The relief law is the simplest monotone one with the right limits (no film:
//! the full pore; a film much thicker than the pore: none), not a measured levelling curve.
//!
//! **Gloss meters** (\[ISO2813\]): a collimated beam at 20°, 60° or 85° from the normal, a
//! receptor aperture centred on the mirror direction (20°: 1.8° in the plane of incidence ×
//! 3.6° across it; 60°: 4.4° × 11.7°; 85°: 4.0° × 6.0°), calibrated so that polished black glass
//! of index 1.567 reads 100 gloss units (GU). A surface with Rouge's lobe then reads
//!   GU(θ) = 100 · ∫_aperture f_r(l, v) cos θ_v dω_v / F(θ; 1.567),
//! the flux into the aperture relative to the standard's mirror reflectance, both with Schlick's
//! Fresnel (so a perfectly smooth surface of index 1.567 reads exactly 100, [`gloss_units`]).
//! The source's own aperture is taken as a point and the light scattered below the surface into
//! the aperture is ignored: gloss is measured on films over black, where it is small.

use crate::analysis::optimize::golden_section;
use crate::preset::Specular;
use crate::specular::{fresnel_f0, kelemen};
use glam::DVec3;
use serde::{Deserialize, Serialize};

/// A named finish, with its default lobe and film properties.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FinishKind {
    /// Powders and matte foundations: a broad lobe, fillers that scatter the shine below.
    Matte,
    /// Between matte and dewy: most foundations.
    Satin,
    /// A moist glow: a sharper lobe, a nearly clear film.
    Dewy,
    /// Lip gloss, top coats: a sharp lobe, a clear film that levels.
    Gloss,
}

impl FinishKind {
    /// Every kind, from the most matte.
    pub const ALL: [FinishKind; 4] = [FinishKind::Matte, FinishKind::Satin, FinishKind::Dewy, FinishKind::Gloss];

    /// The kind's name in files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            FinishKind::Matte => "matte",
            FinishKind::Satin => "satin",
            FinishKind::Dewy => "dewy",
            FinishKind::Gloss => "gloss",
        }
    }

    /// The kind named `name` (`matte`, `satin`, `dewy` or `gloss`).
    pub fn from_name(name: &str) -> Option<FinishKind> {
        FinishKind::ALL.into_iter().find(|k| k.name() == name)
    }

    /// *Choice*: the default lobe and film of the kind (see the module doc). At 60° the lobes
    /// read about 1 (matte), 3.1 (satin), 12 (dewy) and 45 GU (gloss): under 10 GU is the usual
    /// class of matte films, and lip glosses read tens of GU.
    pub fn defaults(self) -> (Specular, Finish) {
        let (roughness, ior, clarity, levelling) = match self {
            FinishKind::Matte => (0.45, 1.45, 0.3, 0.4),
            FinishKind::Satin => (0.25, 1.45, 0.7, 0.6),
            FinishKind::Dewy => (0.12, 1.48, 0.9, 0.8),
            FinishKind::Gloss => (0.04, 1.50, 1.0, 1.0),
        };
        (Specular { roughness, ior }, Finish { kind: self, clarity, levelling, shimmer: None, glitter: None })
    }
}

/// A layer's finish (preset schema version 2, field `finish`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Finish {
    /// The named finish.
    pub kind: FinishKind,
    /// The part of the light reflected specularly below the layer that it passes specularly, in
    /// [0, 1].
    pub clarity: f64,
    /// How much the film flattens the skin's relief, in [0, 1] ([`pore_relief`]).
    pub levelling: f64,
    /// Pearlescent platelets in the film, if any (shimmer).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shimmer: Option<Shimmer>,
    /// Glitter flakes in the film, if any.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub glitter: Option<Glitter>,
}

/// Glitter: discrete mirror flakes in the film, each large enough to be seen on its own, so that
/// the layer sparkles (a point of light wherever a flake's normal lies within a light's disc of
/// the half vector) rather than shines. The flake field and its rendering are
/// `rouge_render::glitter` (docs/FINISHES.md "Glitter").
///
/// *Choice*: flakes are squares of edge `size_um`, one candidate per grid cell of twice that
/// edge, so they never overlap; hence `density_per_mm2` · (2 · size)² ≤ 1.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Glitter {
    /// Edge of a flake, µm, 20-2000 (cosmetic glitters: 50-1000 µm).
    pub size_um: f64,
    /// Flakes per mm² of the film's surface at the preset's thickness (a thinner film has
    /// proportionally fewer), in (0, 1/(2·size)²].
    pub density_per_mm2: f64,
    /// Reflectance of a flake's face, linear sRGB, each channel in [0, 1].
    pub color: [f64; 3],
    /// RMS slope of the flakes' normals about the surface normal (a Beckmann roughness: the
    /// slopes are Gaussian, σ = spread/√2 per axis), in (0, 1].
    pub spread: f64,
}

impl Glitter {
    /// Checks the ranges; the message names the field.
    ///
    /// # Errors
    /// A field outside its range (see the fields) or not finite.
    pub fn validate(&self) -> Result<(), String> {
        if !(20.0..=2000.0).contains(&self.size_um) {
            return Err(format!("`finish.glitter.size_um` = {} must be in [20, 2000]", self.size_um));
        }
        let cell_mm = 2.0 * self.size_um * 1e-3;
        let most = 1.0 / (cell_mm * cell_mm);
        if !(self.density_per_mm2 > 0.0 && self.density_per_mm2 <= most * (1.0 + 1e-9)) {
            return Err(format!(
                "`finish.glitter.density_per_mm2` = {} must be in (0, {most:.4}] (flakes of {} µm never overlap: at most one per {:.3} mm square)",
                self.density_per_mm2, self.size_um, cell_mm
            ));
        }
        if let Some(c) = self.color.iter().find(|c| !(0.0..=1.0).contains(*c)) {
            return Err(format!("`finish.glitter.color` has {c}: each channel must be in [0, 1]"));
        }
        if !(self.spread > 0.0 && self.spread <= 1.0) {
            return Err(format!("`finish.glitter.spread` = {} must be in (0, 1]", self.spread));
        }
        Ok(())
    }
}

/// Pearlescent (shimmer) pigment in a film: mica platelets coated with rutile TiO₂
/// ([`crate::thin_film::CoatedPlatelet`]) lying roughly parallel to the surface. Their
/// interference colour is reflected as a second lobe of the layer: a Beckmann lobe of the
/// platelets' tilt `spread` whose Fresnel factor is the platelets' reflectance at the half
/// vector's angle (in the binder), times `strength`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Shimmer {
    /// Thickness of the TiO₂ film, nm, 0-1000 (at normal incidence about 50 silver, 70 gold, 90
    /// red, 105 violet, 125 blue, 145 green; thicker films repeat the sequence, paler).
    pub film_nm: f64,
    /// The part of the film's area the platelets cover, facing up, in [0, 1].
    pub strength: f64,
    /// RMS tilt of the platelets (a Beckmann roughness), in (0, 1].
    pub spread: f64,
}

impl Shimmer {
    /// The platelet of this shimmer.
    pub fn platelet(&self) -> crate::thin_film::CoatedPlatelet {
        crate::thin_film::CoatedPlatelet::mica_tio2(self.film_nm)
    }

    /// The platelets' reflectance as linear sRGB (D65, CIE 1931) at `entries` values of the
    /// cosine of the angle in air between the half vector and the light, c = i/(entries − 1):
    /// the table the lighting pass reads.
    pub fn interference_table(&self, entries: usize) -> Vec<[f64; 3]> {
        let colorimeter = crate::colorimetry::Colorimeter::get(crate::colorimetry::Viewing::D65_1931);
        let platelet = self.platelet();
        (0..entries)
            .map(|i| {
                let cos_air = i as f64 / (entries.max(2) - 1) as f64;
                let theta = crate::thin_film::angle_in_binder(cos_air.acos(), platelet.binder_index);
                colorimeter.srgb_linear(&colorimeter.xyz(&platelet.spectrum(theta)))
            })
            .collect()
    }
}

impl Finish {
    /// Checks the ranges; the message names the field.
    ///
    /// # Errors
    /// `clarity` or `levelling` outside [0, 1] or not finite.
    pub fn validate(&self) -> Result<(), String> {
        for (field, v) in [("clarity", self.clarity), ("levelling", self.levelling)] {
            if !(0.0..=1.0).contains(&v) {
                return Err(format!("`finish.{field}` = {v} must be in [0, 1]"));
            }
        }
        if let Some(s) = &self.shimmer {
            if !(0.0..=1000.0).contains(&s.film_nm) {
                return Err(format!("`finish.shimmer.film_nm` = {} must be in [0, 1000]", s.film_nm));
            }
            if !(0.0..=1.0).contains(&s.strength) {
                return Err(format!("`finish.shimmer.strength` = {} must be in [0, 1]", s.strength));
            }
            if !(s.spread > 0.0 && s.spread <= 1.0) {
                return Err(format!("`finish.shimmer.spread` = {} must be in (0, 1]", s.spread));
            }
        }
        if let Some(g) = &self.glitter {
            g.validate()?;
        }
        Ok(())
    }
}

/// The residual relief, as a fraction of the bare skin's, of a pore `pore_depth_mm` deep under a
/// film `thickness_mm` thick with `levelling` in [0, 1]: exp(−levelling·t/d) (module doc). 1 for
/// no film or a film that follows the relief; falls monotonically with thickness. Non-positive
/// or non-finite inputs count as no film (1), a pore of no depth as filled (0).
pub fn pore_relief(thickness_mm: f64, pore_depth_mm: f64, levelling: f64) -> f64 {
    if !(thickness_mm > 0.0 && levelling > 0.0 && thickness_mm.is_finite()) {
        return 1.0;
    }
    if pore_depth_mm.is_nan() || pore_depth_mm <= 0.0 {
        return 0.0;
    }
    (-levelling.min(1.0) * thickness_mm / pore_depth_mm).exp()
}

/// The three geometries of a gloss meter (\[ISO2813\]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GlossGeometry {
    /// 20°: high-gloss surfaces (above ~70 GU at 60°).
    Deg20,
    /// 60°: every surface; the reference geometry.
    Deg60,
    /// 85°: low-gloss surfaces (below ~10 GU at 60°), the sheen of matte films.
    Deg85,
}

/// Refractive index of the black-glass gloss standard (\[ISO2813\]): 100 GU at every angle.
pub const GLOSS_STANDARD_IOR: f64 = 1.567;

impl GlossGeometry {
    /// Every geometry.
    pub const ALL: [GlossGeometry; 3] = [GlossGeometry::Deg20, GlossGeometry::Deg60, GlossGeometry::Deg85];

    /// Angle of incidence from the normal, degrees.
    pub fn incidence_deg(self) -> f64 {
        match self {
            GlossGeometry::Deg20 => 20.0,
            GlossGeometry::Deg60 => 60.0,
            GlossGeometry::Deg85 => 85.0,
        }
    }

    /// The receptor aperture, degrees: in the plane of incidence, across it (\[ISO2813\]).
    pub fn receptor_deg(self) -> (f64, f64) {
        match self {
            GlossGeometry::Deg20 => (1.8, 3.6),
            GlossGeometry::Deg60 => (4.4, 11.7),
            GlossGeometry::Deg85 => (4.0, 6.0),
        }
    }
}

/// The gloss units a surface with the lobe `specular` reads at `geometry` (module doc).
///
/// The integral over the aperture is taken over the half vectors' slopes (p, q) rather than
/// over view directions, so that lobes far narrower than the aperture (at 85° a smooth film's
/// lobe is a few hundredths of a degree across) are resolved as well as broad ones: v is the
/// mirror image of l about h = (−p, −q, 1)/√(1 + p² + q²), dω_v = 4 (h·v) dω_h and
/// dω_h = cos³θ_h dp dq, and the midpoint rule runs over the slopes whose mirror directions can
/// reach the aperture (in the plane of incidence a tilt δ of h turns v by 2δ, across it by
/// 2δ cos θ; 1.5 × that, within 6 m of the mean where the Beckmann density is below e⁻³⁶).
pub fn gloss_units(specular: Specular, geometry: GlossGeometry) -> f64 {
    let theta = geometry.incidence_deg().to_radians();
    let (a, b) = geometry.receptor_deg();
    let (half_a, half_b) = (0.5 * a.to_radians(), 0.5 * b.to_radians());
    let m = specular.roughness;
    let f0 = fresnel_f0(specular.ior);
    let l = DVec3::new(-theta.sin(), 0.0, theta.cos());
    let p_max = (1.5 * half_a / 2.0).min(6.0 * m);
    let q_max = (1.5 * half_b / (2.0 * theta.cos())).min(6.0 * m);
    let cells = 128;
    let (dp, dq) = (2.0 * p_max / cells as f64, 2.0 * q_max / cells as f64);
    let mut flux = 0.0;
    for i in 0..cells {
        let p = -p_max + (i as f64 + 0.5) * dp;
        for j in 0..cells {
            let q = -q_max + (j as f64 + 0.5) * dq;
            let h = DVec3::new(-p, -q, 1.0).normalize();
            let h_dot_l = h.dot(l);
            if h_dot_l <= 0.0 {
                continue;
            }
            let v = 2.0 * h_dot_l * h - l;
            let (alpha, beta) = (v.x.atan2(v.z), v.y.clamp(-1.0, 1.0).asin());
            if v.z <= 0.0 || (alpha - theta).abs() > half_a || beta.abs() > half_b {
                continue;
            }
            let jacobian = 4.0 * h_dot_l * h.z.powi(3) * dp * dq;
            flux += kelemen(DVec3::Z, l, v, m, f0) * v.z * jacobian;
        }
    }
    let standard = crate::specular::schlick(fresnel_f0(GLOSS_STANDARD_IOR), theta.cos());
    100.0 * flux / standard
}

/// A gloss reading: geometry and gloss units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GlossReading {
    /// The geometry.
    pub geometry: GlossGeometry,
    /// Gloss units read.
    pub gu: f64,
}

/// The roughness fitted to gloss readings, and how well it reproduces them.
#[derive(Clone, Debug, PartialEq)]
pub struct GlossFit {
    /// The lobe: the fitted roughness with the given index.
    pub specular: Specular,
    /// The kind whose default roughness is nearest (in log roughness).
    pub nearest_kind: FinishKind,
    /// Per reading: geometry, measured GU, GU of the fitted lobe.
    pub readings: Vec<(GlossGeometry, f64, f64)>,
}

/// Fits the roughness of a lobe of index `ior` to gloss `readings` (one or more geometries):
/// least squares in log(1 + GU), so that 2 GU against 4 weighs like 40 against 80, by
/// golden-section search over roughness in [0.01, 1] (gloss falls monotonically with roughness
/// at every geometry, so the fit is well posed with one reading).
///
/// # Errors
/// No readings, a geometry given twice, a reading not finite or outside [0, 200] GU (meters
/// read up to ~2000 GU on mirrors, but films do not exceed the standard by much), or `ior`
/// outside [1, 3]. The message names the reading.
pub fn fit_gloss(readings: &[GlossReading], ior: f64) -> Result<GlossFit, String> {
    if readings.is_empty() {
        return Err("no gloss readings: give at least one of 20°, 60°, 85°".into());
    }
    if !(1.0..=3.0).contains(&ior) {
        return Err(format!("index {ior}: must be in [1, 3]"));
    }
    for (i, r) in readings.iter().enumerate() {
        if !(0.0..=200.0).contains(&r.gu) {
            return Err(format!("gloss at {}° = {} GU: must be in [0, 200]", r.geometry.incidence_deg(), r.gu));
        }
        if readings[..i].iter().any(|q| q.geometry == r.geometry) {
            return Err(format!("gloss at {}° given twice", r.geometry.incidence_deg()));
        }
    }
    let misfit = |log_m: f64| {
        let specular = Specular { roughness: log_m.exp(), ior };
        readings.iter().map(|r| (gloss_units(specular, r.geometry).ln_1p() - r.gu.ln_1p()).powi(2)).sum::<f64>()
    };
    let (log_m, _) = golden_section(misfit, 0.01f64.ln(), 0.0, 1e-4);
    let specular = Specular { roughness: log_m.exp(), ior };
    let nearest_kind = FinishKind::ALL
        .into_iter()
        .min_by(|a, b| {
            let d = |k: FinishKind| (k.defaults().0.roughness.ln() - log_m).abs();
            d(*a).total_cmp(&d(*b))
        })
        .unwrap_or(FinishKind::Satin);
    let readings = readings.iter().map(|r| (r.geometry, r.gu, gloss_units(specular, r.geometry))).collect();
    Ok(GlossFit { specular, nearest_kind, readings })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_standard_reads_100_at_every_angle_and_rough_surfaces_less() {
        for g in GlossGeometry::ALL {
            // A nearly smooth surface of the standard's index: all of the lobe in the aperture.
            let smooth = gloss_units(Specular { roughness: 0.0005, ior: GLOSS_STANDARD_IOR }, g);
            assert!((smooth - 100.0).abs() < 0.5, "{g:?}: {smooth}");
            // Monotone in roughness: flat (to the integration's 1e-4) while the whole lobe fits
            // in the aperture, then falling.
            let mut last = f64::INFINITY;
            for m in [0.002, 0.005, 0.01, 0.03, 0.1, 0.2, 0.35, 0.6, 1.0] {
                let gu = gloss_units(Specular { roughness: m, ior: 1.5 }, g);
                assert!(gu.is_finite() && gu > 0.0 && gu < last * (1.0 + 1e-4), "{g:?}, m {m}: {gu} after {last}");
                if m >= 0.03 {
                    assert!(gu < 0.9 * last, "{g:?}, m {m}: {gu} after {last}");
                }
                last = gu;
            }
        }
        // A lower index reads less (less Fresnel reflectance).
        let at = |ior| gloss_units(Specular { roughness: 0.05, ior }, GlossGeometry::Deg60);
        assert!(at(1.4) < at(1.5) && at(1.5) < at(1.6));
    }

    #[test]
    fn the_finishes_read_as_their_names_say() {
        // 60° gloss: matte below 5 GU (under 10 GU is the usual class of matte films), gloss
        // tens of GU.
        let gu = |k: FinishKind| gloss_units(k.defaults().0, GlossGeometry::Deg60);
        assert!(gu(FinishKind::Matte) < 5.0, "matte {}", gu(FinishKind::Matte));
        assert!(gu(FinishKind::Gloss) > 30.0, "gloss {}", gu(FinishKind::Gloss));
        for w in FinishKind::ALL.windows(2) {
            assert!(gu(w[0]) < gu(w[1]), "{:?} vs {:?}", w[0], w[1]);
        }
        for k in FinishKind::ALL {
            assert_eq!(FinishKind::from_name(k.name()), Some(k));
            assert!(k.defaults().1.validate().is_ok());
        }
    }

    #[test]
    fn gloss_readings_give_back_the_roughness_that_made_them() {
        for m in [0.03, 0.08, 0.2, 0.45] {
            let truth = Specular { roughness: m, ior: 1.5 };
            let readings: Vec<_> =
                GlossGeometry::ALL.map(|g| GlossReading { geometry: g, gu: gloss_units(truth, g) }).into();
            let fit = fit_gloss(&readings, 1.5).expect("fit");
            assert!((fit.specular.roughness / m - 1.0).abs() < 2e-3, "m {m}: {:?}", fit.specular);
            // One reading is enough.
            let one = fit_gloss(&readings[1..2], 1.5).expect("fit 60°");
            assert!((one.specular.roughness / m - 1.0).abs() < 2e-3, "60° only, m {m}");
        }
        let g = |gu| GlossReading { geometry: GlossGeometry::Deg60, gu };
        assert!(fit_gloss(&[], 1.5).unwrap_err().contains("no gloss"));
        assert!(fit_gloss(&[g(f64::NAN)], 1.5).unwrap_err().contains("60°"));
        assert!(fit_gloss(&[g(-1.0)], 1.5).is_err());
        assert!(fit_gloss(&[g(50.0), g(40.0)], 1.5).unwrap_err().contains("twice"));
        assert!(fit_gloss(&[g(50.0)], 0.5).unwrap_err().contains("index"));
        // A gloss beyond the smoothest lobe's reading fits the smoothest roughness, not NaN.
        let fit = fit_gloss(&[g(180.0)], 1.5).expect("fit");
        assert!((fit.specular.roughness - 0.01).abs() < 1e-3, "{:?}", fit.specular);
    }

    #[test]
    fn pore_relief_falls_monotonically_with_thickness() {
        let mut last = 1.0;
        for t_um in [0.0, 2.0, 5.0, 10.0, 20.0, 40.0, 80.0] {
            let r = pore_relief(t_um * 1e-3, 0.03, 0.8);
            assert!(r <= last && (0.0..=1.0).contains(&r), "{t_um} µm: {r}");
            if t_um > 0.0 {
                assert!(r < last);
            }
            last = r;
        }
        assert_eq!(pore_relief(0.0, 0.03, 1.0), 1.0);
        assert_eq!(pore_relief(0.02, 0.03, 0.0), 1.0, "a film that follows the relief");
        assert_eq!(pore_relief(0.02, 0.0, 1.0), 0.0, "no pore");
        assert_eq!(pore_relief(f64::NAN, 0.03, 1.0), 1.0);
        assert_eq!(pore_relief(f64::INFINITY, 0.03, 1.0), 1.0);
        assert!(pore_relief(0.02, 0.03, 0.3) > pore_relief(0.02, 0.03, 0.9), "levelling flattens");
    }

    #[test]
    fn a_shimmers_colour_changes_with_angle() {
        let gold = Shimmer { film_nm: 110.0, strength: 0.5, spread: 0.2 };
        let table = gold.interference_table(64);
        assert_eq!(table.len(), 64);
        assert!(table.iter().flatten().all(|v| v.is_finite()));
        let (normal, oblique) = (table[63], table[20]);
        let chroma =
            |c: [f64; 3]| c.iter().copied().fold(f64::MIN, f64::max) - c.iter().copied().fold(f64::MAX, f64::min);
        let hue_shift = (0..3).map(|i| (normal[i] / normal[1] - oblique[i] / oblique[1]).abs()).fold(0.0, f64::max);
        assert!(chroma(normal) > 0.02 && hue_shift > 0.05, "{normal:?} against {oblique:?}");
        let mut f = FinishKind::Satin.defaults().1;
        f.shimmer = Some(Shimmer { spread: 0.0, ..gold });
        assert!(f.validate().unwrap_err().contains("shimmer.spread"));
        f.shimmer = Some(Shimmer { film_nm: 2000.0, ..gold });
        assert!(f.validate().unwrap_err().contains("shimmer.film_nm"));
    }

    #[test]
    fn bad_glitter_names_the_field() {
        let good = Glitter { size_um: 100.0, density_per_mm2: 10.0, color: [0.9, 0.8, 0.5], spread: 0.3 };
        let mut f = FinishKind::Gloss.defaults().1;
        f.glitter = Some(good);
        assert!(f.validate().is_ok());
        // 100 µm flakes: one per 0.2 mm square at most, 25 per mm².
        assert!(Glitter { density_per_mm2: 25.0, ..good }.validate().is_ok());
        for (bad, field) in [
            (Glitter { size_um: 5.0, ..good }, "glitter.size_um"),
            (Glitter { size_um: f64::NAN, ..good }, "glitter.size_um"),
            (Glitter { density_per_mm2: 26.0, ..good }, "glitter.density_per_mm2"),
            (Glitter { density_per_mm2: 0.0, ..good }, "glitter.density_per_mm2"),
            (Glitter { color: [0.5, 1.5, 0.5], ..good }, "glitter.color"),
            (Glitter { color: [0.5, f64::NAN, 0.5], ..good }, "glitter.color"),
            (Glitter { spread: 0.0, ..good }, "glitter.spread"),
        ] {
            f.glitter = Some(bad);
            assert!(f.validate().unwrap_err().contains(field), "{bad:?}");
        }
    }

    #[test]
    fn bad_finishes_name_the_field() {
        let (_, mut f) = FinishKind::Matte.defaults();
        f.clarity = 1.5;
        assert!(f.validate().unwrap_err().contains("finish.clarity"));
        f.clarity = 0.5;
        f.levelling = f64::NAN;
        assert!(f.validate().unwrap_err().contains("finish.levelling"));
    }
}
