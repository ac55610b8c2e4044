//! Rouge CSV: `# key: value` comment lines, a header naming `wavelength_nm`, `r_inf`, `r`, `rg`
//! (any order; other columns are refused, so a typo in a name cannot silently drop data), then
//! one row per wavelength. Keys understood: `name`, `kind`, `thickness_mm`, `instrument`,
//! `scale` (`fraction` or `percent`; `unit` is accepted too); all keys are kept in the metadata.

use super::{
    Cell, Kind, LocatedError, Measurement, Scale, check_reflectance_range, check_wavelengths, detect_scale,
    parse_number,
};
use crate::spectrum::SampledSpectrum;
use std::collections::BTreeMap;
use std::path::Path;

const COLUMNS: [&str; 4] = ["wavelength_nm", "r_inf", "r", "rg"];

/// Parses the `# key: value` lines of a CSV (anywhere in the file) into a map, keys lower-cased.
pub(crate) fn comment_metadata(text: &str) -> BTreeMap<String, String> {
    text.lines()
        .filter_map(|l| l.trim().strip_prefix('#'))
        .filter_map(|l| {
            let (k, v) = l.split_once(':')?;
            let k = k.trim().to_ascii_lowercase();
            (!k.is_empty() && !k.contains(' ')).then(|| (k, v.trim().to_string()))
        })
        .collect()
}

/// Splits a CSV line into trimmed cells at `delimiter` (Rouge CSV holds numbers and plain names:
/// no quoting beyond a pair of double quotes around a whole name, which is removed).
pub(crate) fn cells(line: &str, delimiter: char) -> Vec<&str> {
    line.split(delimiter).map(|c| c.trim().trim_matches('"').trim()).collect()
}

/// The delimiter of a table, from its header line: a comma, or a tab where the header has tabs
/// and no comma (colour-science's transposed test files).
fn delimiter(header: &str) -> char {
    if !header.contains(',') && header.contains('\t') { '\t' } else { ',' }
}

/// A CSV table of numbers: the header line, its names, and every column's cells.
struct NumericTable {
    header_line: usize,
    header: String,
    names: Vec<String>,
    columns: Vec<Vec<Cell>>,
    /// With `labelled` rows: each data row's first cell (a name, not a number).
    labels: Vec<String>,
}

impl NumericTable {
    /// The index of the column named `name` (case-insensitive).
    fn column(&self, name: &str) -> Option<usize> {
        self.names.iter().position(|n| n.eq_ignore_ascii_case(name))
    }
}

/// The first line that is neither blank nor a `#` comment, with its 1-based number.
fn header_of(text: &str) -> Option<(usize, &str)> {
    text.lines().enumerate().map(|(i, l)| (i + 1, l.trim())).find(|(_, l)| !l.is_empty() && !l.starts_with('#'))
}

/// Reads the header, lets `check_header` refuse it before any row is read (so a bad header is
/// reported at the header), then every data row (`#` comments and blank lines skipped), parsing
/// each cell as a finite number (with `labelled`, all but the first, which is the row's name);
/// errors name the line and column.
fn read_numeric_table(
    path: &Path,
    text: &str,
    labelled: bool,
    check_header: impl FnOnce(&NumericTable) -> Result<(), LocatedError>,
) -> Result<NumericTable, LocatedError> {
    let mut rows =
        text.lines().enumerate().map(|(i, l)| (i + 1, l.trim())).filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let (header_line, header) = rows.next().ok_or_else(|| LocatedError::file(path, "no header line"))?;
    let delimiter = delimiter(header);
    let names: Vec<String> = cells(header, delimiter).iter().map(|c| c.to_string()).collect();
    let mut table = NumericTable {
        header_line,
        header: header.to_string(),
        columns: vec![Vec::new(); names.len()],
        names,
        labels: Vec::new(),
    };
    check_header(&table)?;
    let names = &table.names;
    let first_number = usize::from(labelled);
    for (line, row) in rows {
        let c = cells(row, delimiter);
        if c.len() != names.len() {
            return Err(LocatedError::at(
                path,
                line,
                Some(c.len().min(names.len()) + 1),
                format!("{} cells, but the header has {}", c.len(), names.len()),
            ));
        }
        if labelled {
            table.labels.push(c[0].to_string());
        }
        for (i, (text, column)) in c.iter().zip(table.columns.iter_mut()).enumerate().skip(first_number) {
            let what = if labelled { format!("`{}` at {} nm", c[0], names[i]) } else { names[i].clone() };
            let value = parse_number(path, text, line, i + 1, &what)?;
            column.push(Cell { value, line, column: i + 1 });
        }
    }
    let data_rows = if labelled { table.labels.len() } else { table.columns.first().map_or(0, Vec::len) };
    let least = if labelled { 1 } else { 2 };
    if data_rows < least {
        return Err(LocatedError::at(
            path,
            header_line,
            None,
            format!("{data_rows} data rows after the header: a spectrum needs at least 2 wavelengths"),
        ));
    }
    Ok(table)
}

/// Fraction or percent: the `# scale:` comment (or `# unit:`) if present, else detected.
fn resolve_scale(path: &Path, metadata: &BTreeMap<String, String>, cells: &[Cell]) -> Result<Scale, LocatedError> {
    match metadata.get("scale").or_else(|| metadata.get("unit")).map(|u| u.to_ascii_lowercase()) {
        None => Ok(detect_scale(cells)),
        Some(u) if u == "percent" || u == "%" => Ok(Scale::Percent { declared: true }),
        Some(u) if u == "fraction" => Ok(Scale::Fraction { declared: true }),
        Some(u) => Err(LocatedError::file(path, format!("unknown `# scale: {u}` (use `fraction` or `percent`)"))),
    }
}

/// Parses a Rouge CSV measurement.
pub fn parse(path: &Path, text: &str) -> Result<Measurement, LocatedError> {
    let metadata = comment_metadata(text);
    if text.lines().all(|l| l.trim().is_empty() || l.trim().starts_with('#')) {
        return Err(LocatedError::file(path, "no header line (expected `wavelength_nm,r_inf,r,rg`)"));
    }
    let header_index = |t: &NumericTable| -> Result<[usize; 4], LocatedError> {
        let mut index = [0usize; 4];
        for (slot, want) in index.iter_mut().zip(COLUMNS) {
            *slot = t.column(want).ok_or_else(|| {
                LocatedError::at(
                    path,
                    t.header_line,
                    None,
                    format!(
                        "the header has no `{want}` column (expected `wavelength_nm,r_inf,r,rg`, found `{}`)",
                        t.header
                    ),
                )
            })?;
        }
        if let Some((col, extra)) =
            t.names.iter().enumerate().find(|(_, n)| !COLUMNS.contains(&n.to_ascii_lowercase().as_str()))
        {
            return Err(LocatedError::at(
                path,
                t.header_line,
                Some(col + 1),
                format!("unknown column `{extra}` (Rouge CSV has exactly wavelength_nm, r_inf, r, rg)"),
            ));
        }
        Ok(index)
    };
    let table = read_numeric_table(path, text, false, |t| header_index(t).map(|_| ()))?;
    let index = header_index(&table)?;
    let mut all = table.columns;
    let columns: [Vec<Cell>; 4] = index.map(|i| std::mem::take(&mut all[i]));
    check_wavelengths(path, &columns[0])?;
    let reflectances: Vec<Cell> = columns[1..].iter().flatten().copied().collect();
    let scale = resolve_scale(path, &metadata, &reflectances)?;
    let factor = scale.factor();
    check_reflectance_range(path, &reflectances, factor)?;
    let kind = match metadata.get("kind") {
        None => None,
        Some(k) => Some(Kind::parse(k).ok_or_else(|| {
            LocatedError::file(path, format!("unknown `# kind: {k}` (foundation, blush, eyeshadow, lipstick or other)"))
        })?),
    };
    let thickness_mm = match metadata.get("thickness_mm") {
        None => None,
        Some(t) => {
            let line = text
                .lines()
                .position(|l| l.trim_start().starts_with('#') && l.contains("thickness_mm"))
                .map_or(1, |i| i + 1);
            let v = parse_number(path, t, line, 1, "thickness_mm")?;
            if v <= 0.0 {
                return Err(LocatedError::at(path, line, None, format!("thickness_mm = {v} must be positive")));
            }
            Some(v)
        }
    };
    let wavelengths: Vec<f64> = columns[0].iter().map(|c| c.value).collect();
    let spectrum = |k: usize| {
        let values = columns[k].iter().map(|c| c.value * factor).collect();
        SampledSpectrum::new(wavelengths.clone(), values).map_err(|e| LocatedError::file(path, e.to_string()))
    };
    Ok(Measurement {
        source: path.to_path_buf(),
        format: "Rouge CSV".into(),
        name: metadata
            .get("name")
            .cloned()
            .unwrap_or_else(|| path.file_stem().map_or_else(String::new, |s| s.to_string_lossy().into_owned())),
        kind,
        thickness_mm,
        instrument: metadata.get("instrument").cloned(),
        metadata,
        scale,
        r_inf: spectrum(1)?,
        r: spectrum(2)?,
        rg: spectrum(3)?,
    })
}

/// Names a table's wavelength column may have (case-insensitive): Rouge's own, and the one
/// colour-science writes and reads.
const WAVELENGTH_COLUMNS: [&str; 2] = ["wavelength_nm", "wavelength"];

/// A table of spectra (the input of `rouge color`), in either layout colour-science uses:
///
/// * **columns**: a `wavelength_nm` (or `wavelength`) column and one column per sample, the header
///   naming the samples;
/// * **rows** (transposed): one spectrum per row, its name in the first cell, the wavelengths in
///   the header after a first cell of any name (`wavelength,380,385,...`).
///
/// The layout is read from the header: every cell after the first a number means rows. Cells are
/// separated by commas, or by tabs when the header has tabs and no comma. Fractions or percent by
/// the same rule as measurements; `#` comment lines are skipped; errors name line and column.
pub fn parse_spectra_table(path: &Path, text: &str) -> Result<(Vec<(String, SampledSpectrum)>, Scale), LocatedError> {
    let metadata = comment_metadata(text);
    let transposed = is_transposed(text);
    let (names, wl, values) = if transposed { spectra_in_rows(path, text)? } else { spectra_in_columns(path, text)? };
    check_wavelengths(path, &wl)?;
    let all: Vec<Cell> = values.iter().flatten().copied().collect();
    let scale = resolve_scale(path, &metadata, &all)?;
    check_reflectance_range(path, &all, scale.factor())?;
    let grid: Vec<f64> = wl.iter().map(|c| c.value).collect();
    let mut out = Vec::with_capacity(names.len());
    for (name, cells) in names.into_iter().zip(values) {
        let v = cells.iter().map(|c| c.value * scale.factor()).collect();
        let s = SampledSpectrum::new(grid.clone(), v).map_err(|e| LocatedError::file(path, e.to_string()))?;
        out.push((name, s));
    }
    Ok((out, scale))
}

/// Whether a table of spectra holds one spectrum per row: its header after the first cell is a
/// row of wavelengths (numbers within 100-3000 nm), and its first column is not (colour-science
/// writes `wavelength,1,2,...` with samples named by numbers, and reads the transposed
/// `wavelength,380,385,...` with rows named `1`, `2`, ...).
fn is_transposed(text: &str) -> bool {
    let Some((_, header)) = header_of(text) else { return false };
    let d = delimiter(header);
    let nm = |x: &&str| x.parse::<f64>().is_ok_and(|v| (100.0..=3000.0).contains(&v));
    let head = cells(header, d);
    let mut rows = text.lines().map(str::trim).filter(|l| !l.is_empty() && !l.starts_with('#')).skip(1);
    head.len() >= 3 && head[1..].iter().all(nm) && !rows.all(|l| nm(&cells(l, d)[0]))
}

/// Sample names, the wavelength cells, and each sample's value cells.
type SpectraCells = (Vec<String>, Vec<Cell>, Vec<Vec<Cell>>);

fn spectra_in_columns(path: &Path, text: &str) -> Result<SpectraCells, LocatedError> {
    let wavelength_column = |t: &NumericTable| WAVELENGTH_COLUMNS.iter().find_map(|w| t.column(w));
    let check = |t: &NumericTable| -> Result<(), LocatedError> {
        if wavelength_column(t).is_none() {
            return Err(LocatedError::at(
                path,
                t.header_line,
                None,
                format!(
                    "the header has no `wavelength_nm` or `wavelength` column, and is not a row of wavelengths \
                     either (found `{}`)",
                    t.header
                ),
            ));
        }
        if t.names.len() < 2 {
            return Err(LocatedError::at(path, t.header_line, None, "no sample columns besides the wavelengths"));
        }
        if let Some(i) = t.names.iter().position(String::is_empty) {
            return Err(LocatedError::at(path, t.header_line, Some(i + 1), "a column has no name"));
        }
        Ok(())
    };
    let mut table = read_numeric_table(path, text, false, check)?;
    let wl_col = wavelength_column(&table).unwrap_or(0);
    let wl = std::mem::take(&mut table.columns[wl_col]);
    let sample_cols: Vec<usize> = (0..table.names.len()).filter(|&i| i != wl_col).collect();
    let names = sample_cols.iter().map(|&i| table.names[i].clone()).collect();
    let values = sample_cols.iter().map(|&i| std::mem::take(&mut table.columns[i])).collect();
    Ok((names, wl, values))
}

fn spectra_in_rows(path: &Path, text: &str) -> Result<SpectraCells, LocatedError> {
    let mut table = read_numeric_table(path, text, true, |_| Ok(()))?;
    let wl = table.names[1..]
        .iter()
        .enumerate()
        .map(|(i, n)| {
            let value = parse_number(path, n, table.header_line, i + 2, "wavelength")?;
            Ok(Cell { value, line: table.header_line, column: i + 2 })
        })
        .collect::<Result<Vec<Cell>, LocatedError>>()?;
    if let Some((i, _)) = table.labels.iter().enumerate().find(|(_, l)| l.is_empty()) {
        let line = table.columns[1][i].line;
        return Err(LocatedError::at(path, line, Some(1), "a spectrum has no name"));
    }
    // Row r's values: the r-th cell of every wavelength column.
    let values = (0..table.labels.len()).map(|r| table.columns[1..].iter_mut().map(|col| col[r]).collect()).collect();
    Ok((std::mem::take(&mut table.labels), wl, values))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p() -> &'static Path {
        Path::new("sample.csv")
    }

    fn body(rows: &[(f64, f64, f64, f64)]) -> String {
        rows.iter().map(|(w, a, b, c)| format!("{w},{a},{b},{c}\n")).collect()
    }

    #[test]
    fn reads_fractions_and_metadata() {
        let text = format!(
            "# name: Test\n# kind: blush\n# thickness_mm: 0.02\nwavelength_nm,r_inf,r,rg\n{}",
            body(&[(380.0, 0.5, 0.3, 0.1), (390.0, 0.6, 0.35, 0.1)])
        );
        let m = parse(p(), &text).unwrap();
        assert_eq!(m.name, "Test");
        assert_eq!(m.kind, Some(Kind::Blush));
        assert_eq!(m.thickness_mm, Some(0.02));
        assert_eq!(m.scale, Scale::Fraction { declared: false });
        assert_eq!(m.r.values(), &[0.3, 0.35]);
    }

    #[test]
    fn detects_percent() {
        let text = format!("wavelength_nm,r_inf,r,rg\n{}", body(&[(380.0, 50.0, 30.0, 3.0), (390.0, 60.0, 35.0, 4.0)]));
        let m = parse(p(), &text).unwrap();
        assert_eq!(m.scale, Scale::Percent { declared: false });
        assert!((m.r_inf.values()[0] - 0.5).abs() < 1e-15);
    }

    #[test]
    fn errors_name_line_and_column() {
        let text = "wavelength_nm,r_inf,r,rg\n380,0.5,0.3,0.1\n390,0.5,abc,0.1\n";
        let e = parse(p(), text).unwrap_err();
        assert_eq!((e.line, e.column), (Some(3), Some(3)), "{e}");
        assert!(e.to_string().starts_with("sample.csv:3:3: r `abc`"), "{e}");

        let text = "wavelength_nm,r_inf,r,rg\n380,0.5,0.3,0.1\n380,0.5,0.3,0.1\n";
        let e = parse(p(), text).unwrap_err();
        assert!(e.to_string().contains("appears twice"), "{e}");

        let text = "wavelength_nm,r_inf,r,rg\n390,0.5,0.3,0.1\n380,0.5,0.3,0.1\n";
        assert!(parse(p(), text).unwrap_err().to_string().contains("must increase"));

        let text = "wavelength_nm,r_inf,r,rg\n380,0.5,0.3,NaN\n390,0.5,0.3,0.1\n";
        let e = parse(p(), text).unwrap_err();
        assert_eq!((e.line, e.column), (Some(2), Some(4)), "{e}");

        let text = "wavelength_nm,r_inf,r\n380,0.5,0.3\n";
        assert!(parse(p(), text).unwrap_err().to_string().contains("no `rg` column"));

        let text = "wavelength_nm,r_inf,r,rg\n380,0.5,0.3,0.1\n390,0.5,-0.01,0.1\n";
        let e = parse(p(), text).unwrap_err();
        assert_eq!((e.line, e.column), (Some(3), Some(3)), "{e}");

        let text = "wavelength_nm,r_inf,r,rg\n380,0.5,0.3,0.1\n390,0.5,0.3\n";
        assert_eq!(parse(p(), text).unwrap_err().line, Some(3));

        let mut rows = String::from("wavelength_nm,r_inf,r,rg\n");
        for i in 0..10 {
            rows.push_str(&format!("{},0.5,0.3,0.1\n", 380 + 10 * i));
        }
        rows.push_str("480,0.5,7.0,0.1\n");
        let e = parse(p(), &rows).unwrap_err();
        assert_eq!((e.line, e.column), (Some(12), Some(3)), "{e}");
    }

    #[test]
    fn spectra_tables_in_both_layouts_and_delimiters() {
        let columns =
            "# colour-science writes `wavelength`\nwavelength,1,2\n380,0.048,0.10\n385,0.051,0.12\n390,0.055,0.14\n";
        let (spectra, scale) = parse_spectra_table(p(), columns).unwrap();
        assert_eq!(scale, Scale::Fraction { declared: false });
        let names: Vec<&str> = spectra.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(names, ["1", "2"]);
        assert_eq!(spectra[1].1.wavelengths_nm(), &[380.0, 385.0, 390.0]);
        assert_eq!(spectra[1].1.values(), &[0.10, 0.12, 0.14]);

        let rows = "wavelength\t380\t385\t390\n1\t0.048\t0.051\t0.055\n\"2\"\t0.10\t0.12\t0.14\n";
        let (t, _) = parse_spectra_table(p(), rows).unwrap();
        assert_eq!(t, spectra, "the transposed, tab-separated table reads as the same spectra");
        let (c, _) = parse_spectra_table(p(), &rows.replace('\t', ",")).unwrap();
        assert_eq!(c, spectra);
        let (n, _) = parse_spectra_table(p(), &columns.replace("wavelength,", "wavelength_nm,")).unwrap();
        assert_eq!(n, spectra);
    }

    #[test]
    fn spectra_table_errors_name_line_and_column() {
        let e = parse_spectra_table(p(), "nm,a\n380,0.1\n390,0.2\n").unwrap_err();
        assert_eq!(e.line, Some(1));
        assert!(e.message.contains("no `wavelength_nm` or `wavelength` column"), "{e}");
        let e = parse_spectra_table(p(), "wavelength,380,390,400\na,0.1,0.2,0.3\nb,0.1,x,0.3\n").unwrap_err();
        assert_eq!((e.line, e.column), (Some(3), Some(3)), "{e}");
        assert!(e.message.contains("`b` at 390 nm `x` is not a number"), "{e}");
        let e = parse_spectra_table(p(), "wavelength,380,390,390\na,0.1,0.2,0.3\n").unwrap_err();
        assert_eq!((e.line, e.column), (Some(1), Some(4)), "{e}");
        let e = parse_spectra_table(p(), "wavelength,380,390,400\na,0.1,0.2\n").unwrap_err();
        assert_eq!(e.line, Some(2), "{e}");
        let e = parse_spectra_table(p(), "wavelength,380,390,400\na,0.1,0.2,3.0\nb,0.1,0.2,0.3\n").unwrap_err();
        assert_eq!((e.line, e.column), (Some(2), Some(4)), "{e}");
        let e = parse_spectra_table(p(), "wavelength,380,390,400\n").unwrap_err();
        assert!(e.message.contains("0 data rows"), "{e}");
    }
}
