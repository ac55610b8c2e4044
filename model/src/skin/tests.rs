//! The maps' invariant at the edges of the domain: every texel valid, never NaN.

use super::*;
use rouge_measure::skin::skin_tones;

/// Bases at the corners of the parameter box (and past them), with the scattering that makes the
/// epidermis' bound tighter than its range.
fn edge_bases() -> Vec<SkinParams> {
    let mut out = Vec::new();
    for (lo, hi) in [(true, false), (false, true), (true, true), (false, false)] {
        let pick = |r: rouge_measure::skin::ParamRange, high: bool| if high { r.max } else { r.min };
        let a: Vec<f64> =
            SkinParams::RANGES.iter().enumerate().map(|(i, &r)| pick(r, if i % 2 == 0 { lo } else { hi })).collect();
        out.push(SkinParams::from_array(a.try_into().unwrap()));
    }
    out.push(SkinParams {
        epidermis_thickness_mm: 0.3,
        scattering_500nm_per_mm: 10.0,
        scattering_power: 4.0,
        ..SkinParams::LIGHT
    });
    out.push(SkinParams { melanin_fraction: f64::NAN, blood_fraction: f64::INFINITY, ..SkinParams::LIGHT });
    out.push(SkinParams {
        oxygen_saturation: -1.0,
        pheomelanin_share: 7.0,
        epidermis_thickness_mm: -0.1,
        ..SkinParams::LIGHT
    });
    out.extend(skin_tones().iter().map(|t| t.params));
    out
}

#[test]
fn clamping_makes_every_base_valid_and_keeps_valid_values() {
    for p in edge_bases() {
        let c = clamp_params(&p);
        c.validate().unwrap_or_else(|e| panic!("{p:?} clamps to {c:?}: {e}"));
        assert!(c.to_array().iter().all(|v| v.is_finite()));
        if p.validate().is_ok() {
            assert_eq!(c, p, "a valid base is left as it is");
        }
    }
    // The epidermis' bound under the strongest scattering is the table's: μs′(380)·d just under 3.
    let thick = SkinParams {
        epidermis_thickness_mm: 0.3,
        scattering_500nm_per_mm: 10.0,
        scattering_power: 4.0,
        ..SkinParams::LIGHT
    };
    let d = clamp_params(&thick).epidermis_thickness_mm;
    assert!(d < 0.3 && d > 0.05, "{d}");
    assert!(SkinChannel::Epidermis.with(&thick, d * (1.0 + 1e-6)).validate().is_err(), "the bound is tight");
}

#[test]
fn uniform_maps_are_valid_everywhere_they_are_read() {
    for p in edge_bases() {
        let m = SkinMaps::uniform(&p);
        assert_eq!((m.width(), m.height()), (1, 1));
        for (x, y) in [(0, 0), (5, 9), (u32::MAX, u32::MAX)] {
            m.texel(x, y).validate().unwrap_or_else(|e| panic!("{p:?} texel ({x}, {y}): {e}"));
        }
        for (u, v) in [(0.5, 0.5), (-3.0, 7.0), (f32::NAN, f32::INFINITY), (1.0, 0.0)] {
            m.sample_uv(u, v).validate().unwrap_or_else(|e| panic!("{p:?} uv ({u}, {v}): {e}"));
        }
    }
}

#[test]
fn from_planes_refuses_what_is_out_of_range_naming_it() {
    let base = SkinParams::LIGHT;
    let planes = || SkinChannel::ALL.map(|c| vec![c.of(&base) as f32; 6]);
    assert!(SkinMaps::from_planes(3, 2, &base, planes()).is_ok());
    let mut bad = planes();
    bad[SkinChannel::Blood as usize][4] = 0.5;
    let e = SkinMaps::from_planes(3, 2, &base, bad).unwrap_err();
    assert!(e.contains("texel (1, 1)") && e.contains("blood_fraction") && e.contains("0.5"), "{e}");
    let mut nan = planes();
    nan[SkinChannel::Oxygen as usize][0] = f32::NAN;
    assert!(SkinMaps::from_planes(3, 2, &base, nan).unwrap_err().contains("oxygen_saturation"));
    let e = SkinMaps::from_planes(4, 2, &base, planes()).unwrap_err();
    assert!(e.contains("6 values for 4×2"), "{e}");
    assert!(SkinMaps::from_planes(0, 0, &base, Default::default()).is_err());
}

#[test]
fn bilinear_sampling_meets_the_texel_centres_and_stays_between_them() {
    let base = SkinParams::LIGHT;
    let mut planes = SkinChannel::ALL.map(|c| vec![c.of(&base) as f32; 4]);
    planes[SkinChannel::Blood as usize] = vec![0.0, 0.1, 0.2, 0.29];
    let m = SkinMaps::from_planes(2, 2, &base, planes).unwrap();
    let blood = |u: f32, v: f32| m.sample_uv(u, v).blood_fraction;
    // Texel (1, 0) is the top right: centre u = 0.75, v = 0.75.
    assert_eq!(blood(0.75, 0.75), f64::from(0.1f32));
    assert_eq!(m.texel(1, 0).blood_fraction, f64::from(0.1f32));
    let mid = blood(0.5, 0.5);
    assert!((mid - 0.1475).abs() < 1e-7, "{mid}");
    assert_eq!(blood(-1.0, 2.0), 0.0, "clamp to edge");
    assert_eq!(blood(1.0, 0.0), f64::from(0.29f32), "the bottom right texel's centre and past it");
}
