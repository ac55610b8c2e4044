//! Skin microgeometry: what makes skin look like skin up close, and what a primer or a foundation
//! fills. Two images, both generated, deterministic per seed:
//!
//! - [`DetailTile`]: a tileable patch of [`TILE_MM`] × [`TILE_MM`] of skin relief (pores and the
//!   fine cross-hatched lines of the skin surface) as a tangent-space normal map with a cavity
//!   channel, and its mip chain (averaged normals shorten where the relief is finer than a texel,
//!   so distant skin is smooth, not aliased). The renderer tiles it over the face at the mesh's
//!   scale.
//! - [`RegionDetail`]: per texel of the default head's UVs, how deep the pores are there and how
//!   oily the skin is, from the head's region masks ([`AnatomyRegion`]).
//!
//! *Choice* (no measured statistic is used): visible facial pores are 0.06-0.14 mm across and a
//! few hundredths of a mm deep ([`PORE_DEPTH_MM`]), [`PORES_PER_MM2`] of them on average, placed
//! on a jittered grid; the relative depth by region (nose deepest, then cheeks, chin, forehead;
//! fine on the eyelids, none on the lips) and the T-zone's oiliness (nose, forehead, chin) follow
//! the usual description of facial skin, not a data set. The lines are two families of shallow
//! furrows crossing at about 80°, 0.4-0.6 mm apart. Lip furrows and expression wrinkles are not
//! modelled yet.

use super::AnatomyRegion;
use crate::thickness::splitmix64;
use glam::Vec2;

/// Side of the detail tile on the skin, mm.
pub const TILE_MM: f32 = 8.0;
/// Side of the detail tile, texels (15.6 µm a texel).
pub const TILE_PX: u32 = 512;
/// Depth of a pore at full region depth, mm (*choice*).
pub const PORE_DEPTH_MM: f32 = 0.03;
/// Mean number of visible pores per mm² (*choice*).
pub const PORES_PER_MM2: f32 = 1.5;
/// Depth of the fine lines relative to [`PORE_DEPTH_MM`] (*choice*).
const LINE_DEPTH: f32 = 0.12;
/// Side of the region map, texels.
pub const REGION_PX: u32 = 256;

/// How many detail tiles one UV unit of `mesh` holds so that a tile covers [`TILE_MM`] of skin:
/// the mesh's mean scale √(Σ 3D area / Σ UV area) (mm per UV unit) over [`TILE_MM`]. `None` for a
/// mesh without area in 3D or in UV.
pub fn tiles_per_uv(mesh: &crate::mesh::TriangleMesh) -> Option<f32> {
    let (mut area_mm2, mut area_uv) = (0.0f64, 0.0f64);
    for t in mesh.indices.chunks_exact(3) {
        let [a, b, c] = [t[0], t[1], t[2]].map(|i| i as usize);
        let (Some(pa), Some(pb), Some(pc)) = (mesh.positions.get(a), mesh.positions.get(b), mesh.positions.get(c))
        else {
            continue;
        };
        let (Some(ua), Some(ub), Some(uc)) = (mesh.uvs.get(a), mesh.uvs.get(b), mesh.uvs.get(c)) else { continue };
        area_mm2 += 0.5 * f64::from((*pb - *pa).cross(*pc - *pa).length());
        area_uv += 0.5 * f64::from((*ub - *ua).perp_dot(*uc - *ua)).abs();
    }
    let mm_per_uv = (area_mm2 / area_uv).sqrt();
    (mm_per_uv.is_finite() && mm_per_uv > 0.0).then(|| (mm_per_uv / f64::from(TILE_MM)) as f32)
}

/// One level of the tile: RGBA8, rgb = the tangent-space normal (n·0.5 + 0.5, averaged over the
/// texels below it, so shorter than 1 where the relief is finer than the level), a = cavity
/// (1 on the open surface, down to ~0.3 at the bottom of the deepest pores).
pub type TileLevel = image::RgbaImage;

/// The tileable relief and its mip chain, level 0 first (down to 1 × 1).
#[derive(Clone, Debug)]
pub struct DetailTile {
    /// The levels.
    pub levels: Vec<TileLevel>,
}

/// A number in [0, 1) from the grid cell (x, y) and `seed`, by the crate's SplitMix64 finaliser
/// (as the skin conditions draw theirs).
fn hash(x: i32, y: i32, seed: u32) -> f32 {
    let cell = (u64::from(x as u32) << 32) | u64::from(y as u32);
    (splitmix64(u64::from(seed) ^ splitmix64(cell)) >> 40) as f32 / (1u64 << 24) as f32
}

impl DetailTile {
    /// The tile of `seed`: pores on a jittered grid and two families of fine lines, as a height
    /// field in mm (0 on the surface, negative in pores and lines), then normals by central
    /// differences with wrap-around and cavity from the depth.
    pub fn generate(seed: u32) -> DetailTile {
        let n = TILE_PX as usize;
        let texel_mm = TILE_MM / TILE_PX as f32;
        let mut height = vec![0.0f32; n * n];
        // Pores: one per grid cell of area 1/PORES_PER_MM2, jittered, radius and depth random.
        let cells = (TILE_MM * PORES_PER_MM2.sqrt()).round().max(1.0) as i32;
        let cell_mm = TILE_MM / cells as f32;
        for cy in 0..cells {
            for cx in 0..cells {
                let centre = Vec2::new(
                    (cx as f32 + 0.15 + 0.7 * hash(cx, cy, seed)) * cell_mm,
                    (cy as f32 + 0.15 + 0.7 * hash(cx, cy, seed ^ 0x9e37)) * cell_mm,
                );
                let radius_mm = 0.03 + 0.04 * hash(cx, cy, seed ^ 0x51ed);
                let depth_mm = PORE_DEPTH_MM * (0.4 + 0.6 * hash(cx, cy, seed ^ 0x2c1b));
                let reach = (2.5 * radius_mm / texel_mm).ceil() as i32;
                let (px, py) = ((centre.x / texel_mm) as i32, (centre.y / texel_mm) as i32);
                for dy in -reach..=reach {
                    for dx in -reach..=reach {
                        let (x, y) = ((px + dx).rem_euclid(n as i32) as usize, (py + dy).rem_euclid(n as i32) as usize);
                        let d = Vec2::new((px + dx) as f32 + 0.5, (py + dy) as f32 + 0.5) * texel_mm - centre;
                        let r2 = d.length_squared() / (radius_mm * radius_mm);
                        height[y * n + x] -= depth_mm * (-r2).exp();
                    }
                }
            }
        }
        // Fine lines: two families of shallow V furrows with whole numbers of periods across the
        // tile (so it tiles), their depth modulated by a smooth tileable envelope.
        let families = [(13.0f32, 7.0f32), (-9.0f32, 14.0f32)];
        let tau = std::f32::consts::TAU;
        for y in 0..n {
            for x in 0..n {
                let (u, v) = ((x as f32 + 0.5) / n as f32, (y as f32 + 0.5) / n as f32);
                let mut h = 0.0;
                for (i, (kx, ky)) in families.iter().enumerate() {
                    let phase = tau * (kx * u + ky * v) + i as f32;
                    let envelope = 0.5 + 0.5 * (tau * (2.0 * u + 3.0 * v) + 1.7 * i as f32).sin();
                    // |sin| has sharp troughs: a furrow once per half period.
                    h -= envelope * (1.0 - phase.sin().abs()).powi(4);
                }
                height[y * n + x] += LINE_DEPTH * PORE_DEPTH_MM * h;
            }
        }
        let mut level = image::RgbaImage::new(TILE_PX, TILE_PX);
        let at = |x: i32, y: i32| height[y.rem_euclid(n as i32) as usize * n + x.rem_euclid(n as i32) as usize];
        for y in 0..n as i32 {
            for x in 0..n as i32 {
                // Image rows go down the tile's v; slopes per mm.
                let sx = (at(x + 1, y) - at(x - 1, y)) / (2.0 * texel_mm);
                let sy = -(at(x, y + 1) - at(x, y - 1)) / (2.0 * texel_mm);
                let normal = glam::Vec3::new(-sx, -sy, 1.0).normalize();
                let cavity = (1.0 + 0.7 * at(x, y) / PORE_DEPTH_MM).clamp(0.0, 1.0);
                let byte = |c: f32| ((c * 0.5 + 0.5) * 255.0).round().clamp(0.0, 255.0) as u8;
                let pixel = [byte(normal.x), byte(normal.y), byte(normal.z), (cavity * 255.0).round() as u8];
                level.put_pixel(x as u32, y as u32, image::Rgba(pixel));
            }
        }
        let mut levels = vec![level];
        while let Some(last) = levels.last().filter(|l| l.width() > 1) {
            levels.push(halve(last));
        }
        DetailTile { levels }
    }
}

/// The next mip level: each texel the mean of the four below it (in the encoded values, which
/// are linear in the normal's components, so the mean normal shortens where it varies).
fn halve(level: &TileLevel) -> TileLevel {
    let side = (level.width() / 2).max(1);
    image::RgbaImage::from_fn(side, side, |x, y| {
        let mut sum = [0u32; 4];
        for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            let p = level.get_pixel((2 * x + dx).min(level.width() - 1), (2 * y + dy).min(level.height() - 1));
            for c in 0..4 {
                sum[c] += u32::from(p[c]);
            }
        }
        image::Rgba(sum.map(|s| ((s + 2) / 4) as u8))
    })
}

/// How deep the pores are (relative to [`PORE_DEPTH_MM`]) and how oily the skin is in a region,
/// *choice* (module doc).
fn region_detail(region: AnatomyRegion) -> (f32, f32) {
    match region {
        AnatomyRegion::Nose => (1.0, 1.0),
        AnatomyRegion::Cheeks => (0.85, 0.35),
        AnatomyRegion::Chin => (0.75, 0.7),
        AnatomyRegion::Forehead => (0.7, 0.85),
        AnatomyRegion::Temples => (0.5, 0.4),
        AnatomyRegion::UnderEye => (0.3, 0.2),
        AnatomyRegion::Eyelids => (0.2, 0.2),
        AnatomyRegion::Ears => (0.3, 0.2),
        AnatomyRegion::Lips => (0.0, 0.3),
    }
}

/// Pore depth and oiliness outside every region.
const ELSEWHERE: (f32, f32) = (0.45, 0.3);
/// The skin's specular where it is driest, relative to the oiliest (*choice*): sebum smooths
/// and wets the surface, so the T-zone shines.
pub const DRY_SPECULAR: f32 = 0.5;

/// Per texel of the default head's UVs: r = relative pore depth (0-1), g = the skin's specular
/// scale from its oiliness, [`DRY_SPECULAR`] + (1 − [`DRY_SPECULAR`])·oiliness, b and a unused
/// (0, 255). Row 0 is v = 1, as every UV map of Rouge.
#[derive(Clone, Debug)]
pub struct RegionDetail {
    /// The map, [`REGION_PX`] square.
    pub image: image::RgbaImage,
}

impl RegionDetail {
    /// The map of the default head: each region's values blended in by its mask's weight over
    /// the values elsewhere (where masks overlap, the heavier wins).
    pub fn default_head() -> RegionDetail {
        let side = REGION_PX;
        let image = image::RgbaImage::from_fn(side, side, |x, y| {
            let (u, v) = ((x as f32 + 0.5) / side as f32, 1.0 - (y as f32 + 0.5) / side as f32);
            let (mut depth, mut oil, mut best) = (ELSEWHERE.0, ELSEWHERE.1, 0.0f32);
            for region in AnatomyRegion::ALL {
                let w = region.weight_uv(u, v) as f32;
                if w > best {
                    let (d, o) = region_detail(region);
                    depth = ELSEWHERE.0 + w * (d - ELSEWHERE.0);
                    oil = ELSEWHERE.1 + w * (o - ELSEWHERE.1);
                    best = w;
                }
            }
            let byte = |c: f32| (c.clamp(0.0, 1.0) * 255.0).round() as u8;
            image::Rgba([byte(depth), byte(DRY_SPECULAR + (1.0 - DRY_SPECULAR) * oil), 0, 255])
        });
        RegionDetail { image }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_tile_tiles_has_pores_and_its_mips_flatten() {
        let tile = DetailTile::generate(7);
        assert_eq!(tile.levels.len(), 10, "512 down to 1");
        let l0 = &tile.levels[0];
        // Wrap-around: the first and last columns differ no more than neighbours inside do.
        let step = |a: &image::Rgba<u8>, b: &image::Rgba<u8>| {
            (0..3).map(|c| (a[c] as i32 - b[c] as i32).abs()).max().unwrap_or(0)
        };
        let worst_inside = (0..TILE_PX).map(|y| step(l0.get_pixel(100, y), l0.get_pixel(101, y))).max().unwrap_or(0);
        let worst_seam =
            (0..TILE_PX).map(|y| step(l0.get_pixel(TILE_PX - 1, y), l0.get_pixel(0, y))).max().unwrap_or(0);
        assert!(worst_seam <= worst_inside.max(4) + 2, "seam {worst_seam} against {worst_inside}");
        // Pores: some texels deep in cavity, most on the open surface.
        let cavities: Vec<u8> = l0.pixels().map(|p| p[3]).collect();
        let deep = cavities.iter().filter(|&&c| c < 180).count() as f32 / cavities.len() as f32;
        assert!((0.005..0.2).contains(&deep), "deep fraction {deep}");
        // Tilt (1 − n_z) falls with the level: finer relief averages out.
        let tilt = |l: &TileLevel| {
            l.pixels().map(|p| 1.0 - (p[2] as f32 / 255.0 * 2.0 - 1.0)).sum::<f32>() / (l.width() * l.height()) as f32
        };
        let (t0, t3, t6) = (tilt(&tile.levels[0]), tilt(&tile.levels[3]), tilt(&tile.levels[6]));
        assert!(t0 > 0.0 && t3 < t0 * 0.95 && t6 < t3, "tilt {t0} {t3} {t6}");
        // Deterministic per seed, different across seeds.
        assert_eq!(DetailTile::generate(7).levels[0], tile.levels[0]);
        assert_ne!(DetailTile::generate(8).levels[0], tile.levels[0]);
    }

    #[test]
    fn the_nose_has_the_deepest_pores_and_the_t_zone_is_oily() {
        let map = RegionDetail::default_head();
        let at = |region: AnatomyRegion| {
            // The texel of the region's strongest weight.
            let side = REGION_PX;
            let (mut best, mut texel) = (0.0, [0u8; 4]);
            for y in 0..side {
                for x in 0..side {
                    let (u, v) = ((x as f32 + 0.5) / side as f32, 1.0 - (y as f32 + 0.5) / side as f32);
                    let w = region.weight_uv(u, v);
                    if w > best {
                        best = w;
                        texel = map.image.get_pixel(x, y).0;
                    }
                }
            }
            texel
        };
        let (nose, cheeks, lips, forehead) =
            (at(AnatomyRegion::Nose), at(AnatomyRegion::Cheeks), at(AnatomyRegion::Lips), at(AnatomyRegion::Forehead));
        assert!(nose[0] > cheeks[0] && cheeks[0] > lips[0], "depth nose {nose:?} cheeks {cheeks:?} lips {lips:?}");
        assert!(lips[0] < 30, "lips have no pores: {lips:?}");
        assert!(
            nose[1] > cheeks[1] && forehead[1] > cheeks[1],
            "oil nose {nose:?} forehead {forehead:?} cheeks {cheeks:?}"
        );
    }
}
