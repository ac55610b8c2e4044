//! Batch correction (`analysis::correction`) on batches whose colorants are off in strength:
//! the batch is made with the true colorants, measured, corrected with the library's; the
//! corrected recipe is made with the true colorants again, and so on.

use rouge_measure::analysis::Layer;
use rouge_measure::analysis::correction::{Presentation, correct_batch};
use rouge_measure::analysis::mixing::duncan_mix;
use rouge_measure::colorimetry::delta_e_2000_raw;
use rouge_measure::{Colorimeter, Preset, Spectrum, Viewing};
use std::path::PathBuf;

fn colorant(name: &str) -> Layer {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("../data/presets/{name}.json"));
    Layer::from_preset(&Preset::load(&path).expect("sample preset")).expect("valid")
}

/// `layer` with S and K scaled by `strength` (a stronger or weaker lot of the same colorant).
fn scaled(layer: &Layer, strength: f64) -> Layer {
    Layer::new(&layer.name, Spectrum(layer.s.0.map(|v| v * strength)), Spectrum(layer.k.0.map(|v| v * strength)))
        .expect("valid")
}

/// ΔE2000 of the batch after each of `n` rounds of correction (`n = 0`: the uncorrected batch).
fn rounds(library: &[Layer], truth: &[Layer], recipe: &[f64], how: &Presentation, n: usize) -> Vec<f64> {
    let c = Colorimeter::get(Viewing::D65_1931);
    let standard = how.reflectance(&duncan_mix("standard", library, recipe).expect("mix"));
    let mut made = recipe.to_vec();
    let mut out = Vec::new();
    if n == 0 {
        let batch = how.reflectance(&duncan_mix("batch", truth, &made).expect("mix"));
        return vec![delta_e_2000_raw(c.lab(&c.xyz(&batch)).lab, c.lab(&c.xyz(&standard)).lab)];
    }
    for _ in 0..n {
        let batch = how.reflectance(&duncan_mix("batch", truth, &made).expect("mix"));
        let fix = correct_batch(library, &made, &batch, &standard, how, c).expect("corrects");
        made = fix.concentrations;
        let next = how.reflectance(&duncan_mix("batch", truth, &made).expect("mix"));
        out.push(delta_e_2000_raw(c.lab(&c.xyz(&next)).lab, c.lab(&c.xyz(&standard)).lab));
    }
    out
}

#[test]
fn correction_converges_within_two_rounds_for_strengths_ten_percent_off() {
    let library: Vec<Layer> =
        ["foundation_01_porcelain", "foundation_04_caramel", "lipstick_02_red"].map(colorant).to_vec();
    let recipe = [0.5, 0.35, 0.15];
    let skin = Spectrum(std::array::from_fn(|i| 0.25 + 0.3 * i as f64 / 80.0));
    let mut worst = [0.0f64; 3];
    for how in [Presentation::Opaque, Presentation::Over { background: Box::new(skin), thickness_mm: 0.02 }] {
        for which in 0..library.len() {
            for strength in [0.9, 1.1] {
                let mut truth = library.clone();
                truth[which] = scaled(&library[which], strength);
                let before = rounds(&library, &truth, &recipe, &how, 0);
                let de = rounds(&library, &truth, &recipe, &how, 2);
                worst = [worst[0].max(before[0]), worst[1].max(de[0]), worst[2].max(de[1])];
                assert!(de[1] < 0.1, "{how:?} colorant {which} at {strength}: ΔE2000 after rounds {de:?}");
            }
        }
        // All three off at once.
        let truth: Vec<Layer> = library.iter().zip([1.1, 0.9, 1.08]).map(|(l, f)| scaled(l, f)).collect();
        let de = rounds(&library, &truth, &recipe, &how, 2);
        assert!(de[1] < 0.1, "{how:?} all off: {de:?}");
    }
    eprintln!("worst ΔE2000 uncorrected / after 1 round / after 2 rounds: {worst:?}");
}

#[test]
fn bad_recipes_say_what_is_wrong() {
    let library: Vec<Layer> = ["foundation_01_porcelain", "foundation_04_caramel"].map(colorant).to_vec();
    let c = Colorimeter::get(Viewing::D65_1931);
    let r = library[0].r_inf();
    let e = correct_batch(&library, &[0.5], &r, &r, &Presentation::Opaque, c).expect_err("one amount").to_string();
    assert!(e.contains("1 amounts for 2 colorants"), "{e}");
    let e = correct_batch(&library, &[0.5, -1.0], &r, &r, &Presentation::Opaque, c).expect_err("negative").to_string();
    assert!(e.contains("Foundation 04"), "{e}");
    let mut bad = r;
    bad.0[80] = 2.0;
    let e = correct_batch(&library, &[0.5, 0.5], &bad, &r, &Presentation::Opaque, c).expect_err("R > 1").to_string();
    assert!(e.contains("the batch") && e.contains("780 nm"), "{e}");
}
