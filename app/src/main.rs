//! `rouge`: the painting app (no arguments) and the Rouge command line.
//!
//! Every subcommand prints machine-readable JSON on stdout (numbers in the shortest form that
//! reads back bit-for-bit) except `import`, `demo` and `analyze`, which print a report for people
//! (`--json` for a machine). Errors: a message on stderr and exit status 2.

mod analyze_plot;
mod atlas_args;
mod bench_aa;
mod bench_atlas;
mod bench_deform;
mod bench_translucency;
mod cmd_analyze;
mod cmd_bench;
mod cmd_color;
mod cmd_export;
mod cmd_import;
mod cmd_km;
mod cmd_render;
mod cmd_skin;
mod dipole_args;
mod fit_thickness;
mod plot_png;
mod scene_args;
mod thickness_args;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

/// Rouge: cosmetic measurement and makeup preview.
///
/// Without arguments, opens the painting app: paint foundation, blush, eyeshadow and lipstick
/// on a 3D face and see it rendered live. With a subcommand: import spectroradiometer
/// measurements of cosmetics, invert them into Kubelka-Munk scattering S and absorption K,
/// check them in colour terms, build material presets, render frames and run benchmarks.
#[derive(Debug, Parser)]
#[command(name = "rouge", version, propagate_version = true)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    /// Project folder to open in the app (look.json + maps/).
    #[arg(long)]
    project: Option<std::path::PathBuf>,
    /// Mesh to paint in the app instead of the default head (.obj, .gltf, .glb).
    #[arg(long)]
    mesh: Option<std::path::PathBuf>,
    /// Millimetres per unit of --mesh (25 fits the LeePerrySmith scan).
    #[arg(long, default_value_t = 1.0)]
    mesh_scale: f32,
    /// Open the app, wait until the face is drawn, save a screenshot of the window to this PNG
    /// and quit (checks a real window, e.g. under Xvfb).
    #[arg(long)]
    window_screenshot: Option<std::path::PathBuf>,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Import a measurement (R∞, R, Rg) into a material preset and print the inversion report.
    ///
    /// FILE may be a Rouge CSV, a CGATS / X-Rite / i1Profiler / ArgyllCMS .ti3 text file, or a
    /// CS-2000 radiance export (the format is recognised from the content). Three ArgyllCMS .sp
    /// files can be given with --r-inf, --r and --rg instead.
    Import(cmd_import::ImportArgs),
    /// Import the embedded sample measurement (Foundation 02 Ivory, synthetic) and print its report.
    Demo(cmd_import::DemoArgs),
    /// Kubelka-Munk calculations on single values.
    #[command(subcommand)]
    Km(cmd_km::KmCommand),
    /// Colour of spectra: XYZ, CIELAB, linear and encoded sRGB as a JSON array.
    ///
    /// FILE is a CSV with a `wavelength_nm` (or `wavelength`, as colour-science writes) column and
    /// one column per sample, or transposed: one sample per row with the wavelengths in the header
    /// (reflectance as fractions or percent), on any grid covering 380-780 nm (resampled with
    /// Sprague).
    Color(cmd_color::ColorArgs),
    /// Render the face with makeup: one frame to a PNG (tone-mapped) or an EXR (linear).
    ///
    /// Defaults: the embedded head, foundation + blush + lipstick, a studio light rig, 1280×720.
    /// Runs on any wgpu adapter, Mesa's lavapipe included when there is no GPU.
    Render(cmd_render::RenderArgs),
    /// Export a scene for another renderer (Mitsuba 3, the ground truth for translucency).
    #[command(subcommand)]
    Export(cmd_export::ExportCommand),
    /// Speed-against-error studies (figures for docs/BENCHMARKS.md).
    #[command(subcommand)]
    Bench(cmd_bench::BenchCommand),
    /// What formulators ask of S and K: coverage, shade matching over skins, mixing bases
    /// (tables for people, --json and --plot; docs/FORMULATION.md).
    #[command(subcommand)]
    Analyze(cmd_analyze::AnalyzeCommand),
    /// The spectral skin model: fit measured skin spectra (melanin, blood, scattering), the
    /// forward model, and the named skin tones (docs/SKIN.md).
    #[command(subcommand)]
    Skin(cmd_skin::SkinCommand),
}

/// Writes `text` and a newline to stdout. A closed pipe (`rouge ... | head`) ends the program
/// quietly instead of panicking as `println!` would.
pub fn emit(text: &str) -> anyhow::Result<()> {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    match writeln!(out, "{text}").and_then(|()| out.flush()) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => std::process::exit(0),
        Err(e) => Err(anyhow::anyhow!("cannot write to stdout: {e}")),
    }
}

fn main() -> ExitCode {
    // RUST_LOG=info shows the adapter and wgpu's warnings. By default only errors, and none from
    // wgpu-hal, whose loader messages (a Vulkan loader without drivers, say) would bury the one
    // line that says what to install; wgpu's own errors reach the user as rouge's messages.
    env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("error,wgpu_hal=off")).init();
    let cli = Cli::parse();
    let Some(command) = cli.command else {
        let options = rouge_app::gui::Options {
            data_dir: rouge_app::gui::Options::default_data_dir(),
            project: cli.project,
            autosave: true,
            mesh: cli.mesh.map(|m| (m, cli.mesh_scale)),
            window_screenshot: cli.window_screenshot,
        };
        return match rouge_app::gui::run(options) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("rouge: {e:#}");
                ExitCode::from(2)
            }
        };
    };
    let result = match command {
        Command::Import(args) => cmd_import::run(&args),
        Command::Demo(args) => cmd_import::demo(&args),
        Command::Km(cmd) => cmd_km::run(&cmd),
        Command::Color(args) => cmd_color::run(&args),
        Command::Render(args) => cmd_render::run(&args),
        Command::Export(cmd) => cmd_export::run(&cmd),
        Command::Bench(cmd) => cmd_bench::run(&cmd),
        Command::Analyze(cmd) => cmd_analyze::run(&cmd),
        Command::Skin(cmd) => cmd_skin::run(&cmd),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("rouge: {e:#}");
            ExitCode::from(2)
        }
    }
}
