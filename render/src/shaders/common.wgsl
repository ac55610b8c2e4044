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
    // x: the light's scale of the thickness translucency, y: near and z: far plane of its shadow
    // projection (mm), w: 1 for a perspective (point light) projection, 0 for orthographic.
    translucency: vec4<f32>,
    shadow_view_proj: mat4x4<f32>,
}

struct Layer {
    // x: Beckmann roughness, y: Fresnel F0, z: thickness (mm) at which the layer's own specular
    // lobe is fully formed, w: the clarity of its finish (the part of the lobes below it that a
    // fully formed layer passes specularly).
    params: vec4<f32>,
    // x: the finish's levelling (rouge_measure::finish::pore_relief), y: its shimmer's strength
    // (0 without one), z: the shimmer platelets' spread (Beckmann roughness), w: unused.
    film: vec4<f32>,
    // The glitter's flake field (render/src/glitter.rs FlakeField): x cell edge (mm; 0 without
    // glitter), y flake edge (mm), z probability of a flake in a cell, w the flakes' spread.
    glitter: vec4<f32>,
    // rgb: the flakes' reflectance (linear sRGB), w: the preset's thickness (mm) at which the
    // flakes have their density (a thinner film has proportionally fewer).
    glitter_color: vec4<f32>,
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
    // x: skin Beckmann roughness, y: skin F0, z: 1 when specular is on, w: skin detail tiles per
    // UV unit (render/src/gpu_look.rs SkinDetailTextures; 0 without detail)
    skin: vec4<f32>,
    // x: SSS width (profile scale), y: depth follow (mm), z: sample count, w: the skin's diffuse
    // law (0 Lambert, 1 half-space: render/src/half_space.rs, lighting.wgsl)
    sss: vec4<f32>,
    // rgb: background at the top, w: unused
    background: vec4<f32>,
    // x: lights, y: layers, z: table entries per row, w: unused
    counts: vec4<u32>,
    // [0]: the wrinkle map's UV square (u0, v0, side, 1 / texels across; side 0 without wrinkles);
    // [1], [2]: each family's depth (mm: forehead, crow's feet, nasolabial, lip furrows) on the
    // left (+x) and the right (model/src/skin/wrinkles.rs)
    wrinkles: array<vec4<f32>, 3>,
    sh: array<vec4<f32>, 9>,
    lights: array<Light, 4>,
    layers: array<Layer, 8>,
    // x: the mesh's mm per UV unit (the glitter's flake field; 0 without glitter), yzw: unused
    surface: vec4<f32>,
}

@group(0) @binding(0) var<uniform> frame: Frame;

const PI: f32 = 3.14159265358979;

// View depth (mm, positive) from a [0, 1] depth-buffer value of the perspective projection.
fn linear_depth(d: f32) -> f32 {
    let n = frame.projection.y;
    let f = frame.projection.z;
    return n * f / (f - d * (f - n));
}

// World position (mm) of the pixel at `frag` (pixel coordinates) with depth-buffer value `depth`.
fn world_at(frag: vec2<f32>, depth: f32) -> vec3<f32> {
    let ndc = vec2<f32>(frag.x * frame.viewport.z * 2.0 - 1.0, 1.0 - frag.y * frame.viewport.w * 2.0);
    let world_h = frame.inv_view_proj * vec4<f32>(ndc, depth, 1.0);
    return world_h.xyz / world_h.w;
}

// How a light arrives at `world`: the unit vector toward it and its irradiance at normal
// incidence there (a point light's falls off with the squared distance from the scene centre's).
struct Arrival {
    l: vec3<f32>,
    e: vec3<f32>,
}

fn light_arrival(light: Light, world: vec3<f32>) -> Arrival {
    var a: Arrival;
    a.e = light.color.rgb;
    if light.position.w == 0.0 {
        a.l = light.position.xyz;
    } else {
        let d = light.position.xyz - world;
        let d2 = max(dot(d, d), 1e-6);
        a.l = d * inverseSqrt(d2);
        a.e = a.e * (light.color.w / d2);
    }
    return a;
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
