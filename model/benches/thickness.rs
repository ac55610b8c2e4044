//! Local-thickness bake time ([BarreBrisebois2011]) of the render mesh: the default head,
//! Catmull-Clark twice and triangulated, as `load_mesh(None, 1.0, 2)` gives the renderer
//! (render/src/job.rs: subdivision 2), at the default settings (64 rays, cutoff 30 mm).
//! Prints the vertex count and rays/s once. Measured 2026-11-23 on the shared 2-core CPU (load
//! about 5.8 from other builds): 71 346 vertices, 140 864 triangles, 4.57 M rays, median 3.2 s
//! (2.9-3.6 s), 1.4 M rays/s.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use rouge_model::mesh::default_head;
use rouge_model::thickness::{BakeSettings, bake_local_thickness};
use std::hint::black_box;

fn bench_bake(c: &mut Criterion) {
    let Ok(head) = default_head() else { panic!("embedded head must parse") };
    let mesh = head.catmull_clark(2).triangulate();
    let settings = BakeSettings::default();
    let rays = mesh.vertex_count() as u64 * u64::from(settings.rays);
    match bake_local_thickness(&mesh, &settings) {
        Ok(bake) => eprintln!(
            "head: {} vertices, {} triangles, {} rays: one bake {:.1} ms ({:.2} Mrays/s)",
            mesh.vertex_count(),
            mesh.triangle_count(),
            rays,
            bake.bake_seconds * 1.0e3,
            rays as f64 / bake.bake_seconds / 1.0e6
        ),
        Err(e) => panic!("bake failed: {e}"),
    }
    let mut group = c.benchmark_group("thickness");
    group.sample_size(10);
    group.throughput(Throughput::Elements(rays));
    group.bench_function("bake_head_sub2_64rays", |b| {
        b.iter(|| bake_local_thickness(black_box(&mesh), black_box(&settings)).map(|t| t.value.len()))
    });
    group.finish();
}

criterion_group!(benches, bench_bake);
criterion_main!(benches);
