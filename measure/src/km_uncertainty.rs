//! How certain Kubelka-Munk S and K are: the standard uncertainty of the inversion
//! ([`crate::km::invert_s_k`]) from the uncertainties of its inputs, by linear propagation
//! through its Jacobian (\[GUM\] §5.1-5.2, eq. 10 and 13: `U_y = J U_x Jᵀ`), the inversion's
//! condition number, and the thin-layer thickness that would make S and K most certain
//! (experiment design).
//!
//! # The Jacobian
//!
//! With `L = ln[(1 − R R∞)(Rg − R∞) / ((1 − Rg R∞)(R − R∞))] = ln(1 + z)` (the logarithm of
//! `km.rs`, computed as `ln1p(z)`) and `c = R∞ / (1 − R∞²) = 1/(2b)`, `S D = c L` and
//! `K = S g` with `g = (1 − R∞)² / (2R∞)`. Differentiating:
//!
//! * `∂(SD)/∂R  = −c [R∞/(1 − R R∞) + 1/(R − R∞)]`
//! * `∂(SD)/∂Rg =  c [R∞/(1 − Rg R∞) + 1/(Rg − R∞)]`
//! * `∂(SD)/∂R∞ = c′ L + c [1/(R − R∞) − 1/(Rg − R∞) + Rg/(1 − Rg R∞) − R/(1 − R R∞)]`,
//!   `c′ = (1 + R∞²)/(1 − R∞²)²`
//! * `∂S/∂D = −S/D`; `∂K/∂x = g ∂S/∂x` for `x ∈ {R, Rg, D}` and
//!   `∂K/∂R∞ = g ∂S/∂R∞ + S g′` with `g′ = −(1 − R∞²)/(2R∞²)`.
//!
//! The two terms of `∂(SD)/∂R∞` cancel as `R∞ → 1` (`c`, `c′` diverge); above
//! `R∞ = 1 − 1e-3` the derivative is taken by a central difference of the inversion instead.
//! `kubelka_munk_jacobian_matches_finite_differences` (tests) checks both against differences.
//!
//! # What goes in
//!
//! The three readings' standard uncertainties (absolute reflectance, per wavelength: the
//! instrument's repeatability), a correlation coefficient between readings (a shared component,
//! e.g. the calibration tile's; 0 for independent readings) and the thickness's standard
//! uncertainty. The Monte Carlo of \[JCGM101\] checks the propagation (`measure/tests/uncertainty.rs`:
//! 1,000 seeded draws on every sample preset agree to 10 %).

use crate::analysis::optimize::golden_section;
use crate::km::{self, KmCoefficients, KmError, invert_s_k};
use crate::preset::{Preset, PresetError, PresetUncertainty};
use crate::spectrum::{Spectrum, WORKING_LEN, working_wavelength_nm};
use nalgebra::{Matrix2, Matrix2x3, Matrix2x4, Matrix4};

/// Standard uncertainties of one wavelength's inputs to the inversion.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct InputUncertainty {
    /// u(R∞), absolute reflectance.
    pub u_r_inf: f64,
    /// u(R), absolute reflectance.
    pub u_r: f64,
    /// u(Rg), absolute reflectance.
    pub u_rg: f64,
    /// u(D), mm.
    pub u_thickness_mm: f64,
    /// Correlation coefficient between any two of the three readings (in [0, 1]; 0: independent).
    pub reading_correlation: f64,
}

impl InputUncertainty {
    /// Every reading with the same `u_reflectance`, independent, and `u_thickness_mm`.
    pub fn readings(u_reflectance: f64, u_thickness_mm: f64) -> Self {
        InputUncertainty {
            u_r_inf: u_reflectance,
            u_r: u_reflectance,
            u_rg: u_reflectance,
            u_thickness_mm,
            reading_correlation: 0.0,
        }
    }

    fn check(&self) -> Result<(), KmError> {
        for (name, v) in
            [("u(R∞)", self.u_r_inf), ("u(R)", self.u_r), ("u(Rg)", self.u_rg), ("u(D)", self.u_thickness_mm)]
        {
            if !(v >= 0.0 && v.is_finite()) {
                return Err(KmError::BadCoefficient { name, value: v });
            }
        }
        if !(0.0..=1.0).contains(&self.reading_correlation) {
            return Err(KmError::BadCoefficient { name: "reading correlation", value: self.reading_correlation });
        }
        Ok(())
    }

    /// The 4×4 input covariance, order (R∞, R, Rg, D).
    fn covariance(&self) -> Matrix4<f64> {
        let u = [self.u_r_inf, self.u_r, self.u_rg, self.u_thickness_mm];
        Matrix4::from_fn(|i, j| {
            if i == j {
                u[i] * u[i]
            } else if i < 3 && j < 3 {
                self.reading_correlation * u[i] * u[j]
            } else {
                0.0
            }
        })
    }
}

/// Classes of instrument with a documented default repeatability (one standard deviation of
/// repeated readings of the same spot, absolute reflectance, flat over the spectrum). Rouge's
/// choice, of the order that manufacturers specify for such instruments on a white tile
/// (spectrophotometer datasheets give "within 0.1 %" for benchtop and portable sphere
/// instruments): give the instrument's own figure (`--u-reflectance`) when you have it, and
/// remember that sample preparation usually varies more than the instrument.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum InstrumentClass {
    /// Benchtop d/8 sphere spectrophotometer: u = 0.001.
    Benchtop,
    /// Portable (hand-held) sphere spectrophotometer: u = 0.002.
    Portable,
    /// Multispectral or RGB camera reconstruction: u = 0.01.
    Imaging,
}

impl InstrumentClass {
    /// All classes.
    pub const ALL: [InstrumentClass; 3] =
        [InstrumentClass::Benchtop, InstrumentClass::Portable, InstrumentClass::Imaging];

    /// Name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            InstrumentClass::Benchtop => "benchtop",
            InstrumentClass::Portable => "portable",
            InstrumentClass::Imaging => "imaging",
        }
    }

    /// Parses a name of [`InstrumentClass::name`].
    pub fn parse(s: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|c| c.name().eq_ignore_ascii_case(s.trim()))
    }

    /// How a preset names this default (`PresetUncertainty::source`).
    pub fn source_text(self) -> String {
        format!("± {} ({} instrument class default)", self.u_reflectance(), self.name())
    }

    /// The default repeatability, absolute reflectance.
    pub fn u_reflectance(self) -> f64 {
        match self {
            InstrumentClass::Benchtop => 0.001,
            InstrumentClass::Portable => 0.002,
            InstrumentClass::Imaging => 0.01,
        }
    }
}

/// The thickness's standard uncertainty `rouge import` and Python's `Preset.from_measurement`
/// assume unless told (0.5 µm, mm): Rouge's choice, about what a wet-film applicator's gap or a
/// profilometer gives on a 10-20 µm film.
pub const DEFAULT_U_THICKNESS_MM: f64 = 0.0005;

/// S and K with their standard uncertainties at one wavelength.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct SkUncertainty {
    /// S, mm⁻¹.
    pub s_per_mm: f64,
    /// K, mm⁻¹.
    pub k_per_mm: f64,
    /// u(S), mm⁻¹.
    pub u_s_per_mm: f64,
    /// u(K), mm⁻¹.
    pub u_k_per_mm: f64,
    /// Correlation coefficient of S and K (0 when either is certain).
    pub correlation_sk: f64,
    /// Relative condition number of the inversion in the reflectances: the largest singular
    /// value of `(∂yᵢ/∂xⱼ)(xⱼ/yᵢ)`, y = (S, K), x = (R∞, R, Rg): a relative error ε in the
    /// readings moves S or K by up to κε. `None` where S or K is 0 (no relative error).
    pub condition: Option<f64>,
}

/// Above this relative condition number the inversion is flagged as ill-conditioned: a 0.5 %
/// relative reading error (a benchtop instrument's 0.001 at R ≈ 0.2) can then move S or K by more
/// than 10 %, where linear propagation stops being reliable (`measure/tests/uncertainty.rs`).
/// Rouge's choice, stated so reports can be read against it.
pub const ILL_CONDITIONED: f64 = 20.0;

const FINITE_DIFFERENCE_ABOVE_R_INF: f64 = 1.0 - 1e-3;

/// S, K and the Jacobian `∂(S, K)/∂(R∞, R, Rg, D)` of the inversion (module documentation).
/// Domain and errors as [`invert_s_k`].
///
/// # Examples
///
/// The inversion's own example (R∞ 0.2, R 0.132 over Rg 0.03, 50 µm): S = 3.7315 /mm, and
/// `∂S/∂D = −S/D`.
///
/// ```
/// use rouge_measure::km_uncertainty::invert_s_k_jacobian;
///
/// let (sk, j) = invert_s_k_jacobian(0.2, 0.132, 0.03, 0.05)?;
/// assert!((sk.s_per_mm - 3.731_475_278_712_077).abs() < 1e-12);
/// assert!((j[(0, 3)] + sk.s_per_mm / 0.05).abs() < 1e-9);
/// # Ok::<(), rouge_measure::KmError>(())
/// ```
pub fn invert_s_k_jacobian(
    r_inf: f64,
    r: f64,
    rg: f64,
    thickness_mm: f64,
) -> Result<(KmCoefficients, Matrix2x4<f64>), KmError> {
    let sk = invert_s_k(r_inf, r, rg, thickness_mm)?;
    let (s, d) = (sk.s_per_mm, thickness_mm);
    let one_minus_sq = (1.0 - r_inf) * (1.0 + r_inf);
    let c = r_inf / one_minus_sq;
    let (dr, dg) = (r - r_inf, rg - r_inf);
    let (a_r, a_g) = ((-r).mul_add(r_inf, 1.0), (-rg).mul_add(r_inf, 1.0));
    let dsd_dr = -c * (r_inf / a_r + 1.0 / dr);
    let dsd_drg = c * (r_inf / a_g + 1.0 / dg);
    let ds_dr_inf = if r_inf > FINITE_DIFFERENCE_ABOVE_R_INF {
        central_difference_r_inf(r_inf, r, rg, d)?
    } else {
        let log = s * d / c; // L = SD/c, as the inversion computed it (ln1p, no cancellation)
        let c_prime = (1.0 + r_inf * r_inf) / (one_minus_sq * one_minus_sq);
        (c_prime * log + c * (1.0 / dr - 1.0 / dg + rg / a_g - r / a_r)) / d
    };
    let g = (1.0 - r_inf) * (1.0 - r_inf) / (2.0 * r_inf);
    let g_prime = -one_minus_sq / (2.0 * r_inf * r_inf);
    let ds = [ds_dr_inf, dsd_dr / d, dsd_drg / d, -s / d];
    let mut j = Matrix2x4::zeros();
    for (col, v) in ds.into_iter().enumerate() {
        j[(0, col)] = v;
        j[(1, col)] = g * v;
    }
    j[(1, 0)] += s * g_prime;
    Ok((sk, j))
}

/// `∂S/∂R∞` by a central difference of the inversion, with a step that stays inside the domain.
fn central_difference_r_inf(r_inf: f64, r: f64, rg: f64, d: f64) -> Result<f64, KmError> {
    let room = (r - r_inf).abs().min((rg - r_inf).abs()).min(1.0 - r_inf).max(0.0);
    let h = (1e-6 * r_inf).min(0.25 * room);
    if h <= 0.0 {
        // R∞ = 1 exactly: a one-sided difference from below.
        let h = 1e-7;
        return Ok((invert_s_k(r_inf, r, rg, d)?.s_per_mm - invert_s_k(r_inf - h, r, rg, d)?.s_per_mm) / h);
    }
    Ok((invert_s_k(r_inf + h, r, rg, d)?.s_per_mm - invert_s_k(r_inf - h, r, rg, d)?.s_per_mm) / (2.0 * h))
}

/// The standard uncertainties of S and K at one wavelength by linear propagation
/// (\[GUM\] eq. 13, `U_SK = J U_in Jᵀ` with nalgebra), and the condition number. Domain and
/// errors as [`invert_s_k`]; uncertainties must be finite and ≥ 0, the correlation in [0, 1].
///
/// # Examples
///
/// Only the thickness uncertain (1 % of D): S and K are uncertain by 1 % too, fully correlated.
///
/// ```
/// use rouge_measure::km_uncertainty::{InputUncertainty, propagate_s_k};
///
/// let u = propagate_s_k(0.2, 0.132, 0.03, 0.05, &InputUncertainty::readings(0.0, 0.0005))?;
/// assert!((u.u_s_per_mm / u.s_per_mm - 0.01).abs() < 1e-12, "{u:?}");
/// assert!((u.u_k_per_mm / u.k_per_mm - 0.01).abs() < 1e-12, "{u:?}");
/// assert!((u.correlation_sk - 1.0).abs() < 1e-9);
/// # Ok::<(), rouge_measure::KmError>(())
/// ```
pub fn propagate_s_k(
    r_inf: f64,
    r: f64,
    rg: f64,
    thickness_mm: f64,
    u: &InputUncertainty,
) -> Result<SkUncertainty, KmError> {
    u.check()?;
    let (sk, j) = invert_s_k_jacobian(r_inf, r, rg, thickness_mm)?;
    let cov: Matrix2<f64> = j * u.covariance() * j.transpose();
    let (var_s, var_k) = (cov[(0, 0)].max(0.0), cov[(1, 1)].max(0.0));
    let (u_s, u_k) = (var_s.sqrt(), var_k.sqrt());
    let correlation_sk = if u_s > 0.0 && u_k > 0.0 { (cov[(0, 1)] / (u_s * u_k)).clamp(-1.0, 1.0) } else { 0.0 };
    let condition = if sk.s_per_mm > 0.0 && sk.k_per_mm > 0.0 {
        let x = [r_inf, r, rg];
        let y = [sk.s_per_mm, sk.k_per_mm];
        let rel = Matrix2x3::from_fn(|i, k| j[(i, k)] * x[k] / y[i]);
        let sv = rel.singular_values();
        Some(sv.max()).filter(|v| v.is_finite())
    } else {
        None
    };
    Ok(SkUncertainty {
        s_per_mm: sk.s_per_mm,
        k_per_mm: sk.k_per_mm,
        u_s_per_mm: u_s,
        u_k_per_mm: u_k,
        correlation_sk,
        condition,
    })
}

/// Per-wavelength results of [`propagate_spectrum`].
#[derive(Clone, Debug, PartialEq)]
pub struct SpectralUncertainty {
    /// Per wavelength of the working grid.
    pub per_wavelength: Vec<SkUncertainty>,
}

impl SpectralUncertainty {
    /// u(S) per wavelength, mm⁻¹.
    pub fn u_s(&self) -> Spectrum {
        Spectrum(std::array::from_fn(|i| self.per_wavelength[i].u_s_per_mm))
    }

    /// u(K) per wavelength, mm⁻¹.
    pub fn u_k(&self) -> Spectrum {
        Spectrum(std::array::from_fn(|i| self.per_wavelength[i].u_k_per_mm))
    }

    /// Wavelengths (nm) where the inversion is ill-conditioned (condition > [`ILL_CONDITIONED`]),
    /// with the condition number.
    pub fn ill_conditioned(&self) -> Vec<(f64, f64)> {
        self.per_wavelength
            .iter()
            .enumerate()
            .filter_map(|(i, u)| u.condition.filter(|c| *c > ILL_CONDITIONED).map(|c| (working_wavelength_nm(i), c)))
            .collect()
    }
}

/// [`propagate_s_k`] at every wavelength of the working grid; `u_reflectance` is the readings'
/// repeatability per wavelength. An error names the first wavelength without a solution.
///
/// # Examples
///
/// A grey film whose R sits 0.002 from R∞ at every wavelength is flagged everywhere.
///
/// ```
/// use rouge_measure::km_uncertainty::propagate_spectrum;
/// use rouge_measure::Spectrum;
///
/// let c = Spectrum::constant;
/// let u = propagate_spectrum(&c(0.5), &c(0.498), &c(0.03), 0.05, &c(0.001), 0.0, 0.0).expect("in the domain");
/// assert_eq!(u.ill_conditioned().len(), 81);
/// let e = propagate_spectrum(&c(0.5), &c(0.6), &c(0.03), 0.05, &c(0.001), 0.0, 0.0).expect_err("R beyond R∞");
/// assert_eq!(e.0, 380.0);
/// ```
pub fn propagate_spectrum(
    r_inf: &Spectrum,
    r: &Spectrum,
    rg: &Spectrum,
    thickness_mm: f64,
    u_reflectance: &Spectrum,
    u_thickness_mm: f64,
    reading_correlation: f64,
) -> Result<SpectralUncertainty, (f64, KmError)> {
    let mut per_wavelength = Vec::with_capacity(WORKING_LEN);
    for i in 0..WORKING_LEN {
        let u =
            InputUncertainty { reading_correlation, ..InputUncertainty::readings(u_reflectance.0[i], u_thickness_mm) };
        let v =
            propagate_s_k(r_inf.0[i], r.0[i], rg.0[i], thickness_mm, &u).map_err(|e| (working_wavelength_nm(i), e))?;
        per_wavelength.push(v);
    }
    Ok(SpectralUncertainty { per_wavelength })
}

/// The thin-layer thickness at which a measurement of this product over this background would
/// give the most certain S and K (experiment design).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct ThicknessDesign {
    /// The best thickness, mm.
    pub thickness_mm: f64,
    /// The criterion there: RMS over wavelengths of `√((u(S)/S)² + (u(K)/K)²)`.
    pub relative_uncertainty: f64,
}

/// The criterion of [`optimal_thickness_mm`] at thickness `d`: the measurement that S, K would
/// give over `rg` at `d` (R∞ and R by the forward model) is propagated; wavelengths where S or
/// K is 0 carry no relative error and are left out. `None` where the inversion fails (R
/// indistinguishable from R∞: too thick).
pub fn design_criterion(
    s: &Spectrum,
    k: &Spectrum,
    rg: &Spectrum,
    d_mm: f64,
    u_reflectance: &Spectrum,
    u_thickness_mm: f64,
) -> Option<f64> {
    let (mut sum, mut n) = (0.0, 0usize);
    for i in 0..WORKING_LEN {
        let (si, ki) = (s.0[i], k.0[i]);
        if !(si > 0.0 && ki > 0.0) {
            continue;
        }
        let r_inf = km::r_inf_from_s_k(si, ki);
        let r = km::reflectance_over_background(si, ki, d_mm, rg.0[i]).ok()?;
        let u = propagate_s_k(r_inf, r, rg.0[i], d_mm, &InputUncertainty::readings(u_reflectance.0[i], u_thickness_mm))
            .ok()?;
        sum += (u.u_s_per_mm / si).powi(2) + (u.u_k_per_mm / ki).powi(2);
        n += 1;
    }
    (n > 0 && sum.is_finite()).then(|| (sum / n as f64).sqrt())
}

/// The thickness in `[lo_mm, hi_mm]` that minimises [`design_criterion`]: a scan of 49 points
/// even in log D, then a golden-section search (\[Kiefer1953\]) in log D around the best.
/// Thin layers lose S and K in the readings' noise (R ≈ Rg) and in the thickness's relative
/// uncertainty; thick ones hide the background (R ≈ R∞): the optimum lies between. `None`
/// when no thickness of the range gives a solution.
///
/// # Examples
///
/// A grey film (S 20, K 2 /mm) over a black card read to 0.001 with D known to 1 µm: the best
/// film is tens of µm thick, and it beats 5 µm and 1 mm.
///
/// ```
/// use rouge_measure::km_uncertainty::{design_criterion, optimal_thickness_mm};
/// use rouge_measure::Spectrum;
///
/// let (s, k, black, u) = (Spectrum::constant(20.0), Spectrum::constant(2.0), Spectrum::constant(0.03), Spectrum::constant(0.001));
/// let best = optimal_thickness_mm(&s, &k, &black, &u, 0.001, 0.001, 1.0).expect("a solution");
/// assert!(best.thickness_mm > 0.01 && best.thickness_mm < 0.5, "{best:?}");
/// for d in [0.005, 1.0] {
///     assert!(design_criterion(&s, &k, &black, d, &u, 0.001).unwrap_or(f64::INFINITY) > best.relative_uncertainty);
/// }
/// ```
pub fn optimal_thickness_mm(
    s: &Spectrum,
    k: &Spectrum,
    rg: &Spectrum,
    u_reflectance: &Spectrum,
    u_thickness_mm: f64,
    lo_mm: f64,
    hi_mm: f64,
) -> Option<ThicknessDesign> {
    if !(lo_mm > 0.0 && hi_mm >= lo_mm && hi_mm.is_finite()) {
        return None;
    }
    let f = |log_d: f64| design_criterion(s, k, rg, log_d.exp(), u_reflectance, u_thickness_mm).unwrap_or(f64::MAX);
    let (a, b) = (lo_mm.ln(), hi_mm.ln());
    const N: usize = 49;
    let grid: Vec<f64> = (0..N).map(|i| a + (b - a) * i as f64 / (N - 1) as f64).collect();
    let values: Vec<f64> = grid.iter().map(|&x| f(x)).collect();
    let best = (0..N).min_by(|&i, &j| values[i].total_cmp(&values[j]))?;
    if values[best] == f64::MAX {
        return None;
    }
    let (lo, hi) = (grid[best.saturating_sub(1)], grid[(best + 1).min(N - 1)]);
    let (x, v) = golden_section(f, lo, hi, 1e-4);
    let (x, v) = if v <= values[best] { (x, v) } else { (grid[best], values[best]) };
    Some(ThicknessDesign { thickness_mm: x.exp(), relative_uncertainty: v })
}

impl Preset {
    /// The standard uncertainties of S and K from the preset's own measurement
    /// ([`crate::km_uncertainty::propagate_spectrum`]; through the Saunderson correction's
    /// derivative when one was applied), stored in the preset and returned per wavelength.
    /// Errors: no measurement, or a wavelength without a solution (named).
    ///
    /// # Examples
    ///
    /// The demo measurement (Ivory) read to 0.001 with D known to 0.5 µm: S to a few per cent
    /// at 550 nm, and the preset keeps it.
    ///
    /// ```
    /// use rouge_measure::import::{ImportOptions, Kind, read_measurement};
    /// use rouge_measure::{Extrapolation, Preset, Spectrum};
    ///
    /// let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/measurements/foundation_02_ivory.csv");
    /// let m = read_measurement(&path, &ImportOptions::default())?;
    /// let w = m.to_working_grid(Extrapolation::Refuse)?;
    /// let (mut preset, _) = Preset::from_measurement(&m, &w, "Ivory", Kind::Foundation, 0.02, None)?;
    /// let u = preset.estimate_uncertainty("benchtop", &Spectrum::constant(0.001), 0.0005, 0.0)?;
    /// let at_550 = u.per_wavelength[34];
    /// assert!(at_550.u_s_per_mm / at_550.s_per_mm < 0.05, "{at_550:?}");
    /// assert!(preset.uncertainty.is_some());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn estimate_uncertainty(
        &mut self,
        source: &str,
        u_reflectance: &Spectrum,
        u_thickness_mm: f64,
        reading_correlation: f64,
    ) -> Result<SpectralUncertainty, PresetError> {
        let name = self.name.clone();
        let m = self.measurement.as_ref().ok_or_else(|| PresetError::Invalid {
            path: name.clone(),
            message: "no source measurement: the uncertainty of S and K needs the readings".into(),
        })?;
        let internal = |v: &[f64]| -> Spectrum {
            Spectrum(std::array::from_fn(|i| m.saunderson.map_or(v[i], |c| c.to_internal(v[i]))))
        };
        let (r_inf, r, rg) = (internal(&m.r_inf), internal(&m.r), internal(&m.rg));
        // u of an internal reading = u of the measured one × d(internal)/d(measured); the three
        // readings differ, so the largest factor stands for all (conservative).
        let u_in = Spectrum(std::array::from_fn(|i| {
            let f = m.saunderson.map_or(1.0, |c| {
                [m.r_inf[i], m.r[i], m.rg[i]].into_iter().map(|v| c.to_internal_derivative(v)).fold(0.0, f64::max)
            });
            u_reflectance.0[i] * f
        }));
        let u = propagate_spectrum(&r_inf, &r, &rg, self.thickness_mm, &u_in, u_thickness_mm, reading_correlation)
            .map_err(|(wavelength_nm, error)| PresetError::Inversion { path: name.clone(), wavelength_nm, error })?;
        self.uncertainty = Some(PresetUncertainty {
            source: source.to_string(),
            u_reflectance: u_reflectance.0.to_vec(),
            u_thickness_mm,
            reading_correlation,
            u_s_per_mm: u.u_s().0.to_vec(),
            u_k_per_mm: u.u_k().0.to_vec(),
        });
        Ok(u)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Central differences of the inversion itself, in every input.
    fn numeric(r_inf: f64, r: f64, rg: f64, d: f64) -> Matrix2x4<f64> {
        let x = [r_inf, r, rg, d];
        let mut j = Matrix2x4::zeros();
        for col in 0..4 {
            let h = 1e-6 * x[col].abs().max(1e-3);
            let (mut p, mut m) = (x, x);
            p[col] += h;
            m[col] -= h;
            let (a, b) =
                (invert_s_k(p[0], p[1], p[2], p[3]).expect("p"), invert_s_k(m[0], m[1], m[2], m[3]).expect("m"));
            j[(0, col)] = (a.s_per_mm - b.s_per_mm) / (2.0 * h);
            j[(1, col)] = (a.k_per_mm - b.k_per_mm) / (2.0 * h);
        }
        j
    }

    #[test]
    fn kubelka_munk_jacobian_matches_finite_differences() {
        // Dark and light backgrounds, mid and high R∞ (the difference branch above 0.999).
        for &(r_inf, r, rg, d) in &[
            (0.2, 0.132, 0.03, 0.05),
            (0.6, 0.45, 0.05, 0.02),
            (0.6, 0.7, 0.85, 0.02),
            (0.9, 0.5, 0.03, 0.01),
            (0.9995, 0.6, 0.04, 0.01),
        ] {
            let (_, j) = invert_s_k_jacobian(r_inf, r, rg, d).expect("in domain");
            let n = numeric(r_inf, r, rg, d);
            for i in 0..2 {
                for c in 0..4 {
                    let tol = 1e-5 * n[(i, c)].abs().max(1e-3);
                    assert!((j[(i, c)] - n[(i, c)]).abs() < tol, "{r_inf} {r} {rg}: {j} vs {n}");
                }
            }
        }
    }

    #[test]
    fn near_r_inf_the_inversion_is_flagged() {
        // R within 0.005 of R∞: a thick film over black, S and K barely determined.
        let u = InputUncertainty::readings(0.001, 0.0);
        let thick = propagate_s_k(0.5, 0.495, 0.03, 0.1, &u).expect("in domain");
        let thin = propagate_s_k(0.5, 0.3, 0.03, 0.01, &u).expect("in domain");
        assert!(thick.condition.expect("S, K > 0") > ILL_CONDITIONED, "{thick:?}");
        assert!(thin.condition.expect("S, K > 0") < ILL_CONDITIONED, "{thin:?}");
        assert!(thick.u_s_per_mm / thick.s_per_mm > 3.0 * thin.u_s_per_mm / thin.s_per_mm, "{thick:?} {thin:?}");
    }

    #[test]
    fn bad_uncertainties_are_refused() {
        let u = InputUncertainty { u_r: f64::NAN, ..InputUncertainty::readings(0.001, 0.0) };
        assert!(propagate_s_k(0.2, 0.132, 0.03, 0.05, &u).is_err());
        let u = InputUncertainty { reading_correlation: 1.5, ..InputUncertainty::readings(0.001, 0.0) };
        assert!(propagate_s_k(0.2, 0.132, 0.03, 0.05, &u).is_err());
    }
}
