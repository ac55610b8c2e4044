//! Glitter: a field of discrete mirror flakes on the surface (`rouge_measure::finish::Glitter`)
//! and the real-time estimate of a pixel's sparkle from it. This module is the one definition of
//! the flake field (the hash, the flake draw) and the CPU twin of what a shader draws from it;
//! `glitter_study` renders the same field with explicit flakes, supersampled, as the reference.
//!
//! **The flake field.** On the surface's UV space scaled to millimetres (the skin detail's scale,
//! `rouge_model::skin::detail::tiles_per_uv` × its tile's 8 mm), a square grid of cells of edge
//! [`CELL_PER_FLAKE`] × the flake's edge. Each cell holds at most one flake, present with
//! probability density × cell², centred at a point drawn uniformly where the flake stays inside
//! its cell (so flakes never overlap), a square of the flake's edge aligned with the UV axes,
//! with a normal whose slopes (p, q) are Gaussian of σ = spread/√2 per axis: flake normals follow
//! the Beckmann distribution of roughness `spread` (\[Beckmann1963\]). The random numbers are
//! `pcg4d` of the cell's integer coordinates, the level and a seed (\[Jarzynski2020\]'s `pcg4d`
//! listing: a 4-D PCG-style permutation, exact in 32-bit integer arithmetic on every GPU), so a flake belongs
//! to the surface: it moves with it and stays where it is from frame to frame.
//!
//! **A flake sparkles** when its normal lies within half the light's angular radius of the half
//! vector h: then the flake mirrors the light's disc (angular radius δ, [`LIGHT_HALF_ANGLE_RAD`],
//! a *choice*: a studio softbox) into the viewer (for small δ, v lies in the mirrored disc iff
//! ∠(n_flake, h) < δ/2). A lit flake's radiance is its reflectance × the light's radiance,
//! E⊥/(π sin²δ) for a uniform disc of irradiance E⊥; the pixel shows that × the part of its
//! footprint the lit flakes cover ([`sparkle_lobe`]).
//!
//! **The estimator** ([`pixel_sparkle`]) is the box-filtered lit area over the pixel's footprint
//! in the surface's UVs (the parallelogram of the UVs' screen derivatives, taken as its bounding
//! box), on a hierarchy of grids in the spirit of \[Zirr2016\] (a pixel's flakes are taken on
//! the grid level whose cells match the footprint, so that the work per pixel is bounded) with
//! the counts of the coarse levels drawn as binomial laws as \[Deliot2023\] does:
//! - level 0 is the flakes themselves, each lit flake's square intersected with the footprint
//!   exactly (no sampling: antialiased, and stable as the footprint slides over the flakes);
//! - level L ≥ 1 has cells of 2^L fine cells a side; in each, the number of lit flakes is
//!   Binomial(4^L, p) with p = (density × cell²) × P(∠(n, h) < δ/2), the latter
//!   D(h)(n·h) · 2π(1 − cos δ/2) for the Beckmann D (the cone's solid angle times the density
//!   of normals in it: the small-cone limit), drawn by inverse CDF from one uniform number per
//!   coarse cell and bin of half vectors (exact summation up to 64 flakes, a normal law above).
//!   The first [`PLACED_FLAKES`] of the count are *placed*: squares of the flake's edge at
//!   uniform random places in the cell, intersected with the footprint like level 0's, so a
//!   distant flake is a point of light of its own size, not a glow over the coarse cell (spread
//!   over the cell, a flake lit 1.6 times the pixels the explicit flakes light at 1 mm a pixel);
//!   the rest of a larger count is spread over the cell;
//! - the bins: a coarse cell's count is drawn anew when the half vector's slopes cross a line
//!   of its grid of bins (πδ/4 wide in slope, `slope_bin`, offset per cell), as often as
//!   explicit flakes turn on and off, so a distant glitter twinkles as the head turns (with one
//!   draw per cell it stays still: a quarter of the explicit flakes' flicker at 1 mm a pixel);
//! - between levels: the footprint's level λ = log2(across / [`EXPLICIT_CELLS`]) falls between L
//!   and L + 1; each cell of level L + 1 shows its own flakes when its fixed choice number is
//!   below λ − L, else its four children's (no blending: a blend of two levels halves each
//!   flake and lights twice the pixels), so cells change level one by one as the footprint grows.
//!
//! In the lighting pass the probability of a flake per cell is scaled by the layer's thickness
//! over its preset's (`min(1, t / thickness_mm)`: a film thinner than the product's holds
//! proportionally fewer flakes), and the sparkle is a lobe of its layer ([`sparkle_lobe`] ×
//! the layer's coverage, attenuated by the layers above it, as a shimmer's).
//!
//! *Approximations*: the footprint is the bounding box of the UV parallelogram (exact where the
//! UV axes are aligned with the screen's, as on the study's turntable; larger, hence blurrier,
//! elsewhere); a coarse level's flakes are not the fine level's (a distant sparkle is a
//! statistical one: its places, count and twinkle have the explicit flakes' statistics, not
//! their identity); the flakes' tilt is in
//! the UVs' frame; a flake is lit over its whole face or not at all (no partial overlap of the
//! cone and the disc); flakes cast no shadows and are not masked; a coarse cell's placed flakes
//! may overlap, and within a bin its count follows p(h) smoothly.

use glam::{Vec2, Vec3};
use rouge_measure::finish::Glitter;

/// A grid cell's edge in flake edges: a flake is drawn where it stays inside its cell.
pub const CELL_PER_FLAKE: f32 = 2.0;
/// *Choice*: the angular radius of every light as the flakes see it (5°: a 17 cm softbox at
/// 1 m). Sparkles are as many as flakes whose normal lies within half of it of h.
pub const LIGHT_HALF_ANGLE_RAD: f32 = 0.087_266_46;
/// cos(δ/2): a flake sparkles when n·h exceeds it.
fn cos_half_cone() -> f32 {
    (0.5 * LIGHT_HALF_ANGLE_RAD).cos()
}
/// Footprints up to this many cells across are drawn with their flakes only; up to twice as
/// many, with their flakes and level 1's counts; and so on up the levels.
pub const EXPLICIT_CELLS: f32 = 2.0;
/// The coarsest level (cells of 2^8 fine cells a side).
pub const MAX_LEVEL: u32 = 8;
/// Most lit flakes a coarse cell places one by one; the rest of its count is spread over it
/// (above four lit flakes in a cell of at most a footprint, the pixel is lit all over anyway).
pub const PLACED_FLAKES: u32 = 4;
/// The tag (bits 4-7 of the hash's third word) of a coarse cell's light-independent words.
const CELL_TAG: u32 = 15;
/// The width of a coarse cell's bins of half vectors, in slope (tan of the tilt): π/4 × δ, so
/// that a cell draws its lit flakes anew as often as explicit flakes turn on and off. A flake is
/// lit while h lies in a disc of diameter δ around its normal; moving h by dx crosses the discs
/// of 2δ·dx/(πδ²/4) = 8/(πδ)·dx of the lit flakes per lit flake, and a cell whose bins are b wide
/// redraws (all its lit flakes off, as many on) 2/b per unit: b = πδ/4.
fn slope_bin() -> f32 {
    std::f32::consts::FRAC_PI_4 * LIGHT_HALF_ANGLE_RAD
}
/// Up to this many flakes a binomial count is drawn exactly; above, by its normal law.
const EXACT_COUNT: u32 = 64;
/// Most cells of the coarser level a footprint spans per axis beyond the first (bounds the
/// shader's loops: a footprint spans at most 3; only one wider than 3 cells of the coarsest
/// level, 150 mm for 100 µm flakes, is cut).
pub const MAX_SPAN: i32 = 2;

/// The constants of the glitter for WGSL (injected by `shader::shader_source`).
pub fn wgsl_constants() -> String {
    let cone = std::f32::consts::TAU * (1.0 - cos_half_cone());
    let s = LIGHT_HALF_ANGLE_RAD.sin();
    format!(
        "const GLITTER_COS_HALF_CONE: f32 = {:?};\nconst GLITTER_CONE_SR: f32 = {cone:?};\nconst GLITTER_SIN2_LIGHT: f32 = {:?};\n\
         const GLITTER_EXPLICIT_CELLS: f32 = {EXPLICIT_CELLS:?};\nconst GLITTER_MAX_LEVEL: u32 = {MAX_LEVEL}u;\n\
         const GLITTER_EXACT_COUNT: u32 = {EXACT_COUNT}u;\nconst GLITTER_MAX_SPAN: i32 = {MAX_SPAN};\n\
         const GLITTER_PLACED_FLAKES: u32 = {PLACED_FLAKES}u;\nconst GLITTER_CELL_TAG: u32 = {CELL_TAG}u;\n\
         const GLITTER_SLOPE_BIN: f32 = {:?};\n",
        cos_half_cone(),
        s * s,
        slope_bin()
    )
}

/// \[Jarzynski2020\]'s `pcg4d`: four 32-bit words from four, in integer arithmetic that WGSL
/// reproduces bit for bit (wrapping multiplications and additions, shifts).
pub fn pcg4d(v: [u32; 4]) -> [u32; 4] {
    let mut v = v.map(|x| x.wrapping_mul(1_664_525).wrapping_add(1_013_904_223));
    let mix = |v: &mut [u32; 4]| {
        v[0] = v[0].wrapping_add(v[1].wrapping_mul(v[3]));
        v[1] = v[1].wrapping_add(v[2].wrapping_mul(v[0]));
        v[2] = v[2].wrapping_add(v[0].wrapping_mul(v[1]));
        v[3] = v[3].wrapping_add(v[1].wrapping_mul(v[2]));
    };
    mix(&mut v);
    v = v.map(|x| x ^ (x >> 16));
    mix(&mut v);
    v
}

/// A word as a uniform number in [0, 1): its top 24 bits, exact in f32.
pub fn unit(x: u32) -> f32 {
    (x >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// The flake field of a layer's glitter, in f32 as the shader has it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlakeField {
    /// Edge of a grid cell, mm.
    pub cell_mm: f32,
    /// Edge of a flake, mm.
    pub size_mm: f32,
    /// Probability that a cell holds a flake (density × cell²), in (0, 1].
    pub p_flake: f32,
    /// Beckmann roughness of the flakes' normals.
    pub spread: f32,
    /// Seed of the field (the layer's index: two layers' flakes differ).
    pub seed: u32,
}

/// One flake: centre in the surface's mm UVs, normal in the UVs' tangent frame (x along +u,
/// y along +v, z the surface normal).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Flake {
    /// Centre, mm.
    pub centre_mm: Vec2,
    /// Unit normal, tangent frame.
    pub normal: Vec3,
}

impl FlakeField {
    /// The field of `glitter` with `seed`.
    pub fn new(glitter: &Glitter, seed: u32) -> FlakeField {
        let size_mm = (glitter.size_um * 1e-3) as f32;
        let cell_mm = CELL_PER_FLAKE * size_mm;
        let p_flake = (glitter.density_per_mm2 as f32 * cell_mm * cell_mm).clamp(0.0, 1.0);
        FlakeField { cell_mm, size_mm, p_flake, spread: glitter.spread as f32, seed }
    }

    /// The flake of cell (i, j), if the cell holds one.
    pub fn flake(&self, cell: [i32; 2]) -> Option<Flake> {
        let [a, b, c, d] = pcg4d([cell[0] as u32, cell[1] as u32, 0, self.seed]);
        if unit(a) >= self.p_flake {
            return None;
        }
        let room = self.cell_mm - self.size_mm;
        let corner = Vec2::new(cell[0] as f32, cell[1] as f32) * self.cell_mm;
        let centre_mm = corner + Vec2::splat(0.5 * self.size_mm) + Vec2::new(unit(b), unit(c)) * room;
        // Box-Muller from d's two halves: Gaussian slopes of σ = spread/√2.
        let (u1, u2) = ((d >> 16) as f32 * (1.0 / 65536.0), (d & 0xffff) as f32 * (1.0 / 65536.0));
        let r = self.spread * std::f32::consts::FRAC_1_SQRT_2 * (-2.0 * (1.0 - u1).ln()).sqrt();
        let angle = std::f32::consts::TAU * u2;
        let normal = Vec3::new(-r * angle.cos(), -r * angle.sin(), 1.0).normalize();
        Some(Flake { centre_mm, normal })
    }

    /// Whether cell `cell` of `level` (2^level fine cells a side) overlaps the box [lo, hi].
    fn cell_overlaps(&self, level: u32, cell: [i32; 2], lo: Vec2, hi: Vec2) -> bool {
        let cell_mm = self.cell_mm * (1u32 << level) as f32;
        let corner = Vec2::new(cell[0] as f32, cell[1] as f32) * cell_mm;
        corner.x < hi.x && corner.y < hi.y && corner.x + cell_mm > lo.x && corner.y + cell_mm > lo.y
    }

    /// The area inside [lo, hi] of a flake's square centred at `centre_mm`.
    fn square_inside(&self, centre_mm: Vec2, lo: Vec2, hi: Vec2) -> f32 {
        let (a, b) = (centre_mm - 0.5 * self.size_mm, centre_mm + 0.5 * self.size_mm);
        overlap(a.x, b.x, lo.x, hi.x) * overlap(a.y, b.y, lo.y, hi.y)
    }

    /// The area inside [lo, hi] of cell `cell`'s flake when it sparkles for `h` (0 otherwise).
    fn flake_lit_area(&self, cell: [i32; 2], h: Vec3, lo: Vec2, hi: Vec2) -> f32 {
        self.flake(cell).filter(|f| f.lit(h)).map_or(0.0, |f| self.square_inside(f.centre_mm, lo, hi))
    }

    /// The area of the lit flakes inside the box centred at `uv_mm` with half extents
    /// `half_mm`, every cell visited: the exact box filter the estimator approximates (the
    /// reference of `glitter_study`; its cost grows with the footprint's area in cells).
    pub fn lit_area(&self, uv_mm: Vec2, half_mm: Vec2, h: Vec3) -> f32 {
        let (lo, hi) = (uv_mm - half_mm, uv_mm + half_mm);
        let (c0, c1) = ((lo / self.cell_mm).floor(), (hi / self.cell_mm).floor());
        let mut lit = 0.0;
        for j in c0.y as i32..=c1.y as i32 {
            for i in c0.x as i32..=c1.x as i32 {
                lit += self.flake_lit_area([i, j], h, lo, hi);
            }
        }
        lit
    }

    /// Whether a flake covers the point `uv_mm` and sparkles for the half vector `h` (unit,
    /// tangent frame): the integrand the reference supersamples.
    pub fn point_sparkle(&self, uv_mm: Vec2, h: Vec3) -> bool {
        let cell = (uv_mm / self.cell_mm).floor();
        self.flake([cell.x as i32, cell.y as i32]).is_some_and(|f| {
            let d = (uv_mm - f.centre_mm).abs();
            d.x <= 0.5 * self.size_mm && d.y <= 0.5 * self.size_mm && f.lit(h)
        })
    }

    /// The probability that a cell holds a flake that sparkles for `h`: p_flake × D(h)(n·h) ·
    /// 2π(1 − cos δ/2) (module doc), at most p_flake.
    pub fn p_lit(&self, h: Vec3) -> f32 {
        if h.z <= 0.0 {
            return 0.0;
        }
        let cone = std::f32::consts::TAU * (1.0 - cos_half_cone());
        let c2 = (h.z * h.z).max(1e-6);
        let m2 = self.spread * self.spread;
        let d = ((c2 - 1.0) / (m2 * c2)).exp() / (std::f32::consts::PI * m2 * c2 * c2);
        self.p_flake * (d * h.z * cone).min(1.0)
    }
}

impl Flake {
    /// Whether the flake mirrors the light into the viewer: ∠(n, h) < δ/2.
    pub fn lit(&self, h: Vec3) -> bool {
        self.normal.dot(h) > cos_half_cone()
    }
}

/// Length of the overlap of [a0, a1] and [b0, b1].
fn overlap(a0: f32, a1: f32, b0: f32, b1: f32) -> f32 {
    (a1.min(b1) - a0.max(b0)).max(0.0)
}

/// The pixel's footprint in the surface's mm UVs from the UVs' screen derivatives: the half
/// extents of the bounding box of the parallelogram they span.
pub fn footprint_half_mm(duv_dx_mm: Vec2, duv_dy_mm: Vec2) -> Vec2 {
    0.5 * (duv_dx_mm.abs() + duv_dy_mm.abs())
}

/// The part of the footprint centred at `uv_mm` with half extents `half_mm` that lit flakes
/// cover, for the half vector `h` (unit, tangent frame): the estimator of the module doc.
pub fn pixel_sparkle(field: &FlakeField, uv_mm: Vec2, half_mm: Vec2, h: Vec3) -> f32 {
    if h.z <= 0.0 {
        return 0.0;
    }
    let half_mm = half_mm.max(Vec2::splat(1e-6 * field.cell_mm));
    let across = 2.0 * half_mm.max_element() / field.cell_mm;
    let lambda = (across / EXPLICIT_CELLS).log2().clamp(0.0, MAX_LEVEL as f32);
    let level = (lambda.floor() as u32).min(MAX_LEVEL - 1);
    let w = lambda - level as f32;
    let (lo, hi) = (uv_mm - half_mm, uv_mm + half_mm);
    let area = 4.0 * half_mm.x * half_mm.y;
    if level == 0 && w <= 0.0 {
        // Footprints of at most EXPLICIT_CELLS cells: their flakes alone (most of a close-up).
        return (field.lit_area(uv_mm, half_mm, h) / area).min(1.0);
    }
    let counts = Counts::new(field, h);
    // The cells of level + 1 over the footprint; each shows its own flakes with probability w
    // (its choice number below w), else its four children's.
    let parent_mm = field.cell_mm * (2u32 << level) as f32;
    let c0 = (lo / parent_mm).floor();
    let c1 = (hi / parent_mm).floor().min(c0 + MAX_SPAN as f32);
    let mut lit = 0.0;
    for j in c0.y as i32..=c1.y as i32 {
        for i in c0.x as i32..=c1.x as i32 {
            let words = cell_words(field, [i, j], level + 1);
            if unit(words[0]) < w {
                lit += counts.cell_lit(level + 1, [i, j], words, lo, hi);
                continue;
            }
            for (a, b) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                let child = [2 * i + a, 2 * j + b];
                if !field.cell_overlaps(level, child, lo, hi) {
                    continue;
                }
                lit += if level == 0 {
                    field.flake_lit_area(child, h, lo, hi)
                } else {
                    counts.cell_lit(level, child, cell_words(field, child, level), lo, hi)
                };
            }
        }
    }
    (lit / area).min(1.0)
}

/// The words of a coarse cell that do not depend on the light: its choice number between
/// levels (word 0) and the offsets of its grid of half vectors (words 1, 2).
fn cell_words(field: &FlakeField, cell: [i32; 2], level: u32) -> [u32; 4] {
    pcg4d([cell[0] as u32, cell[1] as u32, level | (CELL_TAG << 4), field.seed])
}

/// The lit flakes of the coarse levels for one half vector: their probability per fine cell
/// and the half vector's slopes in units of `slope_bin()`.
struct Counts<'a> {
    field: &'a FlakeField,
    p: f32,
    slope: Vec2,
}

impl Counts<'_> {
    fn new(field: &FlakeField, h: Vec3) -> Counts<'_> {
        Counts { field, p: field.p_lit(h), slope: Vec2::new(h.x, h.y) / (h.z * slope_bin()) }
    }

    /// The area inside [lo, hi] of the lit flakes of coarse cell `cell` at `level` ≥ 1 (its
    /// [`cell_words`] `words`; a cell outside the box gives 0): a Binomial(4^level, p) count
    /// drawn for the cell's bin of half vectors, its first [`PLACED_FLAKES`] flakes placed in the
    /// cell, the rest spread over it.
    fn cell_lit(&self, level: u32, cell: [i32; 2], words: [u32; 4], lo: Vec2, hi: Vec2) -> f32 {
        let field = self.field;
        let cell_mm = field.cell_mm * (1u32 << level) as f32;
        let corner = Vec2::new(cell[0] as f32, cell[1] as f32) * cell_mm;
        let bin = (self.slope + Vec2::new(unit(words[1]), unit(words[2]))).floor();
        let angle_tag = ((bin.x as i32 as u32) & 0xfff) << 8 | ((bin.y as i32 as u32) & 0xfff) << 20;
        let draw = |m: u32| pcg4d([cell[0] as u32, cell[1] as u32, level | m << 4 | angle_tag, field.seed]);
        let n = (1u32 << level) * (1u32 << level);
        let count = binomial_quantile(n, self.p, unit(draw(0)[0]));
        let placed = (count as u32).min(PLACED_FLAKES);
        let room = cell_mm - field.size_mm;
        let mut lit = 0.0;
        for m in 1..=placed {
            let r = draw(m);
            let centre = corner + Vec2::splat(0.5 * field.size_mm) + Vec2::new(unit(r[0]), unit(r[1])) * room;
            lit += field.square_inside(centre, lo, hi);
        }
        let inside = overlap(corner.x, corner.x + cell_mm, lo.x, hi.x)
            * overlap(corner.y, corner.y + cell_mm, lo.y, hi.y)
            / (cell_mm * cell_mm);
        lit + (count - placed as f32) * field.size_mm * field.size_mm * inside
    }
}

/// The `u`-quantile of Binomial(n, p): the smallest k with CDF(k) > u, summed exactly while the
/// mean is below 32 (and k ≤ 64); above, the normal law's quantile, continuous and clamped to
/// [0, n], with Φ⁻¹(u) taken as the logistic law's of the same variance, (√3/π) ln(u/(1 − u))
/// (*approximation*: its tails are heavier than the normal's; its mean and variance are exact).
pub fn binomial_quantile(n: u32, p: f32, u: f32) -> f32 {
    if p <= 0.0 || n == 0 {
        return 0.0;
    }
    let mean = n as f32 * p;
    let q = 1.0 - p;
    if mean < 0.5 * EXACT_COUNT as f32 && q > 0.0 {
        // pmf(0) = q^n through exp(n ln q), then pmf(k+1) = pmf(k) (n − k)/(k + 1) p/q.
        let mut pmf = (n as f32 * q.ln()).exp();
        let mut cdf = pmf;
        let mut k = 0u32;
        while cdf <= u && k < EXACT_COUNT.min(n) {
            pmf *= (n - k) as f32 / (k + 1) as f32 * p / q;
            k += 1;
            cdf += pmf;
        }
        return k as f32;
    }
    let u = u.clamp(1e-6, 1.0 - 1e-6);
    let z = (u / (1.0 - u)).ln() * (3.0f32.sqrt() / std::f32::consts::PI);
    (mean + (mean * q).sqrt() * z).clamp(0.0, n as f32)
}

/// The glitter's lobe per unit irradiance E·(n·l): a lit fraction `sparkle` of the footprint
/// shows the light's radiance E⊥/(π sin²δ) × the flakes' reflectance, so the lobe is
/// sparkle · colour / (π sin²δ (n·l)) (`n_dot_l` at least 1e-3).
pub fn sparkle_lobe(sparkle: f32, color: [f32; 3], n_dot_l: f32) -> [f32; 3] {
    let s = LIGHT_HALF_ANGLE_RAD.sin();
    let k = sparkle / (std::f32::consts::PI * s * s * n_dot_l.max(1e-3));
    color.map(|c| c * k)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn field() -> FlakeField {
        FlakeField::new(&Glitter { size_um: 100.0, density_per_mm2: 16.0, color: [1.0; 3], spread: 0.3 }, 7)
    }

    #[test]
    fn pcg4d_is_the_papers() {
        // Jarzynski & Olano's pcg4d of (0, 0, 0, 0): every word 1013904223 after the LCG step,
        // then the two mixing rounds and the xorshift, worked by hand in u64 arithmetic mod 2³².
        let m = |a: u64, b: u64| (a * b) & 0xffff_ffff;
        let s = |a: u64, b: u64| (a + b) & 0xffff_ffff;
        let mut v = [1_013_904_223u64; 4];
        let round = |v: &mut [u64; 4]| {
            v[0] = s(v[0], m(v[1], v[3]));
            v[1] = s(v[1], m(v[2], v[0]));
            v[2] = s(v[2], m(v[0], v[1]));
            v[3] = s(v[3], m(v[1], v[2]));
        };
        round(&mut v);
        v = v.map(|x| x ^ (x >> 16));
        round(&mut v);
        assert_eq!(pcg4d([0; 4]), v.map(|x| x as u32));
        assert_ne!(pcg4d([1, 0, 0, 0]), pcg4d([0, 1, 0, 0]));
    }

    #[test]
    fn the_field_has_its_density_and_its_normals_their_spread() {
        let f = field();
        let (mut count, mut slope2) = (0usize, 0.0f64);
        let cells = 200;
        for j in -cells / 2..cells / 2 {
            for i in -cells / 2..cells / 2 {
                if let Some(flake) = f.flake([i, j]) {
                    count += 1;
                    // Inside its cell, whole.
                    let lo = Vec2::new(i as f32, j as f32) * f.cell_mm;
                    let d = flake.centre_mm - lo;
                    assert!(
                        d.min_element() >= 0.5 * f.size_mm - 1e-6
                            && d.max_element() <= f.cell_mm - 0.5 * f.size_mm + 1e-6
                    );
                    let n = flake.normal;
                    slope2 += ((n.x / n.z).powi(2) + (n.y / n.z).powi(2)) as f64;
                }
            }
        }
        let area_mm2 = (cells as f64 * f.cell_mm as f64).powi(2);
        let density = count as f64 / area_mm2;
        assert!((density / 16.0 - 1.0).abs() < 0.03, "{density} per mm²");
        // Beckmann of roughness m: the mean squared slope is m².
        let ms = slope2 / count as f64;
        assert!((ms / 0.09 - 1.0).abs() < 0.05, "mean squared slope {ms}");
    }

    #[test]
    fn the_estimate_is_the_lit_area_and_its_mean_the_expected_one() {
        let f = field();
        let h = Vec3::new(0.05, -0.03, 1.0).normalize();
        // A footprint of one cell over many positions: the exact lit area, the mean over the
        // surface tending to p_lit × (size/cell)².
        let expected = f.p_lit(h) * (f.size_mm / f.cell_mm).powi(2);
        let mut sum = 0.0f64;
        let mut n = 0;
        for j in 0..200 {
            for i in 0..200 {
                let uv = Vec2::new(i as f32, j as f32) * f.cell_mm + 0.37;
                let s = pixel_sparkle(&f, uv, Vec2::splat(0.5 * f.cell_mm), h);
                assert!((0.0..=1.0).contains(&s));
                sum += s as f64;
                n += 1;
            }
        }
        let mean = sum / n as f64;
        assert!((mean / expected as f64 - 1.0).abs() < 0.15, "{mean} against {expected}");
        // The coarse levels have the same mean (binomial counts of the same p).
        let mut coarse = 0.0f64;
        for j in 0..40 {
            for i in 0..40 {
                let uv = Vec2::new(i as f32, j as f32) * 3.1;
                coarse += pixel_sparkle(&f, uv, Vec2::splat(1.5), h) as f64;
            }
        }
        let coarse = coarse / 1600.0;
        assert!((coarse / expected as f64 - 1.0).abs() < 0.1, "{coarse} against {expected}");
        // Nothing below the horizon, nothing NaN for degenerate footprints.
        assert_eq!(pixel_sparkle(&f, Vec2::ZERO, Vec2::splat(0.1), Vec3::new(1.0, 0.0, -0.1)), 0.0);
        assert!(pixel_sparkle(&f, Vec2::ZERO, Vec2::ZERO, h).is_finite());
        assert!(pixel_sparkle(&f, Vec2::ZERO, Vec2::splat(1e9), h).is_finite());
    }

    #[test]
    fn binomial_quantiles_have_the_laws_mean() {
        for (n, p) in [(4u32, 0.02f32), (16, 0.1), (256, 0.05), (65536, 0.01)] {
            let k = 4000;
            let mean: f64 =
                (0..k).map(|i| binomial_quantile(n, p, (i as f32 + 0.5) / k as f32) as f64).sum::<f64>() / k as f64;
            let want = n as f64 * p as f64;
            assert!((mean / want - 1.0).abs() < 0.03, "n {n}, p {p}: {mean} against {want}");
        }
        assert_eq!(binomial_quantile(10, 0.0, 0.99), 0.0);
        assert_eq!(binomial_quantile(10, 1.0, 0.5), 10.0);
    }
}
