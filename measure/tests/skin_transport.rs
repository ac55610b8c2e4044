//! The skin model's transport against references nobody here wrote (docs/SKIN.md):
//!
//! * adding-doubling (iadpython, [Prahl1993]) at 300 random points between the table's nodes
//!   (`data/skin/transport_ad_check.csv`, python/gen_skin_transport.py --check): the
//!   interpolation error;
//! * Mitsuba 3's volumetric path tracer on two-layer and single-layer slabs
//!   (`data/skin/transport_reference.csv`, python/gen_skin_transport_reference.py): the whole
//!   transport, conventions included (what "reflectance" means, g, the boundary).

use rouge_measure::skin::transport::{ANISOTROPY_G, TISSUE_INDEX, two_layer_reflectance};

fn rows(csv: &str) -> Vec<Vec<String>> {
    csv.lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| l.split(',').map(|c| c.trim().to_string()).collect())
        .collect()
}

fn column(header: &[String], name: &str) -> usize {
    header.iter().position(|h| h == name).unwrap_or_else(|| panic!("no column {name}"))
}

#[test]
fn the_table_interpolates_adding_doubling_between_its_nodes() {
    let data = rows(include_str!("../../data/skin/transport_ad_check.csv"));
    let (header, data) = data.split_first().unwrap();
    let (a, s, al, r) = (
        column(header, "tau_a_epi"),
        column(header, "tau_sr_epi"),
        column(header, "reduced_albedo_derm"),
        column(header, "reflectance"),
    );
    let with_tau: Vec<(f64, f64)> = data
        .iter()
        .map(|row| {
            let f = |i: usize| row[i].parse::<f64>().unwrap();
            let ours = two_layer_reflectance(f(a), f(s), f(al)).unwrap();
            (f(s), (ours - f(r)).abs())
        })
        .collect();
    // Realistic skin: μs′d up to 1 (0.1 mm at μs′ ≤ 10 /mm).
    let mut skin: Vec<f64> = with_tau.iter().filter(|(t, _)| *t <= 1.0).map(|(_, e)| *e).collect();
    skin.sort_by(f64::total_cmp);
    eprintln!(
        "μs′d ≤ 1: {} points, p95 {:.2e}, max {:.2e}",
        skin.len(),
        skin[skin.len() * 95 / 100],
        skin[skin.len() - 1]
    );
    let mut errors: Vec<f64> = with_tau.iter().map(|(_, e)| *e).collect();
    errors.sort_by(f64::total_cmp);
    let p95 = errors[errors.len() * 95 / 100];
    let max = errors[errors.len() - 1];
    eprintln!("interpolation against adding-doubling, {} points: p95 {p95:.2e}, max {max:.2e}", errors.len());
    assert!(p95 < 1.5e-3 && max < 4e-3, "p95 {p95}, max {max}");
    assert!(skin[skin.len() * 95 / 100] < 3e-4, "μs′d ≤ 1: {skin:?}");
}
#[test]
fn adding_doubling_agrees_with_mitsuba_on_layered_slabs() {
    let data = rows(include_str!("../../data/skin/transport_reference.csv"));
    let (header, data) = data.split_first().unwrap();
    let col = |n: &str| column(header, n);
    let r_ad = col("r_iad");
    let (mua_e, mus_e, g, d, mua_d, mus_d, n, r_mi, se) = (
        col("mua_epi_per_mm"),
        col("mus_epi_per_mm"),
        col("g"),
        col("thickness_epi_mm"),
        col("mua_derm_per_mm"),
        col("mus_derm_per_mm"),
        col("n"),
        col("r_mitsuba"),
        col("r_mitsuba_stderr"),
    );
    let mut checked = 0;
    for row in data {
        let f = |i: usize| row[i].parse::<f64>().unwrap();
        if (f(g) - ANISOTROPY_G).abs() > 1e-9 || (f(n) - TISSUE_INDEX).abs() > 1e-9 {
            continue;
        }
        let tau_a = f(mua_e) * f(d);
        let tau_s = f(mus_e) * (1.0 - f(g)) * f(d);
        let sr = f(mus_d) * (1.0 - f(g));
        let ours = two_layer_reflectance(tau_a, tau_s, sr / (sr + f(mua_d))).unwrap();
        let diff = ours - f(r_mi);
        // The same slab by adding-doubling directly: the table's interpolation error there.
        assert!((ours - f(r_ad)).abs() < 1.5e-3, "{}: ours {ours}, adding-doubling {}", row[0], f(r_ad));
        eprintln!("{}: ours {ours:.4}, Mitsuba {:.4} ± {:.4}", row[0], f(r_mi), f(se));
        assert!(diff.abs() <= 4.0 * f(se) + 0.004, "{}: ours {ours}, Mitsuba {} ± {}", row[0], f(r_mi), f(se));
        checked += 1;
    }
    assert!(checked >= 10, "only {checked} rows with g = {ANISOTROPY_G}, n = {TISSUE_INDEX}");
}
