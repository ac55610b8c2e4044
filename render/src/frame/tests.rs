//! The frame plan's unit tests: which passes, targets and variants a scene gets.

use super::*;
use crate::local_thickness::ThicknessSource;
use crate::scene::{SlabThrough, SubsurfaceModel};
use crate::shader::ThicknessVariant;
use glam::Vec3;

fn read(plan: &FramePlan, i: usize, r: Resource) -> bool {
    plan.passes[i].reads.contains(&r)
}

fn settings() -> FrameSettings {
    FrameSettings {
        width: 64,
        height: 48,
        display: true,
        max_side: 8192,
        max_color_bytes: 32,
        aa: EdgeAa::Off,
        hair_aa: false,
    }
}

/// What is uploaded: `layers` layers and nothing else.
fn uploaded(layers: u32) -> Uploaded {
    Uploaded {
        layers,
        albedo_map: false,
        normal_map: false,
        local_thickness_map: false,
        skin_detail: false,
        glitter: 0,
        shadow_maps_kept: 0,
        hair_strands: 0,
    }
}

fn steps(plan: &FramePlan) -> Vec<String> {
    plan.passes.iter().map(|p| p.step.name()).collect()
}

#[test]
fn the_studio_frame_runs_every_pass() {
    let plan = FramePlan::new(&Scene::studio(), uploaded(3), settings()).expect("plan");
    assert_eq!(steps(&plan), ["shadow 0", "gbuffer", "lighting", "sss horizontal", "sss vertical", "composite"]);
    assert!(plan.targets.contains(&Target::ThicknessA) && !plan.targets.contains(&Target::ThicknessB));
    let text = plan.explain();
    assert!(text.contains("shadow pass for light 1 (point): the light casts no shadow"), "{text}");
    assert!(text.contains("thickness 4-7 target"), "{text}");
}

#[test]
fn what_the_scene_does_not_use_is_skipped_with_a_reason() {
    let mut scene = Scene::white_light(Vec3::Z);
    scene.skin.subsurface = SubsurfaceModel::None;
    let plan = FramePlan::new(&scene, uploaded(0), settings()).expect("plan");
    assert_eq!(steps(&plan), ["gbuffer", "lighting", "composite"]);
    assert_eq!(plan.passes[2].step, Step::Composite(Target::Diffuse));
    for t in [Target::ThicknessA, Target::ThicknessB, Target::SssScratch, Target::Scattered, Target::ExitT] {
        assert!(!plan.targets.contains(&t), "{t:?} allocated for a bare frame without SSS");
    }
    let text = plan.explain();
    for reason in ["the look is bare", "subsurface model is none", "no environment", "casts no shadow"] {
        assert!(text.contains(reason), "{reason:?} missing from:\n{text}");
    }
    scene.skin.subsurface = SubsurfaceModel::skin_screen_space();
    scene.sss.width = 0.0;
    let plan = FramePlan::new(&scene, uploaded(0), settings()).expect("plan");
    assert!(plan.explain().contains("the SSS width is 0"));
}

#[test]
fn the_thickness_pass_and_target_exist_only_when_a_material_uses_them() {
    use crate::local_thickness::TranslucencyParams;
    let up = Uploaded { local_thickness_map: true, ..uploaded(0) };
    let mut scene = Scene::rig(crate::scene::LightRig::Back);
    // Not used: neither the pass nor the target.
    let plan = FramePlan::new(&scene, up, settings()).expect("plan");
    assert!(!steps(&plan).contains(&"thickness".to_string()));
    assert!(!plan.targets.contains(&Target::LocalThickness) && !plan.targets.contains(&Target::BackDepth));
    assert!(
        plan.explain()
            .contains("back-face depth pass and local-thickness target: no material uses the thickness model")
    );
    // Baked: the G-buffer samples the map, the pass adds to the diffuse radiance, no SSS.
    let params = TranslucencyParams::THREE_JS;
    let baked = ThicknessSource::for_medium(true, None, 8, 20.0);
    scene.skin.subsurface = SubsurfaceModel::Thickness { params, source: baked.clone(), kernel: None };
    let plan = FramePlan::new(&scene, up, settings()).expect("plan");
    assert_eq!(steps(&plan), ["shadow 0", "gbuffer", "lighting", "thickness", "composite"]);
    assert!(plan.targets.contains(&Target::LocalThickness) && plan.kernel.is_none());
    assert_eq!(plan.variant.thickness, ThicknessVariant::Baked);
    assert!(read(&plan, 1, Resource::LocalThicknessMap));
    // Under a kernel (screen-space+thickness): the term is added to the diffuse radiance before
    // the blur, which then scatters it with the rest.
    let kernel = Some(crate::sss::DiffusionProfile::skin());
    scene.skin.subsurface = SubsurfaceModel::Thickness { params, source: baked.clone(), kernel };
    let plan = FramePlan::new(&scene, up, settings()).expect("plan");
    assert_eq!(
        steps(&plan),
        ["shadow 0", "gbuffer", "lighting", "thickness", "sss horizontal", "sss vertical", "composite"]
    );
    assert!(plan.kernel.is_some() && plan.explain().contains("subsurface screen-space+thickness"));
    scene.skin.subsurface = SubsurfaceModel::Thickness { params, source: baked.clone(), kernel: None };
    // The baked source without its map is an error that says what to do.
    let none = Uploaded { local_thickness_map: false, ..up };
    let err = FramePlan::new(&scene, none, settings()).expect_err("no map");
    assert!(err.to_string().contains("set_local_thickness"), "{err}");
    // Shadow-map source: lights without a shadow map get no term, and with none the pass goes.
    scene.skin.subsurface =
        SubsurfaceModel::Thickness { params, source: ThicknessSource::for_medium(false, None, 8, 20.0), kernel: None };
    let plan = FramePlan::new(&scene, none, settings()).expect("plan");
    assert_eq!(plan.variant.thickness, ThicknessVariant::ShadowMap);
    assert!(
        plan.passes.iter().any(|p| matches!(p.step, Step::Thickness(_)) && p.reads.contains(&Resource::ShadowMaps))
    );
    scene.lights[0].shadows = false;
    let plan = FramePlan::new(&scene, none, settings()).expect("plan");
    assert!(!plan.targets.contains(&Target::LocalThickness));
    let text = plan.explain();
    assert!(text.contains("no light has a shadow map") && text.contains("thickness translucency of light 0"), "{text}");
    // Parameters out of their domain.
    scene.skin.subsurface = SubsurfaceModel::Thickness {
        params: TranslucencyParams { power: -1.0, ..params },
        source: baked,
        kernel: None,
    };
    assert!(FramePlan::new(&scene, up, settings()).is_err());
}

#[test]
fn the_slab_law_runs_the_thickness_pass_on_the_shadow_maps_and_needs_a_medium() {
    let up = uploaded(0);
    let mut scene = Scene::rig(crate::scene::LightRig::Back);
    scene.skin.subsurface = SubsurfaceModel::Slab { kernel: None, through: SlabThrough::Law };
    // No physical medium: an error that says how to give one.
    let err = FramePlan::new(&scene, up, settings()).expect_err("no medium");
    assert!(err.to_string().contains("--medium"), "{err}");
    scene.skin.medium = Some(rouge_model::medium::Medium::builtin("marble").expect("marble"));
    let plan = FramePlan::new(&scene, up, settings()).expect("plan");
    assert_eq!(steps(&plan), ["shadow 0", "gbuffer", "lighting", "back depth", "thickness", "composite"]);
    assert_eq!(plan.variant.thickness, ThicknessVariant::Slab);
    // The back faces' depth is the slab law's alone: the thickness pass reads it there.
    assert!(plan.passes.iter().any(|p| matches!(p.step, Step::Thickness(_))
        && p.reads.contains(&Resource::Target(crate::targets::Target::BackDepth))));
    assert!(
        plan.passes
            .iter()
            .any(|p| matches!(p.step, Step::Thickness(u) if u.is_slab()) && p.reads.contains(&Resource::ShadowMaps))
    );
    assert!(!plan.passes.iter().any(|p| p.reads.contains(&Resource::LocalThicknessMap)));
    let text = plan.explain();
    assert!(text.contains("subsurface slab (each shadowed light through a plane slab"), "{text}");
    // Marble's η of 1.5: the law's table holds the boundary, and the plan says at which η.
    assert!(text.contains("under the medium's boundary (η 1.5:"), "{text}");
    // The side faces' drain is part of the law, and the plan names it; so is the march.
    assert!(text.contains("drained toward the edges where the face meets a side face"), "{text}");
    assert!(text.contains("marched along the view ray to the back faces' depth"), "{text}");
    // Past the table's last η the plan is refused, naming the medium's η.
    let mut dense = scene.clone();
    dense.skin.medium =
        Some(rouge_model::medium::Medium::builtin("marble").expect("marble").with_eta(2.0).expect("η 2"));
    let err = FramePlan::new(&dense, up, settings()).expect_err("η 2 is past the table");
    assert!(err.to_string().contains("covers η from 1 to 1.6: marble has η 2"), "{err}");
    // The gather knows which kernel carries the seen entries' light: none here.
    let kernel = |plan: &FramePlan| {
        plan.passes.iter().find_map(|p| if let Step::Thickness(u) = p.step { Some(u.screen_kernel) } else { None })
    };
    assert_eq!(kernel(&plan), Some([0.0; 4]));
    // Under the kernel, before the blur; the gather leaves the kernel its reach (3σ of the
    // profile's widest Gaussian, 8.2 mm for d'Eon's skin) and its depth-follow distance.
    let profile = crate::sss::DiffusionProfile::skin();
    let reach = 3.0 * profile.max_sigma_mm() as f32;
    scene.skin.subsurface = SubsurfaceModel::Slab { kernel: Some(profile), through: SlabThrough::Law };
    let plan = FramePlan::new(&scene, up, settings()).expect("plan");
    assert_eq!(
        steps(&plan),
        ["shadow 0", "gbuffer", "lighting", "back depth", "thickness", "sss horizontal", "sss vertical", "composite"]
    );
    assert_eq!(kernel(&plan), Some([reach, 3.0, 0.0, 0.0]));
    // At width 0 no kernel runs, and the gather takes all of the seen entries' excess.
    scene.sss.width = 0.0;
    let plan = FramePlan::new(&scene, up, settings()).expect("plan");
    assert!(!steps(&plan).contains(&"sss horizontal".to_string()));
    assert_eq!(kernel(&plan), Some([0.0; 4]));
    scene.sss.width = 1.0;
    // No shadow map: no pass, and the plan says why.
    scene.lights[0].shadows = false;
    let plan = FramePlan::new(&scene, up, settings()).expect("plan");
    assert!(!plan.targets.contains(&Target::LocalThickness));
    let text = plan.explain();
    assert!(
        text.contains("no light has a shadow map for the slab law") && text.contains("slab translucency of light 0")
    );
}

#[test]
fn bad_requests_are_errors() {
    let up = uploaded(0);
    let scene = Scene::studio();
    assert!(FramePlan::new(&scene, up, FrameSettings { width: 0, ..settings() }).is_err());
    assert!(FramePlan::new(&scene, up, FrameSettings { width: 9000, ..settings() }).is_err());
    let mut many = scene.clone();
    many.lights = vec![scene.lights[0]; MAX_LIGHTS + 1];
    assert!(FramePlan::new(&many, up, settings()).is_err());
    let mut nan = scene.clone();
    nan.sss.width = f32::NAN;
    assert!(FramePlan::new(&nan, up, settings()).is_err());
    let mut even = scene;
    even.sss.samples = 4;
    assert!(FramePlan::new(&even, up, settings()).is_err());
}

#[test]
fn glitter_is_planned_only_where_a_layer_has_it_and_the_device_takes_its_target() {
    let up = |glitter| Uploaded { glitter, ..uploaded(2) };
    let roomy = FrameSettings { max_color_bytes: 128, ..settings() };
    let plan = FramePlan::new(&Scene::studio(), up(0), roomy).expect("plan");
    assert!(!plan.variant.glitter && !plan.targets.contains(&Target::Glitter));
    assert!(plan.explain().contains("glitter: none in the look"), "{}", plan.explain());
    let plan = FramePlan::new(&Scene::studio(), up(0b10), roomy).expect("plan");
    assert!(plan.variant.glitter && plan.targets.contains(&Target::Glitter));
    assert!(read(&plan, 2, Resource::Glitter(0b10)) && read(&plan, 2, Resource::Target(Target::Glitter)));
    assert!(plan.explain().contains("glitter of layer(s) 1 (flake fields)"), "{}", plan.explain());
    // The G-buffer with glitter takes 40 bytes a pixel: a device with WebGPU's 32 draws none.
    let plan = FramePlan::new(&Scene::studio(), up(0b10), settings()).expect("plan");
    assert!(!plan.variant.glitter && !plan.targets.contains(&Target::Glitter));
    assert!(plan.explain().contains("40 bytes a pixel, the device takes 32"), "{}", plan.explain());
    let mut dark = Scene::studio();
    dark.specular = false;
    let plan = FramePlan::new(&dark, up(1), roomy).expect("plan");
    assert!(!plan.variant.glitter && plan.explain().contains("glitter: specular is off"), "{}", plan.explain());
}

#[test]
fn the_hair_pass_runs_only_for_a_mesh_with_strands() {
    let plan = FramePlan::new(&Scene::studio(), uploaded(3), settings()).expect("plan");
    assert!(!steps(&plan).iter().any(|s| s.starts_with("hair")));
    assert!(!plan.targets.contains(&Target::Hair) && !plan.variant.hair);
    assert!(plan.explain().contains("hair pass: the mesh has no hair strands"), "{}", plan.explain());
    let with_hair = Uploaded { hair_strands: 620, ..uploaded(3) };
    for antialiased in [false, true] {
        let plan = FramePlan::new(&Scene::studio(), with_hair, FrameSettings { hair_aa: antialiased, ..settings() })
            .expect("plan");
        let names = steps(&plan);
        let hair = names.iter().position(|s| s.starts_with("hair")).expect("a hair pass");
        assert_eq!(names[hair + 1], "composite", "the hair is composited: {names:?}");
        assert_eq!(plan.passes[hair].step, Step::Hair(crate::passes::hair::HairStep { antialiased }));
        assert!(plan.passes[hair + 1].reads.contains(&Resource::Target(Target::Hair)));
        assert!(plan.explain().contains("620 hair strands"), "{}", plan.explain());
    }
}

#[test]
fn the_half_space_law_and_its_curvature_term_are_planned_only_where_they_apply() {
    let up = uploaded(0);
    let mut scene = Scene::studio();
    let step = |plan: &FramePlan| match plan.passes.iter().find(|p| p.step.name() == "lighting").map(|p| &p.step) {
        Some(Step::Lighting(s)) => *s,
        other => panic!("no lighting step: {other:?}"),
    };
    // Lambert: no table.
    let plan = FramePlan::new(&scene, up, settings()).expect("plan");
    assert_eq!(step(&plan).half_space, None);
    assert!(plan.explain().contains("half-space law table: the skin's diffuse law is Lambert"));
    // The law without a medium: the table at the skin's IOR, no curvature term.
    scene.skin = scene.skin.clone().half_space();
    let plan = FramePlan::new(&scene, up, settings()).expect("plan");
    let law = step(&plan).half_space.expect("the law's table");
    assert_eq!((law.eta, law.curvature), (f64::from(scene.skin.ior), None));
    assert!(plan.explain().contains("environment term: the skin has no medium"), "{}", plan.explain());
    // With a medium and the studio's environment: the term, and the plan says so.
    scene.skin.medium = Some(rouge_model::medium::Medium::builtin("skin1").expect("skin1"));
    let plan = FramePlan::new(&scene, up, settings()).expect("plan");
    let curvature = step(&plan).half_space.and_then(|l| l.curvature).expect("the curvature term");
    assert!((curvature[0][1] - (0.032 + 0.74)).abs() < 1e-9, "σt′ of skin1's red: {curvature:?}");
    assert!(plan.explain().contains("corrected per pixel for the surface's mean curvature"));
    // Not from normals that carry pores.
    let plan = FramePlan::new(&scene, Uploaded { skin_detail: true, ..up }, settings()).expect("plan");
    assert_eq!(step(&plan).half_space.and_then(|l| l.curvature), None);
    assert!(plan.explain().contains("carry a normal map or skin detail"));
    // Without an environment there is nothing for it to correct.
    scene.environment = None;
    let plan = FramePlan::new(&scene, up, settings()).expect("plan");
    assert_eq!(step(&plan).half_space.and_then(|l| l.curvature), None);
    assert!(plan.explain().contains("environment term: the scene has no environment"));
    // An IOR outside the table is an error that names it.
    scene.skin.ior = 3.5;
    let err = FramePlan::new(&scene, up, settings()).expect_err("η 3.5").to_string();
    assert!(err.contains("3.5"), "{err}");
}

#[test]
fn the_bounce_runs_only_when_asked_and_the_blur_reads_its_output() {
    let mut scene = Scene::studio();
    let plan = FramePlan::new(&scene, uploaded(3), settings()).expect("plan");
    assert!(!plan.targets.contains(&Target::Bounced) && !plan.targets.contains(&Target::BounceLight));
    assert!(plan.explain().contains("bounce pass and its targets: light between surfaces is off"));
    scene.bounce = Some(crate::bounce::BounceSettings::default());
    let plan = FramePlan::new(&scene, uploaded(3), settings()).expect("plan");
    assert_eq!(
        steps(&plan),
        [
            "shadow 0",
            "gbuffer",
            "lighting",
            "bounce (64 samples to 100 mm)",
            "sss horizontal",
            "sss vertical",
            "composite"
        ]
    );
    // It adds to the diffuse radiance, and reads the stack's T of the 3 layers; the blur starts
    // from its output.
    for r in [Target::Diffuse, Target::Normal, Target::Albedo, Target::Depth, Target::ExitT] {
        assert!(read(&plan, 3, Resource::Target(r)), "{r:?}");
    }
    assert!(read(&plan, 4, Resource::Target(Target::Bounced)) && !read(&plan, 4, Resource::Target(Target::Diffuse)));
    assert_eq!(plan.passes[6].step, Step::Composite(Target::Scattered));
    // Without the blur, the composite reads it.
    scene.skin.subsurface = SubsurfaceModel::None;
    let plan = FramePlan::new(&scene, uploaded(0), settings()).expect("plan");
    assert!(!read(&plan, 3, Resource::Target(Target::ExitT)));
    assert_eq!(plan.passes[4].step, Step::Composite(Target::Bounced));
    scene.bounce = Some(crate::bounce::BounceSettings { samples: 0, ..Default::default() });
    let e = FramePlan::new(&scene, uploaded(0), settings()).expect_err("no samples").to_string();
    assert!(e.contains("bounce samples 0"), "{e}");
}
