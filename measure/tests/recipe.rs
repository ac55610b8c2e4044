//! Recipe search on the sample presets (`rouge_measure::analysis::recipe`): a target mixed from
//! library colorants with measurement noise gives its recipe back; limits, fixed pairs and the
//! several-illuminant objective shape the answer.

use rouge_measure::analysis::correction::Presentation;
use rouge_measure::analysis::mixing::duncan_mix;
use rouge_measure::analysis::recipe::{Colorant, FixedRatio, Recipe, RecipeSearch, WeightedViewing, search_recipes};
use rouge_measure::analysis::{Layer, lab_of};
use rouge_measure::colorimetry::{Colorimeter, Illuminant, Viewing, delta_e_2000_raw};
use rouge_measure::spectrum::Spectrum;
use rouge_measure::{Observer, Preset};
use std::path::Path;

/// A library of sample presets of different kinds (a foundation, a blush, an eyeshadow, a
/// lipstick...), so that its colorants are not near-metamers of each other.
const LIBRARY: [&str; 7] = [
    "foundation_02_ivory",
    "foundation_05_espresso",
    "blush_02_coral",
    "eyeshadow_02_sapphire",
    "eyeshadow_03_bronze",
    "lipstick_02_red",
    "lipstick_03_berry",
];

fn library() -> Vec<Colorant> {
    LIBRARY
        .iter()
        .map(|name| {
            let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("../data/presets/{name}.json"));
            let preset = Preset::load(&path).expect("sample preset");
            Colorant::new(Layer::new(name, preset.s(), preset.k()).expect("valid S and K"))
        })
        .collect()
}

fn viewings(illuminants: &[(Illuminant, f64)]) -> Vec<WeightedViewing> {
    illuminants
        .iter()
        .map(|&(illuminant, weight)| WeightedViewing {
            viewing: Viewing { illuminant, observer: Observer::Cie1931 },
            weight,
        })
        .collect()
}

/// Reflectance noise of a spectrophotometer: deterministic pseudo-random, uniform ±`amplitude`.
fn noisy(r: &Spectrum, amplitude: f64, seed: u64) -> Spectrum {
    let mut state = seed;
    Spectrum(std::array::from_fn(|i| {
        state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        let u = (state >> 11) as f64 / (1u64 << 53) as f64;
        (r.0[i] + amplitude * (2.0 * u - 1.0)).clamp(0.0, 1.0)
    }))
}

#[test]
fn recipe_search_recovers_a_noisy_synthetic_mixture() {
    let lib = library();
    let layers: Vec<Layer> = lib.iter().map(|c| c.layer.clone()).collect();
    // Ivory, coral blush and bronze eyeshadow, 0.6 : 0.25 : 0.15, over 0.3 % reflectance noise.
    let (truth, amounts) = ([0usize, 2, 4], [0.6, 0.25, 0.15]);
    let chosen: Vec<Layer> = truth.iter().map(|&i| layers[i].clone()).collect();
    let clean = duncan_mix("target", &chosen, &amounts).expect("mixable").r_inf();
    let target = noisy(&clean, 0.003, 7);
    let search = RecipeSearch {
        colorants: lib,
        fixed: vec![],
        k: 3,
        viewings: viewings(&[(Illuminant::D65, 1.0), (Illuminant::A, 0.5), (Illuminant::Fl11, 0.5)]),
        presentation: Presentation::Opaque,
        cost_weight: 0.0,
    };
    let report = search_recipes(&search, &target, 5).expect("a valid search");
    assert_eq!(report.combinations, 35);
    let best = &report.recipes[0];
    assert_eq!(best.indices, truth, "{:?}", report.recipes);
    for (got, want) in best.amounts.iter().zip(amounts) {
        assert!((got - want).abs() < 0.01, "amounts {:?} against {amounts:?}", best.amounts);
    }
    assert!(best.delta_e.iter().all(|de| *de < 0.3), "{best:?}");
    assert!(best.metamerism.iter().all(|m| m.delta_e_2000 < 0.3), "{best:?}");
    // The runner-up is a worse match, not a tie.
    assert!(report.recipes[1].objective > 2.0 * best.objective, "{:?}", report.recipes);
}

#[test]
fn several_illuminants_prefer_the_recipe_that_holds_under_each() {
    let lib = library();
    let layers: Vec<Layer> = lib.iter().map(|c| c.layer.clone()).collect();
    let truth = [layers[0].clone(), layers[4].clone(), layers[6].clone()];
    let target = duncan_mix("t", &truth, &[0.6, 0.25, 0.15]).expect("mixable").r_inf();
    // Four colorants match a colour under one light in many ways (four amounts, three
    // coordinates): under D65 alone several recipes match and most are metamers.
    let mut search = RecipeSearch {
        colorants: lib,
        fixed: vec![],
        k: 4,
        viewings: viewings(&[(Illuminant::D65, 1.0)]),
        presentation: Presentation::Opaque,
        cost_weight: 0.0,
    };
    let lights = viewings(&[(Illuminant::D65, 1.0), (Illuminant::A, 1.0), (Illuminant::Fl11, 1.0)]);
    let under_all = |r: &Recipe| -> Vec<f64> {
        let chosen: Vec<Layer> = r.indices.iter().map(|&i| layers[i].clone()).collect();
        let reflectance = duncan_mix("r", &chosen, &r.amounts).expect("mixable").r_inf();
        lights
            .iter()
            .map(|v| {
                let c = Colorimeter::get(v.viewing);
                delta_e_2000_raw(lab_of(c, &reflectance), lab_of(c, &target))
            })
            .collect()
    };
    let worst = |de: &[f64]| de.iter().copied().fold(0.0, f64::max);
    let one_light = search_recipes(&search, &target, 35).expect("valid").recipes;
    let lucky: Vec<&Recipe> = one_light.iter().filter(|r| r.delta_e[0] < 0.05).collect();
    // (The sample presets share nine pigments, so their metamers differ by tenths of a ΔE.)
    assert!(lucky.iter().any(|r| worst(&under_all(r)) > 0.2), "no metameric match to beat: {one_light:?}");
    search.viewings = lights.clone();
    let steady = search_recipes(&search, &target, 1).expect("valid").recipes.remove(0);
    assert!(worst(&steady.delta_e) < 0.01, "{steady:?}");
    for i in [0, 4, 6] {
        assert!(steady.indices.contains(&i), "{steady:?}");
    }
    assert!(steady.metamerism.iter().all(|m| m.delta_e_2000 < 0.01), "{steady:?}");
}

#[test]
fn limits_and_fixed_pairs_hold_and_bad_searches_are_refused() {
    let mut lib = library();
    lib[0].min = 0.5; // ivory in every recipe, at least half
    lib[2].max = 0.1;
    lib[4].cost_per_unit = 20.0;
    let fixed = vec![FixedRatio { a: "lipstick_02_red".into(), b: "lipstick_03_berry".into(), ratio: 2.0 }];
    let search = RecipeSearch {
        colorants: lib,
        fixed,
        k: 3,
        viewings: viewings(&[(Illuminant::D65, 1.0)]),
        presentation: Presentation::Opaque,
        cost_weight: 0.0,
    };
    let target = Spectrum::constant(0.35);
    let report = search_recipes(&search, &target, 100).expect("feasible");
    // Ivory + the red:berry pair, or ivory + two of the four others: 1 + 6.
    assert_eq!(report.combinations, 7);
    for r in &report.recipes {
        let amount = |name: &str| r.names.iter().position(|n| n == name).map(|j| r.amounts[j]);
        assert!(amount("foundation_02_ivory").expect("required") >= 0.5 - 1e-12, "{r:?}");
        assert!(amount("blush_02_coral").unwrap_or(0.0) <= 0.1 + 1e-12, "{r:?}");
        if let (Some(red), Some(berry)) = (amount("lipstick_02_red"), amount("lipstick_03_berry")) {
            assert!((red - 2.0 * berry).abs() < 1e-9, "{r:?}");
        }
        assert!((r.cost - 20.0 * amount("eyeshadow_03_bronze").unwrap_or(0.0)).abs() < 1e-12);
    }
    // A target outside [0, 1] names the wavelength.
    let mut bad = target;
    bad.0[4] = 1.2;
    let e = search_recipes(&search, &bad, 1).expect_err("out of range").to_string();
    assert!(e.contains("the target") && e.contains("400 nm"), "{e}");
    let e = search_recipes(&RecipeSearch { viewings: vec![], ..search.clone() }, &target, 1)
        .expect_err("no light")
        .to_string();
    assert!(e.contains("no viewing"), "{e}");
}
