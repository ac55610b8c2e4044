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
    return glitter_square_inside(f, centre, lo, hi);
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

// The area inside [lo, hi] of a flake's square centred at `centre` (mm).
fn glitter_square_inside(f: FlakeField, centre: vec2<f32>, lo: vec2<f32>, hi: vec2<f32>) -> f32 {
    let a = centre - vec2<f32>(0.5 * f.size_mm);
    let b = centre + vec2<f32>(0.5 * f.size_mm);
    let o = max(min(b, hi) - max(a, lo), vec2<f32>(0.0));
    return o.x * o.y;
}

// Whether cell `cell` of `level` overlaps the box [lo, hi].
fn glitter_cell_overlaps(f: FlakeField, level: u32, cell: vec2<i32>, lo: vec2<f32>, hi: vec2<f32>) -> bool {
    let cell_mm = f.cell_mm * f32(1u << level);
    let corner = vec2<f32>(f32(cell.x), f32(cell.y)) * cell_mm;
    return all(corner < hi) && all(corner + vec2<f32>(cell_mm) > lo);
}

// A coarse cell's light-independent words: its choice number between levels (x) and the
// offsets of its grid of half vectors (y, z).
fn glitter_cell_words(f: FlakeField, cell: vec2<i32>, level: u32) -> vec4<u32> {
    return pcg4d(vec4<u32>(bitcast<u32>(cell.x), bitcast<u32>(cell.y), level | (GLITTER_CELL_TAG << 4u), f.seed));
}

// The area inside [lo, hi] of the lit flakes of coarse cell `cell` at `level` ≥ 1 (its
// glitter_cell_words `words`), for the lit probability `p` per fine cell and the half vector's
// slopes `slope` in bins.
fn glitter_cell_lit(f: FlakeField, level: u32, cell: vec2<i32>, words: vec4<u32>, p: f32, slope: vec2<f32>, lo: vec2<f32>, hi: vec2<f32>) -> f32 {
    let cell_mm = f.cell_mm * f32(1u << level);
    let corner = vec2<f32>(f32(cell.x), f32(cell.y)) * cell_mm;
    let bin = floor(slope + vec2<f32>(glitter_unit(words.y), glitter_unit(words.z)));
    let angle_tag = ((bitcast<u32>(i32(bin.x)) & 0xfffu) << 8u) | ((bitcast<u32>(i32(bin.y)) & 0xfffu) << 20u);
    let base = vec4<u32>(bitcast<u32>(cell.x), bitcast<u32>(cell.y), level | angle_tag, f.seed);
    let n = (1u << level) * (1u << level);
    let count = binomial_quantile(n, p, glitter_unit(pcg4d(base).x));
    let placed = min(u32(count), GLITTER_PLACED_FLAKES);
    let room = cell_mm - f.size_mm;
    var lit = 0.0;
    for (var m = 1u; m <= placed; m++) {
        let r = pcg4d(base | vec4<u32>(0u, 0u, m << 4u, 0u));
        let centre = corner + vec2<f32>(0.5 * f.size_mm) + vec2<f32>(glitter_unit(r.x), glitter_unit(r.y)) * room;
        lit += glitter_square_inside(f, centre, lo, hi);
    }
    let o = max(min(corner + vec2<f32>(cell_mm), hi) - max(corner, lo), vec2<f32>(0.0));
    return lit + (count - f32(placed)) * f.size_mm * f.size_mm * (o.x * o.y / (cell_mm * cell_mm));
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
    let level = min(u32(floor(lambda)), GLITTER_MAX_LEVEL - 1u);
    let w = lambda - f32(level);
    let lo = uv - half_mm;
    let hi = uv + half_mm;
    var lit = 0.0;
    if level == 0u && w <= 0.0 {
        // Footprints of at most EXPLICIT_CELLS cells: their flakes alone (most of a close-up).
        let c0 = vec2<i32>(floor(lo / f.cell_mm));
        let c1 = min(vec2<i32>(floor(hi / f.cell_mm)), c0 + vec2<i32>(2 * GLITTER_MAX_SPAN + 1));
        for (var j = c0.y; j <= c1.y; j++) {
            for (var i = c0.x; i <= c1.x; i++) {
                lit += flake_lit_area(f, vec2<i32>(i, j), h, lo, hi);
            }
        }
        return min(lit / (4.0 * half_mm.x * half_mm.y), 1.0);
    }
    let p = glitter_p_lit(f, h);
    let slope = h.xy / (h.z * GLITTER_SLOPE_BIN);
    let parent_mm = f.cell_mm * f32(2u << level);
    let c0 = vec2<i32>(floor(lo / parent_mm));
    let c1 = min(vec2<i32>(floor(hi / parent_mm)), c0 + vec2<i32>(GLITTER_MAX_SPAN));
    for (var j = c0.y; j <= c1.y; j++) {
        for (var i = c0.x; i <= c1.x; i++) {
            let words = glitter_cell_words(f, vec2<i32>(i, j), level + 1u);
            if glitter_unit(words.x) < w {
                lit += glitter_cell_lit(f, level + 1u, vec2<i32>(i, j), words, p, slope, lo, hi);
                continue;
            }
            for (var k = 0; k < 4; k++) {
                let child = vec2<i32>(2 * i + (k & 1), 2 * j + (k >> 1u));
                if !glitter_cell_overlaps(f, level, child, lo, hi) {
                    continue;
                }
                if level == 0u {
                    lit += flake_lit_area(f, child, h, lo, hi);
                } else {
                    lit += glitter_cell_lit(f, level, child, glitter_cell_words(f, child, level), p, slope, lo, hi);
                }
            }
        }
    }
    return min(lit / (4.0 * half_mm.x * half_mm.y), 1.0);
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
