//! The brush's symmetry plane: an axis and an offset, fitted to the mesh or set by hand (a scan
//! rarely sits centred on its bounds).

use super::*;
use rouge_measure::analysis::optimize::golden_section;

/// How many surface points [`MirrorPlane::fit`] compares with their mirror images.
const FIT_SAMPLES: usize = 1500;
/// [`MirrorPlane::fit`] stops when the offset is known to this, mm.
const FIT_TOLERANCE_MM: f64 = 0.01;

/// A world axis, the normal of a symmetry plane.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Axis {
    /// Left-right (the default head's midplane is x = 0).
    X,
    /// Up-down.
    Y,
    /// Front-back.
    Z,
}

impl Axis {
    /// All axes, X first.
    pub const ALL: [Axis; 3] = [Axis::X, Axis::Y, Axis::Z];

    /// The component index (0, 1, 2).
    pub fn index(self) -> usize {
        match self {
            Axis::X => 0,
            Axis::Y => 1,
            Axis::Z => 2,
        }
    }

    /// "x", "y" or "z".
    pub fn name(self) -> &'static str {
        ["x", "y", "z"][self.index()]
    }
}

/// The plane `p[axis] = offset_mm` a mirrored brush reflects its dabs across.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MirrorPlane {
    /// The plane's normal.
    pub axis: Axis,
    /// Where the plane cuts the axis, mm.
    pub offset_mm: f32,
}

impl MirrorPlane {
    /// The plane normal to `axis` through the centre of the surface's bounds.
    pub fn fitted(axis: Axis, surface: &SurfaceMap) -> MirrorPlane {
        MirrorPlane { axis, offset_mm: surface.centre()[axis.index()] }
    }

    /// The plane normal to `axis` about which the surface is most nearly symmetric: the offset
    /// minimising the mean distance from mirrored surface points (every n-th covered texel) to
    /// the surface, by golden-section search (\[Kiefer1953\]) within a fifth of the bounds' extent either side of
    /// the bounds' centre. For a scan whose shoulders or hair make the bounds lopsided this finds
    /// the face's own midplane. Falls back to [`MirrorPlane::fitted`] on an empty surface.
    pub fn fit(axis: Axis, surface: &SurfaceMap) -> MirrorPlane {
        let centre = MirrorPlane::fitted(axis, surface);
        let n = surface.points.len();
        if n == 0 {
            return centre;
        }
        let a = axis.index();
        let (lo, hi) =
            surface.points.iter().fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), p| (lo.min(p[a]), hi.max(p[a])));
        let reach = 0.2 * (hi - lo);
        let samples: Vec<Vec3> = surface.points.iter().step_by((n / FIT_SAMPLES).max(1)).copied().collect();
        let cap = (hi - lo).max(1.0);
        let mismatch = |offset: f32| {
            let plane = MirrorPlane { axis, offset_mm: offset };
            let sum: f64 = samples
                .iter()
                .map(|&p| {
                    let q = plane.reflect(p);
                    f64::from(surface.nearest_on_surface(q, cap).map_or(cap, |s| s.distance(q)))
                })
                .sum();
            sum / samples.len() as f64
        };
        let (lo, hi) = (f64::from(centre.offset_mm - reach), f64::from(centre.offset_mm + reach));
        let (offset, _) = golden_section(|x| mismatch(x as f32), lo, hi, FIT_TOLERANCE_MM);
        MirrorPlane { axis, offset_mm: offset as f32 }
    }

    /// The mirror image of `p`.
    pub fn reflect(&self, p: Vec3) -> Vec3 {
        let mut q = p;
        let a = self.axis.index();
        q[a] = 2.0 * self.offset_mm - p[a];
        q
    }

    /// The covered texels within `tolerance_mm` of the plane, (position, normal), at most about
    /// 20 000 of them (evenly thinned): where the plane cuts the surface, for drawing it.
    pub fn trace(&self, surface: &SurfaceMap, tolerance_mm: f32) -> Vec<(Vec3, Vec3)> {
        let near: Vec<usize> =
            (0..surface.points.len()).filter(|&s| self.distance(surface.points[s]).abs() <= tolerance_mm).collect();
        let step = (near.len() / 20_000).max(1);
        near.into_iter().step_by(step).map(|s| (surface.points[s], surface.normals[s])).collect()
    }

    /// Signed distance of `p` from the plane, mm.
    pub fn distance(&self, p: Vec3) -> f32 {
        p[self.axis.index()] - self.offset_mm
    }
}
