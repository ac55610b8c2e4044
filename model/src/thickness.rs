//! Local thickness baked per vertex, for the renderer's thickness-based translucency
//! ([BarreBrisebois2011], "Computing Local Thickness": ambient occlusion computed with inverted
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
//! [`thickness_uv_map`] rasterises the per-vertex values into the mesh's UV space (the same
//! rasteriser and seam dilation as the brush's [`crate::paint::SurfaceMap`]);
//! [`bake_local_thickness_cached`] keeps bakes on disk keyed by the mesh and the settings;
//! [`morph_to_bounding_sphere`] deforms a mesh for tests of re-baking under deformation.

use std::collections::HashMap;
use std::fmt;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use glam::{Vec3, Vec3A};
use obvhs::BvhBuildParams;
use obvhs::cwbvh::CwBvh;
use obvhs::cwbvh::builder::build_cwbvh_from_tris;
use obvhs::ray::{Ray, RayHit};
use obvhs::triangle::Triangle;

use crate::mesh::{Bounds, TriangleMesh};
use crate::paint::{dilate_and_collect, par_rows, rasterise};

/// Ray origins sit this fraction of the mesh's bounding-box diagonal inside the surface, and hits
/// closer than it are ignored (self hits).
const EPSILON_PER_DIAGONAL: f32 = 1.0e-4;
/// The smallest epsilon, mm (a mesh of zero extent).
const MIN_EPSILON_MM: f32 = 1.0e-6;
/// Most texels a [`UvMap`] may have (16384²).
const MAX_UV_TEXELS: usize = 1 << 28;
/// First bytes of a cache file.
const CACHE_MAGIC: &[u8; 8] = b"ROUGE-LT";
/// Version of the cache file layout and of the bake it stores: bump it whenever either changes,
/// so old files are rebaked rather than misread.
const CACHE_VERSION: u32 = 1;
/// Bytes of a cache file before the per-vertex data.
const CACHE_HEADER_BYTES: usize = 8 + 4 + 16 + 8 + 4 + 4 + 4 + 12 + 8 + 8;

// ------------------------------------------------------------------------------------------
// Settings

/// How the hit distance t (mm) of an inward ray weighs into the local-thickness value
/// ([BarreBrisebois2011]: the grey map is inverted ambient occlusion, the coloured one a tint per
/// channel). A ray that hits nothing within the cutoff weighs 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Falloff {
    /// Grey: w(t) = (1 − t/cutoff)^exponent for t < cutoff, 0 beyond (exponent > 0, finite).
    /// `exponent: 1` is the linear falloff of obscurance-style ambient occlusion.
    Power {
        /// Exponent of the falloff, > 0.
        exponent: f32,
    },
    /// Coloured (the talk's coloured local thickness): w_c(t) = exp(−per_mm[c]·t) for
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

// ------------------------------------------------------------------------------------------
// Errors and results

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

/// Whether [`bake_local_thickness_cached`] used its cache.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CacheUse {
    /// Read from a valid cache file; nothing was traced.
    Hit,
    /// Baked (no file, or a corrupt, stale or mismatched one) and written to the cache.
    Miss,
    /// No cache directory: baked and not stored.
    Off,
}

/// An RGBA f32 texture in a mesh's UV space: row 0 at the top (v = 1), texel (x, y) centred at
/// u = (x + 0.5)/width, v = 1 − (y + 0.5)/height, as [`crate::paint::SurfaceMap`] and the
/// looks' maps.
#[derive(Clone, PartialEq)]
pub struct UvMap {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// Row-major texels, `width × height`, row 0 at the top.
    pub texels: Vec<[f32; 4]>,
}

impl fmt::Debug for UvMap {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let covered = self.texels.iter().filter(|t| t[3] > 0.0).count();
        f.debug_struct("UvMap")
            .field("width", &self.width)
            .field("height", &self.height)
            .field("covered", &covered)
            .finish()
    }
}

impl UvMap {
    /// Texel (x, y) (row 0 at the top); `None` outside the map.
    pub fn texel(&self, x: u32, y: u32) -> Option<[f32; 4]> {
        if x >= self.width || y >= self.height {
            return None;
        }
        self.texels.get(y as usize * self.width as usize + x as usize).copied()
    }
}

// ------------------------------------------------------------------------------------------
// Baking

/// Bakes the local thickness of every vertex of `mesh` ([BarreBrisebois2011], "Computing Local
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
    settings.validate()?;
    check_mesh(mesh)?;
    let start = Instant::now();
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
    let per_vertex: Vec<(f32, [f32; 3])> = par_rows(mesh.vertex_count(), |range| {
        range
            .map(|i| {
                let n = mesh.normals[i].try_normalize().or_else(|| fallback.get(i).and_then(|n| n.try_normalize()));
                match n {
                    Some(n) => tracer.vertex(mesh.positions[i], n, i as u64),
                    None => (settings.cutoff_mm, [0.0; 3]),
                }
            })
            .collect::<Vec<_>>()
    })
    .concat();
    let (mean_chord_mm, value) = per_vertex.into_iter().unzip();
    Ok(LocalThickness { settings: *settings, mean_chord_mm, value, bake_seconds: start.elapsed().as_secs_f64() })
}

/// Rejects meshes the baker cannot trace.
fn check_mesh(mesh: &TriangleMesh) -> Result<(), ThicknessError> {
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

/// What every vertex's rays share.
struct Tracer<'a> {
    bvh: &'a CwBvh,
    triangles: &'a [Triangle],
    settings: &'a BakeSettings,
    epsilon_mm: f32,
}

impl Tracer<'_> {
    /// (mean chord mm, mean weight) of the vertex at `p` with unit outward normal `n`.
    fn vertex(&self, p: Vec3, n: Vec3, vertex: u64) -> (f32, [f32; 3]) {
        let BakeSettings { rays, cutoff_mm, falloff, seed } = *self.settings;
        let inward = -n;
        let (b1, b2) = inward.any_orthonormal_pair();
        let origin = p + inward * self.epsilon_mm;
        let rotation = splitmix64(seed ^ splitmix64(vertex));
        let shift = [unit_f32(rotation), unit_f32(rotation >> 32)];
        let (mut chord_sum, mut weight_sum) = (0.0f64, [0.0f32; 3]);
        for k in 0..rays {
            let d = cosine_direction(k, rays, shift, [b1, b2, inward]);
            let ray = Ray::new(origin.into(), d.into(), self.epsilon_mm, cutoff_mm);
            let shear = WatertightRay::new(origin, d);
            let mut hit = RayHit::none();
            let found = self.bvh.ray_traverse(ray, &mut hit, |ray, id| {
                shear.intersect(&self.triangles[self.bvh.primitive_indices[id] as usize], ray.tmin, ray.tmax)
            });
            // The chord from the vertex itself, not from the offset origin.
            let chord = if found { (origin + d * hit.t).distance(p) } else { cutoff_mm };
            if chord < cutoff_mm {
                chord_sum += f64::from(chord);
                let w = falloff.weight(chord, cutoff_mm);
                for c in 0..3 {
                    weight_sum[c] += w[c];
                }
            } else {
                chord_sum += f64::from(cutoff_mm);
            }
        }
        let n = rays as f32;
        ((chord_sum / f64::from(rays)) as f32, weight_sum.map(|w| (w / n).clamp(0.0, 1.0)))
    }
}

/// A ray prepared for the watertight ray-triangle test of Woop, Benthin and Wald (JCGT 2013,
/// "Watertight Ray/Triangle Intersection"): the ray is sheared onto +z so that the three edge
/// tests are exact on shared edges (a ray through an edge or a vertex hits one of the triangles
/// there; with obvhs's Möller-Trumbore test some rays slipped between the built-in sphere's
/// triangles and counted as misses, which the sphere tests caught). Two-sided.
struct WatertightRay {
    origin: Vec3A,
    /// Axis permutation: the largest |direction| component last.
    k: [usize; 3],
    /// Shear constants (Sx, Sy, Sz).
    shear: [f32; 3],
}

impl WatertightRay {
    fn new(origin: Vec3, d: Vec3) -> Self {
        let a = d.abs();
        let kz = if a.x >= a.y && a.x >= a.z {
            0
        } else if a.y >= a.z {
            1
        } else {
            2
        };
        let (mut kx, mut ky) = ((kz + 1) % 3, (kz + 2) % 3);
        if d[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        WatertightRay { origin: origin.into(), k: [kx, ky, kz], shear: [d[kx] / d[kz], d[ky] / d[kz], 1.0 / d[kz]] }
    }

    /// Distance to the triangle along the ray within [tmin, tmax), or +∞.
    fn intersect(&self, tri: &Triangle, tmin: f32, tmax: f32) -> f32 {
        let [kx, ky, kz] = self.k;
        let [sx, sy, sz] = self.shear;
        let (a, b, c) = (tri.v0 - self.origin, tri.v1 - self.origin, tri.v2 - self.origin);
        let xy = |p: Vec3A| (p[kx] - sx * p[kz], p[ky] - sy * p[kz]);
        let ((ax, ay), (bx, by), (cx, cy)) = (xy(a), xy(b), xy(c));
        let (mut u, mut v, mut w) = (cx * by - cy * bx, ax * cy - ay * cx, bx * ay - by * ax);
        if u == 0.0 || v == 0.0 || w == 0.0 {
            // On an edge in single precision: decide in double, as the paper does.
            let e = |px: f32, py: f32, qx: f32, qy: f32| {
                (f64::from(px) * f64::from(qy) - f64::from(py) * f64::from(qx)) as f32
            };
            (u, v, w) = (e(cx, cy, bx, by), e(ax, ay, cx, cy), e(bx, by, ax, ay));
        }
        if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
            return f32::INFINITY;
        }
        let det = u + v + w;
        if det == 0.0 {
            return f32::INFINITY;
        }
        let t = (u * sz * a[kz] + v * sz * b[kz] + w * sz * c[kz]) / det;
        if t >= tmin && t < tmax { t } else { f32::INFINITY }
    }
}

/// Ray `k` of `rays` about the frame's third axis: a rank-1 lattice point (cos²θ stratified,
/// azimuth in golden-ratio steps), toroidally shifted by `shift`, mapped to the cosine-weighted
/// hemisphere (Malley's method: a uniform disc point lifted onto the hemisphere).
fn cosine_direction(k: u32, rays: u32, shift: [f32; 2], frame: [Vec3; 3]) -> Vec3 {
    /// 1/φ, the golden ratio's fractional part.
    const GOLDEN: f64 = 0.618_033_988_749_894_9;
    // u1 ∈ [0, 1): one sample in each stratum [k/rays, (k+1)/rays) of sin²θ.
    let u1 = ((k as f32 + shift[0]) / rays as f32).min(1.0 - f32::EPSILON);
    let u2 = (f64::from(k) * GOLDEN + f64::from(shift[1])).fract() as f32;
    let (r, phi) = (u1.sqrt(), std::f32::consts::TAU * u2);
    let cos_theta = (1.0 - u1).sqrt();
    (frame[0] * (r * phi.cos()) + frame[1] * (r * phi.sin()) + frame[2] * cos_theta).normalize()
}

/// SplitMix64's finaliser: a well-mixed 64-bit hash of `x`.
fn splitmix64(x: u64) -> u64 {
    let mut z = x.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The low 24 bits of `x` as a number in [0, 1).
fn unit_f32(x: u64) -> f32 {
    (x & 0xff_ffff) as f32 / (1u32 << 24) as f32
}

/// Area-weighted smooth normals of a triangle mesh, one per vertex but equal for every vertex at
/// the same position (a [`TriangleMesh`] splits vertices at UV seams and hard edges; the normal
/// must not). A position with no area gets the zero vector.
fn smooth_normals_per_position(mesh: &TriangleMesh) -> Vec<Vec3> {
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

// ------------------------------------------------------------------------------------------
// UV map

/// The per-vertex values rasterised into the mesh's UV space (`width` × `height`, row 0 at top =
/// v = 1, like [`crate::paint::SurfaceMap`]), dilated across seams, RGBA f32 with alpha 1 where
/// covered, 0 elsewhere.
///
/// Values are interpolated barycentrically at texel centres; texels in the two-texel ring around
/// a UV island take the value of the nearest covered texel (alpha 1 too), so bilinear sampling
/// at seams reads baked values. Uncovered texels are [0, 0, 0, 0]. Triangles with no area in UV
/// space are skipped; where islands overlap the later triangle wins.
///
/// # Errors
/// [`ThicknessError::Map`] when `values` does not hold one finite value per vertex, the mesh has
/// fewer UVs than vertices, or the size is zero or over 16384² texels.
pub fn thickness_uv_map(
    mesh: &TriangleMesh,
    values: &[[f32; 3]],
    width: u32,
    height: u32,
) -> Result<UvMap, ThicknessError> {
    let n = mesh.vertex_count();
    if values.len() != n {
        return Err(ThicknessError::Map(format!("{} values for {n} vertices", values.len())));
    }
    if mesh.uvs.len() != n {
        return Err(ThicknessError::Map(format!("{} UVs for {n} vertices", mesh.uvs.len())));
    }
    if let Some((i, v)) = values.iter().enumerate().find(|(_, v)| !v.iter().all(|c| c.is_finite())) {
        return Err(ThicknessError::Map(format!("vertex {i}: non-finite value {v:?}")));
    }
    let (w, h) = (width as usize, height as usize);
    if w == 0 || h == 0 || w.checked_mul(h).is_none_or(|t| t > MAX_UV_TEXELS) {
        return Err(ThicknessError::Map(format!("size {width}×{height}: must be at least 1×1 and at most 16384²")));
    }
    let attribute: Vec<Vec3> = values.iter().map(|&v| Vec3::from_array(v)).collect();
    let raster = rasterise(mesh, &attribute, w, h);
    let mut texels = vec![[0.0; 4]; w * h];
    for (i, v) in dilate_and_collect(&raster, w, h) {
        texels[i as usize] = [v.x, v.y, v.z, 1.0];
    }
    Ok(UvMap { width, height, texels })
}

// ------------------------------------------------------------------------------------------
// Cache

/// [`bake_local_thickness`] with an on-disk cache: `<dir>/<hex key>.bin`, the key a 128-bit hash
/// of the mesh's positions, normals and indices (the normals steer the rays, so they are part of
/// the key) and of the settings. The file has a versioned header that repeats the key, vertex
/// count and settings, and a checksum of its contents; it is written to a temporary file in the
/// same directory and renamed into place, so a reader never sees half a file. A missing,
/// corrupt, stale or mismatched file is ignored and rebaked (and replaced), never a panic.
/// `cache_dir = None` bakes without a cache ([`CacheUse::Off`]).
///
/// # Errors
/// As [`bake_local_thickness`]; [`ThicknessError::Cache`] when the directory cannot be created or
/// the file cannot be written (the bake is lost: call again with `None` to bake without a cache).
pub fn bake_local_thickness_cached(
    mesh: &TriangleMesh,
    settings: &BakeSettings,
    cache_dir: Option<&Path>,
) -> Result<(LocalThickness, CacheUse), ThicknessError> {
    let Some(dir) = cache_dir else {
        return Ok((bake_local_thickness(mesh, settings)?, CacheUse::Off));
    };
    settings.validate()?;
    check_mesh(mesh)?;
    let key = cache_key(mesh, settings);
    let path = dir.join(format!("{}.bin", hex(&key)));
    if let Ok(bytes) = std::fs::read(&path)
        && let Some(bake) = decode_cache(&bytes, &key, mesh.vertex_count(), settings)
    {
        return Ok((bake, CacheUse::Hit));
    }
    let bake = bake_local_thickness(mesh, settings)?;
    let cache_error = |path: &Path, source| ThicknessError::Cache { path: path.to_path_buf(), source };
    std::fs::create_dir_all(dir).map_err(|e| cache_error(dir, e))?;
    let temp = dir.join(format!(".{}.{}.tmp", hex(&key), std::process::id()));
    let written = std::fs::File::create(&temp).and_then(|mut f| {
        f.write_all(&encode_cache(&bake, &key))?;
        f.sync_all()
    });
    if let Err(e) = written.and_then(|()| std::fs::rename(&temp, &path)) {
        let _ = std::fs::remove_file(&temp);
        return Err(cache_error(&path, e));
    }
    Ok((bake, CacheUse::Miss))
}

/// The thickness cache directory: `$ROUGE_CACHE_DIR`, else `$XDG_CACHE_HOME/rouge/thickness`,
/// else `~/.cache/rouge/thickness` (`$HOME`); `None` when none of them is set (empty counts as
/// unset).
pub fn default_cache_dir() -> Option<PathBuf> {
    let var = |name: &str| std::env::var_os(name).filter(|v| !v.is_empty()).map(PathBuf::from);
    var("ROUGE_CACHE_DIR")
        .or_else(|| var("XDG_CACHE_HOME").map(|d| d.join("rouge").join("thickness")))
        .or_else(|| var("HOME").map(|d| d.join(".cache").join("rouge").join("thickness")))
}

/// A two-lane 64-bit multiply-xorshift hash over 32-bit words: stable across platforms and
/// Rust versions (unlike `std`'s `DefaultHasher`), for cache keys and file checksums. Not
/// cryptographic: the cache header re-checks vertex count and settings.
struct WordHasher([u64; 2]);

impl WordHasher {
    fn new() -> Self {
        WordHasher([0x6a09_e667_f3bc_c908, 0xbb67_ae85_84ca_a73b])
    }

    fn word(&mut self, w: u32) {
        let [a, b] = &mut self.0;
        *a = (*a ^ u64::from(w)).wrapping_mul(0x0000_0100_0000_01b3).rotate_left(23);
        *b = (*b ^ u64::from(w).rotate_left(17)).wrapping_mul(0x9e37_79b9_7f4a_7c15) ^ (*b >> 29);
    }

    fn finish(&self) -> [u8; 16] {
        let [a, b] = self.0;
        let (a, b) = (splitmix64(a ^ b.rotate_left(32)), splitmix64(b ^ a));
        let mut out = [0u8; 16];
        out[..8].copy_from_slice(&a.to_le_bytes());
        out[8..].copy_from_slice(&b.to_le_bytes());
        out
    }
}

/// The settings as the 32-bit words the key and the header store.
fn settings_words(s: &BakeSettings) -> [u32; 9] {
    let (tag, params) = match s.falloff {
        Falloff::Power { exponent } => (0, [exponent, 0.0, 0.0]),
        Falloff::Exponential { per_mm } => (1, per_mm),
    };
    [
        s.rays,
        s.cutoff_mm.to_bits(),
        tag,
        params[0].to_bits(),
        params[1].to_bits(),
        params[2].to_bits(),
        s.seed as u32,
        (s.seed >> 32) as u32,
        0,
    ]
}

fn cache_key(mesh: &TriangleMesh, settings: &BakeSettings) -> [u8; 16] {
    let mut h = WordHasher::new();
    h.word(CACHE_VERSION);
    for list in [&mesh.positions, &mesh.normals] {
        h.word(list.len() as u32);
        for c in list.iter().flat_map(|p| p.to_array()) {
            h.word(c.to_bits());
        }
    }
    h.word(mesh.indices.len() as u32);
    mesh.indices.iter().for_each(|&i| h.word(i));
    for w in settings_words(settings) {
        h.word(w);
    }
    h.finish()
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// The checksum of a cache file's contents before the checksum itself.
fn checksum(bytes: &[u8]) -> [u8; 16] {
    let mut h = WordHasher::new();
    h.word(bytes.len() as u32);
    for chunk in bytes.chunks(4) {
        let mut w = [0u8; 4];
        w[..chunk.len()].copy_from_slice(chunk);
        h.word(u32::from_le_bytes(w));
    }
    h.finish()
}

/// Layout (little-endian): magic, version u32, key [16], vertex count u64, the settings words
/// (rays, cutoff, falloff tag, 3 parameters; seed u64), bake seconds f64, mean chords f32 × n,
/// values f32 × 3n, checksum [16].
fn encode_cache(bake: &LocalThickness, key: &[u8; 16]) -> Vec<u8> {
    let n = bake.mean_chord_mm.len();
    let mut out = Vec::with_capacity(CACHE_HEADER_BYTES + 16 * n + 16);
    out.extend_from_slice(CACHE_MAGIC);
    out.extend_from_slice(&CACHE_VERSION.to_le_bytes());
    out.extend_from_slice(key);
    out.extend_from_slice(&(n as u64).to_le_bytes());
    for w in &settings_words(&bake.settings)[..8] {
        out.extend_from_slice(&w.to_le_bytes());
    }
    out.extend_from_slice(&bake.bake_seconds.to_le_bytes());
    debug_assert_eq!(out.len(), CACHE_HEADER_BYTES);
    for c in &bake.mean_chord_mm {
        out.extend_from_slice(&c.to_le_bytes());
    }
    for v in bake.value.iter().flatten() {
        out.extend_from_slice(&v.to_le_bytes());
    }
    let sum = checksum(&out);
    out.extend_from_slice(&sum);
    out
}

/// The bake a cache file holds, when it is intact and for this key, vertex count and settings.
fn decode_cache(bytes: &[u8], key: &[u8; 16], n: usize, settings: &BakeSettings) -> Option<LocalThickness> {
    let expected = n.checked_mul(16)?.checked_add(CACHE_HEADER_BYTES + 16)?;
    if bytes.len() != expected {
        return None;
    }
    let (body, sum) = bytes.split_at(bytes.len() - 16);
    if checksum(body) != sum {
        return None;
    }
    let mut at = 0;
    let mut take = |len: usize| {
        let s = &body[at..at + len];
        at += len;
        s
    };
    let word = |s: &[u8]| u32::from_le_bytes([s[0], s[1], s[2], s[3]]);
    if take(8) != CACHE_MAGIC || word(take(4)) != CACHE_VERSION || take(16) != key {
        return None;
    }
    if u64::from_le_bytes(take(8).try_into().ok()?) != n as u64 {
        return None;
    }
    let stored: Vec<u32> = (0..8).map(|_| word(take(4))).collect();
    if stored[..] != settings_words(settings)[..8] {
        return None;
    }
    let bake_seconds = f64::from_le_bytes(take(8).try_into().ok()?);
    let mut float = || f32::from_le_bytes(take(4).try_into().unwrap_or([0xff; 4]));
    let mean_chord_mm: Vec<f32> = (0..n).map(|_| float()).collect();
    let value: Vec<[f32; 3]> = (0..n).map(|_| [float(), float(), float()]).collect();
    let sane = mean_chord_mm.iter().all(|c| c.is_finite()) && value.iter().flatten().all(|v| (0.0..=1.0).contains(v));
    sane.then_some(LocalThickness { settings: *settings, mean_chord_mm, value, bake_seconds })
}

// ------------------------------------------------------------------------------------------
// Morph

/// A morph of the mesh toward its bounding sphere (a deformation for testing re-bakes):
/// p′ = lerp(p, c + R·(p − c)/|p − c|, t), c = the centre of the positions' bounding box,
/// R = max |p − c|. For t > 0 the normals are recomputed as area-weighted smooth normals, equal
/// for every vertex at the same position (a [`TriangleMesh`] has one vertex per (position, uv,
/// normal)); tangents are dropped (regenerate them). t = 0 returns the mesh unchanged, normals
/// included. A vertex exactly at c has no direction and stays where it is.
///
/// # Errors
/// [`ThicknessError::MorphT`] for t outside [0, 1] (or NaN); [`ThicknessError::Mesh`] for a
/// non-finite position.
pub fn morph_to_bounding_sphere(mesh: &TriangleMesh, t: f32) -> Result<TriangleMesh, ThicknessError> {
    if !(0.0..=1.0).contains(&t) {
        return Err(ThicknessError::MorphT(t));
    }
    if let Some((i, p)) = mesh.positions.iter().enumerate().find(|(_, p)| !p.is_finite()) {
        return Err(ThicknessError::Mesh(format!("vertex {i}: non-finite position {p}")));
    }
    if t == 0.0 {
        return Ok(mesh.clone());
    }
    let Some(bounds) = Bounds::of(&mesh.positions) else { return Ok(mesh.clone()) };
    let c = bounds.center();
    let radius = mesh.positions.iter().map(|p| p.distance(c)).fold(0.0f32, f32::max);
    let mut out = mesh.clone();
    for p in &mut out.positions {
        if let Some(dir) = (*p - c).try_normalize() {
            let on_sphere = c + dir * radius;
            *p = if t == 1.0 { on_sphere } else { p.lerp(on_sphere, t) };
        }
    }
    let smooth = smooth_normals_per_position(&out);
    out.normals = smooth.iter().map(|n| if *n == Vec3::ZERO { Vec3::Z } else { *n }).collect();
    out.tangents = None;
    Ok(out)
}
