//! The one texel-rectangle type of Rouge: what a dab changed, what a stroke's undo step holds,
//! what the renderer re-uploads.

/// A rectangle of texels, half-open: x0 ≤ x < x1, y0 ≤ y < y1 (row 0 at the top of the map).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct TexelRect {
    /// First column.
    pub x0: u32,
    /// First row.
    pub y0: u32,
    /// One past the last column.
    pub x1: u32,
    /// One past the last row.
    pub y1: u32,
}

impl TexelRect {
    /// The empty rectangle.
    pub const EMPTY: TexelRect = TexelRect { x0: 0, y0: 0, x1: 0, y1: 0 };

    /// The rectangle x0..x1 × y0..y1.
    pub const fn new(x0: u32, y0: u32, x1: u32, y1: u32) -> TexelRect {
        TexelRect { x0, y0, x1, y1 }
    }

    /// The whole of a `width` × `height` map.
    pub fn whole(width: u32, height: u32) -> TexelRect {
        TexelRect { x0: 0, y0: 0, x1: width, y1: height }
    }

    /// The smallest rectangle holding both (an empty one adds nothing).
    pub fn union(self, other: TexelRect) -> TexelRect {
        if self.is_empty() {
            return other;
        }
        if other.is_empty() {
            return self;
        }
        TexelRect {
            x0: self.x0.min(other.x0),
            y0: self.y0.min(other.y0),
            x1: self.x1.max(other.x1),
            y1: self.y1.max(other.y1),
        }
    }

    /// The part inside a `width` × `height` map.
    pub fn clamped(self, width: u32, height: u32) -> TexelRect {
        TexelRect { x0: self.x0.min(width), y0: self.y0.min(height), x1: self.x1.min(width), y1: self.y1.min(height) }
    }

    /// Whether it holds no texel.
    pub fn is_empty(&self) -> bool {
        self.x1 <= self.x0 || self.y1 <= self.y0
    }

    /// Columns it spans (0 when empty).
    pub fn width(&self) -> u32 {
        self.x1.saturating_sub(self.x0)
    }

    /// Rows it spans (0 when empty).
    pub fn height(&self) -> u32 {
        self.y1.saturating_sub(self.y0)
    }

    /// Number of texels it holds.
    pub fn area(&self) -> usize {
        if self.is_empty() { 0 } else { self.width() as usize * self.height() as usize }
    }

    /// Grows the rectangle to hold texel (x, y).
    pub fn include(&mut self, x: u32, y: u32) {
        *self = self.union(TexelRect { x0: x, y0: y, x1: x + 1, y1: y + 1 });
    }
}

impl Default for TexelRect {
    fn default() -> Self {
        TexelRect::EMPTY
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clamp_and_size() {
        let a = TexelRect::new(0, 3, 5, 12);
        assert_eq!((a.width(), a.height()), (5, 9));
        assert_eq!(a.clamped(4, 8), TexelRect::new(0, 3, 4, 8));
        assert_eq!(TexelRect::new(9, 0, 2, 1).width(), 0);
        assert!(TexelRect { x0: 5, y0: 0, x1: 9, y1: 9 }.clamped(4, 4).is_empty());
        let mut c = TexelRect::EMPTY;
        c.include(7, 1);
        assert_eq!(c, TexelRect { x0: 7, y0: 1, x1: 8, y1: 2 });
    }
}
