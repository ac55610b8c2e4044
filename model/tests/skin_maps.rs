//! Skin maps: the anatomy and each condition change the parameters where they are placed and
//! nowhere else, the same for a seed and not for another, every texel valid at amounts 0 and 1,
//! and the maps saved in a project come back bit for bit (a project saved before them opens).
//!
//! `ROUGE_SKIN_FIGURE=docs/images/skin_maps.png cargo test -p rouge-model --test model
//! skin_maps::figure` writes the figure of docs/SKIN.md ("Skin maps").

use rouge_measure::skin::{SkinParams, skin_tone};
use rouge_model::mesh::load_mesh;
use rouge_model::paint::SurfaceMap;
use rouge_model::skin::anatomy::{AnatomyRegion, LogFactors};
use rouge_model::skin::{Condition, SkinChannel, SkinConditions, SkinMaps, clamp_params};
use std::sync::OnceLock;

/// Side of the maps most tests make: the masks' own resolution, about a texel per mm.
const SIZE: u32 = 1024;

fn surface() -> &'static SurfaceMap {
    static SURFACE: OnceLock<SurfaceMap> = OnceLock::new();
    SURFACE.get_or_init(|| SurfaceMap::build(&load_mesh(None, 1.0, 1).expect("default head"), SIZE, SIZE))
}

fn light() -> SkinParams {
    skin_tone("light").expect("a built-in tone").params
}

fn generate(conditions: &str, seed: u64) -> SkinMaps {
    let c: SkinConditions = conditions.parse().expect("conditions");
    SkinMaps::generate_on(&light(), &c, seed, surface()).expect("generate")
}

fn uv(i: usize, n: u32) -> (f32, f32) {
    let (x, y) = ((i % n as usize) as f32, (i / n as usize) as f32);
    ((x + 0.5) / n as f32, 1.0 - (y + 0.5) / n as f32)
}

/// The largest weight of `regions` within ±`reach` texels of texel i (at the masks' 1024²).
fn near(regions: &[AnatomyRegion], i: usize, reach: i64) -> f32 {
    let (x, y) = ((i % SIZE as usize) as i64, (i / SIZE as usize) as i64);
    let mut best = 0.0f32;
    for r in regions {
        let m = r.mask();
        for dy in -reach..=reach {
            for dx in -reach..=reach {
                let (mx, my) = ((x + dx).clamp(0, 1023) as u32, (y + dy).clamp(0, 1023) as u32);
                best = best.max(m.texel(mx, my));
            }
        }
    }
    best
}

/// Indices of the texels where channel `c` differs between `a` and `b`.
fn changed(a: &SkinMaps, b: &SkinMaps, c: SkinChannel) -> Vec<usize> {
    a.plane(c).iter().zip(b.plane(c)).enumerate().filter(|(_, (x, y))| x != y).map(|(i, _)| i).collect()
}

fn same_channel(a: &SkinMaps, b: &SkinMaps, c: SkinChannel) -> bool {
    a.plane(c).iter().zip(b.plane(c)).all(|(x, y)| x.to_bits() == y.to_bits())
}

#[test]
fn the_anatomy_follows_the_regions() {
    let base = light();
    let m = SkinMaps::generate(&base, &SkinConditions::NONE, 0, 512).expect("generate");
    assert_eq!((m.width(), m.height()), (512, 512));
    // Every texel is the tone × the regions' factors at their masks' weights.
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-6 * b.abs().max(1e-12);
    for i in (0..512 * 512).step_by(7) {
        let (u, v) = uv(i, 512);
        let l = LogFactors::anatomy_at(u, v);
        let p = m.texel((i % 512) as u32, (i / 512) as u32);
        assert!(close(p.blood_fraction, base.blood_fraction * l.blood.exp()), "texel {i} blood");
        assert!(close(p.melanin_fraction, base.melanin_fraction * l.melanin.exp()), "texel {i} melanin");
        assert!(close(p.epidermis_thickness_mm, base.epidermis_thickness_mm * l.epidermis.exp()), "texel {i}");
        assert_eq!(p.pheomelanin_share, f64::from(base.pheomelanin_share as f32));
        assert_eq!(p.scattering_500nm_per_mm, base.scattering_500nm_per_mm, "the scattering is the tone's");
    }
    // Where a region's mask is (nearly) 1, its factors apply (with those of overlapping regions).
    let at_full = |r: AnatomyRegion| -> SkinParams {
        let i = (0..512 * 512)
            .find(|&i| {
                let (u, v) = uv(i, 512);
                r.weight_uv(u, v) >= 0.98
            })
            .unwrap_or_else(|| panic!("{} has an inside", r.name()));
        m.texel((i % 512) as u32, (i / 512) as u32)
    };
    let lips = at_full(AnatomyRegion::Lips);
    assert!(lips.blood_fraction > 3.0 * base.blood_fraction && lips.melanin_fraction < base.melanin_fraction);
    assert!(at_full(AnatomyRegion::Cheeks).blood_fraction > 1.5 * base.blood_fraction);
    assert!(at_full(AnatomyRegion::UnderEye).epidermis_thickness_mm < base.epidermis_thickness_mm);
    assert!(at_full(AnatomyRegion::Forehead).melanin_fraction > base.melanin_fraction);
    assert!(at_full(AnatomyRegion::Temples).blood_fraction < base.blood_fraction);
    // Away from every region (the back of the head) the skin is the tone.
    assert!(AnatomyRegion::ALL.iter().all(|r| r.mask().texel(700, 300) == 0.0));
    let back = m.texel(350, 150);
    assert!(close(back.blood_fraction, base.blood_fraction) && close(back.melanin_fraction, base.melanin_fraction));
}

#[test]
fn redness_raises_the_blood_only_over_the_cheeks_and_nose() {
    let (bare, red) = (generate("none", 3), generate("redness=1", 3));
    for c in [SkinChannel::Melanin, SkinChannel::Pheomelanin, SkinChannel::Oxygen, SkinChannel::Epidermis] {
        assert!(same_channel(&bare, &red, c), "redness leaves {} alone", c.name());
    }
    let regions = [AnatomyRegion::Cheeks, AnatomyRegion::Nose];
    let diff = changed(&bare, &red, SkinChannel::Blood);
    assert!(diff.len() > 2000, "{} texels redder", diff.len());
    for &i in &diff {
        assert!(near(&regions, i, 0) > 0.0, "redness at texel {i} outside the cheeks and nose");
        assert!(red.plane(SkinChannel::Blood)[i] > bare.plane(SkinChannel::Blood)[i], "redness only adds blood");
    }
    // Inside the regions it is there nearly everywhere.
    let inside = (0..(SIZE * SIZE) as usize).filter(|&i| near(&regions, i, 0) == 1.0).count();
    let red_inside = diff.iter().filter(|&&i| near(&regions, i, 0) == 1.0).count();
    assert!(red_inside as f64 > 0.99 * inside as f64, "{red_inside} of {inside}");
}

#[test]
fn each_spot_condition_changes_its_parameter_only_near_its_regions() {
    use AnatomyRegion as R;
    let bare = generate("none", 11);
    let cases = [
        ("freckles=1", SkinChannel::Melanin, &[R::Cheeks, R::Nose, R::Forehead][..]),
        ("acne=1", SkinChannel::Blood, &[R::Forehead, R::Cheeks, R::Chin, R::Nose][..]),
        ("hyperpigmentation=1", SkinChannel::Melanin, &[R::Forehead, R::Cheeks, R::Chin, R::Nose][..]),
        ("moles=1", SkinChannel::Melanin, &[R::Cheeks, R::Nose, R::Forehead, R::Chin, R::Temples, R::UnderEye][..]),
        ("veins=1", SkinChannel::Oxygen, &[R::Temples, R::Eyelids, R::UnderEye][..]),
    ];
    for (conditions, channel, regions) in cases {
        let m = generate(conditions, 11);
        let diff = changed(&bare, &m, channel);
        assert!(diff.len() > 30, "{conditions}: {} texels changed", diff.len());
        // A spot's centre has placement weight; its radius (at most 3 mm, 3 texels) reaches past it.
        for &i in &diff {
            assert!(near(regions, i, 4) > 0.0, "{conditions}: texel {i} changed far from its regions");
        }
        let raised = |i: &usize| m.plane(channel)[*i] > bare.plane(channel)[*i];
        let lowered = |i: &usize| m.plane(channel)[*i] < bare.plane(channel)[*i];
        let expected_up = channel != SkinChannel::Oxygen;
        assert!(diff.iter().all(|i| if expected_up { raised(i) } else { lowered(i) }), "{conditions}: one direction");
        for c in SkinChannel::ALL {
            let touched = c == channel || (conditions.starts_with("veins") && c == SkinChannel::Blood);
            if !touched {
                assert!(same_channel(&bare, &m, c), "{conditions} leaves {} alone", c.name());
            }
        }
    }
}

#[test]
fn under_eye_darkness_stays_under_the_eyes() {
    let (bare, dark) = (generate("none", 5), generate("under_eye=1", 5));
    for c in [SkinChannel::Melanin, SkinChannel::Oxygen, SkinChannel::Blood] {
        let diff = changed(&bare, &dark, c);
        assert!(diff.len() > 500, "{} {}", c.name(), diff.len());
        assert!(diff.iter().all(|&i| near(&[AnatomyRegion::UnderEye], i, 0) > 0.0), "{}", c.name());
    }
    assert!(same_channel(&bare, &dark, SkinChannel::Epidermis));
}

#[test]
fn a_seed_gives_the_same_maps_and_another_seed_others() {
    let conditions = "freckles=0.5,moles=0.5,acne=0.3,redness=0.4,veins=0.5";
    let a = generate(conditions, 42);
    assert_eq!(a, generate(conditions, 42), "deterministic");
    let b = generate(conditions, 43);
    assert!(!changed(&a, &b, SkinChannel::Melanin).is_empty() && !changed(&a, &b, SkinChannel::Blood).is_empty());
    // Each condition has its own random stream: adding acne does not move the freckles.
    let (f, fa) = (generate("freckles=0.5", 42), generate("freckles=0.5,acne=0.5", 42));
    assert!(same_channel(&f, &fa, SkinChannel::Melanin));
}

/// Every texel of `m` passes the skin model's own check.
fn assert_all_valid(m: &SkinMaps, what: &str) {
    for y in 0..m.height() {
        for x in 0..m.width() {
            let p = m.texel(x, y);
            p.validate().unwrap_or_else(|e| panic!("{what}: texel ({x}, {y}) {p:?}: {e}"));
        }
    }
}

#[test]
fn every_texel_is_valid_at_amounts_0_and_1_on_every_tone_and_at_the_edges() {
    let all: SkinConditions =
        Condition::ALL.iter().map(|c| format!("{c}=1")).collect::<Vec<_>>().join(",").parse().unwrap();
    let dark = skin_tone("very-deep").unwrap().params;
    // Parameters at the top of their ranges: the anatomy and the conditions push past them.
    let top = SkinParams {
        melanin_fraction: 0.6,
        blood_fraction: 0.3,
        oxygen_saturation: 1.0,
        pheomelanin_share: 1.0,
        scattering_500nm_per_mm: 10.0,
        scattering_power: 4.0,
        epidermis_thickness_mm: 0.3,
    };
    // The thickest epidermis this scattering allows.
    let edge = clamp_params(&top);
    assert_eq!(edge.epidermis_thickness_mm, top.max_epidermis_mm());
    let zero = SkinParams {
        melanin_fraction: 0.0,
        blood_fraction: 0.0,
        oxygen_saturation: 0.0,
        epidermis_thickness_mm: 0.0,
        ..light()
    };
    for (name, base) in [("light", light()), ("very-deep", dark), ("the top of every range", edge), ("zeros", zero)] {
        for conditions in [SkinConditions::NONE, all] {
            let m = SkinMaps::generate_on(&base, &conditions, 9, surface()).expect("generate");
            assert_all_valid(&m, &format!("{name}, {conditions}"));
            assert!(SkinChannel::ALL.iter().all(|&c| m.plane(c).iter().all(|v| v.is_finite())));
        }
    }
}

#[test]
fn generate_refuses_a_bad_base_or_size_naming_it() {
    let bad = SkinParams { blood_fraction: 0.5, ..light() };
    let e = SkinMaps::generate(&bad, &SkinConditions::NONE, 0, 64).unwrap_err().to_string();
    assert!(e.contains("blood_fraction = 0.5"), "{e}");
    let e = SkinMaps::generate(&light(), &SkinConditions::NONE, 0, 8).unwrap_err().to_string();
    assert!(e.contains("8 texels") && e.contains("16..=4096"), "{e}");
}

/// `ROUGE_SKIN_FIGURE=path`: the blood and melanin maps of one generated face, side by side,
/// cropped to the face and turned upright (forehead up).
#[test]
fn figure() {
    let Some(path) = std::env::var_os("ROUGE_SKIN_FIGURE") else { return };
    let conditions = "freckles=0.6,moles=0.4,redness=0.5,acne=0.3,hyperpigmentation=0.3,under_eye=0.6,veins=0.6";
    let (base, n) = (light(), 2048u32);
    let m = SkinMaps::generate(&base, &conditions.parse().expect("conditions"), 7, n).expect("generate");
    // The face in the UV atlas: the face looks toward +u (forehead at small u).
    let (x0, y0, side) = (1520u32, 840u32, 440u32);
    let ramp = |t: f64, stops: &[[f64; 3]]| -> [u8; 3] {
        let t = t.clamp(0.0, 1.0) * (stops.len() - 1) as f64;
        let (k, f) = ((t.floor() as usize).min(stops.len() - 2), t - t.floor().min((stops.len() - 2) as f64));
        std::array::from_fn(|c| ((stops[k][c] + (stops[k + 1][c] - stops[k][c]) * f) * 255.0).round() as u8)
    };
    let red = [[0.02, 0.02, 0.05], [0.55, 0.05, 0.1], [0.95, 0.45, 0.2], [1.0, 0.95, 0.75]];
    let brown = [[0.98, 0.95, 0.88], [0.75, 0.55, 0.35], [0.4, 0.22, 0.1], [0.08, 0.04, 0.02]];
    let panels = [(SkinChannel::Blood, 0.08, &red), (SkinChannel::Melanin, 0.06, &brown)];
    let (gap, w) = (8u32, side * 2 + 8);
    let mut img = image::RgbImage::from_pixel(w, side, image::Rgb([255, 255, 255]));
    for (k, (c, top, stops)) in panels.into_iter().enumerate() {
        let plane = m.plane(c);
        for j in 0..side {
            for i in 0..side {
                // Upright: the image's row j is the map's column x0 + j, its column i the map's row.
                let (x, y) = (x0 + j, y0 + side - 1 - i);
                let v = f64::from(plane[(y * n + x) as usize]) / top;
                img.put_pixel(k as u32 * (side + gap) + i, j, image::Rgb(ramp(v, stops)));
            }
        }
    }
    img.save(std::path::Path::new(&path)).expect("write the figure");
}

#[test]
fn the_albedo_texture_is_the_tables_colour_encoded() {
    use rouge_measure::colorimetry::srgb_encode;
    use rouge_measure::skin::SkinColorTable;
    let base = light();
    let table = SkinColorTable::new(&base).expect("table");
    let uniform = SkinMaps::uniform(&base);
    let img = uniform.albedo_image(&table);
    assert_eq!((img.width(), img.height()), (uniform.width(), uniform.height()));
    let want = table.linear_srgb(&base).map(|c| (srgb_encode(f64::from(c)) * 255.0).round() as u8);
    assert!(img.pixels().all(|p| p.0 == [want[0], want[1], want[2], 255]));
    // A generated face: the lips (more blood, less melanin) are redder than the forehead.
    let m = SkinMaps::generate(&base, &SkinConditions::default(), 1, 128).expect("generate");
    let t = SkinColorTable::new(m.base()).expect("table");
    let img = m.albedo_image(&t);
    let redness = |p: &image::Rgba<u8>| f64::from(p.0[0]) - f64::from(p.0[1]);
    let (mut lips, mut other) = ((0.0, 0), (0.0, 0));
    for (i, p) in img.pixels().enumerate() {
        let (u, v) = uv(i, 128);
        if AnatomyRegion::Lips.weight_uv(u, v) > 0.9 {
            lips = (lips.0 + redness(p), lips.1 + 1);
        } else if AnatomyRegion::Forehead.weight_uv(u, v) > 0.9 {
            other = (other.0 + redness(p), other.1 + 1);
        }
    }
    assert!(lips.1 > 0 && other.1 > 0);
    assert!(lips.0 / lips.1 as f64 > other.0 / other.1 as f64 + 10.0, "lips {lips:?}, forehead {other:?}");
}

#[test]
fn blood_follows_the_expression_by_region() {
    use rouge_model::mesh::targets::Weights;
    use rouge_model::skin::blood_flow::blood_factors;
    let m = generate("", 1);
    let units = |pairs: &[(&str, f32)]| -> Weights { pairs.iter().map(|(n, w)| (n.to_string(), *w)).collect() };
    assert!(blood_factors(&Weights::new()).is_empty());
    assert_eq!(m.with_blood_flow(&Weights::new()), m, "a neutral face moves no blood");
    let smile = m.with_blood_flow(&units(&[("mouthSmileLeft", 1.0), ("mouthSmileRight", 1.0)]));
    let press = m.with_blood_flow(&units(&[("mouthPressLeft", 1.0), ("mouthPressRight", 1.0)]));
    let (before, smiled, pressed) =
        (m.plane(SkinChannel::Blood), smile.plane(SkinChannel::Blood), press.plane(SkinChannel::Blood));
    let (mut cheeks_up, mut lips_down) = (0usize, 0usize);
    for i in 0..before.len() {
        let (u, v) = uv(i, SIZE);
        let (cheek, lips) = (AnatomyRegion::Cheeks.weight_uv(u, v), AnatomyRegion::Lips.weight_uv(u, v));
        if cheek > 0.9 {
            assert!(smiled[i] > before[i] * 1.5, "texel {i}: {} -> {}", before[i], smiled[i]);
            cheeks_up += 1;
        } else if cheek == 0.0 {
            assert_eq!(smiled[i], before[i], "a smile moved blood outside the cheeks at texel {i}");
        }
        if lips > 0.9 {
            assert!(pressed[i] < before[i] * 0.7, "texel {i}: {} -> {}", before[i], pressed[i]);
            lips_down += 1;
        } else if lips == 0.0 {
            assert_eq!(pressed[i], before[i], "pressed lips moved blood outside the lips at texel {i}");
        }
    }
    assert!(cheeks_up > 100 && lips_down > 100, "{cheeks_up} {lips_down}");
    // Only blood moves.
    for c in [SkinChannel::Melanin, SkinChannel::Oxygen, SkinChannel::Epidermis, SkinChannel::Pheomelanin] {
        assert_eq!(smile.plane(c), m.plane(c));
    }
}
