//! The glTF export's bake ([`rouge_render::gltf_export::bake_surface`]) on the CPU: the baked
//! base colour under the default look's lipstick follows the 81-wavelength composition of its
//! layers over the skin's spectrum (\[Huang2013\] eq. 1-4 per wavelength: a reference that does
//! not go through the render tables or the compositing basis), and is far from bare skin; where
//! no layer covers, the bake is the skin exactly; the specular lobe turns into the lipstick's
//! under an opaque coat.

use rouge_measure::colorimetry::{Colorimeter, Viewing, delta_e_2000_raw, linear_srgb_to_lab};
use rouge_measure::km::{LayerRt, stack};
use rouge_measure::layer_table::layer_spectra;
use rouge_measure::skin::SkinParams;
use rouge_model::look::Look;
use rouge_render::Skin;
use rouge_render::gltf_export::{SkinSurface, bake_surface, gltf_roughness};
use rouge_render::renderer::LayerInput;
use rouge_render::scene::fresnel_f0;

const SIDE: u32 = 256;

fn layers(look: &Look) -> Vec<LayerInput<'_>> {
    look.visible_layers().map(|l| LayerInput { preset: &l.preset, map: &l.map, multiplier: 1.0 }).collect()
}

#[test]
fn lipstick_texel_follows_the_spectral_composition_and_bare_texels_keep_the_skin() {
    let skin_spectrum = SkinParams::LIGHT.reflectance().expect("light skin");
    let skin = Skin::from_spectrum(&skin_spectrum);
    let surface =
        SkinSurface { albedo: skin.albedo, albedo_map: None, beckmann_roughness: skin.roughness, ior: skin.ior };
    let look = Look::default_look();
    let names: Vec<&str> = look.layers.iter().map(|l| l.preset_ref.as_str()).collect();
    assert_eq!(names, ["builtin:foundation_02_ivory", "builtin:blush_01_petal", "builtin:lipstick_02_red"]);
    let baked = bake_surface(&surface, &layers(&look), SIDE).expect("bake");

    // The texel where the lipstick is thickest (the middle of the lips mask: 20 µm).
    let maps: Vec<Vec<f32>> = look.layers.iter().map(|l| l.map.resized(SIDE, SIDE).mm).collect();
    let lips = (0..maps[2].len()).max_by(|&a, &b| maps[2][a].total_cmp(&maps[2][b])).expect("texels");
    assert!((maps[2][lips] - 0.02).abs() < 1e-4, "lipstick {} mm", maps[2][lips]);

    // The reference: every covering layer at that texel, top first, over the skin's spectrum.
    let c = Colorimeter::get(Viewing::D65_1931);
    let spectral = |top_first: &[usize]| -> [f64; 3] {
        let rt: Vec<_> = top_first
            .iter()
            .map(|&i| {
                let p = &look.layers[i].preset;
                layer_spectra(&p.s(), &p.k(), f64::from(maps[i][lips]))
            })
            .collect();
        let r = rouge_measure::Spectrum(std::array::from_fn(|w| {
            let mut s: Vec<LayerRt> = rt.iter().map(|(r0, t)| LayerRt { r: r0.0[w], t: t.0[w] }).collect();
            s.push(LayerRt::opaque(skin_spectrum.0[w]));
            stack(&s).r
        }));
        c.lab(&c.xyz(&r)).lab
    };
    let covering: Vec<usize> = (0..3).rev().filter(|&i| maps[i][lips] > 0.0).collect();
    let reference = spectral(&covering);
    let got = linear_srgb_to_lab(baked.base_color[lips].map(f64::from));
    let de = delta_e_2000_raw(got, reference);
    // The compositing basis is within 1.35 ΔE2000 of the spectral composition at its 95th
    // percentile on stacked pairs (measure/src/compositing.rs); the tables add < 0.1.
    assert!(de < 1.5, "lips: baked Lab {got:?} vs spectral {reference:?}: ΔE2000 {de:.3}");
    let bare = linear_srgb_to_lab(skin.albedo.map(f64::from));
    let from_skin = delta_e_2000_raw(got, bare);
    assert!(from_skin > 20.0, "the lipstick texel is {from_skin:.1} ΔE2000 from bare skin");
    assert!(got[1] > bare[1] + 15.0, "lipstick is redder than skin: a* {} vs {}", got[1], bare[1]);

    // Under 20 µm of lipstick the lobe is mostly the lipstick's: roughness moves from the skin's
    // toward the preset's, and F0 toward the lipstick's.
    let lip = &look.layers[2].preset.specular;
    let (m, f0) = (baked.beckmann_roughness[lips], baked.f0[lips]);
    let (skin_m, lip_m) = (skin.roughness, lip.roughness as f32);
    assert!((m - lip_m).abs() < (skin_m - lip_m).abs() * 0.5, "roughness {m} (skin {skin_m}, lipstick {lip_m})");
    assert!(f0 > fresnel_f0(lip.ior as f32) * 0.9, "F0 {f0}");

    // A bare look bakes the skin itself: colour, roughness and F0 exactly.
    let bare_bake = bake_surface(&surface, &[], SIDE).expect("bare bake");
    assert!(bare_bake.base_color.iter().all(|&c| c == skin.albedo));
    assert!(bare_bake.beckmann_roughness.iter().all(|&m| m == skin.roughness));
    assert!(bare_bake.f0.iter().all(|&f| f == fresnel_f0(skin.ior)));
    assert!((gltf_roughness(0.36) - 0.6).abs() < 1e-6);
}

#[test]
fn an_albedo_map_is_sampled_in_the_meshs_uv_convention_and_bad_sizes_are_refused() {
    // A 2×2 albedo map: top row (v = 1) red, bottom row (v = 0) blue.
    let mut img = image::RgbaImage::new(2, 2);
    for x in 0..2 {
        img.put_pixel(x, 0, image::Rgba([255, 0, 0, 255]));
        img.put_pixel(x, 1, image::Rgba([0, 0, 255, 255]));
    }
    let surface = SkinSurface { albedo: [0.5; 3], albedo_map: Some(&img), beckmann_roughness: 0.35, ior: 1.4 };
    let baked = bake_surface(&surface, &[], 16).expect("bake");
    let top = baked.texel_at_uv(0.5, 0.99).base_color;
    let bottom = baked.texel_at_uv(0.5, 0.01).base_color;
    assert_eq!(top, [1.0, 0.0, 0.0], "v = 1 is the image's first row");
    assert_eq!(bottom, [0.0, 0.0, 1.0]);
    for bad in [0, 8, 100_000] {
        let e = bake_surface(&surface, &[], bad).unwrap_err().to_string();
        assert!(e.contains(&format!("texture size {bad}")), "{e}");
    }
}
