// Shadow pass: depth of the mesh seen from one light. The light's matrix is in `frame.lights`;
// which light is given by the per-pass uniform below.

struct ShadowPass {
    // x: light index
    index: vec4<u32>,
}
@group(1) @binding(0) var<uniform> shadow_pass: ShadowPass;

@vertex
fn vs_shadow(@location(0) position: vec3<f32>) -> @builtin(position) vec4<f32> {
    return frame.lights[shadow_pass.index.x].shadow_view_proj * vec4<f32>(position, 1.0);
}
