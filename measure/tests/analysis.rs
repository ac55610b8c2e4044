//! The formulation analyses on the repository's sample presets: coverage (contrast ratio,
//! hiding thickness), shade matching on synthetic skins made from the shades, and Duncan mixing
//! against mixtures computed directly (the pigment library the samples were made from).

use rouge_measure::analysis::coverage::{ContrastChart, HIDING_CONTRAST_RATIO, contrast, hiding_thickness_mm};
use rouge_measure::analysis::matching::{Target, match_shades, product_line_coverage};
use rouge_measure::analysis::mixing::{MixTarget, duncan_mix, fit_mix};
use rouge_measure::analysis::skin::read_skins;
use rouge_measure::analysis::{Layer, lab_of};
use rouge_measure::colorimetry::{Colorimeter, Viewing};
use rouge_measure::spectrum::{Extrapolation, Spectrum};
use rouge_measure::{Preset, delta_e_2000};
use std::path::{Path, PathBuf};

fn data(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../data").join(rel)
}

fn preset(name: &str) -> Layer {
    let preset = Preset::load(&data(&format!("presets/{name}.json"))).expect("sample preset");
    Layer::from_preset(&preset).expect("valid S and K")
}

/// Every sample preset's file stem (`data/presets/*.json`).
fn all_presets() -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(data("presets"))
        .expect("data/presets")
        .filter_map(|e| e.ok()?.path().file_stem().map(|s| s.to_string_lossy().into_owned()))
        .collect();
    names.sort();
    names
}

const FOUNDATIONS: [&str; 5] = [
    "foundation_01_porcelain",
    "foundation_02_ivory",
    "foundation_03_sand",
    "foundation_04_caramel",
    "foundation_05_espresso",
];

fn colorimeter() -> &'static Colorimeter {
    Colorimeter::get(Viewing::D65_1931)
}

#[test]
fn contrast_ratio_rises_monotonically_to_one_for_every_sample() {
    let chart = ContrastChart::default();
    for name in all_presets() {
        let name = name.as_str();
        let l = preset(name);
        let cr = |x: f64| contrast(&l, x, chart, colorimeter()).unwrap().contrast_ratio;
        assert!((cr(0.0) - chart.black / chart.white).abs() < 1e-12, "{name}");
        assert_eq!(cr(f64::INFINITY), 1.0, "{name}: an opaque film");
        let mut prev = cr(0.0);
        for i in 1..=400 {
            let x = 0.5 * f64::from(i) / 400.0;
            let v = cr(x);
            assert!(v >= prev - 1e-15 && v <= 1.0, "{name}: CR({x}) = {v} after {prev}");
            prev = v;
        }
        assert!(cr(10.0) > 0.999, "{name}: 10 mm is opaque");
    }
}

#[test]
fn hiding_thickness_matches_a_direct_search() {
    let chart = ContrastChart::new(0.04, 0.80).unwrap();
    for name in ["foundation_02_ivory", "foundation_05_espresso", "blush_01_petal"] {
        let l = preset(name);
        let x = hiding_thickness_mm(&l, chart, colorimeter(), HIDING_CONTRAST_RATIO).unwrap().unwrap();
        // Direct search: 0.1 µm steps from 0 until the ratio reaches 0.98.
        let step = 1e-4;
        let first = (0..100_000)
            .map(|i| f64::from(i) * step)
            .find(|&x| contrast(&l, x, chart, colorimeter()).unwrap().contrast_ratio >= HIDING_CONTRAST_RATIO)
            .unwrap();
        assert!(x <= first && x > first - step, "{name}: {x} mm against the scan's {first} mm");
    }
}

#[test]
fn shade_matching_returns_the_generating_shade_and_thickness() {
    let shades: Vec<Layer> = FOUNDATIONS.iter().map(|n| preset(n)).collect();
    let skins = read_skins(&data("skin/colorchecker_skin.csv"), Extrapolation::Refuse).unwrap();
    let c = colorimeter();
    for (skin_name, skin) in &skins {
        for (i, x) in [(1usize, 0.0123), (3, 0.0371), (4, 0.0066)] {
            let target = lab_of(c, &shades[i].reflectance_over(x, skin));
            let fits = match_shades(&shades, skin, Target::Lab(target), (0.0, 0.1), c).unwrap();
            let best = &fits[0];
            assert_eq!(best.shade, i, "{skin_name}: {fits:?}");
            assert!((best.thickness_mm - x).abs() < 1e-6 && best.delta_e < 1e-3, "{skin_name}: {best:?}");
            assert!(fits[1].delta_e > 0.1, "{skin_name}: another shade matches too well: {fits:?}");
        }
    }
    // "Your shade": a skin with the colour of an opaque layer of shade i is matched by shade i
    // at any wear thickness; the line covers those skins with no gap.
    let synthetic: Vec<(String, Spectrum)> = shades.iter().map(|s| (s.name.clone(), s.r_inf())).collect();
    let cover = product_line_coverage(&shades, &synthetic, Target::BareSkin, (0.02, 0.02), 1.0, c).unwrap();
    for (i, sc) in cover.iter().enumerate() {
        assert_eq!(sc.best.shade, i);
        assert!(sc.best.delta_e < 1e-9 && !sc.gap && sc.best.thickness_mm == 0.02, "{sc:?}");
    }
}

#[test]
fn mixing_recovers_known_concentrations() {
    let c = colorimeter();
    let bases: Vec<Layer> = ["foundation_01_porcelain", "foundation_04_caramel", "foundation_05_espresso"]
        .iter()
        .map(|n| preset(n))
        .collect();
    let truth = [0.2, 0.5, 0.3];
    let mix = duncan_mix("truth", &bases, &truth).unwrap();
    let fit = fit_mix(&bases, &MixTarget::RInf(lab_of(c, &mix.r_inf())), c).unwrap();
    for (a, b) in fit.concentrations.iter().zip(truth) {
        assert!((a - b).abs() < 1e-5, "{:?}", fit.concentrations);
    }
    assert!(fit.delta_e < 1e-6 && (fit.concentrations.iter().sum::<f64>() - 1.0).abs() < 1e-12);
    // Two bases over skin at a thickness.
    let skin = &read_skins(&data("skin/colorchecker_skin.csv"), Extrapolation::Refuse).unwrap()[1].1;
    let two = [bases[0].clone(), bases[2].clone()];
    let mix = duncan_mix("truth", &two, &[0.65, 0.35]).unwrap();
    let lab = lab_of(c, &mix.reflectance_over(0.015, skin));
    let fit = fit_mix(&two, &MixTarget::Covered { skin: Box::new(*skin), thickness_mm: 0.015, lab }, c).unwrap();
    assert!((fit.concentrations[0] - 0.65).abs() < 1e-5, "{:?}", fit.concentrations);
    // Four bases: the colour is reached (the concentrations need not be unique).
    let four: Vec<Layer> =
        ["foundation_01_porcelain", "foundation_03_sand", "foundation_05_espresso", "blush_02_coral"]
            .iter()
            .map(|n| preset(n))
            .collect();
    let mix = duncan_mix("truth", &four, &[0.4, 0.3, 0.2, 0.1]).unwrap();
    let target = lab_of(c, &mix.r_inf());
    let fit = fit_mix(&four, &MixTarget::RInf(target), c).unwrap();
    assert!(fit.delta_e < 1e-3, "{fit:?}");
    // A target outside the bases' reach: the closest mixture, and how far it stays.
    let fit = fit_mix(&bases, &MixTarget::RInf([50.0, 0.0, -60.0]), c).unwrap();
    assert!(fit.delta_e > 10.0);
    let lab_c = rouge_measure::Lab { lab: fit.lab, viewing: Viewing::D65_1931 };
    let lab_t = rouge_measure::Lab { lab: [50.0, 0.0, -60.0], viewing: Viewing::D65_1931 };
    assert!((delta_e_2000(&lab_c, &lab_t).unwrap() - fit.delta_e).abs() < 1e-12);
}

/// Duncan's rule against the mixtures `python/gen_samples.py` computed directly (numpy) from the
/// pigment library for each sample product's recipe (`data/measurements/truth/*.csv`).
#[test]
fn duncan_mix_reproduces_the_sample_products_from_their_pigments() {
    let lib = std::fs::read_to_string(data("pigments/pigment_library.csv")).unwrap();
    let mut rows = lib.lines().filter(|l| !l.starts_with('#'));
    let header: Vec<&str> = rows.next().unwrap().split(',').collect();
    let table: Vec<Vec<f64>> = rows.map(|l| l.split(',').map(|v| v.parse().unwrap()).collect()).collect();
    assert_eq!(table.len(), 81);
    let pigment = |key: &str| {
        let col = |p: &str| header.iter().position(|h| *h == format!("{p}_{key}")).unwrap();
        let (ks, ss) = (col("k"), col("s"));
        Layer::new(
            key,
            Spectrum(std::array::from_fn(|i| table[i][ss])),
            Spectrum(std::array::from_fn(|i| table[i][ks])),
        )
        .unwrap()
    };
    let mut checked = 0;
    for name in all_presets() {
        let name = name.as_str();
        let truth = std::fs::read_to_string(data(&format!("measurements/truth/{name}.csv"))).unwrap();
        let recipe = truth.lines().find_map(|l| l.strip_prefix("# recipe: ")).unwrap();
        let (mut bases, mut conc) = (Vec::new(), Vec::new());
        for part in recipe.split(", ") {
            let (key, c) = part.split_once('=').unwrap();
            bases.push(pigment(key));
            conc.push(c.trim().parse::<f64>().unwrap());
        }
        let mix = duncan_mix(name, &bases, &conc).unwrap();
        for line in truth.lines().filter(|l| !l.starts_with('#')).skip(1) {
            let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
            let i = ((v[0] - 380.0) / 5.0) as usize; // some truths are on a 10 nm grid
            for (got, want) in [(mix.s.0[i], v[1]), (mix.k.0[i], v[2])] {
                // The library is written with 6 significant digits, the truth with 6 decimals.
                assert!((got - want).abs() <= 2e-5 * want.abs() + 1e-6, "{name} at {} nm: {got} vs {want}", v[0]);
            }
        }
        checked += 1;
    }
    assert_eq!(checked, 13);
}
