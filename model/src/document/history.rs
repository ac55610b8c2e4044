//! Strokes, undo and redo of the [`Document`]: the open stroke, the history of edits with
//! its memory budget, and the rectangles a stroke step stores.

use super::*;

impl Document {
    // --------------------------------------------------------------------------------------
    // Strokes

    /// Opens a stroke on layer `layer` (ending any open stroke) and returns its map to paint;
    /// `None` if there is no such layer. The map as it was is kept (shared, no copy) until
    /// [`Document::end_stroke`]; the returned map is the document's own copy.
    pub fn begin_stroke(&mut self, layer: usize) -> Option<&mut ThicknessMap> {
        self.finish_stroke();
        let start = Arc::clone(&self.layers.get(layer)?.map);
        self.stroke = Some(OpenStroke { layer, start, rect: None });
        self.layers.get_mut(layer).map(|l| Arc::make_mut(&mut l.map))
    }

    /// The map being painted: `Some` only while a stroke is open on `layer`.
    pub fn stroke_map(&mut self, layer: usize) -> Option<&mut ThicknessMap> {
        if self.stroke.as_ref().is_none_or(|s| s.layer != layer) {
            return None;
        }
        self.layers.get_mut(layer).map(|l| Arc::make_mut(&mut l.map))
    }

    /// Reports texels the painter changed during the open stroke (half-open, clamped to the
    /// map); the document keeps the union. Ignored when no stroke is open.
    pub fn note_dirty(&mut self, rect: TexelRect) {
        if let Some(stroke) = self.skin_stroke.as_mut() {
            let rect = rect.clamped(stroke.start.width(), stroke.start.height());
            if !rect.is_empty() {
                stroke.rect = Some(stroke.rect.map_or(rect, |r| r.union(rect)));
            }
            return;
        }
        let Some(stroke) = self.stroke.as_mut() else { return };
        let (w, h) = (stroke.start.width, stroke.start.height);
        let rect = rect.clamped(w, h);
        if rect.is_empty() {
            return;
        }
        stroke.rect = Some(stroke.rect.map_or(rect, |r| r.union(rect)));
    }

    /// Ends the open stroke: one undo step holding the changed texels' bounding box before and
    /// after, and `Change::Map` naming it; `Change::Nothing` if no texel changed (or no stroke
    /// was open). Without any [`Document::note_dirty`] the whole map is compared.
    pub fn end_stroke(&mut self) -> Change {
        self.finish_stroke()
    }

    pub(super) fn finish_stroke(&mut self) -> Change {
        let skin = self.finish_skin_stroke();
        if skin != Change::Nothing {
            return skin;
        }
        let Some(stroke) = self.stroke.take() else { return Change::Nothing };
        let Some(layer) = self.layers.get(stroke.layer) else { return Change::Nothing };
        let (old, new) = (&*stroke.start, &*layer.map);
        if (old.width, old.height, old.mm.len()) != (new.width, new.height, new.mm.len()) {
            // The painter replaced the map by one of another size: record the whole layer list.
            let mut before = self.layers.clone();
            if let Some(l) = before.get_mut(stroke.layer) {
                l.map = stroke.start;
            }
            let after = self.layers.clone();
            self.push(Edit::Layers { before, after });
            return Change::Layers;
        }
        let search = stroke.rect.unwrap_or(TexelRect::whole(old.width, old.height));
        let Some(rect) = changed_bounds(old, new, search) else {
            // Nothing changed: give the layer its old map back, so that history steps sharing
            // it do not keep a second copy alive.
            if let Some(l) = self.layers.get_mut(stroke.layer) {
                l.map = stroke.start;
            }
            return Change::Nothing;
        };
        let (before, after) = (read_rect(old, rect), read_rect(new, rect));
        self.push(Edit::Stroke { layer: stroke.layer, rect, before, after });
        Change::Map { layer: stroke.layer, rect }
    }

    // --------------------------------------------------------------------------------------
    // The skin

    /// Replaces the skin (other maps, or `None` for the tone's flat skin) as one undo step;
    /// nothing (no step) when `skin` is the skin already there (the same `Arc`). The edits go
    /// with the [`ProjectSkin`]: to keep them over regenerated maps, put the current
    /// [`ProjectSkin::edits`] into the new one.
    pub fn set_skin(&mut self, skin: Option<Arc<ProjectSkin>>) -> Change {
        self.finish_stroke();
        let same = match (&self.skin, &skin) {
            (Some(a), Some(b)) => Arc::ptr_eq(a, b),
            (a, b) => a.is_none() && b.is_none(),
        };
        if same {
            return Change::Nothing;
        }
        let before = std::mem::replace(&mut self.skin, skin.clone());
        self.push(Edit::Skin { before, after: skin });
        Change::Skin { rect: None }
    }

    /// Puts `mascara` on the lashes (`None`, or one that changes nothing: natural lashes) as one
    /// undo step; nothing (no step) when it is the mascara already there.
    ///
    /// # Errors
    /// A field out of its range ([`Mascara::validate`], naming it); the document is unchanged.
    pub fn set_mascara(&mut self, mascara: Option<Mascara>) -> Result<Change> {
        let mascara = mascara.filter(|m| !m.is_none());
        if let Some(m) = &mascara {
            m.validate()?;
        }
        Ok(self.set_hair((mascara, self.brow_gel)))
    }

    /// Puts `brow_gel` on the brows (`None`: natural brows) as one undo step; nothing (no step)
    /// when it is the gel already there.
    ///
    /// # Errors
    /// A colour or strength out of range ([`BrowGel::validate`], naming it); the document is
    /// unchanged.
    pub fn set_brow_gel(&mut self, brow_gel: Option<BrowGel>) -> Result<Change> {
        if let Some(g) = &brow_gel {
            g.validate()?;
        }
        Ok(self.set_hair((self.mascara, brow_gel)))
    }

    /// The hair products as one undo step (none when unchanged).
    fn set_hair(&mut self, after: (Option<Mascara>, Option<BrowGel>)) -> Change {
        self.finish_stroke();
        let before = (self.mascara, self.brow_gel);
        if before == after {
            return Change::Nothing;
        }
        (self.mascara, self.brow_gel) = after;
        self.push(Edit::Hair { before, after });
        Change::Hair
    }

    /// Opens a skin brush stroke (ending any open stroke) and returns the skin edits to paint,
    /// made empty ([`MAP_SIZE`]²) if the skin has none; `None` without skin maps. The edits as
    /// they were are kept (shared) until the stroke ends.
    pub fn begin_skin_stroke(&mut self) -> Option<&mut SkinEdits> {
        self.finish_stroke();
        let skin = Arc::make_mut(self.skin.as_mut()?);
        let edits = skin.edits.get_or_insert_with(|| Arc::new(SkinEdits::new(MAP_SIZE, MAP_SIZE)));
        self.skin_stroke = Some(OpenSkinStroke { start: Arc::clone(edits), rect: None });
        Some(Arc::make_mut(edits))
    }

    /// The skin edits being painted: `Some` only while a skin stroke is open.
    pub fn skin_stroke_edits(&mut self) -> Option<&mut SkinEdits> {
        self.skin_stroke.as_ref()?;
        let skin = Arc::make_mut(self.skin.as_mut()?);
        skin.edits.as_mut().map(Arc::make_mut)
    }

    /// Ends the open skin stroke: one undo step holding the dirty rectangle of both planes
    /// before and after; `Change::Nothing` if nothing was noted dirty.
    fn finish_skin_stroke(&mut self) -> Change {
        let Some(stroke) = self.skin_stroke.take() else { return Change::Nothing };
        let Some(edits) = self.skin.as_ref().and_then(|s| s.edits.clone()) else { return Change::Nothing };
        let Some(rect) = stroke.rect.map(|r| r.clamped(edits.width(), edits.height())).filter(|r| !r.is_empty()) else {
            return Change::Nothing;
        };
        let (before, after) = (stroke.start.read_rect(rect), edits.read_rect(rect));
        if before == after {
            return Change::Nothing;
        }
        self.push(Edit::SkinStroke { rect, before, after });
        Change::Skin { rect: Some(rect) }
    }

    // --------------------------------------------------------------------------------------
    // Undo / redo

    /// Whether there is a step to undo (an open stroke counts: undo ends and undoes it).
    pub fn can_undo(&self) -> bool {
        !self.history.undo.is_empty()
            || self.stroke.as_ref().is_some_and(|s| s.rect.is_some())
            || self.skin_stroke.as_ref().is_some_and(|s| s.rect.is_some())
    }

    /// Whether there is a step to redo.
    pub fn can_redo(&self) -> bool {
        !self.history.redo.is_empty()
    }

    /// Undoes the last step (ending an open stroke first); maps come back bit for bit.
    pub fn undo(&mut self) -> Change {
        self.finish_stroke();
        let Some(entry) = self.history.undo.pop_back() else { return Change::Nothing };
        let change = self.apply(&entry.edit, false);
        self.history.redo.push(entry);
        change
    }

    /// Redoes the last undone step.
    pub fn redo(&mut self) -> Change {
        self.finish_stroke();
        let Some(entry) = self.history.redo.pop() else { return Change::Nothing };
        let change = self.apply(&entry.edit, true);
        self.history.undo.push_back(entry);
        change
    }

    pub(super) fn apply(&mut self, edit: &Edit, forward: bool) -> Change {
        match edit {
            Edit::Layers { before, after } => {
                self.layers = if forward { after.clone() } else { before.clone() };
                Change::Layers
            }
            Edit::Stroke { layer, rect, before, after } => {
                let Some(l) = self.layers.get_mut(*layer) else { return Change::Nothing };
                write_rect(Arc::make_mut(&mut l.map), *rect, if forward { after } else { before });
                Change::Map { layer: *layer, rect: *rect }
            }
            Edit::Skin { before, after } => {
                self.skin = if forward { after.clone() } else { before.clone() };
                Change::Skin { rect: None }
            }
            Edit::SkinStroke { rect, before, after } => {
                let Some(skin) = self.skin.as_mut() else { return Change::Nothing };
                let skin = Arc::make_mut(skin);
                let edits = skin.edits.get_or_insert_with(|| Arc::new(SkinEdits::new(MAP_SIZE, MAP_SIZE)));
                Arc::make_mut(edits).write_rect(*rect, if forward { after } else { before });
                Change::Skin { rect: Some(*rect) }
            }
            Edit::Hair { before, after } => {
                (self.mascara, self.brow_gel) = if forward { *after } else { *before };
                Change::Hair
            }
        }
    }

    /// Records a new step: clears the redo steps and drops the oldest steps past the budget.
    pub(super) fn push(&mut self, edit: Edit) {
        let h = &mut self.history;
        h.redo.clear();
        h.undo.push_back(Entry { id: h.next_id, edit });
        h.next_id += 1;
        self.trim_history();
    }

    /// Bytes each undo step keeps alive, oldest first. A map no longer in the document is
    /// counted once, with the newest step holding it (dropping older steps does not free it).
    pub(super) fn step_costs(&self) -> Vec<usize> {
        let live: HashSet<*const ThicknessMap> = self.layers.iter().map(|l| Arc::as_ptr(&l.map)).collect();
        let live_skin = self.skin.as_ref().map(Arc::as_ptr);
        let mut seen_skin = HashSet::new();
        let mut seen = HashSet::new();
        let mut costs: Vec<usize> = self
            .history
            .undo
            .iter()
            .rev()
            .map(|e| match &e.edit {
                Edit::Stroke { before, after, .. } => (before.len() + after.len()) * std::mem::size_of::<f32>(),
                Edit::SkinStroke { before, after, .. } => skin_stroke_bytes(before, after),
                Edit::Hair { .. } => std::mem::size_of::<Edit>(),
                Edit::Skin { before, after } => before
                    .iter()
                    .chain(after)
                    .map(|s| {
                        let p = Arc::as_ptr(s);
                        if live_skin != Some(p) && seen_skin.insert(p) { skin_bytes(s) } else { 0 }
                    })
                    .sum(),
                Edit::Layers { before, after } => before
                    .iter()
                    .chain(after)
                    .map(|l| {
                        let p = Arc::as_ptr(&l.map);
                        let map = if !live.contains(&p) && seen.insert(p) {
                            l.map.mm.len() * std::mem::size_of::<f32>()
                        } else {
                            0
                        };
                        LAYER_SNAPSHOT_BYTES + map
                    })
                    .sum(),
            })
            .collect();
        costs.reverse();
        costs
    }

    pub(super) fn trim_history(&mut self) {
        let costs = self.step_costs();
        let mut total: usize = costs.iter().sum();
        let mut drop = 0;
        // The newest step always stays.
        while total > self.history.budget_bytes && drop + 1 < costs.len() {
            total -= costs[drop];
            drop += 1;
        }
        for _ in 0..drop {
            if let Some(e) = self.history.undo.pop_front() {
                self.history.base_id = e.id;
            }
        }
    }

    /// Memory the undo and redo steps keep alive beyond the document itself, bytes (estimated
    /// for names and presets; maps and stroke rectangles exactly).
    pub fn history_bytes(&self) -> usize {
        let redo: usize = self
            .history
            .redo
            .iter()
            .map(|e| match &e.edit {
                Edit::Stroke { before, after, .. } => (before.len() + after.len()) * std::mem::size_of::<f32>(),
                Edit::SkinStroke { before, after, .. } => skin_stroke_bytes(before, after),
                Edit::Skin { before, after } => before.iter().chain(after).map(|s| skin_bytes(s)).sum(),
                Edit::Hair { .. } => std::mem::size_of::<Edit>(),
                Edit::Layers { before, after } => (before.len() + after.len()) * LAYER_SNAPSHOT_BYTES,
            })
            .sum();
        self.step_costs().iter().sum::<usize>() + redo
    }

    /// Sets the history's memory budget (default [`HISTORY_BUDGET_BYTES`]); the oldest steps
    /// past it are dropped now and as new steps come (the newest step always stays).
    pub fn set_history_budget(&mut self, bytes: usize) {
        self.history.budget_bytes = bytes;
        self.trim_history();
    }

    /// Whether the document differs from the last save or open (a stroke in progress that
    /// reported a dirty rect counts, and so do a changed face and other skin maps).
    pub fn is_modified(&self) -> bool {
        let same_skin = match (&self.skin, &self.saved_skin) {
            (Some(a), Some(b)) => Arc::ptr_eq(a, b),
            (a, b) => a.is_none() && b.is_none(),
        };
        self.history.saved_id != Some(self.history.state_id())
            || self.stroke.as_ref().is_some_and(|s| s.rect.is_some())
            || self.skin_stroke.as_ref().is_some_and(|s| s.rect.is_some())
            || self.face != self.saved_face
            || self.name != self.saved_name
            || self.subsurface != self.saved_subsurface
            || self.diffuse != self.saved_diffuse
            || !same_skin
    }
}

/// Bytes a skin stroke step holds.
fn skin_stroke_bytes(before: &[Vec<f32>; 2], after: &[Vec<f32>; 2]) -> usize {
    before.iter().chain(after).map(|p| p.len() * std::mem::size_of::<f32>()).sum()
}

/// Bytes a skin's maps and edits hold.
fn skin_bytes(skin: &ProjectSkin) -> usize {
    let texels = |w: u32, h: u32| w as usize * h as usize * std::mem::size_of::<f32>();
    5 * texels(skin.maps.width(), skin.maps.height())
        + skin.edits.as_ref().map_or(0, |e| 2 * texels(e.width(), e.height()))
}

// ------------------------------------------------------------------------------------------
// Rectangles

/// The bounding box of the texels inside `search` whose bits differ between `old` and `new`
/// (same size), or `None`.
pub(super) fn changed_bounds(old: &ThicknessMap, new: &ThicknessMap, search: TexelRect) -> Option<TexelRect> {
    let w = old.width as usize;
    let (x0, y0, x1, y1) = (search.x0 as usize, search.y0 as usize, search.x1 as usize, search.y1 as usize);
    let mut bounds: Option<(usize, usize, usize, usize)> = None;
    for y in y0..y1 {
        let (Some(a), Some(b)) = (old.mm.get(y * w + x0..y * w + x1), new.mm.get(y * w + x0..y * w + x1)) else {
            continue;
        };
        let differs = |(p, q): (&f32, &f32)| p.to_bits() != q.to_bits();
        let Some(first) = a.iter().zip(b).position(differs) else { continue };
        let last = a.iter().zip(b).rposition(differs).unwrap_or(first);
        let (lo, hi) = (x0 + first, x0 + last + 1);
        bounds = Some(match bounds {
            None => (lo, y, hi, y + 1),
            Some((bx0, by0, bx1, _)) => (bx0.min(lo), by0, bx1.max(hi), y + 1),
        });
    }
    // The bounds lie inside `search`, which holds u32s.
    bounds.map(|(x0, y0, x1, y1)| TexelRect { x0: x0 as u32, y0: y0 as u32, x1: x1 as u32, y1: y1 as u32 })
}

/// The texels of `rect`, row by row.
pub(super) fn read_rect(map: &ThicknessMap, rect: TexelRect) -> Vec<f32> {
    let w = map.width as usize;
    let (x0, x1) = (rect.x0 as usize, rect.x1 as usize);
    let mut out = Vec::with_capacity(rect.area());
    for y in rect.y0 as usize..rect.y1 as usize {
        if let Some(row) = map.mm.get(y * w + x0..y * w + x1) {
            out.extend_from_slice(row);
        }
    }
    out
}

/// Writes `values` (row by row, as [`read_rect`] gives them) into `rect`.
pub(super) fn write_rect(map: &mut ThicknessMap, rect: TexelRect, values: &[f32]) {
    let w = map.width as usize;
    let (x0, x1) = (rect.x0 as usize, rect.x1 as usize);
    if x1 <= x0 {
        return;
    }
    let rows = values.chunks_exact(x1 - x0);
    for (y, row) in (rect.y0 as usize..rect.y1 as usize).zip(rows) {
        if let Some(dst) = map.mm.get_mut(y * w + x0..y * w + x1) {
            dst.copy_from_slice(row);
        }
    }
}
