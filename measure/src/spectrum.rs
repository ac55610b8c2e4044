//! Spectra on wavelength grids, and resampling onto Rouge's working grid.
//!
//! Every computation in Rouge happens on the **working grid**: 380-780 nm every 5 nm (81 samples),
//! the grid CIE 15:2004 recommends for colorimetry by summation. Measurements arrive on other grids
//! (1 nm from a spectroradiometer, 10 nm from an i1Pro, 400-700 nm from older instruments);
//! [`SampledSpectrum::to_working_grid`] brings them onto it:
//!
//! * **Uniform input grids** are interpolated with the \[Sprague1880\] fifth-order polynomial, as
//!   \[CIE167\] recommends for uniformly spaced spectral data. It passes through the measured
//!   values, so a 1 nm measurement resampled to 5 nm keeps its values at 380, 385, ... nm exactly
//!   (no band-pass averaging, as colour-science does).
//! * **Non-uniform grids** are interpolated linearly (Sprague needs equal spacing).
//! * A grid that does not cover 380-780 nm is **refused** unless the caller asks for
//!   [`Extrapolation::Constant`]: the nearest measured value is held out to the missing ends,
//!   the method CIE 15:2004 (section 7.2.2.1) suggests when nothing better is known. This changes
//!   colour noticeably only where the observer is sensitive; the importer says when it did it.

use std::fmt;

/// First wavelength of the working grid, nm.
pub const WORKING_START_NM: f64 = 380.0;
/// Spacing of the working grid, nm.
pub const WORKING_STEP_NM: f64 = 5.0;
/// Number of samples of the working grid (380, 385, ..., 780 nm).
pub const WORKING_LEN: usize = 81;

/// Wavelength of sample `i` of the working grid, nm.
#[inline]
pub fn working_wavelength_nm(i: usize) -> f64 {
    WORKING_START_NM + WORKING_STEP_NM * i as f64
}

/// The working grid's wavelengths, nm.
pub fn working_wavelengths_nm() -> [f64; WORKING_LEN] {
    std::array::from_fn(working_wavelength_nm)
}

/// A spectrum on the working grid (380-780 nm, 5 nm): reflectance, transmittance, S or K.
#[derive(Clone, Copy, PartialEq)]
pub struct Spectrum(pub [f64; WORKING_LEN]);

impl Spectrum {
    /// A spectrum with the same value at every wavelength.
    pub fn constant(value: f64) -> Self {
        Spectrum([value; WORKING_LEN])
    }

    /// Builds a spectrum from a function of wavelength (nm).
    pub fn from_fn(mut f: impl FnMut(f64) -> f64) -> Self {
        Spectrum(std::array::from_fn(|i| f(working_wavelength_nm(i))))
    }

    /// Builds a spectrum from exactly 81 values on the working grid.
    pub fn from_slice(values: &[f64]) -> Result<Self, SpectrumError> {
        let arr: [f64; WORKING_LEN] =
            values.try_into().map_err(|_| SpectrumError::WrongLength { expected: WORKING_LEN, found: values.len() })?;
        Ok(Spectrum(arr))
    }

    /// The values, in working-grid order.
    pub fn values(&self) -> &[f64; WORKING_LEN] {
        &self.0
    }

    /// Pairs of (wavelength nm, value).
    pub fn iter_nm(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.0.iter().enumerate().map(|(i, &v)| (working_wavelength_nm(i), v))
    }

    /// Applies `f` to every value.
    pub fn map(&self, mut f: impl FnMut(f64) -> f64) -> Self {
        Spectrum(std::array::from_fn(|i| f(self.0[i])))
    }

    /// Smallest and largest value.
    pub fn min_max(&self) -> (f64, f64) {
        self.0.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| (lo.min(v), hi.max(v)))
    }
}

impl std::borrow::Borrow<[f64; WORKING_LEN]> for Spectrum {
    fn borrow(&self) -> &[f64; WORKING_LEN] {
        &self.0
    }
}

impl fmt::Debug for Spectrum {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (lo, hi) = self.min_max();
        write!(
            f,
            "Spectrum(380-780 nm/5, min {lo}, max {hi}, [{}, {}, ..., {}])",
            self.0[0],
            self.0[1],
            self.0[WORKING_LEN - 1]
        )
    }
}

/// What to do when a measured grid does not cover 380-780 nm.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Extrapolation {
    /// Refuse: an error names the missing range. The default.
    #[default]
    Refuse,
    /// Hold the nearest measured value constant (CIE 15:2004, 7.2.2.1).
    Constant,
}

/// How [`SampledSpectrum::to_working_grid`] produced its result, for import reports.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ResampleMethod {
    /// The input was already on the working grid: values copied unchanged.
    Identity,
    /// \[Sprague1880\] interpolation of a uniform grid (\[CIE167\]).
    Sprague,
    /// Linear interpolation of a non-uniform grid.
    Linear,
}

/// Report of a resampling.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Resampled {
    /// The spectrum on the working grid.
    pub spectrum: Spectrum,
    /// Interpolation used.
    pub method: ResampleMethod,
    /// Working-grid wavelengths below the measured range that were extrapolated (nm, inclusive), if any.
    pub extrapolated_below_nm: Option<(f64, f64)>,
    /// Working-grid wavelengths above the measured range that were extrapolated (nm, inclusive), if any.
    pub extrapolated_above_nm: Option<(f64, f64)>,
}

/// Errors about a spectrum's grid or values.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SpectrumError {
    /// Fewer samples than interpolation needs.
    #[error("a spectrum needs at least 2 samples, found {0}")]
    TooFewSamples(usize),
    /// Wavelengths and values differ in length.
    #[error("{wavelengths} wavelengths but {values} values")]
    LengthMismatch {
        /// number of wavelengths
        wavelengths: usize,
        /// number of values
        values: usize,
    },
    /// Working-grid spectrum of the wrong length.
    #[error("expected {expected} values on the 380-780 nm / 5 nm grid, found {found}")]
    WrongLength {
        /// expected length
        expected: usize,
        /// found length
        found: usize,
    },
    /// A wavelength or value that is not a finite number.
    #[error("non-finite {what} at index {index} ({value})")]
    NonFinite {
        /// "wavelength" or "value"
        what: &'static str,
        /// index in the input
        index: usize,
        /// the offending number
        value: f64,
    },
    /// Wavelengths not strictly increasing.
    #[error("wavelengths must increase strictly: {next_nm} nm follows {prev_nm} nm")]
    NotIncreasing {
        /// earlier wavelength
        prev_nm: f64,
        /// the wavelength that does not increase
        next_nm: f64,
    },
    /// The grid does not cover the working range and extrapolation was not requested.
    #[error(
        "the measured range {first_nm}-{last_nm} nm does not cover 380-780 nm; \
         ask for constant extrapolation (--extrapolate) to hold the end values"
    )]
    DoesNotCover {
        /// first measured wavelength
        first_nm: f64,
        /// last measured wavelength
        last_nm: f64,
    },
}

/// A spectrum measured on an arbitrary, strictly increasing wavelength grid.
#[derive(Clone, Debug, PartialEq)]
pub struct SampledSpectrum {
    wavelengths_nm: Vec<f64>,
    values: Vec<f64>,
}

impl SampledSpectrum {
    /// Checks the grid (finite, strictly increasing, at least 2 samples) and the values (finite).
    pub fn new(wavelengths_nm: Vec<f64>, values: Vec<f64>) -> Result<Self, SpectrumError> {
        if wavelengths_nm.len() != values.len() {
            return Err(SpectrumError::LengthMismatch { wavelengths: wavelengths_nm.len(), values: values.len() });
        }
        if wavelengths_nm.len() < 2 {
            return Err(SpectrumError::TooFewSamples(wavelengths_nm.len()));
        }
        for (index, (&w, &v)) in wavelengths_nm.iter().zip(&values).enumerate() {
            if !w.is_finite() {
                return Err(SpectrumError::NonFinite { what: "wavelength", index, value: w });
            }
            if !v.is_finite() {
                return Err(SpectrumError::NonFinite { what: "value", index, value: v });
            }
        }
        for pair in wavelengths_nm.windows(2) {
            if pair[1] <= pair[0] {
                return Err(SpectrumError::NotIncreasing { prev_nm: pair[0], next_nm: pair[1] });
            }
        }
        Ok(SampledSpectrum { wavelengths_nm, values })
    }

    /// The measured wavelengths, nm.
    pub fn wavelengths_nm(&self) -> &[f64] {
        &self.wavelengths_nm
    }

    /// The measured values.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// Whether the grid is uniform (all steps equal to within 1e-6 nm).
    pub fn uniform_step_nm(&self) -> Option<f64> {
        let w = &self.wavelengths_nm;
        let step = (w[w.len() - 1] - w[0]) / (w.len() - 1) as f64;
        w.windows(2).all(|p| ((p[1] - p[0]) - step).abs() <= 1e-6).then_some(step)
    }

    /// Resamples onto the working grid (see the module documentation for the method).
    pub fn to_working_grid(&self, extrapolation: Extrapolation) -> Result<Resampled, SpectrumError> {
        let w = &self.wavelengths_nm;
        let first = w[0];
        let last = w[w.len() - 1];
        let working_last = working_wavelength_nm(WORKING_LEN - 1);
        let tol = 1e-6;
        let covers = first <= WORKING_START_NM + tol && last >= working_last - tol;
        if !covers && extrapolation == Extrapolation::Refuse {
            return Err(SpectrumError::DoesNotCover { first_nm: first, last_nm: last });
        }
        let step = self.uniform_step_nm();
        // Identity: exactly the working grid.
        if w.len() == WORKING_LEN
            && step.is_some_and(|s| (s - WORKING_STEP_NM).abs() <= tol)
            && (first - WORKING_START_NM).abs() <= tol
        {
            let spectrum = Spectrum::from_slice(&self.values)?;
            return Ok(Resampled {
                spectrum,
                method: ResampleMethod::Identity,
                extrapolated_below_nm: None,
                extrapolated_above_nm: None,
            });
        }
        let method = match step {
            Some(_) if w.len() >= 6 => ResampleMethod::Sprague,
            _ => ResampleMethod::Linear,
        };
        let sprague = match (method, step) {
            (ResampleMethod::Sprague, Some(step)) => Some(Sprague::new(first, step, &self.values)),
            _ => None,
        };
        let mut below: Option<(f64, f64)> = None;
        let mut above: Option<(f64, f64)> = None;
        let spectrum = Spectrum::from_fn(|nm| {
            if nm < first - tol {
                below = Some((below.map_or(nm, |b| b.0), nm));
                self.values[0]
            } else if nm > last + tol {
                above = Some((above.map_or(nm, |a| a.0), nm));
                self.values[self.values.len() - 1]
            } else if let Some(s) = &sprague {
                s.eval(nm)
            } else {
                linear_interpolate(w, &self.values, nm)
            }
        });
        Ok(Resampled { spectrum, method, extrapolated_below_nm: below, extrapolated_above_nm: above })
    }
}

/// Linear interpolation on a strictly increasing grid; outside it the end values are held.
pub(crate) fn linear_interpolate(xs: &[f64], ys: &[f64], x: f64) -> f64 {
    let i = xs.partition_point(|&v| v <= x);
    if i == 0 {
        return ys[0];
    }
    if i >= xs.len() {
        return ys[ys.len() - 1];
    }
    let (x0, x1) = (xs[i - 1], xs[i]);
    let t = (x - x0) / (x1 - x0);
    ys[i - 1] + t * (ys[i] - ys[i - 1])
}

/// \[Sprague1880\] interpolation of uniformly spaced data, with the \[CIE167\] end extension.
///
/// Two points are added at each end by the fixed Sprague extrapolation coefficients, then each
/// interval [r_i, r_{i+1}] is a quintic through r_{i-2} .. r_{i+3}. Coefficients as published in
/// \[CIE167\] (and used by colour-science's `SpragueInterpolator`).
struct Sprague {
    first_nm: f64,
    step_nm: f64,
    /// Values with two extrapolated points prepended and appended.
    padded: Vec<f64>,
}

impl Sprague {
    fn new(first_nm: f64, step_nm: f64, y: &[f64]) -> Self {
        let n = y.len();
        debug_assert!(n >= 6);
        let dot = |c: [f64; 6], v: [f64; 6]| c.iter().zip(v).map(|(c, v)| c * v).sum::<f64>() / 209.0;
        let head = [y[0], y[1], y[2], y[3], y[4], y[5]];
        let tail = [y[n - 1], y[n - 2], y[n - 3], y[n - 4], y[n - 5], y[n - 6]];
        let c_outer = [884.0, -1960.0, 3033.0, -2648.0, 1080.0, -180.0];
        let c_inner = [508.0, -540.0, 488.0, -367.0, 144.0, -24.0];
        let mut padded = Vec::with_capacity(n + 4);
        padded.push(dot(c_outer, head));
        padded.push(dot(c_inner, head));
        padded.extend_from_slice(y);
        padded.push(dot(c_inner, tail));
        padded.push(dot(c_outer, tail));
        Sprague { first_nm, step_nm, padded }
    }

    fn eval(&self, nm: f64) -> f64 {
        let n = self.padded.len() - 4;
        let pos = (nm - self.first_nm) / self.step_nm;
        let i = (pos.floor().max(0.0) as usize).min(n - 2);
        let x = (pos - i as f64).clamp(0.0, 1.0);
        if x == 0.0 {
            return self.padded[i + 2];
        }
        let r = &self.padded[i..i + 6]; // r[2] is y[i]
        let a0 = r[2];
        let a1 = (2.0 * r[0] - 16.0 * r[1] + 16.0 * r[3] - 2.0 * r[4]) / 24.0;
        let a2 = (-r[0] + 16.0 * r[1] - 30.0 * r[2] + 16.0 * r[3] - r[4]) / 24.0;
        let a3 = (-9.0 * r[0] + 39.0 * r[1] - 70.0 * r[2] + 66.0 * r[3] - 33.0 * r[4] + 7.0 * r[5]) / 24.0;
        let a4 = (13.0 * r[0] - 64.0 * r[1] + 126.0 * r[2] - 124.0 * r[3] + 61.0 * r[4] - 12.0 * r[5]) / 24.0;
        let a5 = (-5.0 * r[0] + 25.0 * r[1] - 50.0 * r[2] + 50.0 * r[3] - 25.0 * r[4] + 5.0 * r[5]) / 24.0;
        a0 + x * (a1 + x * (a2 + x * (a3 + x * (a4 + x * a5))))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(start: f64, step: f64, end: f64) -> Vec<f64> {
        let n = ((end - start) / step).round() as usize + 1;
        (0..n).map(|i| start + step * i as f64).collect()
    }

    #[test]
    fn working_grid_is_identity() {
        let w = grid(380.0, 5.0, 780.0);
        let v: Vec<f64> = w.iter().map(|x| (x / 100.0).sin()).collect();
        let r = SampledSpectrum::new(w, v.clone()).unwrap().to_working_grid(Extrapolation::Refuse).unwrap();
        assert_eq!(r.method, ResampleMethod::Identity);
        assert_eq!(&r.spectrum.0[..], &v[..]);
    }

    #[test]
    fn one_nm_data_keeps_its_values_at_the_5nm_knots() {
        let w = grid(360.0, 1.0, 830.0);
        let v: Vec<f64> = w.iter().map(|x| 0.5 + 0.3 * (x / 37.0).sin()).collect();
        let r = SampledSpectrum::new(w.clone(), v.clone()).unwrap().to_working_grid(Extrapolation::Refuse).unwrap();
        assert_eq!(r.method, ResampleMethod::Sprague);
        for (i, (nm, val)) in r.spectrum.iter_nm().enumerate() {
            let j = (nm - 360.0) as usize;
            assert_eq!(val, v[j], "at {nm} nm (index {i})");
        }
    }

    #[test]
    fn sprague_reproduces_a_quintic_exactly_inside() {
        // Sprague is exact for polynomials up to degree 5 away from the ends.
        let p = |x: f64| {
            let t = (x - 580.0) / 200.0;
            0.4 + 0.1 * t - 0.2 * t * t + 0.05 * t.powi(3) + 0.02 * t.powi(4) - 0.01 * t.powi(5)
        };
        let w = grid(360.0, 10.0, 830.0);
        let v: Vec<f64> = w.iter().map(|&x| p(x)).collect();
        let r = SampledSpectrum::new(w, v).unwrap().to_working_grid(Extrapolation::Refuse).unwrap();
        for (nm, val) in r.spectrum.iter_nm() {
            assert!((val - p(nm)).abs() < 1e-13, "{nm}: {val} vs {}", p(nm));
        }
    }

    #[test]
    fn short_grid_is_refused_unless_extrapolation_is_asked() {
        let w = grid(400.0, 10.0, 700.0);
        let v = vec![0.5; w.len()];
        let s = SampledSpectrum::new(w, v).unwrap();
        let err = s.to_working_grid(Extrapolation::Refuse).unwrap_err();
        assert!(err.to_string().contains("400-700 nm"), "{err}");
        let r = s.to_working_grid(Extrapolation::Constant).unwrap();
        assert_eq!(r.extrapolated_below_nm, Some((380.0, 395.0)));
        assert_eq!(r.extrapolated_above_nm, Some((705.0, 780.0)));
        assert!(r.spectrum.0.iter().all(|&v| (v - 0.5).abs() < 1e-15));
    }

    #[test]
    fn non_uniform_grid_is_linear() {
        let w = vec![370.0, 500.0, 520.0, 800.0];
        let v = vec![0.0, 1.0, 1.0, 0.0];
        let r = SampledSpectrum::new(w, v).unwrap().to_working_grid(Extrapolation::Refuse).unwrap();
        assert_eq!(r.method, ResampleMethod::Linear);
        assert!((r.spectrum.0[((435.0 - 380.0) / 5.0) as usize] - 0.5).abs() < 1e-15);
    }

    #[test]
    fn bad_grids_are_errors() {
        assert!(matches!(
            SampledSpectrum::new(vec![400.0, 400.0, 410.0], vec![0.1; 3]),
            Err(SpectrumError::NotIncreasing { .. })
        ));
        assert!(matches!(
            SampledSpectrum::new(vec![400.0, 410.0], vec![0.1, f64::NAN]),
            Err(SpectrumError::NonFinite { .. })
        ));
        assert!(matches!(SampledSpectrum::new(vec![400.0], vec![0.1]), Err(SpectrumError::TooFewSamples(1))));
    }
}
