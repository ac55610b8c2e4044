//! A deforming frame's CPU side on the default head (the app's expressions, `rouge bench
//! deform`): the Face Units applied, then the planned subdivision's update at levels 1 and 2 on
//! one thread and on every core ([`SubdivisionPlan::update_on`]), against subdividing afresh
//! (figures in docs/BENCHMARKS.md, "Deforming the face per frame").

use criterion::{Criterion, criterion_group, criterion_main};
use rouge_model::mesh::default_head;
use rouge_model::mesh::deform::SubdivisionPlan;
use rouge_model::mesh::targets::{FacePose, TargetSet, expression_cycle};
use std::hint::black_box;

fn bench_deform(c: &mut Criterion) {
    let (Ok(head), Ok(targets)) = (default_head(), TargetSet::default_head()) else {
        panic!("the default head and its targets load")
    };
    let pose = FacePose { expression: expression_cycle(1.3), ..FacePose::default() };
    let mut posed = head.positions.clone();
    if let Err(e) = targets.apply(&pose, &mut posed) {
        panic!("the cycle's pose applies: {e}")
    }
    let mut g = c.benchmark_group("deform");
    g.sample_size(20);
    g.bench_function("targets", |b| {
        b.iter(|| {
            let mut p = head.positions.clone();
            black_box(targets.apply(black_box(&pose), &mut p).is_ok());
            p
        })
    });
    for level in [1u32, 2] {
        let plan = SubdivisionPlan::new(&head, level);
        let mut out = plan.rest().clone();
        for threads in [1, SubdivisionPlan::threads()] {
            g.bench_function(format!("update_level{level}_threads{threads}"), |b| {
                b.iter(|| plan.update_on(black_box(&posed), &mut out, threads))
            });
        }
        let mut moved = head.clone();
        moved.positions = posed.clone();
        g.bench_function(format!("afresh_level{level}"), |b| {
            b.iter(|| black_box(moved.catmull_clark(level).triangulate()))
        });
    }
    g.finish();
}

criterion_group!(benches, bench_deform);
criterion_main!(benches);
