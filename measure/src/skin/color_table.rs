//! The skin's colour over a face, fast: the linear sRGB (D65, CIE 1931) of the model's
//! reflectance tabulated over the five parameters that vary from place to place on a face
//! (melanin fraction, pheomelanin share, blood fraction, oxygen saturation, epidermis thickness),
//! for the scattering of one tone, and interpolated multilinearly in the logarithm of the colour. What a skin map needs per
//! texel: the exact model costs 17 µs a spectrum (docs/BENCHMARKS.md), a megatexel map 17 s; the
//! table is built once per tone (109,375 spectra, about 1 s on two cores) and read in a fraction
//! of a microsecond. Its error against the
//! exact model is measured by the test `the_table_matches_the_model` (measure/tests/skin_table.rs).
//!
//! Melanin is tabulated as its column f_mel·d (the epidermis' absorbance is proportional to it;
//! with f_mel and d on separate axes the table's error reached 5 ΔE2000 on deep skin with a thin
//! epidermis). The column and blood axes are spaced in their square root (nodes crowd where skin
//! lives: melanin 0.01-0.13 and blood 0.005-0.05 on the ten tones, the colour changing fastest
//! there), the others evenly. The epidermis axis runs from [`MIN_EPIDERMIS_MM`] to where the
//! tone's scattering lets the transport table reach ([`SkinParams::validate`]).

use super::{SkinError, SkinParams};
use crate::colorimetry::{Colorimeter, Viewing};

/// Nodes per axis: melanin column, pheomelanin share, blood, oxygen saturation, epidermis
/// thickness.
pub const NODES: [usize; 5] = [25, 5, 25, 5, 7];

/// The thinnest epidermis the table holds, mm: thinner reads as this (facial epidermis is
/// 0.04-0.1 mm; \[Jacques1998\]).
pub const MIN_EPIDERMIS_MM: f64 = 0.02;

/// Smallest linear sRGB value stored (the logarithm's floor; no skin comes near it).
const MIN_RGB: f64 = 1e-6;

/// First bytes of [`SkinColorTable::to_bytes`].
const BYTES_MAGIC: &[u8; 8] = b"ROUGE-ST";
/// Version of that layout: bump it when the layout changes (a change of the model is caught by
/// the probe nodes instead, [`SkinColorTable::from_bytes`]).
const BYTES_VERSION: u32 = 1;
/// Bytes before the nodes in [`SkinColorTable::to_bytes`]: magic, version, 12 f64, 5 u32.
const BYTES_HEADER: usize = 8 + 4 + 8 * 12 + 4 * 5;
/// Nodes [`SkinColorTable::from_bytes`] recomputes with the model (about 17 µs each).
const PROBE_NODES: usize = 8;

/// The table of one tone's scattering.
#[derive(Clone, Debug)]
pub struct SkinColorTable {
    /// The tone whose scattering (a, b) the table holds.
    pub base: SkinParams,
    /// Each axis's upper end (the lower is 0): the parameter's range, the epidermis's shortened
    /// to what the tone's scattering allows.
    max: [f64; 5],
    /// ln of the linear sRGB per node, the last axis fastest: absorbers attenuate light
    /// exponentially, so the logarithm is nearer linear in them than the colour is.
    rgb: Vec<[f32; 3]>,
}

/// The five varying parameters of `p` on the table's axes: the melanin column f_mel·d (mm: what
/// the epidermis' absorbance is proportional to, so that melanin and thickness do not interact
/// across a cell), the pheomelanin share, blood, oxygen saturation, the epidermis thickness d.
fn varying(p: &SkinParams) -> [f64; 5] {
    let d = p.epidermis_thickness_mm.max(MIN_EPIDERMIS_MM);
    [p.melanin_fraction * d, p.pheomelanin_share, p.blood_fraction, p.oxygen_saturation, d]
}

/// The lower end of axis `axis`.
const fn axis_min(axis: usize) -> f64 {
    if axis == 4 { MIN_EPIDERMIS_MM } else { 0.0 }
}

/// Whether axis `axis` is spaced in the square root of its value.
const fn square_root_axis(axis: usize) -> bool {
    axis == 0 || axis == 2
}

impl SkinColorTable {
    /// The table for `base`'s scattering, computed with the exact model at every node (109,375
    /// spectra, shared over the machine's cores).
    ///
    /// # Errors
    /// [`SkinError`] when `base` is outside the model's domain.
    pub fn new(base: &SkinParams) -> Result<SkinColorTable, SkinError> {
        base.validate()?;
        let ranges = SkinParams::RANGES;
        let mut max = [ranges[0].max * ranges[6].max, ranges[1].max, ranges[2].max, ranges[3].max, ranges[6].max];
        max[4] = max[4].min(base.max_epidermis_mm());
        let count: usize = NODES.iter().product();
        let colorimeter = Colorimeter::get(Viewing::D65_1931);
        let threads = std::thread::available_parallelism().map_or(1, |n| n.get()).clamp(1, 16);
        let chunk = count.div_ceil(threads);
        let mut rgb = vec![[0.0f32; 3]; count];
        std::thread::scope(|s| -> Result<(), SkinError> {
            let handles: Vec<_> = rgb
                .chunks_mut(chunk)
                .enumerate()
                .map(|(c, out)| {
                    s.spawn(move || -> Result<(), SkinError> {
                        for (j, slot) in out.iter_mut().enumerate() {
                            *slot = node_value(colorimeter, &node_params(base, &max, c * chunk + j))?;
                        }
                        Ok(())
                    })
                })
                .collect();
            for h in handles {
                // A panic in a worker is a bug: carry it on rather than hide it in an error.
                h.join().unwrap_or_else(|e| std::panic::resume_unwind(e))?;
            }
            Ok(())
        })?;
        Ok(SkinColorTable { base: *base, max, rgb })
    }

    /// The linear sRGB of `p`'s melanin, pheomelanin share, blood, oxygen saturation and
    /// epidermis thickness (its scattering is taken as the table's), each clamped to the table's
    /// axis; multilinear between nodes. Never NaN: a NaN parameter reads as 0.
    pub fn linear_srgb(&self, p: &SkinParams) -> [f32; 3] {
        let v = varying(p);
        // Per axis: the lower node and the weight of the upper one.
        let mut base = [0usize; 5];
        let mut frac = [0.0f64; 5];
        for axis in 0..5 {
            let x = ((v[axis] - axis_min(axis)) / (self.max[axis] - axis_min(axis))).clamp(0.0, 1.0);
            let x = if x.is_nan() { 0.0 } else { x };
            let t = if square_root_axis(axis) { x.sqrt() } else { x } * (NODES[axis] - 1) as f64;
            let k = (t.floor() as usize).min(NODES[axis] - 2);
            base[axis] = k;
            frac[axis] = t - k as f64;
        }
        let mut out = [0.0f64; 3];
        for corner in 0..32usize {
            let mut index = 0;
            let mut weight = 1.0;
            for axis in 0..5 {
                let up = (corner >> axis) & 1;
                index = index * NODES[axis] + base[axis] + up;
                weight *= if up == 1 { frac[axis] } else { 1.0 - frac[axis] };
            }
            if weight > 0.0 {
                for (o, c) in out.iter_mut().zip(self.rgb[index]) {
                    *o += weight * f64::from(c);
                }
            }
        }
        out.map(|c| c.exp() as f32)
    }

    /// The axes' upper ends, in the order melanin column (f_mel·d, mm), pheomelanin share, blood,
    /// oxygen saturation, epidermis thickness (mm).
    pub fn max(&self) -> [f64; 5] {
        self.max
    }

    /// The table as bytes, for a cache on disk (little-endian): magic, layout version u32, the
    /// base's seven parameters f64 ([`SkinParams::to_array`]), the axes' upper ends f64 × 5, the
    /// nodes per axis u32 × 5, then ln(linear sRGB) f32 × 3 per node. 1.3 MB.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(BYTES_HEADER + 12 * self.rgb.len());
        out.extend_from_slice(BYTES_MAGIC);
        out.extend_from_slice(&BYTES_VERSION.to_le_bytes());
        for v in self.base.to_array().iter().chain(&self.max) {
            out.extend_from_slice(&v.to_le_bytes());
        }
        for n in NODES {
            out.extend_from_slice(&(n as u32).to_le_bytes());
        }
        for v in self.rgb.iter().flatten() {
            out.extend_from_slice(&v.to_le_bytes());
        }
        debug_assert_eq!(out.len(), BYTES_HEADER + 12 * self.rgb.len());
        out
    }

    /// The table [`SkinColorTable::to_bytes`] wrote for `base`, or `None` unless the bytes are
    /// whole, of this layout, of `base` bit for bit, on the nodes [`SkinColorTable::new`] would
    /// use, finite, and their probe nodes (8, spread over the table) equal the model's values
    /// computed now bit for bit: a table written by another version of the skin model, or of the
    /// colorimetry, is refused rather than read.
    pub fn from_bytes(base: &SkinParams, bytes: &[u8]) -> Option<SkinColorTable> {
        let count: usize = NODES.iter().product();
        let header = BYTES_HEADER;
        if bytes.len() != header + 12 * count || &bytes[..8] != BYTES_MAGIC {
            return None;
        }
        let word = |at: usize| u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]);
        let float = |at: usize| f64::from_le_bytes(bytes[at..at + 8].try_into().unwrap_or([0xff; 8]));
        if word(8) != BYTES_VERSION {
            return None;
        }
        let stored: [f64; 12] = std::array::from_fn(|k| float(12 + 8 * k));
        let same_base = stored[..7].iter().zip(base.to_array()).all(|(a, b)| a.to_bits() == b.to_bits());
        if !same_base || (0..5).any(|k| word(12 + 96 + 4 * k) as usize != NODES[k]) {
            return None;
        }
        let max: [f64; 5] = std::array::from_fn(|k| stored[7 + k]);
        let single = |at: usize| f32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]);
        let rgb: Vec<[f32; 3]> = (0..count).map(|i| std::array::from_fn(|c| single(header + 12 * i + 4 * c))).collect();
        if !rgb.iter().flatten().all(|v| v.is_finite()) {
            return None;
        }
        let colorimeter = Colorimeter::get(Viewing::D65_1931);
        for k in 0..PROBE_NODES {
            let i = (k * count + count / 2) / PROBE_NODES;
            let fresh = node_value(colorimeter, &node_params(base, &max, i)).ok()?;
            if fresh.map(f32::to_bits) != rgb[i].map(f32::to_bits) {
                return None;
            }
        }
        Some(SkinColorTable { base: *base, max, rgb })
    }
}

/// The parameters at node `i` (the last axis fastest) of the table for `base` whose axes end
/// at `max`.
fn node_params(base: &SkinParams, max: &[f64; 5], i: usize) -> SkinParams {
    let mut rest = i;
    let mut v = [0.0; 5];
    for axis in (0..5).rev() {
        let k = rest % NODES[axis];
        rest /= NODES[axis];
        let t = k as f64 / (NODES[axis] - 1) as f64;
        v[axis] = axis_min(axis) + (max[axis] - axis_min(axis)) * if square_root_axis(axis) { t * t } else { t };
    }
    SkinParams {
        // A column no epidermis of this thickness can hold reads as the densest melanin.
        melanin_fraction: (v[0] / v[4]).min(SkinParams::RANGES[0].max),
        pheomelanin_share: v[1],
        blood_fraction: v[2],
        oxygen_saturation: v[3],
        epidermis_thickness_mm: v[4],
        ..*base
    }
}

/// What the table stores for `p`: ln of its linear sRGB, floored at [`MIN_RGB`].
fn node_value(colorimeter: &Colorimeter, p: &SkinParams) -> Result<[f32; 3], SkinError> {
    let r = p.reflectance()?;
    Ok(colorimeter.srgb_linear(&colorimeter.xyz(&r)).map(|v| v.max(MIN_RGB).ln() as f32))
}
