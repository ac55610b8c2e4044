// Shared declarations of every Rouge pass. The Rust side of `Frame` is `renderer::FrameUniform`;
// tests/shaders.rs checks the two layouts against each other with naga.
// Units: millimetres; world +Y up, the face looks toward +Z.

struct Light {
    // xyz: unit direction toward the light (w = 0) or position in mm (w = 1).
    position: vec4<f32>,
    // rgb: irradiance at normal incidence (directional) or at the scene centre (point);
    // w: squared distance of a point light to the scene centre, mm².
    color: vec4<f32>,
    // x: shadow map layer or -1, y: depth bias, z: normal offset (mm), w: shadow map texel size (uv).
    shadow: vec4<f32>,
    shadow_view_proj: mat4x4<f32>,
}

struct Layer {
    // x: Beckmann roughness, y: Fresnel F0, z: thickness (mm) at which the layer's own specular
    // lobe is fully formed, w: unused.
    params: vec4<f32>,
}

struct Frame {
    view_proj: mat4x4<f32>,
    inv_view_proj: mat4x4<f32>,
    view: mat4x4<f32>,
    camera_pos: vec4<f32>,
    // width, height, 1/width, 1/height
    viewport: vec4<f32>,
    // focal length in pixels, near (mm), far (mm), exposure
    projection: vec4<f32>,
    // x: skin Beckmann roughness, y: skin F0, z: 1 when specular is on, w: unused
    skin: vec4<f32>,
    // x: SSS width (profile scale), y: depth follow (mm), z: sample count, w: unused
    sss: vec4<f32>,
    // rgb: background at the top, w: unused
    background: vec4<f32>,
    // x: lights, y: layers, z: table entries per row, w: unused
    counts: vec4<u32>,
    sh: array<vec4<f32>, 9>,
    lights: array<Light, 4>,
    layers: array<Layer, 8>,
}

@group(0) @binding(0) var<uniform> frame: Frame;

const PI: f32 = 3.14159265358979;

// View depth (mm, positive) from a [0, 1] depth-buffer value of the perspective projection.
fn linear_depth(d: f32) -> f32 {
    let n = frame.projection.y;
    let f = frame.projection.z;
    return n * f / (f - d * (f - n));
}

struct FullscreenOut {
    @builtin(position) clip: vec4<f32>,
}

// One triangle covering the viewport.
@vertex
fn vs_fullscreen(@builtin(vertex_index) i: u32) -> FullscreenOut {
    let x = f32((i << 1u) & 2u);
    let y = f32(i & 2u);
    var out: FullscreenOut;
    out.clip = vec4<f32>(x * 2.0 - 1.0, 1.0 - y * 2.0, 0.0, 1.0);
    return out;
}
