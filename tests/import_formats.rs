//! Measurement import end to end (`docs/FORMATS.md`):
//!
//! * every product in `data/measurements/*.csv` imports, resamples to the working grid and
//!   inverts; the recovered S and K match the noise-free truth (`truth/<slug>.csv`) with a
//!   median relative error below 5 % (measurement noise makes single wavelengths much worse);
//! * the instrument examples in `data/measurements/formats/` (X-Rite CGATS, Argyll .ti3 and .sp,
//!   CS-2000 radiance, i1Profiler) give the same R∞, R and Rg as `foundation_02_ivory.csv`, to
//!   the tolerance `docs/FORMATS.md` gives for each format;
//! * every file in `data/measurements/bad/` fails with the line and column its `# BAD FILE:`
//!   comment names, and a missing file gives an error naming its path.
//!
//! Run with `--nocapture` to see the error tables.

use rouge_measure::LocatedError;
use rouge_measure::import::{self, ImportOptions, Kind, Measurement, WorkingMeasurement};
use rouge_measure::preset::{Preset, PresetError};
use rouge_measure::spectrum::{Extrapolation, working_wavelength_nm};
use rouge_tests::{Table, data_path, median};
use std::path::{Path, PathBuf};

fn measurements_dir() -> PathBuf {
    data_path("measurements")
}

fn read(path: &Path) -> Measurement {
    import::read_measurement(path, &ImportOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

fn working(m: &Measurement, extrapolation: Extrapolation) -> WorkingMeasurement {
    m.to_working_grid(extrapolation).unwrap_or_else(|e| panic!("{e}"))
}

/// Index of a wavelength on the working grid (380..780 nm every 5 nm).
fn working_index(nm: f64) -> usize {
    let i = ((nm - 380.0) / 5.0).round();
    assert!((0.0..=80.0).contains(&i) && (working_wavelength_nm(i as usize) - nm).abs() < 1e-9, "{nm} nm");
    i as usize
}

fn preset(m: &Measurement, w: &WorkingMeasurement, thickness_mm: f64) -> Result<Preset, PresetError> {
    Preset::from_measurement(m, w, &m.name, m.kind.unwrap_or(Kind::Other), thickness_mm, None).map(|(p, _)| p)
}

// ---------------------------------------------------------------------------------------------
// Products against their truth

#[test]
fn every_product_inverts_close_to_its_truth() {
    let mut products: Vec<PathBuf> = std::fs::read_dir(measurements_dir())
        .expect("data/measurements")
        .map(|e| e.expect("directory entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "csv"))
        .collect();
    products.sort();
    assert_eq!(products.len(), 13, "docs/FORMATS.md lists 13 products: {products:?}");
    let mut failures = Vec::new();
    eprintln!(
        "{:<26} {:>4} {:>9} {:>9} {:>7} {:>9} {:>9} {:>7}",
        "product", "n", "S median", "S max", "at nm", "K median", "K max", "at nm"
    );
    for path in &products {
        let slug = path.file_stem().expect("file name").to_string_lossy().into_owned();
        let m = read(path);
        let w = working(&m, Extrapolation::Refuse);
        let thickness = m.thickness_mm.unwrap_or_else(|| panic!("{slug}: no thickness_mm"));
        let p = match preset(&m, &w, thickness) {
            Ok(p) => p,
            Err(e) => {
                failures.push(format!("{slug}: inversion failed: {e}"));
                continue;
            }
        };
        let truth = Table::read(&measurements_dir().join("truth").join(format!("{slug}.csv")));
        let (mut es, mut ek) = (Vec::new(), Vec::new());
        let (mut worst_s, mut worst_k) = ((0.0f64, 0.0), (0.0f64, 0.0));
        for row in &truth.rows {
            let nm = truth.num(row, "wavelength_nm");
            let i = working_index(nm);
            let (s, k) = (truth.num(row, "s_per_mm"), truth.num(row, "k_per_mm"));
            assert!(s > 0.0 && k > 0.0, "{slug} {nm} nm: truth S, K must be positive for relative errors");
            let e_s = (p.s_per_mm[i] - s).abs() / s;
            let e_k = (p.k_per_mm[i] - k).abs() / k;
            if e_s > worst_s.0 {
                worst_s = (e_s, nm);
            }
            if e_k > worst_k.0 {
                worst_k = (e_k, nm);
            }
            es.push(e_s);
            ek.push(e_k);
        }
        let (ms, mk) = (median(&es), median(&ek));
        eprintln!(
            "{slug:<26} {:>4} {:>8.2}% {:>8.2}% {:>7} {:>8.2}% {:>8.2}% {:>7}",
            es.len(),
            100.0 * ms,
            100.0 * worst_s.0,
            worst_s.1,
            100.0 * mk,
            100.0 * worst_k.0,
            worst_k.1
        );
        if !(ms < 0.05 && mk < 0.05) {
            failures.push(format!("{slug}: median relative error S {ms:.4}, K {mk:.4} (limit 0.05)"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

// ---------------------------------------------------------------------------------------------
// Instrument formats against the Rouge CSV of the same product

fn formats_dir() -> PathBuf {
    measurements_dir().join("formats")
}

/// The reference: `foundation_02_ivory.csv` (5 nm grid, so on the working grid unchanged).
fn ivory_reference() -> WorkingMeasurement {
    let m = read(&measurements_dir().join("foundation_02_ivory.csv"));
    working(&m, Extrapolation::Refuse)
}

/// Largest |a − b| over the three spectra at the given wavelengths; panics with the first
/// difference above `tol`. Returns the largest difference for the report.
fn compare(label: &str, got: &WorkingMeasurement, want: &WorkingMeasurement, nms: &[f64], tol: f64) -> f64 {
    let mut worst = 0.0f64;
    for (role, a, b) in [("R∞", &got.r_inf, &want.r_inf), ("R", &got.r, &want.r), ("Rg", &got.rg, &want.rg)] {
        for &nm in nms {
            let i = working_index(nm);
            let d = (a.0[i] - b.0[i]).abs();
            assert!(
                d <= tol,
                "{label}: {role} at {nm} nm is {} vs {} in the Rouge CSV (|Δ| {d:e} > {tol:e})",
                a.0[i],
                b.0[i]
            );
            worst = worst.max(d);
        }
    }
    eprintln!("{label:<42} {:>3} wavelengths, max |Δ| {worst:.2e} (tolerance {tol:.1e})", nms.len());
    worst
}

fn grid(first: f64, last: f64, step: f64) -> Vec<f64> {
    let n = ((last - first) / step).round() as usize;
    (0..=n).map(|i| first + step * i as f64).collect()
}

/// "Exact" formats carry the same 6-decimal fractions (or 4-decimal percent): they differ from
/// the CSV only by the rounding of a division by 100 or of the resampling at a grid node.
const EXACT: f64 = 1e-12;

/// Inverts with the thickness the product was measured at; the instrument files must be usable.
fn check_inverts(label: &str, m: &Measurement, w: &WorkingMeasurement) {
    if let Err(e) = preset(m, w, 0.020) {
        panic!("{label}: inversion failed: {e}");
    }
}

#[test]
fn xrite_cgats_matches_the_csv() {
    let m = read(&formats_dir().join("foundation_02_ivory_xrite.txt"));
    assert_eq!(m.thickness_mm, Some(0.020), "ROUGE_THICKNESS_MM");
    let w = working(&m, Extrapolation::Refuse);
    // 10 nm file: compare only at the measured wavelengths (Sprague between them differs from
    // the 5 nm data).
    compare("X-Rite CGATS (.txt, 10 nm)", &w, &ivory_reference(), &grid(380.0, 780.0, 10.0), EXACT);
    check_inverts("X-Rite", &m, &w);
}

#[test]
fn argyll_ti3_matches_the_csv() {
    let m = read(&formats_dir().join("foundation_02_ivory.ti3"));
    assert_eq!(m.thickness_mm, Some(0.020), "ROUGE_THICKNESS_MM");
    let w = working(&m, Extrapolation::Refuse);
    compare("Argyll .ti3 (percent, 10 nm)", &w, &ivory_reference(), &grid(380.0, 780.0, 10.0), EXACT);
    check_inverts("Argyll .ti3", &m, &w);
}

#[test]
fn argyll_sp_files_match_the_csv() {
    let f = |role: &str| formats_dir().join(format!("foundation_02_ivory_{role}.sp"));
    let m = import::read_measurement_files(&f("r_inf"), &f("r"), &f("rg")).unwrap_or_else(|e| panic!("{e}"));
    let w = working(&m, Extrapolation::Refuse);
    compare("Argyll .sp x3 (percent, 5 nm)", &w, &ivory_reference(), &grid(380.0, 780.0, 5.0), EXACT);
    check_inverts("Argyll .sp", &m, &w);
    // A file given in a role its ROUGE_ROLE contradicts is refused, naming that file.
    let e = import::read_measurement_files(&f("r"), &f("r_inf"), &f("rg")).expect_err("roles swapped");
    assert_eq!(e.path, f("r"), "{e}");
}

#[test]
fn cs2000_radiance_matches_the_csv() {
    let m = read(&formats_dir().join("foundation_02_ivory_cs2000.csv"));
    let w = working(&m, Extrapolation::Refuse);
    // 1 nm radiance: every 5 nm working wavelength was measured. 6 significant digits of radiance.
    compare("CS-2000 radiance (1 nm)", &w, &ivory_reference(), &grid(380.0, 780.0, 5.0), 2e-5);
    check_inverts("CS-2000", &m, &w);
}

#[test]
fn i1profiler_needs_extrapolation_and_then_matches_the_csv() {
    let m = read(&formats_dir().join("foundation_02_ivory_i1profiler.txt"));
    let e = m.to_working_grid(Extrapolation::Refuse).expect_err("380-730 nm does not cover the working grid");
    assert!(e.to_string().contains("730"), "the error should name where the data ends: {e}");
    let w = working(&m, Extrapolation::Constant);
    // 4 decimals: rounding of the CSV's 6-decimal values by up to 5e-5.
    compare(
        "i1Profiler CGATS (4 decimals, 380-730 nm)",
        &w,
        &ivory_reference(),
        &grid(380.0, 730.0, 10.0),
        5e-5 + EXACT,
    );
    assert_eq!(w.extrapolated, vec![(735.0, 780.0)], "the extrapolated range is reported");
    for (role, measured, s) in [("R∞", &m.r_inf, &w.r_inf), ("R", &m.r, &w.r), ("Rg", &m.rg, &w.rg)] {
        assert_eq!(measured.wavelengths_nm().last(), Some(&730.0));
        let end = *measured.values().last().expect("values");
        // At the node the interpolation reproduces the measured value (up to its rounding).
        assert!((s.0[working_index(730.0)] - end).abs() <= EXACT, "{role} at 730 nm");
        for nm in grid(735.0, 780.0, 5.0) {
            assert_eq!(s.0[working_index(nm)], end, "{role} at {nm} nm: constant extrapolation holds the 730 nm value");
        }
    }
    check_inverts("i1Profiler", &m, &w);
}

// ---------------------------------------------------------------------------------------------
// Malformed files

fn bad_dir() -> PathBuf {
    measurements_dir().join("bad")
}

/// What a `# BAD FILE:` comment says.
#[derive(Debug, Default, PartialEq)]
struct BadFileComment {
    text: String,
    /// Where the fault is: the last `line N` (or the end of `lines A-B`) mentioned before
    /// `column M`, or the last one mentioned when there is no column.
    line: Option<usize>,
    column: Option<usize>,
    /// `at N nm`, for faults found by the inversion.
    wavelength_nm: Option<f64>,
}

/// Reads the number (or `A-B` range, giving B) starting at `s`.
fn number_at(s: &str) -> Option<usize> {
    let digits = |t: &str| t.chars().take_while(char::is_ascii_digit).collect::<String>();
    let first = digits(s);
    if first.is_empty() {
        return None;
    }
    let rest = &s[first.len()..];
    let end = rest.strip_prefix('-').map(digits).filter(|d| !d.is_empty());
    end.unwrap_or(first).parse().ok()
}

/// Positions and numbers of every `word N` (`word` a whole word, optionally plural).
fn mentions(text: &str, word: &str) -> Vec<(usize, usize)> {
    let lower = text.to_ascii_lowercase();
    let mut out = Vec::new();
    for (pos, _) in lower.match_indices(word) {
        if lower[..pos].chars().next_back().is_some_and(|c| c.is_ascii_alphanumeric()) {
            continue;
        }
        let after = &lower[pos + word.len()..];
        let after = after.strip_prefix('s').unwrap_or(after);
        if let Some(n) = after.strip_prefix(' ').and_then(number_at) {
            out.push((pos, n));
        }
    }
    out
}

fn parse_bad_file_comment(file_text: &str) -> Option<BadFileComment> {
    let text = file_text.lines().take(2).find_map(|l| l.trim().strip_prefix("# BAD FILE:"))?.trim().to_string();
    let lines = mentions(&text, "line");
    let column = mentions(&text, "column").first().copied();
    let line = match column {
        Some((pos, _)) => lines.iter().rev().find(|(p, _)| *p < pos).map(|l| l.1),
        None => lines.last().map(|l| l.1),
    };
    let wavelength_nm = text.find(" nm").and_then(|end| {
        let start = text[..end].rfind(|c: char| !c.is_ascii_digit()).map_or(0, |i| i + 1);
        text[start..end].parse().ok()
    });
    Some(BadFileComment { line, column: column.map(|c| c.1), wavelength_nm, text })
}

#[test]
fn bad_file_comments_are_read_as_intended() {
    let p = |s: &str| parse_bad_file_comment(&format!("# BAD FILE: {s}\n")).expect("comment");
    let c =
        p("END_DATA missing: BEGIN_DATA at line 23, last data row at line 26, END_DATA expected at line 27, column 1");
    assert_eq!((c.line, c.column), (Some(27), Some(1)));
    let c = p("header line 9, first data row line 10, column 4");
    assert_eq!((c.line, c.column), (Some(10), Some(4)));
    let c = p("wavelength 500 repeated at line 23, column 1 (first at line 22)");
    assert_eq!((c.line, c.column), (Some(23), Some(1)));
    let c = p("610 then 600 at lines 32-33, column 1");
    assert_eq!((c.line, c.column), (Some(33), Some(1)));
    let c = p("data row with 3 fields instead of 4 at line 42 (column 4, rg, missing)");
    assert_eq!((c.line, c.column), (Some(42), Some(4)));
    let c = p("no data rows (header at line 9)");
    assert_eq!((c.line, c.column), (Some(9), None));
    let c = p("r 0.4 > r_inf 0.3 at line 27, column 3: no KM solution at 550 nm (inversion must reject)");
    assert_eq!((c.line, c.column, c.wavelength_nm), (Some(27), Some(3), Some(550.0)));
    assert_eq!(parse_bad_file_comment("wavelength_nm,r_inf,r,rg\n"), None);
}

/// Reads a bad file and its comment; the import must fail.
fn import_error(name: &str) -> (PathBuf, BadFileComment, LocatedError) {
    let path = bad_dir().join(name);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let comment = parse_bad_file_comment(&text).unwrap_or_else(|| panic!("{name}: no `# BAD FILE:` comment"));
    let e = match import::read_measurement(&path, &ImportOptions::default()) {
        Ok(m) => panic!("{name} imported ({} samples); its comment: {}", m.r.values().len(), comment.text),
        Err(e) => e,
    };
    assert_eq!(e.path, path, "the error names the file: {e}");
    (path, comment, e)
}

/// A file whose import must fail at the line and column its comment names.
fn assert_fails_where_it_says(name: &str) {
    let (_, comment, e) = import_error(name);
    eprintln!("{name}: {e}");
    assert_eq!(
        (e.line, e.column),
        (comment.line, comment.column),
        "{name}: error `{e}` vs the file's comment `{}`",
        comment.text
    );
}

macro_rules! bad_file_tests {
    ($($(#[$attr:meta])* $test:ident => $file:literal,)*) => {$(
        #[test]
        $(#[$attr])*
        fn $test() {
            assert_fails_where_it_says($file);
        }
    )*};
}

// Three files fail, but not where their comments (and docs/FORMATS.md section 3) say: the
// library reports a different line or no column. Ignored until the importer is fixed.
bad_file_tests! {
    bad_non_numeric => "non_numeric.csv",
    bad_nan_value => "nan_value.csv",
    bad_missing_wavelength => "missing_wavelength.csv",
    bad_duplicate_wavelength => "duplicate_wavelength.csv",
    bad_non_monotonic => "non_monotonic.csv",
    bad_reflectance_too_high => "reflectance_too_high.csv",
    bad_negative_value => "negative_value.csv",
    bad_header_missing_column => "header_missing_column.csv",
    bad_wrong_field_count => "wrong_field_count.csv",
    bad_no_data_rows => "no_data_rows.csv",
    bad_cgats_missing_end_data => "cgats_missing_end_data.txt",
}

/// The files the tests above and below cover: a new bad file must get a test.
const COVERED: [&str; 14] = [
    "non_numeric.csv",
    "nan_value.csv",
    "missing_wavelength.csv",
    "duplicate_wavelength.csv",
    "non_monotonic.csv",
    "reflectance_too_high.csv",
    "negative_value.csv",
    "header_missing_column.csv",
    "wrong_field_count.csv",
    "no_data_rows.csv",
    "cgats_missing_end_data.txt",
    "empty.csv",
    "missing_thickness.csv",
    "r_outside_bounds.csv",
];

#[test]
fn every_bad_file_is_covered() {
    let mut found: Vec<String> = std::fs::read_dir(bad_dir())
        .expect("data/measurements/bad")
        .map(|e| e.expect("directory entry").file_name().to_string_lossy().into_owned())
        .collect();
    found.sort();
    let mut covered: Vec<String> = COVERED.iter().map(|s| s.to_string()).collect();
    covered.sort();
    assert_eq!(found, covered);
}

#[test]
fn every_bad_file_fails_to_import() {
    // Position aside (checked per file above), every file whose fault is in its syntax is refused.
    for name in COVERED.iter().filter(|n| !["empty.csv", "missing_thickness.csv", "r_outside_bounds.csv"].contains(n)) {
        let (_, _, e) = import_error(name);
        assert!(e.line.is_some() || e.column.is_none(), "{name}: a column without a line: {e}");
    }
}

#[test]
fn bad_empty_file() {
    let path = bad_dir().join("empty.csv");
    let e = import::read_measurement(&path, &ImportOptions::default()).expect_err("an empty file");
    assert_eq!((e.path.as_path(), e.line, e.column), (path.as_path(), None, None), "{e}");
    assert!(e.message.contains("empty"), "{e}");
}

#[test]
fn bad_missing_thickness() {
    // The library leaves the thickness to the caller: the import succeeds without one, and the
    // file cannot be inverted until the caller supplies D (the CLI says "pass --thickness-mm").
    let path = bad_dir().join("missing_thickness.csv");
    let text = std::fs::read_to_string(&path).expect("readable");
    let comment = parse_bad_file_comment(&text).expect("BAD FILE comment");
    assert!(comment.text.contains("thickness_mm") && comment.column.is_none(), "{}", comment.text);
    let m = read(&path);
    assert_eq!(m.thickness_mm, None, "no `# thickness_mm:` key");
    let w = working(&m, Extrapolation::Refuse);
    preset(&m, &w, 0.020).unwrap_or_else(|e| panic!("with D supplied it inverts: {e}"));
    // D must be given and valid.
    assert!(matches!(preset(&m, &w, 0.0), Err(PresetError::Invalid { .. })));
    assert!(matches!(preset(&m, &w, f64::NAN), Err(PresetError::Invalid { .. })));
}

#[test]
fn bad_r_outside_bounds_fails_at_inversion() {
    let path = bad_dir().join("r_outside_bounds.csv");
    let text = std::fs::read_to_string(&path).expect("readable");
    let comment = parse_bad_file_comment(&text).expect("BAD FILE comment");
    let nm = comment.wavelength_nm.expect("the comment names the wavelength");
    let m = read(&path);
    let w = working(&m, Extrapolation::Refuse);
    let thickness = m.thickness_mm.expect("thickness_mm");
    match preset(&m, &w, thickness) {
        Err(e @ PresetError::Inversion { wavelength_nm, .. }) => {
            assert_eq!(wavelength_nm, nm, "{e}");
            assert!(e.to_string().contains(&format!("{nm} nm")), "the message names the wavelength: {e}");
            eprintln!("r_outside_bounds.csv: {e}");
        }
        Err(e) => panic!("expected an inversion error at {nm} nm, got {e}"),
        Ok(_) => panic!("r_outside_bounds.csv inverted; its comment: {}", comment.text),
    }
}

#[test]
fn missing_file_names_its_path() {
    let path = measurements_dir().join("no_such_product.csv");
    let e = import::read_measurement(&path, &ImportOptions::default()).expect_err("missing file");
    assert_eq!(e.path, path);
    assert!(e.to_string().contains(&path.display().to_string()), "{e}");
    let e = import::read_measurement_files(&path, &path, &path).expect_err("missing file");
    assert!(e.to_string().contains(&path.display().to_string()), "{e}");
}
