//! # rouge-measure
//!
//! The spectral core of Rouge: spectra on the 380-780 nm working grid, measurement import,
//! numerically stable Kubelka-Munk inversion and forward model, CIE colorimetry that matches
//! colour-science, and material presets. No GPU, no UI.
//!
//! The physics follows Huang et al., *Physically-based Cosmetic Rendering* (\[Huang2013\] in
//! docs/REFERENCES.md), sections 3.1 and 4; every function documents its equation, the corrections
//! made to the printed forms, and its domain.

#[macro_use]
pub mod simd;

pub mod analysis;
pub mod colorimetry;
pub mod compositing;
pub mod error;
pub mod file_set;
pub mod finish;
pub mod import;
pub mod km;
pub mod km_batch;
pub mod km_uncertainty;
pub mod layer_table;
pub mod preset;
pub mod skin;
pub mod spectrum;
pub mod specular;
pub mod thin_film;

pub use colorimetry::{Colorimeter, Illuminant, Lab, Observer, Viewing, Xyz, delta_e_2000};
pub use error::LocatedError;
pub use import::{ImportOptions, Kind, Measurement, read_measurement};
pub use km::{KmCoefficients, KmError, LayerRt, Saunderson};
pub use preset::{Preset, PresetError};
pub use spectrum::{Extrapolation, SampledSpectrum, Spectrum};
