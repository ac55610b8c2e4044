//! The looks library: complete looks on the default head (data/looks/*.json, built-in presets
//! and region masks only, so they need no other file) with thumbnails Rouge rendered
//! (data/looks/thumbnails.sh), embedded in the binary. The app applies one in a click.

use anyhow::Result;
use rouge_model::look::Look;
use std::path::Path;

/// One look of the library.
#[derive(Clone, Copy, Debug)]
pub struct LibraryLook {
    /// The file stem in data/looks.
    pub id: &'static str,
    /// The look document.
    pub json: &'static str,
    /// Its thumbnail, a PNG rendered by `rouge render` (data/looks/thumbnails.sh).
    pub thumbnail_png: &'static [u8],
}

macro_rules! library_look {
    ($id:literal) => {
        LibraryLook {
            id: $id,
            json: include_str!(concat!("../../data/looks/", $id, ".json")),
            thumbnail_png: include_bytes!(concat!("../../data/looks/", $id, ".png")),
        }
    };
}

/// The library, lightest to boldest.
pub const LIBRARY: [LibraryLook; 4] =
    [library_look!("natural"), library_look!("evening"), library_look!("editorial"), library_look!("bold_lip")];

impl LibraryLook {
    /// The look, resolved (presets built in, maps from the default head's region masks).
    ///
    /// # Errors
    /// When the embedded document does not parse (named as data/looks/ID.json).
    pub fn look(&self) -> Result<Look> {
        let path = Path::new("data/looks").join(format!("{}.json", self.id));
        Ok(Look::from_json(self.json, &path)?)
    }
}
