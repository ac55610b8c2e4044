//! [`SkinMaps::generate`]: a tone, the default head's anatomy ([`super::anatomy`]) and the
//! conditions ([`SkinConditions`]), deterministic for a seed.
//!
//! **Seams.** Everything smooth comes from the region masks, which are per-vertex weights of the
//! 3D head rasterised per face (a seam's two sides carry the same weights). Everything small
//! (spots, veins, the blotches of redness) is placed in 3D: spots are dabs of the brush
//! ([`crate::paint::apply_dab`]) on the [`SurfaceMap`], which reach along the surface whatever
//! the UV islands, and the blotches are a noise of the surface position. So no condition stops at
//! a UV island's border.
//!
//! **Sizes and counts.** A spot's parameter change is one of the database ratios of
//! [`super::anatomy`] (how dark, how red); its size comes from the clinical description cited at
//! each condition; how many there are at amount 1 is a *choice* (said so at each constant).
//! Every condition has its own random stream (the seed mixed with the condition), so adding one
//! does not move another's spots.

use super::anatomy::{
    AnatomyRegion, BLOOD_SPREAD, BLOOD_STEP, Factors, LogFactors, MELANIN_RANGE, MELANIN_SPREAD, SATURATION_LOW,
};
use super::{Condition, SkinConditions, SkinMaps};
use crate::error::{ModelError, Result};
use crate::look::ThicknessMap;
use crate::paint::{Brush, BrushMode, Falloff, Reach, SurfaceMap, apply_dab, stroke};
use crate::thickness::splitmix64;
use glam::Vec3;
use rouge_measure::skin::SkinParams;

/// Smallest map [`SkinMaps::generate`] makes, texels a side.
pub const MIN_SIZE_PX: u32 = 16;
/// Largest map [`SkinMaps::generate`] makes, texels a side (4096² × 5 channels × 4 bytes = 320 MiB).
pub const MAX_SIZE_PX: u32 = 4096;

/// How one spot condition is drawn: where, how large, how many.
struct Spots {
    /// The regions it appears in (the placement weight is the largest of their masks).
    regions: &'static [AnatomyRegion],
    /// Radius range, mm.
    radius_mm: (f32, f32),
    /// The brush's hardness (1 = a sharp edge).
    hardness: f32,
    /// Spots at amount 1.
    count: f64,
}

/// Ephelides: small light-brown macules on sun-exposed skin, on the face the cheeks and nose
/// (\[Praetorius2014\]); the forehead is as exposed. *Choice*: 1-3 mm across (radius 0.5-1.5
/// mm), soft-edged, 300 on the face at amount 1.
const FRECKLES: Spots = Spots {
    regions: &[AnatomyRegion::Cheeks, AnatomyRegion::Nose, AnatomyRegion::Forehead],
    radius_mm: (0.5, 1.5),
    hardness: 0.3,
    count: 300.0,
};

/// Melanocytic naevi: anywhere on the facial skin; a common mole is under the 6 mm that the
/// "D" of the ABCD rule flags (\[Abbasi2004\]): radius 1-2.5 mm, a sharp edge. *Choice*: 12 at
/// amount 1.
const MOLES: Spots = Spots {
    regions: &[
        AnatomyRegion::Cheeks,
        AnatomyRegion::Nose,
        AnatomyRegion::Forehead,
        AnatomyRegion::Chin,
        AnatomyRegion::Temples,
        AnatomyRegion::UnderEye,
    ],
    radius_mm: (1.0, 2.5),
    hardness: 0.7,
    count: 12.0,
};

/// Inflammatory papules: acne affects the face in almost every case, the forehead, cheeks and
/// chin (\[Williams2012\]); papules are the small inflamed lesions, nodules the large ones.
/// *Choice*: 2-5 mm across (radius 1-2.5 mm) with a soft inflamed rim, 40 at amount 1.
const ACNE: Spots = Spots {
    regions: &[AnatomyRegion::Forehead, AnatomyRegion::Cheeks, AnatomyRegion::Chin, AnatomyRegion::Nose],
    radius_mm: (1.0, 2.5),
    hardness: 0.1,
    count: 40.0,
};

/// Post-inflammatory hyperpigmentation: brown macules where the inflammation (acne) was
/// (\[Davis2010\]). *Choice*: a little larger than the papules (radius 1.5-3 mm), 30 at amount 1.
const HYPERPIGMENTATION: Spots = Spots { radius_mm: (1.5, 3.0), hardness: 0.2, count: 30.0, ..ACNE };

/// Visible veins on the temples and around the eyes (\[Roh2009\]: the lower lid's thin skin
/// shows its veins; the superficial temporal veins cross the temple). Radius 0.4-0.8 mm
/// (*choice*: a visible superficial vein 1-1.5 mm wide), each a wandering line 12-30 mm long
/// (*choice*). *Choice*: 6 at amount 1.
const VEINS: Spots = Spots {
    regions: &[AnatomyRegion::Temples, AnatomyRegion::Eyelids, AnatomyRegion::UnderEye],
    radius_mm: (0.4, 0.8),
    hardness: 0.5,
    count: 6.0,
};

/// Regions of rosacea's persistent centrofacial erythema: cheeks and nose (\[Gallo2018\]).
const REDNESS_REGIONS: &[AnatomyRegion] = &[AnatomyRegion::Cheeks, AnatomyRegion::Nose];

/// *Choice*: the size of rosacea's blotches, mm (the scale of the noise that modulates it).
const REDNESS_BLOTCH_MM: f32 = 7.0;

/// A vein's length range, mm (*choice*, see [`VEINS`]).
const VEIN_LENGTH_MM: (f32, f32) = (12.0, 30.0);

/// The SplitMix64 generator ([`splitmix64`] of a running state).
struct Rng(u64);

impl Rng {
    fn new(seed: u64, condition: Condition) -> Rng {
        Rng(splitmix64(seed ^ splitmix64(condition as u64 + 1)))
    }

    fn next_u64(&mut self) -> u64 {
        let out = splitmix64(self.0);
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        out
    }

    /// Uniform in [0, 1).
    fn unit(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32
    }

    fn range(&mut self, (lo, hi): (f32, f32)) -> f32 {
        lo + (hi - lo) * self.unit()
    }

    /// A direction uniform on the sphere.
    fn direction(&mut self) -> Vec3 {
        let z = 2.0 * self.unit() - 1.0;
        let phi = std::f32::consts::TAU * self.unit();
        let r = (1.0 - z * z).max(0.0).sqrt();
        Vec3::new(r * phi.cos(), r * phi.sin(), z)
    }
}

/// Value noise of a 3D point in [0, 1): a hash of the lattice corners, interpolated trilinearly
/// with smoothstep weights; continuous, so seam-free on the surface.
fn value_noise(p: Vec3, seed: u64) -> f32 {
    let cell = p.floor();
    let f = p - cell;
    let s = f * f * (Vec3::splat(3.0) - 2.0 * f);
    let corner = |dx: i64, dy: i64, dz: i64| {
        let k = |c: f32, d: i64| (c as i64 + d) as u64;
        let h = splitmix64(seed ^ k(cell.x, dx)) ^ splitmix64(k(cell.y, dy).rotate_left(21));
        let h = splitmix64(h ^ k(cell.z, dz).rotate_left(42));
        (h >> 40) as f32 / (1u64 << 24) as f32
    };
    let lerp = |a: f32, b: f32, t: f32| a + (b - a) * t;
    let x = |dy, dz| lerp(corner(0, dy, dz), corner(1, dy, dz), s.x);
    lerp(lerp(x(0, 0), x(1, 0), s.y), lerp(x(0, 1), x(1, 1), s.y), s.z)
}

/// OBJ-convention UV of texel (x, y)'s centre in a `w × h` map.
fn texel_uv(x: u32, y: u32, w: u32, h: u32) -> (f32, f32) {
    ((x as f32 + 0.5) / w as f32, 1.0 - (y as f32 + 0.5) / h as f32)
}

/// The largest of `regions`' mask weights at UV (u, v).
fn placement(regions: &[AnatomyRegion], u: f32, v: f32) -> f64 {
    regions.iter().map(|r| r.weight_uv(u, v)).fold(0.0, f64::max)
}

/// The covered texels where `regions` place anything, with the cumulative placement weight,
/// for drawing spot centres in proportion to it.
struct Candidates {
    texels: Vec<(u32, u32)>,
    cumulative: Vec<f64>,
}

impl Candidates {
    fn of(regions: &[AnatomyRegion], surface: &SurfaceMap) -> Candidates {
        let (w, h) = (surface.width, surface.height);
        let (mut texels, mut cumulative, mut total) = (Vec::new(), Vec::new(), 0.0);
        for y in 0..h {
            for x in 0..w {
                let (u, v) = texel_uv(x, y, w, h);
                let weight = placement(regions, u, v);
                if weight > 0.0 && surface.position(x, y).is_some() {
                    total += weight;
                    texels.push((x, y));
                    cumulative.push(total);
                }
            }
        }
        Candidates { texels, cumulative }
    }

    fn draw(&self, rng: &mut Rng) -> Option<(u32, u32)> {
        let total = *self.cumulative.last()?;
        let target = f64::from(rng.unit()) * total;
        let i = self.cumulative.partition_point(|&c| c <= target).min(self.texels.len() - 1);
        Some(self.texels[i])
    }
}

/// A brush that paints a spot's weight (the "thickness" is the weight, 0-1) along the surface,
/// from nowhere in particular (no facing or occlusion test), unmirrored.
fn spot_brush(radius_mm: f32, hardness: f32, weight: f32) -> Brush {
    Brush {
        mode: BrushMode::Paint,
        radius_mm,
        thickness_mm: weight,
        flow: 1.0,
        hardness,
        falloff: Falloff::Smooth,
        mirror: false,
        mirror_plane: None,
        spacing: 0.25,
        reach: Reach::Surface,
        front_faces_only: false,
        occlusion: false,
    }
}

/// The weight map (0-1 per texel) of a spot condition at `amount`: round(amount · count) spots
/// at centres drawn by placement weight, each of a random radius and a weight in [0.6, 1].
fn paint_spots(spots: &Spots, condition: Condition, amount: f64, seed: u64, surface: &SurfaceMap) -> ThicknessMap {
    let mut map = empty_like(surface);
    let n = (amount * spots.count).round() as usize;
    let candidates = Candidates::of(spots.regions, surface);
    let mut rng = Rng::new(seed, condition);
    for _ in 0..n {
        let Some((x, y)) = candidates.draw(&mut rng) else { break };
        let (radius, weight) = (rng.range(spots.radius_mm), rng.range((0.6, 1.0)));
        if let Some(centre) = surface.position(x, y) {
            apply_dab(&mut map, surface, &spot_brush(radius, spots.hardness, weight), centre);
        }
    }
    map
}

/// The weight map of the veins at `amount`: each a line wandering along the surface from a
/// drawn start, 1 mm a step, turning a little each step, until its length or the edge of its
/// regions, drawn as one brush stroke.
fn paint_veins(amount: f64, seed: u64, surface: &SurfaceMap) -> ThicknessMap {
    let mut map = empty_like(surface);
    let n = (amount * VEINS.count).round() as usize;
    let candidates = Candidates::of(VEINS.regions, surface);
    let mut rng = Rng::new(seed, Condition::Veins);
    let (w, h) = (surface.width, surface.height);
    for _ in 0..n {
        let Some((x, y)) = candidates.draw(&mut rng) else { break };
        let (Some(start), Some(normal)) = (surface.position(x, y), surface.normal(x, y)) else { continue };
        let (radius, length) = (rng.range(VEINS.radius_mm), rng.range(VEIN_LENGTH_MM));
        let tangent = |d: Vec3, n: Vec3| (d - n * d.dot(n)).normalize_or_zero();
        let mut dir = tangent(rng.direction(), normal);
        let mut points = vec![start];
        let mut p = start;
        while (points.len() as f32) < length && dir != Vec3::ZERO {
            let Some(next) = surface.nearest_on_surface(p + dir, 3.0) else { break };
            let Some((tx, ty)) = surface.nearest_texel(next, 3.0) else { break };
            let (u, v) = texel_uv(tx, ty, w, h);
            if placement(VEINS.regions, u, v) < 0.1 {
                break;
            }
            let n = surface.normal(tx, ty).unwrap_or(normal);
            dir = tangent((next - p).normalize_or_zero() + 0.35 * rng.direction(), n);
            points.push(next);
            p = next;
        }
        stroke(&mut map, surface, &spot_brush(radius, VEINS.hardness, rng.range((0.6, 1.0))), &points);
    }
    map
}

fn empty_like(surface: &SurfaceMap) -> ThicknessMap {
    let n = surface.width as usize * surface.height as usize;
    ThicknessMap { width: surface.width, height: surface.height, mm: vec![0.0; n] }
}

/// The conditions' weight maps, painted once on the surface.
struct Painted {
    freckles: Option<ThicknessMap>,
    moles: Option<ThicknessMap>,
    acne: Option<ThicknessMap>,
    hyperpigmentation: Option<ThicknessMap>,
    veins: Option<ThicknessMap>,
}

impl Painted {
    fn new(conditions: &SkinConditions, seed: u64, surface: &SurfaceMap) -> Painted {
        let spots = |spots: &Spots, c: Condition| {
            let a = conditions.get(c);
            (a > 0.0).then(|| paint_spots(spots, c, a, seed, surface))
        };
        let veins = conditions.get(Condition::Veins);
        Painted {
            freckles: spots(&FRECKLES, Condition::Freckles),
            moles: spots(&MOLES, Condition::Moles),
            acne: spots(&ACNE, Condition::Acne),
            hyperpigmentation: spots(&HYPERPIGMENTATION, Condition::Hyperpigmentation),
            veins: (veins > 0.0).then(|| paint_veins(veins, seed, surface)),
        }
    }
}

/// The value of a weight map at texel i (0 without the map).
fn at(map: &Option<ThicknessMap>, i: usize) -> f64 {
    map.as_ref().and_then(|m| m.mm.get(i)).map_or(0.0, |&v| f64::from(v))
}

impl SkinMaps {
    /// Skin maps of the default head, `size_px` × `size_px`: `base` (a tone, see
    /// [`rouge_measure::skin::skin_tone`]) with the anatomy of [`super::anatomy`] and
    /// `conditions`, the same for the same seed. Builds the head's [`SurfaceMap`] when a
    /// condition is present (the anatomy alone needs none); [`SkinMaps::generate_on`] takes one
    /// already built.
    ///
    /// # Errors
    /// [`ModelError::Invalid`] for a `base` that fails [`SkinParams::validate`] or a size outside
    /// [`MIN_SIZE_PX`]..=[`MAX_SIZE_PX`].
    pub fn generate(base: &SkinParams, conditions: &SkinConditions, seed: u64, size_px: u32) -> Result<SkinMaps> {
        check(base, size_px)?;
        if conditions.is_none() {
            return Ok(compose(base, conditions, seed, size_px, size_px, None));
        }
        let mesh = crate::mesh::load_mesh(None, 1.0, 1)?;
        let surface = SurfaceMap::build(&mesh, size_px, size_px);
        Ok(compose(base, conditions, seed, size_px, size_px, Some(&surface)))
    }

    /// [`SkinMaps::generate`] on a surface map already built (of the default head or a posed
    /// one with the same UVs), at its size.
    ///
    /// # Errors
    /// As [`SkinMaps::generate`] (the surface's width and height must be equal and in range).
    pub fn generate_on(
        base: &SkinParams,
        conditions: &SkinConditions,
        seed: u64,
        surface: &SurfaceMap,
    ) -> Result<SkinMaps> {
        check(base, surface.width)?;
        if surface.height != surface.width {
            return Err(ModelError::Invalid(format!(
                "skin maps are square: the surface map is {}×{}",
                surface.width, surface.height
            )));
        }
        Ok(compose(base, conditions, seed, surface.width, surface.height, Some(surface)))
    }
}

fn check(base: &SkinParams, size_px: u32) -> Result<()> {
    base.validate().map_err(|e| ModelError::Invalid(format!("skin maps' base: {e}")))?;
    check_size(size_px)
}

fn check_size(size_px: u32) -> Result<()> {
    if !(MIN_SIZE_PX..=MAX_SIZE_PX).contains(&size_px) {
        return Err(ModelError::Invalid(format!(
            "skin maps of {size_px} texels a side: the size must be in {MIN_SIZE_PX}..={MAX_SIZE_PX}"
        )));
    }
    Ok(())
}

/// What a condition does to the skin where it is at full strength (weight 1: the centre of a spot,
/// or the middle of its region at amount 1); weights in between scale the logarithms.
///
/// - Freckles and post-inflammatory hyperpigmentation: melanin × [`MELANIN_SPREAD`] (brown
///   macules as dark as the database's 95th percentile is to its median).
/// - Moles: melanin × [`MELANIN_RANGE`] (the darkest spots: the database's 5th to 95th percentile).
/// - Redness and acne: blood × [`BLOOD_SPREAD`] (as red as the reddest measured skin).
/// - Under-eye darkness: melanin first, then deoxygenated blood (\[Matsui2015\]); more melanin
///   and more haemoglobin measured in dark circles (\[MacMary2019\]): melanin ×
///   [`MELANIN_SPREAD`], saturation × [`SATURATION_LOW`], blood × [`BLOOD_STEP`].
/// - Veins: blood at the reddest measured skin's fraction, at the least oxygenated measured skin's
///   saturation (blood × [`BLOOD_SPREAD`], saturation × [`SATURATION_LOW`]); the two-layer model
///   cannot put the vessel deep, which is what makes veins look blue (\[Kienle1996\]), so they
///   come out dark and purplish.
pub fn condition_factors(c: Condition) -> Factors {
    match c {
        Condition::Freckles | Condition::Hyperpigmentation => Factors { melanin: MELANIN_SPREAD, ..Factors::NONE },
        Condition::Moles => Factors { melanin: MELANIN_RANGE, ..Factors::NONE },
        Condition::Redness | Condition::Acne => Factors { blood: BLOOD_SPREAD, ..Factors::NONE },
        Condition::UnderEye => {
            Factors { melanin: MELANIN_SPREAD, blood: BLOOD_STEP, oxygen: SATURATION_LOW, ..Factors::NONE }
        }
        Condition::Veins => Factors { blood: BLOOD_SPREAD, oxygen: SATURATION_LOW, ..Factors::NONE },
    }
}

/// `base` where condition `c` is at full strength ([`condition_factors`]), clamped into the
/// model's ranges as the maps are: the skin of a spot's centre.
pub fn at_full_strength(base: &SkinParams, c: Condition) -> SkinParams {
    let mut l = LogFactors::default();
    l.add(condition_factors(c), 1.0);
    super::clamp_params(&l.apply(base))
}

/// Where each condition is: its weight per texel (1 at the centre of a spot, or where its region is
/// full at amount 1), painted once.
struct ConditionField<'a> {
    painted: Option<Painted>,
    redness: f64,
    under_eye: f64,
    noise_seed: u64,
    surface: Option<&'a SurfaceMap>,
}

impl<'a> ConditionField<'a> {
    fn new(conditions: &SkinConditions, seed: u64, surface: Option<&'a SurfaceMap>) -> ConditionField<'a> {
        ConditionField {
            painted: surface.map(|s| Painted::new(conditions, seed, s)),
            redness: conditions.get(Condition::Redness),
            under_eye: conditions.get(Condition::UnderEye),
            noise_seed: splitmix64(seed ^ splitmix64(Condition::Redness as u64 + 101)),
            surface,
        }
    }

    /// Every condition's weight at texel (x, y) of a w × h map, in [`Condition::ALL`]'s order.
    fn weights(&self, x: u32, y: u32, w: u32, h: u32) -> [f64; 7] {
        let (u, v) = texel_uv(x, y, w, h);
        let i = y as usize * w as usize + x as usize;
        let mut out = [0.0; 7];
        if self.redness > 0.0 {
            let blotch = self
                .surface
                .and_then(|s| s.position(x, y))
                .map_or(1.0, |p| 0.5 + f64::from(value_noise(p / REDNESS_BLOTCH_MM, self.noise_seed)));
            out[Condition::Redness as usize] = placement(REDNESS_REGIONS, u, v) * self.redness * blotch;
        }
        if self.under_eye > 0.0 {
            out[Condition::UnderEye as usize] = AnatomyRegion::UnderEye.weight_uv(u, v) * self.under_eye;
        }
        if let Some(p) = &self.painted {
            out[Condition::Freckles as usize] = at(&p.freckles, i);
            out[Condition::Moles as usize] = at(&p.moles, i);
            out[Condition::Acne as usize] = at(&p.acne, i);
            out[Condition::Hyperpigmentation as usize] = at(&p.hyperpigmentation, i);
            out[Condition::Veins as usize] = at(&p.veins, i);
        }
        out
    }
}

/// The maps: per texel the anatomy's log factors plus each condition's, applied to `base`.
fn compose(
    base: &SkinParams,
    conditions: &SkinConditions,
    seed: u64,
    w: u32,
    h: u32,
    surface: Option<&SurfaceMap>,
) -> SkinMaps {
    let field = ConditionField::new(conditions, seed, surface);
    SkinMaps::from_fn(w, h, base, |x, y| {
        let (u, v) = texel_uv(x, y, w, h);
        let mut l = LogFactors::anatomy_at(u, v);
        for (c, weight) in Condition::ALL.into_iter().zip(field.weights(x, y, w, h)) {
            if weight > 0.0 {
                l.add(condition_factors(c), weight);
            }
        }
        l.apply(base)
    })
}

/// Where `conditions` are on the default head, `size_px` × `size_px` in the maps' UV layout: per
/// texel the largest weight of any condition (1 at a spot's centre or where a region is full at
/// amount 1), for the seed the maps use. A concealer's thickness map: cover what the conditions
/// drew and nothing else (`rouge skin maps --conditions-mask`).
///
/// # Errors
/// A size outside [`MIN_SIZE_PX`]..=[`MAX_SIZE_PX`], or the head failing to load.
pub fn conditions_mask(conditions: &SkinConditions, seed: u64, size_px: u32) -> Result<ThicknessMap> {
    check_size(size_px)?;
    let surface = if conditions.is_none() {
        None
    } else {
        let mesh = crate::mesh::load_mesh(None, 1.0, 1)?;
        Some(SurfaceMap::build(&mesh, size_px, size_px))
    };
    let field = ConditionField::new(conditions, seed, surface.as_ref());
    let mut mask = ThicknessMap { width: size_px, height: size_px, mm: vec![0.0; (size_px * size_px) as usize] };
    for y in 0..size_px {
        for x in 0..size_px {
            let w = field.weights(x, y, size_px, size_px).into_iter().fold(0.0, f64::max);
            mask.mm[(y * size_px + x) as usize] = w.clamp(0.0, 1.0) as f32;
        }
    }
    Ok(mask)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn condition_weights_follow_the_conditions_order() {
        // ConditionField::weights indexes by discriminant; ALL lists them in the same order.
        for (i, c) in Condition::ALL.into_iter().enumerate() {
            assert_eq!(c as usize, i, "{c:?}");
        }
    }

    #[test]
    fn the_conditions_mask_is_where_the_maps_moved() {
        let size = 64;
        let conditions: SkinConditions = "moles=1,redness=0.6".parse().expect("conditions");
        let mask = conditions_mask(&conditions, 5, size).expect("mask");
        let base = rouge_measure::skin::skin_tone("medium").expect("tone").params;
        let with = SkinMaps::generate(&base, &conditions, 5, size).expect("maps");
        let without = SkinMaps::generate(&base, &SkinConditions::default(), 5, size).expect("maps");
        let (mut inside, mut moved_outside) = (0, 0);
        for y in 0..size {
            for x in 0..size {
                let w = mask.mm[(y * size + x) as usize];
                assert!((0.0..=1.0).contains(&w), "{w}");
                let (a, b) = (with.texel(x, y), without.texel(x, y));
                let moved = (a.melanin_fraction / b.melanin_fraction - 1.0).abs() > 1e-6
                    || (a.blood_fraction / b.blood_fraction - 1.0).abs() > 1e-6;
                if w > 0.0 {
                    inside += 1;
                } else if moved {
                    moved_outside += 1;
                }
            }
        }
        assert!(inside > 20, "{inside} texels in the mask");
        assert_eq!(moved_outside, 0, "the maps moved where the mask is 0");
        assert!(conditions_mask(&SkinConditions::default(), 5, size).expect("mask").mm.iter().all(|&w| w == 0.0));
        assert!(conditions_mask(&conditions, 5, 4).unwrap_err().to_string().contains("size"));
    }

    #[test]
    fn noise_is_continuous_bounded_and_seeded() {
        let mut worst = 0.0f32;
        for k in 0..2000 {
            let p = Vec3::new(k as f32 * 0.0137, (k as f32 * 0.31).sin() * 5.0, -3.3 + k as f32 * 0.002);
            let (a, b) = (value_noise(p, 7), value_noise(p + Vec3::splat(1e-3), 7));
            assert!((0.0..1.0).contains(&a), "{a}");
            worst = worst.max((a - b).abs());
        }
        assert!(worst < 0.01, "a 1 µm step changes the noise by {worst}");
        assert_ne!(value_noise(Vec3::new(0.5, 0.5, 0.5), 1), value_noise(Vec3::new(0.5, 0.5, 0.5), 2));
    }

    #[test]
    fn the_random_stream_is_uniform_enough_and_per_condition() {
        let mut rng = Rng::new(42, Condition::Freckles);
        let mean = (0..10_000).map(|_| f64::from(rng.unit())).sum::<f64>() / 10_000.0;
        assert!((mean - 0.5).abs() < 0.01, "{mean}");
        assert_ne!(Rng::new(42, Condition::Freckles).next_u64(), Rng::new(42, Condition::Moles).next_u64());
    }
}
