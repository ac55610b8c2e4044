//! `rouge bench skin`: the colour the renderer gives skin under a cosmetic layer against the
//! 81-wavelength computation. Each of the skin model's ten tones under each of the five sample
//! foundations at 0-60 µm: a flat square rendered on the GPU (white directional light of
//! irradiance π from the front, no specular, no environment, subsurface off, linear output), its
//! centre pixel against Kubelka-Munk composition done per wavelength, R = R0 + T²·Rs / (1 − R0·Rs)
//! (\[Huang2013\] eq. 3-4, the layer's R0 and T from its preset's S and K), both as CIELAB of their
//! linear sRGB (D65). The renderer composes the same formula per linear-sRGB channel with the
//! tone's colour as the skin's albedo; the difference is what compositing in three channels
//! costs (the accuracy target of the skin issue: ΔE2000 0.5 mean, 1.0 at the 95th percentile).

use crate::bench::report::{emit_with_json, markdown_table};
use anyhow::{Context, Result, bail};
use clap::Args;
use glam::Vec3;
use rouge_measure::colorimetry::{Colorimeter, Viewing, delta_e_2000_raw, linear_srgb_to_lab};
use rouge_measure::layer_table::layer_spectra;
use rouge_measure::skin::skin_tones;
use rouge_measure::spectrum::Spectrum;
use rouge_model::look::{ThicknessMap, builtin_preset, builtin_preset_names};
use rouge_model::mesh::TriangleMesh;
use rouge_render::renderer::LayerInput;
use rouge_render::{Camera, Gpu, Renderer, Scene, Skin, SubsurfaceModel};
use serde::Serialize;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct SkinBenchArgs {
    /// Layer thicknesses, µm.
    #[arg(long, value_delimiter = ',', default_values_t = [0.0f64, 5.0, 10.0, 20.0, 40.0, 60.0])]
    pub thickness_um: Vec<f64>,
    /// Also write the rows as JSON here.
    #[arg(long)]
    pub json: Option<PathBuf>,
}

/// One tone's errors over the foundations and thicknesses (or all tones: `tone` "all").
#[derive(Debug, Serialize)]
struct Row {
    tone: String,
    method: &'static str,
    samples: usize,
    delta_e_mean: f64,
    delta_e_p95: f64,
    delta_e_max: f64,
    worst: String,
    device: String,
}

fn stats(tone: &str, errors: &mut [(f64, String)], device: &str) -> Row {
    errors.sort_by(|a, b| a.0.total_cmp(&b.0));
    let n = errors.len();
    Row {
        tone: tone.into(),
        method: "linear sRGB (3 channels)",
        samples: n,
        delta_e_mean: errors.iter().map(|e| e.0).sum::<f64>() / n as f64,
        delta_e_p95: errors[(n * 95 / 100).min(n - 1)].0,
        delta_e_max: errors[n - 1].0,
        worst: errors[n - 1].1.clone(),
        device: device.into(),
    }
}

/// Per wavelength: a layer (R0, T) over skin of reflectance `skin`, composed.
fn composed(r0: &Spectrum, t: &Spectrum, skin: &Spectrum) -> Spectrum {
    let mut out = *skin;
    for (i, o) in out.0.iter_mut().enumerate() {
        let (r, t, s) = (r0.0[i], t.0[i], skin.0[i]);
        *o = r + t * t * s / (1.0 - r * s);
    }
    out
}

pub fn run(args: &SkinBenchArgs) -> Result<()> {
    if args.thickness_um.iter().any(|t| !(0.0..=1000.0).contains(t)) {
        bail!("--thickness-um: each thickness must be 0 to 1000 µm");
    }
    let colorimeter = Colorimeter::get(Viewing::D65_1931);
    let lab = |s: &Spectrum| linear_srgb_to_lab(colorimeter.srgb_linear(&colorimeter.xyz(s)));
    let gpu = Gpu::headless()?;
    let device = gpu.describe();
    let mut renderer = Renderer::new(&gpu.device, &gpu.queue);
    let mesh = TriangleMesh::flat_square(100.0);
    let mut scene = Scene::white_light(Vec3::Z);
    scene.specular = false;
    scene.environment = None;
    scene.skin.subsurface = SubsurfaceModel::None;
    let size = 8;
    // The sample foundations: the built-in presets named foundation_*.
    let foundations: Vec<&str> =
        builtin_preset_names().iter().copied().filter(|n| n.starts_with("foundation_")).collect();
    let mut rows = Vec::new();
    let mut all = Vec::new();
    for tone in skin_tones() {
        let skin = tone.params.reflectance().with_context(|| format!("tone {}", tone.name))?;
        scene.skin = Skin { subsurface: SubsurfaceModel::None, ..Skin::from_spectrum(&skin) };
        renderer.set_mesh(&mesh, scene.skin.albedo)?;
        let camera = Camera::framing(&renderer.mesh_bounds().context("no mesh bounds")?, 0.0, 0.0);
        let mut errors = Vec::new();
        for &name in &foundations {
            let preset = builtin_preset(name).with_context(|| format!("no built-in preset {name}"))?;
            for &um in &args.thickness_um {
                let map = ThicknessMap::uniform((um * 1e-3) as f32);
                renderer.set_layers(&[LayerInput { preset: &preset, map: &map, multiplier: 1.0 }])?;
                renderer.render(&scene, &camera, size, size, false)?;
                let pixels = renderer.read_linear()?;
                let centre = pixels[(size * size / 2 + size / 2) as usize];
                let rendered = linear_srgb_to_lab([0, 1, 2].map(|c| f64::from(centre[c])));
                let (r0, t) = layer_spectra(&preset.s(), &preset.k(), um * 1e-3);
                let reference = lab(&composed(&r0, &t, &skin));
                let e = delta_e_2000_raw(rendered, reference);
                errors.push((e, format!("{} {um} µm on {}", preset.name, tone.name)));
            }
        }
        all.extend(errors.iter().cloned());
        rows.push(stats(&tone.name, &mut errors, &device));
    }
    rows.push(stats("all", &mut all, &device));
    let caption = format!(
        "Skin under one foundation layer, rendered (linear sRGB compositing) against the 81-wavelength \
         composition: {} foundations × {} thicknesses per tone, {device}",
        foundations.len(),
        args.thickness_um.len()
    );
    let header = ["tone", "method", "ΔE2000 mean", "p95", "max", "worst"];
    let cells = rows.iter().map(|r| {
        vec![
            r.tone.clone(),
            r.method.into(),
            format!("{:.2}", r.delta_e_mean),
            format!("{:.2}", r.delta_e_p95),
            format!("{:.2}", r.delta_e_max),
            r.worst.clone(),
        ]
    });
    let table = markdown_table(&caption, &header, 2, cells);
    emit_with_json(&table, &rows, args.json.as_deref())
}
