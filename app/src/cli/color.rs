//! `rouge color FILE`: colorimetry of a table of spectra or a CGATS file.

use anyhow::Result;
use clap::Args;
use rouge_measure::colorimetry::{Colorimeter, Illuminant, Observer, Viewing};
use rouge_measure::import::read_spectra;
use rouge_measure::spectrum::Extrapolation;
use serde_json::json;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct ColorArgs {
    /// Spectra: a CSV with `wavelength_nm` and one column per sample (or one sample per row), or
    /// a CGATS file (X-Rite, i1Profiler, ArgyllCMS), read as `rouge import` reads them.
    pub file: PathBuf,
    /// Illuminant: D65, D55, D50, A, E, FL2, FL7, FL11 (or F11) or LED-B3.
    #[arg(long, default_value = "D65", value_parser = parse_illuminant)]
    pub illuminant: Illuminant,
    /// Observer: 1931 (2°) or 1964 (10°).
    #[arg(long, default_value = "1931", value_parser = parse_observer)]
    pub observer: Observer,
    /// Hold the end values when the grid does not cover 380-780 nm (CIE 15 constant extrapolation).
    #[arg(long)]
    pub extrapolate: bool,
}

pub fn parse_illuminant(s: &str) -> Result<Illuminant, String> {
    Illuminant::parse(s)
        .ok_or_else(|| format!("unknown illuminant `{s}` (D65, D55, D50, A, E, FL2, FL7, FL11, LED-B3)"))
}

pub fn parse_observer(s: &str) -> Result<Observer, String> {
    Observer::parse(s).ok_or_else(|| format!("unknown observer `{s}` (1931 or 1964)"))
}

pub fn run(args: &ColorArgs) -> Result<()> {
    let extrapolation = if args.extrapolate { Extrapolation::Constant } else { Extrapolation::Refuse };
    let spectra = read_spectra(&args.file)?.to_working_grid(extrapolation)?;
    let viewing = Viewing { illuminant: args.illuminant, observer: args.observer };
    let c = Colorimeter::get(viewing);
    let mut out = Vec::with_capacity(spectra.len());
    for (name, s) in &spectra {
        let xyz = c.xyz(s);
        out.push(json!({
            "name": name,
            "xyz": xyz.xyz,
            "lab": c.lab(&xyz).lab,
            "srgb_linear": c.srgb_linear(&xyz),
            "srgb": c.srgb(&xyz),
        }));
    }
    crate::emit(&serde_json::Value::Array(out).to_string())
}
