//! Two-flux Kubelka-Munk theory: inversion of S and K from measurements, forward reflectance and
//! transmittance of a layer, and composition of layers. Scalar reference implementations, accurate
//! over the whole domain; [`crate::km_batch`] holds the data-parallel fast paths.
//!
//! Reference: \[Huang2013\] eq. 1-4 (layer and composition) and eq. 6-7 (inversion), which restate
//! the hyperbolic solution of \[Kubelka1948\] and the layer composition of \[Kubelka1954\]; the
//! two-flux model is \[Kubelka1931\]. Keys: docs/REFERENCES.md.
//!
//! # Derivations and the printed equations
//!
//! With `a = 1 + K/S = (1/R∞ + R∞)/2` and `b = √(a²−1) = (1/R∞ − R∞)/2`:
//!
//! * **Inversion (eq. 6).** The printed form `S = [coth⁻¹((a−R)/b) − coth⁻¹((a−Rg)/b)]/(bD)` is
//!   undefined when the background is lighter than the layer (`Rg > R∞` puts `(a−Rg)/b` inside
//!   (−1, 1), outside `coth⁻¹`'s real domain), and it cancels catastrophically when `R ≈ Rg` (thin
//!   layer) or `R∞ → 1` (`b → 0`). Writing `coth⁻¹ u = ½ ln((u+1)/(u−1))` and using
//!   `a ± b = R∞^{∓1}` gives one logarithm valid on both sides of `R∞`:
//!   `2bSD = ln[(1 − R R∞)(Rg − R∞) / ((1 − Rg R∞)(R − R∞))] = ln(1 + z)` with
//!   `z = (Rg − R)(1 − R∞²) / ((1 − Rg R∞)(R − R∞))` (the numerator minus the denominator of the
//!   ratio factors exactly). Since `2b = (1 − R∞²)/R∞`,
//!   `SD = R∞ · φ(z) · (Rg − R) / ((1 − Rg R∞)(R − R∞))` with `φ(z) = ln(1+z)/z`, `φ(0) = 1`.
//!   Every factor is a product of accurately computed differences: no cancellation remains, and
//!   at `R∞ = 1` it is exactly the `K = 0` limit `SD = (R − Rg)/((1 − R)(1 − Rg))`.
//! * **K (eq. 7)** `K = S(a − 1) = S (1 − R∞)² / (2R∞)`, which keeps `K → 0` accurate as `R∞ → 1`.
//! * **Forward (eq. 1-2).** With `β = bS = √(K(K + 2S))`, `y = βX`, `q = tanh(y)/β` (`q → X` as
//!   `β → 0`) and `w = (S + K) q`: `R0 = S q / (1 + w)` and `T = sech(y) / (1 + w)`. Dividing
//!   numerator and denominator of eq. 1-2 by `cosh` removes the overflow of `sinh`/`cosh` at large
//!   `SX`, and `q` removes the `0/0` at `K = 0` (`R0 = SX/(1+SX)`, `T = 1/(1+SX)`) and at `S = 0`
//!   (`R0 = 0`, `T = e^{−KX}`).
//! * **Composition (eq. 3-4).** \[Huang2013\] prints `R₁,₂ = R₁ + T₁R₁T₁/(1 − R₁R₂)`; summing the
//!   inter-reflection series gives `R₁,₂ = R₁ + T₁² R₂/(1 − R₁R₂)` (the light that reaches layer 2
//!   is reflected by `R₂`, not `R₁`). `T₁,₂ = T₁T₂/(1 − R₁R₂)` is printed correctly. KM layers are
//!   symmetric (same `R` from both sides), so a stack is folded from the bottom up.

use std::fmt;

/// Scattering and absorption coefficients of a layer, per millimetre.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KmCoefficients {
    /// Scattering coefficient S, mm⁻¹.
    pub s_per_mm: f64,
    /// Absorption coefficient K, mm⁻¹.
    pub k_per_mm: f64,
}

/// Diffuse reflectance and transmittance of a layer (or a stack) for diffuse illumination.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LayerRt {
    /// Reflectance over an ideal black background (R0 of eq. 1).
    pub r: f64,
    /// Transmittance (T of eq. 2).
    pub t: f64,
}

impl LayerRt {
    /// A layer that is not there: reflects nothing, transmits everything.
    pub const CLEAR: LayerRt = LayerRt { r: 0.0, t: 1.0 };

    /// An opaque background of reflectance `rg` (transmits nothing).
    pub fn opaque(rg: f64) -> Self {
        LayerRt { r: rg, t: 0.0 }
    }
}

/// Why a set of inputs has no Kubelka-Munk solution.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum KmError {
    /// R∞ outside (0, 1] or not a number.
    #[error("R∞ = {0} is outside (0, 1]: an opaque layer reflects more than nothing and at most everything")]
    RInfOutOfRange(f64),
    /// A reflectance outside [0, 1] or not a number.
    #[error("{name} = {value} is outside [0, 1]")]
    ReflectanceOutOfRange {
        /// "R", "Rg", "R0" or "T"
        name: &'static str,
        /// the value
        value: f64,
    },
    /// Thickness not strictly positive and finite.
    #[error("thickness D = {0} mm must be positive and finite")]
    BadThickness(f64),
    /// R and Rg on opposite sides of R∞.
    #[error(
        "R = {r} and Rg = {rg} lie on opposite sides of R∞ = {r_inf}: a layer moves reflectance \
         from the background's towards R∞, never past it"
    )]
    OppositeSides {
        /// R∞
        r_inf: f64,
        /// R
        r: f64,
        /// Rg
        rg: f64,
    },
    /// R farther from R∞ than Rg.
    #[error(
        "R = {r} lies farther from R∞ = {r_inf} than Rg = {rg} does: a layer can only move \
         reflectance from the background's towards R∞"
    )]
    BeyondBackground {
        /// R∞
        r_inf: f64,
        /// R
        r: f64,
        /// Rg
        rg: f64,
    },
    /// R = R∞ over a background of a different reflectance.
    #[error("R = R∞ = {r_inf} while Rg = {rg}: only an infinitely thick layer hides its background completely")]
    InfinitelyThick {
        /// R∞
        r_inf: f64,
        /// Rg
        rg: f64,
    },
    /// The background has the layer's own R∞, so R carries no information about S.
    #[error("Rg = R∞ = {r_inf}: over a background of its own colour a layer is invisible, so S cannot be measured")]
    BackgroundEqualsRInf {
        /// R∞
        r_inf: f64,
    },
    /// The result is too large to represent.
    #[error("S = {s_times_d} / D overflows (D = {thickness_mm} mm is too small)")]
    Overflow {
        /// S·D
        s_times_d: f64,
        /// D
        thickness_mm: f64,
    },
    /// A coefficient that is negative or not finite.
    #[error("{name} = {value} must be finite and ≥ 0")]
    BadCoefficient {
        /// "S", "K" or "X"
        name: &'static str,
        /// the value
        value: f64,
    },
    /// A layer that creates energy (R + T > 1).
    #[error("R = {r} and T = {t} add up to more than 1")]
    NotPassive {
        /// R
        r: f64,
        /// T
        t: f64,
    },
}

fn check_unit(name: &'static str, value: f64) -> Result<(), KmError> {
    if (0.0..=1.0).contains(&value) { Ok(()) } else { Err(KmError::ReflectanceOutOfRange { name, value }) }
}

/// `ln(1 + z) / z` for `z ≥ 0`, accurate near 0 and finite for `z = ∞` (returns 0).
#[inline]
pub(crate) fn ln1p_over_x(z: f64) -> f64 {
    if z < 1e-4 {
        // Taylor series; the first omitted term z⁴/5 is below 2e-17 here.
        1.0 - z * (0.5 - z * (1.0 / 3.0 - z * 0.25))
    } else {
        z.ln_1p() / z
    }
}

/// Inverts Kubelka-Munk S and K (per mm) from the reflectance `r_inf` of an opaque layer, the
/// reflectance `r` of a layer of thickness `thickness_mm` over a background, and the background's
/// reflectance `rg` (\[Huang2013\] eq. 6-7, rewritten as derived in the module documentation).
///
/// Domain: `0 < R∞ ≤ 1`; `R, Rg ∈ [0, 1]` on the same side of `R∞` with `R` between `Rg` and
/// `R∞` (background darker *or lighter* than the layer); `D > 0`. `R = Rg ≠ R∞` gives
/// `S = K = 0` (no layer). Accurate to a few ulps of the exact result for the given inputs across
/// the domain, including `R∞ = 1` (`K = 0`), `R ≈ Rg` (very thin) and `R ≈ R∞` (very thick).
/// Outside the domain: an error saying why. Never NaN.
///
/// # Examples
///
/// R∞ = 0.2, and R = 0.132 for 50 µm over a black card of Rg = 0.03: S = 3.73148 /mm,
/// K = 5.97036 /mm by 50-digit mpmath (`data/reference/km_invert.csv`, `ordinary_rinf0.2_black03`).
///
/// ```
/// use rouge_measure::km::invert_s_k;
///
/// let sk = invert_s_k(0.2, 0.132, 0.03, 0.05)?;
/// assert!((sk.s_per_mm / 3.731_475_278_712_077 - 1.0).abs() < 1e-13, "{sk}");
/// assert!((sk.k_per_mm / 5.970_360_445_939_322 - 1.0).abs() < 1e-13, "{sk}");
/// // R beyond R∞, seen from a darker background, has no solution: an error, not NaN.
/// assert!(invert_s_k(0.2, 0.25, 0.03, 0.05).is_err());
/// # Ok::<(), rouge_measure::KmError>(())
/// ```
pub fn invert_s_k(r_inf: f64, r: f64, rg: f64, thickness_mm: f64) -> Result<KmCoefficients, KmError> {
    if !(r_inf > 0.0 && r_inf <= 1.0) {
        return Err(KmError::RInfOutOfRange(r_inf));
    }
    check_unit("R", r)?;
    check_unit("Rg", rg)?;
    if !(thickness_mm > 0.0 && thickness_mm.is_finite()) {
        return Err(KmError::BadThickness(thickness_mm));
    }
    let dr = r - r_inf;
    let dg = rg - r_inf;
    if dg == 0.0 {
        return Err(KmError::BackgroundEqualsRInf { r_inf });
    }
    if dr == 0.0 {
        return Err(KmError::InfinitelyThick { r_inf, rg });
    }
    if (dr > 0.0) != (dg > 0.0) {
        return Err(KmError::OppositeSides { r_inf, r, rg });
    }
    if dr.abs() > dg.abs() {
        return Err(KmError::BeyondBackground { r_inf, r, rg });
    }
    if r == rg {
        return Ok(KmCoefficients { s_per_mm: 0.0, k_per_mm: 0.0 });
    }
    let one_minus = 1.0 - r_inf;
    let one_minus_sq = one_minus * (1.0 + r_inf); // 1 − R∞², no cancellation
    let one_minus_rg_rinf = (-rg).mul_add(r_inf, 1.0); // 1 − Rg R∞, correctly rounded
    // (Rg − R) / ((1 − Rg R∞)(R − R∞)) > 0 by the checks above.
    let ratio = (rg - r) / one_minus_rg_rinf / dr;
    let z = ratio * one_minus_sq;
    let s_times_d = if z.is_finite() {
        r_inf * ln1p_over_x(z) * ratio
    } else {
        // z overflowed (R − R∞ subnormal): ln(1+z) = ln z to far below an ulp.
        let ln_z = (rg - r).abs().ln() + one_minus_sq.ln() - one_minus_rg_rinf.ln() - dr.abs().ln();
        r_inf / one_minus_sq * ln_z
    };
    let s_per_mm = s_times_d / thickness_mm;
    if !s_per_mm.is_finite() {
        return Err(KmError::Overflow { s_times_d, thickness_mm });
    }
    let k_per_mm = s_per_mm * (one_minus * one_minus / (2.0 * r_inf));
    Ok(KmCoefficients { s_per_mm, k_per_mm })
}

fn check_coefficient(name: &'static str, value: f64) -> Result<(), KmError> {
    if value >= 0.0 && value.is_finite() { Ok(()) } else { Err(KmError::BadCoefficient { name, value }) }
}

/// `sech(y)` for `y ≥ 0` without overflow: `2e^{−y}/(1 + e^{−2y})`.
#[inline]
fn sech(y: f64) -> f64 {
    let m = (-y).exp();
    2.0 * m / (1.0 + m * m)
}

/// Reflectance R0 (over black) and transmittance T of a layer with scattering `s_per_mm`,
/// absorption `k_per_mm` and thickness `thickness_mm` (\[Huang2013\] eq. 1-2, rewritten as derived in
/// the module documentation).
///
/// Domain: S, K finite and ≥ 0; X ≥ 0, `X = ∞` allowed (an opaque layer: `T = 0`, `R0 = R∞`).
/// Stable for `K = 0`, `S = 0`, `S = K = 0` (a clear layer), tiny `SX` and huge `SX` (no
/// overflow: `R0 → R∞`, `T → 0`, underflowing gracefully).
///
/// # Examples
///
/// S = 10 /mm, K = 1 /mm, 50 µm: R0 = 0.318992, T = 0.632435 by 50-digit mpmath
/// (`data/reference/km_forward.csv`, `ordinary0_black`); infinitely thick, R0 = R∞ and T = 0.
///
/// ```
/// use rouge_measure::km::{layer_r_t, r_inf_from_s_k};
///
/// let film = layer_r_t(10.0, 1.0, 0.05)?;
/// assert!((film.r - 0.318_991_668_936_967_9).abs() < 1e-15, "{film:?}");
/// assert!((film.t - 0.632_434_987_322_699_3).abs() < 1e-15, "{film:?}");
/// let opaque = layer_r_t(10.0, 1.0, f64::INFINITY)?;
/// assert!((opaque.r - r_inf_from_s_k(10.0, 1.0)).abs() < 1e-15 && opaque.t == 0.0, "{opaque:?}");
/// # Ok::<(), rouge_measure::KmError>(())
/// ```
pub fn layer_r_t(s_per_mm: f64, k_per_mm: f64, thickness_mm: f64) -> Result<LayerRt, KmError> {
    check_coefficient("S", s_per_mm)?;
    check_coefficient("K", k_per_mm)?;
    if thickness_mm.is_nan() || thickness_mm < 0.0 {
        return Err(KmError::BadCoefficient { name: "X", value: thickness_mm });
    }
    Ok(layer_r_t_unchecked(s_per_mm, k_per_mm, thickness_mm))
}

/// `β = bS = √(K(K + 2S))`: one square root of the product (as the batch path computes it, so
/// both round alike), or the product of two roots where the product would overflow or underflow.
#[inline]
pub(crate) fn beta(s: f64, k: f64) -> f64 {
    let prod = k * (k + 2.0 * s);
    if prod.is_finite() && (prod == 0.0 || prod >= f64::MIN_POSITIVE) {
        prod.sqrt()
    } else {
        k.sqrt() * (k + 2.0 * s).sqrt()
    }
}

/// [`layer_r_t`] without the argument checks (the caller guarantees the domain).
#[inline]
pub(crate) fn layer_r_t_unchecked(s: f64, k: f64, x: f64) -> LayerRt {
    let sk = s + k;
    if x == 0.0 || sk == 0.0 {
        return LayerRt::CLEAR;
    }
    let beta = beta(s, k);
    let (y, q) = if beta == 0.0 {
        (0.0, x)
    } else {
        let y = beta * x;
        let q = if y < 1e-4 {
            // tanh(y)/y = 1 − y²/3 + 2y⁴/15 − …; the omitted term is below 1e-25.
            let y2 = y * y;
            x * (1.0 - y2 * (1.0 / 3.0 - y2 * (2.0 / 15.0)))
        } else {
            y.tanh() / beta
        };
        (y, q)
    };
    let w = sk * q;
    // R0 = S q / (1 + w), written so that w = ∞ (K = 0, X = ∞) gives S/(S+K) instead of ∞/∞.
    let r = (s / sk) / (1.0 + 1.0 / w);
    let t = sech(y) / (1.0 + w);
    LayerRt { r, t }
}

/// Reflectance of an opaque layer, `R∞ = 1 + K/S − √((K/S)² + 2K/S) = S/(S + K + √(K(K+2S)))`
/// (the second form has no cancellation). `S = K = 0` gives 0 (a clear layer reflects nothing
/// however thick). Domain: S, K finite and ≥ 0.
/// (\[Kubelka1948\]; the `a − b` of \[Huang2013\] eq. 1-2 with `a = 1 + K/S`, `b = √(a² − 1)`.)
///
/// # Examples
///
/// S = 10 /mm, K = 1 /mm: `a = 1.1`, `R∞ = 1.1 − √0.21 = 0.641742…`; no scattering, no
/// reflectance.
///
/// ```
/// use rouge_measure::km::r_inf_from_s_k;
///
/// assert!((r_inf_from_s_k(10.0, 1.0) - (1.1 - 0.21f64.sqrt())).abs() < 1e-15);
/// assert_eq!(r_inf_from_s_k(0.0, 3.0), 0.0);
/// assert_eq!(r_inf_from_s_k(5.0, 0.0), 1.0);
/// ```
pub fn r_inf_from_s_k(s_per_mm: f64, k_per_mm: f64) -> f64 {
    let den = s_per_mm + k_per_mm + k_per_mm.sqrt() * (k_per_mm + 2.0 * s_per_mm).sqrt();
    if den == 0.0 { 0.0 } else { s_per_mm / den }
}

/// Puts layer `top` over `bottom` (\[Huang2013\] eq. 3-4, corrected: see the module documentation).
///
/// `top` must be a symmetric layer (a single KM layer: same R from above and below); `bottom`
/// may be anything seen from above, including an opaque background ([`LayerRt::opaque`]).
/// If `R₁R₂ = 1` (two perfect reflectors) the result is `R = 1, T = 0`.
///
/// # Examples
///
/// R₁ = 0.3, T₁ = 0.5 over R₂ = 0.4, T₂ = 0.4: R = 0.3 + 0.25·0.4/0.88 = 0.413636, T =
/// 0.2/0.88 = 0.227273 (`data/reference/km_stack.csv`, `ordinary_a`); the printed numerator
/// T₁R₁T₁ would give 0.385227.
///
/// ```
/// use rouge_measure::km::{LayerRt, compose};
///
/// let both = compose(LayerRt { r: 0.3, t: 0.5 }, LayerRt { r: 0.4, t: 0.4 });
/// assert!((both.r - 0.413_636_363_636_363_6).abs() < 1e-15, "{both:?}");
/// assert!((both.t - 0.227_272_727_272_727_3).abs() < 1e-15, "{both:?}");
/// ```
#[inline]
pub fn compose(top: LayerRt, bottom: LayerRt) -> LayerRt {
    let den = (-top.r).mul_add(bottom.r, 1.0);
    if den <= 0.0 {
        return LayerRt { r: 1.0, t: 0.0 };
    }
    LayerRt { r: top.r + top.t * top.t * bottom.r / den, t: top.t * bottom.t / den }
}

/// Composite R and T of a stack of KM layers listed **top first**, folded from the bottom up so
/// each step puts one symmetric layer over what lies below. An empty stack is clear.
///
/// # Examples
///
/// A sheer film (R = 0.05, T = 0.9) over another (R = 0.6, T = 0.2) is
/// `compose(top, bottom)`: R = 0.551031, T = 0.185567 (`data/reference/km_stack.csv`,
/// `ordinary_b`); over an opaque skin the stack transmits nothing.
///
/// ```
/// use rouge_measure::km::{LayerRt, stack};
///
/// let (top, bottom) = (LayerRt { r: 0.05, t: 0.9 }, LayerRt { r: 0.6, t: 0.2 });
/// let two = stack(&[top, bottom]);
/// assert!((two.r - 0.551_030_927_835_051_6).abs() < 1e-15, "{two:?}");
/// assert!((two.t - 0.185_567_010_309_278_4).abs() < 1e-15, "{two:?}");
/// assert_eq!(stack(&[top, bottom, LayerRt::opaque(0.35)]).t, 0.0);
/// assert_eq!(stack(&[]), LayerRt::CLEAR);
/// ```
pub fn stack(layers_top_first: &[LayerRt]) -> LayerRt {
    layers_top_first.iter().rev().fold(LayerRt::CLEAR, |below, &layer| compose(layer, below))
}

/// Checks a layer given by R and T: both in [0, 1] and `R + T ≤ 1` (within 1e-12).
pub fn check_layer(layer: LayerRt) -> Result<LayerRt, KmError> {
    check_unit("R0", layer.r)?;
    check_unit("T", layer.t)?;
    if layer.r + layer.t > 1.0 + 1e-12 {
        return Err(KmError::NotPassive { r: layer.r, t: layer.t });
    }
    Ok(layer)
}

/// Reflectance of a KM layer (S, K per mm, thickness mm) over an opaque background of
/// reflectance `rg`: `R = R0 + T² Rg/(1 − R0 Rg)`.
/// (\[Huang2013\] eq. 1-3: the layer of [`layer_r_t`] composed with the background.)
///
/// # Examples
///
/// S = 10 /mm, K = 1 /mm, 50 µm over a white card (Rg = 0.85): R = 0.785445 by 50-digit
/// mpmath (`data/reference/km_forward.csv`, `ordinary0_white`).
///
/// ```
/// use rouge_measure::km::reflectance_over_background;
///
/// let r = reflectance_over_background(10.0, 1.0, 0.05, 0.85)?;
/// assert!((r - 0.785_445_134_075_400_6).abs() < 1e-15, "{r}");
/// # Ok::<(), rouge_measure::KmError>(())
/// ```
pub fn reflectance_over_background(s_per_mm: f64, k_per_mm: f64, thickness_mm: f64, rg: f64) -> Result<f64, KmError> {
    check_unit("Rg", rg)?;
    let layer = layer_r_t(s_per_mm, k_per_mm, thickness_mm)?;
    Ok(compose(layer, LayerRt::opaque(rg)).r)
}

/// Duncan's mixing rule (\[Duncan1940\]): the S and K of a mixture are the concentration-weighted
/// sums of its components' S and K, `S = Σ cᵢ Sᵢ`, `K = Σ cᵢ Kᵢ`, with `cᵢ` the volume fraction
/// of component `i` and `Sᵢ`, `Kᵢ` its coefficients at concentration 1 (the two-constant form).
///
/// Domain: every `cᵢ`, `Sᵢ`, `Kᵢ` finite and ≥ 0; the fractions need not add up to 1 (a binder
/// with `S = K = 0` takes the rest). Valid while the components scatter independently (low
/// pigment volume fractions; crowding of TiO₂ above ~10 vol% lowers S below the sum).
///
/// # Examples
///
/// A quarter of a white (S = 40, K = 1 /mm) with three quarters of a dark pigment (S = 2,
/// K = 8 /mm): S = 11.5 /mm, K = 6.25 /mm.
///
/// ```
/// use rouge_measure::km::{KmCoefficients, duncan_mix};
///
/// let white = KmCoefficients { s_per_mm: 40.0, k_per_mm: 1.0 };
/// let dark = KmCoefficients { s_per_mm: 2.0, k_per_mm: 8.0 };
/// let mix = duncan_mix([(0.25, white), (0.75, dark)])?;
/// assert_eq!((mix.s_per_mm, mix.k_per_mm), (11.5, 6.25));
/// # Ok::<(), rouge_measure::KmError>(())
/// ```
pub fn duncan_mix(components: impl IntoIterator<Item = (f64, KmCoefficients)>) -> Result<KmCoefficients, KmError> {
    let mut mix = KmCoefficients { s_per_mm: 0.0, k_per_mm: 0.0 };
    for (c, KmCoefficients { s_per_mm, k_per_mm }) in components {
        check_coefficient("concentration", c)?;
        check_coefficient("S", s_per_mm)?;
        check_coefficient("K", k_per_mm)?;
        mix.s_per_mm = c.mul_add(s_per_mm, mix.s_per_mm);
        mix.k_per_mm = c.mul_add(k_per_mm, mix.k_per_mm);
    }
    if !(mix.s_per_mm.is_finite() && mix.k_per_mm.is_finite()) {
        return Err(KmError::BadCoefficient { name: "mixture S or K", value: f64::INFINITY });
    }
    Ok(mix)
}

/// \[Saunderson1942\] correction between the reflectance an instrument measures and the internal
/// reflectance that Kubelka-Munk describes.
///
/// Light meets the air/binder interface twice: a fraction `K1` of the incident light is
/// reflected at the surface before it enters, and a fraction `K2` of the diffuse light inside
/// is reflected back in on its way out. Then
/// `R_measured = f·K1 + (1 − K1)(1 − K2) R_internal / (1 − K2 R_internal)` with `f = 1` when the
/// instrument includes the specular reflection (SCI, d/8 with the gloss trap closed) and `f = 0`
/// when it excludes it (SCE, 45/0).
///
/// **When to use it:** for glossy, resin- or oil-bound films (lipsticks, liquid foundations)
/// whose refractive index differs from air, when S and K must transfer between thicknesses and
/// backgrounds: the correction makes R∞ and R consistent with KM's assumption of no interface.
/// Without it, S and K absorb the interface's effect and remain fine for re-rendering the same
/// kind of measurement (which is what \[Huang2013\] does). **What it changes:** internal
/// reflectances are lower than measured ones at low reflectance (the surface reflection is
/// removed) and higher at high reflectance (internal re-reflection is added back), so K/S rises
/// for dark colours and S rises for most layers. Typical values: `K1 = ((n−1)/(n+1))²` = 0.04
/// for n = 1.5; `K2` ≈ 0.4-0.6 (0.6 is the classic value for diffuse light inside n = 1.5).
///
/// # Examples
///
/// n = 1.5 (K1 = 0.04), K2 = 0.6, specular included: an internal 0.5 is measured as
/// 0.04 + 0.96·0.4·0.5/0.7 = 0.314286, and the correction takes it back.
///
/// ```
/// use rouge_measure::Saunderson;
///
/// let c = Saunderson::from_refractive_index(1.5, 0.6, true)?;
/// assert!((c.k1 - 0.04).abs() < 1e-15);
/// let measured = c.to_measured(0.5);
/// assert!((measured - (0.04 + 0.96 * 0.4 * 0.5 / 0.7)).abs() < 1e-15, "{measured}");
/// assert!((c.to_internal(measured) - 0.5).abs() < 1e-15);
/// # Ok::<(), rouge_measure::KmError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Saunderson {
    /// External (Fresnel) reflectance at normal incidence.
    pub k1: f64,
    /// Internal diffuse reflectance.
    pub k2: f64,
    /// Whether the measurement includes the specular component (SCI).
    pub specular_included: bool,
}

impl Saunderson {
    /// `K1` from the refractive index `n` (Fresnel at normal incidence), with the given `K2`.
    pub fn from_refractive_index(n: f64, k2: f64, specular_included: bool) -> Result<Self, KmError> {
        if !(n >= 1.0 && n.is_finite()) {
            return Err(KmError::BadCoefficient { name: "refractive index", value: n });
        }
        if !(0.0..1.0).contains(&k2) {
            return Err(KmError::BadCoefficient { name: "K2", value: k2 });
        }
        let k1 = ((n - 1.0) / (n + 1.0)).powi(2);
        Ok(Saunderson { k1, k2, specular_included })
    }

    fn f_k1(&self) -> f64 {
        if self.specular_included { self.k1 } else { 0.0 }
    }

    /// Measured reflectance → internal reflectance:
    /// `R_i = (R_m − fK1) / ((1 − K1)(1 − K2) + K2 (R_m − fK1))`. Result clamped to [0, 1]
    /// (measurement noise can push a black sample below the surface reflection).
    pub fn to_internal(&self, r_measured: f64) -> f64 {
        let x = r_measured - self.f_k1();
        let r = x / ((1.0 - self.k1) * (1.0 - self.k2) + self.k2 * x);
        r.clamp(0.0, 1.0)
    }

    /// `dR_i/dR_m`, the derivative of [`Saunderson::to_internal`]:
    /// `A / (A + K2 (R_m − fK1))²` with `A = (1 − K1)(1 − K2)` (0 where the result is clamped),
    /// what carries a reading's uncertainty to the internal reflectance.
    ///
    /// ```
    /// use rouge_measure::Saunderson;
    ///
    /// let c = Saunderson::from_refractive_index(1.5, 0.6, true)?;
    /// let h = 1e-6;
    /// let numeric = (c.to_internal(0.3 + h) - c.to_internal(0.3 - h)) / (2.0 * h);
    /// assert!((c.to_internal_derivative(0.3) - numeric).abs() < 1e-8);
    /// # Ok::<(), rouge_measure::KmError>(())
    /// ```
    pub fn to_internal_derivative(&self, r_measured: f64) -> f64 {
        let x = r_measured - self.f_k1();
        let a = (1.0 - self.k1) * (1.0 - self.k2);
        let r = x / (a + self.k2 * x);
        if (0.0..=1.0).contains(&r) { a / (a + self.k2 * x).powi(2) } else { 0.0 }
    }

    /// Internal reflectance → measured reflectance.
    pub fn to_measured(&self, r_internal: f64) -> f64 {
        self.f_k1() + (1.0 - self.k1) * (1.0 - self.k2) * r_internal / (1.0 - self.k2 * r_internal)
    }
}

impl fmt::Display for KmCoefficients {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "S = {} /mm, K = {} /mm", self.s_per_mm, self.k_per_mm)
    }
}
