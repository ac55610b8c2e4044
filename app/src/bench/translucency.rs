//! `rouge bench translucency`: every subsurface model × reference scene × parameter set, GPU ms
//! per frame against the error to the Mitsuba 3 reference (docs/TRANSLUCENCY.md). Rows follow
//! ../shared/DESIGN.md's benchmark table. Each row's error is the mean ΔE2000 per pixel and over
//! 4×4 blocks of both images (`delta_e_binned`), where the references' own noise weighs less.

use crate::bench::fit_thickness::{Fit, Scene};
use crate::cli::render::scene_args::{Diffuse, Profile, SceneArgs};
use anyhow::{Context, Result, bail};
use clap::{Args, Parser};
use rouge_model::thickness::BakeSettings;
use rouge_render::job::{Prepared, RenderJob, bake_thickness_map};
use rouge_render::local_thickness::ThicknessSource;
use rouge_render::translucency::{BIN_PX, ReferenceImage, measure};
use rouge_render::{Skin, SubsurfaceModel};
use serde::Serialize;
use serde_json::json;
use std::path::{Path, PathBuf};

mod configs;
use configs::{
    COMBINATION_SAMPLES, atlas_configs, combination_configs, dipole_configs, slab_configs, thickness_configs,
};

// clap prints these doc comments as `--help` verbatim: citations stay `[Key]` (`\[Key\]` would show).
#[allow(rustdoc::broken_intra_doc_links)]
#[derive(Debug, Args)]
pub struct TranslucencyBenchArgs {
    /// Folder of references (NAME.exr + NAME.json sidecars from python/render_reference.py).
    #[arg(long, default_value = "data/reference/translucency")]
    pub references: PathBuf,
    /// Only these scenes (sidecar names), comma-separated.
    #[arg(long, value_delimiter = ',')]
    pub only: Vec<String>,
    /// Screen-space kernel sample counts (odd, 3-33).
    #[arg(long, value_delimiter = ',', default_values_t = [5u32, 7, 11, 17, 25, 33])]
    pub samples: Vec<u32>,
    /// Profiles the screen-space kernel is built from.
    #[arg(long, value_delimiter = ',', value_enum, default_values_t = [Profile::Dipole, Profile::BetterDipole, Profile::Burley])]
    pub profiles: Vec<Profile>,
    /// Diffuse laws of the screen-space rows and of `none`: Lambert with the medium's exact
    /// albedo (adding-doubling, which the profile's total approximates), and the exact half-space of the medium (Chandrasekhar's H-function).
    #[arg(long, value_delimiter = ',', value_enum, default_values_t = [Diffuse::Lambert, Diffuse::HalfSpace])]
    pub diffuse: Vec<Diffuse>,
    /// Frames timed per configuration (after two warm-up frames).
    #[arg(long, default_value_t = 3)]
    pub frames: u32,
    /// Write the rows as JSON here.
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// Draw speed against mean ΔE2000 here (PNG): one panel per scene, a line per profile
    /// through its sample counts, a cross for no scattering, a diamond for today's skin, a
    /// square per thickness-translucency configuration.
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// Instead of running: read the rows a run wrote with --json from this file and draw
    /// --plot from them (to redraw a plot without the run's quarter of an hour).
    #[arg(long, requires = "plot")]
    pub replot: Option<PathBuf>,
    /// Rays per vertex of the thickness model's local-thickness bake.
    #[arg(long, default_value_t = 64)]
    pub thickness_rays: u32,
    /// Cutoff (mm) of the local thickness.
    #[arg(long, default_value_t = 30.0)]
    pub thickness_cutoff_mm: f32,
    /// Also sweep the directional dipole's samples N (1, 10, 50, 100) and directions K (4, 8, 16,
    /// 32), and its artifact fixes one by one (slow: use --only).
    #[arg(long)]
    pub dipole_sweep: bool,
    /// Also run the cube atlas's ablations ([Benmounah2009] figures 6 and 9): kernels 3×3 to
    /// 9×9, atlas sizes 256-1024, the reach, each self-occlusion test, without the global term.
    #[arg(long)]
    pub atlas_sweep: bool,
    /// Instead of the table: fit the thickness translucency's distortion, power, scale and
    /// ambient per medium and local-thickness source to the references (least squares on linear
    /// radiance) and print the fits (docs/BENCHMARKS.md; the media files carry them).
    #[arg(long)]
    pub fit_thickness: bool,
}

/// Which local-thickness map a configuration needs uploaded.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum ThicknessMap {
    /// None (another model, or the shadow-map source).
    None,
    /// Baked on the mesh as drawn.
    Current,
    /// Baked on the mesh before `--morph`.
    Rest,
}

/// One configuration of a scene.
#[derive(Clone)]
struct Config {
    model: &'static str,
    params: serde_json::Value,
    skin: Skin,
    samples: u32,
    map: ThicknessMap,
    /// The bounce between facing parts, when the row has it.
    bounce: Option<rouge_render::bounce::BounceSettings>,
}

/// One row of the table (../shared/DESIGN.md).
#[derive(Debug, Serialize, serde::Deserialize)]
struct Row {
    scene: String,
    model: String,
    params: serde_json::Value,
    gpu_ms: Option<f64>,
    /// GPU ms of each pass, summed over its runs in a frame (the thickness pass's own cost is
    /// `thickness`).
    pass_ms: std::collections::BTreeMap<String, f64>,
    wall_ms: f64,
    rmse: f64,
    delta_e_mean: f64,
    delta_e_p95: f64,
    pixels: usize,
    /// Mean ΔE2000 over blocks of `bin_px`² pixels (`rouge_render::translucency::binned`); absent
    /// from rows written before it.
    #[serde(default)]
    delta_e_binned: Option<f64>,
    #[serde(default)]
    bin_px: Option<usize>,
    reference: String,
    reference_noise_rms: f64,
    device: String,
}

/// Parses a sidecar's `rouge_options` as `rouge render` would.
#[derive(Debug, Parser)]
struct OptionsOnly {
    #[command(flatten)]
    scene: SceneArgs,
}

fn sidecars(dir: &Path, only: &[String]) -> Result<Vec<(String, serde_json::Value)>> {
    let mut out = Vec::new();
    let entries = std::fs::read_dir(dir).with_context(|| format!("{}: cannot list the references", dir.display()))?;
    for entry in entries {
        let path = entry?.path();
        if path.extension().is_none_or(|e| e != "json") {
            continue;
        }
        let name = path.file_stem().and_then(|s| s.to_str()).unwrap_or_default().to_string();
        if !only.is_empty() && !only.contains(&name) {
            continue;
        }
        let text = std::fs::read_to_string(&path).with_context(|| format!("{}: cannot read", path.display()))?;
        let value: serde_json::Value = serde_json::from_str(&text)
            .with_context(|| format!("{}: not a reference sidecar (JSON)", path.display()))?;
        out.push((name, value));
    }
    out.sort_by(|a, b| a.0.cmp(&b.0));
    if let Some(missing) = only.iter().find(|n| !out.iter().any(|(m, _)| m == *n)) {
        bail!("{}: no reference named {missing}", dir.display());
    }
    if out.is_empty() {
        bail!("{}: no references (make them with python/render_reference.py)", dir.display());
    }
    Ok(out)
}

pub fn run(args: &TranslucencyBenchArgs) -> Result<()> {
    if let (Some(from), Some(path)) = (&args.replot, &args.plot) {
        let text = std::fs::read_to_string(from).with_context(|| format!("--replot {}", from.display()))?;
        let rows: Vec<Row> = serde_json::from_str(&text)
            .with_context(|| format!("{}: not the rows of `rouge bench translucency --json`", from.display()))?;
        return crate::write_output(path, &plot(&rows)?);
    }
    if let Some(&n) = args.samples.iter().find(|&&n| !(3..=33).contains(&n) || n % 2 == 0) {
        bail!("--samples {n}: each count must be odd, 3-33");
    }
    let mut rows = Vec::new();
    let mut fit = Fit::default();
    for (name, sidecar) in sidecars(&args.references, &args.only)? {
        let sidecar_path = args.references.join(format!("{name}.json"));
        let options: Vec<String> = serde_json::from_value(sidecar["rouge_options"].clone())
            .with_context(|| format!("{}: rouge_options must be a list of strings", sidecar_path.display()))?;
        let parsed = OptionsOnly::try_parse_from(std::iter::once("rouge".to_string()).chain(options.clone()))
            .with_context(|| format!("{}: rouge_options {options:?}", sidecar_path.display()))?;
        let exr = args.references.join(sidecar["image"].as_str().unwrap_or(&format!("{name}.exr")));
        let reference = ReferenceImage::load(&exr)?;
        let noise = sidecar["noise_rms"].as_f64().unwrap_or(f64::NAN);
        let (base, _) = parsed.scene.job()?;
        let Some(medium) = base.scene.skin.medium.clone() else {
            bail!("{}: the scene names no medium", sidecar_path.display());
        };
        eprintln!("rouge: {name} ({}×{}, reference noise {noise:.2e})", reference.width, reference.height);
        // One load and one device per scene; each configuration changes only the skin (its
        // albedo is per vertex, so the mesh is uploaded again), the kernel's sample count and,
        // for the thickness model, the local-thickness map.
        let mut job: RenderJob = base.clone();
        job.scene.specular = false;
        job.scene.background = [0.0; 3];
        job.scene.exposure = 1.0;
        let mut loaded = job.load()?;
        // The head's references were rendered before the head had its parts: draw it as they
        // have it (the skin, the mouth bag as skin, the eyes; no lashes, brows, teeth or tongue).
        loaded.mesh = as_referenced(&loaded.mesh);
        loaded.rest_mesh = loaded.rest_mesh.as_ref().map(as_referenced);
        let mut prepared = job.prepare_loaded(&loaded)?;
        // Lambert unless a row says otherwise: the thickness fits were made under it.
        let better = Skin::from_medium(&medium, Profile::BetterDipole.model()).0.lambert();
        // The combination's skin: the better dipole's kernel over the half-space law.
        let combined = better.clone().half_space();
        let sources = [true, false].map(|baked| {
            ThicknessSource::for_medium(baked, Some(&medium), args.thickness_rays, args.thickness_cutoff_mm)
        });
        let settings = match &sources[0] {
            ThicknessSource::Baked(s) => *s,
            ThicknessSource::ShadowMap { .. } => BakeSettings::default(),
        };
        let (current_map, bake) = bake_thickness_map(&loaded.mesh, &settings)?;
        let rest_map = loaded.rest_mesh.as_ref().map(|m| bake_thickness_map(m, &settings)).transpose()?;
        let upload = |prepared: &mut Prepared, map: ThicknessMap| -> Result<()> {
            let map = match map {
                ThicknessMap::None => None,
                ThicknessMap::Current => Some(&current_map),
                ThicknessMap::Rest => rest_map.as_ref().map(|(m, _)| m),
            };
            prepared.renderer.set_local_thickness(map.map(|m| (m.width, m.height, m.texels.as_slice())))?;
            Ok(())
        };
        if args.fit_thickness {
            if job.morph != 0.0 {
                eprintln!("  (deformed: measured, not fitted on)");
                continue;
            }
            // The thickness model alone, then under the kernel (`screen-space+thickness`).
            prepared.scene.sss.samples = COMBINATION_SAMPLES;
            for (skin, kernel) in [(&better, None), (&combined, better.subsurface.profile())] {
                prepared.renderer.set_mesh(&loaded.mesh, skin.albedo)?;
                prepared.scene.skin = skin.clone();
                for source in &sources {
                    let map = if matches!(source, ThicknessSource::Baked(_)) {
                        ThicknessMap::Current
                    } else {
                        ThicknessMap::None
                    };
                    upload(&mut prepared, map)?;
                    let mut scene =
                        Scene { name: &name, medium: &medium, prepared: &mut prepared, reference: &reference };
                    fit.add_scene(&mut scene, source, kernel)?;
                }
            }
            continue;
        }
        let mut configs: Vec<Config> = Vec::new();
        let plain = |model, params, skin, samples| Config {
            model,
            params,
            skin,
            samples,
            map: ThicknessMap::None,
            bounce: None,
        };
        for &law in &args.diffuse {
            let half = law == Diffuse::HalfSpace;
            let with_law = |skin: Skin| if half { skin.half_space() } else { skin.lambert() };
            let albedo = if half { "half-space" } else { "better-dipole" };
            configs.push(plain(
                "none",
                json!({"albedo": albedo}),
                with_law(Skin { subsurface: SubsurfaceModel::None, ..better.clone() }),
                0,
            ));
            for &profile in &args.profiles {
                let (skin, fit) = Skin::from_medium(&medium, profile.model());
                let skin = with_law(skin);
                for &n in &args.samples {
                    let mut params = json!({"profile": fit.model.name(), "samples": n, "fit_error": fit.fit_error});
                    if half {
                        params["diffuse"] = json!("half-space");
                    }
                    configs.push(plain("screen-space", params, skin.clone(), n));
                }
            }
        }
        if medium.name.starts_with("skin") {
            // Today's skin: the ColorChecker albedo and d'Eon's six Gaussians, 11 samples.
            configs.push(plain("screen-space", json!({"profile": "deon-skin", "samples": 11}), Skin::default(), 11));
        }
        configs.extend(thickness_configs(&medium, &sources, &better, rest_map.is_some(), bake.seconds));
        configs.extend(combination_configs(&medium, &sources, &combined, bake.seconds));
        configs.extend(slab_configs(&better, &combined));
        configs.extend(dipole_configs(&better, args.dipole_sweep));
        configs.extend(atlas_configs(&better, args.atlas_sweep));
        for Config { model, params, skin, samples, map, bounce } in configs {
            prepared.renderer.set_mesh(&loaded.mesh, skin.albedo)?;
            upload(&mut prepared, map)?;
            prepared.scene.skin = skin;
            prepared.scene.bounce = bounce;
            if samples > 0 {
                prepared.scene.sss.samples = samples;
            }
            let m = measure(&mut prepared, &reference, args.frames)?;
            eprintln!(
                "  {model:<12} {params}: gpu {} ms, rmse {:.4}, ΔE mean {:.2} p95 {:.2}, over {BIN_PX}² blocks {:.2}",
                m.gpu_ms.map_or("-".to_string(), |v| format!("{v:.2}")),
                m.error.rmse,
                m.error.delta_e_mean,
                m.error.delta_e_p95,
                m.error.delta_e_binned
            );
            rows.push(Row {
                scene: name.clone(),
                model: model.to_string(),
                params,
                gpu_ms: m.gpu_ms,
                // A pass that runs several times a frame (a face, a direction, a light) sums.
                pass_ms: m.pass_ms.iter().fold(Default::default(), |mut sums, (pass, ms)| {
                    *sums.entry(pass.clone()).or_insert(0.0) += ms;
                    sums
                }),
                wall_ms: m.wall_ms,
                rmse: m.error.rmse,
                delta_e_mean: m.error.delta_e_mean,
                delta_e_p95: m.error.delta_e_p95,
                pixels: m.error.pixels,
                delta_e_binned: Some(m.error.delta_e_binned),
                bin_px: Some(BIN_PX),
                reference: exr.display().to_string(),
                reference_noise_rms: noise,
                device: prepared.gpu.describe(),
            });
        }
    }
    if args.fit_thickness {
        let fits = fit.solve();
        for f in &fits {
            eprintln!(
                "rouge: {} {}: distortion {}, power {}, scale {:.4}, ambient {:.4}; rmse {:.5} (without the term {:.5}) over {}",
                f.medium,
                f.source,
                f.distortion,
                f.power,
                f.scale,
                f.ambient,
                f.rmse,
                f.rmse_without,
                f.scenes.join(", ")
            );
        }
        let text = serde_json::to_string_pretty(&fits)?;
        if let Some(path) = &args.json {
            crate::write_output(path, text.as_bytes())?;
        }
        return crate::emit(&text);
    }
    if let Some(path) = &args.plot {
        let png = plot(&rows)?;
        crate::write_output(path, &png)?;
    }
    let text = serde_json::to_string_pretty(&rows)?;
    if let Some(path) = &args.json {
        crate::write_output(path, text.as_bytes())?;
    }
    crate::emit(&text)
}

/// The plot label of a thickness or dipole row (drawn as squares), `None` for the others.
fn square_label(r: &Row) -> Option<String> {
    let text = |k: &str| r.params.get(k).and_then(|v| v.as_str()).unwrap_or("?").to_string();
    let number = |k: &str| r.params.get(k).and_then(|v| v.as_u64()).unwrap_or(0);
    match r.model.as_str() {
        "thickness" => Some(format!("thickness {} {}", text("source"), text("params"))),
        "screen-space+thickness" => Some(format!("kernel + thickness {} {}", text("source"), text("params"))),
        "slab" => Some(format!("slab law, {}", text("diffuse"))),
        "screen-space+slab" => Some("kernel + slab law".to_string()),
        "slab-gather" => Some(format!("transmission gather, {}", text("diffuse"))),
        "screen-space+slab-gather" => Some("kernel + transmission gather".to_string()),
        "screen-space+slab+bounce" => Some("kernel + slab law + bounce".to_string()),
        "screen-space+slab-gather+bounce" => Some("kernel + transmission gather + bounce".to_string()),
        "directional-dipole" | "directional-dipole-mfp" | "standard-dipole" => {
            Some(format!("{} N{} K{}", r.model, number("samples"), number("directions")))
        }
        "cube-atlas" => {
            let adaptive = r.params.get("adaptive").and_then(|v| v.as_bool()).unwrap_or(true);
            Some(format!(
                "atlas {}² k{} reach {}{} {} global {}",
                number("atlas_px"),
                number("kernel"),
                text("reach"),
                if adaptive { "" } else { " fixed" },
                text("occlusion"),
                text("global")
            ))
        }
        _ => None,
    }
}

/// The speed-against-error plot of `rows`: one chart per scene.
fn plot(rows: &[Row]) -> Result<Vec<u8>> {
    use crate::plot_png::{Chart, Marker, Series};
    let mut scenes: Vec<&str> = rows.iter().map(|r| r.scene.as_str()).collect();
    scenes.dedup();
    let timed = rows.iter().all(|r| r.gpu_ms.is_some());
    let x = |r: &Row| if timed { r.gpu_ms.unwrap_or(r.wall_ms) } else { r.wall_ms };
    let palette = [[31, 119, 180], [255, 127, 14], [44, 160, 44], [148, 103, 189], [23, 190, 207], [140, 86, 75]];
    // One colour per thickness, slab or dipole configuration in every chart (16 before any repeats).
    let mut thickness_labels: Vec<String> = Vec::new();
    for label in rows.iter().filter_map(square_label) {
        if !thickness_labels.contains(&label) {
            thickness_labels.push(label);
        }
    }
    let thickness_palette = [
        [140, 86, 75],
        [227, 119, 194],
        [127, 127, 127],
        [188, 189, 34],
        [23, 190, 207],
        [255, 187, 120],
        [57, 59, 121],
        [99, 121, 57],
        [214, 97, 107],
        [0, 0, 255],
        [255, 127, 14],
        [44, 160, 44],
        [148, 103, 189],
        [158, 218, 229],
        [219, 219, 141],
        [196, 156, 148],
    ];
    let charts: Vec<Chart> = scenes
        .iter()
        .map(|&scene| {
            let in_scene: Vec<&Row> = rows.iter().filter(|r| r.scene == scene).collect();
            let mut series: Vec<Series> = Vec::new();
            for r in &in_scene {
                let profile = r.params.get("profile").and_then(|p| p.as_str());
                let half = r.params.get("diffuse").and_then(|p| p.as_str()) == Some("half-space")
                    || r.params.get("albedo").and_then(|p| p.as_str()) == Some("half-space");
                let law = if half { " + half-space" } else { "" };
                let (label, marker, line) = match (r.model.as_str(), profile) {
                    ("none", _) => (format!("none{law}"), Marker::Cross, false),
                    _ if square_label(r).is_some() => (square_label(r).unwrap_or_default(), Marker::Square, false),
                    (_, Some("deon-skin")) => ("today's skin".to_string(), Marker::Diamond, false),
                    (_, Some(p)) => (format!("{p}{law}"), Marker::Dot, true),
                    (m, None) => (m.to_string(), Marker::Dot, true),
                };
                let samples = r.params.get("samples").and_then(|n| n.as_u64()).map(|n| n.to_string());
                let index = series.iter().position(|s| s.label == label).unwrap_or_else(|| {
                    let rgb = match marker {
                        Marker::Cross if half => [31, 119, 180],
                        Marker::Cross => [0, 0, 0],
                        Marker::Diamond => [214, 39, 40],
                        Marker::Square => {
                            let k = thickness_labels.iter().position(|l| *l == label).unwrap_or(0);
                            thickness_palette[k % thickness_palette.len()]
                        }
                        Marker::Dot | Marker::None => palette[series.iter().filter(|s| s.line).count() % palette.len()],
                    };
                    series.push(Series { label: label.clone(), rgb, points: Vec::new(), line, marker });
                    series.len() - 1
                });
                series[index].points.push((x(r), r.delta_e_mean, samples));
            }
            for s in series.iter_mut().filter(|s| s.line) {
                // Label only the first and last sample counts, in order of samples.
                s.points.sort_by_key(|p| p.2.as_deref().and_then(|n| n.parse::<u32>().ok()).unwrap_or(0));
                let n = s.points.len();
                for (i, p) in s.points.iter_mut().enumerate() {
                    if i != 0 && i + 1 != n {
                        p.2 = None;
                    }
                }
            }
            let noise = in_scene.first().map_or(f64::NAN, |r| r.reference_noise_rms);
            Chart {
                title: format!("{scene}  (reference noise {noise:.1e})"),
                x_label: if timed { "GPU ms per frame" } else { "wall ms per frame" }.to_string(),
                y_label: "mean ΔE2000".to_string(),
                series,
            }
        })
        .collect();
    let device = rows.first().map_or(String::new(), |r| r.device.clone());
    crate::plot_png::render(&format!("Subsurface models against Mitsuba 3: speed against error, {device}"), &charts, 4)
}

/// The default head as the committed Mitsuba references of `data/reference/translucency/` have
/// it: its tissue (the mouth bag drawn as skin, as it was) and its eyes, without the parts added
/// since (lashes, brows, teeth, tongue). Any other mesh is returned as it is.
fn as_referenced(mesh: &rouge_model::mesh::TriangleMesh) -> rouge_model::mesh::TriangleMesh {
    use rouge_model::mesh::Part;
    let mut out = mesh.without_parts();
    for g in out.groups.iter_mut().filter(|g| g.part() == Part::Mouth) {
        g.material = Some("skin".into());
    }
    out
}
