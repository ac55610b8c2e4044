// Glitter: the flake field and the estimate of a pixel's sparkle. The one definition of both,
// the module doc and the citations are in render/src/glitter.rs (`pcg4d`, `FlakeField::flake`,
// `pixel_sparkle`, `binomial_quantile`, `sparkle_lobe`), which this follows line for line; the
// constants GLITTER_* are injected from there by shader::shader_source.

// [Jarzynski2020]'s pcg4d, in wrapping 32-bit integer arithmetic.
fn pcg4d(v_in: vec4<u32>) -> vec4<u32> {
    var v = v_in * 1664525u + 1013904223u;
    v.x += v.y * v.w;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v.w += v.y * v.z;
    v = v ^ (v >> vec4<u32>(16u));
    v.x += v.y * v.w;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v.w += v.y * v.z;
    return v;
}

// A word as a uniform number in [0, 1): its top 24 bits.
fn glitter_unit(x: u32) -> f32 {
    return f32(x >> 8u) * (1.0 / 16777216.0);
}

// A layer's flake field: x cell edge (mm), y flake edge (mm), z probability of a flake in a cell,
// w the flakes' Beckmann roughness; `seed` the layer's.
struct FlakeField {
    cell_mm: f32,
    size_mm: f32,
    p_flake: f32,
    spread: f32,
    seed: u32,
}

// The area of cell `cell`'s flake inside [lo, hi] when it sparkles for `h` (0 otherwise).
fn flake_lit_area(f: FlakeField, cell: vec2<i32>, h: vec3<f32>, lo: vec2<f32>, hi: vec2<f32>) -> f32 {
    let r = pcg4d(vec4<u32>(bitcast<u32>(cell.x), bitcast<u32>(cell.y), 0u, f.seed));
    if glitter_unit(r.x) >= f.p_flake {
        return 0.0;
    }
    let room = f.cell_mm - f.size_mm;
    let corner = vec2<f32>(f32(cell.x), f32(cell.y)) * f.cell_mm;
    let centre = corner + vec2<f32>(0.5 * f.size_mm) + vec2<f32>(glitter_unit(r.y), glitter_unit(r.z)) * room;
    let u1 = f32(r.w >> 16u) * (1.0 / 65536.0);
    let u2 = f32(r.w & 0xffffu) * (1.0 / 65536.0);
    let rad = f.spread * 0.70710678 * sqrt(-2.0 * log(1.0 - u1));
    let angle = 6.28318531 * u2;
    let n = normalize(vec3<f32>(-rad * cos(angle), -rad * sin(angle), 1.0));
    if dot(n, h) <= GLITTER_COS_HALF_CONE {
        return 0.0;
    }
    let a = centre - vec2<f32>(0.5 * f.size_mm);
    let b = centre + vec2<f32>(0.5 * f.size_mm);
    let o = max(min(b, hi) - max(a, lo), vec2<f32>(0.0));
    return o.x * o.y;
}

// The probability that a cell holds a flake sparkling for `h`.
fn glitter_p_lit(f: FlakeField, h: vec3<f32>) -> f32 {
    if h.z <= 0.0 {
        return 0.0;
    }
    let c2 = max(h.z * h.z, 1e-6);
    let m2 = f.spread * f.spread;
    let d = exp((c2 - 1.0) / (m2 * c2)) / (PI * m2 * c2 * c2);
    return f.p_flake * min(d * h.z * GLITTER_CONE_SR, 1.0);
}

// The u-quantile of Binomial(n, p).
fn binomial_quantile(n: u32, p: f32, u_in: f32) -> f32 {
    if p <= 0.0 || n == 0u {
        return 0.0;
    }
    let mean = f32(n) * p;
    let q = 1.0 - p;
    if mean < 0.5 * f32(GLITTER_EXACT_COUNT) && q > 0.0 {
        var pmf = exp(f32(n) * log(q));
        var cdf = pmf;
        var k = 0u;
        let last = min(GLITTER_EXACT_COUNT, n);
        while cdf <= u_in && k < last {
            pmf *= f32(n - k) / f32(k + 1u) * p / q;
            k += 1u;
            cdf += pmf;
        }
        return f32(k);
    }
    let u = clamp(u_in, 1e-6, 1.0 - 1e-6);
    let z = log(u / (1.0 - u)) * (1.7320508 / PI);
    return clamp(mean + sqrt(mean * q) * z, 0.0, f32(n));
}

// The lit part of the footprint [uv − half_mm, uv + half_mm] at one level.
fn glitter_level(f: FlakeField, level: u32, uv: vec2<f32>, half_mm: vec2<f32>, h: vec3<f32>) -> f32 {
    let cell_mm = f.cell_mm * f32(1u << level);
    let lo = uv - half_mm;
    let hi = uv + half_mm;
    let c0 = vec2<i32>(floor(lo / cell_mm));
    let c1 = min(vec2<i32>(floor(hi / cell_mm)), c0 + vec2<i32>(GLITTER_MAX_SPAN));
    let n = (1u << level) * (1u << level);
    var p = 0.0;
    if level > 0u {
        p = glitter_p_lit(f, h);
    }
    var lit = 0.0;
    for (var j = c0.y; j <= c1.y; j++) {
        for (var i = c0.x; i <= c1.x; i++) {
            if level == 0u {
                lit += flake_lit_area(f, vec2<i32>(i, j), h, lo, hi);
            } else {
                let u = glitter_unit(pcg4d(vec4<u32>(bitcast<u32>(i), bitcast<u32>(j), level, f.seed)).x);
                let count = binomial_quantile(n, p, u);
                let corner = vec2<f32>(f32(i), f32(j)) * cell_mm;
                let o = max(min(corner + vec2<f32>(cell_mm), hi) - max(corner, lo), vec2<f32>(0.0));
                lit += count * f.size_mm * f.size_mm * (o.x * o.y / (cell_mm * cell_mm));
            }
        }
    }
    return min(lit / (4.0 * half_mm.x * half_mm.y), 1.0);
}

// The part of the footprint centred at `uv` (mm) with half extents `half_in_mm` (mm) that lit
// flakes cover for the half vector `h` (unit, tangent frame).
fn pixel_sparkle(f: FlakeField, uv: vec2<f32>, half_in_mm: vec2<f32>, h: vec3<f32>) -> f32 {
    if h.z <= 0.0 {
        return 0.0;
    }
    let half_mm = max(half_in_mm, vec2<f32>(1e-6 * f.cell_mm));
    let across = 2.0 * max(half_mm.x, half_mm.y) / f.cell_mm;
    let lambda = clamp(log2(across / GLITTER_EXPLICIT_CELLS), 0.0, f32(GLITTER_MAX_LEVEL));
    let level = u32(floor(lambda));
    let w = lambda - f32(level);
    let fine = glitter_level(f, level, uv, half_mm, h);
    if w <= 0.0 || level >= GLITTER_MAX_LEVEL {
        return fine;
    }
    return (1.0 - w) * fine + w * glitter_level(f, level + 1u, uv, half_mm, h);
}

// The glitter's lobe per unit irradiance E·(n·l): sparkle · colour / (π sin²δ (n·l)).
fn sparkle_lobe(sparkle: f32, color: vec3<f32>, n_dot_l: f32) -> vec3<f32> {
    return color * (sparkle / (PI * GLITTER_SIN2_LIGHT * max(n_dot_l, 1e-3)));
}

// The footprint's half extents (mm, 2⁻¹⁶-2¹⁶) as codes in ±[0.001, 0.999] of their log2, the
// first signed by `hand` (±1): snorm16 keeps them to 0.07 % and the sign.
fn footprint_encode(half_mm: vec2<f32>, hand: f32) -> vec2<f32> {
    let t = clamp((log2(half_mm) + 16.0) / 32.0, vec2<f32>(0.0), vec2<f32>(1.0));
    let c = 0.001 + 0.998 * t;
    return vec2<f32>(c.x * hand, c.y);
}

fn footprint_decode(code: vec2<f32>) -> vec2<f32> {
    let t = (abs(code) - 0.001) / 0.998;
    return exp2(t * 32.0 - 16.0);
}

// Octahedral encoding of a unit vector into [-1, 1]² ([Cigolle2014]) and its inverse.
fn oct_encode(n: vec3<f32>) -> vec2<f32> {
    let p = n.xy / (abs(n.x) + abs(n.y) + abs(n.z));
    if n.z >= 0.0 {
        return p;
    }
    return (1.0 - abs(p.yx)) * select(vec2<f32>(-1.0), vec2<f32>(1.0), p >= vec2<f32>(0.0));
}

fn oct_decode(e: vec2<f32>) -> vec3<f32> {
    var n = vec3<f32>(e, 1.0 - abs(e.x) - abs(e.y));
    if n.z < 0.0 {
        n = vec3<f32>((1.0 - abs(e.yx)) * select(vec2<f32>(-1.0), vec2<f32>(1.0), e >= vec2<f32>(0.0)), n.z);
    }
    return normalize(n);
}
