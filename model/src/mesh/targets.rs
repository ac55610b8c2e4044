//! Morph targets of the default head: the Face Units expressions (52 ARKit-named units) and
//! MakeHuman shapes, as sparse offsets of its base (unsubdivided) vertices in millimetres,
//! applied as a weighted sum before subdivision. UVs are untouched, so every UV-space map
//! (thickness layers, region masks, baked local thickness) follows the skin as it moves.
//!
//! Data: data/heads/hm08_targets.txt (python/gen_head_targets.py; CC0, data/SOURCES.md).

use std::collections::BTreeMap;
use std::path::Path;
use std::sync::OnceLock;

use glam::Vec3;
use serde::{Deserialize, Serialize};

/// The default head's targets, embedded like the head itself.
pub const DEFAULT_HEAD_TARGETS: &str = include_str!("../../../data/heads/hm08_targets.txt");

/// Millimetres per stored unit of the targets file.
pub const TARGET_UNIT_MM: f32 = 0.1;

/// Errors from reading targets or naming weights.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TargetError {
    /// A syntax or index error in a targets file, with its 1-based line and column.
    #[error(transparent)]
    Parse(#[from] rouge_measure::LocatedError),
    /// A weight list that is not `NAME=W,...`.
    #[error("{option} {spec:?}: {message}")]
    Syntax {
        /// The option (`--expression`, `--shape`).
        option: String,
        /// The text given.
        spec: String,
        /// What is wrong.
        message: String,
    },
    /// A name that is neither a target nor a preset.
    #[error("{option}: no {what} `{name}`{}", near_text(.near))]
    Unknown {
        /// The option or field.
        option: String,
        /// "expression unit or preset" or "shape".
        what: String,
        /// The name given.
        name: String,
        /// Known names close to it.
        near: Vec<String>,
    },
    /// A weight outside its range, or not finite.
    #[error("{option}: {name}={value} is outside {lo} to {hi}")]
    Range {
        /// The option or field.
        option: String,
        /// The target or preset.
        name: String,
        /// The weight given.
        value: f32,
        /// Smallest weight.
        lo: f32,
        /// Largest weight.
        hi: f32,
    },
    /// Targets applied to a mesh they were not made for.
    #[error(
        "the face's targets are for the default head ({expected} vertices); this mesh has {got}: use the default head"
    )]
    WrongMesh {
        /// Vertices the targets index.
        expected: usize,
        /// Vertices of the mesh.
        got: usize,
    },
}

fn near_text(near: &[String]) -> String {
    if near.is_empty() { String::new() } else { format!(" (did you mean {}?)", near.join(", ")) }
}

/// Weights by target name.
pub type Weights = BTreeMap<String, f32>;

/// Sparse offsets: `offsets_mm[i]` moves vertex `vertices[i]`.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SparseOffsets {
    /// Base-mesh vertices, ascending.
    pub vertices: Vec<u32>,
    /// Their offsets, mm.
    pub offsets_mm: Vec<Vec3>,
}

impl SparseOffsets {
    fn add_scaled(&self, w: f32, positions: &mut [Vec3]) {
        for (&v, &d) in self.vertices.iter().zip(&self.offsets_mm) {
            positions[v as usize] += w * d;
        }
    }
}

/// A shape target: one side (weights 0 to 1) or two (-1 applies `decr`, +1 `incr`).
#[derive(Debug, Clone, PartialEq)]
pub struct ShapeTarget {
    /// Its name (`age`, `nose-hump`, ...).
    pub name: String,
    /// Offsets at weight -1 (as a positive-weight target), for a two-sided shape.
    pub decr: Option<SparseOffsets>,
    /// Offsets at weight +1.
    pub incr: SparseOffsets,
}

impl ShapeTarget {
    /// The weights it takes: -1 to 1 when two-sided, else 0 to 1.
    pub fn range(&self) -> (f32, f32) {
        (if self.decr.is_some() { -1.0 } else { 0.0 }, 1.0)
    }
}

/// A named mix of expression units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExpressionPreset {
    /// Its name.
    pub name: &'static str,
    /// Unit weights at preset weight 1.
    pub units: &'static [(&'static str, f32)],
}

/// The named expressions, built from the Face Units (`neutral` sets nothing).
pub const EXPRESSION_PRESETS: &[ExpressionPreset] = &[
    ExpressionPreset { name: "neutral", units: &[] },
    ExpressionPreset {
        name: "smile",
        units: &[
            ("mouthSmileLeft", 1.0),
            ("mouthSmileRight", 1.0),
            ("cheekSquintLeft", 0.5),
            ("cheekSquintRight", 0.5),
            ("eyeSquintLeft", 0.3),
            ("eyeSquintRight", 0.3),
        ],
    },
    ExpressionPreset {
        name: "surprise",
        units: &[
            ("browInnerUp", 1.0),
            ("browOuterUpLeft", 1.0),
            ("browOuterUpRight", 1.0),
            ("eyeWideLeft", 1.0),
            ("eyeWideRight", 1.0),
            ("jawOpen", 0.35),
        ],
    },
    ExpressionPreset { name: "blink", units: &[("eyeBlinkLeft", 1.0), ("eyeBlinkRight", 1.0)] },
    ExpressionPreset {
        name: "talk",
        units: &[
            ("jawOpen", 0.3),
            ("mouthFunnel", 0.3),
            ("mouthLowerDownLeft", 0.3),
            ("mouthLowerDownRight", 0.3),
            ("mouthUpperUpLeft", 0.2),
            ("mouthUpperUpRight", 0.2),
        ],
    },
];

/// The face as the user sets it: expression weights by unit or preset name (0 to 1; a preset
/// scales its units, and a unit's total over presets and itself is clamped to 0 to 1) and shape
/// weights by shape name. Saved with projects. Empty maps (or all zeros) are the neutral head.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct FacePose {
    /// Expression unit or preset → weight.
    #[serde(default)]
    pub expression: BTreeMap<String, f32>,
    /// Shape → weight.
    #[serde(default)]
    pub shape: BTreeMap<String, f32>,
}

impl FacePose {
    /// Whether every weight is zero (the neutral, unshaped head).
    pub fn is_neutral(&self) -> bool {
        self.expression.values().chain(self.shape.values()).all(|&w| w == 0.0)
    }

    /// Parses `NAME=W,NAME=W` (what `--expression` and `--shape` take; `NAME` alone is weight 1);
    /// `option` names the option in errors. Names are checked by [`TargetSet::resolve`].
    ///
    /// # Errors
    /// [`TargetError::Syntax`] naming the option and the item at fault.
    pub fn parse_weights(spec: &str, option: &str) -> Result<BTreeMap<String, f32>, TargetError> {
        let fail = |message: String| TargetError::Syntax { option: option.into(), spec: spec.into(), message };
        let mut out = BTreeMap::new();
        for item in spec.split(',').map(str::trim).filter(|s| !s.is_empty()) {
            let (name, w) = item.split_once('=').unwrap_or((item, "1"));
            if name.trim().is_empty() {
                return Err(fail(format!("`{item}`: give NAME=WEIGHT (or NAME alone for weight 1)")));
            }
            let w: f32 =
                w.trim().parse().map_err(|_| fail(format!("`{item}`: the weight `{}` is not a number", w.trim())))?;
            if !w.is_finite() {
                return Err(fail(format!("`{item}`: the weight must be finite")));
            }
            if out.insert(name.trim().to_string(), w).is_some() {
                return Err(fail(format!("`{}` is given twice", name.trim())));
            }
        }
        Ok(out)
    }

    /// A preset alone at weight 1 (`neutral` gives the empty pose).
    pub fn preset(name: &str) -> FacePose {
        let mut pose = FacePose::default();
        if name != "neutral" {
            pose.expression.insert(name.to_string(), 1.0);
        }
        pose
    }
}

/// The expression presets' weights at time `t_s` of the app's animation cycle: neutral, smile,
/// blink, talk, surprise and back, one second each, blending linearly in between.
pub fn expression_cycle(t_s: f64) -> BTreeMap<String, f32> {
    const KEYS: [&str; 5] = ["neutral", "smile", "blink", "talk", "surprise"];
    let n = KEYS.len() as f64;
    let t = t_s.rem_euclid(n);
    let i = t.floor() as usize % KEYS.len();
    let f = (t - t.floor()) as f32;
    let mut out = BTreeMap::new();
    for (key, w) in [(KEYS[i], 1.0 - f), (KEYS[(i + 1) % KEYS.len()], f)] {
        if key != "neutral" && w > 0.0 {
            *out.entry(key.to_string()).or_insert(0.0) += w;
        }
    }
    out
}

/// The expressions and shapes of one base mesh.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct TargetSet {
    /// Vertices of the base mesh the targets index.
    pub vertex_count: usize,
    /// Expression units, in file order (alphabetical).
    pub expressions: Vec<(String, SparseOffsets)>,
    /// Shapes, in file order.
    pub shapes: Vec<ShapeTarget>,
}

impl TargetSet {
    /// The embedded default head's targets, parsed once.
    ///
    /// # Errors
    /// Only if the embedded file were corrupt (a build error in practice).
    pub fn default_head() -> Result<&'static TargetSet, TargetError> {
        static SET: OnceLock<Result<TargetSet, TargetError>> = OnceLock::new();
        SET.get_or_init(|| TargetSet::parse(DEFAULT_HEAD_TARGETS, Path::new("<embedded data/heads/hm08_targets.txt>")))
            .as_ref()
            .map_err(Clone::clone)
    }

    /// Parses the targets format of python/gen_head_targets.py.
    ///
    /// # Errors
    /// [`TargetError::Parse`] naming `path`, line and column.
    pub fn parse(text: &str, path: &Path) -> Result<TargetSet, TargetError> {
        let mut set = TargetSet::default();
        let mut lines = text.lines().enumerate().filter(|(_, l)| !l.trim().is_empty() && !l.starts_with('#'));
        let err = |line: usize, column: usize, message: String| {
            TargetError::Parse(rouge_measure::LocatedError::at(path, line + 1, Some(column), message))
        };
        // Column (1-based) of the k-th whitespace-separated token of a line.
        let column = |line: &str, k: usize| -> usize {
            let mut in_token = false;
            let mut seen = 0;
            for (i, ch) in line.char_indices() {
                let space = ch.is_whitespace();
                if !space && !in_token {
                    if seen == k {
                        return line[..i].chars().count() + 1;
                    }
                    seen += 1;
                }
                in_token = !space;
            }
            1
        };
        let Some((n, first)) = lines.next() else { return Err(err(0, 1, "empty targets file".into())) };
        let toks: Vec<&str> = first.split_whitespace().collect();
        set.vertex_count = match toks.as_slice() {
            ["vertices", count] => {
                count.parse().map_err(|_| err(n, column(first, 1), format!("bad count `{count}`")))?
            }
            _ => return Err(err(n, 1, "expected `vertices N`".into())),
        };
        while let Some((n, head)) = lines.next() {
            let toks: Vec<&str> = head.split_whitespace().collect();
            let (kind, name, side, count_tok, count_at) = match toks.as_slice() {
                ["expression", name, count] => ("expression", *name, "", *count, 2),
                ["shape", name, side, count] => ("shape", *name, *side, *count, 3),
                _ => {
                    return Err(err(
                        n,
                        1,
                        "expected `expression NAME COUNT` or `shape NAME decr|incr|both COUNT`".into(),
                    ));
                }
            };
            let count: usize =
                count_tok.parse().map_err(|_| err(n, column(head, count_at), format!("bad count `{count_tok}`")))?;
            let mut offsets = SparseOffsets::default();
            for _ in 0..count {
                let Some((m, line)) = lines.next() else {
                    return Err(err(n, 1, format!("{name}: the file ends before its {count} offsets do")));
                };
                let toks: Vec<&str> = line.split_whitespace().collect();
                if toks.len() != 4 {
                    return Err(err(m, 1, "expected `VERTEX DX DY DZ`".into()));
                }
                let v: u32 = toks[0].parse().map_err(|_| err(m, 1, format!("bad vertex `{}`", toks[0])))?;
                if v as usize >= set.vertex_count || offsets.vertices.last().is_some_and(|&p| p >= v) {
                    return Err(err(m, 1, format!("vertex {v} out of order or range (< {})", set.vertex_count)));
                }
                let mut d = [0f32; 3];
                for k in 0..3 {
                    let i: i32 = toks[k + 1]
                        .parse()
                        .map_err(|_| err(m, column(line, k + 1), format!("bad offset `{}`", toks[k + 1])))?;
                    d[k] = i as f32 * TARGET_UNIT_MM;
                }
                offsets.vertices.push(v);
                offsets.offsets_mm.push(Vec3::from(d));
            }
            match (kind, side) {
                ("expression", _) => set.expressions.push((name.to_string(), offsets)),
                (_, "incr") => match set.shapes.last_mut() {
                    Some(s) if s.name == name && s.incr.vertices.is_empty() => s.incr = offsets,
                    _ => set.shapes.push(ShapeTarget { name: name.into(), decr: None, incr: offsets }),
                },
                (_, "decr") => set.shapes.push(ShapeTarget {
                    name: name.into(),
                    decr: Some(offsets),
                    incr: SparseOffsets::default(),
                }),
                (_, "both") => {
                    let neg = SparseOffsets {
                        vertices: offsets.vertices.clone(),
                        offsets_mm: offsets.offsets_mm.iter().map(|d| -*d).collect(),
                    };
                    set.shapes.push(ShapeTarget { name: name.into(), decr: Some(neg), incr: offsets });
                }
                _ => return Err(err(n, column(head, 2), format!("`{side}`: expected decr, incr or both"))),
            }
        }
        Ok(set)
    }

    /// The expression unit named `name`.
    pub fn expression(&self, name: &str) -> Option<&SparseOffsets> {
        self.expressions.iter().find(|(n, _)| n == name).map(|(_, t)| t)
    }

    /// The shape named `name`.
    pub fn shape(&self, name: &str) -> Option<&ShapeTarget> {
        self.shapes.iter().find(|s| s.name == name)
    }

    /// The pose's per-unit expression weights (presets expanded, totals clamped to 0 to 1) and
    /// shape weights, checked.
    ///
    /// # Errors
    /// [`TargetError::Unknown`] (with near names) or [`TargetError::Range`], naming `--expression`
    /// or `--shape`.
    pub fn resolve(&self, pose: &FacePose) -> Result<(Weights, Weights), TargetError> {
        self.resolve_named(pose, ["--expression", "--shape"])
    }

    /// [`TargetSet::resolve`] with errors naming `fields` (the expression's and the shape's)
    /// instead of the command line's options: a project's `face.json` says `` `expression` ``.
    ///
    /// # Errors
    /// As [`TargetSet::resolve`].
    pub fn resolve_named(&self, pose: &FacePose, fields: [&str; 2]) -> Result<(Weights, Weights), TargetError> {
        let [expression_field, shape_field] = fields;
        let range = |option: &str, name: &str, value: f32, (lo, hi): (f32, f32)| {
            if value.is_finite() && (lo..=hi).contains(&value) {
                Ok(())
            } else {
                Err(TargetError::Range { option: option.into(), name: name.into(), value, lo, hi })
            }
        };
        let mut units: BTreeMap<String, f32> = BTreeMap::new();
        for (name, &w) in &pose.expression {
            range(expression_field, name, w, (0.0, 1.0))?;
            if let Some(p) = EXPRESSION_PRESETS.iter().find(|p| p.name == name) {
                for &(u, uw) in p.units {
                    *units.entry(u.to_string()).or_insert(0.0) += w * uw;
                }
            } else if self.expression(name).is_some() {
                *units.entry(name.clone()).or_insert(0.0) += w;
            } else {
                let known =
                    EXPRESSION_PRESETS.iter().map(|p| p.name).chain(self.expressions.iter().map(|(n, _)| n.as_str()));
                return Err(TargetError::Unknown {
                    option: expression_field.into(),
                    what: "expression unit or preset".into(),
                    name: name.clone(),
                    near: near_names(name, known),
                });
            }
        }
        for w in units.values_mut() {
            *w = w.clamp(0.0, 1.0);
        }
        for (name, &w) in &pose.shape {
            let Some(s) = self.shape(name) else {
                return Err(TargetError::Unknown {
                    option: shape_field.into(),
                    what: "shape".into(),
                    name: name.clone(),
                    near: near_names(name, self.shapes.iter().map(|s| s.name.as_str())),
                });
            };
            range(shape_field, name, w, s.range())?;
        }
        Ok((units, pose.shape.clone()))
    }

    /// Moves `positions` (the base mesh's, in its order) by the pose: every nonzero weight adds
    /// its weight times its offsets. All-zero weights leave the positions bit for bit.
    ///
    /// # Errors
    /// As [`TargetSet::resolve`]; [`TargetError::WrongMesh`] for another vertex count.
    pub fn apply(&self, pose: &FacePose, positions: &mut [Vec3]) -> Result<(), TargetError> {
        if positions.len() != self.vertex_count {
            return Err(TargetError::WrongMesh { expected: self.vertex_count, got: positions.len() });
        }
        let (units, shapes) = self.resolve(pose)?;
        for (name, w) in units {
            if let (Some(t), true) = (self.expression(&name), w != 0.0) {
                t.add_scaled(w, positions);
            }
        }
        for (name, w) in shapes {
            let Some(s) = self.shape(&name) else { continue };
            match (w > 0.0, &s.decr) {
                (true, _) => s.incr.add_scaled(w, positions),
                (false, Some(decr)) if w < 0.0 => decr.add_scaled(-w, positions),
                _ => {}
            }
        }
        Ok(())
    }
}

/// Up to five of `known` closest to `name` (case-insensitive edit distance within a third of
/// its length, at least 2, or one containing the other).
pub fn near_names<'a>(name: &str, known: impl Iterator<Item = &'a str>) -> Vec<String> {
    let lower = name.to_ascii_lowercase();
    let limit = (lower.len() / 3).max(2);
    let mut scored: Vec<(usize, &str)> = known
        .filter_map(|k| {
            let kl = k.to_ascii_lowercase();
            let d = edit_distance(&lower, &kl);
            let contains = lower.len() >= 3 && (kl.contains(&lower) || lower.contains(&kl));
            (d <= limit || contains).then_some((if contains { d.min(limit) } else { d }, k))
        })
        .collect();
    scored.sort();
    scored.into_iter().take(5).map(|(_, k)| k.to_string()).collect()
}

/// Levenshtein distance over bytes.
fn edit_distance(a: &str, b: &str) -> usize {
    let (a, b) = (a.as_bytes(), b.as_bytes());
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, &ca) in a.iter().enumerate() {
        let mut cur = vec![i + 1; b.len() + 1];
        for (j, &cb) in b.iter().enumerate() {
            cur[j + 1] = (prev[j] + usize::from(ca != cb)).min(prev[j + 1] + 1).min(cur[j] + 1);
        }
        prev = cur;
    }
    prev[b.len()]
}
