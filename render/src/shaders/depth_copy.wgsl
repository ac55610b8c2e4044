// Depth copy: the depth buffer, read as an unfilterable float texture, written bit for bit into
// an Rgba8Unorm target (the f32's four bytes, least significant in r), for backends that cannot
// copy depth textures to buffers and cannot render to 32-bit float targets (wgpu's GL backend).
// Picking and frame captures read the copy and reassemble the floats.

@group(1) @binding(0) var depth_in: texture_2d<f32>;

@fragment
fn fs_depth_copy(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    return unpack4x8unorm(bitcast<u32>(textureLoad(depth_in, vec2<i32>(frag.xy), 0).r));
}
