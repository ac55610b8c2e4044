//! Local thickness baked per vertex, for the renderer's thickness-based translucency
//! (\[BarreBrisebois2011\], "Computing Local Thickness": ambient occlusion computed with inverted
//! normals, then inverted so that white means thin; optionally coloured).
//!
//! From every vertex, `rays` cosine-weighted directions about the *inward* normal −n are traced
//! into the interior against a BVH of the mesh's triangles ([`obvhs`]). A hit at distance t
//! (mm, measured from the vertex) weighs w(t) ([`Falloff`]); a ray that hits nothing within the
//! cutoff weighs 0. The vertex's value is the mean weight: 1 (white) where every ray leaves the
//! body at once, 0 (black) where none leaves within the cutoff. [`LocalThickness::mean_chord_mm`]
//! keeps the plain mean chord as well, in millimetres, for checks and for models that want a
//! distance.
//!
//! Directions are a rank-1 lattice (stratified in cos²θ, golden-ratio steps in azimuth), shifted
//! per vertex by a hash of the seed and the vertex index (Cranley-Patterson rotation), so a bake
//! is reproducible bit for bit and each vertex's estimate is unbiased. Because the cos²θ
//! coordinate has exactly one sample per stratum of width 1/rays, any weight that depends only on
//! θ and is monotone in it (a convex body seen from a point whose normal is radial, such as the
//! sphere) is integrated with an error of at most (w_max − w_min)/rays.
//!
//! Domain of validity: a closed (watertight) mesh in millimetres with outward normals. On an
//! open mesh, rays that leave through a hole count as misses (thick). At a sharp edge of a
//! flat-shaded mesh (split vertices, face normals), the rays that leave through the adjacent
//! faces at once also count as misses, so corners read thicker than they are; the renderer's
//! smooth-shaded meshes do not have them.
//!
//! [`bake_ambient_occlusion`] sends the same rays about the outward normal: ambient occlusion,
//! for exports that carry an occlusion texture (glTF's `occlusionTexture`).
//!
//! [`thickness_uv_map`] rasterises the per-vertex values into the mesh's UV space (the same
//! rasteriser and seam dilation as the brush's [`crate::paint::SurfaceMap`]);
//! [`bake_local_thickness_cached`] keeps bakes on disk keyed by the mesh and the settings;
//! [`morph_to_bounding_sphere`] deforms a mesh for tests of re-baking under deformation.

use std::collections::HashMap;
use std::path::PathBuf;
use std::time::{Duration, Instant};

use glam::{Vec3, Vec3A};
use obvhs::BvhBuildParams;
use obvhs::cwbvh::builder::build_cwbvh_from_tris;
use obvhs::triangle::Triangle;

use crate::mesh::{Bounds, TriangleMesh};
use crate::paint::par_rows;

mod cache;
mod morph;
mod trace;
mod uv_map;

pub use cache::{CacheUse, bake_local_thickness_cached, default_cache_dir};
pub use morph::morph_to_bounding_sphere;
pub use uv_map::{UvMap, thickness_uv_map};

use trace::Tracer;
pub(crate) use trace::splitmix64;

/// Ray origins sit this fraction of the mesh's bounding-box diagonal inside the surface, and hits
/// closer than it are ignored (self hits).
const EPSILON_PER_DIAGONAL: f32 = 1.0e-4;
/// The smallest epsilon, mm (a mesh of zero extent).
const MIN_EPSILON_MM: f32 = 1.0e-6;

/// How the hit distance t (mm) of an inward ray weighs into the local-thickness value
/// (\[BarreBrisebois2011\]: the grey map is inverted ambient occlusion, the coloured one a tint per
/// channel). A ray that hits nothing within the cutoff weighs 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Falloff {
    /// Grey: w(t) = (1 − t/cutoff)^exponent for t < cutoff, 0 beyond (exponent > 0, finite).
    /// `exponent: 1` is the linear falloff of obscurance-style ambient occlusion.
    Power {
        /// Exponent of the falloff, > 0.
        exponent: f32,
    },
    /// Coloured (the talk's coloured local thickness): w_c(t) = exp(−per_mm\[c\]·t) for
    /// t < cutoff, 0 beyond (rates ≥ 0, finite). Rouge passes the medium's σ_tr here, so each
    /// channel is the Beer-Lambert transmittance along the chord, averaged over the cosine lobe.
    Exponential {
        /// Attenuation rate per channel (R, G, B), mm⁻¹, ≥ 0.
        per_mm: [f32; 3],
    },
}

impl Falloff {
    /// The weight of a hit at `t_mm` (< `cutoff_mm`), per channel.
    fn weight(&self, t_mm: f32, cutoff_mm: f32) -> [f32; 3] {
        match *self {
            Falloff::Power { exponent } => [(1.0 - t_mm / cutoff_mm).max(0.0).powf(exponent); 3],
            Falloff::Exponential { per_mm } => per_mm.map(|k| (-k * t_mm).exp()),
        }
    }
}

/// Settings of [`bake_local_thickness`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BakeSettings {
    /// Rays per vertex, ≥ 1. The error of a vertex's estimate falls about as 1/rays (see the
    /// module documentation).
    pub rays: u32,
    /// Longest chord that counts, mm (finite, > 0): a ray that hits nothing closer counts as a
    /// miss (chord = cutoff, weight 0).
    pub cutoff_mm: f32,
    /// The weight of a hit at distance t.
    pub falloff: Falloff,
    /// Seed of the per-vertex rotation of the ray pattern: the same seed gives the same bake.
    pub seed: u64,
}

impl Default for BakeSettings {
    /// 64 rays, cutoff 30 mm (about a head's half-width at the cheeks), linear grey falloff.
    fn default() -> Self {
        BakeSettings { rays: 64, cutoff_mm: 30.0, falloff: Falloff::Power { exponent: 1.0 }, seed: 0 }
    }
}

impl BakeSettings {
    /// Checks every parameter's domain.
    ///
    /// # Errors
    /// [`ThicknessError::Setting`] naming the first parameter out of its domain and why.
    pub fn validate(&self) -> Result<(), ThicknessError> {
        let bad = |parameter: &'static str, value: String, reason: &'static str| {
            Err(ThicknessError::Setting { parameter, value, reason })
        };
        if self.rays == 0 {
            return bad("rays", "0".into(), "at least one ray per vertex is needed");
        }
        if !(self.cutoff_mm.is_finite() && self.cutoff_mm > 0.0) {
            return bad("cutoff_mm", self.cutoff_mm.to_string(), "must be finite and > 0 mm");
        }
        match self.falloff {
            Falloff::Power { exponent } => {
                if !(exponent.is_finite() && exponent > 0.0) {
                    return bad("falloff.exponent", exponent.to_string(), "must be finite and > 0");
                }
            }
            Falloff::Exponential { per_mm } => {
                if let Some(k) = per_mm.iter().find(|k| !(k.is_finite() && **k >= 0.0)) {
                    return bad("falloff.per_mm", format!("{k} (in {per_mm:?})"), "rates must be finite and ≥ 0 mm⁻¹");
                }
            }
        }
        Ok(())
    }
}

/// Errors from baking, mapping, caching or morphing local thickness.
#[derive(Debug, thiserror::Error)]
pub enum ThicknessError {
    /// A bake setting out of its domain.
    #[error("local thickness: {parameter} = {value}: {reason}")]
    Setting {
        /// The parameter at fault (`rays`, `cutoff_mm`, `falloff.exponent`, `falloff.per_mm`).
        parameter: &'static str,
        /// Its value.
        value: String,
        /// What the domain is.
        reason: &'static str,
    },
    /// A mesh the baker cannot use: what is wrong and where.
    #[error("local thickness: mesh: {0}")]
    Mesh(String),
    /// Values or a map size that do not fit the mesh.
    #[error("local thickness: UV map: {0}")]
    Map(String),
    /// A morph parameter outside [0, 1].
    #[error("morph to bounding sphere: t = {0}: must be in [0, 1]")]
    MorphT(f32),
    /// The cache directory or file could not be written.
    #[error("local thickness cache {path}: {source}")]
    Cache {
        /// The file or directory at fault.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
}

/// A bake: per-vertex mean chord and local-thickness value, and how it was made.
#[derive(Debug, Clone, PartialEq)]
pub struct LocalThickness {
    /// The settings it was baked with.
    pub settings: BakeSettings,
    /// Per vertex of the TriangleMesh: the cosine-weighted mean chord length into the interior,
    /// mm (a ray that hits nothing within cutoff counts as cutoff). For a sphere of radius r and
    /// a cutoff ≥ 2r this is 4r/3 (Cauchy: the chord at angle θ from the normal is 2r·cosθ, and
    /// the cosine-weighted mean of cosθ is 2/3).
    pub mean_chord_mm: Vec<f32>,
    /// Per vertex: the local thickness value, RGB in [0, 1], white = thin: the mean over the rays
    /// of w(t) (0 for a miss). Grey falloffs give three equal channels.
    pub value: Vec<[f32; 3]>,
    /// Wall-clock time of the bake (BVH build and tracing), s; for a cache hit, the time of the
    /// bake that wrote the file.
    pub bake_seconds: f64,
}

/// Bakes the local thickness of every vertex of `mesh` (\[BarreBrisebois2011\], "Computing Local
/// Thickness": ambient occlusion with inverted normals, inverted). See the module documentation
/// for the sampling, its error bound and the domain of validity (closed meshes, mm, outward
/// normals).
///
/// A vertex whose normal has no direction (zero length) uses the area-weighted normal of the
/// triangles at its position; where that has none either, it gets chord = cutoff and value 0
/// (as if every ray missed), never NaN. Uses all available cores (`std::thread::scope`).
///
/// # Errors
/// [`ThicknessError::Setting`] for settings out of their domain; [`ThicknessError::Mesh`] for a
/// mesh with no triangles, an index out of range, a normal count that is not the vertex count,
/// or a non-finite position or normal (naming the vertex).
pub fn bake_local_thickness(mesh: &TriangleMesh, settings: &BakeSettings) -> Result<LocalThickness, ThicknessError> {
    let start = Instant::now();
    let (mean_chord_mm, value) = trace_vertices(mesh, settings, Side::Inward)?.into_iter().unzip();
    Ok(LocalThickness { settings: *settings, mean_chord_mm, value, bake_seconds: start.elapsed().as_secs_f64() })
}

/// Bakes the ambient occlusion of every vertex of `mesh`: the same rays as
/// [`bake_local_thickness`] about the *outward* normal (the eye sockets, the nostrils and the
/// folds under the chin see less of the sky), 1 − the mean weight w(t) of their hits: 1 where
/// every ray leaves, down to 0 where every ray hits at once. With the default settings' linear
/// falloff, a hit at distance t darkens by 1 − t/cutoff (the "distance" ambient occlusion of
/// Blender's and Substance Painter's bakers). Same domain and errors as [`bake_local_thickness`];
/// a vertex without a normal reads 1 (unoccluded).
///
/// # Errors
/// As [`bake_local_thickness`].
pub fn bake_ambient_occlusion(mesh: &TriangleMesh, settings: &BakeSettings) -> Result<Vec<f32>, ThicknessError> {
    Ok(trace_vertices(mesh, settings, Side::Outward)?.into_iter().map(|(_, w)| 1.0 - w[0]).collect())
}

/// Which way a vertex's rays go.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Side {
    /// About −n, into the body (local thickness).
    Inward,
    /// About +n, away from the surface (ambient occlusion).
    Outward,
}

/// Every vertex's (mean chord, mean weight) of its rays on `side`, traced in parallel.
fn trace_vertices(
    mesh: &TriangleMesh,
    settings: &BakeSettings,
    side: Side,
) -> Result<Vec<(f32, [f32; 3])>, ThicknessError> {
    settings.validate()?;
    check_mesh(mesh)?;
    let triangles: Vec<Triangle> = mesh
        .indices
        .chunks_exact(3)
        .map(|t| {
            let p = |k: usize| Vec3A::from(mesh.positions[t[k] as usize]);
            Triangle { v0: p(0), v1: p(1), v2: p(2) }
        })
        .collect();
    let bvh = build_cwbvh_from_tris(&triangles, BvhBuildParams::medium_build(), &mut Duration::default());
    let diagonal = Bounds::of(&mesh.positions).map_or(0.0, |b| b.size().length());
    let epsilon_mm = (EPSILON_PER_DIAGONAL * diagonal).max(MIN_EPSILON_MM);
    let needs_fallback = mesh.normals.iter().any(|n| n.length_squared() <= f32::MIN_POSITIVE);
    let fallback = if needs_fallback { smooth_normals_per_position(mesh) } else { Vec::new() };
    let tracer = Tracer { bvh: &bvh, triangles: &triangles, settings, epsilon_mm };
    // The tracer sends its rays about the inward normal it is given.
    let toward = if side == Side::Inward { 1.0 } else { -1.0 };
    Ok(par_rows(mesh.vertex_count(), |range| {
        range
            .map(|i| {
                let n = mesh.normals[i].try_normalize().or_else(|| fallback.get(i).and_then(|n| n.try_normalize()));
                match n {
                    Some(n) => tracer.vertex(mesh.positions[i], toward * n, i as u64),
                    None => (settings.cutoff_mm, [0.0; 3]),
                }
            })
            .collect::<Vec<_>>()
    })
    .concat())
}

/// Rejects meshes the baker cannot trace.
pub(super) fn check_mesh(mesh: &TriangleMesh) -> Result<(), ThicknessError> {
    let n = mesh.vertex_count();
    if mesh.normals.len() != n {
        return Err(ThicknessError::Mesh(format!("{} normals for {n} vertices", mesh.normals.len())));
    }
    if mesh.indices.len() < 3 {
        return Err(ThicknessError::Mesh("no triangles".into()));
    }
    if !mesh.indices.len().is_multiple_of(3) {
        return Err(ThicknessError::Mesh(format!("{} indices: not a multiple of 3", mesh.indices.len())));
    }
    if let Some((k, i)) = mesh.indices.iter().enumerate().find(|(_, i)| **i as usize >= n) {
        return Err(ThicknessError::Mesh(format!("index {k} (triangle {}) = {i}: only {n} vertices", k / 3)));
    }
    if let Some((i, p)) = mesh.positions.iter().enumerate().find(|(_, p)| !p.is_finite()) {
        return Err(ThicknessError::Mesh(format!("vertex {i}: non-finite position {p}")));
    }
    if let Some((i, v)) = mesh.normals.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(ThicknessError::Mesh(format!("vertex {i}: non-finite normal {v}")));
    }
    Ok(())
}

/// Area-weighted smooth normals of a triangle mesh, one per vertex but equal for every vertex at
/// the same position (a [`TriangleMesh`] splits vertices at UV seams and hard edges; the normal
/// must not). A position with no area gets the zero vector.
pub(super) fn smooth_normals_per_position(mesh: &TriangleMesh) -> Vec<Vec3> {
    let key = |p: Vec3| p.to_array().map(|c| if c == 0.0 { 0 } else { c.to_bits() });
    let mut ids: HashMap<[u32; 3], usize> = HashMap::new();
    let shared: Vec<usize> = mesh
        .positions
        .iter()
        .map(|&p| {
            let next = ids.len();
            *ids.entry(key(p)).or_insert(next)
        })
        .collect();
    let mut acc = vec![Vec3::ZERO; ids.len()];
    for t in mesh.indices.chunks_exact(3) {
        let [a, b, c] = [0, 1, 2].map(|k| t[k] as usize);
        let (Some(&pa), Some(&pb), Some(&pc)) = (mesh.positions.get(a), mesh.positions.get(b), mesh.positions.get(c))
        else {
            continue;
        };
        // Twice the area times the unit normal.
        let n = (pb - pa).cross(pc - pa);
        if n.is_finite() {
            for v in [a, b, c] {
                acc[shared[v]] += n;
            }
        }
    }
    shared.iter().map(|&s| acc[s].normalize_or_zero()).collect()
}
