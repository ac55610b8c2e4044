//! `rouge`: the painting app (no arguments) and the Rouge command line.
//!
//! Every subcommand prints machine-readable JSON on stdout (numbers in the shortest form that
//! reads back bit-for-bit) except `import`, `demo` and `analyze`, which print a report for people
//! (`--json` for a machine). Errors: a message on stderr and exit status 2.
//!
//! Where things are: `cli/` has a module per subcommand (its options, its run, its output;
//! `cli/render/` with the render options shared by export and the translucency bench), `bench/`
//! the speed-against-error studies of `rouge bench`, and the library (`lib.rs`: `gui/` and the
//! egui-free editor core) the painting app.

mod bench;
mod cli;
mod plot_png;

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
    /// Adopt the autosave without asking (how the app starts itself again after its graphics
    /// device was lost).
    #[arg(long, hide = true)]
    recover: bool,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Import a measurement (R∞, R, Rg) into a material preset and print the inversion report.
    ///
    /// FILE may be a Rouge CSV, a CGATS / X-Rite / i1Profiler / ArgyllCMS .ti3 text file, or a
    /// CS-2000 radiance export (the format is recognised from the content). Three ArgyllCMS .sp
    /// files can be given with --r-inf, --r and --rg instead.
    Import(cli::import::ImportArgs),
    /// Import the embedded sample measurement (Foundation 02 Ivory, synthetic) and print its report.
    Demo(cli::import::DemoArgs),
    /// Kubelka-Munk calculations on single values.
    #[command(subcommand)]
    Km(cli::km::KmCommand),
    /// Colour of spectra: XYZ, CIELAB, linear and encoded sRGB as a JSON array.
    ///
    /// FILE is a CSV with a `wavelength_nm` (or `wavelength`, as colour-science writes) column and
    /// one column per sample, or transposed: one sample per row with the wavelengths in the header
    /// (reflectance as fractions or percent), on any grid covering 380-780 nm (resampled with
    /// Sprague).
    Color(cli::color::ColorArgs),
    /// Render the face with makeup: one frame to a PNG (tone-mapped) or an EXR (linear).
    ///
    /// Defaults: the embedded head, foundation + blush + lipstick, a studio light rig, 1280×720.
    /// Runs on any wgpu adapter, Mesa's lavapipe included when there is no GPU.
    Render(cli::render::RenderArgs),
    /// A cosmetic's finish (matte, satin, dewy, gloss): the gloss a meter would read of it, a
    /// named finish, or the lobe fitted to gloss readings (`--gloss 60=12`), written into the
    /// preset.
    Finish(cli::finish::FinishArgs),
    /// Export a scene for another renderer (Mitsuba 3, the ground truth for translucency).
    #[command(subcommand)]
    Export(cli::export::ExportCommand),
    /// Speed-against-error studies (figures for docs/BENCHMARKS.md).
    #[command(subcommand)]
    Bench(bench::BenchCommand),
    /// What formulators ask of S and K: coverage, shade matching over skins, mixing bases
    /// (tables for people, --json and --plot; docs/FORMULATION.md).
    #[command(subcommand)]
    Analyze(cli::analyze::AnalyzeCommand),
    /// Quality control: production batches against a standard, pass/fail in ΔE2000, CMC(l:c)
    /// or ΔE*ab, with 555 shade numbers; a batch report as JSON.
    Qc(cli::qc::QcArgs),
    /// The spectral skin model: fit measured skin spectra (melanin, blood, scattering), the
    /// forward model, and the named skin tones (docs/SKIN.md).
    #[command(subcommand)]
    Skin(cli::skin::SkinCommand),
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

/// Writes an output file (a JSON report, a plot, a map) through a temporary file beside it and a
/// rename: a failed write (a full disk, a kill) leaves the previous file whole, never a partial one.
///
/// # Errors
/// The write's error, naming `path`.
pub fn write_output(path: &std::path::Path, bytes: impl AsRef<[u8]>) -> anyhow::Result<()> {
    use anyhow::Context as _;
    rouge_measure::file_set::write_atomic(path, bytes.as_ref())
        .with_context(|| format!("cannot write {}", path.display()))
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
            recover: cli.recover,
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
        Command::Import(args) => cli::import::run(&args),
        Command::Demo(args) => cli::import::demo(&args),
        Command::Km(cmd) => cli::km::run(&cmd),
        Command::Color(args) => cli::color::run(&args),
        Command::Render(args) => cli::render::run(&args),
        Command::Finish(args) => cli::finish::run(&args),
        Command::Export(cmd) => cli::export::run(&cmd),
        Command::Bench(cmd) => bench::run(&cmd),
        Command::Analyze(cmd) => cli::analyze::run(&cmd),
        Command::Qc(args) => cli::qc::run(&args),
        Command::Skin(cmd) => cli::skin::run(&cmd),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("rouge: {e:#}");
            ExitCode::from(2)
        }
    }
}
