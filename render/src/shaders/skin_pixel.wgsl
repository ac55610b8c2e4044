// The G-buffer of a full-screen pass that adds a diffusion model's light to the skin
// (passes/skin_gather.rs: the dipoles' combination, the cube atlas's gather), and the skin pixel
// under a fragment.

@group(1) @binding(1) var gb_normal: texture_2d<f32>;
@group(1) @binding(2) var gb_albedo: texture_2d<f32>;
@group(1) @binding(3) var gb_depth: texture_2d<f32>;
// The cosmetic stack's transmittance (the lighting pass's exit T); bound to a stand-in and not
// read when the look has no layers.
@group(1) @binding(15) var gb_exit_t: texture_2d<f32>;

// A skin pixel: its world position x (mm), unit normal n, unit direction v toward the camera,
// the cosmetic stack's transmittance t over it (1 without layers), the way in for light that a
// diffusion model gathers (passes/skin_gather.rs); ok is false where there is no skin.
struct SkinPixel {
    x: vec3<f32>,
    n: vec3<f32>,
    v: vec3<f32>,
    t: vec3<f32>,
    ok: bool,
}

fn skin_pixel(frag: vec4<f32>) -> SkinPixel {
    var s: SkinPixel;
    let p = vec2<i32>(frag.xy);
    let nd = textureLoad(gb_normal, p, 0);
    s.ok = nd.w != 0.0 && textureLoad(gb_albedo, p, 0).a >= 0.5;
    if !s.ok {
        return s;
    }
    s.n = normalize(nd.xyz);
    s.x = world_at(frag.xy, textureLoad(gb_depth, p, 0).r);
    s.v = normalize(frame.camera_pos.xyz - s.x);
    s.t = vec3<f32>(1.0);
    if frame.counts.y > 0u {
        s.t = textureLoad(gb_exit_t, p, 0).rgb;
    }
    return s;
}
