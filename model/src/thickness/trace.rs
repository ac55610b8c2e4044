//! Tracing one vertex's inward rays: the ray pattern and a watertight ray-triangle test.

use glam::{Vec3, Vec3A};
use obvhs::cwbvh::CwBvh;
use obvhs::ray::{Ray, RayHit};
use obvhs::triangle::Triangle;

use super::BakeSettings;

/// What every vertex's rays share.
pub(super) struct Tracer<'a> {
    pub(super) bvh: &'a CwBvh,
    pub(super) triangles: &'a [Triangle],
    pub(super) settings: &'a BakeSettings,
    pub(super) epsilon_mm: f32,
}

impl Tracer<'_> {
    /// (mean chord mm, mean weight) of the vertex at `p` with unit outward normal `n`.
    pub(super) fn vertex(&self, p: Vec3, n: Vec3, vertex: u64) -> (f32, [f32; 3]) {
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

/// A ray prepared for the watertight ray-triangle test of \[Woop2013\] (section 3, with its
/// double-precision fallback on edges): the ray is sheared onto +z so that the three edge
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
pub(crate) fn splitmix64(x: u64) -> u64 {
    let mut z = x.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The low 24 bits of `x` as a number in [0, 1).
fn unit_f32(x: u64) -> f32 {
    (x & 0xff_ffff) as f32 / (1u32 << 24) as f32
}
