//! Fast thickness translucency (\[BarreBrisebois2011\]): the subsurface model `thickness`. Light
//! that enters on the far side of a thin part of the mesh leaves toward the viewer, scaled by a
//! precomputed *local thickness* (white = thin) and a view-dependent lobe around the light's
//! direction seen through the object:
//!
//! ```text
//! L_t = albedo/π · E · (s_light · s · saturate(V · −(L + N δ))^p + a) · T
//! ```
//!
//! with E the light's irradiance at normal incidence (the talk's `cLightDiffuse ·
//! fLightAttenuation`; point lights fall off with the squared distance), δ the distortion, p the
//! power, s the material's scale, s_light the light's scale, a the ambient term and T the local
//! thickness (RGB). The talk's HLSL (slide "Code") has no 1/π; Rouge's lights are irradiances,
//! so the term is written as the radiance of a Lambertian of that albedo, and the scale carries
//! the rest. The talk does not normalise L + Nδ (the saturate keeps only the back side); neither
//! does Rouge, so the term is exactly the printed one.
//!
//! Domain: any δ (the talk uses 0 to 0.2; [`TranslucencyParams::check`] asks for finite
//! values), p > 0, s ≥ 0, a ≥ 0, T in [0, 1]. It is an artist's approximation with no energy
//! bound: `rouge bench translucency` measures it against Mitsuba 3 and fits its parameters per
//! medium (docs/BENCHMARKS.md).
//!
//! The local thickness comes from one of two sources ([`ThicknessSource`]): the talk's bake
//! (ambient occlusion with inverted normals, [`rouge_model::thickness`]), or, for meshes that
//! deform, an on-the-fly estimate from each light's shadow map (the distance the light travelled
//! inside the mesh, as in translucent shadow maps \[Dachsbacher2003\] and the depth-based thickness
//! of \[Oat2008\]), mapped through the same falloff as the bake.

use crate::error::{RenderError, Result};
use glam::Vec3;
use rouge_model::medium::{FittedTranslucency, Medium};
use rouge_model::thickness::{BakeSettings, Falloff};

/// The per-material parameters of \[BarreBrisebois2011\] (slides "fLTAmbient", "iLTPower",
/// "fLTDistortion", "fLTScale"). The scale is per light in the talk; Rouge keeps a material scale
/// (what the fit to the path tracer sets) and multiplies it by each light's
/// [`crate::Light::translucency_scale`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TranslucencyParams {
    /// δ: how far the normal bends the light vector (0 to 1; the talk shows 0.2).
    pub distortion: f32,
    /// p: the power of the view-dependent back lobe (the talk shows 4 and 12).
    pub power: f32,
    /// s: the scale of the back lobe (the talk shows 1 and 5).
    pub scale: f32,
    /// a: the ambient translucency, seen from every side.
    pub ambient: f32,
}

impl TranslucencyParams {
    /// The hand-set defaults three.js ships with its port of the technique
    /// (`MeshPhongMaterial` translucency example: distortion 0.1, power 2, scale 10, ambient 0).
    pub const THREE_JS: TranslucencyParams =
        TranslucencyParams { distortion: 0.1, power: 2.0, scale: 10.0, ambient: 0.0 };

    /// Checks the domain: finite δ, p > 0, s ≥ 0, a ≥ 0.
    ///
    /// # Errors
    /// [`RenderError::Invalid`] naming the parameter.
    pub fn check(&self) -> Result<()> {
        let bad =
            |what: &str, v: f32, rule: &str| Err(RenderError::Invalid(format!("translucency {what} {v}: {rule}")));
        if !self.distortion.is_finite() {
            return bad("distortion", self.distortion, "must be finite");
        }
        if !(self.power.is_finite() && self.power > 0.0) {
            return bad("power", self.power, "must be positive");
        }
        if !(self.scale.is_finite() && self.scale >= 0.0) {
            return bad("scale", self.scale, "must be ≥ 0");
        }
        if !(self.ambient.is_finite() && self.ambient >= 0.0) {
            return bad("ambient", self.ambient, "must be ≥ 0");
        }
        Ok(())
    }

    /// The key of parameters fitted for the local-thickness `source` (`baked`, `shadow-map`),
    /// with `+kernel` when fitted under the screen-space kernel (`screen-space+thickness`).
    pub fn fit_key(source: &str, kernel: bool) -> String {
        if kernel { format!("{source}+kernel") } else { source.to_string() }
    }

    /// The parameters fitted to the path tracer for `medium` and `key` ([`TranslucencyParams::fit_key`])
    /// when its file carries them (`translucency` in `rouge-medium`), else the three.js defaults;
    /// with the word for which.
    pub fn for_medium(medium: Option<&Medium>, key: &str) -> (TranslucencyParams, &'static str) {
        match medium.and_then(|m| own_fit(m, key)) {
            Some(t) => (TranslucencyParams::from(t), "fitted to the path tracer"),
            None => (TranslucencyParams::THREE_JS, "three.js defaults"),
        }
    }

    /// The parameters of the thickness term of `source` (`baked`, `shadow-map`) alone or under a
    /// screen-space `kernel`, with the words for where they come from, the first that exists of:
    /// those fitted for `medium` (under the kernel if asked: `SOURCE+kernel`); under a kernel,
    /// those fitted for `medium` alone; those fitted for the built-in medium nearest to `medium`
    /// ([`nearest_fitted`]: a medium nobody fitted gets a measured neighbour's); the three.js
    /// defaults.
    pub fn fitted(medium: Option<&Medium>, source: &str, kernel: bool) -> (TranslucencyParams, FitOrigin) {
        let key = Self::fit_key(source, kernel);
        let Some(m) = medium else {
            return (TranslucencyParams::THREE_JS, FitOrigin::Defaults);
        };
        if let Some(t) = own_fit(m, &key) {
            return (TranslucencyParams::from(t), FitOrigin::Fitted);
        }
        if let Some(t) = own_fit(m, source).filter(|_| kernel) {
            return (TranslucencyParams::from(t), FitOrigin::FittedAlone);
        }
        match nearest_fitted(m, &key) {
            Some((name, p)) => (p, FitOrigin::Nearest(name)),
            None => (TranslucencyParams::THREE_JS, FitOrigin::Defaults),
        }
    }

    /// As the GPU reads them: δ, p, s, a.
    pub fn to_gpu(self) -> [f32; 4] {
        [self.distortion, self.power, self.scale, self.ambient]
    }
}

/// Where the local thickness T comes from.
#[derive(Clone, Debug, PartialEq)]
pub enum ThicknessSource {
    /// The talk's bake: inverted-normal ambient occlusion per vertex, rasterised into the mesh's
    /// UV space, cached by mesh. Right for a rigid mesh; stale once it deforms.
    Baked(BakeSettings),
    /// Per light, every frame: the distance d the light travelled inside the mesh before the
    /// shaded point, from the light's shadow map, through the falloff w(d) of the bake. Follows
    /// any deformation; needs the light to cast shadows (a light without a shadow map gets no
    /// term, and the frame plan says so).
    ShadowMap {
        /// Distance beyond which the mesh counts as opaque, mm.
        cutoff_mm: f32,
        /// w(d): the bake's falloff.
        falloff: Falloff,
    },
}

impl ThicknessSource {
    /// The name used on the command line and in `--explain`.
    pub fn name(&self) -> &'static str {
        match self {
            ThicknessSource::Baked(_) => "baked",
            ThicknessSource::ShadowMap { .. } => "shadow-map",
        }
    }

    /// The source for a material: the coloured falloff exp(−σ_tr·d) of its medium (σ_tr the
    /// diffusion's effective transport coefficient, \[Jensen2001\]) when it has one, else the grey
    /// linear falloff; `cutoff_mm` as given.
    pub fn for_medium(baked: bool, medium: Option<&Medium>, rays: u32, cutoff_mm: f32) -> ThicknessSource {
        let falloff = match medium {
            Some(m) => Falloff::Exponential { per_mm: sigma_tr_per_mm(m).map(|v| v as f32) },
            None => Falloff::Power { exponent: 1.0 },
        };
        if baked {
            ThicknessSource::Baked(BakeSettings { rays, cutoff_mm, falloff, ..BakeSettings::default() })
        } else {
            ThicknessSource::ShadowMap { cutoff_mm, falloff }
        }
    }

    /// The falloff and cutoff.
    pub fn falloff(&self) -> (Falloff, f32) {
        match self {
            ThicknessSource::Baked(s) => (s.falloff, s.cutoff_mm),
            ThicknessSource::ShadowMap { cutoff_mm, falloff } => (*falloff, *cutoff_mm),
        }
    }
}

/// σ_tr = √(3 σa (σa + σs′)) per channel, mm⁻¹: the diffusion approximation's effective
/// transport coefficient (\[Jensen2001\] eq. 5 context; the decay rate of the fluence far from a
/// source). Valid where scattering dominates (σs′ ≫ σa); elsewhere it still decreases with depth
/// Where [`TranslucencyParams::fitted`]'s parameters come from.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum FitOrigin {
    /// Fitted for the medium (under the kernel, when one was asked for).
    Fitted,
    /// Fitted for the medium, for the thickness model alone (asked under a kernel).
    FittedAlone,
    /// Fitted for this built-in medium, the nearest to the one asked for.
    Nearest(String),
    /// The three.js defaults ([`TranslucencyParams::THREE_JS`]).
    Defaults,
}

impl FitOrigin {
    /// A short label: `fitted`, `fitted alone`, `nearest (NAME)`, `three.js`.
    pub fn label(&self) -> String {
        match self {
            FitOrigin::Fitted => "fitted".into(),
            FitOrigin::FittedAlone => "fitted alone".into(),
            FitOrigin::Nearest(name) => format!("nearest ({name})"),
            FitOrigin::Defaults => "three.js".into(),
        }
    }
}

/// `medium`'s own entry for `key`.
fn own_fit<'a>(medium: &'a Medium, key: &str) -> Option<&'a FittedTranslucency> {
    medium.translucency.iter().find(|t| t.source == key)
}

impl From<&FittedTranslucency> for TranslucencyParams {
    fn from(t: &FittedTranslucency) -> TranslucencyParams {
        TranslucencyParams {
            distortion: t.distortion as f32,
            power: t.power as f32,
            scale: t.scale as f32,
            ambient: t.ambient as f32,
        }
    }
}

/// The built-in medium nearest to `medium` with parameters fitted for `key`, and those
/// parameters. Two media are as near as the light in them goes as far and is absorbed as much:
/// the distance is the sum over the channels of the squared differences of ln σ_tr (the
/// diffusion's decay rate, [`sigma_tr_per_mm`]) and of ln(1 − α′) (the part of each scattering
/// absorbed), each floored at 10⁻⁶. A choice, measured on media nobody fitted
/// (docs/BENCHMARKS.md).
pub fn nearest_fitted(medium: &Medium, key: &str) -> Option<(String, TranslucencyParams)> {
    let coordinates = |m: &Medium| {
        let (tr, albedo) = (sigma_tr_per_mm(m), m.reduced_albedo());
        std::array::from_fn::<f64, 6, _>(|i| {
            if i < 3 { tr[i].max(1e-6).ln() } else { (1.0 - albedo[i - 3]).max(1e-6).ln() }
        })
    };
    let here = coordinates(medium);
    rouge_model::medium::BUILTIN_MEDIA
        .iter()
        .filter_map(|name| Medium::builtin(name).ok())
        .filter_map(|m| {
            let fit = own_fit(&m, key).map(TranslucencyParams::from)?;
            let d: f64 = coordinates(&m).iter().zip(&here).map(|(a, b)| (a - b).powi(2)).sum();
            Some((d, m.name.clone(), fit))
        })
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, name, fit)| (name, fit))
}

/// as a rate should.
pub fn sigma_tr_per_mm(m: &Medium) -> [f64; 3] {
    std::array::from_fn(|c| {
        let (a, s) = (m.sigma_a_per_mm[c], m.sigma_s_prime_per_mm[c]);
        (3.0 * a * (a + s)).sqrt()
    })
}

/// The thickness translucency of one light at one point, as radiance over albedo × irradiance:
/// `(s_light · s · saturate(v · −(l + n δ))^p + a) · T / π`. CPU twin of `translucency` in
/// shaders/thickness.wgsl (used by tests and the fit).
///
/// `l` points toward the light, `n` is the unit normal, `v` points toward the viewer.
pub fn translucency_term(
    l: Vec3,
    n: Vec3,
    v: Vec3,
    params: TranslucencyParams,
    light_scale: f32,
    thickness: [f32; 3],
) -> [f32; 3] {
    let bent = l + n * params.distortion;
    let lobe = v.dot(-bent).clamp(0.0, 1.0);
    // pow(0, p) is 0 for p > 0; written out so that the GPU's exp2(p·log2(0)) case is explicit.
    let back = if lobe > 0.0 { lobe.powf(params.power) } else { 0.0 };
    let k = (light_scale * params.scale * back + params.ambient) / std::f32::consts::PI;
    thickness.map(|t| k * t)
}

#[cfg(test)]
mod tests {
    use super::*;

    const P: TranslucencyParams = TranslucencyParams { distortion: 0.2, power: 4.0, scale: 5.0, ambient: 0.0 };

    #[test]
    fn the_term_is_zero_where_the_talk_says() {
        // Light in front of the surface, viewer in front: V·−L < 0, and no ambient.
        let (n, v) = (Vec3::Z, Vec3::Z);
        assert_eq!(translucency_term(Vec3::Z, n, v, P, 1.0, [1.0; 3]), [0.0; 3]);
        // Light behind, looking along it: the lobe's peak, 5/π with T = 1.
        let t = translucency_term(-Vec3::Z, n, v, TranslucencyParams { distortion: 0.0, ..P }, 1.0, [1.0; 3]);
        assert!((t[0] - 5.0 / std::f32::consts::PI).abs() < 1e-6, "{t:?}");
        // Zero thickness: nothing.
        assert_eq!(translucency_term(-Vec3::Z, n, v, P, 1.0, [0.0; 3]), [0.0; 3]);
    }

    #[test]
    fn the_term_grows_with_thinness_and_the_light_scale_multiplies_it() {
        let (l, n, v) = (Vec3::new(0.2, 0.0, -1.0).normalize(), Vec3::Z, Vec3::Z);
        let thick = translucency_term(l, n, v, P, 1.0, [0.2; 3]);
        let thin = translucency_term(l, n, v, P, 1.0, [0.8; 3]);
        assert!(thin[0] > thick[0] && thick[0] > 0.0);
        let scaled = translucency_term(l, n, v, P, 3.0, [0.8; 3]);
        assert!((scaled[0] - 3.0 * thin[0]).abs() <= 1e-6 * scaled[0], "{scaled:?} {thin:?}");
        // Ambient is seen from every side, light in front included.
        let amb = translucency_term(Vec3::Z, n, v, TranslucencyParams { ambient: 0.5, ..P }, 1.0, [1.0; 3]);
        assert!((amb[0] - 0.5 / std::f32::consts::PI).abs() < 1e-7);
    }

    #[test]
    fn parameters_outside_the_domain_are_errors() {
        assert!(P.check().is_ok() && TranslucencyParams::THREE_JS.check().is_ok());
        for bad in [
            TranslucencyParams { power: 0.0, ..P },
            TranslucencyParams { scale: -1.0, ..P },
            TranslucencyParams { ambient: f32::NAN, ..P },
            TranslucencyParams { distortion: f32::INFINITY, ..P },
        ] {
            assert!(bad.check().is_err(), "{bad:?}");
        }
    }

    #[test]
    fn sigma_tr_of_skin1_is_the_diffusion_rate() {
        let m = Medium::builtin("skin1").expect("skin1");
        let s = sigma_tr_per_mm(&m);
        for ((s, a), sp) in s.iter().zip(m.sigma_a_per_mm).zip(m.sigma_s_prime_per_mm) {
            assert!((s * s - 3.0 * a * (a + sp)).abs() < 1e-12);
        }
        assert!(s[0] < s[1] && s[1] < s[2], "red travels farthest in skin: {s:?}");
    }
}
