//! CGATS.17 text files (ANSI CGATS.17-2009) as X-Rite, i1Profiler and ArgyllCMS write them.
//!
//! Structure: an identifier line (`CGATS.17`, `CTI3`, `SPECT`, ...), keyword lines
//! (`NAME "value"`), `BEGIN_DATA_FORMAT` … `END_DATA_FORMAT` listing field names, then
//! `BEGIN_DATA` … `END_DATA` with one sample per line. Spectral fields are recognised by name:
//! `nm380` (X-Rite), `SPECTRAL_NM380` / `SPECTRAL_NM_380` (i1Profiler), `SPEC_380` (Argyll),
//! `SPECTRAL_380`. Values are divided by `SPECTRAL_NORM` when the file gives it (Argyll writes
//! 100 for percent); otherwise fraction or percent is detected as for Rouge CSV. Samples are
//! named by `SAMPLE_NAME` (else `SAMPLE_LOC`, as Argyll writes, else `SAMPLE_ID`).
//! Rouge's own optional keywords: `ROUGE_THICKNESS_MM`, `ROUGE_KIND`, and `ROUGE_ROLE`
//! (`R_INF`, `R` or `RG`) in single-spectrum files.

use super::{
    Cell, Kind, LocatedError, Measurement, SampleNames, Scale, check_reflectance_range, check_wavelengths,
    detect_scale, parse_number,
};
use crate::spectrum::SampledSpectrum;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Whether `text` is a CGATS-family file (it has a `BEGIN_DATA_FORMAT` line).
pub fn looks_like_cgats(text: &str) -> bool {
    text.lines().any(|l| l.trim() == "BEGIN_DATA_FORMAT")
}

/// One sample's spectrum.
#[derive(Clone, Debug, PartialEq)]
pub struct NamedSpectrum {
    /// `SAMPLE_NAME`, else `SAMPLE_ID`, else the 1-based row number.
    pub name: String,
    /// Line the sample was read from.
    pub line: usize,
    /// Reflectance as fractions.
    pub spectrum: SampledSpectrum,
}

/// A parsed CGATS file.
#[derive(Clone, Debug, PartialEq)]
pub struct CgatsFile {
    /// The file.
    pub path: PathBuf,
    /// First token of the identifier line.
    pub identifier: String,
    /// Keyword values (`DESCRIPTOR`, `ORIGINATOR`, `SPECTRAL_NORM`, ...), keys upper-case.
    pub keywords: BTreeMap<String, String>,
    /// How values were scaled.
    pub scale: Scale,
    /// The spectra, in file order.
    pub samples: Vec<NamedSpectrum>,
}

/// Splits a line into tokens: whitespace-separated, `"quoted strings"` kept whole (quotes removed).
fn tokens(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut chars = line.chars().peekable();
    while let Some(&c) = chars.peek() {
        if c.is_whitespace() {
            chars.next();
        } else if c == '#' {
            break; // a comment runs to the end of the line
        } else if c == '"' {
            chars.next();
            let mut s = String::new();
            for ch in chars.by_ref() {
                if ch == '"' {
                    break;
                }
                s.push(ch);
            }
            out.push(s);
        } else {
            let mut s = String::new();
            while let Some(&ch) = chars.peek() {
                if ch.is_whitespace() || ch == '#' {
                    break;
                }
                s.push(ch);
                chars.next();
            }
            out.push(s);
        }
    }
    out
}

/// Wavelength of a spectral field name, if it is one.
fn spectral_field_nm(name: &str) -> Option<f64> {
    let upper = name.to_ascii_uppercase();
    ["SPECTRAL_NM_", "SPECTRAL_NM", "SPECTRAL_", "SPEC_", "NM_", "NM"]
        .iter()
        .find_map(|p| upper.strip_prefix(p))
        .and_then(|rest| rest.parse::<f64>().ok())
        .filter(|v| v.is_finite() && *v > 0.0)
}

/// Parses a CGATS file's structure and spectra.
pub fn parse(path: &Path, text: &str) -> Result<CgatsFile, LocatedError> {
    let mut lines =
        text.lines().enumerate().map(|(i, l)| (i + 1, l.trim())).filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let (_, first) = lines.next().ok_or_else(|| LocatedError::file(path, "the file is empty"))?;
    let identifier = tokens(first).into_iter().next().unwrap_or_default();
    let mut keywords = BTreeMap::new();
    let mut fields: Vec<String> = Vec::new();
    let mut format_line = 0;
    let mut rows: Vec<(usize, Vec<String>)> = Vec::new();
    #[derive(Clone, Copy, PartialEq)]
    enum State {
        Header,
        Format,
        AfterFormat,
        Data,
        Done,
    }
    use State::*;
    let mut state = Header;
    let mut data_line = 0;
    for (line, l) in lines {
        let t = tokens(l);
        let Some(head) = t.first() else { continue };
        match (state, head.as_str()) {
            (Header | AfterFormat, "BEGIN_DATA_FORMAT") => {
                state = Format;
                format_line = line;
            }
            (Format, "END_DATA_FORMAT") => state = AfterFormat,
            (Format, _) => fields.extend(t),
            (AfterFormat, "BEGIN_DATA") => {
                state = Data;
                data_line = line;
            }
            (Data, "END_DATA") => state = Done,
            (Data, _) => rows.push((line, t)),
            (Header | AfterFormat | Done, "KEYWORD") => {}
            (Header | AfterFormat | Done, key) => {
                let value = t[1..].join(" ");
                keywords.insert(key.to_ascii_uppercase(), value);
            }
        }
    }
    match state {
        Header => return Err(LocatedError::file(path, "no BEGIN_DATA_FORMAT section")),
        Format => {
            return Err(LocatedError::at(
                path,
                format_line,
                None,
                "BEGIN_DATA_FORMAT is never closed by END_DATA_FORMAT",
            ));
        }
        AfterFormat => return Err(LocatedError::file(path, "no BEGIN_DATA section")),
        Data => {
            let end = text.lines().count() + 1;
            return Err(LocatedError::at(
                path,
                end,
                Some(1),
                format!("the file ends without END_DATA (BEGIN_DATA is on line {data_line})"),
            ));
        }
        Done => {}
    }
    if let Some(n) = keywords.get("NUMBER_OF_FIELDS")
        && n.trim().parse::<usize>().ok() != Some(fields.len())
    {
        {
            return Err(LocatedError::at(
                path,
                format_line,
                None,
                format!("NUMBER_OF_FIELDS says {n} but the data format lists {} fields", fields.len()),
            ));
        }
    }
    if let Some(n) = keywords.get("NUMBER_OF_SETS")
        && n.trim().parse::<usize>().ok() != Some(rows.len())
    {
        {
            return Err(LocatedError::at(
                path,
                data_line,
                None,
                format!("NUMBER_OF_SETS says {n} but the data section has {} rows", rows.len()),
            ));
        }
    }
    let spectral: Vec<(usize, f64)> =
        fields.iter().enumerate().filter_map(|(i, f)| spectral_field_nm(f).map(|nm| (i, nm))).collect();
    if spectral.len() < 2 {
        return Err(LocatedError::at(
            path,
            format_line,
            None,
            "no spectral fields (expected names like nm380, SPECTRAL_NM380 or SPEC_380)",
        ));
    }
    let wl_cells: Vec<Cell> =
        spectral.iter().map(|&(i, nm)| Cell { value: nm, line: format_line, column: i + 1 }).collect();
    check_wavelengths(path, &wl_cells)?;
    let name_field = ["SAMPLE_NAME", "SAMPLE_LOC", "SAMPLE_ID"]
        .iter()
        .find_map(|n| fields.iter().position(|f| f.eq_ignore_ascii_case(n)));
    let mut values: Vec<Vec<Cell>> = Vec::with_capacity(rows.len());
    for (line, row) in &rows {
        if row.len() != fields.len() {
            return Err(LocatedError::at(
                path,
                *line,
                Some(row.len().min(fields.len()) + 1),
                format!("{} values, but the data format lists {} fields", row.len(), fields.len()),
            ));
        }
        let mut cells = Vec::with_capacity(spectral.len());
        for &(i, nm) in &spectral {
            let value = parse_number(path, &row[i], *line, i + 1, &format!("the value at {nm} nm"))?;
            cells.push(Cell { value, line: *line, column: i + 1 });
        }
        values.push(cells);
    }
    let all: Vec<Cell> = values.iter().flatten().copied().collect();
    let scale = match keywords.get("SPECTRAL_NORM") {
        Some(norm) => match norm.trim().parse::<f64>() {
            Ok(n) if (n - 100.0).abs() < 1e-9 => Scale::Percent { declared: true },
            Ok(n) if (n - 1.0).abs() < 1e-9 => Scale::Fraction { declared: true },
            _ => {
                return Err(LocatedError::file(path, format!("SPECTRAL_NORM {norm} is neither 1 nor 100")));
            }
        },
        None => detect_scale(&all),
    };
    check_reflectance_range(path, &all, scale.factor())?;
    let wavelengths: Vec<f64> = spectral.iter().map(|&(_, nm)| nm).collect();
    let mut samples = Vec::with_capacity(rows.len());
    for (k, ((line, row), cells)) in rows.iter().zip(&values).enumerate() {
        let name = name_field.map_or_else(|| (k + 1).to_string(), |i| row[i].clone());
        let spectrum =
            SampledSpectrum::new(wavelengths.clone(), cells.iter().map(|c| c.value * scale.factor()).collect())
                .map_err(|e| LocatedError::at(path, *line, None, e.to_string()))?;
        samples.push(NamedSpectrum { name, line: *line, spectrum });
    }
    Ok(CgatsFile { path: path.to_path_buf(), identifier, keywords, scale, samples })
}

impl CgatsFile {
    /// The sample called `name` (case-insensitive).
    pub fn sample(&self, name: &str) -> Result<&NamedSpectrum, LocatedError> {
        let found: Vec<&NamedSpectrum> = self.samples.iter().filter(|s| s.name.eq_ignore_ascii_case(name)).collect();
        match found.as_slice() {
            [one] => Ok(one),
            [] => Err(LocatedError::file(
                &self.path,
                format!(
                    "no sample named `{name}` (samples: {}); choose them with --samples R_INF,R,RG",
                    self.samples.iter().map(|s| s.name.as_str()).collect::<Vec<_>>().join(", ")
                ),
            )),
            [a, b, ..] => Err(LocatedError::at(
                &self.path,
                b.line,
                None,
                format!("sample name `{name}` is used twice (also on line {})", a.line),
            )),
        }
    }

    /// Builds a measurement from the three named samples.
    pub fn measurement(&self, names: &SampleNames) -> Result<Measurement, LocatedError> {
        if self.samples.len() == 1 {
            return Err(LocatedError::file(
                &self.path,
                "this file holds a single spectrum (e.g. an ArgyllCMS .sp): give R∞, R and Rg as three files \
                 (rouge import --r-inf A.sp --r B.sp --rg C.sp)",
            ));
        }
        let kw = |k: &str| self.keywords.get(k).cloned();
        let thickness_mm = match kw("ROUGE_THICKNESS_MM").or_else(|| kw("THICKNESS_MM")) {
            None => None,
            Some(t) => Some(t.trim().parse::<f64>().ok().filter(|v| *v > 0.0 && v.is_finite()).ok_or_else(|| {
                LocatedError::file(&self.path, format!("THICKNESS_MM `{t}` is not a positive number"))
            })?),
        };
        let kind = match kw("ROUGE_KIND").or_else(|| kw("KIND")) {
            None => None,
            Some(k) => {
                Some(Kind::parse(&k).ok_or_else(|| LocatedError::file(&self.path, format!("unknown KIND `{k}`")))?)
            }
        };
        Ok(Measurement {
            source: self.path.clone(),
            format: format!("CGATS text ({})", self.identifier),
            name: kw("ROUGE_NAME").unwrap_or_else(|| {
                self.path.file_stem().map_or_else(String::new, |s| s.to_string_lossy().into_owned())
            }),
            kind,
            thickness_mm,
            instrument: kw("INSTRUMENTATION").or_else(|| kw("TARGET_INSTRUMENT")).or_else(|| kw("ORIGINATOR")),
            metadata: self.keywords.clone(),
            scale: self.scale.clone(),
            r_inf: self.sample(&names.r_inf)?.spectrum.clone(),
            r: self.sample(&names.r)?.spectrum.clone(),
            rg: self.sample(&names.rg)?.spectrum.clone(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const XRITE: &str = "CGATS.17\nORIGINATOR \"test\"\nKEYWORD \"THICKNESS_MM\"\nTHICKNESS_MM \"0.03\"\n\
NUMBER_OF_FIELDS 5\nBEGIN_DATA_FORMAT\nSAMPLE_ID SAMPLE_NAME nm380 nm390 nm400\nEND_DATA_FORMAT\n\
NUMBER_OF_SETS 3\nBEGIN_DATA\n1 R_INF 50.0 52.0 54.0\n2 R 30.0 31.0 32.0\n3 RG 4.0 4.1 4.2\nEND_DATA\n";

    #[test]
    fn reads_xrite_style_percent() {
        let f = parse(Path::new("x.txt"), XRITE).unwrap();
        assert_eq!(f.identifier, "CGATS.17");
        assert_eq!(f.scale, Scale::Percent { declared: false });
        let m = f.measurement(&SampleNames::default()).unwrap();
        assert_eq!(m.thickness_mm, Some(0.03));
        assert_eq!(m.r.wavelengths_nm(), &[380.0, 390.0, 400.0]);
        assert!((m.rg.values()[2] - 0.042).abs() < 1e-15);
    }

    #[test]
    fn field_names() {
        assert_eq!(spectral_field_nm("nm380"), Some(380.0));
        assert_eq!(spectral_field_nm("SPECTRAL_NM380"), Some(380.0));
        assert_eq!(spectral_field_nm("SPECTRAL_NM_385"), Some(385.0));
        assert_eq!(spectral_field_nm("SPEC_780"), Some(780.0));
        assert_eq!(spectral_field_nm("SAMPLE_NAME"), None);
        assert_eq!(spectral_field_nm("LAB_L"), None);
    }

    #[test]
    fn structural_errors() {
        let no_end = XRITE.replace("END_DATA\n", "");
        let e = parse(Path::new("x.txt"), &no_end).unwrap_err();
        assert!(e.to_string().contains("ends without END_DATA (BEGIN_DATA is on line 10)"), "{e}");
        let short_row = XRITE.replace("2 R 30.0 31.0 32.0", "2 R 30.0 31.0");
        assert_eq!(parse(Path::new("x.txt"), &short_row).unwrap_err().line, Some(12));
        let bad = XRITE.replace("31.0", "x1");
        let e = parse(Path::new("x.txt"), &bad).unwrap_err();
        assert_eq!((e.line, e.column), (Some(12), Some(4)), "{e}");
        let f = parse(Path::new("x.txt"), XRITE).unwrap();
        let names = SampleNames { r: "THIN".into(), ..Default::default() };
        assert!(f.measurement(&names).unwrap_err().to_string().contains("no sample named `THIN`"));
    }
}
