//! The mouth's parts on the GPU (lavapipe on CI): the teeth and the tongue of the default head
//! show only when the lips part, and the cavity behind them is dark.

use rouge_model::mesh::Part;
use rouge_model::skin::AnatomyRegion;
use rouge_render::job::{FacePose, LookChoice, RenderJob};

const SIZE: u32 = 192;

/// A close-up of the lips in `pose`, drawn with every part and again without the teeth and
/// the tongue; returns both frames (RGBA8) and the pixels where they differ.
fn with_and_without_teeth(pose: &[(&str, f32)]) -> (Vec<u8>, usize) {
    let job = RenderJob {
        look: LookChoice::Bare,
        width: SIZE,
        height: SIZE,
        subdivision: 1,
        close_up: Some(AnatomyRegion::Lips),
        face: FacePose { expression: pose.iter().map(|&(n, w)| (n.to_string(), w)).collect(), ..FacePose::default() },
        ..RenderJob::default()
    };
    let loaded = job.load().expect("load");
    let mut prepared = job.prepare_loaded(&loaded).expect("prepare");
    let with = prepared.render_display().expect("render");
    // The same vertices (and tangents), fewer triangles: only the teeth and tongue are gone.
    let without_mesh = loaded.mesh.only(|g| !matches!(g.part(), Part::Teeth | Part::Tongue));
    prepared.renderer.set_mesh(&without_mesh, loaded.scene.skin.albedo).expect("set mesh");
    let without = prepared.render_display().expect("render");
    let differ = with
        .chunks_exact(4)
        .zip(without.chunks_exact(4))
        .filter(|(a, b)| (0..3).map(|c| a[c].abs_diff(b[c]) as u32).sum::<u32>() > 12)
        .count();
    (with, differ)
}

#[test]
fn the_teeth_and_tongue_show_only_when_the_lips_part() {
    let (_, closed) = with_and_without_teeth(&[("mouthClose", 1.0)]);
    // hm08's neutral mouth is relaxed, the lips about a millimetre apart: the incisors' edge
    // shows in the slit, as in a real relaxed mouth.
    let (_, relaxed) = with_and_without_teeth(&[]);
    let (_, open) = with_and_without_teeth(&[("jawOpen", 0.6)]);
    println!(
        "pixels that change without the teeth and tongue: lips closed {closed}, relaxed {relaxed}, jaw open 0.6 {open}"
    );
    assert_eq!(closed, 0, "closed lips hide the teeth and the tongue");
    assert!(open > (SIZE * SIZE / 50) as usize, "an open mouth shows them: {open} px");
    assert!(relaxed < open / 5, "the relaxed mouth shows a sliver: {relaxed} px");
}

#[test]
fn the_open_mouth_is_dark_inside() {
    // The middle of the mouth opening (the close-up centres on the lips): what shows there is
    // the tongue or the cavity, darker than the lips around it.
    let (open, _) = with_and_without_teeth(&[("jawOpen", 0.8)]);
    let luma = |x: u32, y: u32| {
        let i = 4 * (y * SIZE + x) as usize;
        0.2126 * f32::from(open[i]) + 0.7152 * f32::from(open[i + 1]) + 0.0722 * f32::from(open[i + 2])
    };
    let centre = luma(SIZE / 2, SIZE / 2);
    let lips = (0..SIZE).map(|y| luma(SIZE / 2, y)).fold(0.0f32, f32::max);
    println!("luma at the mouth's centre {centre:.0}, brightest on the vertical through it {lips:.0}");
    assert!(centre < 0.5 * lips, "the open mouth is dark inside: {centre} against {lips}");
}

#[test]
fn mascara_darkens_and_lengthens_the_lash_line() {
    use rouge_model::mesh::lashes::Mascara;
    let frame = |mascara: Option<Mascara>| {
        let job = RenderJob {
            look: LookChoice::Bare,
            width: SIZE,
            height: SIZE,
            subdivision: 1,
            close_up: Some(AnatomyRegion::Eyelids),
            mascara,
            ..RenderJob::default()
        };
        // Without the brows, which lie above the lashes in this view.
        let loaded = job.load().expect("load");
        let mut prepared = job.prepare_loaded(&loaded).expect("prepare");
        let no_brows = loaded.mesh.only(|g| g.part() != Part::Brow);
        prepared.renderer.set_mesh(&no_brows, loaded.scene.skin.albedo).expect("set mesh");
        prepared.render_display().expect("render")
    };
    // Dark pixels in the middle half of the columns (the eye; the background shows at the
    // frame's edge): the lashes, the pupil and the iris' rim; and the highest of them.
    let dark = |f: &[u8]| {
        let px: Vec<u32> = (0..SIZE * SIZE)
            .filter(|&i| (SIZE / 4..3 * SIZE / 4).contains(&(i % SIZE)))
            .filter(|&i| {
                let p = &f[4 * i as usize..4 * i as usize + 3];
                0.2126 * f32::from(p[0]) + 0.7152 * f32::from(p[1]) + 0.0722 * f32::from(p[2]) < 50.0
            })
            .collect();
        let top = px.iter().map(|&i| i / SIZE).min().unwrap_or(SIZE);
        (px.len(), top)
    };
    let (bare, bare_top) = dark(&frame(None));
    let (coated, coated_top) = dark(&frame(Some(Mascara { length: 1.5, volume: 3.0, curl_deg: 20.0, color: None })));
    println!("dark pixels: natural lashes {bare} (top row {bare_top}), with mascara {coated} (top row {coated_top})");
    assert!(coated as f32 > 1.3 * bare as f32, "mascara darkens the lash line: {bare} -> {coated}");
    assert!(coated_top + 2 < bare_top, "mascara lengthens the upper lashes: top row {bare_top} -> {coated_top}");
    // A coloured mascara colours the lashes: a bright red one, against the natural lashes, on
    // the lash pixels of the natural frame (the dark ones).
    let natural = frame(None);
    let red = frame(Some(Mascara { color: Some([0.6, 0.02, 0.02]), ..Mascara::default() }));
    let lash_px: Vec<usize> = (0..(SIZE * SIZE) as usize)
        .filter(|&i| (SIZE as usize / 4..3 * SIZE as usize / 4).contains(&(i % SIZE as usize)))
        .filter(|&i| i32::from(natural[4 * i]) < 40 && i32::from(natural[4 * i + 2]) < 40)
        .collect();
    let redness = |f: &[u8]| {
        lash_px.iter().map(|&i| f64::from(f[4 * i]) - f64::from(f[4 * i + 1])).sum::<f64>() / lash_px.len() as f64
    };
    println!(
        "red minus green on {} lash pixels: natural {:.1}, red mascara {:.1}",
        lash_px.len(),
        redness(&natural),
        redness(&red)
    );
    assert!(redness(&red) > redness(&natural) + 5.0, "a red mascara reddens the lashes");
}

/// A close-up of the brows of the bare head at one subdivision level, with `brow_gel`.
fn brows_job(brow_gel: Option<rouge_model::mesh::brow_gel::BrowGel>) -> RenderJob {
    RenderJob {
        look: LookChoice::Bare,
        width: SIZE,
        height: SIZE,
        subdivision: 1,
        close_up: Some(AnatomyRegion::Forehead),
        brow_gel,
        ..RenderJob::default()
    }
}

#[test]
fn a_brow_gel_tints_the_brow_hairs_and_nothing_else() {
    use rouge_model::mesh::brow_gel::BrowGel;
    let frame = |brow_gel: Option<BrowGel>, brows: bool| {
        let job = brows_job(brow_gel);
        let loaded = job.load().expect("load");
        let mut prepared = job.prepare_loaded(&loaded).expect("prepare");
        if !brows {
            let no_brows = loaded.mesh.only(|g| g.part() != Part::Brow);
            prepared.renderer.set_mesh(&no_brows, loaded.scene.skin.albedo).expect("set mesh");
        }
        prepared.render_display().expect("render")
    };
    let red = BrowGel { color: [0.6, 0.02, 0.02], strength: 1.0, fill: 0.0 };
    // Without the brow hairs the gel changes nothing.
    assert!(frame(None, false) == frame(Some(red), false), "the gel changed a pixel that is not a brow hair");
    // With them, the brow pixels redden.
    let (natural, gel) = (frame(None, true), frame(Some(red), true));
    let redder = (0..(SIZE * SIZE) as usize)
        .filter(|&i| i32::from(gel[4 * i]) - i32::from(natural[4 * i]) > 20 && gel[4 * i + 1] <= natural[4 * i + 1] + 5)
        .count();
    println!("brow pixels reddened by the gel: {redder}");
    assert!(redder > 30, "the gel reddens the brows: {redder} pixels");
    // Half strength: half way.
    let half = frame(Some(BrowGel { strength: 0.5, ..red }), true);
    let between = (0..(SIZE * SIZE) as usize)
        .filter(|&i| i32::from(gel[4 * i]) - i32::from(natural[4 * i]) > 20)
        .filter(|&i| half[4 * i] > natural[4 * i] && half[4 * i] < gel[4 * i])
        .count();
    assert!(between * 10 > redder * 8, "half strength lies between: {between} of {redder}");
}

#[test]
fn a_fibre_gel_fills_the_brows() {
    use rouge_model::mesh::brow_gel::BrowGel;
    let frame = |fill: f32| {
        let job = brows_job(Some(BrowGel { color: [0.045, 0.027, 0.016], strength: 0.0, fill }));
        let loaded = job.load().expect("load");
        let mut prepared = job.prepare_loaded(&loaded).expect("prepare");
        prepared.renderer.set_hair_aa(true);
        prepared.render_display().expect("render")
    };
    let luma = |f: &[u8]| -> f64 {
        f.chunks_exact(4).map(|p| 0.2126 * f64::from(p[0]) + 0.7152 * f64::from(p[1]) + 0.0722 * f64::from(p[2])).sum()
    };
    let (bare, half, full) = (frame(0.0), frame(0.5), frame(1.0));
    let (darker_half, darker_full) = (luma(&bare) - luma(&half), luma(&bare) - luma(&full));
    println!("luma taken by the fill (sum over the frame): half {darker_half:.0}, full {darker_full:.0}");
    assert!(darker_half > 0.0 && darker_full > 1.5 * darker_half, "more fill, darker brows");
    // Only the brows change: the rows above the brows' top are the same.
    let changed_rows: Vec<usize> = (0..SIZE as usize)
        .filter(|&y| (0..SIZE as usize).any(|x| bare[4 * (y * SIZE as usize + x)] != full[4 * (y * SIZE as usize + x)]))
        .collect();
    assert!(changed_rows.len() < SIZE as usize / 2, "the fill changes the brow rows only: {} rows", changed_rows.len());
}

#[test]
fn hairs_sorted_for_one_eye_are_drawn_again_as_they_are_and_sorted_again_when_the_eye_moves() {
    // The hair pass sorts its strands back to front once per eye (passes/hair.rs): a frame from
    // the same eye reuses the upload, a moved eye sorts again. Either way the frame is what a
    // fresh renderer draws from that eye, bit for bit.
    let job = brows_job(None);
    let loaded = job.load().expect("load");
    let render = |p: &mut rouge_render::job::Prepared| p.render_display().expect("render");
    let mut reused = job.prepare_loaded(&loaded).expect("prepare");
    reused.renderer.set_hair_aa(true);
    let front = render(&mut reused);
    assert!(render(&mut reused) == front, "the same eye draws the same frame");
    for yaw in [50.0, -50.0] {
        reused.camera.yaw_deg = yaw;
        let turned = render(&mut reused);
        let mut fresh = job.prepare_loaded(&loaded).expect("prepare");
        fresh.renderer.set_hair_aa(true);
        fresh.camera = reused.camera;
        assert!(turned == render(&mut fresh), "yaw {yaw}: the reused renderer's hairs differ from a fresh one's");
        assert!(turned != front);
    }
}
