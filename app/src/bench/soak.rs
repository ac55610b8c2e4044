//! `rouge bench soak`: a scripted hour of work on the editor core (no window, no GPU): at least
//! 100,000 dabs in strokes of every brush mode and size, bursts of undo and redo, layer edits
//! (add, duplicate, remove, move, rename, multiplier, hide and show, lock and unlock, another
//! active layer, a look applied now and then), pose changes (expression and face shape), the
//! subsurface model, saves every ten minutes of work and autosaves every minute (by dabs: an
//! hour is taken as 100,000 dabs, about 28 a second). It reports, per tenth of the run, the
//! resident memory (`VmRSS` of /proc/self/status), the undo history's bytes and the time per dab
//! (a stroke's time, its undo step included, over its dabs): memory must stop growing at the
//! undo budget and the dabs must not slow down. At the end the project is saved and reopened,
//! and the last autosave recovered, and both must equal the document in memory. Figures:
//! docs/BENCHMARKS.md, "Soak".

use crate::bench::report::{emit_with_json, markdown_table};
use anyhow::{Context, Result, bail};
use clap::Args;
use glam::Vec3;
use rouge_app::editor::Editor;
use rouge_model::document::{Document, MAP_SIZE, SubsurfaceChoice};
use rouge_model::look::{Look, builtin_preset};
use rouge_model::mesh::{TriangleMesh, load_mesh};
use rouge_model::paint::{BrushMode, SurfaceMap};
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

#[derive(Debug, Args)]
#[command(about = "Soak: a scripted hour of work on the editor core (100,000 dabs, undo/redo, layer edits, poses, \
             saves, autosaves): memory and time per dab per tenth of the run, and the project reopened")]
pub struct SoakBenchArgs {
    /// Dabs in the whole run (an hour of painting is taken as 100,000).
    #[arg(long, default_value_t = 100_000)]
    pub dabs: usize,
    /// The undo history's memory budget, MiB (the app's is 1024).
    #[arg(long, default_value_t = 1024)]
    pub history_budget_mib: usize,
    /// The script's random seed.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Folder for the project and the autosave (default: one in the temporary folder, removed
    /// after).
    #[arg(long)]
    pub dir: Option<PathBuf>,
    /// Also write the report as JSON here.
    #[arg(long)]
    pub json: Option<PathBuf>,
}

/// What the script does, and how much.
#[derive(Clone, Debug)]
pub struct SoakSettings {
    /// Dabs in the whole run.
    pub dabs: usize,
    /// The undo history's budget, bytes.
    pub history_budget_bytes: usize,
    /// The script's random seed.
    pub seed: u64,
    /// Dabs between autosaves (a minute of work at 100,000 dabs an hour).
    pub autosave_every_dabs: usize,
    /// Dabs between saves (ten minutes of work).
    pub save_every_dabs: usize,
}

impl SoakSettings {
    /// `dabs` dabs with the app's undo budget, a save every ten minutes and an autosave every
    /// minute of work (at 100,000 dabs an hour).
    pub fn new(dabs: usize, history_budget_bytes: usize, seed: u64) -> SoakSettings {
        SoakSettings { dabs, history_budget_bytes, seed, autosave_every_dabs: 1_667, save_every_dabs: 16_667 }
    }
}

/// One tenth of the run.
#[derive(Clone, Debug, Serialize)]
pub struct SoakSlice {
    /// The run's share done at the end of the slice, percent.
    pub percent: u32,
    /// Dabs and strokes in the slice.
    pub dabs: usize,
    pub strokes: usize,
    /// Mean time per dab over the slice's strokes, ms.
    pub dab_ms_mean: f64,
    /// 95th percentile over the slice's strokes of a stroke's time per dab, ms.
    pub dab_ms_p95: f64,
    /// Resident memory at the slice's end, MiB.
    pub rss_mib: f64,
    /// The undo history's bytes at the slice's end, MiB.
    pub history_mib: f64,
}

/// What the run did and measured.
#[derive(Clone, Debug, Serialize)]
pub struct SoakReport {
    pub slices: Vec<SoakSlice>,
    pub dabs: usize,
    pub strokes: usize,
    /// Strokes refused (a hidden or locked active layer: the script shows and unlocks at once,
    /// so these are undo steps that brought such a state back).
    pub refused_strokes: usize,
    pub undos: usize,
    pub redos: usize,
    pub layer_edits: usize,
    pub pose_changes: usize,
    pub saves: usize,
    pub autosaves: usize,
    pub save_ms_mean: f64,
    pub autosave_ms_mean: f64,
    pub history_budget_mib: f64,
    /// Resident memory before the first stroke (document, mesh, surface map), MiB.
    pub rss_start_mib: f64,
    /// The project saved at the end reopens equal to the document (layers bit for bit, name,
    /// face, mascara, subsurface model), and so does the last autosave.
    pub reopened_identical: bool,
    /// What differs where the project or the autosave did not reopen identical.
    pub reopen_difference: Option<String>,
    pub wall_s: f64,
}

/// Resident memory of this process, MiB (`VmRSS` of /proc/self/status; 0 where there is none).
pub fn rss_mib() -> f64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    status
        .lines()
        .find_map(|l| l.strip_prefix("VmRSS:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<f64>().ok())
        .map_or(0.0, |kib| kib / 1024.0)
}

/// xorshift64*, the script's dice.
struct Rng(u64);

impl Rng {
    fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    /// Uniform in [0, 1).
    fn unit(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32
    }
    /// Uniform in 0..n (n > 0).
    fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n.max(1) as u64) as usize
    }
}

/// Surface points for strokes: walks along the mesh's edges, keeping roughly straight.
struct Walker {
    positions: Vec<Vec3>,
    neighbours: Vec<Vec<u32>>,
}

impl Walker {
    fn new(mesh: &TriangleMesh) -> Walker {
        let mut neighbours = vec![Vec::new(); mesh.positions.len()];
        for t in mesh.indices.chunks_exact(3) {
            for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
                neighbours[a as usize].push(b);
                neighbours[b as usize].push(a);
            }
        }
        Walker { positions: mesh.positions.clone(), neighbours }
    }

    /// `steps` points from a random vertex, each a neighbour of the last, preferring the one
    /// that goes on the way the walk goes.
    fn stroke(&self, rng: &mut Rng, steps: usize) -> Vec<Vec3> {
        let mut at = rng.below(self.positions.len());
        let mut points = vec![self.positions[at]];
        let mut heading: Option<Vec3> = None;
        for _ in 1..steps {
            let next = &self.neighbours[at];
            if next.is_empty() {
                break;
            }
            let score = |&n: &u32| {
                let d = (self.positions[n as usize] - self.positions[at]).normalize_or_zero();
                heading.map_or(0.0, |h| d.dot(h))
            };
            let (a, b) = (next[rng.below(next.len())], next[rng.below(next.len())]);
            let n = if score(&a) >= score(&b) { a } else { b } as usize;
            heading = Some((self.positions[n] - self.positions[at]).normalize_or_zero());
            at = n;
            points.push(self.positions[at]);
        }
        points
    }
}

/// The built-in presets layers are added from.
const PRESETS: [&str; 5] =
    ["foundation_03_sand", "blush_02_coral", "eyeshadow_01_smoky", "lipstick_01_nude", "eyeshadow_03_bronze"];

/// Runs the script on `surface` (of `mesh`), saving into `dir/project` and autosaving into
/// `dir/recovery`.
///
/// # Errors
/// A save, an autosave or reopening fails.
pub fn soak(mesh: &TriangleMesh, surface: Arc<SurfaceMap>, s: &SoakSettings, dir: &Path) -> Result<SoakReport> {
    let (project, recovery) = (dir.join("project"), dir.join("recovery"));
    let mut doc = Document::default_project();
    doc.set_history_budget(s.history_budget_bytes);
    let mut e = Editor::new(doc);
    e.set_surface(Some(surface));
    let walker = Walker::new(mesh);
    let mut rng = Rng(s.seed.max(1).wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1);
    let start = Instant::now();
    let rss_start_mib = rss_mib();
    let mut r = SoakReport {
        slices: Vec::new(),
        dabs: 0,
        strokes: 0,
        refused_strokes: 0,
        undos: 0,
        redos: 0,
        layer_edits: 0,
        pose_changes: 0,
        saves: 0,
        autosaves: 0,
        save_ms_mean: 0.0,
        autosave_ms_mean: 0.0,
        history_budget_mib: s.history_budget_bytes as f64 / (1 << 20) as f64,
        rss_start_mib,
        reopened_identical: false,
        reopen_difference: None,
        wall_s: 0.0,
    };
    let (mut save_ms, mut autosave_ms) = (0.0, 0.0);
    let (mut next_save, mut next_autosave) = (s.save_every_dabs, s.autosave_every_dabs);
    // The current slice: dabs, strokes, total ms and each stroke's ms per dab.
    let (mut slice_dabs, mut slice_strokes, mut slice_ms, mut per_stroke) = (0usize, 0usize, 0.0f64, Vec::new());
    while r.dabs < s.dabs {
        // A stroke with a brush of this moment.
        let b = &mut e.brush;
        b.radius_mm = 2.0 + 10.0 * rng.unit();
        b.mode = match rng.below(10) {
            0 | 1 => BrushMode::Erase,
            2 => BrushMode::Smooth,
            _ => BrushMode::Paint,
        };
        b.thickness_mm = 0.005 + 0.03 * rng.unit();
        b.mirror = rng.below(3) == 0;
        let steps = 8 + rng.below(40);
        let points = walker.stroke(&mut rng, steps);
        let t = Instant::now();
        e.begin_stroke();
        let mut refused = false;
        for p in points {
            refused |= e.stroke_to(p).is_err();
        }
        e.end_stroke();
        let ms = t.elapsed().as_secs_f64() * 1e3;
        let dabs = e.last_stroke_dabs().len();
        if refused && dabs == 0 {
            r.refused_strokes += 1;
        }
        r.dabs += dabs;
        r.strokes += 1;
        slice_dabs += dabs;
        slice_strokes += 1;
        slice_ms += ms;
        if dabs > 0 {
            per_stroke.push(ms / dabs as f64);
        }
        script_step(&mut e, &mut rng, &mut r);
        if r.dabs >= next_autosave {
            next_autosave += s.autosave_every_dabs;
            let t = Instant::now();
            e.document_mut().autosave(&recovery).context("autosave")?;
            autosave_ms += t.elapsed().as_secs_f64() * 1e3;
            r.autosaves += 1;
        }
        if r.dabs >= next_save {
            next_save += s.save_every_dabs;
            let t = Instant::now();
            e.document_mut().save_project(&project).context("save")?;
            save_ms += t.elapsed().as_secs_f64() * 1e3;
            r.saves += 1;
        }
        let tenths = (r.dabs * 10 / s.dabs.max(1)).min(10);
        while r.slices.len() < tenths {
            per_stroke.sort_by(f64::total_cmp);
            let p95 = per_stroke.get(per_stroke.len() * 95 / 100).copied().unwrap_or(0.0);
            r.slices.push(SoakSlice {
                percent: 10 * (r.slices.len() as u32 + 1),
                dabs: slice_dabs,
                strokes: slice_strokes,
                dab_ms_mean: if slice_dabs > 0 { slice_ms / slice_dabs as f64 } else { 0.0 },
                dab_ms_p95: p95,
                rss_mib: rss_mib(),
                history_mib: e.document().history_bytes() as f64 / (1 << 20) as f64,
            });
            (slice_dabs, slice_strokes, slice_ms) = (0, 0, 0.0);
            per_stroke.clear();
        }
    }
    r.save_ms_mean = save_ms / r.saves.max(1) as f64;
    r.autosave_ms_mean = autosave_ms / r.autosaves.max(1) as f64;
    // The end of the session: the project and the autosave reopen as the document is.
    e.document_mut().autosave(&recovery).context("the last autosave")?;
    e.document_mut().save_project(&project).context("the last save")?;
    let opened = Document::open_project(&project).context("reopening the project")?;
    let recovered = Document::open_recovery(&recovery).context("recovering the autosave")?;
    r.reopen_difference = document_difference(e.document(), &opened)
        .map(|d| format!("the saved project: {d}"))
        .or_else(|| document_difference(e.document(), &recovered).map(|d| format!("the autosave: {d}")));
    r.reopened_identical = r.reopen_difference.is_none();
    r.wall_s = start.elapsed().as_secs_f64();
    Ok(r)
}

/// What `b` holds that `a` does not, in words, or `None` when `b` holds what `a` holds: the
/// layers (maps bit for bit, the first differing texel named), the name, the face, the mascara,
/// the skin and the subsurface model.
pub fn document_difference(a: &Document, b: &Document) -> Option<String> {
    if a.layers.len() != b.layers.len() {
        return Some(format!("{} layers against {}", a.layers.len(), b.layers.len()));
    }
    for (i, (x, y)) in a.layers.iter().zip(&b.layers).enumerate() {
        let what = (&x.name, &x.preset_ref, x.visible, x.locked, x.multiplier.to_bits());
        if what != (&y.name, &y.preset_ref, y.visible, y.locked, y.multiplier.to_bits()) {
            return Some(format!("layer {i} ({}): name, preset, visibility, lock or multiplier", x.name));
        }
        if x.preset != y.preset {
            return Some(format!("layer {i} ({}): the preset's contents", x.name));
        }
        if x.map.mm.len() != y.map.mm.len() {
            return Some(format!(
                "layer {i} ({}): map of {} texels against {}",
                x.name,
                x.map.mm.len(),
                y.map.mm.len()
            ));
        }
        if let Some(t) = x.map.mm.iter().zip(&y.map.mm).position(|(p, q)| p.to_bits() != q.to_bits()) {
            let count = x.map.mm.iter().zip(&y.map.mm).filter(|(p, q)| p.to_bits() != q.to_bits()).count();
            return Some(format!(
                "layer {i} ({}): {count} texels differ, the first {t}: {:?} mm against {:?} mm",
                x.name, x.map.mm[t], y.map.mm[t]
            ));
        }
    }
    let parts = [
        (a.name != b.name, "the project name"),
        (a.face != b.face, "the face (shape, pose or parts)"),
        (a.mascara != b.mascara, "the mascara"),
        (a.skin != b.skin, "the skin"),
        (a.subsurface != b.subsurface, "the subsurface model"),
    ];
    parts.iter().find(|(differs, _)| *differs).map(|(_, what)| what.to_string())
}

/// What happens between two strokes: now and then an undo burst (and redoing part of it), a
/// layer edit, a pose change, another subsurface model.
fn script_step(e: &mut Editor, rng: &mut Rng, r: &mut SoakReport) {
    if rng.below(4) == 0 {
        let k = 1 + rng.below(5);
        for _ in 0..k {
            if e.document().can_undo() {
                e.undo();
                r.undos += 1;
            }
        }
        for _ in 0..rng.below(k + 1) {
            if e.document().can_redo() {
                e.redo();
                r.redos += 1;
            }
        }
    }
    if rng.below(12) == 0 {
        layer_edit(e, rng);
        r.layer_edits += 1;
    }
    if rng.below(25) == 0 {
        let face = &mut e.document_mut().face;
        face.expression.insert("smile".into(), (rng.below(11) as f32) / 10.0);
        face.expression.insert("jawOpen".into(), (rng.below(6) as f32) / 10.0);
        face.shape.insert("age".into(), (rng.below(21) as f32) / 10.0 - 1.0);
        r.pose_changes += 1;
    }
    if rng.below(60) == 0 {
        e.document_mut().subsurface = SubsurfaceChoice::ALL[rng.below(SubsurfaceChoice::ALL.len())];
    }
}

/// One layer edit (the hide and lock edits undone at once, so the next strokes paint).
fn layer_edit(e: &mut Editor, rng: &mut Rng) {
    let n = e.document().layers.len();
    let i = rng.below(n);
    match rng.below(9) {
        0 if n < 6 => {
            let name = PRESETS[rng.below(PRESETS.len())];
            if let Some(p) = builtin_preset(name) {
                e.add_layer(&format!("builtin:{name}"), p);
            }
        }
        1 if n < 6 => {
            e.edit(|d| d.duplicate_layer(i));
        }
        0..=2 if n > 2 => {
            e.edit(|d| d.remove_layer(i));
        }
        3 => {
            let to = rng.below(n);
            e.edit(|d| d.move_layer(i, to));
        }
        4 => {
            let name = format!("layer {}", rng.below(1000));
            e.edit(|d| d.rename_layer(i, &name));
        }
        5 => {
            let m = 0.5 + 1.5 * rng.unit();
            e.edit(|d| d.set_multiplier(i, m));
        }
        6 => {
            e.edit(|d| d.set_visible(i, false));
            e.edit(|d| d.set_visible(i, true));
            e.edit(|d| d.set_locked(i, true));
            e.edit(|d| d.set_locked(i, false));
        }
        7 if rng.below(8) == 0 => {
            e.apply_look(&Look::default_look());
        }
        _ => {
            e.set_active_layer(rng.below(n));
        }
    }
}

/// `rouge bench soak`: the run on the default head (subdivision 2, as the app paints it).
pub fn run(args: &SoakBenchArgs) -> Result<()> {
    if args.dabs == 0 || args.history_budget_mib == 0 {
        bail!("--dabs and --history-budget-mib must be above 0");
    }
    let t = Instant::now();
    let mesh = load_mesh(None, 1.0, 2).context("the default head")?;
    let surface = Arc::new(SurfaceMap::build(&mesh, MAP_SIZE, MAP_SIZE));
    eprintln!("rouge bench soak: head and surface map ready in {:.1} s", t.elapsed().as_secs_f64());
    let dir =
        args.dir.clone().unwrap_or_else(|| std::env::temp_dir().join(format!("rouge-soak-{}", std::process::id())));
    let settings = SoakSettings::new(args.dabs, args.history_budget_mib << 20, args.seed);
    let r = soak(&mesh, surface, &settings, &dir);
    if args.dir.is_none() {
        let _ = std::fs::remove_dir_all(&dir);
    }
    let r = r?;
    let rows = r.slices.iter().map(|s| {
        vec![
            format!("{} %", s.percent),
            s.dabs.to_string(),
            s.strokes.to_string(),
            format!("{:.3}", s.dab_ms_mean),
            format!("{:.3}", s.dab_ms_p95),
            format!("{:.0}", s.rss_mib),
            format!("{:.0}", s.history_mib),
        ]
    });
    let caption = format!(
        "Soak: {} dabs in {} strokes ({} refused), {} undos, {} redos, {} layer edits, {} pose changes, {} saves \
         ({:.0} ms each), {} autosaves ({:.0} ms each); undo budget {:.0} MiB; RSS {:.0} MiB before the first stroke; \
         {:.0} s; reopened identical: {}",
        r.dabs,
        r.strokes,
        r.refused_strokes,
        r.undos,
        r.redos,
        r.layer_edits,
        r.pose_changes,
        r.saves,
        r.save_ms_mean,
        r.autosaves,
        r.autosave_ms_mean,
        r.history_budget_mib,
        r.rss_start_mib,
        r.wall_s,
        if r.reopened_identical { "yes" } else { "NO" },
    );
    let table = markdown_table(
        &caption,
        &["run done", "dabs", "strokes", "ms/dab (mean)", "ms/dab (p95 of strokes)", "RSS MiB", "undo history MiB"],
        1,
        rows,
    );
    emit_with_json(&table, &r, args.json.as_deref())?;
    if !r.reopened_identical {
        bail!(
            "the project reopened differs from the document in memory: {}",
            r.reopen_difference.as_deref().unwrap_or("?")
        );
    }
    Ok(())
}
