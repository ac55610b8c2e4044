//! The brushes of a makeup kit: a size, film thickness, flow, hardness, spacing and falloff per
//! job, applied over the painter's own mode, symmetry and reach settings.

use super::*;

/// One brush of the kit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BrushPreset {
    /// Its name in the brush panel.
    pub name: &'static str,
    /// What it is for, shown as a tooltip.
    pub purpose: &'static str,
    /// Radius, mm on the skin.
    pub radius_mm: f32,
    /// Target film thickness, mm.
    pub thickness_mm: f32,
    /// Flow per dab.
    pub flow: f32,
    /// Hardness.
    pub hardness: f32,
    /// Dab spacing, fraction of the radius.
    pub spacing: f32,
    /// Falloff shape.
    pub falloff: Falloff,
}

/// The kit: foundation sponge, blush brush, contour brush, liner, lipstick.
pub const BRUSH_PRESETS: [BrushPreset; 5] = [
    BrushPreset {
        name: "Foundation sponge",
        purpose: "a broad, even film (about 15 µm) pressed on with a sponge",
        radius_mm: 18.0,
        thickness_mm: 0.015,
        flow: 0.5,
        hardness: 0.6,
        spacing: 0.3,
        falloff: Falloff::Linear,
    },
    BrushPreset {
        name: "Blush brush",
        purpose: "a soft, diffuse veil (about 6 µm) built up over the cheekbones",
        radius_mm: 14.0,
        thickness_mm: 0.006,
        flow: 0.2,
        hardness: 0.0,
        spacing: 0.2,
        falloff: Falloff::Smooth,
    },
    BrushPreset {
        name: "Contour brush",
        purpose: "a narrower soft stroke (about 8 µm) under the cheekbone and along the jaw",
        radius_mm: 7.0,
        thickness_mm: 0.008,
        flow: 0.25,
        hardness: 0.2,
        spacing: 0.2,
        falloff: Falloff::Smooth,
    },
    BrushPreset {
        name: "Liner",
        purpose: "a fine, dense line (about 20 µm) along the lash line",
        radius_mm: 1.2,
        thickness_mm: 0.02,
        flow: 0.9,
        hardness: 0.8,
        spacing: 0.15,
        falloff: Falloff::Sphere,
    },
    BrushPreset {
        name: "Lipstick",
        purpose: "an opaque film (about 25 µm) with a crisp edge",
        radius_mm: 3.5,
        thickness_mm: 0.025,
        flow: 0.7,
        hardness: 0.7,
        spacing: 0.15,
        falloff: Falloff::Sphere,
    },
];

impl BrushPreset {
    /// `brush` with this preset's size, thickness, flow, hardness, spacing and falloff, in
    /// Paint mode; its symmetry, reach, facing and occlusion settings stay.
    pub fn apply(&self, brush: &Brush) -> Brush {
        Brush {
            mode: BrushMode::Paint,
            radius_mm: self.radius_mm,
            thickness_mm: self.thickness_mm,
            flow: self.flow,
            hardness: self.hardness,
            spacing: self.spacing,
            falloff: self.falloff,
            ..*brush
        }
    }

    /// Whether `brush` paints as this preset does (the panel marks the chosen one).
    pub fn matches(&self, brush: &Brush) -> bool {
        self.apply(brush) == *brush
    }
}
