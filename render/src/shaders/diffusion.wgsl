// Shared by the diffusion models' passes (the dipoles, the cube atlas): the Fresnel reflectance
// and the flux of a point source of the classic dipole.

// Unpolarised Fresnel reflectance from outside into relative index η (CPU: diffusion::fresnel_dielectric).
fn fresnel_in(cos_i: f32, eta: f32) -> f32 {
    let c = clamp(cos_i, 0.0, 1.0);
    let sin2_t = (1.0 - c * c) / (eta * eta);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = sqrt(1.0 - sin2_t);
    let rs = (c - eta * cos_t) / (c + eta * cos_t);
    let rp = (eta * c - cos_t) / (eta * c + cos_t);
    return 0.5 * (rs * rs + rp * rp);
}

// z(1 + σ_tr d)e^{−σ_tr d}/d³: the flux through the surface of a point source at depth (or
// height) z seen at distance d, the term of [Jensen2001]'s dipole (CPU: diffusion::point_source_flux).
fn point_source_flux(z: f32, d_in: f32, sigma_tr: f32) -> f32 {
    let d = max(d_in, 1e-6);
    return z * (1.0 + sigma_tr * d) * exp(-sigma_tr * d) / (d * d * d);
}

// [Benmounah2009] Table 1 corrected (diffusion::ChannelProfile::classic_between): the classic
// dipole's R per mm² for light entering at `xi` (outward normal `ni`) and leaving at `xo`, the
// real source at xi − z_r·ni and the virtual one at xi + z_v·ni; `m` is one channel's
// (α′, σ_tr mm⁻¹, z_r mm, z_v mm) (ChannelProfile::classic_constants).
fn classic_between(m: vec4<f32>, xi: vec3<f32>, ni: vec3<f32>, xo: vec3<f32>) -> f32 {
    return m.x / (4.0 * PI) * (point_source_flux(m.z, length(xi - m.z * ni - xo), m.y)
        + point_source_flux(m.w, length(xi + m.w * ni - xo), m.y));
}

// [Jensen2001]'s dipole R(r) per mm² at distance `r_mm` on a plane (diffusion::ChannelProfile::
// radial, classic), `m` as in classic_between.
fn dipole_radial(m: vec4<f32>, r_mm: f32) -> f32 {
    let r2 = r_mm * r_mm;
    return m.x / (4.0 * PI) * (point_source_flux(m.z, sqrt(r2 + m.z * m.z), m.y)
        + point_source_flux(m.w, sqrt(r2 + m.w * m.w), m.y));
}
