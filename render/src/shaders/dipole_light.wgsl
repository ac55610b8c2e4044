// Dipole light G-buffer ([DirDipoleThesis] section 4.2, step 1): the mesh seen from one
// directional light, orthographically: the world normal where the skin is (a = 1), nothing where
// it is not (eyes are not the medium); positions come back from the depth attachment.
//#insert diffusion
//#insert dipole_common

fn layer_view_proj(layer: u32) -> mat4x4<f32> {
    return dipole.light_view_proj[layer];
}

//#insert layered_mesh

@fragment
fn fs_dipole_light(in: LayerVsOut, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
    var n = normalize(in.normal);
    if !front {
        n = -n;
    }
    return vec4<f32>(n, select(0.0, 1.0, in.skin > 0.5));
}
