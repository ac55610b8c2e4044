//! A tinted brow gel on the eyebrow hairs: the products that colour the brows themselves (a
//! brow pencil or powder colours the skin under them: a layer on the `brows` region).
//!
//! A tinted gel coats each hair with a thin coloured film; where it covers, the hair shows the
//! film's colour. Rouge draws the brows' colour as one albedo ([`BrowGel::tint`]): the natural
//! hair's mixed with the gel's by its coverage `strength` (0 = untouched, 1 = every hair fully
//! coated). A fibre gel also fills the brows: its microfibres cling between the hairs, which the
//! renderer draws as `fill` × as many extra hairs again, each midway between a hair and its
//! nearest neighbour (so most where the hairs are far apart: the sparse parts). Clear gels and
//! the gel's hold (hairs brushed up) are not modelled. The app's Lashes and brows panel sets it
//! ([`crate::document::Document::set_brow_gel`], one undo step).

use serde::{Deserialize, Serialize};

use super::lashes::parse_color;
use crate::error::{ModelError, Result};

/// A tinted brow gel.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BrowGel {
    /// Linear albedo of the gel's film, each channel in 0..=1 (`black`, `brown` or `R/G/B` on the
    /// command line, as a mascara's).
    pub color: [f32; 3],
    /// The part of the hairs' surface the gel coats, 0..=1 (1 when left out).
    #[serde(default = "full")]
    pub strength: f32,
    /// Extra hairs, as a fraction of the brow's own, 0..=1 (0 when left out: a gel without
    /// fibres).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub fill: f32,
}

fn is_zero(v: &f32) -> bool {
    *v == 0.0
}

fn full() -> f32 {
    1.0
}

impl BrowGel {
    /// The brows' albedo over `natural` hair: the two mixed by the gel's strength.
    pub fn tint(&self, natural: [f32; 3]) -> [f32; 3] {
        std::array::from_fn(|c| natural[c] + (self.color[c] - natural[c]) * self.strength)
    }

    /// Checks the colour and the strength.
    ///
    /// # Errors
    /// [`ModelError::Invalid`] naming the field, its value and its range.
    pub fn validate(&self) -> Result<()> {
        if !self.color.iter().all(|v| v.is_finite() && (0.0..=1.0).contains(v)) {
            return Err(ModelError::Invalid(format!(
                "brow gel color {:?}: each channel must be within 0..=1 (linear albedo)",
                self.color
            )));
        }
        if !(self.strength.is_finite() && (0.0..=1.0).contains(&self.strength)) {
            return Err(ModelError::Invalid(format!("brow gel strength {}: must be within 0..=1", self.strength)));
        }
        if !(self.fill.is_finite() && (0.0..=1.0).contains(&self.fill)) {
            return Err(ModelError::Invalid(format!(
                "brow gel fill {}: must be within 0..=1 (extra hairs, a fraction of the brow's)",
                self.fill
            )));
        }
        Ok(())
    }

    /// Parses `color=brown,strength=0.8,fill=0.5` (`color` is required: a named shade or `R/G/B`).
    ///
    /// # Errors
    /// A missing colour, an unknown key, a number that does not parse, or a value out of range,
    /// named.
    pub fn parse(spec: &str) -> Result<BrowGel> {
        let (mut color, mut strength, mut fill) = (None, 1.0, 0.0);
        let number = |key: &str, v: &str| -> Result<f32> {
            v.trim().parse().map_err(|_| ModelError::Invalid(format!("brow gel {key}: `{}` is not a number", v.trim())))
        };
        for item in spec.split(',').map(str::trim).filter(|s| !s.is_empty()) {
            let (k, v) = item
                .split_once('=')
                .ok_or_else(|| ModelError::Invalid(format!("brow gel `{item}`: expected KEY=VALUE")))?;
            match k.trim() {
                "color" => color = Some(parse_color("brow gel", v.trim())?),
                "strength" => strength = number("strength", v)?,
                "fill" => fill = number("fill", v)?,
                other => {
                    return Err(ModelError::Invalid(format!(
                        "brow gel: unknown `{other}` (use color, strength, fill)"
                    )));
                }
            }
        }
        let color = color.ok_or_else(|| ModelError::Invalid("brow gel: give color=NAME or color=R/G/B".into()))?;
        let gel = BrowGel { color, strength, fill };
        gel.validate()?;
        Ok(gel)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_tints_and_refuses_what_is_out_of_range() {
        let gel = BrowGel::parse("color=black,strength=0.5").expect("gel");
        let natural = [0.055, 0.038, 0.027];
        let tinted = gel.tint(natural);
        for c in 0..3 {
            assert!((tinted[c] - 0.5 * (natural[c] + gel.color[c])).abs() < 1e-7);
        }
        assert_eq!(BrowGel::parse("color=0.1/0.05/0.02").expect("rgb").strength, 1.0);
        assert_eq!(BrowGel { color: [0.2; 3], strength: 0.0, fill: 0.0 }.tint(natural), natural);
        assert_eq!(BrowGel::parse("color=brown,fill=0.4").expect("fill").fill, 0.4);
        for (bad, says) in [
            ("strength=0.5", "give color"),
            ("color=green", "brow gel color `green`"),
            ("color=black,strength=1.5", "strength 1.5"),
            ("color=black,strength=nan", "strength NaN"),
            ("color=black,hold=2", "unknown `hold`"),
            ("color=black,fill=2", "fill 2"),
            ("color=black,fill=x", "fill: `x`"),
            ("color=2/0/0", "0..=1"),
        ] {
            let e = BrowGel::parse(bad).expect_err(bad).to_string();
            assert!(e.contains(says), "{bad}: {e}");
        }
    }
}
