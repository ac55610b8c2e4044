// Shared by the cube-atlas passes (atlas_irradiance, atlas_gather): their uniform and the atlas
// geometry. CPU twins: render/src/cube_atlas.rs (AtlasFrame; derivations there). Keep `AtlasPass`
// in sync with passes/cube_atlas/mod.rs (tests/shaders.rs checks it with naga).

struct AtlasPass {
    // per face: world → clip of its orthographic view
    view_proj: array<mat4x4<f32>, 6>,
    // per face: outward axis a, image right U, image up V (xyz)
    axis: array<vec4<f32>, 6>,
    right: array<vec4<f32>, 6>,
    up: array<vec4<f32>, 6>,
    // xyz the cube's centre (mm), w half its side (mm)
    cube: vec4<f32>,
    // per channel c: x α′, y σ_tr (mm⁻¹), z z_r (mm), w z_v (mm) of the classic dipole
    medium: array<vec4<f32>, 3>,
    // x η, y texel side (mm), z face side (texels), w smallest n·a of a texel's area
    params: vec4<f32>,
    // x kernel half side (taps), y adaptive kernel (0/1), z self-occlusion test
    // (0 off, 1 plane offset, 2 tangent plane), w global term (0 off, 1 real source, 2 slab)
    settings: vec4<u32>,
    // x the kernel's radius at sp = 1 (reach × the longest mean free path, mm)
    kernel: vec4<f32>,
    // the environment's SH bands scaled for the Fresnel transmittance (l = 0, 1, 2 in x, y, z)
    sh_fresnel: vec4<f32>,
}
@group(1) @binding(0) var<uniform> atlas: AtlasPass;

// Continuous texel coordinates of `p` on face `f` (x right, y down).
fn atlas_texel(f: u32, p: vec3<f32>) -> vec2<f32> {
    let d = p - atlas.cube.xyz;
    let h = atlas.cube.w;
    let n = atlas.params.z;
    return vec2<f32>((dot(atlas.right[f].xyz, d) / h * 0.5 + 0.5) * n, (0.5 - dot(atlas.up[f].xyz, d) / h * 0.5) * n);
}

// The world point at continuous texel coordinates `t` and [0, 1] depth `z` of face `f`.
fn atlas_point(f: u32, t: vec2<f32>, z: f32) -> vec3<f32> {
    let n = atlas.params.z;
    let h = atlas.cube.w;
    let s = 2.0 * t.x / n - 1.0;
    let q = 1.0 - 2.0 * t.y / n;
    return atlas.cube.xyz + atlas.right[f].xyz * (h * s) + atlas.up[f].xyz * (h * q)
        + atlas.axis[f].xyz * (h - 2.0 * h * z);
}
