//! Recipe search: the best recipes of `k` colorants out of a library of `n` for a target
//! reflectance, under amount limits, fixed ratios and costs, judged under several illuminants.
//!
//! # Method (the "combinatorial" formulation of \[Allen1980\] and \[Kuehni1975\])
//!
//! * The **model** of a recipe `c` (amounts ≥ 0 summing to 1, whole products or pastes as
//!   colorants) is Duncan's rule ([`duncan_mix`], \[Duncan1940\]) seen opaque (R∞) or as a layer
//!   over a background ([`Presentation`]).
//! * The **objective** of a recipe is the weighted root mean square of its CIEDE2000 from the
//!   target under each viewing `v` with weight `w_v`, plus an optional price of cost:
//!   `F(c) = √(Σ w_v ΔE00_v² / Σ w_v) + λ_cost · Σ c_i cost_i`. With more than one illuminant a
//!   recipe that only matches under the first (a metameric, "lucky" match) pays for the others,
//!   so the search prefers recipes whose spectra follow the target's.
//! * **Constraints**: per colorant `min ≤ c_i ≤ max`; a colorant with `min > 0` is required in
//!   every recipe and `max = 0` excludes it; a fixed pair `A:B = r` holds `c_A = r c_B` and the
//!   two enter or leave a recipe together (chains `A:B`, `B:C` join one group).
//! * **Search**: every combination of groups with `k` colorants in all is fitted. A group `g` of
//!   fixed relative weights `w_i` (1 for a lone colorant) contributes `c_i = w_i u_g / Σ w`, so a
//!   recipe is a point `u` of the simplex with box bounds from the members' limits. The fit starts
//!   at the best point of a coarse lattice (projected onto the bounds, [`project_box_simplex`]),
//!   takes Gauss-Newton steps on the stacked, weighted CIELAB residuals under every viewing
//!   (`J` by forward differences, nalgebra SVD least squares in the plane `Σ Δu = 0`, projected
//!   back onto the constraints and damped until the residual falls), then polishes `F` itself
//!   (CIEDE2000 has kinks) with the bounded pattern search [`box_simplex_search`]. Combinations
//!   are ranked by `F`.
//! * Each recipe reports ΔE2000 per viewing, its cost and the special metamerism index
//!   ([`metamerism_index`], additive correction, \[CIE15-2018\] §9.2) of target and recipe from
//!   the first viewing to each other (to illuminant A, same observer, when only one is given).
//!
//! `measure/tests/recipe.rs`: the search recovers the colorants and amounts of a synthetic
//! mixture of library colorants with measurement noise.

mod constraints;

use crate::analysis::correction::Presentation;
use crate::analysis::metamerism::{Correction, MetamerismIndex, metamerism_index};
use crate::analysis::mixing::duncan_mix;
use crate::analysis::optimize::{box_simplex_search, project_box_simplex};
use crate::analysis::{AnalysisError, Layer, check_reflectance, check_thickness, invalid};
use crate::colorimetry::{Colorimeter, Illuminant, Viewing, delta_e_2000_raw};
use crate::spectrum::Spectrum;
use constraints::{combinations, groups};
use nalgebra::{DMatrix, DVector};

/// A colorant of the library with its limits and price.
#[derive(Clone, Debug, PartialEq)]
pub struct Colorant {
    /// Its S and K (the name is the colorant's name in constraints and reports).
    pub layer: Layer,
    /// Least amount (fraction of the recipe); > 0 makes the colorant required in every recipe.
    pub min: f64,
    /// Largest amount; 0 excludes the colorant.
    pub max: f64,
    /// Cost per unit amount (any currency per unit mass of the recipe).
    pub cost_per_unit: f64,
}

impl Colorant {
    /// A colorant free in [0, 1] at no cost.
    pub fn new(layer: Layer) -> Self {
        Colorant { layer, min: 0.0, max: 1.0, cost_per_unit: 0.0 }
    }
}

/// Two colorants whose amounts keep a fixed ratio: `amount(a) = ratio × amount(b)`.
#[derive(Clone, Debug, PartialEq)]
pub struct FixedRatio {
    /// The first colorant's name.
    pub a: String,
    /// The second colorant's name.
    pub b: String,
    /// `amount(a) / amount(b)`, > 0.
    pub ratio: f64,
}

/// A viewing of the objective and its weight.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WeightedViewing {
    /// Illuminant and observer.
    pub viewing: Viewing,
    /// Weight ≥ 0 (the weights need not sum to 1).
    pub weight: f64,
}

/// A recipe search: the library, the constraints and the objective.
#[derive(Clone, Debug, PartialEq)]
pub struct RecipeSearch {
    /// The library.
    pub colorants: Vec<Colorant>,
    /// Fixed pairs.
    pub fixed: Vec<FixedRatio>,
    /// Colorants per recipe.
    pub k: usize,
    /// The viewings of the objective; the first is the reference of the metamerism indices.
    pub viewings: Vec<WeightedViewing>,
    /// How recipe and target are seen.
    pub presentation: Presentation,
    /// Price of cost in the objective, ΔE2000 per unit cost (0: cost only reported).
    pub cost_weight: f64,
}

/// One recipe found.
#[derive(Clone, Debug, PartialEq)]
pub struct Recipe {
    /// The colorants' indices in the library.
    pub indices: Vec<usize>,
    /// Their names.
    pub names: Vec<String>,
    /// Their amounts, summing to 1.
    pub amounts: Vec<f64>,
    /// The objective `F` (module documentation).
    pub objective: f64,
    /// CIEDE2000 from the target under each viewing, in order.
    pub delta_e: Vec<f64>,
    /// CIELAB of the recipe under each viewing.
    pub lab: Vec<[f64; 3]>,
    /// Special metamerism index of target and recipe from the first viewing to each other.
    pub metamerism: Vec<MetamerismIndex>,
    /// `Σ amount × cost_per_unit`.
    pub cost: f64,
}

/// The ranked recipes and what the search did.
#[derive(Clone, Debug, PartialEq)]
pub struct RecipeReport {
    /// The best recipes, best first, one per set of colorants used (amount > 1e-7): a recipe
    /// that leaves a colorant at 0 is listed once, not once per combination it fits in.
    pub recipes: Vec<Recipe>,
    /// Combinations fitted.
    pub combinations: usize,
    /// Combinations whose limits leave no recipe (e.g. maxima summing below 1).
    pub infeasible: usize,
    /// Model evaluations over all fits.
    pub evaluations: usize,
}

/// What one fit needs: the colorants of the combination, the viewings and the target.
struct Problem<'a> {
    search: &'a RecipeSearch,
    layers: Vec<Layer>,
    /// (colorant index, group position in `u`, weight / group total)
    map: Vec<(usize, usize, f64)>,
    colorimeters: Vec<&'static Colorimeter>,
    weights: Vec<f64>,
    target_lab: Vec<[f64; 3]>,
}

impl Problem<'_> {
    fn amounts(&self, u: &[f64]) -> Vec<f64> {
        self.map.iter().map(|&(_, g, share)| u[g] * share).collect()
    }

    fn reflectance(&self, amounts: &[f64]) -> Result<Spectrum, AnalysisError> {
        Ok(self.search.presentation.reflectance(&duncan_mix("recipe", &self.layers, amounts)?))
    }

    fn labs(&self, u: &[f64]) -> Option<Vec<[f64; 3]>> {
        let r = self.reflectance(&self.amounts(u)).ok()?;
        Some(self.colorimeters.iter().map(|c| c.lab(&c.xyz(&r)).lab).collect())
    }

    fn cost(&self, amounts: &[f64]) -> f64 {
        self.map.iter().zip(amounts).map(|(&(i, _, _), a)| a * self.search.colorants[i].cost_per_unit).sum()
    }

    /// `F` of the module documentation.
    fn objective(&self, u: &[f64]) -> f64 {
        let Some(labs) = self.labs(u) else { return f64::INFINITY };
        let total: f64 = self.weights.iter().sum();
        let mean_sq: f64 = labs
            .iter()
            .zip(&self.target_lab)
            .zip(&self.weights)
            .map(|((l, t), w)| w * delta_e_2000_raw(*l, *t).powi(2))
            .sum::<f64>()
            / total;
        mean_sq.sqrt() + self.search.cost_weight * self.cost(&self.amounts(u))
    }

    /// The stacked weighted CIELAB residuals, 3 per viewing.
    fn residual(&self, u: &[f64]) -> Option<DVector<f64>> {
        let labs = self.labs(u)?;
        let total: f64 = self.weights.iter().sum();
        Some(DVector::from_fn(3 * labs.len(), |r, _| {
            let (v, j) = (r / 3, r % 3);
            (self.weights[v] / total).sqrt() * (labs[v][j] - self.target_lab[v][j])
        }))
    }
}

/// Gauss-Newton steps on the weighted CIELAB residuals from `u`, in the plane `Σ Δu = 0`, each
/// projected onto the bounds and halved until the residual falls.
fn gauss_newton(p: &Problem, mut u: Vec<f64>, lo: &[f64], hi: &[f64], evaluations: &mut usize) -> Vec<f64> {
    let g = u.len();
    if g < 2 {
        return u;
    }
    let Some(mut r) = p.residual(&u) else { return u };
    *evaluations += 1;
    for _ in 0..8 {
        // Directions e_i − e_last span the plane Σ Δu = 0.
        let h = 1e-6;
        let mut j = DMatrix::<f64>::zeros(r.len(), g - 1);
        for col in 0..g - 1 {
            // Step inward: amounts may not go below 0 (Duncan's rule refuses them).
            let signed = if u[g - 1] >= h {
                h
            } else if u[col] >= h {
                -h
            } else {
                continue;
            };
            let mut moved = u.clone();
            moved[col] += signed;
            moved[g - 1] -= signed;
            let Some(rm) = p.residual(&moved) else { return u };
            *evaluations += 1;
            j.set_column(col, &((rm - &r) / signed));
        }
        let svd = j.svd(true, true);
        let threshold = 1e-9 * svd.singular_values.max();
        let Ok(step) = svd.solve(&(-&r), threshold) else { return u };
        let mut t = 1.0;
        let mut improved = false;
        while t > 1e-3 {
            let mut full: Vec<f64> = u.clone();
            for col in 0..g - 1 {
                full[col] += t * step[col];
                full[g - 1] -= t * step[col];
            }
            let trial = project_box_simplex(&full, lo, hi);
            if let Some(rt) = p.residual(&trial) {
                *evaluations += 1;
                if rt.norm_squared() < r.norm_squared() {
                    let gain = r.norm_squared() - rt.norm_squared();
                    (u, r, improved) = (trial, rt, true);
                    if gain < 1e-14 {
                        return u;
                    }
                    break;
                }
            }
            t *= 0.5;
        }
        if !improved {
            break;
        }
    }
    u
}

/// Every lattice point of step 1/`steps` on the simplex of `g` shares.
fn lattice(g: usize, steps: usize) -> Vec<Vec<f64>> {
    fn walk(g: usize, left: usize, steps: usize, cur: &mut Vec<f64>, out: &mut Vec<Vec<f64>>) {
        if cur.len() + 1 == g {
            cur.push(left as f64 / steps as f64);
            out.push(cur.clone());
            cur.pop();
            return;
        }
        for k in 0..=left {
            cur.push(k as f64 / steps as f64);
            walk(g, left - k, steps, cur, out);
            cur.pop();
        }
    }
    let mut out = Vec::new();
    walk(g, steps, steps, &mut Vec::new(), &mut out);
    out
}

/// The best recipes (at most `top`, best first, one per set of colorants used) of `search.k`
/// colorants of the library for a `target` reflectance seen as `search.presentation` says
/// (module documentation).
///
/// Errors, each naming the colorant and the constraint: an empty library, k outside 1..=n,
/// duplicate names, limits outside [0, 1] or min > max, negative costs, minima summing above
/// 1, more required colorants than k, a fixed pair naming an unknown colorant or contradicting
/// another pair or the limits; no viewing or weights not ≥ 0 with a positive sum; a target
/// outside [0, 1] (with its wavelength). A library whose limits leave no feasible combination
/// returns no recipes (`infeasible` counts them).
///
/// # Examples
///
/// A target mixed from two of three colorants is found again:
///
/// ```
/// use rouge_measure::analysis::correction::Presentation;
/// use rouge_measure::analysis::recipe::{Colorant, RecipeSearch, WeightedViewing, search_recipes};
/// use rouge_measure::analysis::{Layer, mixing::duncan_mix};
/// use rouge_measure::{Spectrum, Viewing};
///
/// let white = Layer::new("white", Spectrum::constant(40.0), Spectrum::constant(0.4))?;
/// let red = Layer::new("red", Spectrum::constant(5.0), Spectrum::from_fn(|nm| if nm < 590.0 { 20.0 } else { 0.5 }))?;
/// let blue = Layer::new("blue", Spectrum::constant(5.0), Spectrum::from_fn(|nm| if nm > 500.0 { 15.0 } else { 0.3 }))?;
/// let target = duncan_mix("t", &[white.clone(), red.clone()], &[0.7, 0.3])?.r_inf();
/// let search = RecipeSearch {
///     colorants: [white, red, blue].into_iter().map(Colorant::new).collect(),
///     fixed: vec![],
///     k: 2,
///     viewings: vec![WeightedViewing { viewing: Viewing::D65_1931, weight: 1.0 }],
///     presentation: Presentation::Opaque,
///     cost_weight: 0.0,
/// };
/// let best = &search_recipes(&search, &target, 1)?.recipes[0];
/// assert_eq!(best.names, ["white", "red"]);
/// assert!((best.amounts[0] - 0.7).abs() < 1e-3 && best.delta_e[0] < 0.01, "{best:?}");
/// # Ok::<(), rouge_measure::analysis::AnalysisError>(())
/// ```
pub fn search_recipes(search: &RecipeSearch, target: &Spectrum, top: usize) -> Result<RecipeReport, AnalysisError> {
    let groups = groups(search)?;
    if search.viewings.is_empty() {
        return Err(invalid("no viewing: give at least one illuminant for the objective"));
    }
    let weights: Vec<f64> = search.viewings.iter().map(|v| v.weight).collect();
    if weights.iter().any(|w| !(*w >= 0.0 && w.is_finite())) || weights.iter().sum::<f64>() <= 0.0 {
        return Err(invalid(format!("viewing weights {weights:?}: each finite and ≥ 0, their sum > 0")));
    }
    if !(search.cost_weight >= 0.0 && search.cost_weight.is_finite()) {
        return Err(invalid(format!("cost weight {}: must be finite and ≥ 0", search.cost_weight)));
    }
    check_reflectance("the target", target)?;
    if let Presentation::Over { background, thickness_mm } = &search.presentation {
        check_reflectance("the background", background)?;
        check_thickness("the thickness", *thickness_mm)?;
    }
    let colorimeters: Vec<&'static Colorimeter> = search.viewings.iter().map(|v| Colorimeter::get(v.viewing)).collect();
    let target_lab: Vec<[f64; 3]> = colorimeters.iter().map(|c| c.lab(&c.xyz(target)).lab).collect();
    let reference = search.viewings[0].viewing;
    let tests: Vec<Viewing> = if search.viewings.len() > 1 {
        search.viewings[1..].iter().map(|v| v.viewing).collect()
    } else {
        vec![Viewing { illuminant: Illuminant::A, ..reference }]
    };
    let combos = combinations(&groups, search.k);
    let mut report = RecipeReport { recipes: Vec::new(), combinations: 0, infeasible: 0, evaluations: 0 };
    for combo in &combos {
        let (lo, hi): (Vec<f64>, Vec<f64>) = combo.iter().map(|&g| (groups[g].lo, groups[g].hi)).unzip();
        if lo.iter().sum::<f64>() > 1.0 + 1e-12 || hi.iter().sum::<f64>() < 1.0 - 1e-12 {
            report.infeasible += 1;
            continue;
        }
        let mut map = Vec::new();
        for (pos, &g) in combo.iter().enumerate() {
            let total: f64 = groups[g].members.iter().map(|m| m.1).sum();
            map.extend(groups[g].members.iter().map(|&(i, w)| (i, pos, w / total)));
        }
        let problem = Problem {
            search,
            layers: map.iter().map(|&(i, _, _)| search.colorants[i].layer.clone()).collect(),
            map,
            colorimeters: colorimeters.clone(),
            weights: weights.clone(),
            target_lab: target_lab.clone(),
        };
        let mut evaluations = 0;
        let start = lattice(combo.len(), 4)
            .into_iter()
            .map(|u| project_box_simplex(&u, &lo, &hi))
            .map(|u| {
                evaluations += 1;
                (problem.objective(&u), u)
            })
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .map(|(_, u)| u)
            .unwrap_or_else(|| project_box_simplex(&vec![1.0; combo.len()], &lo, &hi));
        let u = gauss_newton(&problem, start, &lo, &hi, &mut evaluations);
        let (u, objective, n) = box_simplex_search(|u| problem.objective(u), &lo, &hi, &u, 0.01, 1e-7);
        evaluations += n;
        report.evaluations += evaluations;
        report.combinations += 1;
        let amounts = problem.amounts(&u);
        let r = problem.reflectance(&amounts)?;
        let lab: Vec<[f64; 3]> = colorimeters.iter().map(|c| c.lab(&c.xyz(&r)).lab).collect();
        let metamerism = tests
            .iter()
            .map(|&t| metamerism_index(target, &r, reference, t, Correction::Additive))
            .collect::<Result<Vec<_>, _>>()?;
        let (mut indices, mut names): (Vec<usize>, Vec<String>) =
            problem.map.iter().map(|&(i, _, _)| (i, search.colorants[i].layer.name.clone())).unzip();
        // Report colorants in library order.
        let mut order: Vec<usize> = (0..indices.len()).collect();
        order.sort_by_key(|&j| indices[j]);
        let amounts_sorted: Vec<f64> = order.iter().map(|&j| amounts[j]).collect();
        (indices, names) =
            (order.iter().map(|&j| indices[j]).collect(), order.iter().map(|&j| names[j].clone()).collect());
        report.recipes.push(Recipe {
            delta_e: lab.iter().zip(&target_lab).map(|(a, b)| delta_e_2000_raw(*a, *b)).collect(),
            cost: problem.cost(&amounts),
            indices,
            names,
            amounts: amounts_sorted,
            objective,
            lab,
            metamerism,
        });
    }
    report.recipes.sort_by(|a, b| a.objective.total_cmp(&b.objective));
    // A recipe with a colorant at 0 is a smaller recipe found again in every combination that
    // adds an unused colorant: keep the best of each set of colorants actually used.
    let mut seen: Vec<Vec<usize>> = Vec::new();
    report.recipes.retain(|r| {
        let used: Vec<usize> = r.indices.iter().zip(&r.amounts).filter(|(_, a)| **a > 1e-7).map(|(i, _)| *i).collect();
        let fresh = !seen.contains(&used);
        if fresh {
            seen.push(used);
        }
        fresh
    });
    report.recipes.truncate(top);
    Ok(report)
}

/// Small libraries and searches the tests of this module and of `constraints` share.
#[cfg(test)]
pub(crate) mod test_support {
    use super::*;

    /// Colorants named `names` with S = 20 and distinct K spectra.
    pub(crate) fn lib(names: &[&str]) -> Vec<Colorant> {
        names
            .iter()
            .enumerate()
            .map(|(i, n)| {
                let k = Spectrum::from_fn(|nm| 0.5 + 10.0 * (((nm - 380.0) / 60.0 + i as f64).sin()).powi(2));
                Colorant::new(Layer::new(n, Spectrum::constant(20.0), k).expect("finite"))
            })
            .collect()
    }

    /// A search of `k` of `colorants` under D65, opaque, without cost.
    pub(crate) fn search(colorants: Vec<Colorant>, fixed: Vec<FixedRatio>, k: usize) -> RecipeSearch {
        RecipeSearch {
            colorants,
            fixed,
            k,
            viewings: vec![WeightedViewing { viewing: Viewing::D65_1931, weight: 1.0 }],
            presentation: Presentation::Opaque,
            cost_weight: 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::test_support::{lib, search};
    use super::*;

    #[test]
    fn fixed_pairs_and_limits_hold_in_the_recipes() {
        let mut c = lib(&["a", "b", "c", "d"]);
        c[2].max = 0.25;
        c[3].cost_per_unit = 10.0;
        let fixed = vec![FixedRatio { a: "a".into(), b: "b".into(), ratio: 2.0 }];
        let s = search(c, fixed, 3);
        let target = Spectrum::constant(0.3);
        let report = search_recipes(&s, &target, 10).expect("feasible");
        assert_eq!(report.combinations, 2); // {a, b, c}, {a, b, d}
        for r in &report.recipes {
            assert!((r.amounts.iter().sum::<f64>() - 1.0).abs() < 1e-9, "{r:?}");
            assert!((r.amounts[0] - 2.0 * r.amounts[1]).abs() < 1e-9, "{r:?}");
            if r.names[2] == "c" {
                assert!(r.amounts[2] <= 0.25 + 1e-12, "{r:?}");
            } else {
                assert!((r.cost - 10.0 * r.amounts[2]).abs() < 1e-12, "{r:?}");
            }
        }
        assert!(report.recipes[0].objective <= report.recipes[1].objective);
    }
}
