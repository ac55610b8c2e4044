//! Kubelka-Munk against high-precision references: `data/reference/km_*.csv`, written by
//! `python/gen_km_reference.py` with mpmath at 60 digits from the exact binary64 inputs, printed
//! to 30 significant digits (parsed here with `str::parse::<f64>`, which rounds correctly).
//!
//! Every row is checked on the scalar path (`km::invert_s_k`, `km::layer_r_t`,
//! `km::reflectance_over_background`, `km::compose`) and, for inversion and the forward layer,
//! on the batch fast path (`km_batch::invert_batch`, `km_batch::layer_batch`, all rows at once),
//! to a relative error of 1e-9. References that are exactly 0 must be met exactly; references
//! below `f64::MIN_POSITIVE` need a result of at most 1e-300. The worst relative errors are
//! printed (run with `--nocapture`) for `docs/`.

use rouge_measure::km::{self, LayerRt};
use rouge_measure::km_batch::{self, BatchError};
use rouge_tests::{RefValue, Table, data_path};

const TOL: f64 = 1e-9;

/// Worst relative error seen, with its case and quantity.
#[derive(Debug, Default)]
struct Worst {
    error: f64,
    at: String,
}

impl Worst {
    fn note(&mut self, e: f64, case: &str, what: &str) {
        if e > self.error || self.at.is_empty() {
            self.error = e;
            self.at = format!("{case} ({what})");
        }
    }
}

/// Checks one value, recording a failure (with the case name) or the error.
fn check(failures: &mut Vec<String>, worst: &mut Worst, path: &str, case: &str, what: &str, value: f64, r: RefValue) {
    match r.check(value, TOL) {
        Ok(e) => worst.note(e, case, what),
        Err(msg) => failures.push(format!("{path} {case}: {what} {msg}")),
    }
}

fn finish(file: &str, rows: usize, scalar: &Worst, batch: Option<&Worst>, failures: &[String]) {
    let batch = batch.map_or_else(String::new, |b| format!("; batch {:.2e} at {}", b.error, b.at));
    eprintln!("{file}: {rows} rows, worst relative error: scalar {:.2e} at {}{batch}", scalar.error, scalar.at);
    assert!(failures.is_empty(), "{} failures:\n{}", failures.len(), failures.join("\n"));
}

/// A row whose expected result is an error (a reference cell that is not a number, e.g.
/// `error` / `ValueError`): the library must return `Err`.
fn is_error_row(t: &Table, row: &rouge_tests::Row, columns: &[&str]) -> bool {
    columns.iter().any(|c| RefValue::parse(t.text(row, c)).is_none())
}

#[test]
fn inversion_matches_mpmath() {
    let file = "km_invert.csv";
    let t = Table::read(&data_path(&format!("reference/{file}")));
    let (mut failures, mut scalar, mut batch) = (Vec::new(), Worst::default(), Worst::default());
    let mut ok_rows = Vec::new();
    for row in &t.rows {
        let case = t.text(row, "case");
        let (r_inf, r, rg, d) = (t.num(row, "r_inf"), t.num(row, "r"), t.num(row, "rg"), t.num(row, "thickness_mm"));
        let result = km::invert_s_k(r_inf, r, rg, d);
        if is_error_row(&t, row, &["s_per_mm", "k_per_mm"]) {
            if let Ok(c) = result {
                failures.push(format!("{file} {case}: expected an error, got {c:?}"));
            }
            let (mut s, mut k) = ([0.0], [0.0]);
            match km_batch::invert_batch(&[r_inf], &[r], &[rg], &[d], &mut s, &mut k) {
                Err(BatchError::Sample { index: 0, .. }) => {}
                other => failures.push(format!("{file} {case}: batch should fail at sample 0, got {other:?}")),
            }
            continue;
        }
        match result {
            Ok(c) => {
                check(&mut failures, &mut scalar, file, case, "S", c.s_per_mm, t.reference(row, "s_per_mm"));
                check(&mut failures, &mut scalar, file, case, "K", c.k_per_mm, t.reference(row, "k_per_mm"));
            }
            Err(e) => failures.push(format!("{file} {case}: unexpected error {e}")),
        }
        ok_rows.push(row);
    }
    let col = |name: &str| ok_rows.iter().map(|r| t.num(r, name)).collect::<Vec<f64>>();
    let (r_inf, r, rg, d) = (col("r_inf"), col("r"), col("rg"), col("thickness_mm"));
    let mut s = vec![f64::NAN; ok_rows.len()];
    let mut k = vec![f64::NAN; ok_rows.len()];
    match km_batch::invert_batch(&r_inf, &r, &rg, &d, &mut s, &mut k) {
        Ok(()) => {
            for (i, row) in ok_rows.iter().enumerate() {
                let case = t.text(row, "case");
                check(&mut failures, &mut batch, file, case, "batch S", s[i], t.reference(row, "s_per_mm"));
                check(&mut failures, &mut batch, file, case, "batch K", k[i], t.reference(row, "k_per_mm"));
            }
        }
        Err(e) => {
            let case = match e {
                BatchError::Sample { index, .. } => t.text(ok_rows[index], "case"),
                BatchError::LengthMismatch(_) => "-",
            };
            failures.push(format!("{file}: invert_batch failed: {e} (case {case})"));
        }
    }
    finish(file, t.rows.len(), &scalar, Some(&batch), &failures);
}

#[test]
fn forward_layer_matches_mpmath() {
    let file = "km_forward.csv";
    let t = Table::read(&data_path(&format!("reference/{file}")));
    let (mut failures, mut scalar, mut batch) = (Vec::new(), Worst::default(), Worst::default());
    let mut ok_rows = Vec::new();
    for row in &t.rows {
        let case = t.text(row, "case");
        let (s, k, x, rg) =
            (t.num(row, "s_per_mm"), t.num(row, "k_per_mm"), t.num(row, "thickness_mm"), t.num(row, "rg"));
        let layer = km::layer_r_t(s, k, x);
        let over = km::reflectance_over_background(s, k, x, rg);
        if is_error_row(&t, row, &["r0", "t", "r_over_rg"]) {
            if layer.is_ok() && over.is_ok() {
                failures.push(format!("{file} {case}: expected an error, got {layer:?}, {over:?}"));
            }
            continue;
        }
        match (layer, over) {
            (Ok(l), Ok(ro)) => {
                check(&mut failures, &mut scalar, file, case, "R0", l.r, t.reference(row, "r0"));
                check(&mut failures, &mut scalar, file, case, "T", l.t, t.reference(row, "t"));
                check(&mut failures, &mut scalar, file, case, "R over Rg", ro, t.reference(row, "r_over_rg"));
            }
            (l, ro) => failures.push(format!("{file} {case}: unexpected error {l:?} {ro:?}")),
        }
        ok_rows.push(row);
    }
    let col = |name: &str| ok_rows.iter().map(|r| t.num(r, name)).collect::<Vec<f64>>();
    let (s, k, x) = (col("s_per_mm"), col("k_per_mm"), col("thickness_mm"));
    let mut r0 = vec![f64::NAN; ok_rows.len()];
    let mut tr = vec![f64::NAN; ok_rows.len()];
    match km_batch::layer_batch(&s, &k, &x, &mut r0, &mut tr) {
        Ok(()) => {
            for (i, row) in ok_rows.iter().enumerate() {
                let case = t.text(row, "case");
                check(&mut failures, &mut batch, file, case, "batch R0", r0[i], t.reference(row, "r0"));
                check(&mut failures, &mut batch, file, case, "batch T", tr[i], t.reference(row, "t"));
                // The batch layer over the background, composed as the scalar path does.
                let ro = km::compose(LayerRt { r: r0[i], t: tr[i] }, LayerRt::opaque(t.num(row, "rg"))).r;
                check(&mut failures, &mut batch, file, case, "batch R over Rg", ro, t.reference(row, "r_over_rg"));
            }
        }
        Err(e) => failures.push(format!("{file}: layer_batch failed: {e}")),
    }
    finish(file, t.rows.len(), &scalar, Some(&batch), &failures);
}

#[test]
fn composition_matches_mpmath() {
    let file = "km_stack.csv";
    let t = Table::read(&data_path(&format!("reference/{file}")));
    let (mut failures, mut scalar) = (Vec::new(), Worst::default());
    for row in &t.rows {
        let case = t.text(row, "case");
        let top = LayerRt { r: t.num(row, "r1"), t: t.num(row, "t1") };
        let bottom = LayerRt { r: t.num(row, "r2"), t: t.num(row, "t2") };
        let c = km::compose(top, bottom);
        if is_error_row(&t, row, &["r12", "t12"]) {
            // compose has no error path: an error row would need km::check_layer to refuse an input.
            if km::check_layer(top).is_ok() && km::check_layer(bottom).is_ok() {
                failures.push(format!("{file} {case}: expected an error, got {c:?}"));
            }
            continue;
        }
        check(&mut failures, &mut scalar, file, case, "R12", c.r, t.reference(row, "r12"));
        check(&mut failures, &mut scalar, file, case, "T12", c.t, t.reference(row, "t12"));
        let s = km::stack(&[top, bottom]);
        if s != c {
            failures.push(format!("{file} {case}: stack(&[top, bottom]) = {s:?} differs from compose = {c:?}"));
        }
    }
    finish(file, t.rows.len(), &scalar, None, &failures);
}
