//! Axis ticks, the one home of the rule every plot and legend of the app and the command line
//! uses: steps of 1, 2 or 5 × 10ⁿ, labelled with as many decimals as the step needs.

/// The smallest of 1, 2 or 5 × 10ⁿ that splits `span` into at most `intervals` equal parts
/// (1 for an empty or non-finite span).
pub fn nice_step(span: f64, intervals: usize) -> f64 {
    let raw = span.abs() / intervals.max(1) as f64;
    if !(raw > 0.0 && raw.is_finite()) {
        return 1.0;
    }
    let decade = 10f64.powf(raw.log10().floor());
    // 1.0 + 1e-9: a span that is an exact multiple keeps its step despite rounding in log10.
    [1.0, 2.0, 5.0, 10.0].iter().map(|m| m * decade).find(|&s| s * (1.0 + 1e-9) >= raw).unwrap_or(10.0 * decade)
}

/// The multiples of `step` in [`lo`, `hi`].
pub fn ticks_with_step(lo: f64, hi: f64, step: f64) -> Vec<f64> {
    if !(step > 0.0 && lo.is_finite() && hi.is_finite()) {
        return Vec::new();
    }
    let (first, last) = ((lo / step - 1e-9).ceil() as i64, (hi / step + 1e-9).floor() as i64);
    (first..=last).map(|k| k as f64 * step).collect()
}

/// Tick positions over [`lo`, `hi`]: the multiples of [`nice_step`] of the span in at most
/// `intervals` parts.
pub fn ticks(lo: f64, hi: f64, intervals: usize) -> Vec<f64> {
    ticks_with_step(lo, hi, nice_step(hi - lo, intervals))
}

/// `v` with as many decimals as a tick `step` needs (none for steps of 1 and more).
pub fn label(v: f64, step: f64) -> String {
    let decimals = if step >= 1.0 || step <= 0.0 { 0 } else { (-step.log10().floor()).max(0.0) as usize };
    // -0.0 prints as "-0".
    let v = if v == 0.0 { 0.0 } else { v };
    format!("{v:.decimals$}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_are_one_two_or_five_times_a_power_of_ten_and_fit() {
        assert_eq!(nice_step(1.0, 5), 0.2);
        assert_eq!(nice_step(1.0, 4), 0.5);
        assert_eq!(nice_step(400.0, 8), 50.0);
        assert_eq!(nice_step(37.0, 5), 10.0);
        assert_eq!(nice_step(0.003, 4), 0.001);
        assert_eq!(nice_step(0.0, 4), 1.0);
        for span in [0.013, 0.7, 3.0, 42.0, 950.0, 12_345.0] {
            let s = nice_step(span, 5);
            assert!(span / s <= 5.0 + 1e-9 && span / s > 1.0, "{span}: {s}");
        }
    }

    #[test]
    fn ticks_cover_the_range_and_labels_read() {
        assert_eq!(ticks(0.0, 1.0, 5), vec![0.0, 0.2, 0.4, 0.6000000000000001, 0.8, 1.0]);
        assert_eq!(ticks(380.0, 780.0, 8), vec![400.0, 450.0, 500.0, 550.0, 600.0, 650.0, 700.0, 750.0]);
        assert_eq!(label(0.6000000000000001, 0.2), "0.6");
        assert_eq!(label(750.0, 50.0), "750");
        assert_eq!(label(0.005, 0.005), "0.005");
        assert_eq!(label(-0.0, 0.1), "0.0");
    }
}
