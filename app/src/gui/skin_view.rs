//! The document's skin maps on screen: their colour baked into the renderer's albedo texture
//! (`rouge_render::job::bake_skin_albedo`, the bake `rouge render --skin-maps` uses, through the
//! tone's `SkinColorTable`), the skin edits on top, and the blood following the face's
//! expression (`SkinMaps::with_blood_flow`) while the Animate cycle plays or a pose is held.
//!
//! Work is kept off the frame: generating maps (a new tone, conditions, seed or size) and every
//! full bake run on worker threads, one at a time, the latest wish winning (a pose that moved
//! during a bake is baked again when it is back, so during the Animate cycle the blood is as
//! fresh as the bake rate allows). A skin brush dab re-bakes only the rectangle it changed, on
//! the UI thread, when the blood is still (else a full bake follows it on the worker).

use super::*;
use rouge_measure::skin::{SkinColorTable, SkinParams};
use rouge_model::mesh::targets::Weights;
use rouge_model::skin::blood_flow::blood_factors;
use rouge_model::skin::{AnatomyRegion, ProjectSkin, SkinMaps, SkinRecipe};
use rouge_render::job::{bake_skin_albedo, skin_color_table};

/// The colour table of one base (a tone's scattering), shared with the workers.
type Table = (SkinParams, Arc<SkinColorTable>);

/// A finished full bake.
struct Baked {
    /// The skin it was baked from.
    skin: Arc<ProjectSkin>,
    table: Table,
    /// The generated maps with the edits on top (before the blood flow).
    edited: SkinMaps,
    /// The blood factors it was baked with.
    factors: Vec<(AnatomyRegion, f64)>,
    image: image::RgbaImage,
    /// Time of the blood flow and the bake (not the table), ms.
    bake_ms: f64,
    /// Time building the colour table, ms (0 when it was cached).
    table_ms: f64,
}

/// What the viewport shows of the skin (holding no `Arc` of the document's skin, which would
/// make the next skin stroke copy the maps).
struct Shown {
    recipe: SkinRecipe,
    edited: SkinMaps,
    factors: Vec<(AnatomyRegion, f64)>,
    image: Arc<image::RgbaImage>,
}

/// The skin maps' state in the viewport ([`RougeApp::poll_skin`]).
pub(super) struct SkinView {
    /// Whether the blood follows the expression (the Skin panel's switch; on by default).
    pub(super) blood_follows: bool,
    /// The Face Unit weights of the pose shown.
    units: Weights,
    table: Option<Table>,
    shown: Option<Shown>,
    bake: Option<mpsc::Receiver<Result<Baked, String>>>,
    /// The skin or pose changed while a bake ran: bake again when it is back.
    stale: bool,
    /// Maps being generated for the Skin panel, and what for.
    pub(super) generating: Option<(String, mpsc::Receiver<Result<ProjectSkin, String>>)>,
    /// The last full bake: texels a side, blood flow + bake time, table time, ms.
    pub(super) last_bake: Option<(u32, f64, f64)>,
    /// The last rectangle re-bake after a dab: texels, ms.
    pub(super) last_rect_bake: Option<(usize, f64)>,
}

impl Default for SkinView {
    fn default() -> Self {
        SkinView {
            blood_follows: true,
            units: Weights::new(),
            table: None,
            shown: None,
            bake: None,
            stale: false,
            generating: None,
            last_bake: None,
            last_rect_bake: None,
        }
    }
}

impl std::fmt::Debug for SkinView {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SkinView")
            .field("blood_follows", &self.blood_follows)
            .field("shown", &self.shown.is_some())
            .field("baking", &self.bake.is_some())
            .field("generating", &self.generating.is_some())
            .finish_non_exhaustive()
    }
}

impl SkinView {
    /// The blood factors the viewport should show now.
    fn factors(&self) -> Vec<(AnatomyRegion, f64)> {
        if self.blood_follows { blood_factors(&self.units) } else { Vec::new() }
    }

    /// Whether a full bake is running.
    pub(super) fn bake_running(&self) -> bool {
        self.bake.is_some()
    }

    /// Whether maps are being generated or baked.
    pub(super) fn busy(&self) -> bool {
        self.generating.is_some() || self.bake.is_some() || self.stale
    }
}

/// The last full bake of the skin maps' colour.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FullBake {
    /// The maps' size, texels a side.
    pub size_px: u32,
    /// Skin edits, blood flow and bake, ms.
    pub bake_ms: f64,
    /// Building the tone's colour table (0 when it was cached), ms.
    pub table_ms: f64,
}

/// How long the last skin bakes took ([`RougeApp::skin_bake_times`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkinBakeTimes {
    /// The last full bake.
    pub full: Option<FullBake>,
    /// The last rectangle re-baked after a skin dab: texels, ms.
    pub rect: Option<(usize, f64)>,
}

/// The skin's bake: the one function the app calls (`bake_skin_albedo`, shared with the CLI).
fn bake(maps: &SkinMaps, table: &SkinColorTable) -> image::RgbaImage {
    bake_skin_albedo(maps, table)
}

/// A full bake on the calling thread (a worker's): the table (cached or built), the edits, the
/// blood flow, the bake.
fn bake_full(skin: Arc<ProjectSkin>, units: Weights, follows: bool, cached: Option<Table>) -> Result<Baked, String> {
    let base = *skin.maps.base();
    let start = Instant::now();
    let table = match cached.filter(|(b, _)| *b == base) {
        Some(t) => t,
        None => (base, Arc::new(skin_color_table(&base).map_err(|e| e.to_string())?)),
    };
    let table_ms = start.elapsed().as_secs_f64() * 1e3;
    let start = Instant::now();
    let edited = skin.edited_maps();
    let factors = if follows { blood_factors(&units) } else { Vec::new() };
    let image =
        if factors.is_empty() { bake(&edited, &table.1) } else { bake(&edited.with_blood_flow(&units), &table.1) };
    let bake_ms = start.elapsed().as_secs_f64() * 1e3;
    Ok(Baked { skin, table, edited, factors, image, bake_ms, table_ms })
}

impl RougeApp {
    /// How long the last skin bakes took (tests print them).
    pub fn skin_bake_times(&self) -> SkinBakeTimes {
        SkinBakeTimes {
            full: self.skin.last_bake.map(|(size_px, bake_ms, table_ms)| FullBake { size_px, bake_ms, table_ms }),
            rect: self.skin.last_rect_bake,
        }
    }

    /// Whether the blood follows the expression.
    pub fn blood_follows(&self) -> bool {
        self.skin.blood_follows
    }

    /// Turns the blood following the expression on or off (the Skin panel's switch).
    pub fn set_blood_follows(&mut self, on: bool) {
        if self.skin.blood_follows != on {
            self.skin.blood_follows = on;
            self.request_skin_bake();
        }
    }

    /// Blocks until the skin maps being generated and baked are shown (tests).
    pub fn wait_skin(&mut self) {
        while self.skin.busy() {
            if !self.poll_skin() {
                std::thread::sleep(Duration::from_millis(10));
            }
        }
    }

    /// The pose shown changed: the blood follows it (a new bake when its factors changed).
    pub(super) fn skin_pose(&mut self, units: Weights) {
        self.skin.units = units;
        let wanted = self.skin.factors();
        if self.skin.shown.as_ref().is_some_and(|s| s.factors != wanted) {
            self.request_skin_bake();
        }
    }

    /// Bakes the document's skin anew on a worker (or, without skin maps, goes back to the
    /// flat skin at once).
    pub(super) fn request_skin_bake(&mut self) {
        let Some(skin) = self.editor.document().skin.clone() else {
            self.skin.shown = None;
            self.skin.stale = false;
            if let Err(e) = self.gpu.set_skin_albedo(None) {
                self.ui.message = Some((false, e.to_string()));
            }
            self.view.needs_render = true;
            return;
        };
        if self.skin.bake.is_some() {
            self.skin.stale = true;
            return;
        }
        self.skin.stale = false;
        let (units, follows, cached) = (self.skin.units.clone(), self.skin.blood_follows, self.skin.table.clone());
        let rx =
            super::session::spawn_job("baking the skin maps".into(), move || bake_full(skin, units, follows, cached));
        self.skin.bake = Some(rx);
    }

    /// The skin edits changed inside `rect` (texels of the edits): re-bake that rectangle when
    /// the blood is still and the shown bake is of these maps, else bake everything.
    pub(super) fn skin_edits_changed(&mut self, rect: TexelRect) {
        let Some(skin) = self.editor.document().skin.clone() else { return self.request_skin_bake() };
        let table = self.skin.table.clone().filter(|(b, _)| b == skin.maps.base());
        let wanted = self.skin.factors();
        let usable = self.skin.bake.is_none()
            && self.skin.shown.as_ref().is_some_and(|s| {
                s.recipe == skin.recipe
                    && s.factors.is_empty()
                    && wanted.is_empty()
                    && s.edited.width() == skin.maps.width()
            });
        let (Some((_, table)), Some(edits), true) = (table, skin.edits.as_ref(), usable) else {
            return self.request_skin_bake();
        };
        let Some(shown) = self.skin.shown.as_mut() else { return };
        let start = Instant::now();
        let (w, h) = (skin.maps.width(), skin.maps.height());
        let r = edits.map_rect(rect, w, h);
        shown.edited.reapply_edits_in(&skin.maps, edits, r);
        let patch = bake(&shown.edited.crop(r), &table);
        let image = Arc::make_mut(&mut shown.image);
        image::imageops::replace(image, &patch, i64::from(r.x0), i64::from(r.y0));
        let albedo = Arc::clone(&shown.image);
        self.skin.last_rect_bake = Some((r.area(), start.elapsed().as_secs_f64() * 1e3));
        if let Err(e) = self.gpu.set_skin_albedo(Some(albedo)) {
            self.ui.message = Some((false, e.to_string()));
        }
        self.view.needs_render = true;
    }

    /// Takes finished maps and bakes; returns whether anything new is shown.
    pub(super) fn poll_skin(&mut self) -> bool {
        let mut changed = false;
        if let Some((what, rx)) = &self.skin.generating {
            match rx.try_recv() {
                Ok(result) => {
                    let what = what.clone();
                    self.skin.generating = None;
                    match result {
                        Ok(skin) => {
                            let c = self.editor.set_skin(Some(skin));
                            self.apply_change(c);
                            self.ui.message = Some((true, format!("skin maps: {what}")));
                        }
                        Err(e) => self.ui.message = Some((false, format!("skin maps ({what}): {e}"))),
                    }
                    changed = true;
                }
                Err(mpsc::TryRecvError::Empty) => {}
                Err(mpsc::TryRecvError::Disconnected) => self.skin.generating = None,
            }
        }
        let baked = match self.skin.bake.as_ref().map(|rx| rx.try_recv()) {
            Some(Ok(b)) => Some(b),
            Some(Err(mpsc::TryRecvError::Disconnected)) => Some(Err("the skin bake stopped".to_string())),
            _ => None,
        };
        if let Some(result) = baked {
            self.skin.bake = None;
            changed = true;
            match result {
                Ok(b) => self.show_baked(b),
                Err(e) => self.ui.message = Some((false, format!("skin maps: {e}"))),
            }
            if self.skin.stale {
                self.request_skin_bake();
            }
        }
        if !self.skin.busy() && self.editor.document().skin.is_none() && self.skin.shown.is_some() {
            self.request_skin_bake();
        }
        changed
    }

    fn show_baked(&mut self, b: Baked) {
        self.skin.table = Some(b.table.clone());
        self.skin.last_bake = Some((b.edited.width(), b.bake_ms, b.table_ms));
        let current = self.editor.document().skin.clone();
        let current_pixels = current.as_ref().is_some_and(|s| Arc::ptr_eq(s, &b.skin));
        let recipe = b.skin.recipe.clone();
        drop(current);
        drop(b.skin);
        if !current_pixels || b.factors != self.skin.factors() {
            // The skin or the pose moved on while it baked.
            self.skin.stale = true;
        }
        if self.editor.document().skin.is_none() {
            return;
        }
        let image = Arc::new(b.image);
        if let Err(e) = self.gpu.set_skin_albedo(Some(Arc::clone(&image))) {
            self.ui.message = Some((false, e.to_string()));
        }
        self.skin.shown = Some(Shown { recipe, edited: b.edited, factors: b.factors, image });
        self.view.needs_render = true;
    }
}
