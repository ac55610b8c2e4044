//! Skin maps at the command line's default size (1024²): generating them from a tone with the
//! default head's anatomy, with all seven conditions, and baking their colour into the albedo
//! texture through the tone's colour table, and what the painting app does per animation frame
//! and per skin dab: the blood following a full smile, the skin edits applied, a 32² rectangle
//! re-baked (docs/SKIN.md "Skin maps on screen", "The app's Skin panel"; figures in
//! docs/BENCHMARKS.md).

use criterion::{Criterion, criterion_group, criterion_main};
use rouge_measure::skin::{SkinColorTable, SkinParams};
use rouge_model::TexelRect;
use rouge_model::mesh::targets::Weights;
use rouge_model::skin::{SkinConditions, SkinEdits, SkinMaps};
use std::hint::black_box;

fn bench_skin(c: &mut Criterion) {
    let base = SkinParams::LIGHT;
    let none = SkinConditions::default();
    let all: SkinConditions =
        "freckles=0.6,moles=0.4,redness=0.5,acne=0.3,hyperpigmentation=0.3,under_eye=0.6,veins=0.6"
            .parse()
            .unwrap_or_default();
    let mut g = c.benchmark_group("skin_maps_1024");
    g.sample_size(10);
    g.bench_function("generate_anatomy", |b| b.iter(|| black_box(SkinMaps::generate(&base, &none, 1, 1024))));
    g.bench_function("generate_all_conditions", |b| b.iter(|| black_box(SkinMaps::generate(&base, &all, 1, 1024))));
    let (Ok(maps), Ok(table)) = (SkinMaps::generate(&base, &all, 1, 1024), SkinColorTable::new(&base)) else {
        panic!("the light tone makes maps and a table")
    };
    g.bench_function("albedo_image", |b| b.iter(|| black_box(maps.albedo_image(black_box(&table)))));
    let smile: Weights = ["mouthSmileLeft", "mouthSmileRight"].into_iter().map(|u| (u.to_string(), 1.0)).collect();
    g.bench_function("blood_flow_smile", |b| b.iter(|| black_box(maps.with_blood_flow(black_box(&smile)))));
    let edits = SkinEdits::new(2048, 2048);
    g.bench_function("with_edits", |b| b.iter(|| black_box(maps.with_edits(black_box(&edits)))));
    let rect = TexelRect::new(500, 500, 532, 532);
    g.bench_function("albedo_rect_32", |b| b.iter(|| black_box(maps.crop(rect).albedo_image(black_box(&table)))));
    g.finish();
}

criterion_group!(benches, bench_skin);
criterion_main!(benches);
