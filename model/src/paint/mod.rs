//! 3D painting of cosmetic thickness maps ([Huang2013] future work: "paint the film on the face").
//!
//! A designer paints thickness in millimetres directly on the head. The brush is a ball in 3D:
//! its radius is millimetres on the surface (straight-line distance in 3D, not distance in UV),
//! so a stroke carries on across UV seams and every UV island is painted at the same size
//! whatever its texel density.
//!
//! - [`SurfaceMap`] says where each texel of a UV map lies on the surface. It is built once per
//!   mesh and map size: every triangle is rasterised in UV space, the 3D position interpolated
//!   barycentrically at each texel centre, then the covered area is dilated by two texels so
//!   bilinear sampling at island edges (UV seams) reads painted values. Covered texels are
//!   bucketed in a uniform 3D grid (cells of about 2 mm) for radius queries.
//! - [`apply_dab`] paints, erases or smooths the texels within the brush radius of a surface
//!   point, and of its mirror image across the face's midplane when the brush says so.
//! - [`StrokeSpacer`] turns mouse moves into evenly spaced dab centres on the surface, so a fast
//!   move leaves no gaps; [`stroke`] applies a whole polyline.
//!
//! Pixel convention as in [`crate::look`]: row 0 is the top of the image; pixel (x, y) has its
//! centre at u = (x + 0.5) / w, v = 1 − (y + 0.5) / h (OBJ UVs, v up).
//!
//! Wiring into the app: each dab returns the [`TexelRect`] of texels it changed; hand it to
//! `Renderer::update_thickness(layer, &map, multiplier, rect.into())`, which re-uploads only
//! that rectangle (wgpu's `Queue::write_texture` needs no row alignment). With the mirror on,
//! [`apply_dab_split`] gives one rectangle per side: the two sides lie far apart in UV, and
//! their union is mostly texture that did not change.

mod surface;

pub use surface::*;

use std::fmt;
use std::sync::Mutex;

use glam::{Vec2, Vec3};

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

/// A brush for [`apply_dab`]: all lengths in millimetres on the surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Brush {
    /// What a dab does.
    pub mode: BrushMode,
    /// Radius, mm of 3D distance, in (0, 100].
    pub radius_mm: f32,
    /// Target thickness of [`BrushMode::Paint`], mm, in [0, 10].
    pub thickness_mm: f32,
    /// Fraction of the way to the target one dab goes at the centre, in [0, 1].
    pub flow: f32,
    /// Falloff, in [0, 1]: the weight is 1 within `hardness · radius` and falls to 0 at the
    /// radius along a smoothstep (see [`Brush::weight`]); 1 = flat to the edge, 0 = smooth
    /// falloff from the centre.
    pub hardness: f32,
    /// Also paints the mirror image across the face's midplane ([`SurfaceMap::mirror_x`]).
    pub mirror: bool,
    /// Distance between dabs along a stroke, as a fraction of the radius, in [0.05, 2].
    pub spacing: f32,
}

impl Default for Brush {
    /// Paint, 6 mm, 15 µm (a foundation film), flow 0.35, hardness 0.3, mirrored, spacing 0.25.
    fn default() -> Self {
        Brush {
            mode: BrushMode::Paint,
            radius_mm: 6.0,
            thickness_mm: 0.015,
            flow: 0.35,
            hardness: 0.3,
            mirror: true,
            spacing: 0.25,
        }
    }
}

impl Brush {
    /// The weight of a texel `distance_mm` from the dab centre, in [0, 1]: with r the radius and
    /// h the hardness, 1 for d ≤ h·r, 1 − smoothstep(h·r, r, d) between (smoothstep(t) =
    /// t²(3 − 2t) with t = (d − h·r)/(r − h·r)), and 0 for d ≥ r. Never NaN (0 for a NaN
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
        1.0 - t * t * (3.0 - 2.0 * t)
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
        check("spacing", self.spacing, (0.05..=2.0).contains(&self.spacing), "[0.05, 2] (fraction of the radius)")
    }
}

// ------------------------------------------------------------------------------------------
// Dabs and strokes

/// One dab at surface point `centre` (plus its mirror image when `brush.mirror`).
///
/// Each covered texel within the radius of a centre gets a = flow · w(d), with d its 3D distance
/// to the nearer centre and w [`Brush::weight`] (overlapping mirror dabs near the midplane count
/// once), then: Paint t += (target − t)·a; Erase t −= t·a; Smooth t += (m − t)·a with m the mean
/// thickness of the covered texels within the radius of that centre. Results are clamped to
/// [0, 10] mm and never NaN (a non-finite texel counts as 0). Only covered texels change.
///
/// Returns the rectangle of texels whose value changed (empty if none). Nothing changes for a
/// brush that fails [`Brush::validate`], a non-finite centre, or a map whose size differs from
/// the surface map's.
///
/// With the mirror on, the two sides usually lie far apart in UV, so this rectangle spans much
/// texture that did not change; [`apply_dab_split`] gives one rectangle per side.
pub fn apply_dab(map: &mut ThicknessMap, surface: &SurfaceMap, brush: &Brush, centre: Vec3) -> TexelRect {
    let [a, b] = apply_dab_split(map, surface, brush, centre);
    a.union(b)
}

/// [`apply_dab`], returning the rectangles of changed texels nearer `centre` and nearer its
/// mirror image (empty without the mirror), for uploading the two sides separately.
pub fn apply_dab_split(map: &mut ThicknessMap, surface: &SurfaceMap, brush: &Brush, centre: Vec3) -> [TexelRect; 2] {
    let n = surface.width as usize * surface.height as usize;
    if (map.width, map.height) != (surface.width, surface.height)
        || map.mm.len() != n
        || surface.slot.len() != n
        || !centre.is_finite()
        || brush.validate().is_err()
    {
        return [TexelRect::EMPTY; 2];
    }
    let r = brush.radius_mm;
    let r2 = r * r;
    let mirrored = surface.mirror(centre);
    let centres: &[Vec3] =
        if brush.mirror && mirrored.distance_squared(centre) > 1.0e-8 { &[centre, mirrored] } else { &[centre] };

    // The cell boxes to visit, merged when they touch so no texel is visited twice.
    let grid = &surface.grid;
    let mut boxes: Vec<CellBox> =
        centres.iter().filter_map(|c| grid.range(*c - Vec3::splat(r), *c + Vec3::splat(r))).collect();
    if boxes.len() == 2 && boxes[0].touches(&boxes[1]) {
        boxes = vec![boxes[0].union(&boxes[1])];
    }

    // Texels within the radius: (slot, weight, index of the nearer centre).
    let mut hits: Vec<(u32, f32, u8)> = Vec::new();
    let (mut sum, mut count) = ([0.0f64; 2], [0usize; 2]);
    let smooth = brush.mode == BrushMode::Smooth;
    let texel = |t: f32| if t.is_finite() { t } else { 0.0 };
    for cells in boxes {
        grid.for_each_run(cells, |run| {
            for s in run {
                let p = surface.points[s];
                let mut nearest = (f32::INFINITY, 0u8);
                for (k, c) in centres.iter().enumerate() {
                    let d2 = p.distance_squared(*c);
                    if d2 < r2 {
                        if smooth {
                            sum[k] += f64::from(texel(map.mm[surface.texels[s] as usize]));
                            count[k] += 1;
                        }
                        if d2 < nearest.0 {
                            nearest = (d2, k as u8);
                        }
                    }
                }
                if nearest.0 < r2 {
                    let w = brush.weight(nearest.0.sqrt());
                    if w > 0.0 {
                        hits.push((s as u32, w, nearest.1));
                    }
                }
            }
        });
    }

    let mean = [0, 1].map(|k| if count[k] > 0 { (sum[k] / count[k] as f64) as f32 } else { 0.0 });
    let mut dirty = [TexelRect::EMPTY; 2];
    let width = surface.width as usize;
    for (s, w, k) in hits {
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
