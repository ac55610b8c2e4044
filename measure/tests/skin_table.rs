//! The skin colour table against the exact model: random faces' parameters around every tone,
//! and the edges of the domain.

use rouge_measure::colorimetry::{Colorimeter, Viewing, delta_e_2000_raw, linear_srgb_to_lab};
use rouge_measure::skin::{SkinColorTable, SkinParams, skin_tone};

/// A small deterministic generator (SplitMix64).
fn next(state: &mut u64) -> f64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
}

#[test]
fn the_table_matches_the_model() {
    let c = Colorimeter::get(Viewing::D65_1931);
    let mut state = 7u64;
    let mut errors = Vec::new();
    // The lightest, a middle and the deepest tone (the deepest is the table's hardest case).
    for name in ["very-light", "olive", "very-deep"] {
        let tone = skin_tone(name).expect("a built-in tone");
        let table = SkinColorTable::new(&tone.params).expect("table");
        for _ in 0..60 {
            // What a face map holds around the tone: melanin ×0.3-3, blood ×0.5-6 (lips, flush),
            // any share and saturation, epidermis 0.03-0.15 mm.
            let b = tone.params;
            let p = SkinParams {
                melanin_fraction: (b.melanin_fraction * (0.3 + 2.7 * next(&mut state))).min(0.6),
                pheomelanin_share: next(&mut state),
                blood_fraction: (b.blood_fraction * (0.5 + 5.5 * next(&mut state))).min(0.3),
                oxygen_saturation: next(&mut state),
                epidermis_thickness_mm: 0.03 + 0.12 * next(&mut state),
                ..b
            };
            let exact = c.srgb_linear(&c.xyz(&p.reflectance().expect("model")));
            let fast = table.linear_srgb(&p).map(f64::from);
            errors.push(delta_e_2000_raw(linear_srgb_to_lab(exact), linear_srgb_to_lab(fast)));
        }
    }
    errors.sort_by(f64::total_cmp);
    let p95 = errors[errors.len() * 95 / 100];
    let max = errors[errors.len() - 1];
    eprintln!("skin colour table: ΔE2000 median {:.3}, p95 {p95:.3}, max {max:.3}", errors[errors.len() / 2]);
    assert!(p95 < 0.5 && max < 1.5, "p95 {p95}, max {max}");
}

#[test]
fn the_edges_of_the_domain_give_colours_not_nan() {
    let base = SkinParams::LIGHT;
    let table = SkinColorTable::new(&base).expect("table");
    let [m, _, b, _, e] = table.max();
    for p in [
        SkinParams { melanin_fraction: 0.0, blood_fraction: 0.0, epidermis_thickness_mm: 0.0, ..base },
        SkinParams { melanin_fraction: m / e, blood_fraction: b, epidermis_thickness_mm: e, ..base },
        SkinParams { melanin_fraction: 9.0, blood_fraction: -1.0, oxygen_saturation: f64::NAN, ..base },
    ] {
        let rgb = table.linear_srgb(&p);
        assert!(rgb.iter().all(|v| v.is_finite() && (0.0..=1.0).contains(v)), "{p:?}: {rgb:?}");
    }
    // Out of range reads as the range's edge.
    let edge = table.linear_srgb(&SkinParams { melanin_fraction: 0.0, blood_fraction: b, ..base });
    assert_eq!(table.linear_srgb(&SkinParams { melanin_fraction: -1.0, blood_fraction: 9.0, ..base }), edge);
    // A tone whose scattering forbids a thick epidermis shortens the axis, never errs.
    let dense =
        SkinParams { scattering_500nm_per_mm: 10.0, scattering_power: 4.0, epidermis_thickness_mm: 0.05, ..base };
    let t = SkinColorTable::new(&dense).expect("table");
    assert!(t.max()[4] < 0.3);
}

/// The table's bytes (for the cache on disk, rouge_model::skin::table_cache) read back as the
/// same table, and every way they can be wrong is refused: another tone, a cut, another layout,
/// a probe node the model now computes otherwise (a table of another model version).
#[test]
fn the_table_reads_back_from_its_bytes_and_refuses_what_is_not_it() {
    let base = skin_tone("olive").expect("a built-in tone").params;
    let table = SkinColorTable::new(&base).expect("table");
    let bytes = table.to_bytes();
    let back = SkinColorTable::from_bytes(&base, &bytes).expect("its own bytes");
    assert_eq!(back.to_bytes(), bytes);
    let mut state = 3u64;
    for _ in 0..50 {
        let p = SkinParams {
            melanin_fraction: 0.3 * next(&mut state),
            blood_fraction: 0.1 * next(&mut state),
            epidermis_thickness_mm: 0.03 + 0.1 * next(&mut state),
            ..base
        };
        assert_eq!(back.linear_srgb(&p), table.linear_srgb(&p));
    }
    let other = SkinParams { blood_fraction: base.blood_fraction + 1e-12, ..base };
    assert!(SkinColorTable::from_bytes(&other, &bytes).is_none(), "another tone's table");
    assert!(SkinColorTable::from_bytes(&base, &bytes[..bytes.len() - 1]).is_none(), "cut short");
    assert!(SkinColorTable::from_bytes(&base, &[]).is_none(), "empty");
    let mut layout = bytes.clone();
    layout[8] ^= 1;
    assert!(SkinColorTable::from_bytes(&base, &layout).is_none(), "another layout version");
    // The header is 8 + 4 + 96 + 20 bytes, then 12 per node; node (count/2)/8 is the first of
    // the 8 probes.
    let count = (bytes.len() - 128) / 12;
    let probe = 128 + 12 * ((count / 2) / 8);
    let mut stale = bytes.clone();
    stale[probe] ^= 1;
    assert!(SkinColorTable::from_bytes(&base, &stale).is_none(), "a probe node the model disagrees with");
    let mut nan = bytes.clone();
    nan[128..132].copy_from_slice(&f32::NAN.to_le_bytes());
    assert!(SkinColorTable::from_bytes(&base, &nan).is_none(), "a NaN node");
}
