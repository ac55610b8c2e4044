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
    let (c, _) = best;
    let (c, fc, _) = box_simplex_search(f, &vec![0.0; n], &vec![1.0; n], &c, 0.5 / lattice as f64, tol);
    (c, fc)
}

/// The Euclidean projection of `v` onto the box-bounded simplex `{c : Σ c_i = 1, lo_i ≤ c_i ≤ hi_i}`:
/// `c_i = clamp(v_i − λ, lo_i, hi_i)` with the one λ that makes the sum 1, found by bisection
/// (the sum falls monotonically in λ; the projection's KKT conditions, as \[Duchi2008\] §3 for
/// the plain simplex, with the bounds clamping each term). The caller guarantees `lo ≤ hi` and
/// `Σ lo ≤ 1 ≤ Σ hi` (so that the set is not empty); the result sums to 1 within 1e-12.
pub fn project_box_simplex(v: &[f64], lo: &[f64], hi: &[f64]) -> Vec<f64> {
    let at =
        |lambda: f64| -> f64 { v.iter().zip(lo.iter().zip(hi)).map(|(x, (l, h))| (x - lambda).clamp(*l, *h)).sum() };
    let span = v.iter().chain(lo).chain(hi).fold(0.0f64, |m, x| m.max(x.abs())) + 1.0;
    let (mut a, mut b) = (-2.0 * span, 2.0 * span); // at(a) = Σ hi ≥ 1, at(b) = Σ lo ≤ 1
    for _ in 0..200 {
        let mid = 0.5 * (a + b);
        if at(mid) > 1.0 {
            a = mid
        } else {
            b = mid
        }
        if b - a < 1e-15 * span {
            break;
        }
    }
    let lambda = 0.5 * (a + b);
    v.iter().zip(lo.iter().zip(hi)).map(|(x, (l, h))| (x - lambda).clamp(*l, *h)).collect()
}

/// Minimises `f(c)` over the box-bounded simplex `Σ c_i = 1, lo_i ≤ c_i ≤ hi_i` from the feasible
/// `start` by the pattern search of [`simplex_search`] (moves along `e_i − e_j`, a positive
/// spanning set of the constraint plane, each cut short at the bounds: \[Lewis2000\]), from
/// step `h0`, halving when no move helps, stopping below `tol`. Returns `(c, f(c), evaluations)`.
pub fn box_simplex_search(
    mut f: impl FnMut(&[f64]) -> f64,
    lo: &[f64],
    hi: &[f64],
    start: &[f64],
    h0: f64,
    tol: f64,
) -> (Vec<f64>, f64, usize) {
    let n = start.len();
    let mut c = start.to_vec();
    let mut fc = f(&c);
    let mut evaluations = 1;
    let mut trial = c.clone();
    let mut h = h0;
    while h >= tol {
        let mut improved = false;
        for i in 0..n {
            for j in 0..n {
                let room = (hi[i] - c[i]).min(c[j] - lo[j]);
                if i == j || room <= 0.0 {
                    continue;
                }
                let step = h.min(room);
                trial.copy_from_slice(&c);
                trial[i] += step;
                trial[j] -= step;
                let v = f(&trial);
                evaluations += 1;
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
    (c, fc, evaluations)
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

    #[test]
    fn box_simplex_projection_and_search_respect_the_bounds() {
        let (lo, hi) = ([0.1, 0.0, 0.2], [0.5, 0.3, 1.0]);
        let p = project_box_simplex(&[2.0, 2.0, -1.0], &lo, &hi);
        assert!((p.iter().sum::<f64>() - 1.0).abs() < 1e-12, "{p:?}");
        assert!(p.iter().zip(lo.iter().zip(&hi)).all(|(x, (l, h))| *l <= *x && x <= h), "{p:?}");
        assert_eq!((p[0], p[1]), (0.5, 0.3));
        // Minimum of |c − t|² on the set: for t = (0.9, 0.05, 0.05), c0 held at its bound 0.5 and
        // the rest shared (0.25, 0.25); for t = (0.9, 0.35, −0.25), every bound holds (0.5, 0.3, 0.2).
        let start = project_box_simplex(&[1.0 / 3.0; 3], &lo, &hi);
        let mut n = 0;
        for (target, want) in [([0.9, 0.05, 0.05], [0.5, 0.25, 0.25]), ([0.9, 0.35, -0.25], [0.5, 0.3, 0.2])] {
            let (c, _, evaluations) = box_simplex_search(
                |c| c.iter().zip(&target).map(|(a, b)| (a - b) * (a - b)).sum(),
                &lo,
                &hi,
                &start,
                0.05,
                1e-10,
            );
            assert!(c.iter().zip(&want).all(|(a, b)| (a - b).abs() < 1e-8), "{c:?} against {want:?}");
            n += evaluations;
        }
        assert!(n > 1);
    }
}
