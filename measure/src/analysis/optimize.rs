//! The two small minimisers the analyses need: golden-section search on an interval (a layer's
//! thickness) and a pattern search on the probability simplex (a mixture's concentrations).
//! No derivatives: CIEDE2000 has kinks (hue angles, the rotation term), so both only compare
//! values.

/// Minimises `f` on `[lo, hi]` by golden-section search (\[Kiefer1953\]) until the bracket is
/// narrower than `tol` (absolute). Finds the minimum of a unimodal `f`; for any other it finds
/// a local minimum inside the bracket. Returns `(x, f(x))`, the best point evaluated.
pub fn golden_section(mut f: impl FnMut(f64) -> f64, lo: f64, hi: f64, tol: f64) -> (f64, f64) {
    const INV_PHI: f64 = 0.618_033_988_749_894_8; // (√5 − 1)/2
    let (mut a, mut b) = (lo.min(hi), lo.max(hi));
    let mut best = {
        let (fa, fb) = (f(a), f(b));
        if fa <= fb { (a, fa) } else { (b, fb) }
    };
    let mut c = b - INV_PHI * (b - a);
    let mut d = a + INV_PHI * (b - a);
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..200 {
        if b - a <= tol {
            break;
        }
        if fc <= fd {
            (b, d, fd) = (d, c, fc);
            c = b - INV_PHI * (b - a);
            fc = f(c);
        } else {
            (a, c, fc) = (c, d, fd);
            d = a + INV_PHI * (b - a);
            fd = f(d);
        }
    }
    for (x, fx) in [(c, fc), (d, fd)] {
        if fx < best.1 {
            best = (x, fx);
        }
    }
    best
}

/// Minimises `f(c)` over the simplex `c_i ≥ 0, Σ c_i = 1` by a pattern search along the edge
/// directions `e_i − e_j` (a positive spanning set of the simplex's plane, so the search stops
/// only at a point no such move improves: \[Lewis2000\]'s generalised pattern search with linear
/// constraints). Starts from the best point of the lattice of step 1/`lattice` (every vertex,
/// edge and face point included), halves the step when no move helps, stops below `tol`.
/// Returns `(c, f(c))`. `n ≥ 1`.
pub fn simplex_search(mut f: impl FnMut(&[f64]) -> f64, n: usize, lattice: usize, tol: f64) -> (Vec<f64>, f64) {
    let n = n.max(1);
    let lattice = lattice.max(1);
    let mut best = (vec![0.0; n], f64::INFINITY);
    let mut counts = vec![0usize; n];
    lattice_points(&mut counts, 0, lattice, &mut |counts| {
        let c: Vec<f64> = counts.iter().map(|&k| k as f64 / lattice as f64).collect();
        let v = f(&c);
        if v < best.1 {
            best = (c, v);
        }
    });
    let (mut c, mut fc) = best;
    let mut h = 0.5 / lattice as f64;
    let mut trial = c.clone();
    while h >= tol {
        let mut improved = false;
        for i in 0..n {
            for j in 0..n {
                if i == j || c[j] <= 0.0 {
                    continue;
                }
                let step = h.min(c[j]);
                trial.copy_from_slice(&c);
                trial[i] += step;
                trial[j] -= step;
                if step == c[j] {
                    trial[j] = 0.0;
                }
                let v = f(&trial);
                if v < fc {
                    c.copy_from_slice(&trial);
                    fc = v;
                    improved = true;
                }
            }
        }
        if !improved {
            h *= 0.5;
        }
    }
    (c, fc)
}

/// Calls `visit` with every composition of `total` into `counts.len()` non-negative parts.
fn lattice_points(counts: &mut [usize], at: usize, total: usize, visit: &mut impl FnMut(&[usize])) {
    if at + 1 == counts.len() {
        counts[at] = total;
        visit(counts);
        return;
    }
    for k in 0..=total {
        counts[at] = k;
        lattice_points(counts, at + 1, total - k, visit);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn golden_section_finds_a_parabola_minimum_and_the_ends() {
        let (x, fx) = golden_section(|x| (x - 0.3).powi(2), 0.0, 1.0, 1e-12);
        assert!((x - 0.3).abs() < 1e-6 && fx < 1e-12, "{x} {fx}");
        let (x, _) = golden_section(|x| x, 0.2, 1.0, 1e-12);
        assert_eq!(x, 0.2);
        let (x, _) = golden_section(|x| -x, 0.2, 1.0, 1e-12);
        assert_eq!(x, 1.0);
    }

    #[test]
    fn simplex_search_finds_interior_and_boundary_minima() {
        let target = [0.2, 0.5, 0.3];
        let (c, v) = simplex_search(|c| c.iter().zip(&target).map(|(a, b)| (a - b) * (a - b)).sum(), 3, 10, 1e-12);
        assert!(v < 1e-20, "{c:?} {v}");
        // Minimum outside the simplex: the closest point on it is (0, 0.5, 0.5).
        let (c, _) = simplex_search(|c| (c[0] + 1.0).powi(2) + (c[1] - c[2]).powi(2), 3, 10, 1e-12);
        assert!(c[0] == 0.0 && (c[1] - 0.5).abs() < 1e-9, "{c:?}");
        let (c, _) = simplex_search(|c| (c[0] - 2.0).abs(), 1, 4, 1e-9);
        assert_eq!(c, vec![1.0]);
    }
}
