//! Light scattered by a hair fibre (the lashes and brows of the hair pass, shaders/hair.wgsl
//! `fibre_scattering`, whose twin this is): \[Marschner2003\]'s three lobes of a dielectric
//! cylinder, R (reflection at the cuticle), TT (through the fibre) and TRT (in, reflected
//! inside, out), each a longitudinal Gaussian shifted by the cuticle's tilt times an azimuthal
//! term, with \[Karis2016\]'s closed-form azimuthal terms (the fits Unreal's hair shading uses in
//! place of Marschner's root solving), and absorption inside the fibre from its colour
//! ([`sigma_a_from_color`]) or from its melanin (\[dEon2011\]'s eumelanin and pheomelanin spectra
//! reduced to RGB, the values of PBRT-v4's `HairBxDF`).
//!
//! Conventions: `t` is the fibre's unit tangent from root to tip; `l` toward the light, `v`
//! toward the eye, both unit. sin θ = t·ω; φ the angle between the projections of `l` and `v`
//! on the fibre's normal plane. σa is per unit of the fibre's *radius* (a path through the
//! fibre's axis at normal incidence is 2 long), as in PBRT-v4. The result is the outgoing
//! radiance per unit irradiance of a directional light (irradiance on a plane facing the
//! light), L = E·`scattering(...)`: the quantity PBRT-v4's `HairBxDF` gives averaged across the
//! fibre's width, against which it is measured (`data/hair/pbrt_v4_hair.csv`,
//! [`compare_with_pbrt`]). PBRT-v4 shifts the R lobe toward its tangent `dp/du`, the reverse of
//! Marschner's sign for a curve drawn from root to tip; Rouge keeps Marschner's (R toward the
//! root) and compares with the tangent reversed.
//!
//! Domain: any directions (a fibre seen or lit along its axis has cos θd → 0; the absorption
//! exponents are clamped there); σa ≥ 0; roughness 0.05-1 (β of the R lobe, radians).

use glam::Vec3;

/// Refractive index of hair keratin (\[Marschner2003\] table 1).
pub const ETA: f32 = 1.55;
/// Tilt of the cuticle scales, radians (\[Karis2016\]'s shift, 2°): R is shifted toward the root
/// by twice it, TT toward the tip by it, TRT by four times it (\[Marschner2003\]: α_R = −2α_TT,
/// α_TRT = −3α_R/2; Karis's values).
pub const CUTICLE_TILT_RAD: f32 = 0.035;
/// Longitudinal roughness of the lashes and brows, radians (β_R; TT takes half its variance,
/// TRT twice: \[Karis2016\]). Natural hair is 5-10° (\[Marschner2003\] table 1): 0.15 rad.
pub const ROUGHNESS_RAD: f32 = 0.15;
/// σa per unit radius and per unit concentration of eumelanin, RGB (PBRT-v4 `HairBxDF`, from
/// \[dEon2011\]).
pub const EUMELANIN_SIGMA_A: [f32; 3] = [0.419, 0.697, 1.37];
/// The same for pheomelanin.
pub const PHEOMELANIN_SIGMA_A: [f32; 3] = [0.187, 0.4, 1.05];

/// σa of a fibre with these melanin concentrations (eumelanin about 8 in black hair, 1.3 in
/// brown, 0.3 in blonde: PBRT-v4's scenes).
pub fn sigma_a_from_melanin(eumelanin: f32, pheomelanin: f32) -> [f32; 3] {
    std::array::from_fn(|c| eumelanin.max(0.0) * EUMELANIN_SIGMA_A[c] + pheomelanin.max(0.0) * PHEOMELANIN_SIGMA_A[c])
}

/// σa of a fibre of colour `c` (linear, each channel clamped to 1e-6..1): the fraction of the
/// light it passes straight across its diameter, c = exp(−2σa) (a path of two radii). How the
/// hairs' colours (the natural ones from melanin, [`color_from_melanin`]; a mascara's; a brow
/// gel's tint) become absorption. (Not \[Chiang2016\]'s colour, which is that of a mass of
/// fibres under multiple scattering: lashes and brows are sparse, seen fibre by fibre.)
pub fn sigma_a_from_color(c: [f32; 3]) -> [f32; 3] {
    c.map(|v| -0.5 * v.clamp(1e-6, 1.0).ln())
}

/// The colour ([`sigma_a_from_color`]'s) of a fibre with these melanin concentrations.
pub fn color_from_melanin(eumelanin: f32, pheomelanin: f32) -> [f32; 3] {
    sigma_a_from_melanin(eumelanin, pheomelanin).map(|s| (-2.0 * s).exp())
}

/// The radiance a fibre of absorption `sigma_a` seen across its axis sends toward the eye under
/// a uniform sky of unit radiance: [`scattering`] integrated over the sphere of light directions
/// (the white furnace of PBRT-v4's hair tests; 36 × 72 grid, within 1 % of 180 × 360), the hair
/// pass's response to the environment's light (L = albedo · E / π, as a Lambertian surface of
/// that albedo under irradiance E).
pub fn albedo(sigma_a: [f32; 3], roughness: f32) -> [f32; 3] {
    albedo_on_grid(sigma_a, roughness, 0.0, (36, 72))
}

/// [`albedo`] seen from `theta_o` off the fibre's normal plane, on an `n_theta × n_phi` grid.
fn albedo_on_grid(sigma_a: [f32; 3], roughness: f32, theta_o: f32, (n_theta, n_phi): (usize, usize)) -> [f32; 3] {
    use std::f32::consts::{FRAC_PI_2, PI};
    let t = Vec3::Y;
    let v = Vec3::new(0.0, theta_o.sin(), theta_o.cos());
    let (d_theta, d_phi) = (PI / n_theta as f32, 2.0 * PI / n_phi as f32);
    let mut sum = [0.0f64; 3];
    for i in 0..n_theta {
        let theta = -FRAC_PI_2 + (i as f32 + 0.5) * d_theta;
        for j in 0..n_phi {
            let phi = (j as f32 + 0.5) * d_phi;
            let l = Vec3::new(theta.cos() * phi.sin(), theta.sin(), theta.cos() * phi.cos());
            let s = scattering(t, l, v, sigma_a, roughness);
            for c in 0..3 {
                sum[c] += f64::from(s[c] * theta.cos() * d_theta * d_phi);
            }
        }
    }
    sum.map(|s| s as f32)
}

/// Schlick's Fresnel reflectance of keratin at cos θ (as \[Karis2016\]).
fn fresnel(cos: f32) -> f32 {
    let f0 = ((1.0 - ETA) / (1.0 + ETA)).powi(2);
    f0 + (1.0 - f0) * (1.0 - cos.clamp(0.0, 1.0)).powi(5)
}

/// A unit-area Gaussian of standard deviation `b` at `x`.
fn gaussian(b: f32, x: f32) -> f32 {
    (-0.5 * x * x / (b * b)).exp() / ((2.0 * std::f32::consts::PI).sqrt() * b)
}

/// The fibre's outgoing radiance per unit irradiance of a directional light (see the module
/// doc): R + TT + TRT, each a Gaussian in θi + θo about the lobe's shift, divided by cos θd so
/// that it integrates to its azimuthal share over the sphere of light directions (as
/// \[dEon2011\]'s normalised M_p does), times \[Karis2016\]'s azimuthal term with its Fresnel
/// and absorption factors.
pub fn scattering(t: Vec3, l: Vec3, v: Vec3, sigma_a: [f32; 3], roughness: f32) -> [f32; 3] {
    let theta_i = t.dot(l).clamp(-1.0, 1.0).asin();
    let theta_o = t.dot(v).clamp(-1.0, 1.0).asin();
    let cos_d = (0.5 * (theta_o - theta_i)).cos().max(1e-3);
    let lp = l - t * t.dot(l);
    let vp = v - t * t.dot(v);
    let cos_phi = lp.dot(vp) / (lp.length_squared() * vp.length_squared() + 1e-4).sqrt();
    let cos_half_phi = (0.5 + 0.5 * cos_phi).clamp(0.0, 1.0).sqrt();
    let b = roughness.max(1e-3);
    let m = |width: f32, shift: f32| gaussian(width, theta_i + theta_o - shift) / cos_d;
    // R: Marschner's N_R = cos(φ/2)/4 with the Fresnel factor at the half angle; shifted toward
    // the root by twice the tilt.
    let r =
        m(b, -2.0 * CUTICLE_TILT_RAD) * 0.25 * cos_half_phi * fresnel((0.5 + 0.5 * l.dot(v)).clamp(0.0, 1.0).sqrt());
    // TT: refracted through, half R's width, with Karis's fit of the exit offset h and of N_TT.
    let eta_p = 1.19 / cos_d + 0.36 * cos_d;
    let a = 1.0 / eta_p;
    let h = cos_half_phi * (1.0 + a * (0.6 - 0.8 * cos_phi));
    let f_tt = fresnel(cos_d * (1.0 - h * h).clamp(0.0, 1.0).sqrt());
    let m_tt = m(0.5 * b, CUTICLE_TILT_RAD);
    let n_tt = (-3.65 * cos_phi - 3.98).exp();
    let path_tt = 2.0 * (1.0 - (h * a).powi(2)).clamp(0.0, 1.0).sqrt() / cos_d;
    // TRT: two passes through, one internal reflection, twice R's width.
    let f_trt = fresnel(cos_d * 0.5);
    let m_trt = m(2.0 * b, 4.0 * CUTICLE_TILT_RAD);
    let n_trt = (17.0 * cos_phi - 16.78).exp();
    let path_trt = 3.2 / cos_d;
    std::array::from_fn(|c| {
        let tt = m_tt * n_tt * (1.0 - f_tt).powi(2) * (-sigma_a[c] * path_tt).exp();
        let trt = m_trt * n_trt * (1.0 - f_trt).powi(2) * f_trt * (-sigma_a[c] * path_trt).exp();
        r + tt + trt
    })
}

/// One direction pair of PBRT-v4's hair reference (`data/hair/pbrt_v4_hair.csv`) with Rouge's
/// value beside it.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct PbrtRow {
    /// σa per unit radius.
    pub sigma_a: f32,
    /// The light's and the eye's angles from the fibre's normal plane, and the azimuth between
    /// them, degrees.
    pub theta_i_deg: f32,
    /// As `theta_i_deg`, the eye's.
    pub theta_o_deg: f32,
    /// φo − φi.
    pub phi_deg: f32,
    /// PBRT-v4's `HairBxDF` averaged across the fibre (1/sr).
    pub pbrt: f32,
    /// [`scattering`] for the same directions, tangent reversed (see the module doc).
    pub rouge: f32,
}

/// Reads PBRT-v4's hair reference (the CSV `python/hair_reference.py` writes: `#` comments, a
/// header, then `sigma_a,theta_i_deg,theta_o_deg,phi_deg,wi_x,wi_y,wi_z,wo_x,wo_y,wo_z,f_avg`)
/// and evaluates [`scattering`] at [`ROUGHNESS_RAD`] for each row.
///
/// # Errors
/// A message naming the line and the field that is missing or not a finite number.
pub fn compare_with_pbrt(csv: &str) -> std::result::Result<Vec<PbrtRow>, String> {
    let mut rows = Vec::new();
    let mut header = false;
    for (i, line) in csv.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        if !header {
            header = true;
            continue;
        }
        let fields: Vec<&str> = line.split(',').collect();
        let value = |k: usize| -> std::result::Result<f32, String> {
            let text = fields.get(k).ok_or_else(|| format!("line {}: {} fields, expected 11", i + 1, fields.len()))?;
            text.trim()
                .parse::<f32>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| format!("line {}, field {}: {text:?} is not a finite number", i + 1, k + 1))
        };
        let wi = Vec3::new(value(4)?, value(5)?, value(6)?);
        let wo = Vec3::new(value(7)?, value(8)?, value(9)?);
        let sigma_a = value(0)?;
        let rouge =
            scattering(-Vec3::X, wi.normalize_or_zero(), wo.normalize_or_zero(), [sigma_a; 3], ROUGHNESS_RAD)[0];
        rows.push(PbrtRow {
            sigma_a,
            theta_i_deg: value(1)?,
            theta_o_deg: value(2)?,
            phi_deg: value(3)?,
            pbrt: value(10)?,
            rouge,
        });
    }
    if rows.is_empty() {
        return Err("no rows".into());
    }
    Ok(rows)
}

/// How far Rouge is from PBRT-v4 over the rows of one σa.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct PbrtSummary {
    /// σa per unit radius.
    pub sigma_a: f32,
    /// Rows.
    pub rows: usize,
    /// √(Σ (rouge − pbrt)² / Σ pbrt²).
    pub relative_rms: f64,
    /// Σ rouge / Σ pbrt: the light scattered over the grid, Rouge's against PBRT's.
    pub energy_ratio: f64,
}

/// [`PbrtSummary`] per σa of `rows`, in the order they first appear.
pub fn summarize(rows: &[PbrtRow]) -> Vec<PbrtSummary> {
    let mut sigmas: Vec<f32> = Vec::new();
    for r in rows {
        if !sigmas.contains(&r.sigma_a) {
            sigmas.push(r.sigma_a);
        }
    }
    sigmas
        .into_iter()
        .map(|sigma_a| {
            let of: Vec<&PbrtRow> = rows.iter().filter(|r| r.sigma_a == sigma_a).collect();
            let (mut d2, mut p2, mut sr, mut sp) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
            for r in &of {
                let (p, q) = (f64::from(r.pbrt), f64::from(r.rouge));
                d2 += (q - p).powi(2);
                p2 += p * p;
                sr += q;
                sp += p;
            }
            PbrtSummary {
                sigma_a,
                rows: of.len(),
                relative_rms: (d2 / p2.max(1e-30)).sqrt(),
                energy_ratio: sr / sp.max(1e-30),
            }
        })
        .collect()
}

/// The WGSL twin of [`scattering`] (shaders/fibre.wgsl, inserted into shaders/hair.wgsl): it
/// needs [`wgsl_constants`] before it.
pub const WGSL_SCATTERING: &str = include_str!("shaders/fibre.wgsl");

/// The WGSL constants of the fibre model (shaders/hair.wgsl).
pub fn wgsl_constants() -> String {
    format!("const FIBRE_ETA: f32 = {ETA:?};\nconst CUTICLE_TILT_RAD: f32 = {CUTICLE_TILT_RAD:?};\n")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn melanin_and_colour_give_pbrt_v4s_absorption() {
        // PBRT-v4: black hair (eumelanin 8) σa = 8 × (0.419, 0.697, 1.37).
        let black = sigma_a_from_melanin(8.0, 0.0);
        for (a, b) in black.iter().zip([3.352, 5.576, 10.96]) {
            assert!((a - b).abs() < 1e-4, "{black:?}");
        }
        // Colour and absorption invert each other; white absorbs nothing; out-of-range colours
        // stay finite.
        let c = color_from_melanin(1.3, 0.2);
        let back = sigma_a_from_color(c);
        assert!(back.iter().zip(sigma_a_from_melanin(1.3, 0.2)).all(|(a, b)| (a - b).abs() < 1e-4), "{back:?}");
        assert!(c[0] > c[1] && c[1] > c[2], "melanin passes red most: {c:?}");
        assert_eq!(sigma_a_from_color([1.0; 3]), [0.0; 3]);
        assert!(sigma_a_from_color([0.0, -1.0, f32::INFINITY]).iter().all(|v| v.is_finite() && *v >= 0.0));
    }

    fn albedo_fine(sigma_a: [f32; 3], theta_o: f32) -> [f32; 3] {
        albedo_on_grid(sigma_a, ROUGHNESS_RAD, theta_o, (180, 360))
    }

    #[test]
    fn a_clear_fibre_scatters_all_its_light_an_absorbing_one_only_its_surface_reflection() {
        // White furnace (a uniform sky, the eye at θo): a clear fibre returns all of it
        // (PBRT-v4: 0.998-0.999), an opaque one only R.
        for theta_o in [-1.0f32, -0.5, 0.0, 0.5, 1.0] {
            let clear = albedo_fine([0.0; 3], theta_o)[0];
            let black = albedo_fine([50.0; 3], theta_o)[0];
            println!("θo {theta_o}: clear {clear:.4}, black {black:.4}");
            assert!((0.9..1.1).contains(&clear), "clear fibre at θo {theta_o}: {clear}");
            assert!((0.03..0.15).contains(&black), "black fibre at θo {theta_o}: {black}");
        }
        // Melanin colours: eumelanin absorbs blue most, so a brown fibre scatters red most.
        let brown = albedo_fine(sigma_a_from_melanin(1.3, 0.0), 0.3);
        println!("brown: {brown:?}");
        assert!(brown[0] > brown[1] && brown[1] > brown[2], "{brown:?}");
        // The coarse grid of the hair pass's environment term is within 1 % of the fine one.
        for sigma in [0.0, 0.5, 2.0] {
            let (coarse, fine) = (albedo([sigma; 3], ROUGHNESS_RAD)[0], albedo_fine([sigma; 3], 0.0)[0]);
            assert!((coarse / fine - 1.0).abs() < 0.01, "σa {sigma}: {coarse} against {fine}");
        }
        // Never NaN at the poles (light or eye along the fibre).
        let s = scattering(Vec3::Y, Vec3::Y, Vec3::Y, [1.0; 3], ROUGHNESS_RAD);
        let s2 = scattering(Vec3::Y, Vec3::Y, -Vec3::Y, [1.0; 3], ROUGHNESS_RAD);
        assert!(s.iter().chain(&s2).all(|v| v.is_finite() && *v >= 0.0), "{s:?} {s2:?}");
    }

    #[test]
    fn the_fibre_model_follows_pbrt_v4s_hair_bsdf() {
        let csv = include_str!("../../data/hair/pbrt_v4_hair.csv");
        let rows = compare_with_pbrt(csv).expect("the reference reads");
        assert_eq!(rows.len(), 1300);
        for s in summarize(&rows) {
            println!(
                "σa {}: {} rows, relative RMS {:.3}, energy {:.3}",
                s.sigma_a, s.rows, s.relative_rms, s.energy_ratio
            );
        }
        // A malformed row is an error naming its line and field.
        let bad = compare_with_pbrt("# c\nheader\n0,0,0,0,1,0,0,0,0,1,nan\n").expect_err("nan");
        assert!(bad.contains("line 3, field 11"), "{bad}");
    }
}
