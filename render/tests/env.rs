//! Environment lighting: SH irradiance against brute-force integration, the equirectangular
//! convention, EXR loading and its errors, and the WGSL evaluator.

use std::f32::consts::PI;

use exr::prelude::*;
use glam::Vec3;
use rouge_render::env::{EnvMap, ShIrradiance, WGSL_SH_EVAL, direction_to_uv, studio_radiance};

/// `count` unit normals spread evenly over the sphere (Fibonacci lattice).
fn normals(count: usize) -> Vec<Vec3> {
    let golden = PI * (3.0 - 5f32.sqrt());
    (0..count)
        .map(|i| {
            let y = 1.0 - 2.0 * (i as f32 + 0.5) / count as f32;
            let r = (1.0 - y * y).sqrt();
            let (s, c) = (golden * i as f32).sin_cos();
            Vec3::new(r * c, y, r * s)
        })
        .collect()
}

/// SH irradiance against brute force over 400 normals and 3 channels.
#[derive(Debug)]
struct Errors {
    /// Max and mean of |E_sh − E_ref| / E_ref.
    max_rel: f64,
    mean_rel: f64,
    /// Max and mean of |E_sh − E_ref| / max_n E_ref (per channel): the error relative to the
    /// brightest irradiance, meaningful where a normal can face away from all light.
    max_peak: f64,
    mean_peak: f64,
}

fn sh_errors(env: &EnvMap) -> Errors {
    let sh = env.sh_irradiance();
    let ns = normals(400);
    let reference: Vec<[f64; 3]> = ns.iter().map(|&n| env.irradiance_brute_force(n)).collect();
    let peak: [f64; 3] = std::array::from_fn(|ch| reference.iter().map(|e| e[ch]).fold(0.0, f64::max));
    let mut r = Errors { max_rel: 0.0, mean_rel: 0.0, max_peak: 0.0, mean_peak: 0.0 };
    for (n, e_ref) in ns.iter().zip(&reference) {
        let e = sh.eval(*n);
        for ch in 0..3 {
            let diff = (f64::from(e[ch]) - e_ref[ch]).abs();
            r.max_rel = r.max_rel.max(diff / e_ref[ch]);
            r.mean_rel += diff / e_ref[ch];
            r.max_peak = r.max_peak.max(diff / peak[ch]);
            r.mean_peak += diff / peak[ch];
        }
    }
    r.mean_rel /= 3.0 * ns.len() as f64;
    r.mean_peak /= 3.0 * ns.len() as f64;
    if r.max_rel.is_finite() && r.max_rel < 1.0 {
        println!("  SH vs brute force: |ΔE|/E max {:.3}% mean {:.3}%", 100.0 * r.max_rel, 100.0 * r.mean_rel);
    }
    println!("  SH vs brute force: |ΔE|/max E max {:.3}% mean {:.3}%", 100.0 * r.max_peak, 100.0 * r.mean_peak);
    r
}

#[test]
fn env_constant_environment_gives_pi_l() {
    let l = [0.7f32, 1.3, 2.0];
    let env = EnvMap::from_fn(128, 64, |_| l);
    for sh in [env.sh_irradiance(), ShIrradiance::constant(l)] {
        for n in normals(50).into_iter().chain([Vec3::X, Vec3::NEG_Y, Vec3::Z]) {
            let e = sh.eval(n);
            for ch in 0..3 {
                let rel = (e[ch] / (PI * l[ch]) - 1.0).abs();
                assert!(rel < 1e-5, "n {n}: E = {} vs π L = {} (rel {rel:e})", e[ch], PI * l[ch]);
            }
        }
    }
    // Brute force at texel centres: the clamped cosine's kink costs O(1/N²).
    for n in [Vec3::Y, Vec3::NEG_Z, Vec3::new(0.3, -0.5, 0.8).normalize()] {
        let e = env.irradiance_brute_force(n);
        for ch in 0..3 {
            let rel = (e[ch] / (std::f64::consts::PI * f64::from(l[ch])) - 1.0).abs();
            assert!(rel < 1e-3, "brute force at {n}: {} vs π L (rel {rel:e})", e[ch]);
        }
    }
}

#[test]
fn env_sh_matches_brute_force_for_smooth_environments() {
    // Outdoor: dim ground, a sky brightening toward the horizon, a halo round a low sun (front left).
    let sun = Vec3::new(-0.6, 0.35, 0.7).normalize();
    let outdoor = EnvMap::from_fn(256, 128, |d| {
        if d.y < 0.0 {
            return [0.15, 0.12, 0.09];
        }
        let sky = 0.5 + 0.8 * (1.0 - d.y).powi(3);
        let halo = 3.0 * d.dot(sun).max(0.0).powi(16);
        [0.8 * sky + halo, 0.9 * sky + 0.95 * halo, 1.2 * sky + 0.85 * halo]
    });
    println!("outdoor sky/ground:");
    let e = sh_errors(&outdoor);
    assert!(e.max_rel < 0.18 && e.mean_rel < 0.025 && e.max_peak < 0.04 && e.mean_peak < 0.01, "outdoor: {e:?}");

    // Hard horizon: a step sky/ground is constant + an odd zonal function, and the clamped
    // cosine has no odd band above l = 1 (Â_3 = Â_5 = ... = 0), so 9 terms are exact; what is
    // left is the brute force's sampling error. Fails if a band factor or the basis is wrong.
    let hard = EnvMap::from_fn(256, 128, |d| if d.y > 0.0 { [1.0, 1.08, 1.35] } else { [0.1, 0.08, 0.05] });
    println!("hard horizon:");
    let e = sh_errors(&hard);
    assert!(e.max_rel < 2e-3, "hard horizon: {e:?}");

    // Studio dome: band-limited to l ≤ 2 radiance, so 9 terms are exact up to sampling.
    println!("studio dome:");
    let e = sh_errors(&EnvMap::from_fn(128, 64, studio_radiance));
    assert!(e.max_rel < 1e-3, "studio: {e:?}");
}

#[test]
fn env_sh_matches_brute_force_for_lobes() {
    // A warm light from the upper front right, L = max(0, d·s)^k: from a broad lobe to a small
    // key light. Errors relative to the brightest irradiance (the light itself is zero behind).
    let s = Vec3::new(0.5, 0.6, 0.62).normalize();
    for (k, max_bound, mean_bound) in [(1, 0.015, 0.004), (8, 0.045, 0.013), (64, 0.08, 0.03)] {
        let env = EnvMap::from_fn(256, 128, |d| {
            let v = d.dot(s).max(0.0).powi(k);
            [v, 0.9 * v, 0.8 * v]
        });
        println!("lobe max(0, d·s)^{k}:");
        let e = sh_errors(&env);
        assert!(e.max_peak < max_bound && e.mean_peak < mean_bound, "lobe k = {k}: {e:?}");
    }
}

#[test]
fn env_convention_pins_directions() {
    let env = EnvMap::from_fn(8, 4, |_| [0.0; 3]);
    let close = |a: Vec3, b: Vec3| (a - b).length() < 1e-6;
    assert!(close(env.direction(4.0, 2.0), Vec3::NEG_Z), "image centre is −Z");
    assert!(close(env.direction(6.0, 2.0), Vec3::X), "u = 0.75 is +X");
    assert!(close(env.direction(2.0, 2.0), Vec3::NEG_X), "u = 0.25 is −X");
    assert!(close(env.direction(0.0, 2.0), Vec3::Z), "the left edge is +Z (toward the face)");
    assert!(close(env.direction(3.0, 0.0), Vec3::Y), "the top row is +Y");
    assert!(close(env.direction(3.0, 4.0), Vec3::NEG_Y), "the bottom row is −Y");
    for d in normals(40) {
        let uv = direction_to_uv(d);
        assert!(close(env.direction(uv.x * 8.0, uv.y * 4.0), d), "round trip of {d} through uv {uv}");
    }

    // Light only from above: normals facing up receive more.
    let above = EnvMap::from_fn(64, 32, |d| [d.y.max(0.0).powi(4); 3]).sh_irradiance();
    assert!(above.eval(Vec3::Y)[0] > 10.0 * above.eval(Vec3::NEG_Y)[0].max(1e-3));
    // Light only from texels near the left/right edges (+Z, the face's side): the face is lit.
    let front = EnvMap::from_fn(64, 32, |d| [d.z.max(0.0).powi(4); 3]);
    assert!(front.texels[16 * 64][0] > 0.5 && front.texels[16 * 64 + 32][0] == 0.0, "+Z is at u = 0, −Z at u = 0.5");
    let front = front.sh_irradiance();
    assert!(front.eval(Vec3::Z)[0] > 10.0 * front.eval(Vec3::NEG_Z)[0].max(1e-3));
    assert!(front.eval(Vec3::Z)[0] > 2.0 * front.eval(Vec3::X)[0]);
}

#[test]
fn env_gpu_layout_and_scaling() {
    let sh = ShIrradiance::studio();
    let gpu = sh.scaled(2.0).to_gpu();
    for (g, c) in gpu.iter().zip(&sh.coeffs) {
        assert_eq!([g[0], g[1], g[2], g[3]], [2.0 * c[0], 2.0 * c[1], 2.0 * c[2], 0.0]);
    }
    assert_eq!(ShIrradiance::zero().eval(Vec3::Y), [0.0; 3]);
}

#[test]
fn env_wgsl_snippet_validates_with_naga() {
    let src = format!(
        "{WGSL_SH_EVAL}\n@group(0) @binding(0) var<uniform> sh: array<vec4<f32>, 9>;\n\
         @fragment fn main(@location(0) n: vec3<f32>) -> @location(0) vec4<f32> {{\n\
         return vec4<f32>(sh_irradiance(sh, normalize(n)), 1.0);\n}}\n"
    );
    let module = naga::front::wgsl::parse_str(&src).unwrap_or_else(|e| panic!("{}", e.emit_to_string(&src)));
    naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::all())
        .validate(&module)
        .unwrap_or_else(|e| panic!("{}", e.emit_to_string(&src)));
    assert!(module.functions.iter().any(|(_, f)| f.name.as_deref() == Some("sh_irradiance")));
}

/// Deterministic HDR texel values, including values above 1.
fn texel(x: usize, y: usize) -> [f32; 3] {
    [x as f32 * 0.5, y as f32 * 0.25 + 0.125, (x * y) as f32 * 3.0]
}

#[test]
fn env_exr_round_trip_scanline_f32_and_tiled_f16() {
    let dir = tempfile::tempdir().unwrap();
    let (w, h) = (13, 7);

    let scan = dir.path().join("scan.exr");
    write_rgb_file(&scan, w, h, |x, y| {
        let t = texel(x, y);
        (t[0], t[1], t[2])
    })
    .unwrap();
    let env = EnvMap::load_exr(&scan).unwrap();
    assert_eq!((env.width, env.height, env.texels.len()), (w, h, w * h));
    for y in 0..h {
        for x in 0..w {
            assert_eq!(env.texels[y * w + x], texel(x, y), "scan lines, f32: texel ({x}, {y})");
        }
    }

    // Tiled, f16, with alpha, zip compressed. Values are exact in f16.
    let tiled = dir.path().join("tiled.exr");
    let channels = SpecificChannels::rgba(|Vec2(x, y)| {
        let t = texel(x, y);
        (f16::from_f32(t[0]), f16::from_f32(t[1]), f16::from_f32(t[2]), f16::ONE)
    });
    let encoding = Encoding {
        compression: Compression::ZIP16,
        blocks: Blocks::Tiles(Vec2(4, 4)),
        line_order: LineOrder::Increasing,
    };
    Image::from_encoded_channels((w, h), encoding, channels).write().to_file(&tiled).unwrap();
    let env = EnvMap::load_exr(&tiled).unwrap();
    assert_eq!((env.width, env.height), (w, h));
    for y in 0..h {
        for x in 0..w {
            assert_eq!(env.texels[y * w + x], texel(x, y), "tiles, f16: texel ({x}, {y})");
        }
    }
}

fn load_error(path: &std::path::Path) -> String {
    match EnvMap::load_exr(path) {
        Ok(env) => panic!("{} loaded ({} × {}), expected an error", path.display(), env.width, env.height),
        Err(e) => e.to_string(),
    }
}

#[test]
fn env_exr_errors_name_the_file_and_the_reason() {
    let dir = tempfile::tempdir().unwrap();

    let missing = dir.path().join("missing.exr");
    let msg = load_error(&missing);
    assert!(msg.contains("missing.exr") && msg.contains("cannot read"), "{msg}");

    let text = dir.path().join("text.exr");
    std::fs::write(&text, "this is not an image\n").unwrap();
    let msg = load_error(&text);
    assert!(msg.contains("text.exr") && msg.contains("not a valid OpenEXR"), "{msg}");

    let nan = dir.path().join("nan.exr");
    write_rgb_file(&nan, 6, 4, |x, y| if (x, y) == (5, 2) { (0.5f32, f32::NAN, 0.5f32) } else { (1.0, 1.0, 1.0) })
        .unwrap();
    let msg = load_error(&nan);
    assert!(msg.contains("nan.exr") && msg.contains("non-finite") && msg.contains("(x 5, y 2)"), "{msg}");

    let negative = dir.path().join("negative.exr");
    write_rgb_file(&negative, 6, 4, |x, y| if (x, y) == (0, 3) { (0.5f32, 0.5f32, -0.25f32) } else { (1.0, 1.0, 1.0) })
        .unwrap();
    let msg = load_error(&negative);
    assert!(msg.contains("negative") && msg.contains("(x 0, y 3)") && msg.contains("-0.25"), "{msg}");

    // A header that claims more texels than a map may have is refused before anything is
    // decoded (a few bytes can claim any size); a folder or a pipe is refused before it is
    // opened (a pipe's open blocks until something writes into it).
    let wide = dir.path().join("wide.exr");
    write_rgb_file(&wide, 1, 1, |_, _| (1.0f32, 1.0f32, 1.0f32)).unwrap();
    let mut bytes = std::fs::read(&wide).unwrap();
    let key = b"dataWindow\0box2i\0";
    let at = bytes.windows(key.len()).position(|w| w == key).expect("the data window") + key.len() + 4;
    bytes[at + 8..at + 12].copy_from_slice(&99_999i32.to_le_bytes());
    std::fs::write(&wide, &bytes).unwrap();
    let msg = load_error(&wide);
    assert!(msg.contains("wide.exr") && msg.contains("100000 × 1 texels") && msg.contains("16384"), "{msg}");
    let msg = load_error(dir.path());
    assert!(msg.contains("not a regular file"), "{msg}");
    let fifo = dir.path().join("pipe.exr");
    if std::process::Command::new("mkfifo").arg(&fifo).status().is_ok_and(|s| s.success()) {
        let msg = load_error(&fifo);
        assert!(msg.contains("pipe.exr") && msg.contains("not a regular file"), "{msg}");
    }

    let luminance = dir.path().join("luminance.exr");
    let y_only = AnyChannels::sort(SmallVec::from_vec(vec![AnyChannel::new("Y", FlatSamples::F32(vec![1.0; 12]))]));
    Image::from_channels((4, 3), y_only).write().to_file(&luminance).unwrap();
    let msg = load_error(&luminance);
    assert!(msg.contains("luminance.exr") && msg.contains("no layer has R, G and B channels (channels: Y)"), "{msg}");
}

#[test]
fn env_fresnel_transmitted_irradiance_matches_brute_force() {
    use rouge_render::diffusion::{fresnel_dielectric, fresnel_moment};
    use rouge_render::env::fresnel_band_kernels;
    // At η = 1 nothing is reflected: the plain cosine's kernels.
    let k = fresnel_band_kernels(1.0);
    let plain = [std::f64::consts::PI, 2.0 * std::f64::consts::PI / 3.0, std::f64::consts::PI / 4.0];
    for (a, b) in k.iter().zip(plain) {
        assert!((a - b).abs() < 1e-9 * b, "{k:?}");
    }
    // A uniform environment: E_t = πL(1 − 2∫F μ dμ).
    let eta = 1.4;
    let e = ShIrradiance::constant([1.0; 3]).fresnel_transmitted(eta).eval(Vec3::Y)[0] as f64;
    let expected = std::f64::consts::PI * (1.0 - 2.0 * fresnel_moment(eta, 1));
    assert!((e - expected).abs() < 1e-5 * expected, "uniform: {e} vs {expected}");
    // The studio dome is band-limited (l ≤ 2), so the zonal form is exact for it: against a
    // brute-force sum over 200 000 directions (Fibonacci sphere) of L T(n·ω) max(0, n·ω).
    let sh = EnvMap::from_fn(256, 128, studio_radiance).sh_irradiance().fresnel_transmitted(eta);
    let count = 200_000;
    let dirs: Vec<Vec3> = (0..count)
        .map(|i| {
            let y = 1.0 - 2.0 * (i as f32 + 0.5) / count as f32;
            let r = (1.0 - y * y).sqrt();
            let phi = i as f32 * PI * (3.0 - 5f32.sqrt());
            Vec3::new(r * phi.cos(), y, r * phi.sin())
        })
        .collect();
    for n in normals(40) {
        let mut brute = [0.0f64; 3];
        for d in &dirs {
            let c = n.dot(*d);
            if c > 0.0 {
                let t = 1.0 - fresnel_dielectric(c as f64, eta);
                let l = studio_radiance(*d);
                for ch in 0..3 {
                    brute[ch] += l[ch] as f64 * t * c as f64 * 4.0 * std::f64::consts::PI / count as f64;
                }
            }
        }
        let got = sh.eval(n);
        for ch in 0..3 {
            assert!(
                (got[ch] as f64 - brute[ch]).abs() < 2e-3 * brute[ch],
                "n {n} ch {ch}: {} vs {}",
                got[ch],
                brute[ch]
            );
        }
    }
}
