// Back-face depth pass (render/src/passes/back_depth.rs): the depth of the nearest face turned
// from the camera at each pixel, where the camera's ray leaves the mesh it entered (for a convex
// part; the first part's exit where parts overlap). The slab law marches its single scattering
// along the view ray to it (slab_march.wgsl). Faces toward the camera are discarded: the mesh is
// wound counter-clockwise outward, as the G-buffer's normals assume.

@vertex
fn vs_back_depth(@location(0) position: vec3<f32>) -> @builtin(position) vec4<f32> {
    return frame.view_proj * vec4<f32>(position, 1.0);
}

@fragment
fn fs_back_depth(@builtin(front_facing) front: bool) {
    if front {
        discard;
    }
}
