//! A project save's one commit point (docs/FORMATS.md 5.1): a process killed (SIGKILL) at any
//! moment of a save leaves a folder that opens as exactly the previous project or exactly the new
//! one; a save onto a full disk fails naming the file and leaves the previous project as it was;
//! projects saved before the commit point (`face.json`, `skin.json`) still open.
//!
//! The kill harness runs this test binary again as the child that saves (the same test, with
//! [`CHILD_ENV`] set): it saves (every other state by an autosave) the states 0, 1, 2, ... of
//! [`state`] into one folder and says `saved K` after each, until the parent kills it after a
//! random delay. The parent then opens the folder: it must be the state last said saved or the
//! one after it, whole (every layer, the presets, the face, the skin maps and edits, the
//! subsurface model, the name), and the next child saves over what the kill left.
//! `ROUGE_KILL_ROUNDS` (default 24) sets the number of kills, `ROUGE_KILL_SEED` the
//! random delays; the figures of a long run are in docs/BENCHMARKS.md.

use std::collections::BTreeSet;
use std::io::BufRead;
use std::path::Path;
use std::process::{Command, Stdio};
use std::sync::{Arc, OnceLock};
use std::time::{Duration, Instant};

#[path = "support/tmpfs.rs"]
mod tmpfs;
use tmpfs::Tmpfs;

use rouge_model::document::{Document, MAP_SIZE, PaintLayer, SubsurfaceChoice, TexelRect, UNTITLED};
use rouge_model::look::{Look, ProjectPart, ThicknessMap, ThicknessSource, builtin_preset};
use rouge_model::skin::edits::EditChannel;
use rouge_model::skin::{ProjectSkin, SkinEdits, SkinRecipe};

/// Set in the child: the project folder it saves into.
const CHILD_ENV: &str = "ROUGE_KILL_HARNESS_DIR";
/// Set in the child: the first state it saves.
const CHILD_FROM_ENV: &str = "ROUGE_KILL_HARNESS_FROM";

// ------------------------------------------------------------------------------------------
// The states a save goes through

/// Paints `value` into `rect` of layer `layer` as one stroke.
fn paint(doc: &mut Document, layer: usize, rect: TexelRect, value: f32) {
    let map = doc.begin_stroke(layer).expect("the layer exists");
    for y in rect.y0..rect.y1 {
        for x in rect.x0..rect.x1 {
            map.mm[(y * MAP_SIZE + x) as usize] = value;
        }
    }
    doc.note_dirty(rect);
    doc.end_stroke();
}

/// Two small skins (64², quick), the second with skin edits: generated once per process.
fn skins() -> &'static [Arc<ProjectSkin>; 2] {
    static SKINS: OnceLock<[Arc<ProjectSkin>; 2]> = OnceLock::new();
    SKINS.get_or_init(|| {
        let make = |conditions: &str, seed| {
            let recipe = SkinRecipe::from_tone("tan", conditions.parse().expect("conditions"), seed, 64).expect("tone");
            ProjectSkin::generate(recipe).expect("generate")
        };
        let mut edited = make("moles=0.6", 2);
        let mut planes = [vec![0.0; 64 * 64], vec![0.0; 64 * 64]];
        for (i, v) in planes[EditChannel::ALL.len() - 1].iter_mut().enumerate().take(300) {
            *v = 0.001 * (i % 13) as f32;
        }
        edited.edits = Some(Arc::new(SkinEdits::from_planes(64, 64, planes).expect("edits")));
        [Arc::new(make("freckles=0.5", 1)), Arc::new(edited)]
    })
}

/// The `k`-th state of the project: every part of it differs from the state before (the name,
/// the layers' maps and multipliers, a layer and its own preset there two states in three, the
/// face, the skin maps, their edits or none), so a folder mixing two states is told apart.
fn state(k: u64) -> Document {
    let mut doc = Document::from_look(&Look::bare());
    doc.name = format!("state {k}");
    let blush = builtin_preset("blush_01_petal").expect("built-in");
    doc.add_layer("builtin:blush_01_petal", blush);
    let at = |salt: u64| {
        let x = ((k * 37 + salt) % 2000) as u32;
        let y = ((k * 91 + salt * 7) % 2000) as u32;
        TexelRect::new(x, y, x + 16, y + 16)
    };
    paint(&mut doc, 0, at(0), 0.001 + k as f32 * 1e-6);
    doc.set_multiplier(0, 1.0 + (k % 4) as f32 * 0.25);
    if k % 3 != 2 {
        let mut custom = builtin_preset("lipstick_03_berry").expect("built-in");
        custom.name = format!("custom {}", k % 2);
        doc.add_layer("/elsewhere/custom.json", custom);
        paint(&mut doc, 1, at(5), 0.002 + k as f32 * 1e-6);
    }
    doc.face.expression.insert("smile".into(), (k % 11) as f32 / 10.0);
    doc.subsurface = SubsurfaceChoice::ALL[k as usize % SubsurfaceChoice::ALL.len()];
    doc.skin = match k % 3 {
        0 => None,
        i => Some(Arc::clone(&skins()[i as usize - 1])),
    };
    doc
}

/// Whether two layer lists are the same in everything but where a preset came from (a project
/// refers to its own copy). (Not `assert_eq!`: a failure would print 4 million texels.)
fn same_layers(a: &[PaintLayer], b: &[PaintLayer]) -> bool {
    let key =
        |l: &PaintLayer| (l.name.clone(), l.preset.clone(), Arc::clone(&l.map), l.visible, l.multiplier, l.locked);
    a.iter().map(key).eq(b.iter().map(key))
}

/// Which state the project in `dir` is, after checking that it is all of that state; an error
/// says what differs.
fn which_state(dir: &Path) -> Result<u64, String> {
    let doc = Document::open_project(dir).map_err(|e| format!("does not open: {e}"))?;
    let k: u64 =
        doc.name.strip_prefix("state ").and_then(|k| k.parse().ok()).ok_or_else(|| format!("named {:?}", doc.name))?;
    let want = state(k);
    if !same_layers(&doc.layers, &want.layers) {
        return Err(format!("state {k}'s name with other layers"));
    }
    if doc.face != want.face {
        return Err(format!("state {k}'s name with the face {:?}", doc.face));
    }
    if doc.skin != want.skin {
        return Err(format!("state {k}'s name with other skin maps"));
    }
    if doc.subsurface != want.subsurface {
        return Err(format!("state {k}'s name with the subsurface model {:?}", doc.subsurface));
    }
    Ok(k)
}

// ------------------------------------------------------------------------------------------
// What is in a project folder

/// Every file under `dir`, relative to it.
fn all_files(dir: &Path) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    for sub in ["", "maps", "presets"] {
        let Ok(entries) = std::fs::read_dir(dir.join(sub)) else { continue };
        for e in entries.flatten() {
            if e.path().is_file() {
                out.insert(Path::new(sub).join(e.file_name()).to_string_lossy().into_owned());
            }
        }
    }
    out
}

/// The files the project in `dir` refers to, `look.json` included.
fn referenced_files(dir: &Path) -> BTreeSet<String> {
    let look_path = dir.join("look.json");
    let text = std::fs::read_to_string(&look_path).expect("look.json");
    let (look, part) = Look::from_project_json(&text, &look_path).expect("look.json loads");
    // A project saved before the project part: face.json and skin.json.
    let part = part.unwrap_or_else(|| ProjectPart {
        face: "face.json".into(),
        skin: dir.join("skin.json").is_file().then(|| "skin.json".into()),
        ..ProjectPart::default()
    });
    let mut out = BTreeSet::from(["look.json".to_string(), part.face.clone()]);
    for l in &look.layers {
        if let ThicknessSource::Map { path, .. } = &l.thickness {
            out.insert(path.to_string_lossy().into_owned());
        }
        if !l.preset_ref.starts_with("builtin:") {
            out.insert(l.preset_ref.clone());
        }
    }
    if let Some(skin) = &part.skin {
        out.insert(skin.clone());
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join(skin)).expect("skin file")).expect("JSON");
        for key in ["maps", "edits"] {
            if let Some(p) = json.get(key).and_then(|v| v.as_str()) {
                out.insert(p.to_string());
            }
        }
    }
    out
}

/// Files in `dir` that its project does not refer to.
fn leftovers(dir: &Path) -> BTreeSet<String> {
    let referenced = referenced_files(dir);
    all_files(dir).into_iter().filter(|f| !referenced.contains(f)).collect()
}

// ------------------------------------------------------------------------------------------
// Kills

/// xorshift64*: the kill delays, reproducible from the seed printed.
struct Rng(u64);

impl Rng {
    fn next_f64(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn env_u64(name: &str) -> Option<u64> {
    std::env::var(name).ok().and_then(|v| v.parse().ok())
}

/// The child: saves states `from`, `from + 1`, ... into `dir` until killed, odd states by an
/// autosave (the same writer, as the app's recovery folder gets it).
fn save_until_killed(dir: &Path, from: u64) -> ! {
    let _ = skins();
    // The parent times its kill from here: the start-up (a process, two skins) takes from a
    // few milliseconds to over a second, as loaded as the machine is.
    println!("ready");
    for k in from.. {
        let mut doc = state(k);
        match k % 2 {
            0 => doc.save_project(dir).expect("save"),
            _ => doc.autosave(dir).expect("autosave"),
        }
        println!("saved {k}");
    }
    unreachable!("the states do not run out")
}

/// One kill: a child saving from state `committed + 1` on, killed after `delay`. Returns the
/// last state it said it saved (`committed` if none).
fn kill_one_child(dir: &Path, committed: u64, delay: Duration) -> u64 {
    let exe = std::env::current_exe().expect("the test binary");
    // The test's name as libtest knows it: its module path without the crate (tests/all.rs makes
    // this file a module of the crate's one test executable).
    let module = module_path!().split_once("::").map_or("", |(_, m)| m);
    let name = format!("{module}::sigkill_at_any_moment_of_a_save_leaves_the_old_or_the_new_project");
    let mut child = Command::new(exe)
        .args([name.as_str(), "--exact", "--nocapture"])
        .env(CHILD_ENV, dir)
        .env(CHILD_FROM_ENV, (committed + 1).to_string())
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("spawn the child");
    let stdout = child.stdout.take().expect("piped");
    let (ready_tx, ready) = std::sync::mpsc::channel();
    let reader = std::thread::spawn(move || {
        std::io::BufReader::new(stdout)
            .lines()
            .map_while(Result::ok)
            .inspect(|l| {
                if l == "ready" {
                    let _ = ready_tx.send(());
                }
            })
            .filter_map(|l| l.strip_prefix("saved ").and_then(|k| k.parse::<u64>().ok()))
            .last()
    });
    ready.recv_timeout(Duration::from_secs(120)).expect("the child starts saving");
    std::thread::sleep(delay);
    // Child::kill is SIGKILL on Unix: no destructor, no flush, nothing of the save finishes.
    child.kill().expect("kill");
    let status = child.wait().expect("wait");
    assert!(!status.success(), "the child ended by itself: {status}");
    reader.join().expect("the reader").unwrap_or(committed)
}

#[test]
fn sigkill_at_any_moment_of_a_save_leaves_the_old_or_the_new_project() {
    if let Some(dir) = std::env::var_os(CHILD_ENV) {
        save_until_killed(Path::new(&dir), env_u64(CHILD_FROM_ENV).unwrap_or(1));
    }
    let rounds = env_u64("ROUGE_KILL_ROUNDS").unwrap_or(24);
    let seed = env_u64("ROUGE_KILL_SEED").unwrap_or_else(|| {
        std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(1, |d| d.as_nanos() as u64) | 1
    });
    eprintln!("kill harness: {rounds} kills, ROUGE_KILL_SEED={seed}");
    let mut rng = Rng(seed);
    let tmp = tempfile::tempdir().expect("temp dir");
    let dir = tmp.path().join("project");
    // The time one save takes here, to spread the kills over whole saves.
    let t = Instant::now();
    state(0).save_project(&dir).expect("state 0");
    state(1).save_project(&dir).expect("state 1");
    let save = t.elapsed() / 2;
    let mut committed = 1;
    let (mut old, mut new, mut mid_save) = (0, 0, 0);
    for round in 0..rounds {
        // The child says when it starts saving, then saves every `save`: a delay of up to two
        // saves from then lands anywhere in a save. (Timed from the spawn, with a guess at the
        // start-up, every kill landed before the first save on a loaded machine.)
        let delay = save.mul_f64(2.0 * rng.next_f64());
        let said = kill_one_child(&dir, committed, delay);
        let found = which_state(&dir).unwrap_or_else(|e| panic!("kill {round} after {delay:?}: the project {e}"));
        assert!(
            found == said || found == said + 1,
            "kill {round} after {delay:?}: the folder holds state {found}, the child had saved {said}"
        );
        if found == said {
            old += 1
        } else {
            new += 1
        }
        if !leftovers(&dir).is_empty() {
            mid_save += 1;
        }
        committed = found;
    }
    eprintln!(
        "kill harness: {rounds} kills (one save {save:?}): {old} opened as the state last said saved, {new} as the \
         one after it (killed between the commit and `saved`); {mid_save} left files of an unfinished save"
    );
    assert!(mid_save > 0 || rounds < 20, "no kill landed inside a save: the harness tests nothing");
    // The next save removes what the kills left: only what the project refers to remains.
    state(committed + 1).save_project(&dir).expect("a save after the kills");
    assert_eq!(which_state(&dir), Ok(committed + 1));
    assert_eq!(leftovers(&dir), BTreeSet::new(), "files left by killed saves");
}

// ------------------------------------------------------------------------------------------
// Full disks

/// A layer of values that do not compress (a few MB of EXR).
fn noisy_layer(doc: &mut Document, side: u32) {
    doc.add_layer("builtin:lipstick_02_red", builtin_preset("lipstick_02_red").expect("built-in"));
    let layer = doc.layers.len() - 1;
    let map = doc.begin_stroke(layer).expect("layer");
    let mut h = 0x9E37_79B9u32;
    for y in 0..side {
        for x in 0..side {
            h = h.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            map.mm[(y * MAP_SIZE + x) as usize] = (h >> 8) as f32 * 1e-9;
        }
    }
    doc.note_dirty(TexelRect::new(0, 0, side, side));
    doc.end_stroke();
}

#[test]
fn a_save_onto_a_full_disk_fails_naming_the_file_and_keeps_the_previous_project() {
    let tmp = tempfile::tempdir().expect("temp dir");
    let mount = tmp.path().join("small disk");
    let _disk = match Tmpfs::mount(&mount, "6m") {
        Ok(d) => d,
        Err(e) => {
            eprintln!("SKIPPED: the full-disk test needs to mount a tmpfs (root): {e}");
            return;
        }
    };
    let dir = mount.join("project");
    let mut doc = state(4);
    doc.save_project(&dir).expect("the first save fits");
    let before = all_files(&dir);
    // Two layers of 1024² values that do not compress: 4 MB each, more than the disk holds.
    noisy_layer(&mut doc, 1024);
    noisy_layer(&mut doc, 1024);
    let e = doc.save_project(&dir).expect_err("the disk is full").to_string();
    assert!(e.contains("No space left on device"), "{e}");
    let named = before.iter().all(|f| !e.contains(f.as_str())) && e.contains(&dir.join("maps").display().to_string());
    assert!(named, "the error names the new map's file: {e}");
    assert!(doc.is_modified(), "a failed save leaves the work unsaved");
    assert_eq!(which_state(&dir), Ok(4), "the previous project opens as it was");
    assert_eq!(all_files(&dir), before, "the failed save's files are deleted (and the space with them)");
    // With the space back, the same document saves.
    doc.remove_layer(3);
    doc.save_project(&dir).expect("one noisy layer fits");
    assert!(same_layers(&Document::open_project(&dir).expect("open").layers, &doc.layers));
    // Exports onto the full disk fail naming their file too.
    let e = doc.export_maps(&mount.join("export")).expect_err("no room for the exports").to_string();
    assert!(e.contains("No space left on device") && e.contains(&mount.join("export").display().to_string()), "{e}");
}

#[test]
fn a_failed_save_deletes_the_files_it_wrote() {
    let tmp = tempfile::tempdir().expect("temp dir");
    let dir = tmp.path().join("project");
    let mut doc = state(3);
    doc.save_project(&dir).expect("save");
    let before = all_files(&dir);
    // The next state's face file cannot be written (a folder has its name): its maps are
    // written first, and deleted again when the save fails.
    let mut next = state(4);
    let probe = tmp.path().join("probe");
    next.save_project(&probe).expect("where the face goes");
    let face = referenced_files(&probe).into_iter().find(|f| f.starts_with("face-")).expect("a face file");
    std::fs::create_dir_all(dir.join(&face)).expect("block the face file");
    let e = next.save_project(&dir).expect_err("the face file is a folder").to_string();
    assert!(e.contains(&face), "{e}");
    std::fs::remove_dir(dir.join(&face)).expect("unblock");
    assert_eq!(all_files(&dir), before, "the maps of the failed save are deleted");
    assert_eq!(which_state(&dir), Ok(3));
}

// ------------------------------------------------------------------------------------------
// Projects saved before the commit point

/// A project as the code before the commit point wrote it (`tests/data/
/// project_before_commit_point/`, written by that code): `look.json` without a project part,
/// `face.json`, `skin.json`, a preset and the skin maps' EXR; the two thickness maps are made
/// again here by the unchanged EXR writer.
fn project_before_commit_point(dir: &Path) -> [ThicknessMap; 2] {
    let fixture = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/project_before_commit_point");
    for f in all_files(&fixture) {
        std::fs::create_dir_all(dir.join(&f).parent().expect("a folder")).expect("folders");
        std::fs::copy(fixture.join(&f), dir.join(&f)).expect("copy the fixture");
    }
    let maps = [0u32, 1].map(|layer| {
        let mut map = ThicknessMap { width: MAP_SIZE, height: MAP_SIZE, mm: vec![0.0; (MAP_SIZE * MAP_SIZE) as usize] };
        for y in 1000..1016u32 {
            for x in 800..816u32 {
                map.mm[(y * MAP_SIZE + x) as usize] = 0.001 * (1 + (x + y + layer) % 7) as f32;
            }
        }
        map
    });
    maps[0].save_exr(&dir.join("maps/00-blush-01-petal-pink-9bff78d485696875.exr")).expect("map 0");
    maps[1].save_exr(&dir.join("maps/01-my-berry-133b565a2d6dd3fc.exr")).expect("map 1");
    maps
}

#[test]
fn a_project_saved_before_the_commit_point_opens_and_saves_in_the_new_form() {
    let tmp = tempfile::tempdir().expect("temp dir");
    let dir = tmp.path().join("old");
    let maps = project_before_commit_point(&dir);
    let doc = Document::open_project(&dir).expect("an old project opens");
    assert_eq!(doc.name, "Saved before the commit point");
    assert_eq!((doc.layers.len(), doc.layers[1].multiplier, doc.layers[1].preset.name.as_str()), (2, 1.5, "My berry"));
    assert!(*doc.layers[0].map == maps[0] && *doc.layers[1].map == maps[1], "the maps come back bit for bit");
    assert_eq!((doc.face.expression.get("smile"), doc.face.shape.get("age")), (Some(&0.4), Some(&0.3)));
    let skin = doc.skin.as_ref().expect("the skin maps of skin.json");
    assert_eq!((skin.recipe.seed, skin.recipe.size_px, skin.maps.width()), (3, 128, 128));
    assert!(!doc.is_modified());

    // Saved again, it takes the new form: face.json and skin.json give way to the files
    // look.json names, and it opens as the same project.
    let mut doc = doc;
    doc.save_project(&dir).expect("save");
    let files = all_files(&dir);
    assert!(!files.contains("face.json") && !files.contains("skin.json"), "{files:?}");
    assert_eq!(leftovers(&dir), BTreeSet::new());
    let again = Document::open_project(&dir).expect("reopen");
    assert!(same_layers(&again.layers, &doc.layers));
    assert!(again.name == doc.name && again.face == doc.face && again.skin == doc.skin);
}

#[test]
fn a_project_part_naming_a_file_outside_the_folder_is_refused() {
    let tmp = tempfile::tempdir().expect("temp dir");
    let dir = tmp.path().join("p");
    state(1).save_project(&dir).expect("save");
    let look_path = dir.join("look.json");
    let text = std::fs::read_to_string(&look_path).expect("read");
    let face = referenced_files(&dir).into_iter().find(|f| f.starts_with("face-")).expect("face");
    std::fs::write(&look_path, text.replace(&face, "../face.json")).expect("write");
    let e = Document::open_project(&dir).expect_err("outside the folder").to_string();
    assert!(e.contains("look.json") && e.contains("`project.face`") && e.contains("../face.json"), "{e}");
    std::fs::write(&look_path, text.replace("\"face\":", "\"fase\":")).expect("write");
    let e = Document::open_project(&dir).expect_err("unknown field").to_string();
    assert!(e.contains("look.json") && e.contains("fase"), "{e}");
}

#[test]
fn the_subsurface_model_and_the_name_are_saved_with_the_project() {
    let tmp = tempfile::tempdir().expect("temp dir");
    let dir = tmp.path().join("p");
    let mut doc = Document::default_project();
    assert_eq!(
        (doc.name.as_str(), doc.subsurface, doc.is_modified()),
        (UNTITLED, SubsurfaceChoice::ScreenSpace, false)
    );
    doc.subsurface = SubsurfaceChoice::DirectionalDipole;
    assert!(doc.is_modified(), "another subsurface model is unsaved work");
    doc.save_project(&dir).expect("save");
    assert!(!doc.is_modified());
    doc.name = "Evening for Ana".into();
    assert!(doc.is_modified(), "another name is unsaved work");
    doc.save_project(&dir).expect("save");
    let opened = Document::open_project(&dir).expect("open");
    assert_eq!((opened.name.as_str(), opened.subsurface), ("Evening for Ana", SubsurfaceChoice::DirectionalDipole));
    assert!(!opened.is_modified());
    // Every model has its name in the file.
    for choice in SubsurfaceChoice::ALL {
        doc.subsurface = choice;
        doc.save_project(&dir).expect("save");
        let text = std::fs::read_to_string(dir.join("look.json")).expect("look.json");
        assert!(text.contains(&format!("\"subsurface\": \"{}\"", choice.name())), "{text}");
        assert_eq!(Document::open_project(&dir).expect("open").subsurface, choice);
    }
    // An unknown one is an error naming the file and the models there are.
    let text = std::fs::read_to_string(dir.join("look.json")).expect("look.json");
    std::fs::write(dir.join("look.json"), text.replace("\"none\"", "\"jensen\"")).expect("write");
    let e = Document::open_project(&dir).expect_err("an unknown model").to_string();
    assert!(e.contains("look.json") && e.contains("jensen") && e.contains("cube-atlas"), "{e}");
    // A project saved before either opens with the default model and its look's name.
    let old = tmp.path().join("old");
    project_before_commit_point(&old);
    let doc = Document::open_project(&old).expect("open");
    assert_eq!((doc.name.as_str(), doc.subsurface), ("Saved before the commit point", SubsurfaceChoice::ScreenSpace));
}
