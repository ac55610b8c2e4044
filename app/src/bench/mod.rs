//! `rouge bench ...`: speed-against-error studies whose figures go in docs/BENCHMARKS.md. The
//! compositing and render studies are here; the others have a module each, and `report` prints
//! their tables.

pub mod aa;
pub mod atlas;
pub mod deform;
pub mod export;
pub mod fibre;
pub mod fit_thickness;
pub mod glitter;
pub mod recipe;
pub mod report;
pub mod shading;
pub mod skin;
pub mod soak;
pub mod translucency;

use anyhow::{Context, Result, bail};
use clap::{Args, Subcommand};
use rouge_measure::compositing::{ErrorStats, Method, compositing_error};
use rouge_measure::km::{self, LayerRt};
use rouge_measure::preset::Preset;
use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::time::Instant;

// clap prints these doc comments as `--help` verbatim: citations stay `[Key]` (`\[Key\]` would show).
#[allow(rustdoc::broken_intra_doc_links)]
// The export bench carries every scene option; the command is parsed once per process.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Subcommand)]
pub enum BenchCommand {
    /// Compositing cosmetic layers in linear RGB or a few bands against spectral compositing:
    /// ΔE2000 over all ordered pairs of presets, thicknesses 0-0.2 mm, both ColorChecker skins.
    Compositing(CompositingArgs),
    /// Renderer: per-pass GPU times of a 1280×720 frame (timestamp queries where the adapter has
    /// them) for the bare head, the default look (3 layers), the default look over skin maps
    /// and a 4-layer look; then the SSS sample count against a brute-force reference (RMSE,
    /// mean/p95 ΔE2000), and the error of the layer tables.
    Render(RenderBenchArgs),
    /// Translucency: every subsurface model × reference scene × parameter set against Mitsuba 3
    /// references of the same scenes (data/reference/translucency): GPU ms per frame, RMSE of
    /// linear radiance and ΔE2000 (mean, 95th percentile) of the tone-mapped images over the
    /// object's pixels; `--plot F.png` draws speed against error per scene.
    Translucency(crate::bench::translucency::TranslucencyBenchArgs),
    /// Painting: brush dab to updated frame at 1280×720 with 2048² maps (apply the dab on the
    /// CPU, upload the changed rectangle, render, wait), on the default head.
    Paint(PaintBenchArgs),
    /// Deforming the default head per frame (expression sliders, the app's animation): apply
    /// the targets, subdivide (planned topology against afresh), re-upload, render; ms per frame
    /// at subdivision levels 0, 1 and 2.
    Deform(crate::bench::deform::DeformBenchArgs),
    /// Edge antialiasing ([Sander2001] edge overdraw, unsorted and sorted, the paper's line and
    /// two-sided coverage) against supersampling on turning meshes (head, cube, wedge): RMSE and
    /// ΔE2000 near discontinuities and the crawl between frames against a k×k supersampled
    /// reference, ms per frame, the paper's table 1 edge counts; `--plot F.png`.
    Aa(crate::bench::aa::AaBenchArgs),
    /// The hair fibre model against PBRT-v4's HairBxDF averaged across the fibre
    /// (data/hair/pbrt_v4_hair.csv): relative RMS and energy per σa, CPU cost; `--plot F.png`.
    Fibre(crate::bench::fibre::FibreBenchArgs),
    /// Cube-atlas translucency ([Benmounah2009] Table 2): frames per second with and without
    /// deformation (the mesh morphed toward its bounding sphere each frame) against triangle
    /// count: the hm08 hand and head at subdivision levels 0-3 and the built-in sphere.
    CubeAtlas(crate::bench::atlas::AtlasBenchArgs),
    /// Skin under a cosmetic layer: the rendered colour of each of the ten skin tones under the
    /// five sample foundations at 0-60 µm against the 81-wavelength composition (ΔE2000 mean,
    /// p95, max per tone).
    Skin(crate::bench::skin::SkinBenchArgs),
    /// Recipe search on the sample presets: combinations fitted per second for k = 2, 3, 4 of
    /// the 13 presets, and whether the search finds a noisy synthetic mixture's recipe again.
    Recipe(crate::bench::recipe::RecipeBenchArgs),
    /// glTF export: seconds to bake the look and build the document, to write the .glb, and
    /// the file's size, per texture side (the scene options of `rouge export gltf`).
    Export(crate::bench::export::ExportBenchArgs),
    /// Glitter: Rouge's sparkle estimator against explicit flakes supersampled 16×16 (and 2×2,
    /// 4×4) on a slowly turning patch: flicker between frames and sparkles per frame, relative
    /// to the 16×16 reference, at a few pixel sizes.
    Glitter(crate::bench::glitter::GlitterBenchArgs),
    /// The same per-pixel work (an 11-tap blur, a chain of arithmetic) as a full-screen render
    /// pass and as a compute pass on this device: whether the frame's passes are slow for their
    /// work or for the device's graphics pipeline.
    Shading(crate::bench::shading::ShadingBenchArgs),
    /// A scripted hour of editing through the editor core (dabs, undo/redo, layer edits, poses,
    /// saves, autosaves): memory and ms per dab per tenth of the run, and the project reopened.
    Soak(crate::bench::soak::SoakBenchArgs),
}

#[derive(Debug, Args)]
pub struct PaintBenchArgs {
    /// Frame width.
    #[arg(long, default_value_t = 1280)]
    pub width: u32,
    /// Frame height.
    #[arg(long, default_value_t = 720)]
    pub height: u32,
    /// Dabs to time.
    #[arg(long, default_value_t = 20)]
    pub dabs: usize,
    /// Also write the result as JSON here.
    #[arg(long)]
    pub json: Option<PathBuf>,
}

#[derive(Debug, Args)]
pub struct RenderBenchArgs {
    /// Image width.
    #[arg(long, default_value_t = 1280)]
    pub width: u32,
    /// Image height.
    #[arg(long, default_value_t = 720)]
    pub height: u32,
    /// Frames averaged per configuration.
    #[arg(long, default_value_t = 10)]
    pub frames: u32,
    /// SSS sample counts to study (odd, 3-33).
    #[arg(long, value_delimiter = ',', default_values_t = [5u32, 7, 9, 11, 13, 17, 21, 25, 33])]
    pub sss_samples: Vec<u32>,
    /// Skip the SSS study (its CPU reference takes tens of seconds at 1280×720).
    #[arg(long)]
    pub no_sss_study: bool,
    /// Also write every table as JSON here.
    #[arg(long)]
    pub json: Option<PathBuf>,
}

#[derive(Debug, Args)]
pub struct CompositingArgs {
    /// Directory of material presets (*.json).
    #[arg(long, default_value = "data/presets")]
    pub presets: PathBuf,
    /// Layer thicknesses to combine, mm.
    #[arg(long, value_delimiter = ',', default_values_t = [0.0, 0.005, 0.01, 0.02, 0.05, 0.1, 0.2])]
    pub thicknesses_mm: Vec<f64>,
    /// Band counts to compare besides linear RGB.
    #[arg(long, value_delimiter = ',', default_values_t = [3usize, 4, 6, 8, 16])]
    pub bands: Vec<usize>,
    /// Also write the table as JSON here.
    #[arg(long)]
    pub json: Option<PathBuf>,
}

pub fn run(cmd: &BenchCommand) -> Result<()> {
    match cmd {
        BenchCommand::Compositing(args) => compositing(args),
        BenchCommand::Render(args) => render(args),
        BenchCommand::Paint(args) => paint(args),
        BenchCommand::Translucency(args) => crate::bench::translucency::run(args),
        BenchCommand::Deform(args) => crate::bench::deform::run(args),
        BenchCommand::Aa(args) => crate::bench::aa::run(args),
        BenchCommand::Fibre(args) => crate::bench::fibre::run(args),
        BenchCommand::CubeAtlas(args) => crate::bench::atlas::run(args),
        BenchCommand::Skin(args) => crate::bench::skin::run(args),
        BenchCommand::Recipe(args) => crate::bench::recipe::run(args),
        BenchCommand::Export(args) => crate::bench::export::run(args),
        BenchCommand::Glitter(args) => crate::bench::glitter::run(args),
        BenchCommand::Shading(args) => crate::bench::shading::run(args),
        BenchCommand::Soak(args) => crate::bench::soak::run(args),
    }
}

fn load_presets(dir: &Path) -> Result<Vec<Preset>> {
    let entries = std::fs::read_dir(dir)
        .with_context(|| format!("cannot read the preset directory {} (use --presets DIR)", dir.display()))?;
    let mut paths: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    paths.sort();
    let presets = paths.iter().map(|p| Preset::load(p)).collect::<Result<Vec<_>, _>>()?;
    if presets.len() < 2 {
        bail!("{}: {} presets; the study needs at least 2", dir.display(), presets.len());
    }
    Ok(presets)
}

/// CPU time of composing two layers over skin per pixel with `channels` channels (the layer
/// R and T looked up per channel, as a renderer would after its table fetch).
fn ns_per_pixel(channels: usize) -> f64 {
    let pixels = 200_000usize;
    let layer = |i: usize, c: usize| {
        let r = 0.05 + 0.4 * (((i * 7 + c * 13) % 97) as f64 / 97.0);
        LayerRt { r, t: 0.9 * (1.0 - r) }
    };
    let mut acc = 0.0;
    let start = Instant::now();
    for i in 0..pixels {
        for c in 0..channels {
            let s = km::stack(&[layer(i, c), layer(i + 1, c), LayerRt::opaque(0.4)]);
            acc += s.r;
        }
    }
    black_box(acc);
    start.elapsed().as_secs_f64() * 1e9 / pixels as f64
}

fn compositing(args: &CompositingArgs) -> Result<()> {
    let presets = load_presets(&args.presets)?;
    let skins = crate::cli::analyze::embedded_skins()?;
    if let Some(bad) = args.thicknesses_mm.iter().find(|x| !(**x >= 0.0 && x.is_finite())) {
        bail!("thickness {bad} mm must be finite and ≥ 0");
    }
    if let Some(bad) = args.bands.iter().find(|&&n| n == 0 || n > 81) {
        bail!("{bad} bands: use 1 to 81");
    }
    let mut methods = vec![Method::LinearRgb, Method::Basis];
    methods.extend(args.bands.iter().map(|&n| Method::Bands(n)));
    let stats = compositing_error(&presets, &skins, &args.thicknesses_mm, &methods);
    let timing: Vec<f64> = stats.iter().map(|s| ns_per_pixel(s.channels)).collect();
    let spectral_ns = ns_per_pixel(81);
    let mut out = String::new();
    out.push_str(&format!(
        "Compositing 2 layers over skin: {} presets ({} ordered pairs) x {} x {} thicknesses x {} skins = {} stacks\n",
        presets.len(),
        presets.len() * (presets.len() - 1),
        args.thicknesses_mm.len(),
        args.thicknesses_mm.len(),
        skins.len(),
        stats.first().map_or(0, |s| s.cases)
    ));
    out.push_str("| method | channels | CPU ns/pixel | mean ΔE2000 | p95 ΔE2000 | max ΔE2000 | worst case |\n");
    out.push_str("|---|---:|---:|---:|---:|---:|---|\n");
    out.push_str(&format!("| spectral (reference) | 81 | {spectral_ns:.0} | 0 | 0 | 0 | |\n"));
    for (s, ns) in stats.iter().zip(&timing) {
        out.push_str(&format!(
            "| {} | {} | {ns:.0} | {:.3} | {:.3} | {:.3} | {} |\n",
            s.method, s.channels, s.mean, s.p95, s.max, s.worst_case
        ));
    }
    crate::emit(out.trim_end())?;
    if let Some(path) = &args.json {
        let rows: Vec<serde_json::Value> = stats
            .iter()
            .zip(&timing)
            .map(|(s, ns): (&ErrorStats, &f64)| serde_json::json!({"stats": s, "cpu_ns_per_pixel": ns}))
            .collect();
        let text = serde_json::to_string_pretty(&serde_json::json!({
            "thicknesses_mm": args.thicknesses_mm,
            "spectral_cpu_ns_per_pixel": spectral_ns,
            "methods": rows,
        }))?;
        crate::write_output(path, text.as_bytes())?;
    }
    Ok(())
}

/// The 4-layer look of the frame-time table: foundation, eyeshadow, blush, lipstick.
const FOUR_LAYERS: &str = r#"{"schema": "rouge-look", "version": 1, "name": "four layers", "layers": [
  {"preset": "builtin:foundation_02_ivory", "thickness": {"uniform_mm": 0.015}},
  {"preset": "builtin:eyeshadow_01_smoky", "thickness": {"region": "eyelids", "thickness_mm": 0.006}},
  {"preset": "builtin:blush_01_petal", "thickness": {"region": "cheeks", "thickness_mm": 0.008}},
  {"preset": "builtin:lipstick_02_red", "thickness": {"region": "lips", "thickness_mm": 0.02}}]}"#;

fn render(args: &RenderBenchArgs) -> Result<()> {
    use rouge_render::job::{LookChoice, RenderJob};
    use rouge_render::study;
    let dir = tempfile_dir()?;
    let four = dir.join("four-layers.json");
    crate::write_output(&four, FOUR_LAYERS)?;
    let mut json = serde_json::Map::new();
    let mut out = String::new();
    let mut frame_rows = Vec::new();
    // The spectral skin: the default look over skin maps (every condition), whose colour is one
    // more texture sample in the G-buffer; the maps' bake is on the CPU, once per change.
    let conditions: rouge_model::skin::SkinConditions =
        "freckles=0.5,moles=0.5,redness=0.5,acne=0.5,hyperpigmentation=0.5,under_eye=0.5,veins=0.5".parse()?;
    let skin_maps = rouge_model::skin::SkinRecipe::from_tone("light-medium", conditions, 1, 1024)?;
    // The head's parts (lashes, brows, teeth, tongue) are triangles of the G-buffer and shadow passes:
    // one row draws the default look without them (the head and eyes alone) to price them. The
    // skin detail comes with the default head's wrinkles (lip furrows and nasolabial folds at
    // rest): one row leaves their map out to price them.
    #[derive(PartialEq)]
    enum LeftOut {
        Nothing,
        Parts,
        Wrinkles,
        /// Nothing left out, but every shadow map drawn every frame, as under a moving light
        /// (a still frame keeps its shadow maps: `Renderer::set_keep_shadow_maps`).
        KeptShadowMaps,
    }
    for (label, look, skin_maps, skin_detail, left_out) in [
        ("bare", LookChoice::Bare, None, false, LeftOut::Nothing),
        ("default look (3 layers)", LookChoice::Default, None, false, LeftOut::Nothing),
        ("default look, shadow map drawn every frame", LookChoice::Default, None, false, LeftOut::KeptShadowMaps),
        ("default look, no lashes, brows, teeth or tongue", LookChoice::Default, None, false, LeftOut::Parts),
        ("default look over skin maps", LookChoice::Default, Some(skin_maps.clone()), false, LeftOut::Nothing),
        (
            "default look over skin maps + skin detail, no wrinkles",
            LookChoice::Default,
            Some(skin_maps.clone()),
            true,
            LeftOut::Wrinkles,
        ),
        (
            "default look over skin maps + skin detail and wrinkles",
            LookChoice::Default,
            Some(skin_maps),
            true,
            LeftOut::Nothing,
        ),
        ("4 layers", LookChoice::File(four.clone()), None, false, LeftOut::Nothing),
    ] {
        eprintln!("rouge bench render: {label}");
        let job =
            RenderJob { look, width: args.width, height: args.height, skin_maps, skin_detail, ..RenderJob::default() };
        let loaded = job.load()?;
        let mut p = job.prepare_loaded(&loaded)?;
        if left_out == LeftOut::KeptShadowMaps {
            p.renderer.set_keep_shadow_maps(false);
        } else if left_out == LeftOut::Wrinkles {
            p.renderer.set_wrinkle_map(None)?;
        } else if left_out == LeftOut::Parts {
            use rouge_model::mesh::Part;
            let head = loaded.mesh.only(|g| matches!(g.part(), Part::Skin | Part::Mouth | Part::Eye));
            p.renderer.set_mesh(&head, loaded.scene.skin.albedo)?;
        }
        let t = study::frame_times(&mut p, args.frames)?;
        frame_rows.push((label, t));
    }
    let adapter = frame_rows.first().map(|(_, t)| t.adapter.clone()).unwrap_or_default();
    out.push_str(&format!(
        "Frame at {}×{} on {adapter}, mean of {} frames (ms)\n",
        args.width, args.height, args.frames
    ));
    let mut pass_names: Vec<String> = Vec::new();
    for (_, t) in &frame_rows {
        for (p, _) in &t.passes {
            if !pass_names.contains(p) {
                pass_names.push(p.clone());
            }
        }
    }
    out.push_str("| scene | ");
    for p in &pass_names {
        out.push_str(&format!("{p} | "));
    }
    out.push_str("GPU sum | wall (mean) | wall (min) |\n|---|");
    out.push_str(&"---:|".repeat(pass_names.len() + 3));
    out.push('\n');
    for (label, t) in &frame_rows {
        out.push_str(&format!("| {label} | "));
        for p in &pass_names {
            match t.passes.iter().find(|(n, _)| n == p) {
                Some((_, ms)) => out.push_str(&format!("{ms:.3} | ")),
                None => out.push_str("- | "),
            }
        }
        let gpu = t.gpu_frame_ms.map_or("n/a".to_string(), |v| format!("{v:.3}"));
        out.push_str(&format!("{gpu} | {:.2} | {:.2} |\n", t.wall_frame_ms, t.wall_frame_min_ms));
    }
    json.insert(
        "frames".into(),
        serde_json::to_value(
            frame_rows.iter().map(|(l, t)| serde_json::json!({"scene": l, "times": t})).collect::<Vec<_>>(),
        )?,
    );

    let presets: Vec<_> =
        rouge_model::look::builtin_preset_names().iter().filter_map(|n| rouge_model::look::builtin_preset(n)).collect();
    let table = study::table_study(&presets);
    out.push_str(&format!(
        "\nLayer tables ({} entries, X = {} mm·u/(1−u)) against exact spectral R0 and T, {} presets × {} thicknesses 0.1 µm-2 mm:\nR0 mean ΔE2000 {:.4}, max {:.4}; T max |error| {:.2e}\n",
        table.entries, table.x0_mm, presets.len(), table.thicknesses, table.mean_de_r0, table.max_de_r0, table.max_abs_t
    ));
    json.insert("tables".into(), serde_json::to_value(&table)?);

    if !args.no_sss_study {
        let job =
            RenderJob { look: LookChoice::Default, width: args.width, height: args.height, ..RenderJob::default() };
        let mut p = job.prepare()?;
        let s = study::sss_study(&mut p, &args.sss_samples, &mut |m| eprintln!("rouge bench render: SSS study: {m}"))?;
        out.push_str(&format!(
            "\nSSS samples against the brute-force reference ({}×{}, {} skin pixels, reference {:.1} s on the CPU); final image, skin pixels\n",
            s.width, s.height, s.skin_pixels, s.reference_seconds
        ));
        out.push_str("| samples/direction | SSS passes GPU ms | frame wall ms | RMSE (linear) | mean ΔE2000 | p95 ΔE2000 | max ΔE2000 |\n|---:|---:|---:|---:|---:|---:|---:|\n");
        let r = &s.no_sss;
        out.push_str(&format!(
            "| no SSS | 0 | - | {:.5} | {:.3} | {:.3} | {:.3} |\n",
            r.rmse, r.mean_de, r.p95_de, r.max_de
        ));
        for r in &s.rows {
            let g = r.sss_ms.map_or("n/a".to_string(), |v| format!("{v:.3}"));
            out.push_str(&format!(
                "| {} | {g} | {:.1} | {:.5} | {:.3} | {:.3} | {:.3} |\n",
                r.samples, r.frame_ms, r.rmse, r.mean_de, r.p95_de, r.max_de
            ));
        }
        json.insert("sss".into(), serde_json::to_value(&s)?);
    }
    crate::emit(out.trim_end())?;
    if let Some(path) = &args.json {
        let text = serde_json::to_string_pretty(&serde_json::Value::Object(json))?;
        crate::write_output(path, text.as_bytes())?;
    }
    let _ = std::fs::remove_dir_all(&dir);
    Ok(())
}

fn tempfile_dir() -> Result<PathBuf> {
    let dir = std::env::temp_dir().join(format!("rouge-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).with_context(|| format!("cannot create {}", dir.display()))?;
    Ok(dir)
}

fn paint(args: &PaintBenchArgs) -> Result<()> {
    use rouge_render::job::{LookChoice, RenderJob, load_mesh};
    let job = RenderJob { look: LookChoice::Bare, width: args.width, height: args.height, ..RenderJob::default() };
    let mut p = job.prepare()?;
    let mesh = load_mesh(None, 1.0, job.subdivision)?;
    let t = rouge_render::study::dab_to_frame(&mut p, &mesh, args.dabs)?;
    let out = format!(
        "Dab to frame at {}×{}, {}² maps, radius {} mm, {} dabs on {}\n\
         | surface map build (once) | dab (CPU) | upload | frame (render + wait) | dab → frame mean | max |\n\
         |---:|---:|---:|---:|---:|---:|\n\
         | {:.0} ms | {:.2} ms | {:.2} ms | {:.1} ms | {:.1} ms | {:.1} ms |",
        t.width,
        t.height,
        t.map_size,
        t.radius_mm,
        t.dabs,
        t.adapter,
        t.surface_build_ms,
        t.dab_cpu_ms,
        t.upload_ms,
        t.frame_ms,
        t.total_ms,
        t.total_max_ms
    );
    crate::emit(&out)?;
    if let Some(path) = &args.json {
        let text = serde_json::to_string_pretty(&t)?;
        crate::write_output(path, text.as_bytes())?;
    }
    Ok(())
}
