//! Steadying a stroke: the lazy mouse of painting programs, which eyeliner needs.

use super::*;

/// A lazy-mouse stabiliser: the brush hangs on a string of `string_mm` behind the pointer and
/// moves only when the pointer pulls the string taut, straight toward the pointer. Jitter
/// shorter than the string never reaches the brush; a deliberate line does, `string_mm` late.
#[derive(Clone, Debug, PartialEq)]
pub struct LazyMouse {
    string_mm: f32,
    brush: Option<Vec3>,
}

impl LazyMouse {
    /// A stabiliser with a string of `string_mm` (0, negative or non-finite: off, the brush
    /// follows the pointer exactly).
    pub fn new(string_mm: f32) -> LazyMouse {
        let string_mm = if string_mm.is_finite() { string_mm.max(0.0) } else { 0.0 };
        LazyMouse { string_mm, brush: None }
    }

    /// The string's length, mm.
    pub fn string_mm(&self) -> f32 {
        self.string_mm
    }

    /// Where the brush is, once the stroke has started.
    pub fn brush(&self) -> Option<Vec3> {
        self.brush
    }

    /// Moves the pointer to `p`: the brush's new position, or `None` while the string is slack
    /// (or for a non-finite point). The first point of a stroke places the brush there.
    pub fn follow(&mut self, p: Vec3) -> Option<Vec3> {
        if !p.is_finite() {
            return None;
        }
        let Some(b) = self.brush else {
            self.brush = Some(p);
            return Some(p);
        };
        let d = b.distance(p);
        if d <= self.string_mm {
            return None;
        }
        let moved = b + (p - b) * ((d - self.string_mm) / d);
        self.brush = Some(moved);
        Some(moved)
    }

    /// Ends the stroke: the next [`LazyMouse::follow`] starts afresh.
    pub fn reset(&mut self) {
        self.brush = None;
    }
}
