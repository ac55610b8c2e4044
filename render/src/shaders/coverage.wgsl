// Box-filter coverage of a pixel by half-planes and strips: the edge overdraw's edges
// (edge_overdraw.wgsl) and the hair pass's fibres (hair.wgsl).

// Coverage of a unit pixel (box filter) by the half-plane {y : n · (y − centre) ≤ x}, n unit:
// the distribution function of the projection of a uniform point of the square onto n, a
// trapezoid of width |nx| + |ny| (the convolution of boxes of widths |nx| and |ny|).
fn box_coverage(x: f32, n: vec2<f32>) -> f32 {
    let a = max(abs(n.x), abs(n.y));
    let b = min(abs(n.x), abs(n.y));
    let h = 0.5 * (a + b);
    let k = 0.5 * (a - b);
    if x <= -h {
        return 0.0;
    }
    if x >= h {
        return 1.0;
    }
    if x < -k {
        return (x + h) * (x + h) / (2.0 * a * b);
    }
    if x > k {
        return 1.0 - (h - x) * (h - x) / (2.0 * a * b);
    }
    return 0.5 + x / a;
}

// Coverage of a unit pixel (box filter) by the strip {y : |n · (y − a)| ≤ r} whose centre line
// passes at signed distance x = n · (centre − a) from the pixel centre: the difference of two
// half-planes' coverages ([`box_coverage`]), exact for a straight strip of any width.
fn strip_coverage(x: f32, r: f32, n: vec2<f32>) -> f32 {
    return max(box_coverage(r - x, n) - box_coverage(-r - x, n), 0.0);
}
