//! 3D painting of cosmetic thickness maps (\[Huang2013\] future work: "paint the film on the face").
//!
//! A designer paints thickness in millimetres directly on the head. The brush's radius is
//! millimetres on the surface, so a stroke carries on across UV seams and every UV island is
//! painted at the same size whatever its texel density; and it reaches texels *along the
//! surface*, not through the air, so a dab on the upper lip of a closed mouth leaves the lower lip
//! alone (as it does lids, nostrils and the folds of the ear).
//!
//! - [`SurfaceMap`] says where each texel of a UV map lies on the surface and which way it faces.
//!   It is built once per mesh and map size (any [`TriangleMesh`]: a deformed head with the same
//!   UVs too): every triangle is rasterised in UV space, the 3D position and normal interpolated
//!   barycentrically at each texel centre, then the covered area is dilated by two texels so
//!   bilinear sampling at island edges (UV seams) reads painted values. Covered texels are
//!   bucketed in a uniform 3D grid (cells of about 2 mm); each knows its triangle, and the
//!   mesh's vertices, welded across UV seams, form the graph brush paths run on.
//! - [`apply_dab`] / [`apply_dab_in_view`] paint, erase or smooth the texels a dab reaches
//!   ([`Reach`]: along the surface by default, or the old 3D ball), optionally only those facing
//!   the painter and not hidden in the frame ([`PaintView`]), and the same around its mirror
//!   image across a [`MirrorPlane`] when the brush says so.
//! - [`StrokeSpacer`] turns mouse moves into evenly spaced dab centres on the surface, so a fast
//!   move leaves no gaps; [`stroke`] applies a whole polyline; [`LazyMouse`] steadies a hand.
//! - [`fill`] fills a region mask, a UV island or every covered texel; [`BrushPreset`] holds the
//!   brushes of a makeup kit.
//!
//! Pixel convention as in [`crate::look`]: row 0 is the top of the image; pixel (x, y) has its
//! centre at u = (x + 0.5) / w, v = 1 − (y + 0.5) / h (OBJ UVs, v up).
//!
//! Wiring into the app: each dab returns the [`TexelRect`] of texels it changed; hand it to
//! `Renderer::update_thickness(layer, &map, multiplier, rect.into())`, which re-uploads only
//! that rectangle (wgpu's `Queue::write_texture` needs no row alignment). With the mirror on,
//! [`apply_dab_split`] gives one rectangle per side: the two sides lie far apart in UV, and
//! their union is mostly texture that did not change.

mod fill;
mod presets;
mod reach;
mod stroke;
mod surface;
mod symmetry;

pub use fill::*;
pub use presets::*;
pub use reach::{DepthImage, OCCLUSION_TOLERANCE_MM, PATH_STRETCH, PaintView, Reach};
pub use stroke::*;
pub use surface::*;
pub use symmetry::*;

use std::collections::HashMap;
use std::fmt;
use std::sync::{Arc, Mutex};

use glam::{Mat4, Vec2, Vec3, Vec4};

use crate::look::{MAX_THICKNESS_MM, ThicknessMap};
use crate::mesh::{Bounds, TriangleMesh};
pub use crate::rect::TexelRect;

/// Edge of a [`SurfaceMap`] grid cell, mm: a 10 mm brush visits about 11³ cells.
const GRID_CELL_MM: f32 = 2.0;
/// Most cells a grid may have (about 64 MiB of cell offsets); beyond it the cells grow.
const MAX_GRID_CELLS: usize = 1 << 24;
/// Texels the covered area grows by, so bilinear sampling at island edges reads paint.
const DILATE_TEXELS: usize = 2;
/// Marks a texel that no triangle covers.
const UNCOVERED: u32 = u32::MAX;
/// Most dabs one [`StrokeSpacer::move_to`] returns (a 1 m move of a 0.4 mm brush at spacing 0.25).
const MAX_DABS_PER_MOVE: usize = 1 << 16;
/// Rows of texels handed to a rasterising thread at a time.
const RASTER_BAND_ROWS: usize = 32;

// ------------------------------------------------------------------------------------------
// Brush

/// What a dab does to the thickness.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BrushMode {
    /// Moves the thickness toward the brush's `thickness_mm`.
    Paint,
    /// Moves the thickness toward 0.
    Erase,
    /// Moves the thickness toward the mean of the covered texels within the radius.
    Smooth,
}

/// The shape of a dab's weight between `hardness · radius` and the radius ([`Brush::weight`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Falloff {
    /// 1 − smoothstep: soft at both ends (a blending brush).
    Smooth,
    /// 1 − t: a straight ramp (a sponge).
    Linear,
    /// √(1 − t²): full almost to the edge, then a quick fall (a liner, a lip brush).
    Sphere,
}

impl Falloff {
    /// Every falloff, for menus.
    pub const ALL: [Falloff; 3] = [Falloff::Smooth, Falloff::Linear, Falloff::Sphere];

    /// Its name in menus and presets.
    pub fn name(self) -> &'static str {
        match self {
            Falloff::Smooth => "smooth",
            Falloff::Linear => "linear",
            Falloff::Sphere => "sphere",
        }
    }
}

/// A brush for [`apply_dab`]: all lengths in millimetres on the surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Brush {
    /// What a dab does.
    pub mode: BrushMode,
    /// Radius, mm (along the surface with [`Reach::Surface`]), in (0, 100].
    pub radius_mm: f32,
    /// Target thickness of [`BrushMode::Paint`], mm, in [0, 10].
    pub thickness_mm: f32,
    /// Fraction of the way to the target one dab goes at the centre, in [0, 1].
    pub flow: f32,
    /// Hardness, in [0, 1]: the weight is 1 within `hardness · radius` and falls to 0 at the
    /// radius along `falloff` (see [`Brush::weight`]); 1 = flat to the edge, 0 = falloff from
    /// the centre.
    pub hardness: f32,
    /// The shape of the fall from `hardness · radius` to the radius.
    pub falloff: Falloff,
    /// Also paints the mirror image across `mirror_plane`.
    pub mirror: bool,
    /// The symmetry plane; `None` = the x plane through the centre of the mesh's bounds
    /// ([`MirrorPlane::fitted`]), the default head's midplane.
    pub mirror_plane: Option<MirrorPlane>,
    /// Distance between dabs along a stroke, as a fraction of the radius, in [0.05, 2].
    pub spacing: f32,
    /// How far a dab reaches: along the surface (default) or through the air.
    pub reach: Reach,
    /// Only texels facing the painter (normal toward the eye of the [`PaintView`]) are painted,
    /// and the walk along the surface stops at the silhouette.
    pub front_faces_only: bool,
    /// Texels hidden behind other geometry in the painter's frame are not painted.
    pub occlusion: bool,
}

impl Default for Brush {
    /// Paint, 6 mm, 15 µm (a foundation film), flow 0.35, hardness 0.3, smooth falloff, mirrored
    /// across the fitted midplane, spacing 0.25, along the surface, front faces only, occlusion
    /// on: the safe settings for lips, lids and nostrils.
    fn default() -> Self {
        Brush {
            mode: BrushMode::Paint,
            radius_mm: 6.0,
            thickness_mm: 0.015,
            flow: 0.35,
            hardness: 0.3,
            falloff: Falloff::Smooth,
            mirror: true,
            mirror_plane: None,
            spacing: 0.25,
            reach: Reach::Surface,
            front_faces_only: true,
            occlusion: true,
        }
    }
}

impl Brush {
    /// The weight of a texel `distance_mm` from the dab centre, in [0, 1]: with r the radius, h
    /// the hardness and t = (d − h·r)/(r − h·r), 1 for d ≤ h·r, then by the falloff 1 − t²(3 − 2t)
    /// (smooth), 1 − t (linear) or √(1 − t²) (sphere), and 0 for d ≥ r. Never NaN (0 for a NaN
    /// distance or radius).
    pub fn weight(&self, distance_mm: f32) -> f32 {
        let (d, r) = (distance_mm.abs(), self.radius_mm);
        if d.is_nan() || r.is_nan() || d >= r {
            return 0.0;
        }
        let inner = self.hardness.clamp(0.0, 1.0) * r;
        if d <= inner {
            return 1.0;
        }
        let t = ((d - inner) / (r - inner)).clamp(0.0, 1.0);
        match self.falloff {
            Falloff::Smooth => 1.0 - t * t * (3.0 - 2.0 * t),
            Falloff::Linear => 1.0 - t,
            Falloff::Sphere => (1.0 - t * t).max(0.0).sqrt(),
        }
    }

    /// The symmetry plane on `surface`: `mirror_plane`, or the fitted x plane.
    pub fn plane(&self, surface: &SurfaceMap) -> MirrorPlane {
        self.mirror_plane.unwrap_or_else(|| MirrorPlane::fitted(Axis::X, surface))
    }

    /// This brush at a pen pressure in [0, 1] (1 or a non-finite value: unchanged): radius and
    /// flow scaled by 0.25 + 0.75·pressure, as a pen lightly pressed lays a thinner, lighter line.
    pub fn with_pressure(&self, pressure: f32) -> Brush {
        if !pressure.is_finite() {
            return *self;
        }
        let k = 0.25 + 0.75 * pressure.clamp(0.0, 1.0);
        Brush { radius_mm: (self.radius_mm * k).max(0.05), flow: self.flow * k, ..*self }
    }

    /// Checks every field against its range.
    ///
    /// # Errors
    /// A message naming the field, its value and its range.
    pub fn validate(&self) -> Result<(), String> {
        let check = |name: &str, v: f32, ok: bool, range: &str| {
            if ok { Ok(()) } else { Err(format!("brush {name} {v} is out of range: must be in {range}")) }
        };
        let r = self.radius_mm;
        check("radius_mm", r, r > 0.0 && r <= 100.0, "(0, 100] mm")?;
        let t = self.thickness_mm;
        check("thickness_mm", t, (0.0..=MAX_THICKNESS_MM).contains(&t), "[0, 10] mm")?;
        check("flow", self.flow, (0.0..=1.0).contains(&self.flow), "[0, 1]")?;
        check("hardness", self.hardness, (0.0..=1.0).contains(&self.hardness), "[0, 1]")?;
        check("spacing", self.spacing, (0.05..=2.0).contains(&self.spacing), "[0.05, 2] (fraction of the radius)")?;
        match self.mirror_plane {
            Some(p) if !p.offset_mm.is_finite() => {
                Err(format!("brush mirror plane offset {} mm along {} is not finite", p.offset_mm, p.axis.name()))
            }
            _ => Ok(()),
        }
    }
}

// ------------------------------------------------------------------------------------------
// Dabs and strokes

/// One dab at surface point `centre` (plus its mirror image when `brush.mirror`), seen from
/// nowhere in particular: [`apply_dab_in_view`] without a view (no facing or occlusion test).
///
/// With the mirror on, the two sides usually lie far apart in UV, so the returned rectangle
/// spans much texture that did not change; [`apply_dab_split`] gives one rectangle per side.
pub fn apply_dab(map: &mut ThicknessMap, surface: &SurfaceMap, brush: &Brush, centre: Vec3) -> TexelRect {
    let [a, b] = apply_dab_split(map, surface, brush, centre);
    a.union(b)
}

/// [`apply_dab`], returning the rectangles of changed texels nearer `centre` and nearer its
/// mirror image (empty without the mirror), for uploading the two sides separately.
pub fn apply_dab_split(map: &mut ThicknessMap, surface: &SurfaceMap, brush: &Brush, centre: Vec3) -> [TexelRect; 2] {
    apply_dab_in_view(map, surface, brush, centre, None)
}

/// One dab at surface point `centre`, and one at its mirror image across `brush.plane()` (moved
/// onto the nearest surface within the radius; none where there is no surface that close) when
/// `brush.mirror`, as seen from `view`.
///
/// The texels each centre reaches are those of [`Reach`] (along the surface by default), less
/// those facing away from `view.eye` with `brush.front_faces_only` and those hidden in
/// `view.depth` with `brush.occlusion` (without a view neither test applies). Each reached
/// texel gets a = flow · w(d), with d its distance from the nearer centre and w
/// [`Brush::weight`] (overlapping mirror dabs near the plane count once), then: Paint
/// t += (target − t)·a; Erase t −= t·a; Smooth t += (m − t)·a with m the mean thickness of the
/// texels that centre reaches. Results are clamped to [0, 10] mm and never NaN (a non-finite
/// texel counts as 0). Only covered texels change.
///
/// Returns the rectangles of texels whose value changed nearer `centre` and nearer its mirror
/// image (empty if none). Nothing changes for a brush that fails [`Brush::validate`], a
/// non-finite centre, or a map whose size differs from the surface map's.
pub fn apply_dab_in_view(
    map: &mut ThicknessMap,
    surface: &SurfaceMap,
    brush: &Brush,
    centre: Vec3,
    view: Option<&PaintView>,
) -> [TexelRect; 2] {
    let n = surface.width as usize * surface.height as usize;
    if (map.width, map.height) != (surface.width, surface.height)
        || map.mm.len() != n
        || surface.slot.len() != n
        || !centre.is_finite()
        || brush.validate().is_err()
    {
        return [TexelRect::EMPTY; 2];
    }
    let texel = |t: f32| if t.is_finite() { t } else { 0.0 };
    let (reached, hits) = dab_hits(surface, brush, centre, view);
    let mean = reached.iter().map(|hits| {
        if brush.mode != BrushMode::Smooth || hits.is_empty() {
            return 0.0;
        }
        let sum: f64 = hits.iter().map(|&(s, _)| f64::from(texel(map.mm[surface.texels[s as usize] as usize]))).sum();
        (sum / hits.len() as f64) as f32
    });
    let mean: Vec<f32> = mean.collect();

    let mut dirty = [TexelRect::EMPTY; 2];
    let width = surface.width as usize;
    for (s, d, k) in hits {
        let w = brush.weight(d);
        if w <= 0.0 {
            continue;
        }
        let i = surface.texels[s as usize] as usize;
        let old = map.mm[i];
        let t = texel(old);
        let target = match brush.mode {
            BrushMode::Paint => brush.thickness_mm,
            BrushMode::Erase => 0.0,
            BrushMode::Smooth => mean[k as usize],
        };
        let step = t + (target - t) * (brush.flow * w);
        // Between t and the target whatever the rounding, so repeated dabs never overshoot.
        let new = if target >= t { step.min(target) } else { step.max(target) }.clamp(0.0, MAX_THICKNESS_MM);
        // Bitwise comparison: a NaN texel that gets a weight is replaced.
        if new.to_bits() != old.to_bits() {
            map.mm[i] = new;
            dirty[k as usize].include((i % width) as u32, (i / width) as u32);
        }
    }
    dirty
}

/// The texels one dab at `centre` reaches (and its mirror image's, with `brush.mirror`): per
/// centre the slots it reaches, and every reached slot once with its distance from the nearer
/// centre and which centre that is (0 = `centre`, 1 = the mirror image). The brush, centre and
/// surface must have been checked as [`apply_dab_in_view`] checks them.
fn dab_hits(
    surface: &SurfaceMap,
    brush: &Brush,
    centre: Vec3,
    view: Option<&PaintView>,
) -> (Vec<reach::Reached>, Vec<(u32, f32, u8)>) {
    let mut centres = vec![centre];
    if brush.mirror {
        let image = brush.plane(surface).reflect(centre);
        let on_surface = match brush.reach {
            Reach::Ball => Some(image),
            Reach::Surface => surface.nearest_on_surface(image, brush.radius_mm),
        };
        if let Some(c) = on_surface.filter(|c| c.distance_squared(centre) > 1.0e-8) {
            centres.push(c);
        }
    }
    // Per centre, the texels it reaches; a texel reached by both goes to the nearer.
    let reached: Vec<reach::Reached> = centres.iter().map(|&c| reach::reached(surface, brush, c, view)).collect();
    let mut hits: Vec<(u32, f32, u8)> = Vec::new();
    match &reached[..] {
        [one] => hits.extend(one.iter().map(|&(s, d)| (s, d, 0))),
        [a, b] => {
            let mut nearest: HashMap<u32, (f32, u8)> = a.iter().map(|&(s, d)| (s, (d, 0))).collect();
            for &(s, d) in b {
                let e = nearest.entry(s).or_insert((d, 1));
                if d < e.0 {
                    *e = (d, 1);
                }
            }
            hits.extend(nearest.into_iter().map(|(s, (d, k))| (s, d, k)));
        }
        _ => {}
    }
    (reached, hits)
}

/// The weights one dab of `brush` at `centre` gives the texels of a map of the surface map's
/// size, for painting something other than a thickness map (the skin edits,
/// [`crate::skin::edits`]): (index of the texel, row by row; a = flow · [`Brush::weight`] of its
/// distance from the nearer centre, in (0, 1]; 0 for `centre`'s side, 1 for its mirror image's),
/// each reached texel once. The same texels and weights as [`apply_dab_in_view`] paints; empty
/// for a brush that fails [`Brush::validate`] or a non-finite centre. The brush's mode and
/// thickness play no part.
pub fn dab_weights(
    surface: &SurfaceMap,
    brush: &Brush,
    centre: Vec3,
    view: Option<&PaintView>,
) -> Vec<(usize, f32, u8)> {
    let n = surface.width as usize * surface.height as usize;
    if surface.slot.len() != n || !centre.is_finite() || brush.validate().is_err() {
        return Vec::new();
    }
    let (_, hits) = dab_hits(surface, brush, centre, view);
    hits.into_iter()
        .filter_map(|(s, d, k)| {
            let a = brush.flow * brush.weight(d);
            (a > 0.0).then(|| (surface.texels[s as usize] as usize, a, k))
        })
        .collect()
}

/// Turns mouse moves into evenly spaced dab centres on the surface.
///
/// Dabs lie `brush.spacing · brush.radius_mm` apart along the polyline of input points, the
/// distance carried over from one move to the next so that many small moves space dabs the same
/// as one long move. Each dab point on the straight segment between two input points is projected
/// back onto the surface ([`SurfaceMap::nearest_on_surface`] within the radius) and skipped
/// where there is no surface that close.
#[derive(Clone, Debug, PartialEq)]
pub struct StrokeSpacer {
    spacing_mm: f32,
    radius_mm: f32,
    /// The last input point.
    last: Option<Vec3>,
    /// Distance along the polyline from the last dab to `last`, mm.
    travelled_mm: f32,
}

impl StrokeSpacer {
    /// A spacer for `brush` (its radius and spacing clamped to their valid ranges).
    pub fn new(brush: &Brush) -> Self {
        let radius_mm = if brush.radius_mm.is_finite() { brush.radius_mm.clamp(1.0e-3, 100.0) } else { 6.0 };
        let spacing = if brush.spacing.is_finite() { brush.spacing.clamp(0.05, 2.0) } else { 0.25 };
        StrokeSpacer { spacing_mm: spacing * radius_mm, radius_mm, last: None, travelled_mm: 0.0 }
    }

    /// Starts a stroke at surface point `p` (mouse down): returns `[p]`, the first dab (nothing
    /// for a non-finite point).
    pub fn start(&mut self, p: Vec3) -> Vec<Vec3> {
        self.travelled_mm = 0.0;
        if !p.is_finite() {
            self.last = None;
            return Vec::new();
        }
        self.last = Some(p);
        vec![p]
    }

    /// Continues the stroke to surface point `p` (mouse drag): the dab centres on the segment
    /// from the last point, excluding that point and including `p` when a dab falls on it
    /// (otherwise the remainder carries over to the next move). Without a started stroke this
    /// starts one. At most 65 536 dabs per move; a non-finite point is ignored.
    pub fn move_to(&mut self, p: Vec3, surface: &SurfaceMap) -> Vec<Vec3> {
        let Some(from) = self.last else { return self.start(p) };
        if !p.is_finite() {
            return Vec::new();
        }
        let length = from.distance(p);
        let direction = (p - from).normalize_or_zero();
        let mut dabs = Vec::new();
        // Distance along this segment of dab k: first + k·spacing (no drift over long moves).
        let first = self.spacing_mm - self.travelled_mm;
        let mut last_dab = -self.travelled_mm;
        for k in 0..MAX_DABS_PER_MOVE {
            let s = first + k as f32 * self.spacing_mm;
            if s > length {
                break;
            }
            if let Some(q) = surface.nearest_on_surface(from + direction * s, self.radius_mm) {
                dabs.push(q);
            }
            last_dab = s;
        }
        self.travelled_mm = (length - last_dab).clamp(0.0, self.spacing_mm);
        self.last = Some(p);
        dabs
    }

    /// Ends the stroke (mouse up): a last dab at the final point when more than half a spacing
    /// has passed since the last dab, so the stroke reaches where the mouse let go; the spacer
    /// is then ready for [`StrokeSpacer::start`].
    pub fn finish(&mut self, surface: &SurfaceMap) -> Vec<Vec3> {
        let end = self.last.take();
        let travelled = std::mem::replace(&mut self.travelled_mm, 0.0);
        match end {
            Some(p) if travelled > 0.5 * self.spacing_mm => {
                surface.nearest_on_surface(p, self.radius_mm).into_iter().collect()
            }
            _ => Vec::new(),
        }
    }
}

/// Dabs along the polyline `points` (surface points) with a [`StrokeSpacer`]: start, a move to
/// each further point, finish. Returns the union of the dabs' rectangles.
pub fn stroke(map: &mut ThicknessMap, surface: &SurfaceMap, brush: &Brush, points: &[Vec3]) -> TexelRect {
    let Some((&first, rest)) = points.split_first() else { return TexelRect::EMPTY };
    let mut spacer = StrokeSpacer::new(brush);
    let mut dirty = TexelRect::EMPTY;
    let mut dab = |centres: Vec<Vec3>, map: &mut ThicknessMap| {
        for c in centres {
            dirty = dirty.union(apply_dab(map, surface, brush, c));
        }
    };
    dab(spacer.start(first), map);
    for &p in rest {
        dab(spacer.move_to(p, surface), map);
    }
    dab(spacer.finish(surface), map);
    dirty
}
