//! `rouge km ...`: Kubelka-Munk on single values.

use anyhow::{Result, bail};
use clap::Subcommand;
use rouge_measure::km::{self, LayerRt, Saunderson};
use serde_json::json;

// clap prints these doc comments as `--help` verbatim: citations stay `[Key]` (`\[Key\]` would show).
#[allow(rustdoc::broken_intra_doc_links)]
#[derive(Debug, Subcommand)]
pub enum KmCommand {
    /// S and K (per mm) from R∞, R over a background Rg, and the layer thickness ([Huang2013] eq. 6-7).
    Invert {
        /// Reflectance of an opaque layer, in (0, 1].
        #[arg(long = "r-inf", allow_negative_numbers = true)]
        r_inf: f64,
        /// Reflectance of the layer over the background, in [0, 1].
        #[arg(long, allow_negative_numbers = true)]
        r: f64,
        /// Reflectance of the background, in [0, 1].
        #[arg(long, allow_negative_numbers = true)]
        rg: f64,
        /// Thickness of the layer, mm.
        #[arg(long = "thickness-mm", allow_negative_numbers = true)]
        thickness_mm: f64,
        /// Convert the three measured reflectances to internal ones first ([Saunderson1942],
        /// K1 = ((n-1)/(n+1))², specular included), as `rouge import --saunderson-ior` does.
        #[arg(long = "saunderson-ior")]
        saunderson_ior: Option<f64>,
        /// Internal diffuse reflectance K2 of the Saunderson correction.
        #[arg(long = "saunderson-k2", default_value_t = 0.6, requires = "saunderson_ior")]
        saunderson_k2: f64,
    },
    /// R0 (over black) and T of a layer of S, K (per mm) and thickness ([Huang2013] eq. 1-2).
    Layer {
        /// Scattering coefficient, mm⁻¹.
        #[arg(long, allow_negative_numbers = true)]
        s: f64,
        /// Absorption coefficient, mm⁻¹.
        #[arg(long, allow_negative_numbers = true)]
        k: f64,
        /// Thickness, mm (`inf` for an opaque layer).
        #[arg(long = "thickness-mm", allow_negative_numbers = true)]
        thickness_mm: f64,
    },
    /// R and T of a stack of layers, top layer first ([Huang2013] eq. 3-4, corrected).
    Stack {
        /// Reflectances R0 of the layers, top first, comma-separated.
        #[arg(long, value_delimiter = ',', required = true, allow_negative_numbers = true)]
        r: Vec<f64>,
        /// Transmittances of the layers, top first, comma-separated.
        #[arg(long, value_delimiter = ',', required = true, allow_negative_numbers = true)]
        t: Vec<f64>,
    },
}

pub fn run(cmd: &KmCommand) -> Result<()> {
    let out = match *cmd {
        KmCommand::Invert { r_inf, r, rg, thickness_mm, saunderson_ior, saunderson_k2 } => {
            let to_internal = |v: f64| -> Result<f64> {
                Ok(match saunderson_ior {
                    None => v,
                    Some(n) => Saunderson::from_refractive_index(n, saunderson_k2, true)?.to_internal(v),
                })
            };
            let c = km::invert_s_k(to_internal(r_inf)?, to_internal(r)?, to_internal(rg)?, thickness_mm)?;
            json!({"s_per_mm": c.s_per_mm, "k_per_mm": c.k_per_mm})
        }
        KmCommand::Layer { s, k, thickness_mm } => {
            let l = km::layer_r_t(s, k, thickness_mm)?;
            json!({"r0": l.r, "t": l.t})
        }
        KmCommand::Stack { ref r, ref t } => {
            if r.len() != t.len() {
                bail!("--r has {} values but --t has {}: give R and T for every layer", r.len(), t.len());
            }
            let mut layers = Vec::with_capacity(r.len());
            for (i, (&r, &t)) in r.iter().zip(t).enumerate() {
                let layer = km::check_layer(LayerRt { r, t })
                    .map_err(|e| anyhow::anyhow!("layer {} (from the top): {e}", i + 1))?;
                layers.push(layer);
            }
            let s = km::stack(&layers);
            json!({"r": s.r, "t": s.t})
        }
    };
    crate::emit(&out.to_string())
}
