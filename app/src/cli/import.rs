//! `rouge import` and `rouge demo`: measurement → preset, with a report.

use anyhow::{Context, Result, bail};
use clap::Args;
use rouge_measure::import::{self, ImportOptions, Kind, Measurement, SampleNames, SpectralInput};
use rouge_measure::km::{self, Saunderson};
use rouge_measure::km_uncertainty::{
    DEFAULT_U_THICKNESS_MM, ILL_CONDITIONED, InstrumentClass, SpectralUncertainty, ThicknessDesign, design_criterion,
    optimal_thickness_mm,
};
use rouge_measure::preset::{ImportReport, Preset};
use rouge_measure::spectrum::{Extrapolation, ResampleMethod, SampledSpectrum, Spectrum};
use std::path::{Path, PathBuf};

#[derive(Debug, Args)]
pub struct ImportArgs {
    /// Measurement file (Rouge CSV, CGATS/X-Rite/i1Profiler/ArgyllCMS .ti3, CS-2000 radiance).
    #[arg(required_unless_present = "r_inf")]
    pub file: Option<PathBuf>,
    /// Single-spectrum file (ArgyllCMS .sp) with R∞, the opaque layer.
    #[arg(long = "r-inf", requires_all = ["r", "rg"], conflicts_with = "file")]
    pub r_inf: Option<PathBuf>,
    /// Single-spectrum file with R, the thin layer over the background.
    #[arg(long, requires = "r_inf")]
    pub r: Option<PathBuf>,
    /// Single-spectrum file with Rg, the background.
    #[arg(long, requires = "r_inf")]
    pub rg: Option<PathBuf>,
    #[command(flatten)]
    pub common: CommonArgs,
    /// Where to write the preset (JSON; written atomically).
    #[arg(long)]
    pub out: PathBuf,
}

#[derive(Debug, Args)]
pub struct DemoArgs {
    #[command(flatten)]
    pub common: CommonArgs,
    /// Also write the preset here.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

#[derive(Debug, Args)]
pub struct CommonArgs {
    /// Thickness of the thin layer, mm (default: the file's `thickness_mm`).
    #[arg(long = "thickness-mm")]
    pub thickness_mm: Option<f64>,
    /// Preset name (default: the file's name).
    #[arg(long)]
    pub name: Option<String>,
    /// Cosmetic kind: foundation, blush, eyeshadow, lipstick, other (default: the file's, else other).
    #[arg(long, value_parser = parse_kind)]
    pub kind: Option<Kind>,
    /// Sample names of R∞, R and Rg in multi-sample files.
    #[arg(long, value_delimiter = ',', value_name = "R_INF,R,RG")]
    pub samples: Option<Vec<String>>,
    /// Hold the end values when the file does not cover 380-780 nm (CIE 15 constant extrapolation).
    #[arg(long)]
    pub extrapolate: bool,
    /// Reflectance of the white standard for radiance files (flat; default: the file's, else 0.99).
    #[arg(long = "white-reflectance", conflicts_with = "white_spectrum")]
    pub white_reflectance: Option<f64>,
    /// Reflectance spectrum of the white standard for radiance files: a CSV with
    /// `wavelength_nm` and one reflectance column, or a one-sample CGATS file (e.g. from its
    /// calibration certificate).
    #[arg(long = "white-spectrum")]
    pub white_spectrum: Option<PathBuf>,
    /// Apply the Saunderson surface correction with this refractive index (K1 = ((n-1)/(n+1))²).
    #[arg(long = "saunderson-ior")]
    pub saunderson_ior: Option<f64>,
    /// Internal diffuse reflectance K2 of the Saunderson correction.
    #[arg(long = "saunderson-k2", default_value_t = 0.6, requires = "saunderson_ior")]
    pub saunderson_k2: f64,
    /// The instrument excluded the specular component (SCE, 45/0): K1 is not subtracted.
    #[arg(long = "specular-excluded", requires = "saunderson_ior")]
    pub specular_excluded: bool,
    /// Also draw the app's material plots as a PNG: the measured reflectances with R∞ and R
    /// re-computed from S and K, S, K, and the renderer's R0(X), T(X) per channel.
    #[arg(long, value_parser = png_path)]
    pub plot: Option<PathBuf>,
    /// Print the report as JSON instead of text.
    #[arg(long)]
    pub json: bool,
    /// The instrument's class, for its documented default repeatability (one standard deviation
    /// of a reading, absolute reflectance): benchtop 0.001, portable 0.002, imaging 0.01.
    #[arg(long = "instrument-class", default_value = "benchtop", value_parser = parse_class)]
    pub instrument_class: InstrumentClass,
    /// The readings' repeatability, absolute reflectance (overrides --instrument-class).
    #[arg(long = "u-reflectance", conflicts_with = "repeatability")]
    pub u_reflectance: Option<f64>,
    /// The instrument's repeatability per wavelength (one standard deviation of a reading,
    /// absolute reflectance) from a spectrum file: a CSV table (`wavelength_nm` and one column)
    /// or CGATS, `FILE#NAME` for one of several; resampled to 380-780 nm like a measurement
    /// (overrides --instrument-class).
    #[arg(long)]
    pub repeatability: Option<String>,
    /// Standard uncertainty of the thin layer's thickness, µm.
    #[arg(long = "u-thickness-um", default_value_t = DEFAULT_U_THICKNESS_MM * 1e3)]
    pub u_thickness_um: f64,
    /// Correlation coefficient between the three readings (a shared calibration error), 0-1.
    #[arg(long = "reading-correlation", default_value_t = 0.0)]
    pub reading_correlation: f64,
}

fn parse_class(s: &str) -> Result<InstrumentClass, String> {
    InstrumentClass::parse(s).ok_or_else(|| format!("unknown instrument class `{s}` (benchtop, portable, imaging)"))
}

fn png_path(s: &str) -> Result<PathBuf, String> {
    let path = PathBuf::from(s);
    match path.extension().and_then(|e| e.to_str()) {
        Some(e) if e.eq_ignore_ascii_case("png") => Ok(path),
        _ => Err(format!("`{s}`: the plot is written as PNG, so its name must end in .png")),
    }
}

fn parse_kind(s: &str) -> Result<Kind, String> {
    Kind::parse(s).ok_or_else(|| format!("unknown kind `{s}` (foundation, blush, eyeshadow, lipstick, other)"))
}

/// The embedded sample measurement used by `rouge demo`.
const DEMO_NAME: &str = "foundation_02_ivory.csv";
const DEMO_CSV: &str = include_str!("../../../data/measurements/foundation_02_ivory.csv");

pub fn run(args: &ImportArgs) -> Result<()> {
    let options = options(&args.common)?;
    let m = match (&args.file, &args.r_inf, &args.r, &args.rg) {
        (Some(file), _, _, _) => import::read_measurement(file, &options)?,
        (None, Some(a), Some(b), Some(c)) => import::read_measurement_files(a, b, c)?,
        _ => bail!("give a measurement FILE, or --r-inf, --r and --rg"),
    };
    convert(&m, &args.common, Some(&args.out))
}

pub fn demo(args: &DemoArgs) -> Result<()> {
    let input = SpectralInput::embedded(Path::new("<embedded>").join(DEMO_NAME), DEMO_CSV);
    let m = input.measurement(&ImportOptions::default())?;
    convert(&m, &args.common, args.out.as_deref())
}

fn options(common: &CommonArgs) -> Result<ImportOptions> {
    let samples = match &common.samples {
        None => SampleNames::default(),
        Some(v) => match v.as_slice() {
            [a, b, c] => SampleNames { r_inf: a.clone(), r: b.clone(), rg: c.clone() },
            _ => bail!("--samples needs three names, R∞, R and Rg, separated by commas (got {})", v.len()),
        },
    };
    let white_reflectance = match (common.white_reflectance, &common.white_spectrum) {
        (_, Some(path)) => Some(import::radiance::read_white_standard(path)?),
        (None, None) => None,
        (Some(rho), None) if rho > 0.0 && rho <= 1.0 => {
            Some(SampledSpectrum::new(vec![380.0, 780.0], vec![rho, rho]).context("white reflectance")?)
        }
        (Some(rho), None) => bail!("--white-reflectance {rho} must be in (0, 1]"),
    };
    Ok(ImportOptions { samples, white_reflectance })
}

fn convert(m: &Measurement, common: &CommonArgs, out: Option<&Path>) -> Result<()> {
    let extrapolation = if common.extrapolate { Extrapolation::Constant } else { Extrapolation::Refuse };
    let working = m.to_working_grid(extrapolation)?;
    let thickness_mm = match (common.thickness_mm, m.thickness_mm) {
        (Some(t), _) | (None, Some(t)) => t,
        (None, None) => bail!(
            "{}: the file gives no thickness: pass --thickness-mm (the thickness of the thin layer R was measured on)",
            m.source.display()
        ),
    };
    let kind = common.kind.or(m.kind).unwrap_or(Kind::Other);
    let name = common.name.clone().unwrap_or_else(|| m.name.clone());
    let saunderson = match common.saunderson_ior {
        None => None,
        Some(n) => Some(Saunderson::from_refractive_index(n, common.saunderson_k2, !common.specular_excluded)?),
    };
    let (mut preset, report) = Preset::from_measurement(m, &working, &name, kind, thickness_mm, saunderson)?;
    let unc = uncertainty(&mut preset, common, &working, saunderson)?;
    if let Some(out) = out {
        preset.save(out)?;
    }
    if let Some(path) = &common.plot {
        let r_re = recomputed_r(&preset, &working, saunderson);
        let panels = rouge_app::material_plots::material_panels(&preset, Some(&r_re));
        let title = format!("{} ({}, measured at D = {} mm)", preset.name, preset.kind.name(), preset.thickness_mm);
        let swatch = rouge_app::material_plots::hex_rgb(&preset.derived.r_inf_srgb_hex);
        let png = crate::plot_png::render_panels(&title, swatch, &panels)?;
        crate::write_output(path, &png)?;
    }
    if common.json {
        let v = serde_json::json!({
            "name": preset.name,
            "kind": preset.kind,
            "source": m.source.display().to_string(),
            "format": m.format,
            "scale": m.scale.to_string(),
            "resampling": format!("{:?}", working.method),
            "extrapolated_nm": working.extrapolated,
            "thickness_mm": thickness_mm,
            "saunderson": saunderson,
            "report": report,
            "uncertainty": {
                "source": unc.source, "u_thickness_mm": unc.u_thickness_mm,
                "relative_u_s": unc.relative(true), "relative_u_k": unc.relative(false),
                "ill_conditioned_nm": unc.spectral.ill_conditioned(), "ill_conditioned_above": ILL_CONDITIONED,
                "criterion_at_measured_thickness": unc.criterion_now, "best_thickness": unc.design,
            },
            "preset": out.map(|p| p.display().to_string()),
        });
        crate::emit(&serde_json::to_string_pretty(&v)?)
    } else {
        let mut text = report_text(m, &working, &preset, &report, saunderson, out);
        text.push('\n');
        text.push_str(&unc.text(preset.thickness_mm));
        crate::emit(&text)
    }
}

/// What `rouge import` says about how certain S and K are.
struct ImportUncertainty {
    source: String,
    u_thickness_mm: f64,
    spectral: SpectralUncertainty,
    /// RMS relative uncertainty at the measured thickness (`design_criterion`).
    criterion_now: Option<f64>,
    design: Option<ThicknessDesign>,
}

impl ImportUncertainty {
    /// (median, max, wavelength of the max) of u(S)/S or u(K)/K.
    fn relative(&self, s: bool) -> Option<(f64, f64, f64)> {
        let mut v: Vec<(f64, f64)> = self
            .spectral
            .per_wavelength
            .iter()
            .enumerate()
            .filter_map(|(i, u)| {
                let (x, ux) = if s { (u.s_per_mm, u.u_s_per_mm) } else { (u.k_per_mm, u.u_k_per_mm) };
                (x > 0.0).then(|| (ux / x, rouge_measure::spectrum::working_wavelength_nm(i)))
            })
            .collect();
        if v.is_empty() {
            return None;
        }
        let max = v.iter().copied().fold((0.0, 0.0), |a, b| if b.0 > a.0 { b } else { a });
        v.sort_by(|a, b| a.0.total_cmp(&b.0));
        Some((v[v.len() / 2].0, max.0, max.1))
    }

    fn text(&self, thickness_mm: f64) -> String {
        let mut lines = vec![format!(
            "  uncertainty readings {}; thickness ± {} µm (GUM linear propagation, 1 standard uncertainty)",
            self.source,
            self.u_thickness_mm * 1e3
        )];
        for (name, s) in [("u(S)/S", true), ("u(K)/K", false)] {
            if let Some((median, max, nm)) = self.relative(s) {
                lines.push(format!("  {name:<11} median {:.2} %, max {:.2} % at {nm} nm", 100.0 * median, 100.0 * max));
            }
        }
        let ill = self.spectral.ill_conditioned();
        if let (Some(first), Some(last)) = (ill.first(), ill.last()) {
            let worst = ill.iter().map(|w| w.1).fold(0.0, f64::max);
            lines.push(format!(
                "  WARNING     ill-conditioned inversion at {} wavelengths, {}-{} nm (condition up to {worst:.0} > \
                 {ILL_CONDITIONED}): R is too close to R∞ or to Rg there, so small reading errors move S and K a lot",
                ill.len(),
                first.0,
                last.0
            ));
        }
        if let (Some(d), Some(now)) = (&self.design, self.criterion_now) {
            lines.push(format!(
                "  design      over this background, a {:.1} µm layer would give S, K to {:.2} % (RMS), against {:.2} % at the \
                 measured {:.1} µm",
                d.thickness_mm * 1e3,
                100.0 * d.relative_uncertainty,
                100.0 * now,
                thickness_mm * 1e3
            ));
        }
        lines.join("\n")
    }
}

/// The instrument's repeatability per wavelength from `--repeatability FILE[#NAME]` on the
/// working grid, and the text the report gives as its source. Errors name the file, and the
/// wavelength of a value that is not finite and ≥ 0.
fn repeatability_file(spec: &str, extrapolate: bool) -> Result<(Spectrum, String)> {
    let (path, pick) = crate::cli::analyze_metamerism::split_pick(spec);
    if !Path::new(path).is_file() {
        bail!(
            "--repeatability `{spec}`: no such file (a spectrum file, CSV table or CGATS, `FILE#NAME` for one of several)"
        );
    }
    let (name, u) = crate::cli::analyze_metamerism::read_one_spectrum(Path::new(path), pick, extrapolate)
        .with_context(|| format!("--repeatability {spec}"))?;
    if let Some((nm, v)) = u.iter_nm().find(|(_, v)| !(*v >= 0.0 && v.is_finite())) {
        bail!("--repeatability {name}: at {nm} nm the repeatability is {v}: must be finite and ≥ 0");
    }
    let (lo, hi) = u.min_max();
    Ok((u, format!("per wavelength from {name} ({lo:.4}-{hi:.4})")))
}

/// The uncertainty of the preset's S and K (stored in it), its warnings and the best thickness.
fn uncertainty(
    preset: &mut Preset,
    common: &CommonArgs,
    working: &import::WorkingMeasurement,
    saunderson: Option<Saunderson>,
) -> Result<ImportUncertainty> {
    let (u_spectrum, source) = match (&common.repeatability, common.u_reflectance) {
        (Some(spec), _) => repeatability_file(spec, common.extrapolate)?,
        (None, Some(u)) if u >= 0.0 && u.is_finite() => (Spectrum::constant(u), format!("± {u} (--u-reflectance)")),
        (None, Some(u)) => bail!("--u-reflectance = {u} must be finite and ≥ 0"),
        (None, None) => {
            let c = common.instrument_class;
            (Spectrum::constant(c.u_reflectance()), c.source_text())
        }
    };
    let u_thickness_mm = match common.u_thickness_um {
        v if v >= 0.0 && v.is_finite() => v * 1e-3,
        v => bail!("--u-thickness-um = {v} must be finite and ≥ 0"),
    };
    if !(0.0..=1.0).contains(&common.reading_correlation) {
        bail!("--reading-correlation = {} must be in [0, 1]", common.reading_correlation);
    }
    let spectral = preset.estimate_uncertainty(&source, &u_spectrum, u_thickness_mm, common.reading_correlation)?;
    let rg = Spectrum(std::array::from_fn(|i| saunderson.map_or(working.rg.0[i], |c| c.to_internal(working.rg.0[i]))));
    let (s, k) = (preset.s(), preset.k());
    let criterion_now = design_criterion(&s, &k, &rg, preset.thickness_mm, &u_spectrum, u_thickness_mm);
    let design = optimal_thickness_mm(&s, &k, &rg, &u_spectrum, u_thickness_mm, 1e-3, 1.0);
    Ok(ImportUncertainty { source, u_thickness_mm, spectral, criterion_now, design })
}

/// R of the measured layer over its background, re-computed from the preset's S and K, in the
/// measurement's terms (back through Saunderson when it was applied).
fn recomputed_r(preset: &Preset, working: &import::WorkingMeasurement, saunderson: Option<Saunderson>) -> Vec<f64> {
    let (s, k) = (preset.s(), preset.k());
    (0..s.0.len())
        .map(|i| {
            let rg = saunderson.map_or(working.rg.0[i], |c| c.to_internal(working.rg.0[i]));
            let layer = km::layer_r_t(s.0[i], k.0[i], preset.thickness_mm).unwrap_or(km::LayerRt::CLEAR);
            let r = km::compose(layer, km::LayerRt::opaque(rg)).r;
            saunderson.map_or(r, |c| c.to_measured(r))
        })
        .collect()
}

fn report_text(
    m: &Measurement,
    working: &import::WorkingMeasurement,
    preset: &Preset,
    r: &ImportReport,
    saunderson: Option<Saunderson>,
    out: Option<&Path>,
) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    // Writing to a String cannot fail.
    macro_rules! line { ($($a:tt)*) => {{ let _ = writeln!(s, $($a)*); }} }
    let w = m.r_inf.wavelengths_nm();
    line!("{} ({}) from {}", preset.name, preset.kind.name(), m.source.display());
    line!("  format      {}; values read as {}", m.format, m.scale);
    let grid = match working.method {
        ResampleMethod::Identity => "the working grid itself".to_string(),
        ResampleMethod::Sprague => "resampled to 380-780/5 nm (Sprague, CIE 167)".to_string(),
        ResampleMethod::Linear => "resampled to 380-780/5 nm (linear: non-uniform grid)".to_string(),
    };
    line!("  grid        {}-{} nm, {} samples: {grid}", w[0], w[w.len() - 1], w.len());
    for (a, b) in &working.extrapolated {
        line!("  WARNING     {a}-{b} nm not measured: end value held constant (--extrapolate)");
    }
    if let Some(c) = saunderson {
        line!(
            "  saunderson  K1 = {:.4}, K2 = {:.3}, specular {}",
            c.k1,
            c.k2,
            if c.specular_included { "included" } else { "excluded" }
        );
    }
    line!("  thickness   {} mm", preset.thickness_mm);
    let [(slo, slo_nm), (shi, shi_nm)] = r.s_range_per_mm;
    let [(klo, klo_nm), (khi, khi_nm)] = r.k_range_per_mm;
    line!("  S           {slo:.4} /mm at {slo_nm} nm  ..  {shi:.4} /mm at {shi_nm} nm");
    line!("  K           {klo:.4} /mm at {klo_nm} nm  ..  {khi:.4} /mm at {khi_nm} nm");
    line!("  R∞ colour   {} (sRGB, D65)", r.r_inf_srgb_hex);
    line!(
        "  check R     max |measured − from S,K| = {:.3e} at {} nm; ΔE2000 = {:.6}",
        r.max_abs_r_error.0,
        r.max_abs_r_error.1,
        r.delta_e_2000_r
    );
    line!(
        "  check R∞    max |measured − from S,K| = {:.3e} at {} nm; ΔE2000 = {:.6}",
        r.max_abs_r_inf_error.0,
        r.max_abs_r_inf_error.1,
        r.delta_e_2000_r_inf
    );
    match out {
        Some(p) => line!("  wrote       {}", p.display()),
        None => line!("  (no preset written: add --out PRESET.json)"),
    }
    s.trim_end().to_string()
}
