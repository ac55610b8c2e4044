//! `rouge analyze metamerism STANDARD SAMPLE`: the special metamerism index of a pair for a
//! change of illuminant and of observer (`rouge_measure::analysis::metamerism`; CIE 15:2018 §9,
//! ISO 18314-4).

use crate::cli::analyze::{CommonArgs, load_layer, skins, write_json};
use crate::cli::color::{parse_illuminant, parse_observer};
use anyhow::{Result, anyhow, bail};
use clap::Args;
use rouge_measure::analysis::metamerism::{self, Correction, MetamerismIndex};
use rouge_measure::colorimetry::{Illuminant, Observer, Viewing};
use rouge_measure::import::read_spectra;
use rouge_measure::spectrum::{Extrapolation, Spectrum};
use serde_json::json;
use std::path::{Path, PathBuf};

#[derive(Debug, Args)]
pub struct MetamerismArgs {
    /// The standard: a preset (built-in name or preset file: its R∞, or over the skin at
    /// --thickness-um) or a spectrum file (CSV table or CGATS; `FILE#NAME` picks one spectrum
    /// of several).
    pub standard: String,
    /// The sample, as the standard.
    pub sample: String,
    /// The reference illuminant, under which the pair is matched.
    #[arg(long, default_value = "D65", value_parser = parse_illuminant)]
    pub reference: Illuminant,
    /// Test illuminants, comma-separated (D65, D55, D50, A, E, FL2, FL7, FL11 or F11, LED-B3).
    #[arg(long, value_delimiter = ',', value_parser = parse_illuminant, default_value = "A,FL11,LED-B3")]
    pub test: Vec<Illuminant>,
    /// The observer of the illuminant index and the reference observer of the observer index.
    #[arg(long, default_value = "1931", value_parser = parse_observer)]
    pub observer: Observer,
    /// The test observer of the observer index (under the reference illuminant).
    #[arg(long = "test-observer", default_value = "1964", value_parser = parse_observer)]
    pub test_observer: Observer,
    /// Presets are seen over the skin at this thickness, µm, instead of as R∞ (the skin is
    /// --skin's first sample, or --sample NAME; default the ColorChecker's dark skin).
    #[arg(long = "thickness-um")]
    pub thickness_um: Option<f64>,
    /// Skin reflectances (CSV table or CGATS), for --thickness-um.
    #[arg(long)]
    pub skin: Option<PathBuf>,
    /// A named skin tone of the skin model instead (`rouge skin tones`).
    #[arg(long = "skin-tone")]
    pub skin_tone: Option<String>,
    /// Which sample of --skin.
    #[arg(long = "skin-sample")]
    pub skin_sample: Option<String>,
    /// Hold the end values of spectra that do not cover 380-780 nm.
    #[arg(long)]
    pub extrapolate: bool,
    /// Also write the results as JSON here.
    #[arg(long)]
    pub json: Option<PathBuf>,
}

/// One side of the pair: its name and reflectance on the working grid.
fn side(spec: &str, args: &MetamerismArgs, skin: &Option<(String, Spectrum, f64)>) -> Result<(String, Spectrum)> {
    let (path_text, pick) = split_pick(spec);
    let path = Path::new(path_text);
    let is_preset_file = path.is_file() && path.extension().is_some_and(|e| e.eq_ignore_ascii_case("json"));
    if !path.is_file() || is_preset_file {
        let (preset, layer) = load_layer(spec)?;
        return Ok(match skin {
            None => (format!("{} (R∞)", preset.name), layer.r_inf()),
            Some((name, r, x)) => {
                (format!("{} at {} µm over {name}", preset.name, x * 1e3), layer.reflectance_over(*x, r))
            }
        });
    }
    read_one_spectrum(path, pick, args.extrapolate)
}

/// One spectrum of a spectrum file (CSV table or CGATS) on the working grid: the only one, or
/// the one named `pick` (`FILE#NAME` on the command line); errors name the file and the choices.
pub(crate) fn read_one_spectrum(path: &Path, pick: Option<&str>, extrapolate: bool) -> Result<(String, Spectrum)> {
    let extrapolation = if extrapolate { Extrapolation::Constant } else { Extrapolation::Refuse };
    let all = read_spectra(path)?.to_working_grid(extrapolation)?;
    let names = || all.iter().map(|(n, _)| n.as_str()).collect::<Vec<_>>().join(", ");
    let chosen = match pick {
        Some(n) => all.iter().find(|(name, _)| name == n),
        None if all.len() == 1 => all.first(),
        None => bail!("{}: {} spectra ({}): pick one as {}#NAME", path.display(), all.len(), names(), path.display()),
    };
    let (name, r) = chosen.ok_or_else(|| {
        anyhow!("{}: no spectrum named `{}` (there are: {})", path.display(), pick.unwrap_or(""), names())
    })?;
    Ok((format!("{} ({name})", path.display()), *r))
}

/// `FILE#NAME` → (FILE, NAME) when FILE exists; else the whole text.
pub(crate) fn split_pick(spec: &str) -> (&str, Option<&str>) {
    match spec.rsplit_once('#') {
        Some((p, n)) if Path::new(p).is_file() => (p, Some(n)),
        _ => (spec, None),
    }
}

fn row(m: &MetamerismIndex) -> serde_json::Value {
    json!({
        "test": m.test.to_string(), "illuminant": m.test.illuminant.name(), "observer": m.test.observer.name(),
        "correction": m.correction.name(), "delta_e_ab": m.delta_e_ab, "delta_e_2000": m.delta_e_2000,
        "standard_lab": m.standard_lab, "sample_lab_corrected": m.sample_lab_corrected,
    })
}

pub fn run(args: &MetamerismArgs) -> Result<()> {
    if args.test.is_empty() {
        bail!("--test: give at least one test illuminant");
    }
    let skin = match args.thickness_um {
        None => None,
        Some(t) => {
            if !(t >= 0.0 && t.is_finite()) {
                bail!("--thickness-um = {t} µm must be finite and ≥ 0");
            }
            let common = CommonArgs {
                skin: args.skin.clone(),
                skin_tone: args.skin_tone.iter().cloned().collect(),
                extrapolate: args.extrapolate,
                illuminant: args.reference,
                observer: args.observer,
                json: None,
            };
            let all = skins(&common)?;
            let chosen = match &args.skin_sample {
                None => all.into_iter().next(),
                Some(n) => all.into_iter().find(|(name, _)| name == n),
            };
            let (name, r) = chosen.ok_or_else(|| {
                anyhow!("--skin-sample: no skin named `{}`", args.skin_sample.as_deref().unwrap_or(""))
            })?;
            Some((name, r, t * 1e-3))
        }
    };
    let (std_name, std) = side(&args.standard, args, &skin)?;
    let (smp_name, smp) = side(&args.sample, args, &skin)?;
    let reference = Viewing { illuminant: args.reference, observer: args.observer };
    let matched = metamerism::reference_match(&std, &smp, reference);
    let by_illuminant = metamerism::illuminant_metamerism(&std, &smp, reference, &args.test, &Correction::ALL)?;
    let observer_test = Viewing { observer: args.test_observer, ..reference };
    let by_observer = Correction::ALL
        .into_iter()
        .map(|c| metamerism::metamerism_index(&std, &smp, reference, observer_test, c))
        .collect::<Result<Vec<_>, _>>()?;
    println!("standard {std_name}\nsample   {smp_name}");
    println!(
        "under the reference {reference}: ΔE*ab {:.3}, ΔE2000 {:.3}{}",
        matched.delta_e_ab,
        matched.delta_e_2000,
        if matched.delta_e_2000 > 1.0 {
            " (not a match: the corrected indices say how the mismatch changes, not how a match fails)"
        } else {
            ""
        }
    );
    crate::emit(&format!("{:<22} {:<15} {:>9} {:>9}", "test", "correction", "ΔE*ab", "ΔE2000"))?;
    for m in by_illuminant.iter().chain(&by_observer) {
        crate::emit(&format!(
            "{:<22} {:<15} {:>9.3} {:>9.3}",
            m.test.to_string(),
            m.correction.name(),
            m.delta_e_ab,
            m.delta_e_2000
        ))?;
    }
    let value = json!({
        "standard": {"spec": args.standard, "name": std_name},
        "sample": {"spec": args.sample, "name": smp_name},
        "reference": reference.to_string(),
        "thickness_mm": skin.as_ref().map(|s| s.2), "skin": skin.as_ref().map(|s| s.0.clone()),
        "reference_match": matched,
        "illuminant": by_illuminant.iter().map(row).collect::<Vec<_>>(),
        "observer": by_observer.iter().map(row).collect::<Vec<_>>(),
        "definition": "CIE 15:2018 §9 / ISO 18314-4: sample corrected to the standard under the reference \
                       (additive in CIELAB, multiplicative in XYZ), then ΔE*ab (CIE 1976) and ΔE2000 under the test",
    });
    write_json(&args.json, &value)
}
