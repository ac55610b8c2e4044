// Inserted into thickness.wgsl (the slab variant): the transmission gather's kernel
// (SlabThrough::Gather, render/src/through_gather.rs its CPU twin), which `hidden_entry` takes
// where it is chosen.

// The flux through the exit face (outward normal `no`) at `xo` of a unit point source of the
// diffusion equation at `s`, with its image across the exit face's extrapolated boundary z_b
// outside it (of opposite sign, so the fluence vanishes there): h the source's depth below the
// exit's tangent plane, ρ its offset along it,
//   h·f(√(ρ² + h²)) + (h + 2z_b)·f(√(ρ² + (h + 2z_b)²)),  f(d) = (1 + σd)e^{−σd}/d³,
// a unit source's term of [Donner2005]'s multipole for a slab's transmission, its i = 0 pair,
// for a face of any orientation. Over the whole exit plane it totals 2π(e^{−σh} + e^{−σ(h+2z_b)}).
// The distances are held at `floor_mm` (the real source's depth z_r) and above: a source is a
// mean free path's spread of first scatterings, not a point, and where a thin part's exit lies
// within z_r of it (a fingertip) the point's 1/d² would single out the pixel (a firefly the
// kernel then spreads into its taps' pattern).
fn exit_flux(s: vec3<f32>, xo: vec3<f32>, no: vec3<f32>, z_b: f32, sigma: f32, floor_mm: f32) -> f32 {
    let d = xo - s;
    let h = dot(d, no);
    let rho2 = max(dot(d, d) - h * h, 0.0);
    let h_image = h + 2.0 * z_b;
    return h * point_source_flux(1.0, max(sqrt(rho2 + h * h), floor_mm), sigma)
        + h_image * point_source_flux(1.0, max(sqrt(rho2 + h_image * h_image), floor_mm), sigma);
}

// The light entering at `xi` (outward normal `ni`) that leaves through the exit face at `xo`
// (outward normal `no`) per mm² of entry, one channel: the classic dipole's sources
// ([Jensen2001]: the real one z_r inside the entry face, the virtual one z_v outside it; `m` is
// (α′, σ_tr, z_r, z_v)), each seen through the exit face with its image there (`exit_flux`), at
// the medium's exact asymptotic decay `sigma` = κσt′ (Case's eigenvalue, the slab law's
// `slab_transmittance::kappa`) in place of diffusion's σ_tr, which decays too fast as the
// albedo falls (2% in red, 7% in green, 16% in blue for skin1). The projections on the exit's
// own normal make it a transmission kernel: across a finger the exit face turns away from the
// entry face, and the flux through it is not the entry plane's. Over a plane slab of thickness
// d ≥ 2z_r at right angles it totals
// α′/2 (e^{−σ(d−z_r)} + e^{−σ(d−z_r+2z_b)} − e^{−σ(d+z_v)} − e^{−σ(d+z_v+2z_b)}); the exact
// slab (adding-doubling) carries 1.01-1.05× that in skin1's red from 7 to 25 mm, 1.17-1.28× in
// green, 1.50-1.86× in blue (render/src/through_gather.rs, docs/BENCHMARKS.md).
fn through_entry(m: vec4<f32>, sigma: f32, xi: vec3<f32>, ni: vec3<f32>, xo: vec3<f32>, no: vec3<f32>) -> f32 {
    let z_b = 0.5 * (m.w - m.z);
    let real = exit_flux(xi - m.z * ni, xo, no, z_b, sigma, m.z);
    let virtual_source = exit_flux(xi + m.w * ni, xo, no, z_b, sigma, m.z);
    return max(m.x / (4.0 * PI) * (real - virtual_source), 0.0);
}

// `through_entry` per channel, at the medium's exact decay rates κσt′.
fn through_entry3(xi: vec3<f32>, ni: vec3<f32>, xo: vec3<f32>, no: vec3<f32>) -> vec3<f32> {
    let decay = params.slab_kappa.xyz * params.slab_sigma_t.xyz;
    return vec3<f32>(
        through_entry(params.gather_medium[0], decay.x, xi, ni, xo, no),
        through_entry(params.gather_medium[1], decay.y, xi, ni, xo, no),
        through_entry(params.gather_medium[2], decay.z, xi, ni, xo, no),
    );
}
