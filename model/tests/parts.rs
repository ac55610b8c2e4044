//! The default head's parts follow the face: the eyelashes stay on the lids, outside the
//! eyeballs and the skin, through a blink, a squint and wide eyes; the lower teeth and the
//! tongue drop with the jaw.

use glam::Vec3;
use rouge_model::mesh::deform::SubdivisionPlan;
use rouge_model::mesh::targets::{FacePose, TargetSet};
use rouge_model::mesh::{Part, TriangleMesh, default_head};

fn posed(units: &[(&str, f32)], levels: u32) -> TriangleMesh {
    let base = default_head().expect("head");
    let mut positions = base.positions.clone();
    let pose = FacePose { expression: units.iter().map(|&(n, w)| (n.to_string(), w)).collect(), ..FacePose::default() };
    TargetSet::default_head().expect("targets").apply(&pose, &mut positions).expect("pose");
    SubdivisionPlan::new(&base, levels).mesh(&positions)
}

/// The vertices of the triangles of the groups `keep` accepts.
fn vertices(mesh: &TriangleMesh, keep: impl Fn(&rouge_model::mesh::TriangleGroup) -> bool) -> Vec<u32> {
    let mut v = mesh.only(keep).indices;
    v.sort_unstable();
    v.dedup();
    v
}

#[test]
fn lashes_stay_on_the_lids_outside_the_eyes_and_the_skin() {
    for levels in [0, 1] {
        for pose in [
            vec![],
            vec![("eyeBlinkLeft", 0.5), ("eyeBlinkRight", 0.5)],
            vec![("eyeBlinkLeft", 1.0), ("eyeBlinkRight", 1.0)],
            vec![("eyeSquintLeft", 1.0), ("eyeWideRight", 1.0)],
            vec![("eyeLookUpLeft", 1.0), ("browInnerUp", 1.0)],
        ] {
            let mesh = posed(&pose, levels);
            let skin = vertices(&mesh, |g| g.part() == Part::Skin);
            let mut worst_eye = f32::MAX;
            let mut worst_skin = f32::MAX;
            let mut farthest_root = 0.0f32;
            for (lashes, eye) in [("lashes_l", "eye_l"), ("lashes_r", "eye_r")] {
                let lash = vertices(&mesh, |g| g.name == lashes);
                let eye_v = vertices(&mesh, |g| g.name == eye);
                assert!(!lash.is_empty() && !eye_v.is_empty(), "{lashes} and {eye}");
                let eye_p: Vec<Vec3> = eye_v.iter().map(|&v| mesh.positions[v as usize]).collect();
                let centre = eye_p.iter().sum::<Vec3>() / eye_p.len() as f32;
                let radius = eye_p.iter().map(|p| p.distance(centre)).fold(0.0f32, f32::max);
                for &v in &lash {
                    let p = mesh.positions[v as usize];
                    assert!(p.is_finite());
                    worst_eye = worst_eye.min(p.distance(centre) - radius);
                    // Above the skin: along the nearest skin vertex's normal, the lash is not
                    // more than a fraction of a millimetre inside.
                    let (s, d) = skin
                        .iter()
                        .map(|&s| (s, mesh.positions[s as usize].distance(p)))
                        .min_by(|a, b| a.1.total_cmp(&b.1))
                        .expect("skin");
                    let q = mesh.positions[s as usize];
                    // The roots sit in the lid margin, between the lid and the eyeball, where
                    // the hm08 cards start (up to 1.4 mm behind the margin's surface): the
                    // check is for the strands beyond them.
                    if p.distance(centre) > radius + 1.0 {
                        worst_skin = worst_skin.min((p - q).dot(mesh.normals[s as usize]));
                    }
                    // The roots (the lash vertices nearest the eyeball) sit on the lid margin.
                    if p.distance(centre) < radius + 1.0 {
                        farthest_root = farthest_root.max(d);
                    }
                }
            }
            println!(
                "level {levels} {pose:?}: lashes at least {worst_eye:.2} mm off the eyeballs' spheres, \
                 {worst_skin:.2} mm along the skin's normal; roots within {farthest_root:.2} mm of the skin"
            );
            // The Face Units blend the lid's vertices linearly, so mid-blink the lid (and the
            // cards on it) cuts the eyeball's sphere by the sagitta of its arc (about 1.3 mm).
            assert!(worst_eye > -1.5, "a lash inside an eyeball ({worst_eye} mm) in {pose:?}");
            // Closed or squinting, the upper lashes meet the lower lid and the lower lashes meet
            // the upper (real lashes bend there; these pass up to 2 mm in); open, they clear
            // the skin.
            let closed =
                pose.iter().any(|&(n, w)| (n.starts_with("eyeBlink") || n.starts_with("eyeSquint")) && w == 1.0);
            let skin_limit = if closed { -2.0 } else { -0.5 };
            assert!(worst_skin > skin_limit, "a lash inside the skin ({worst_skin} mm) in {pose:?}");
            assert!(farthest_root < 3.0, "a lash root off the lid ({farthest_root} mm) in {pose:?}");
        }
    }
}

#[test]
fn the_lower_teeth_and_tongue_drop_with_the_jaw() {
    let rest = posed(&[], 0);
    let open = posed(&[("jawOpen", 1.0)], 0);
    let drop = |keep: &dyn Fn(&rouge_model::mesh::TriangleGroup) -> bool| {
        let v = vertices(&rest, keep);
        v.iter().map(|&i| rest.positions[i as usize].y - open.positions[i as usize].y).sum::<f32>() / v.len() as f32
    };
    let (lower, tongue, upper) =
        (drop(&|g| g.name == "teeth_lower"), drop(&|g| g.part() == Part::Tongue), drop(&|g| g.name == "teeth_upper"));
    println!("jawOpen 1: lower teeth drop {lower:.1} mm, tongue {tongue:.1} mm, upper teeth {upper:.1} mm");
    assert!(lower > 10.0 && tongue > 5.0, "the jaw carries the lower teeth and the tongue");
    assert!(upper.abs() < 0.1, "the upper teeth stay with the skull");
}

#[test]
fn mascara_lengthens_thickens_and_curls_every_lash() {
    use rouge_model::mesh::lashes::{LashRig, Mascara};
    let base = default_head().expect("head");
    let rig = LashRig::of(&base);
    // Both sides of every ribbon: 2 × (2 × 60 upper + 2 × 30 lower) strands, less those the
    // generator cut to one row (none reach that short).
    assert_eq!(rig.strand_count(), 2 * 180, "{} strips", rig.strand_count());
    let mut lash: Vec<u32> = base
        .groups
        .iter()
        .filter(|g| g.part() == rouge_model::mesh::Part::Lash)
        .flat_map(|g| base.faces[g.faces.clone()].iter().flat_map(|f| f.corners.iter().map(|c| c.position)))
        .collect();
    lash.sort_unstable();
    lash.dedup();
    let span = |p: &[Vec3]| {
        let b =
            rouge_model::mesh::Bounds::of(&lash.iter().map(|&v| p[v as usize]).collect::<Vec<_>>()).expect("lashes");
        b.size().length()
    };
    let mut long = base.positions.clone();
    rig.apply(&Mascara { length: 1.5, ..Mascara::default() }, &mut long);
    let mut curled = base.positions.clone();
    rig.apply(&Mascara { curl_deg: 30.0, ..Mascara::default() }, &mut curled);
    let mut none = base.positions.clone();
    rig.apply(&Mascara::default(), &mut none);
    assert_eq!(none, base.positions, "no mascara, no change");
    let moved =
        |p: &[Vec3]| lash.iter().map(|&v| p[v as usize].distance(base.positions[v as usize])).fold(0.0f32, f32::max);
    println!(
        "lash span {:.1} mm, ×1.5 length {:.1} mm; the tips move up to {:.1} mm (length) and {:.1} mm (curl 30°)",
        span(&base.positions),
        span(&long),
        moved(&long),
        moved(&curled)
    );
    assert!(span(&long) > span(&base.positions) + 2.0);
    assert!(moved(&long) > 2.0 && moved(&curled) > 1.5);
    assert!(long.iter().chain(&curled).all(|p| p.is_finite()));
    // Nothing but the lashes moves.
    let others: Vec<usize> = (0..base.positions.len()).filter(|v| lash.binary_search(&(*v as u32)).is_err()).collect();
    assert!(others.iter().all(|&v| long[v] == base.positions[v] && curled[v] == base.positions[v]));
    // Curled upper lashes rise: their mean y goes up; the lower ones go down.
    let upper_tips: Vec<u32> = lash.iter().copied().filter(|&v| base.positions[v as usize].y > 3.0).collect();
    let mean_y = |p: &[Vec3]| upper_tips.iter().map(|&v| p[v as usize].y).sum::<f32>() / upper_tips.len() as f32;
    assert!(mean_y(&curled) > mean_y(&base.positions) + 0.2, "curl lifts the upper lashes");
}

#[test]
fn mascara_specs_are_checked() {
    use rouge_model::mesh::lashes::Mascara;
    let m = Mascara::parse("length=1.4, volume=2.5,curl=20").expect("parse");
    assert_eq!(m, Mascara { length: 1.4, volume: 2.5, curl_deg: 20.0, color: None });
    for (bad, says) in [
        ("length=0.5", "length 0.5"),
        ("volume=nan", "volume NaN"),
        ("curl=90", "curl_deg 90"),
        ("colour=1", "unknown `colour`"),
        ("length", "KEY=VALUE"),
        ("length=abc", "not a number"),
        ("color=pink", "use black, brown, blue or R/G/B"),
        ("color=0.1/0.2", "R/G/B"),
        ("color=0.1/2/0.1", "each channel must be within 0..=1"),
    ] {
        let e = Mascara::parse(bad).expect_err(bad).to_string();
        assert!(e.contains(says), "{bad}: {e}");
    }
    // A colour: a named shade or linear R/G/B; in a look's JSON as an array, left out without one.
    assert_eq!(Mascara::parse("color=black").expect("black").color, Mascara::named_color("black"));
    let blue = Mascara::parse("color=0.01/0.02/0.3").expect("rgb");
    assert_eq!(blue.color, Some([0.01, 0.02, 0.3]));
    assert!(!blue.is_none(), "a colour alone is a mascara");
    let json = serde_json::to_string(&blue).expect("json");
    assert!(json.contains("\"color\":[0.01,0.02,0.3]"), "{json}");
    assert!(!serde_json::to_string(&m).expect("json").contains("color"), "no colour, no field");
    let back: Mascara = serde_json::from_str(&json).expect("read back");
    assert_eq!(back, blue);
}

#[test]
fn the_brows_lie_on_the_skin_and_follow_brow_inner_up() {
    let rest = posed(&[], 1);
    let raised = posed(&[("browInnerUp", 1.0)], 1);
    let skin = vertices(&rest, |g| g.part() == Part::Skin);
    for brow in ["brow_l", "brow_r"] {
        let hair = vertices(&rest, |g| g.name == brow);
        assert!(hair.len() > 1000, "{brow}: {} vertices", hair.len());
        // Every hair vertex lies over the skin, under a millimetre off it (along the nearest
        // skin vertex's normal).
        let mut worst = (0.0f32, f32::MAX);
        for &v in &hair {
            let p = rest.positions[v as usize];
            let (s, _) = skin
                .iter()
                .map(|&s| (s, rest.positions[s as usize].distance(p)))
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .expect("skin");
            let along = (p - rest.positions[s as usize]).dot(rest.normals[s as usize]);
            worst = (worst.0.max(along), worst.1.min(along));
        }
        // The brows' heads rise with browInnerUp.
        let medial: Vec<u32> = hair.iter().copied().filter(|&v| rest.positions[v as usize].x.abs() < 25.0).collect();
        let rise = medial.iter().map(|&v| raised.positions[v as usize].y - rest.positions[v as usize].y).sum::<f32>()
            / medial.len() as f32;
        println!(
            "{brow}: {} vertices, {:.2} to {:.2} mm over the skin along its normal; browInnerUp raises the \
             head {rise:.1} mm",
            hair.len(),
            worst.1,
            worst.0
        );
        assert!(worst.0 < 1.0 && worst.1 > -0.3, "{brow} off the skin: {worst:?}");
        assert!(rise > 1.5, "{brow}: browInnerUp raised the brow's head {rise} mm");
    }
}
