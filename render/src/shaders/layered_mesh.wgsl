// The mesh drawn once per array layer of the pass's targets, as instance `layer`
// (FrameEncoder::draw_mesh_per_layer): the dipoles' light G-buffer (a layer per light view), their
// radiance maps (a layer per direction) and the cube atlas (a layer per face). The pass defines
// `fn layer_view_proj(layer: u32) -> mat4x4<f32>`, the view of each layer, before inserting this.
struct LayerVsOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    // Albedo alpha: 1 where the surface is skin (the medium), 0 elsewhere (eyes).
    @location(2) skin: f32,
    @location(3) @interpolate(flat) layer: u32,
}

@vertex
fn vs_layer(
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(3) albedo: vec4<f32>,
    @builtin(instance_index) layer: u32,
) -> LayerVsOut {
    var out: LayerVsOut;
    out.clip = layer_view_proj(layer) * vec4<f32>(position, 1.0);
    out.world = position;
    out.normal = normal;
    out.skin = albedo.a;
    out.layer = layer;
    return out;
}
