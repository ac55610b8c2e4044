//! A look's gloss layers as a clear coat over the rest: what OpenPBR's `coat_*` inputs
//! (`rouge export materialx`) and glTF's `KHR_materials_clearcoat` (`rouge export gltf`) carry.
//!
//! A layer whose finish is `gloss` (lip gloss, top coats: a clear, levelling film with a sharp
//! lobe, docs/FINISHES.md) is a coat: its coverage per texel (the lighting pass's weight of its
//! lobe, [`layer_coverage`]) is the coat's weight, the topmost gloss's roughness and index are the
//! coat's, and its colour stays in the base colour (the bake of every layer). The specular lobe
//! under the coat is baked from the other layers alone, so the coat's lobe is not counted twice.

use super::bake::layer_coverage;
use crate::renderer::LayerInput;
use rouge_measure::finish::FinishKind;

/// The look's gloss layers, as a coat.
#[derive(Clone, Debug, PartialEq)]
pub struct Coat {
    /// Weight per texel, `side_px`² texels, row 0 at v = 1: the largest coverage of a gloss layer.
    pub weight: Vec<f32>,
    /// Beckmann roughness (RMS slope) of the topmost gloss's lobe.
    pub beckmann_roughness: f32,
    /// Index of refraction of the topmost gloss.
    pub ior: f32,
}

impl Coat {
    /// The weight as an 8-bit grey plane (linear; glTF's `clearcoatTexture` reads its red).
    pub fn texels(&self) -> Vec<u8> {
        self.weight.iter().map(|&w| (w.clamp(0.0, 1.0) * 255.0).round() as u8).collect()
    }
}

/// Whether a layer is a gloss (its finish's kind).
fn is_coat(layer: &LayerInput<'_>) -> bool {
    layer.preset.finish.is_some_and(|f| f.kind == FinishKind::Gloss)
}

/// `layers` split into those under the coat and the coat of the glosses among them at
/// `side_px`² texels (`None` without a gloss).
pub fn split_coat<'a>(layers: &[LayerInput<'a>], side_px: u32) -> (Vec<LayerInput<'a>>, Option<Coat>) {
    let under: Vec<LayerInput<'a>> = layers.iter().copied().filter(|l| !is_coat(l)).collect();
    let glosses: Vec<&LayerInput<'a>> = layers.iter().filter(|l| is_coat(l)).collect();
    let Some(top) = glosses.last() else {
        return (under, None);
    };
    let mut weight = vec![0.0f32; (side_px as usize).pow(2)];
    for l in &glosses {
        let map = l.map.resized(side_px, side_px);
        for (w, &mm) in weight.iter_mut().zip(&map.mm) {
            *w = w.max(layer_coverage(mm * l.multiplier));
        }
    }
    let spec = top.preset.specular;
    (under, Some(Coat { weight, beckmann_roughness: spec.roughness as f32, ior: spec.ior as f32 }))
}
