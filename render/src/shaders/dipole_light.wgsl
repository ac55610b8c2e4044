// Dipole light G-buffer ([DirDipoleThesis] section 4.2, step 1): the mesh seen from one
// directional light, orthographically: the world normal where the skin is (a = 1), nothing where
// it is not (eyes are not the medium); positions come back from the depth attachment.
//#insert diffusion
//#insert dipole_common

struct VsOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) normal: vec3<f32>,
    @location(1) skin: f32,
}

@vertex
fn vs_dipole_light(
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(3) albedo: vec4<f32>,
    @builtin(instance_index) slot: u32,
) -> VsOut {
    var out: VsOut;
    out.clip = dipole.light_view_proj[slot] * vec4<f32>(position, 1.0);
    out.normal = normal;
    out.skin = albedo.a;
    return out;
}

@fragment
fn fs_dipole_light(in: VsOut, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
    var n = normalize(in.normal);
    if !front {
        n = -n;
    }
    return vec4<f32>(n, select(0.0, 1.0, in.skin > 0.5));
}
