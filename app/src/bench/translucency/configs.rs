//! The configurations `rouge bench translucency` measures per scene, model by model.

use super::{Config, ThicknessMap};
use rouge_model::medium::Medium;
use rouge_render::bounce::BounceSettings;
use rouge_render::cube_atlas::{AtlasSettings, GlobalTerm, OcclusionTest, Reach};
use rouge_render::local_thickness::{ThicknessSource, TranslucencyParams};
use rouge_render::{DipoleKind, DipoleSettings};
use rouge_render::{Skin, SlabThrough, SubsurfaceModel};
use serde_json::json;

/// The thickness model's configurations: each source with the three.js defaults and, where the
/// medium's file has them, the fitted parameters; on a morphed mesh also the map baked on the
/// rest pose (what a shipped bake gives once the mesh deforms).
pub(super) fn thickness_configs(
    medium: &Medium,
    sources: &[ThicknessSource],
    skin: &Skin,
    morphed: bool,
    bake_seconds: f64,
) -> Vec<Config> {
    let mut out = Vec::new();
    for source in sources {
        let baked = matches!(source, ThicknessSource::Baked(_));
        // The medium's own fit, or its nearest fitted neighbour's (a medium nobody fitted).
        let (fitted, origin) = TranslucencyParams::fitted(Some(medium), source.name(), false);
        let mut sets = vec![("three.js".to_string(), TranslucencyParams::THREE_JS)];
        if fitted != TranslucencyParams::THREE_JS {
            sets.push((origin.label(), fitted));
        }
        let poses: &[ThicknessMap] = match (baked, morphed) {
            (false, _) => &[ThicknessMap::None],
            (true, false) => &[ThicknessMap::Current],
            (true, true) => &[ThicknessMap::Current, ThicknessMap::Rest],
        };
        for (which, params) in &sets {
            let params = *params;
            for &map in poses {
                let source_name = match map {
                    ThicknessMap::Rest => "baked-rest-pose",
                    _ => source.name(),
                };
                let p = thickness_params_json(source_name, which, params, baked.then_some(bake_seconds));
                let skin = Skin {
                    subsurface: SubsurfaceModel::Thickness { params, source: source.clone(), kernel: None },
                    ..skin.clone()
                };
                out.push(Config { model: "thickness", params: p, skin, samples: 0, map, bounce: None });
            }
        }
    }
    out
}

/// A thickness term's row parameters: its local-thickness source, where its parameters come from,
/// the four parameters, and the bake's seconds for the baked source.
pub(super) fn thickness_params_json(
    source: &str,
    which: &str,
    params: TranslucencyParams,
    bake_seconds: Option<f64>,
) -> serde_json::Value {
    let mut p = json!({
        "source": source,
        "params": which,
        "distortion": params.distortion,
        "power": params.power,
        "scale": params.scale,
        "ambient": params.ambient,
    });
    if let Some(s) = bake_seconds {
        p["bake_s"] = json!(s);
    }
    p
}

/// Samples a direction of the combination's kernel (the kernel rows' middle).
pub(super) const COMBINATION_SAMPLES: u32 = 11;

/// `screen-space+thickness` (issue 31 item 4): the kernel of `skin` (the better dipole over the
/// half-space law) with the thickness term of each source, at the parameters fitted under the
/// kernel where the medium's file has them (`baked+kernel`, `shadow-map+kernel`), else those
/// fitted for the thickness model alone.
pub(super) fn combination_configs(
    medium: &Medium,
    sources: &[ThicknessSource],
    skin: &Skin,
    bake_seconds: f64,
) -> Vec<Config> {
    let Some(profile) = skin.subsurface.profile() else {
        return Vec::new();
    };
    sources
        .iter()
        .map(|source| {
            let (params, origin) = TranslucencyParams::fitted(Some(medium), source.name(), true);
            let which = origin.label();
            let baked = matches!(source, ThicknessSource::Baked(_));
            let mut p = thickness_params_json(source.name(), &which, params, baked.then_some(bake_seconds));
            p["profile"] = json!("better-dipole");
            p["samples"] = json!(COMBINATION_SAMPLES);
            p["diffuse"] = json!("half-space");
            let subsurface =
                SubsurfaceModel::Thickness { params, source: source.clone(), kernel: Some(profile.clone()) };
            let map = if baked { ThicknessMap::Current } else { ThicknessMap::None };
            Config {
                model: "screen-space+thickness",
                params: p,
                skin: Skin { subsurface, ..skin.clone() },
                samples: COMBINATION_SAMPLES,
                map,
                bounce: None,
            }
        })
        .collect()
}

/// The dipole models' configurations: both BSSRDFs at the default settings; with `sweep`, the
/// directional dipole over N and K and without each artifact fix.
pub(super) fn dipole_configs(skin: &Skin, sweep: bool) -> Vec<Config> {
    let config = |kind: DipoleKind, settings: DipoleSettings| {
        let params = json!({
            "samples": settings.samples,
            "directions": settings.directions,
            "map_px": settings.map_px,
            "fixes": [settings.shrink, settings.intrusion, settings.world_bias],
        });
        let skin = Skin { subsurface: SubsurfaceModel::Dipole { kind, settings }, ..skin.clone() };
        Config { model: kind.name(), params, skin, samples: 0, map: ThicknessMap::None, bounce: None }
    };
    let base = DipoleSettings::default();
    let mut out = vec![
        config(DipoleKind::Directional, base),
        config(DipoleKind::DirectionalMeanFreePath, base),
        config(DipoleKind::Standard, base),
    ];
    if sweep {
        for samples in [1, 10, 50, 100] {
            for directions in [4, 8, 16, 32] {
                out.push(config(DipoleKind::Directional, DipoleSettings { samples, directions, ..base }));
            }
        }
        out.push(config(DipoleKind::Directional, DipoleSettings { shrink: false, ..base }));
        out.push(config(DipoleKind::Directional, DipoleSettings { intrusion: false, ..base }));
        out.push(config(DipoleKind::Directional, DipoleSettings { world_bias: false, ..base }));
    }
    out
}

/// The cube atlas's configurations: the defaults; with `sweep`, one setting changed at a time.
pub(super) fn atlas_configs(skin: &Skin, sweep: bool) -> Vec<Config> {
    let config = |settings: AtlasSettings| {
        let params = json!({
            "atlas_px": settings.atlas_px,
            "kernel": settings.kernel_max,
            "reach": settings.reach.name(),
            "adaptive": settings.adaptive,
            "occlusion": settings.occlusion.name(),
            "global": settings.global.name(),
        });
        let skin = Skin { subsurface: SubsurfaceModel::CubeAtlas { settings }, ..skin.clone() };
        Config { model: "cube-atlas", params, skin, samples: 0, map: ThicknessMap::None, bounce: None }
    };
    let base = AtlasSettings::default();
    let mut out = vec![config(base)];
    if sweep {
        out.extend([3, 7, 9, 15].map(|kernel_max| config(AtlasSettings { kernel_max, ..base })));
        out.extend([256, 1024].map(|atlas_px| config(AtlasSettings { atlas_px, ..base })));
        out.extend([1.0, 4.0, 16.0].map(|m| config(AtlasSettings { reach: Reach::MeanFreePaths(m), ..base })));
        out.push(config(AtlasSettings { adaptive: false, ..base }));
        out.extend(
            [OcclusionTest::Off, OcclusionTest::PlaneOffset]
                .map(|occlusion| config(AtlasSettings { occlusion, ..base })),
        );
        out.extend([GlobalTerm::Off, GlobalTerm::RealSource].map(|global| config(AtlasSettings { global, ..base })));
    }
    out
}

/// The slab law's configurations (`render/src/slab_transmittance.rs`, no parameter): alone over
/// `lambert` (the medium's exact albedo) and over the half-space law, and under the kernel of
/// `combined` (the better dipole, 11 samples, over the half-space law) as `screen-space+slab`;
/// and the transmission gather in its place ([`SlabThrough::Gather`]) alone over the half-space
/// law and under the same kernel; both combinations also with the bounce between facing parts
/// (`+bounce`, [`BounceSettings::default`]).
pub(super) fn slab_configs(lambert: &Skin, combined: &Skin) -> Vec<Config> {
    let alone = |skin: &Skin, diffuse: &str, through: SlabThrough| {
        let subsurface = SubsurfaceModel::Slab { kernel: None, through };
        Config {
            model: subsurface.name(),
            params: json!({"diffuse": diffuse}),
            skin: Skin { subsurface, ..skin.clone() },
            samples: 0,
            map: ThicknessMap::None,
            bounce: None,
        }
    };
    let half_space = lambert.clone().half_space();
    let mut out = vec![
        alone(lambert, "lambert", SlabThrough::Law),
        alone(&half_space, "half-space", SlabThrough::Law),
        alone(&half_space, "half-space", SlabThrough::Gather),
    ];
    if let Some(profile) = combined.subsurface.profile() {
        let bounce = BounceSettings::default();
        let with_bounce =
            [(SlabThrough::Law, "screen-space+slab+bounce"), (SlabThrough::Gather, "screen-space+slab-gather+bounce")];
        for (through, bounced) in with_bounce {
            let subsurface = SubsurfaceModel::Slab { kernel: Some(profile.clone()), through };
            let params = json!({"profile": "better-dipole", "samples": COMBINATION_SAMPLES, "diffuse": "half-space"});
            let config = Config {
                model: subsurface.name(),
                params: params.clone(),
                skin: Skin { subsurface, ..combined.clone() },
                samples: COMBINATION_SAMPLES,
                map: ThicknessMap::None,
                bounce: None,
            };
            // The same with light between surfaces (render/src/bounce.rs).
            let mut params = params;
            params["bounce"] = json!({"samples": bounce.samples, "reach_mm": bounce.reach_mm});
            let with = Config { model: bounced, params, bounce: Some(bounce), ..config.clone() };
            out.extend([config, with]);
        }
    }
    out
}
