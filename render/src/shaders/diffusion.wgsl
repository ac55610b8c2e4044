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
// height) z seen at distance d, the term of [Jensen2001]'s dipole (CPU: diffusion::ChannelProfile).
fn point_source_flux(z: f32, d_in: f32, sigma_tr: f32) -> f32 {
    let d = max(d_in, 1e-6);
    return z * (1.0 + sigma_tr * d) * exp(-sigma_tr * d) / (d * d * d);
}
