//! Setting the brush radius by moving the mouse, as Blender's F: press F, the brush circle stays
//! where it is drawn and its edge follows the pointer; a click or Enter keeps the new radius, Esc
//! or a right click puts the old one back. No egui here; the viewport feeds it screen points.

use std::ops::RangeInclusive;

/// The radii the brush takes, mm (the brush panel's slider and `[` `]` keep to them too).
pub const RADIUS_RANGE_MM: RangeInclusive<f32> = 0.5..=40.0;

/// A radius drag in progress.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RadiusDrag {
    /// The circle's centre, screen points.
    centre: [f32; 2],
    /// Screen points per millimetre of skin where the circle is drawn.
    points_per_mm: f32,
    /// The radius when the drag began, mm (what a cancel restores).
    start_mm: f32,
    /// The radius now, mm.
    radius_mm: f32,
}

impl RadiusDrag {
    /// Starts a drag with the pointer at `pointer` (screen points) on the edge of the brush
    /// circle of `radius_mm`, drawn at `points_per_mm` (the brush's scale at the surface under
    /// the pointer): the centre is placed `radius` to the left of the pointer, so the circle does
    /// not jump. `None` for a scale that is not positive and finite.
    pub fn start(pointer: [f32; 2], radius_mm: f32, points_per_mm: f32) -> Option<RadiusDrag> {
        if !(points_per_mm > 0.0 && points_per_mm.is_finite()) {
            return None;
        }
        let radius_mm = radius_mm.clamp(*RADIUS_RANGE_MM.start(), *RADIUS_RANGE_MM.end());
        let centre = [pointer[0] - radius_mm * points_per_mm, pointer[1]];
        Some(RadiusDrag { centre, points_per_mm, start_mm: radius_mm, radius_mm })
    }

    /// The pointer moved to `pointer`: the radius is its distance from the centre (within
    /// [`RADIUS_RANGE_MM`]). Returns the new radius, mm.
    pub fn pointer_at(&mut self, pointer: [f32; 2]) -> f32 {
        let d = (pointer[0] - self.centre[0]).hypot(pointer[1] - self.centre[1]);
        self.radius_mm = (d / self.points_per_mm).clamp(*RADIUS_RANGE_MM.start(), *RADIUS_RANGE_MM.end());
        self.radius_mm
    }

    /// The circle's centre, screen points.
    pub fn centre(&self) -> [f32; 2] {
        self.centre
    }

    /// The radius now, mm (what a confirm keeps).
    pub fn radius_mm(&self) -> f32 {
        self.radius_mm
    }

    /// The circle's radius on screen now, points.
    pub fn radius_points(&self) -> f32 {
        self.radius_mm * self.points_per_mm
    }

    /// The radius before the drag, mm (what a cancel restores).
    pub fn start_mm(&self) -> f32 {
        self.start_mm
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_edge_follows_the_pointer_and_stays_in_range() {
        let mut d = RadiusDrag::start([300.0, 200.0], 10.0, 4.0).expect("a drag");
        assert_eq!(d.centre(), [260.0, 200.0]);
        assert_eq!(d.pointer_at([300.0, 200.0]), 10.0);
        assert_eq!(d.pointer_at([260.0, 120.0]), 20.0);
        assert_eq!(d.radius_points(), 80.0);
        assert_eq!(d.pointer_at([261.0, 200.0]), 0.5);
        assert_eq!(d.pointer_at([2000.0, 200.0]), 40.0);
        assert_eq!(d.start_mm(), 10.0);
        assert!(RadiusDrag::start([0.0, 0.0], 10.0, 0.0).is_none());
        assert!(RadiusDrag::start([0.0, 0.0], 10.0, f32::NAN).is_none());
    }
}
