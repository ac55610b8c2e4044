//! The skin model's transport against references nobody here wrote (docs/SKIN.md):
//!
//! * adding-doubling (iadpython, [Prahl1993]) at 300 random points between the table's nodes
//!   (`data/skin/transport_ad_check.csv`, python/gen_skin_transport.py --check): the
//!   interpolation error;
//! * Mitsuba 3's volumetric path tracer on two-layer and single-layer slabs
//!   (`data/skin/transport_reference.csv`, python/gen_skin_transport_reference.py): the whole
//!   transport, conventions included (what "reflectance" means, g, the boundary).

use rouge_measure::skin::transport::two_layer_reflectance;

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
    assert!(p95 < 2.5e-3 && max < 5e-3, "p95 {p95}, max {max}");
    assert!(skin[skin.len() * 95 / 100] < 5e-4, "μs′d ≤ 1: {skin:?}");
}
