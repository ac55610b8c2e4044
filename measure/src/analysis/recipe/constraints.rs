//! The constraints of a recipe search, checked and turned into groups: colorants tied by fixed
//! ratios enter a recipe together, with the bounds their limits put on the group's share
//! (`super` module documentation); and the combinations of groups a search fits.

use super::RecipeSearch;
use crate::analysis::{AnalysisError, invalid};

/// Colorants that enter a recipe together: indices and relative weights.
#[derive(Clone, Debug)]
pub(super) struct Group {
    pub(super) members: Vec<(usize, f64)>,
    /// Bounds of the group's share `u` (its amounts' sum).
    pub(super) lo: f64,
    pub(super) hi: f64,
    pub(super) required: bool,
}

fn name_of(search: &RecipeSearch, i: usize) -> &str {
    &search.colorants[i].layer.name
}

/// Checks the search and builds its groups; every error names the colorant and the constraint.
pub(super) fn groups(search: &RecipeSearch) -> Result<Vec<Group>, AnalysisError> {
    let n = search.colorants.len();
    if n == 0 {
        return Err(invalid("the colorant library is empty"));
    }
    if search.k == 0 || search.k > n {
        return Err(invalid(format!("k = {}: recipes take 1 to {n} colorants (the library's size)", search.k)));
    }
    for (i, c) in search.colorants.iter().enumerate() {
        let name = &c.layer.name;
        if search.colorants[..i].iter().any(|o| &o.layer.name == name) {
            return Err(invalid(format!("colorant `{name}` is in the library twice: names must be unique")));
        }
        if !(c.min >= 0.0 && c.max <= 1.0 && c.min.is_finite() && c.max.is_finite()) {
            return Err(invalid(format!("colorant `{name}`: min {} and max {} must lie in [0, 1]", c.min, c.max)));
        }
        if c.min > c.max {
            return Err(invalid(format!("colorant `{name}`: min {} > max {}", c.min, c.max)));
        }
        if !(c.cost_per_unit >= 0.0 && c.cost_per_unit.is_finite()) {
            return Err(invalid(format!("colorant `{name}`: cost {} must be finite and ≥ 0", c.cost_per_unit)));
        }
    }
    let min_sum: f64 = search.colorants.iter().map(|c| c.min).sum();
    if min_sum > 1.0 + 1e-12 {
        let list: Vec<String> =
            search.colorants.iter().filter(|c| c.min > 0.0).map(|c| format!("{} ≥ {}", c.layer.name, c.min)).collect();
        return Err(invalid(format!("the minimum amounts sum to {min_sum} > 1: {}", list.join(", "))));
    }
    // Union of the fixed pairs, each colorant's weight relative to its group's root.
    let mut weight: Vec<Option<(usize, f64)>> = vec![None; n];
    let find = |name: &str| search.colorants.iter().position(|c| c.layer.name == name);
    let mut pairs = Vec::new();
    for p in &search.fixed {
        let what = format!("fixed pair {}:{} = {}", p.a, p.b, p.ratio);
        let (Some(a), Some(b)) = (find(&p.a), find(&p.b)) else {
            let missing = if find(&p.a).is_none() { &p.a } else { &p.b };
            return Err(invalid(format!("{what}: no colorant `{missing}` in the library")));
        };
        if a == b || !(p.ratio > 0.0 && p.ratio.is_finite()) {
            return Err(invalid(format!("{what}: needs two different colorants and a finite ratio > 0")));
        }
        pairs.push((a, b, p.ratio, what));
    }
    // Spread weights through the pairs until nothing changes (groups are small).
    for root in 0..n {
        if weight[root].is_some() {
            continue;
        }
        weight[root] = Some((root, 1.0));
        let mut changed = true;
        while changed {
            changed = false;
            for (a, b, r, what) in &pairs {
                let (wa, wb) = (weight[*a], weight[*b]);
                match (wa, wb) {
                    (Some((ga, xa)), None) if ga == root => {
                        weight[*b] = Some((root, xa / r));
                        changed = true;
                    }
                    (None, Some((gb, xb))) if gb == root => {
                        weight[*a] = Some((root, xb * r));
                        changed = true;
                    }
                    (Some((ga, xa)), Some((gb, xb)))
                        if ga == root && gb == root && ((xa / xb) / r - 1.0).abs() > 1e-9 =>
                    {
                        return Err(invalid(format!(
                            "{what} contradicts the other fixed pairs, which give {}:{} = {}",
                            name_of(search, *a),
                            name_of(search, *b),
                            xa / xb
                        )));
                    }
                    _ => {}
                }
            }
        }
    }
    let mut out: Vec<Group> = Vec::new();
    for root in 0..n {
        let members: Vec<(usize, f64)> =
            (0..n).filter_map(|i| weight[i].filter(|(g, _)| *g == root).map(|(_, w)| (i, w))).collect();
        if members.is_empty() {
            continue;
        }
        let total: f64 = members.iter().map(|m| m.1).sum();
        // Member i holds u·w_i/total: its limits bound u.
        let (mut lo, mut hi) = (0.0f64, 1.0f64);
        for &(i, w) in &members {
            let c = &search.colorants[i];
            lo = lo.max(c.min * total / w);
            hi = hi.min(c.max * total / w);
        }
        let names = || members.iter().map(|&(i, _)| name_of(search, i)).collect::<Vec<_>>().join(", ");
        if lo > hi * (1.0 + 1e-12) {
            let limits: Vec<String> = members
                .iter()
                .map(|&(i, _)| {
                    format!("{} in [{}, {}]", name_of(search, i), search.colorants[i].min, search.colorants[i].max)
                })
                .collect();
            return Err(invalid(format!(
                "the fixed ratios of {} contradict their limits ({}): no amounts satisfy both",
                names(),
                limits.join(", ")
            )));
        }
        if members.len() > search.k && lo > 0.0 {
            return Err(invalid(format!(
                "{} are required (min > 0) and tied by fixed ratios, {} colorants, more than k = {}",
                names(),
                members.len(),
                search.k
            )));
        }
        out.push(Group { required: lo > 0.0, lo, hi: hi.max(lo), members });
    }
    let required: usize = out.iter().filter(|g| g.required).map(|g| g.members.len()).sum();
    if required > search.k {
        return Err(invalid(format!(
            "{required} colorants are required (min > 0) but a recipe takes k = {}",
            search.k
        )));
    }
    Ok(out)
}

/// Every set of groups with `k` members in all that holds every required group.
pub(super) fn combinations(groups: &[Group], k: usize) -> Vec<Vec<usize>> {
    fn walk(groups: &[Group], at: usize, left: usize, chosen: &mut Vec<usize>, out: &mut Vec<Vec<usize>>) {
        if left == 0 {
            if groups[at..].iter().all(|g| !g.required) {
                out.push(chosen.clone());
            }
            return;
        }
        if at == groups.len() {
            return;
        }
        let size = groups[at].members.len();
        if size <= left && groups[at].hi > 0.0 {
            chosen.push(at);
            walk(groups, at + 1, left - size, chosen, out);
            chosen.pop();
        }
        if !groups[at].required {
            walk(groups, at + 1, left, chosen, out);
        }
    }
    let mut out = Vec::new();
    walk(groups, 0, k, &mut Vec::new(), &mut out);
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::recipe::FixedRatio;
    use crate::analysis::recipe::test_support::{lib, search};

    #[test]
    fn groups_and_combinations_follow_the_constraints() {
        let mut c = lib(&["a", "b", "c", "d"]);
        c[3].min = 0.1;
        let fixed = vec![FixedRatio { a: "a".into(), b: "b".into(), ratio: 2.0 }];
        let s = search(c, fixed, 3);
        let g = groups(&s).expect("valid");
        assert_eq!(g.len(), 3);
        assert_eq!(g[0].members, vec![(0, 1.0), (1, 0.5)]);
        // k = 3 with d required: {a,b,d} or {c,d}+? (c,d is 2): only {a,b}+{d}.
        assert_eq!(combinations(&g, 3), vec![vec![0, 2]]);
        assert_eq!(combinations(&g, 2), vec![vec![1, 2]]);
    }

    #[test]
    fn impossible_constraints_name_the_colorant_and_the_constraint() {
        let err = |s: RecipeSearch| groups(&s).expect_err("impossible").to_string();
        let mut c = lib(&["a", "b", "c"]);
        c[1].min = 0.6;
        c[1].max = 0.4;
        assert!(err(search(c, vec![], 2)).contains("colorant `b`: min 0.6 > max 0.4"));
        let mut c = lib(&["a", "b", "c"]);
        (c[0].min, c[2].min) = (0.7, 0.5);
        let e = err(search(c, vec![], 2));
        assert!(e.contains("sum to 1.2") && e.contains("a ≥ 0.7") && e.contains("c ≥ 0.5"), "{e}");
        let mut c = lib(&["a", "b", "c"]);
        (c[0].max, c[1].min) = (0.1, 0.2);
        let e = err(search(c, vec![FixedRatio { a: "a".into(), b: "b".into(), ratio: 1.0 }], 2));
        assert!(e.contains("fixed ratios of a, b contradict") && e.contains("a in [0, 0.1]"), "{e}");
        let e = err(search(lib(&["a", "b"]), vec![FixedRatio { a: "a".into(), b: "zz".into(), ratio: 1.0 }], 2));
        assert!(e.contains("no colorant `zz`"), "{e}");
        let chain = vec![
            FixedRatio { a: "a".into(), b: "b".into(), ratio: 2.0 },
            FixedRatio { a: "b".into(), b: "c".into(), ratio: 3.0 },
            FixedRatio { a: "a".into(), b: "c".into(), ratio: 5.0 },
        ];
        assert!(err(search(lib(&["a", "b", "c"]), chain, 3)).contains("a:c = 5 contradicts"));
        assert!(err(search(lib(&["a", "b"]), vec![], 3)).contains("k = 3"));
        let mut c = lib(&["a", "b", "c"]);
        (c[0].min, c[1].min) = (0.2, 0.2);
        assert!(err(search(c, vec![], 1)).contains("2 colorants are required"));
    }
}
