//! `rouge export mitsuba`'s scene: the camera, lights, boundary and medium as the renderer has
//! them (the image comparison against Mitsuba itself is python/test_mitsuba_match.py).

use rouge_model::medium::Medium;
use rouge_render::diffusion::ProfileModel;
use rouge_render::job::RenderJob;
use rouge_render::mitsuba::{ExportInput, Interior, MitsubaScene, export};
use rouge_render::{LightRig, Scene, Skin};
use std::path::PathBuf;

fn job(medium: Option<&str>) -> RenderJob {
    let mut scene = Scene::rig(LightRig::FrontLeft);
    if let Some(m) = medium {
        scene.skin = Skin::from_medium(&Medium::builtin(m).expect("medium"), ProfileModel::BetterDipole).0;
    }
    RenderJob { mesh: Some(PathBuf::from("builtin:sphere")), width: 64, height: 48, scene, ..RenderJob::default() }
}

fn exported(job: &RenderJob, interior: Interior, light_radius_deg: f64) -> rouge_render::Result<MitsubaScene> {
    let loaded = job.load().expect("load");
    export(&ExportInput {
        mesh: &loaded.mesh,
        scene: &loaded.scene,
        env: None,
        camera: &loaded.camera,
        width: job.width,
        height: job.height,
        interior,
        spp: 16,
        boundary_alpha: 0.1,
        light_radius_deg,
    })
}

fn xml(job: &RenderJob, interior: Interior, light_radius_deg: f64) -> String {
    exported(job, interior, light_radius_deg).expect("export").xml
}

#[test]
fn camera_lights_and_medium_are_written_as_rendered() {
    let j = job(Some("marble"));
    let loaded = j.load().expect("load");
    let text = xml(&j, Interior::Medium, 0.0);
    let cam = loaded.camera.position();
    assert!(text.contains(&format!("<float name=\"fov\" value=\"{}\"/>", loaded.camera.fov_y_deg)));
    assert!(text.contains(&format!("origin=\"{}, {}, {}\"", cam.x, cam.y, cam.z)), "{text}");
    assert!(text.contains("<integer name=\"width\" value=\"64\"/>") && text.contains("value=\"48\""));
    assert!(text.contains("<emitter type=\"directional\">"));
    assert!(
        text.contains(&format!("<rgb name=\"irradiance\" value=\"{0}, {0}, {0}\"/>", f64::from(std::f32::consts::PI)))
    );
    assert!(text.contains("roughdielectric") && text.contains("<float name=\"int_ior\" value=\"1.5\"/>"));
    // marble: σt = σa + σs′, written relative to its largest channel with that channel as scale.
    let m = Medium::builtin("marble").expect("marble");
    let t = m.sigma_t_per_mm();
    assert!(text.contains(&format!("<float name=\"scale\" value=\"{}\"/>", t[2])), "{text}");
    assert!(text.contains("name=\"max_depth\" value=\"-1\""));
}

#[test]
fn interiors_and_area_lights() {
    let j = job(Some("skin1"));
    let absorber = xml(&j, Interior::Absorber, 0.0);
    assert!(absorber.contains("value=\"10000\"") && absorber.contains("<rgb name=\"albedo\" value=\"0, 0, 0\"/>"));
    let lambert = xml(&j, Interior::Lambert, 0.0);
    assert!(lambert.contains("<bsdf type=\"diffuse\">") && !lambert.contains("<medium"));
    let disk = xml(&j, Interior::Medium, 2.0);
    assert!(disk.contains("<shape type=\"disk\">") && !disk.contains("type=\"directional\""));
    // Index-matched: a null boundary.
    let mut matched = job(None);
    let m = Medium::builtin("skin1").expect("skin1");
    let m1 = Medium::from_coefficients("skin1", m.sigma_a_per_mm, m.sigma_s_prime_per_mm, 1.0).expect("η = 1");
    matched.scene.skin = Skin::from_medium(&m1, ProfileModel::BetterDipole).0;
    assert!(xml(&matched, Interior::Medium, 0.0).contains("<bsdf type=\"null\"/>"));
}

#[test]
fn a_medium_interior_needs_a_medium() {
    let e = exported(&job(None), Interior::Medium, 0.0).expect_err("no medium");
    assert!(e.to_string().contains("--medium"), "{e}");
}
