//! Fills: the active layer set to a thickness inside a region mask, a UV island, or everywhere
//! the mesh covers, in one go (the document makes it one undo step).

use super::*;

/// Where [`fill`] puts thickness.
#[derive(Clone, Copy, Debug)]
pub enum FillRegion<'a> {
    /// A mask of weights in [0, 1] in the mesh's UVs (any size; resampled bilinearly to the
    /// map's, as looks resample masks), e.g. [`crate::look::Region::mask`]: each covered texel
    /// moves toward the thickness by its weight, so a soft mask edge gives a soft film edge.
    Mask(&'a ThicknessMap),
    /// The UV island under texel (x, y): every covered texel joined to it through covered UV
    /// neighbours (a face, an ear, the neck, whichever the island holds).
    Island {
        /// Texel column.
        x: u32,
        /// Texel row (row 0 at the top).
        y: u32,
    },
    /// Every covered texel (the whole head).
    Whole,
}

/// Sets the covered texels of `region` to `thickness_mm` (moved toward it by the mask's weight
/// for [`FillRegion::Mask`]) and returns the rectangle of texels whose value changed.
///
/// # Errors
/// A message naming the value when the thickness is outside [0, 10] mm or not finite, the map's
/// size differs from the surface map's, or the island's texel lies outside the map or is not
/// covered by the mesh.
pub fn fill(
    map: &mut ThicknessMap,
    surface: &SurfaceMap,
    region: FillRegion<'_>,
    thickness_mm: f32,
) -> Result<TexelRect, String> {
    if !(0.0..=MAX_THICKNESS_MM).contains(&thickness_mm) {
        return Err(format!("fill thickness {thickness_mm} mm is out of range: must be in [0, 10] mm"));
    }
    let (w, h) = (surface.width, surface.height);
    if (map.width, map.height) != (w, h) || map.mm.len() != surface.slot.len() {
        return Err(format!("fill: the layer's map is {}×{} but the surface map is {w}×{h}", map.width, map.height));
    }
    let mut dirty = TexelRect::EMPTY;
    let mut set = |i: usize, weight: f32, map: &mut ThicknessMap| {
        let old = map.mm[i];
        let t = if old.is_finite() { old } else { 0.0 };
        let new = if weight >= 1.0 { thickness_mm } else { t + (thickness_mm - t) * weight };
        if weight > 0.0 && new.to_bits() != old.to_bits() {
            map.mm[i] = new;
            dirty.include(i as u32 % w, i as u32 / w);
        }
    };
    match region {
        FillRegion::Whole => {
            for &i in &surface.texels {
                set(i as usize, 1.0, map);
            }
        }
        FillRegion::Mask(mask) => {
            let mask = mask.resized(w, h);
            for &i in &surface.texels {
                let m = mask.mm[i as usize];
                set(i as usize, if m.is_finite() { m.clamp(0.0, 1.0) } else { 0.0 }, map);
            }
        }
        FillRegion::Island { x, y } => {
            if x >= w || y >= h {
                return Err(format!("fill: texel ({x}, {y}) is outside the {w}×{h} map"));
            }
            let seed = (y * w + x) as usize;
            if surface.slot[seed] == UNCOVERED {
                return Err(format!("fill: texel ({x}, {y}) is not on the mesh (no UV island there)"));
            }
            let mut seen = vec![false; surface.slot.len()];
            let mut todo = vec![seed];
            seen[seed] = true;
            while let Some(i) = todo.pop() {
                set(i, 1.0, map);
                let (cx, cy) = ((i % w as usize) as i64, (i / w as usize) as i64);
                for (dx, dy) in [(-1, 0), (1, 0), (0, -1), (0, 1)] {
                    let (nx, ny) = (cx + dx, cy + dy);
                    if nx < 0 || ny < 0 || nx >= i64::from(w) || ny >= i64::from(h) {
                        continue;
                    }
                    let j = (ny * i64::from(w) + nx) as usize;
                    if !seen[j] && surface.slot[j] != UNCOVERED {
                        seen[j] = true;
                        todo.push(j);
                    }
                }
            }
        }
    }
    Ok(dirty)
}
