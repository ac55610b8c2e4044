//! `rouge skin fit|spectrum|tones`: the spectral skin model of `rouge_measure::skin` on the
//! command line (docs/SKIN.md).

use crate::plot_png::{Chart, Marker, Series, render};
use anyhow::{Result, anyhow, bail};
use clap::{Args, Subcommand};
use rouge_measure::analysis::skin::read_sampled_skins;
use rouge_measure::colorimetry::{Colorimeter, Viewing};
use rouge_measure::skin::fit::{SkinFitter, lab_d65};
use rouge_measure::skin::optics::{SkinOptics, rgb_medium};
use rouge_measure::skin::{FitOptions, SkinFit, SkinParams, Specular, ita_deg, skin_tones};
use rouge_measure::spectrum::{Extrapolation, Spectrum, working_wavelength_nm};
use serde_json::json;
use std::path::PathBuf;
use std::time::Instant;

#[derive(Debug, Subcommand)]
pub enum SkinCommand {
    /// Fit the skin model to measured reflectance spectra: melanin, its pheomelanin share, blood,
    /// oxygen saturation and scattering per spectrum, with ΔE2000 (D65, CIE 1931) and spectral RMS.
    ///
    /// FILE is a spectra table (`wavelength_nm` or `wavelength` and one column per skin, as
    /// colour-science writes, or one skin per row) or a CGATS file. Spectra that stop short of
    /// 380 or 780 nm need --extrapolate (their end values are held for the colour difference; the
    /// spectral fit uses the measured wavelengths only).
    Fit(FitArgs),
    /// The forward model: the reflectance of given parameters (or a named tone), 380-780 nm, as
    /// CSV on stdout, with its colour, ITA and the medium the renderer takes in --json.
    Spectrum(SpectrumArgs),
    /// The named skin tones, very light to very deep: ITA, CIELAB, sRGB swatch and parameters.
    Tones(TonesArgs),
    /// The default head's skin maps as files (what `rouge render --skin-maps` draws): the
    /// parameters per texel (OpenEXR), their colour (the albedo texture) and where the conditions
    /// are (a mask for concealer).
    Maps(crate::cli::skin_maps::MapsArgs),
}

#[derive(Debug, Args)]
pub struct FitArgs {
    /// Spectra table or CGATS file.
    pub file: PathBuf,
    /// Hold the end values of spectra that do not cover 380-780 nm (e.g. 360-740 nm data).
    #[arg(long)]
    pub extrapolate: bool,
    /// Whether the spectra include the surface's specular reflection: `included` (SCI, the
    /// default) or `excluded` (SCE, a d/8° sphere with its light trap open).
    #[arg(long, default_value = "included", value_parser = parse_specular)]
    pub specular: Specular,
    /// Thickness of the epidermis, held fixed in the fit, mm.
    #[arg(long, default_value_t = SkinParams::DEFAULT_EPIDERMIS_MM)]
    pub epidermis_mm: f64,
    /// Worker threads (default: every core).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Write one JSON object per spectrum here (name, params, wavelengths_nm, fitted_reflectance,
    /// measured_reflectance, delta_e, rms, lab_measured, lab_fitted, ita_deg, at_bounds).
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// Draw measured against fitted for up to six spectra across the ITA range into this PNG.
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// Print a line per spectrum (by default only for up to 40 spectra, then the summary).
    #[arg(long)]
    pub verbose: bool,
}

/// The model's parameters as options (defaults: [`SkinParams::LIGHT`]).
#[derive(Debug, Args)]
pub struct ParamArgs {
    /// Start from a named tone (`rouge skin tones` lists them); the options below override it.
    #[arg(long)]
    pub tone: Option<String>,
    /// Melanin volume fraction of the epidermis, 0-0.6.
    #[arg(long)]
    pub melanin: Option<f64>,
    /// Share of pheomelanin in the melanin, 0-1.
    #[arg(long)]
    pub pheomelanin: Option<f64>,
    /// Blood volume fraction of the dermis, 0-0.3.
    #[arg(long)]
    pub blood: Option<f64>,
    /// Oxygen saturation of the blood, 0-1.
    #[arg(long)]
    pub saturation: Option<f64>,
    /// Reduced scattering at 500 nm, per mm (0.5-10).
    #[arg(long)]
    pub scattering: Option<f64>,
    /// Power of the scattering's fall with wavelength, 0-4.
    #[arg(long)]
    pub scattering_power: Option<f64>,
    /// Epidermis thickness, mm (0.01-0.3).
    #[arg(long)]
    pub epidermis_mm: Option<f64>,
}

impl ParamArgs {
    pub fn params(&self) -> Result<SkinParams> {
        let overrides = [
            self.melanin,
            self.pheomelanin,
            self.blood,
            self.saturation,
            self.scattering,
            self.scattering_power,
            self.epidermis_mm,
        ];
        Ok(SkinParams::from_tone(self.tone.as_deref(), overrides)?)
    }
}

#[derive(Debug, Args)]
pub struct SpectrumArgs {
    #[command(flatten)]
    pub params: ParamArgs,
    /// Also write parameters, spectrum, colour, ITA, the layers' μa and μs′ per wavelength and the
    /// RGB medium for the renderer as JSON here.
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// Write the RGB medium as a `rouge-medium` file here (for `rouge render --medium FILE`).
    #[arg(long)]
    pub medium: Option<PathBuf>,
}

#[derive(Debug, Args)]
pub struct TonesArgs {
    /// Also write the tones as JSON here (name, fitzpatrick, ita, lab, srgb, params, source).
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// Draw the tones' spectra and their place in L*-b* (the ITA diagram) into this PNG.
    #[arg(long)]
    pub plot: Option<PathBuf>,
}

fn parse_specular(s: &str) -> Result<Specular, String> {
    match s {
        "included" | "sci" | "SCI" => Ok(Specular::Included),
        "excluded" | "sce" | "SCE" => Ok(Specular::Excluded),
        _ => Err(format!("`{s}`: `included` (SCI) or `excluded` (SCE)")),
    }
}

pub fn run(cmd: &SkinCommand) -> Result<()> {
    match cmd {
        SkinCommand::Fit(a) => fit(a),
        SkinCommand::Spectrum(a) => spectrum(a),
        SkinCommand::Tones(a) => tones(a),
        SkinCommand::Maps(a) => crate::cli::skin_maps::run(a),
    }
}

fn percentile(sorted: &[f64], q: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    let k = ((sorted.len() - 1) as f64 * q).round() as usize;
    sorted[k]
}

fn srgb8(r: &Spectrum) -> [u8; 3] {
    let c = Colorimeter::get(Viewing::D65_1931);
    c.srgb(&c.xyz(r)).map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8)
}

fn fit(a: &FitArgs) -> Result<()> {
    let skins = read_sampled_skins(&a.file)?;
    if skins.is_empty() {
        bail!("{}: no spectra", a.file.display());
    }
    let options = FitOptions {
        specular: a.specular,
        epidermis_thickness_mm: a.epidermis_mm,
        extrapolation: if a.extrapolate { Extrapolation::Constant } else { Extrapolation::Refuse },
        ..FitOptions::default()
    };
    let start = Instant::now();
    let fitter = SkinFitter::new(options)?;
    let threads = a.threads.unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get())).max(1);
    let chunk = skins.len().div_ceil(threads);
    let results: Vec<Result<SkinFit>> = std::thread::scope(|s| {
        let handles: Vec<_> = skins
            .chunks(chunk)
            .map(|part| {
                let fitter = &fitter;
                let file = &a.file;
                s.spawn(move || {
                    part.iter()
                        .map(|(name, sp)| {
                            fitter
                                .fit(sp.wavelengths_nm(), sp.values())
                                .map_err(|e| anyhow!("{}: spectrum `{name}`: {e}", file.display()))
                        })
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().unwrap_or_else(|_| vec![Err(anyhow!("a fitting thread stopped"))]))
            .collect()
    });
    let fits: Vec<SkinFit> = results.into_iter().collect::<Result<_>>()?;
    let seconds = start.elapsed().as_secs_f64();

    let verbose = a.verbose || fits.len() <= 40;
    let mut out = String::new();
    if verbose {
        out.push_str("spectrum                   ΔE00    RMS  melanin pheo  blood   sat  μs′500  power  at bounds\n");
        for ((name, _), f) in skins.iter().zip(&fits) {
            let p = &f.params;
            out.push_str(&format!(
                "{:<24} {:6.2} {:6.4} {:8.4} {:5.2} {:6.4} {:5.2} {:7.2} {:6.2}  {}\n",
                name,
                f.delta_e_2000,
                f.rms,
                p.melanin_fraction,
                p.pheomelanin_share,
                p.blood_fraction,
                p.oxygen_saturation,
                p.scattering_500nm_per_mm,
                p.scattering_power,
                f.at_bounds.join(",")
            ));
        }
    }
    let mut de: Vec<f64> = fits.iter().map(|f| f.delta_e_2000).collect();
    de.sort_by(f64::total_cmp);
    let mut rms: Vec<f64> = fits.iter().map(|f| f.rms).collect();
    rms.sort_by(f64::total_cmp);
    out.push_str(&format!(
        "{} spectra in {:.2} s ({} threads, {:.0} model evaluations a spectrum): ΔE2000 median {:.2}, 95th percentile {:.2}, max {:.2}; spectral RMS median {:.4}",
        fits.len(),
        seconds,
        threads,
        fits.iter().map(|f| f.evaluations as f64).sum::<f64>() / fits.len() as f64,
        percentile(&de, 0.5),
        percentile(&de, 0.95),
        de.last().copied().unwrap_or(f64::NAN),
        percentile(&rms, 0.5),
    ));
    crate::emit(&out)?;

    if let Some(path) = &a.json {
        let rows: Vec<_> = skins
            .iter()
            .zip(&fits)
            .map(|((name, sp), f)| {
                let inside = |w: &&f64| (380.0..=780.0).contains(*w);
                let wl: Vec<f64> = sp.wavelengths_nm().iter().filter(inside).copied().collect();
                let measured: Vec<f64> =
                    sp.wavelengths_nm().iter().zip(sp.values()).filter(|(w, _)| inside(w)).map(|(_, v)| *v).collect();
                let fitted = f.params.reflectance_at(&wl).unwrap_or_default();
                json!({
                    "name": name,
                    "params": f.params,
                    "wavelengths_nm": wl,
                    "fitted_reflectance": fitted,
                    "measured_reflectance": measured,
                    "delta_e": f.delta_e_2000,
                    "rms": f.rms,
                    "lab_measured": f.lab_measured,
                    "lab_fitted": f.lab_fitted,
                    "ita_deg": f.ita_deg(),
                    "at_bounds": f.at_bounds,
                })
            })
            .collect();
        crate::write_output(path, serde_json::to_string_pretty(&rows)?.as_bytes())?;
    }
    if let Some(path) = &a.plot {
        crate::write_output(path, &fit_plot(&skins.iter().map(|(n, _)| n.as_str()).collect::<Vec<_>>(), &fits)?)?;
    }
    Ok(())
}

/// Up to six spectra evenly spread over the ITA range, measured (dots) against fitted (line).
fn fit_plot(names: &[&str], fits: &[SkinFit]) -> Result<Vec<u8>> {
    let mut order: Vec<usize> = (0..fits.len()).collect();
    order.sort_by(|&x, &y| fits[y].ita_deg().total_cmp(&fits[x].ita_deg()));
    let n = order.len().min(6);
    let picks: Vec<usize> = (0..n).map(|k| order[if n > 1 { k * (order.len() - 1) / (n - 1) } else { 0 }]).collect();
    let charts: Vec<Chart> = picks
        .iter()
        .map(|&i| {
            let f = &fits[i];
            let rgb = srgb8(&f.measured);
            let wl = |j: usize| working_wavelength_nm(j);
            Chart {
                title: format!("{}: ITA {:.0}°, ΔE00 {:.2}", names[i], f.ita_deg(), f.delta_e_2000),
                x_label: "wavelength (nm)".into(),
                y_label: "reflectance".into(),
                series: vec![
                    Series {
                        label: "measured".into(),
                        rgb,
                        points: (0..81)
                            .step_by(2)
                            .filter(|&j| (f.measured_range_nm.0..=f.measured_range_nm.1).contains(&wl(j)))
                            .map(|j| (wl(j), f.measured.0[j], None))
                            .collect(),
                        line: false,
                        marker: Marker::Dot,
                    },
                    Series {
                        label: "fitted".into(),
                        rgb: [30, 30, 30],
                        points: (0..81).map(|j| (wl(j), f.fitted.0[j], None)).collect(),
                        line: true,
                        marker: Marker::Dot,
                    },
                ],
            }
        })
        .collect();
    render("Skin model fits (dots: measured, in the skin's colour; line: the model)", &charts, 3)
}

fn spectrum(a: &SpectrumArgs) -> Result<()> {
    let p = a.params.params()?;
    let r = p.reflectance()?;
    let mut csv = String::from("wavelength_nm,reflectance\n");
    for (j, v) in r.0.iter().enumerate() {
        csv.push_str(&format!("{},{v:.6}\n", working_wavelength_nm(j)));
    }
    crate::emit(csv.trim_end())?;
    let lab = lab_d65(&r);
    let medium = rgb_medium(&p)?;
    eprintln!(
        "L*a*b* (D65, 1931) {:.2} {:.2} {:.2}, ITA {:.1}°; RGB medium σa {:?} /mm, σs′ {:?} /mm",
        lab.lab[0],
        lab.lab[1],
        lab.lab[2],
        ita_deg(&lab),
        medium.sigma_a_per_mm.map(|v| (v * 1e4).round() / 1e4),
        medium.sigma_s_prime_per_mm.map(|v| (v * 1e4).round() / 1e4)
    );
    if let Some(path) = &a.json {
        let layers: Vec<SkinOptics> = (0..81).map(|j| SkinOptics::at(&p, working_wavelength_nm(j))).collect();
        let v = json!({
            "params": p,
            "wavelengths_nm": (0..81).map(working_wavelength_nm).collect::<Vec<_>>(),
            "reflectance": r.0.to_vec(),
            "lab": lab.lab,
            "ita_deg": ita_deg(&lab),
            "srgb8": srgb8(&r),
            "layers": layers,
            "rgb_medium": medium,
        });
        crate::write_output(path, serde_json::to_string_pretty(&v)?.as_bytes())?;
    }
    if let Some(path) = &a.medium {
        let name = path.file_stem().and_then(|s| s.to_str()).unwrap_or("skin");
        let v = json!({
            "schema": "rouge-medium",
            "version": 1,
            "name": name,
            "description": "Skin from Rouge's spectral skin model (rouge skin spectrum)",
            "sigma_a_per_mm": medium.sigma_a_per_mm,
            "sigma_s_prime_per_mm": medium.sigma_s_prime_per_mm,
            "g": 0.0,
            "eta": medium.eta,
            "source": "rouge_measure::skin::optics::rgb_medium (docs/SKIN.md)",
            "notes": format!("parameters: {}", serde_json::to_string(&p)?),
        });
        crate::write_output(path, serde_json::to_string_pretty(&v)?.as_bytes())?;
    }
    Ok(())
}

/// How far light travels under the lightest, a middle and the deepest tone: 2πr·R(r), the
/// density of the distance between entry and exit, of each tone's RGB medium ([`rgb_medium`]) by
/// the better dipole (\[dEon2012\]; `rouge_render::diffusion`).
fn profile_chart(tones: &[rouge_measure::skin::SkinTone]) -> Result<Chart> {
    use rouge_render::diffusion::{ChannelProfile, ProfileModel};
    let picks = [0, tones.len() / 2, tones.len() - 1];
    let mut series = vec![];
    for &i in &picks {
        let t = &tones[i];
        let m = rgb_medium(&t.params)?;
        for (c, (channel, rgb)) in
            [("R", [200, 40, 40]), ("G", [40, 150, 40]), ("B", [40, 60, 200])].into_iter().enumerate()
        {
            let p =
                ChannelProfile::new(ProfileModel::BetterDipole, m.sigma_a_per_mm[c], m.sigma_s_prime_per_mm[c], m.eta);
            let shade = |v: u8| (f64::from(v) * (0.45 + 0.55 * (1.0 - i as f64 / picks[2].max(1) as f64))) as u8;
            series.push(Series {
                label: format!("{} {channel}", t.name),
                rgb: rgb.map(shade),
                points: (1..=60)
                    .map(|k| {
                        let r = f64::from(k) * 0.05;
                        (r, 2.0 * std::f64::consts::PI * r * p.radial(r), None)
                    })
                    .collect(),
                line: true,
                marker: [Marker::Dot, Marker::Cross, Marker::Diamond][picks.iter().position(|&x| x == i).unwrap_or(0)],
            });
        }
    }
    Ok(Chart {
        title: "Diffusion profiles 2πr·R(r) (lighter: lighter tone)".into(),
        x_label: "r (mm)".into(),
        y_label: "per mm".into(),
        series,
    })
}

fn tones(a: &TonesArgs) -> Result<()> {
    let tones = skin_tones();
    if tones.is_empty() {
        bail!("the built-in tones (data/skin/tones.json) could not be read");
    }
    let mut out =
        String::from("tone          Fitzpatrick    ITA     L*     a*     b*  sRGB     melanin  pheo  blood   sat\n");
    let mut rows = vec![];
    let mut spectra = vec![];
    for t in tones {
        let r = t.params.reflectance()?;
        let lab = lab_d65(&r);
        let rgb = srgb8(&r);
        out.push_str(&format!(
            "{:<13} {:<11} {:6.1} {:6.2} {:6.2} {:6.2}  #{:02x}{:02x}{:02x}  {:7.4} {:5.2} {:6.4} {:5.2}\n",
            t.name,
            t.fitzpatrick,
            ita_deg(&lab),
            lab.lab[0],
            lab.lab[1],
            lab.lab[2],
            rgb[0],
            rgb[1],
            rgb[2],
            t.params.melanin_fraction,
            t.params.pheomelanin_share,
            t.params.blood_fraction,
            t.params.oxygen_saturation
        ));
        rows.push(json!({
            "name": t.name, "fitzpatrick": t.fitzpatrick, "ita": ita_deg(&lab), "lab": lab.lab,
            "srgb8": rgb, "params": t.params, "source": t.source,
        }));
        spectra.push((t.name.clone(), r, rgb, lab));
    }
    crate::emit(out.trim_end())?;
    if let Some(path) = &a.json {
        crate::write_output(path, serde_json::to_string_pretty(&rows)?.as_bytes())?;
    }
    if let Some(path) = &a.plot {
        let spectra_chart = Chart {
            title: "Reflectance of the tones".into(),
            x_label: "wavelength (nm)".into(),
            y_label: "reflectance".into(),
            series: spectra
                .iter()
                .map(|(name, r, rgb, _)| Series {
                    label: name.clone(),
                    rgb: *rgb,
                    points: (0..81).step_by(4).map(|j| (working_wavelength_nm(j), r.0[j], None)).collect(),
                    line: true,
                    marker: Marker::Square,
                })
                .collect(),
        };
        let ita_chart = Chart {
            title: "L* against b* (ITA = atan((L* − 50)/b*))".into(),
            x_label: "b*".into(),
            y_label: "L*".into(),
            series: spectra
                .iter()
                .map(|(name, _, rgb, lab)| Series {
                    label: name.clone(),
                    rgb: *rgb,
                    points: vec![(lab.lab[2], lab.lab[0], Some(format!("{:.0}°", ita_deg(lab))))],
                    line: false,
                    marker: Marker::Square,
                })
                .collect(),
        };
        crate::write_output(
            path,
            &render(
                "Rouge's skin tones, very light to very deep",
                &[spectra_chart, ita_chart, profile_chart(tones)?],
                3,
            )?,
        )?;
    }
    Ok(())
}
