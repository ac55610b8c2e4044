//! The hair shader's fibre scattering (shaders/fibre.wgsl) against its CPU twin
//! (`rouge_render::fibre::scattering`, itself measured against PBRT-v4's hair BSDF), on a real
//! device (lavapipe on CI): the WGSL function run in a compute shader over seeded random
//! tangents, light and view directions, absorptions and roughnesses.

use crate::common;

use glam::Vec3;
use rouge_render::Gpu;
use rouge_render::fibre::{WGSL_SCATTERING, scattering, wgsl_constants};

/// One evaluation: tangent, light, view (xyz) and σa (xyz) with the roughness in w.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Case {
    t: [f32; 4],
    l: [f32; 4],
    v: [f32; 4],
    sigma_a_roughness: [f32; 4],
}

const KERNEL: &str = r#"
struct Case { t: vec4<f32>, l: vec4<f32>, v: vec4<f32>, sigma_a_roughness: vec4<f32> }
@group(0) @binding(0) var<storage, read> cases: array<Case>;
@group(0) @binding(1) var<storage, read_write> results: array<vec4<f32>>;
@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= arrayLength(&cases) { return; }
    let c = cases[id.x];
    let s = c.sigma_a_roughness;
    results[id.x] = vec4<f32>(fibre_scattering(c.t.xyz, c.l.xyz, c.v.xyz, s.xyz, s.w), 0.0);
}
"#;

/// A unit vector from two uniform numbers.
fn direction(u: f32, w: f32) -> Vec3 {
    let z = 2.0 * u - 1.0;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = std::f32::consts::TAU * w;
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// The GPU's scattering of every case.
fn on_gpu(gpu: &Gpu, cases: &[Case]) -> Vec<[f32; 4]> {
    let source = format!("{}{WGSL_SCATTERING}{KERNEL}", wgsl_constants());
    let inputs = [(0, bytemuck::cast_slice(cases), wgpu::BufferUsages::STORAGE)];
    let bytes =
        common::run_kernel(gpu, "fibre twin", &source, &inputs, (1, (cases.len() * 16) as u64), cases.len() as u32);
    bytemuck::cast_slice(&bytes).to_vec()
}

#[test]
fn the_shaders_fibre_scattering_matches_its_cpu_twin() {
    let gpu = Gpu::headless().expect("a wgpu adapter (install mesa-vulkan-drivers for lavapipe)");
    // A seeded LCG: the same cases on every run.
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        (state >> 40) as f32 / (1u64 << 24) as f32
    };
    let cases: Vec<Case> = (0..4096)
        .map(|_| {
            let (t, l, v) = (direction(next(), next()), direction(next(), next()), direction(next(), next()));
            // The lashes' and brows' range: clear to black fibres, roughness 0.15-0.5.
            let sigma_a = [next() * 8.0, next() * 4.0, next() * 2.0];
            let roughness = 0.15 + 0.35 * next();
            Case {
                t: [t.x, t.y, t.z, 0.0],
                l: [l.x, l.y, l.z, 0.0],
                v: [v.x, v.y, v.z, 0.0],
                sigma_a_roughness: [sigma_a[0], sigma_a[1], sigma_a[2], roughness],
            }
        })
        .collect();
    let got = on_gpu(&gpu, &cases);
    let (mut worst, mut peak) = (0.0f32, 0.0f32);
    let mut at = (0.0f32, 0.0f32);
    let mut errors = Vec::new();
    for (c, g) in cases.iter().zip(&got) {
        let v3 = |a: [f32; 4]| Vec3::new(a[0], a[1], a[2]);
        let s = c.sigma_a_roughness;
        let want = scattering(v3(c.t), v3(c.l), v3(c.v), [s[0], s[1], s[2]], s[3]);
        for ch in 0..3 {
            assert!(g[ch].is_finite(), "{:?}: {}", c.t, g[ch]);
            // Relative to the value, with a floor at a hundredth of a typical lobe's height.
            let err = (g[ch] - want[ch]).abs() / want[ch].abs().max(1e-2);
            if err > worst {
                at = (
                    c.t[0] * c.l[0] + c.t[1] * c.l[1] + c.t[2] * c.l[2],
                    c.t[0] * c.v[0] + c.t[1] * c.v[1] + c.t[2] * c.v[2],
                );
            }
            worst = worst.max(err);
            errors.push(err);
            peak = peak.max(want[ch]);
        }
    }
    errors.sort_by(f32::total_cmp);
    let (median, p99) = (errors[errors.len() / 2], errors[errors.len() * 99 / 100]);
    eprintln!(
        "{} cases, peak {peak:.3}, relative error median {median:.1e}, 99th percentile {p99:.1e}, worst {worst:.2e} at t·l {:.5}, t·v {:.5}",
        cases.len(),
        at.0,
        at.1
    );
    assert!(peak > 1.0, "the lobes' peaks are among the cases: {peak}");
    // f32 on both sides. Most cases agree to a few ulp (lavapipe: median 1.4e-6). WGSL allows
    // asin the accuracy of atan2, 4096 ulp (about 2e-4 rad here), and a Gaussian lobe of width
    // b turns an angle error dθ into a relative error of x·dθ/b² at x from its centre: up to a
    // percent in the tails of the narrow TT lobe (lavapipe: 99th percentile 2.2e-3, worst 9.1e-3).
    // A wrong term (a factor, a sign, a width) is off by tens of percent on most cases.
    assert!(median < 1e-4 && p99 < 1e-2 && worst < 5e-2, "median {median}, 99th percentile {p99}, worst {worst}");
}
