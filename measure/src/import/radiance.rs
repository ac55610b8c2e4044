//! Spectroradiometer radiance exports (Konica Minolta CS-2000, CS-S10w-style CSV): the radiance
//! of a white standard, the opaque layer, the thin layer over its background, and the background,
//! all under the same lamp and geometry. Reflectance follows \[Huang2013\] eq. 8,
//! `R(λ) = E_m(λ) / E_L(λ)`: the lamp's radiance `E_L` is measured on the white standard and
//! corrected by the standard's own reflectance, `R = L_sample / L_white · ρ_white`
//! (`ρ_white`: the `White Standard` line of the file, else flat 0.99 for pressed BaSO4, unless
//! the caller gives a spectrum).
//!
//! Layout (`docs/FORMATS.md`; reconstructed, as the vendor's is not public): metadata lines
//! `Name,value[,value]`, then a table whose header's first cell is `No.`, one row per
//! measurement named in the `Data Name` column (`WHITE_BASO4`, `SAMPLE_RINF`, `SAMPLE_R`,
//! `BACKGROUND_RG`), spectral columns named `380nm`, `381nm`, ….

use super::{Cell, Kind, LocatedError, Measurement, SampleNames, Scale, check_wavelengths, parse_number};
use crate::spectrum::{SampledSpectrum, linear_interpolate};
use std::collections::BTreeMap;
use std::path::Path;

/// Default reflectance of the white standard (pressed BaSO4, 99 % pure), as in \[Huang2013\] section 4.
pub const BASO4_REFLECTANCE: f64 = 0.99;

/// Splits one CSV line into cells, honouring RFC 4180 double quotes.
fn split_quoted(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut cur = String::new();
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                cur.push('"');
                chars.next();
            }
            ('"', _) => quoted = !quoted,
            (',', false) => out.push(std::mem::take(&mut cur).trim().to_string()),
            _ => cur.push(c),
        }
    }
    out.push(cur.trim().to_string());
    out
}

fn is_table_header(cells: &[String]) -> bool {
    cells.first().is_some_and(|c| c.eq_ignore_ascii_case("No."))
}

fn spectral_column_nm(name: &str) -> Option<f64> {
    let n = name.trim().strip_suffix("nm")?;
    (!n.is_empty() && n.bytes().all(|b| b.is_ascii_digit() || b == b'.')).then(|| n.parse().ok()).flatten()
}

/// Whether `text` is a radiance export (a table header starting with `No.` and columns `NNNnm`).
pub fn looks_like_radiance(text: &str) -> bool {
    text.lines().map(split_quoted).any(|c| is_table_header(&c) && c.iter().any(|h| spectral_column_nm(h).is_some()))
}

/// The white standard's reflectance spectrum (from its calibration certificate, say) for
/// [`ImportOptions::white_reflectance`](super::ImportOptions): a spectral input holding exactly
/// one spectrum (a table with one column besides the wavelengths, or a one-sample CGATS file),
/// every value in (0, 1]. Errors name the file, and the wavelength of a value out of range.
pub fn read_white_standard(path: &Path) -> Result<SampledSpectrum, LocatedError> {
    let mut spectra = super::read_spectra(path)?.samples;
    if spectra.len() != 1 {
        return Err(LocatedError::file(
            path,
            format!("expected one reflectance column besides wavelength_nm, found {}", spectra.len()),
        ));
    }
    let (_, white) = spectra.remove(0);
    if let Some((nm, v)) = white_out_of_range(white.wavelengths_nm(), white.values()) {
        return Err(LocatedError::file(path, format!("white reflectance {v} at {nm} nm must be in (0, 1]")));
    }
    Ok(white)
}

/// The first wavelength (nm) and value of a white standard's reflectance outside (0, 1], if
/// any: a white standard reflects some light and creates none.
pub fn white_out_of_range(wavelengths_nm: &[f64], values: &[f64]) -> Option<(f64, f64)> {
    wavelengths_nm.iter().zip(values).map(|(&nm, &v)| (nm, v)).find(|(_, v)| !(*v > 0.0 && *v <= 1.0))
}

/// Names each role may carry in the `Data Name` column (case-insensitive), beyond the user's.
const WHITE_NAMES: [&str; 4] = ["WHITE_BASO4", "WHITE", "WHITE_STANDARD", "BASO4"];
const R_INF_NAMES: [&str; 2] = ["SAMPLE_RINF", "R_INF"];
const R_NAMES: [&str; 2] = ["SAMPLE_R", "R"];
const RG_NAMES: [&str; 2] = ["BACKGROUND_RG", "RG"];

/// Parses a radiance export into reflectances.
pub fn parse(
    path: &Path,
    text: &str,
    names: &SampleNames,
    white_reflectance: Option<&SampledSpectrum>,
) -> Result<Measurement, LocatedError> {
    let lines: Vec<(usize, Vec<String>)> =
        text.lines().enumerate().filter(|(_, l)| !l.trim().is_empty()).map(|(i, l)| (i + 1, split_quoted(l))).collect();
    let header_at = lines
        .iter()
        .position(|(_, c)| is_table_header(c))
        .ok_or_else(|| LocatedError::file(path, "no table header (a line starting with `No.`)"))?;
    let mut metadata = BTreeMap::new();
    for (_, c) in &lines[..header_at] {
        if let Some((key, rest)) = c.split_first() {
            metadata.insert(key.to_ascii_lowercase(), rest.join(","));
        }
    }
    let (header_line, header) = &lines[header_at];
    let name_col = header
        .iter()
        .position(|h| h.eq_ignore_ascii_case("Data Name"))
        .ok_or_else(|| LocatedError::at(path, *header_line, None, "the table header has no `Data Name` column"))?;
    let spectral: Vec<(usize, f64)> =
        header.iter().enumerate().filter_map(|(i, h)| spectral_column_nm(h).map(|nm| (i, nm))).collect();
    if spectral.len() < 2 {
        return Err(LocatedError::at(path, *header_line, None, "no spectral columns (`380nm`, `381nm`, ...)"));
    }
    let wl: Vec<Cell> = spectral.iter().map(|&(i, nm)| Cell { value: nm, line: *header_line, column: i + 1 }).collect();
    check_wavelengths(path, &wl)?;
    let mut rows: Vec<(String, usize, Vec<Cell>)> = Vec::new();
    for (line, c) in &lines[header_at + 1..] {
        if c.len() != header.len() {
            return Err(LocatedError::at(
                path,
                *line,
                Some(c.len().min(header.len()) + 1),
                format!("{} cells, but the table header has {}", c.len(), header.len()),
            ));
        }
        let mut cells = Vec::with_capacity(spectral.len());
        for &(i, nm) in &spectral {
            let value = parse_number(path, &c[i], *line, i + 1, &format!("the radiance at {nm} nm"))?;
            if value < 0.0 {
                return Err(LocatedError::at(
                    path,
                    *line,
                    Some(i + 1),
                    format!("radiance {value} at {nm} nm is negative"),
                ));
            }
            cells.push(Cell { value, line: *line, column: i + 1 });
        }
        rows.push((c[name_col].clone(), *line, cells));
    }
    let find = |user: &str, aliases: &[&str], role: &str| -> Result<&Vec<Cell>, LocatedError> {
        let hits: Vec<&(String, usize, Vec<Cell>)> = rows
            .iter()
            .filter(|(n, _, _)| n.eq_ignore_ascii_case(user) || aliases.iter().any(|a| n.eq_ignore_ascii_case(a)))
            .collect();
        match hits.as_slice() {
            [one] => Ok(&one.2),
            [] => Err(LocatedError::file(
                path,
                format!(
                    "no {role} measurement (a `Data Name` of {}); rows: {}",
                    aliases.join(" or "),
                    rows.iter().map(|r| r.0.as_str()).collect::<Vec<_>>().join(", ")
                ),
            )),
            [a, b, ..] => {
                Err(LocatedError::at(path, b.1, None, format!("a second {role} measurement (first on line {})", a.1)))
            }
        }
    };
    let white = find("WHITE_BASO4", &WHITE_NAMES, "white-standard")?;
    let wavelengths: Vec<f64> = spectral.iter().map(|&(_, nm)| nm).collect();
    let rho: Vec<f64> = match white_reflectance {
        Some(spec) => {
            wavelengths.iter().map(|&nm| linear_interpolate(spec.wavelengths_nm(), spec.values(), nm)).collect()
        }
        None => {
            let line_rho = lines[..header_at]
                .iter()
                .find(|(_, c)| c.first().is_some_and(|k| k.eq_ignore_ascii_case("White Standard")));
            let rho = match line_rho {
                Some((line, c)) => match c.get(2) {
                    Some(v) => parse_number(path, v, *line, 3, "the white standard's reflectance")?,
                    None => BASO4_REFLECTANCE,
                },
                None => BASO4_REFLECTANCE,
            };
            if !(rho > 0.0 && rho <= 1.0) {
                return Err(LocatedError::file(path, format!("white-standard reflectance {rho} must be in (0, 1]")));
            }
            vec![rho; wavelengths.len()]
        }
    };
    let reflectance = |cells: &[Cell], what: &str| -> Result<SampledSpectrum, LocatedError> {
        let mut v = Vec::with_capacity(cells.len());
        for ((s, w), r) in cells.iter().zip(white).zip(&rho) {
            if w.value <= 0.0 {
                return Err(LocatedError::at(
                    path,
                    w.line,
                    Some(w.column),
                    format!("white-standard radiance {} must be positive (no light at this wavelength?)", w.value),
                ));
            }
            let refl = s.value / w.value * r;
            if refl > super::MAX_REFLECTANCE {
                return Err(LocatedError::at(
                    path,
                    s.line,
                    Some(s.column),
                    format!("{what} reflectance {refl} (radiance / white radiance × {r}) is above 1.5"),
                ));
            }
            v.push(refl);
        }
        SampledSpectrum::new(wavelengths.clone(), v).map_err(|e| LocatedError::file(path, e.to_string()))
    };
    let r_inf = reflectance(find(&names.r_inf, &R_INF_NAMES, "R∞ (opaque layer)")?, "r_inf")?;
    let r = reflectance(find(&names.r, &R_NAMES, "R (thin layer over background)")?, "r")?;
    let rg = reflectance(find(&names.rg, &RG_NAMES, "Rg (background)")?, "rg")?;
    let kind = metadata.get("kind").and_then(|k| Kind::parse(k));
    let thickness_mm = metadata.get("thickness_mm").and_then(|t| t.trim().parse().ok()).filter(|v: &f64| *v > 0.0);
    Ok(Measurement {
        source: path.to_path_buf(),
        format: format!(
            "spectroradiometer radiance export (white standard ρ = {:.3}…{:.3})",
            rho.iter().copied().fold(f64::INFINITY, f64::min),
            rho.iter().copied().fold(0.0, f64::max)
        ),
        name: path.file_stem().map_or_else(String::new, |s| s.to_string_lossy().into_owned()),
        kind,
        thickness_mm,
        instrument: metadata.get("instrument").cloned(),
        scale: Scale::Fraction { declared: true },
        r_inf,
        r,
        rg,
        metadata,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const FILE: &str = "Instrument,CS-2000\r\nComment,\"a, b\"\r\nWhite Standard,BaSO4,0.980\r\n\r\n\
No.,Data Name,Date,380nm,381nm,382nm\r\n1,WHITE_BASO4,d,2.0,2.0,4.0\r\n2,SAMPLE_RINF,d,1.0,1.5,2.0\r\n\
3,SAMPLE_R,d,0.5,0.5,1.0\r\n4,BACKGROUND_RG,d,0.1,0.1,0.2\r\n";

    #[test]
    fn reflectance_is_radiance_over_white_times_rho() {
        assert!(looks_like_radiance(FILE));
        let m = parse(Path::new("cs.csv"), FILE, &SampleNames::default(), None).unwrap();
        assert_eq!(m.instrument.as_deref(), Some("CS-2000"));
        assert_eq!(m.metadata.get("comment").map(String::as_str), Some("a, b"));
        assert!((m.r_inf.values()[1] - 0.75 * 0.98).abs() < 1e-15);
        assert!((m.rg.values()[2] - 0.05 * 0.98).abs() < 1e-15);
    }

    #[test]
    fn errors() {
        let bad = FILE.replace("1,WHITE_BASO4,d,2.0,2.0,4.0", "1,WHITE_BASO4,d,2.0,0.0,4.0");
        let e = parse(Path::new("cs.csv"), &bad, &SampleNames::default(), None).unwrap_err();
        assert_eq!((e.line, e.column), (Some(6), Some(5)), "{e}");
        let missing = FILE.replace("4,BACKGROUND_RG,d,0.1,0.1,0.2\r\n", "");
        let e = parse(Path::new("cs.csv"), &missing, &SampleNames::default(), None).unwrap_err();
        assert!(e.to_string().contains("no Rg (background) measurement"), "{e}");
    }

    #[test]
    fn white_standard_files_hold_one_spectrum_in_range() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("white.csv");
        std::fs::write(&p, "wavelength_nm,baso4\n380,0.97\n780,0.98\n").unwrap();
        assert_eq!(read_white_standard(&p).unwrap().values(), &[0.97, 0.98]);
        std::fs::write(&p, "CGATS.17\nBEGIN_DATA_FORMAT\nSAMPLE_NAME nm380 nm780\nEND_DATA_FORMAT\nBEGIN_DATA\nW 0.97 0.98\nEND_DATA\n")
            .unwrap();
        assert_eq!(read_white_standard(&p).unwrap().values(), &[0.97, 0.98]);
        std::fs::write(&p, "wavelength_nm,a,b\n380,0.97,0.9\n780,0.98,0.9\n").unwrap();
        let e = read_white_standard(&p).unwrap_err().to_string();
        assert!(e.ends_with(": expected one reflectance column besides wavelength_nm, found 2"), "{e}");
        std::fs::write(&p, "wavelength_nm,baso4\n380,0.97\n780,1.2\n").unwrap();
        let e = read_white_standard(&p).unwrap_err().to_string();
        assert!(e.ends_with(": white reflectance 1.2 at 780 nm must be in (0, 1]"), "{e}");
    }
}
