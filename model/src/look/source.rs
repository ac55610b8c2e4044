//! Thickness sources: the "thickness" object of a look layer (uniform, region, mask, map).

use super::*;

// ------------------------------------------------------------------------------------------
// Thickness sources: the "thickness" object

/// Where a layer's thickness comes from: the `"thickness"` object of a look layer. Paths are
/// kept as written (relative to the look file unless absolute).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "ThicknessJson", into = "ThicknessJson")]
pub enum ThicknessSource {
    /// `{"uniform_mm": t}`: `t` mm everywhere.
    Uniform {
        /// Thickness, mm.
        mm: f32,
    },
    /// `{"region": "cheeks", "thickness_mm": t}`: a built-in mask of the default head × `t`.
    Region {
        /// The region.
        region: Region,
        /// Thickness where the mask is 1, mm.
        mm: f32,
    },
    /// `{"mask": "m.png", "thickness_mm": t}`: a PNG mask (first channel, value / max) × `t`.
    Mask {
        /// The PNG, as written.
        path: PathBuf,
        /// Thickness where the mask is at its maximum, mm.
        mm: f32,
    },
    /// `{"map": "m.exr"}` or `{"map": "m.png", "scale_mm": s}`: an OpenEXR map in mm (times `s`
    /// if given), or a PNG map, value / max × `s` (`s` required).
    Map {
        /// The EXR or PNG file, as written.
        path: PathBuf,
        /// Scale, mm: required for PNG, optional for EXR.
        scale_mm: Option<f32>,
    },
}

/// The JSON shape of [`ThicknessSource`]: one of four keys plus its companion.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ThicknessJson {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    uniform_mm: Option<f32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    region: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    mask: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    map: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    thickness_mm: Option<f32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    scale_mm: Option<f32>,
}

impl TryFrom<ThicknessJson> for ThicknessSource {
    type Error = String;

    fn try_from(j: ThicknessJson) -> std::result::Result<Self, String> {
        let kinds: Vec<&str> = [
            ("uniform_mm", j.uniform_mm.is_some()),
            ("region", j.region.is_some()),
            ("mask", j.mask.is_some()),
            ("map", j.map.is_some()),
        ]
        .into_iter()
        .filter_map(|(k, present)| present.then_some(k))
        .collect();
        let one_of = "give exactly one of `uniform_mm`, `region`, `mask` or `map`";
        match kinds.as_slice() {
            [] => return Err(format!("thickness: {one_of}")),
            [_] => {}
            [a, b, ..] => return Err(format!("thickness: has both `{a}` and `{b}`: {one_of}")),
        }
        let no = |field: &str, present: bool, with: &str| {
            if present { Err(format!("thickness: `{field}` does not go with `{with}`")) } else { Ok(()) }
        };
        let path = |field: &str, p: String| {
            if p.trim().is_empty() { Err(format!("thickness: `{field}` is empty")) } else { Ok(PathBuf::from(p)) }
        };
        let with_thickness = |field: &str| {
            j.thickness_mm
                .ok_or_else(|| format!("thickness: `{field}` needs `thickness_mm`"))
                .and_then(|t| check_field("thickness_mm", t).map_err(|e| format!("thickness: {e}")))
        };
        let checked = |field: &str, v: f32| check_field(field, v).map_err(|e| format!("thickness: {e}"));
        if let Some(mm) = j.uniform_mm {
            no("thickness_mm", j.thickness_mm.is_some(), "uniform_mm")?;
            no("scale_mm", j.scale_mm.is_some(), "uniform_mm")?;
            return Ok(ThicknessSource::Uniform { mm: checked("uniform_mm", mm)? });
        }
        if let Some(name) = j.region {
            no("scale_mm", j.scale_mm.is_some(), "region")?;
            let region = Region::parse(&name).ok_or_else(|| {
                format!("thickness: unknown region {name:?} (regions: lips, cheeks, eyelids, tzone, brows)")
            })?;
            return Ok(ThicknessSource::Region { region, mm: with_thickness("region")? });
        }
        if let Some(p) = j.mask {
            no("scale_mm", j.scale_mm.is_some(), "mask")?;
            return Ok(ThicknessSource::Mask { path: path("mask", p)?, mm: with_thickness("mask")? });
        }
        if let Some(p) = j.map {
            no("thickness_mm", j.thickness_mm.is_some(), "map (a map uses `scale_mm`)")?;
            let scale_mm = j.scale_mm.map(|s| checked("scale_mm", s)).transpose()?;
            return Ok(ThicknessSource::Map { path: path("map", p)?, scale_mm });
        }
        Err(format!("thickness: {one_of}"))
    }
}

impl From<ThicknessSource> for ThicknessJson {
    fn from(s: ThicknessSource) -> Self {
        let text = |p: PathBuf| Some(p.to_string_lossy().into_owned());
        match s {
            ThicknessSource::Uniform { mm } => ThicknessJson { uniform_mm: Some(mm), ..Default::default() },
            ThicknessSource::Region { region, mm } => {
                ThicknessJson { region: Some(region.name().into()), thickness_mm: Some(mm), ..Default::default() }
            }
            ThicknessSource::Mask { path, mm } => {
                ThicknessJson { mask: text(path), thickness_mm: Some(mm), ..Default::default() }
            }
            ThicknessSource::Map { path, scale_mm } => {
                ThicknessJson { map: text(path), scale_mm, ..Default::default() }
            }
        }
    }
}

impl ThicknessSource {
    /// Resolves the source into a thickness map, reading mask and map files relative to
    /// `base_dir` (the look file's folder). Checks every pixel.
    pub fn load_map(&self, base_dir: &Path) -> Result<ThicknessMap> {
        self.resolve(base_dir).map_err(ModelError::Invalid)
    }

    pub(super) fn resolve(&self, base_dir: &Path) -> std::result::Result<ThicknessMap, String> {
        let read = |what: &str, p: &Path| {
            let full = resolve_path(base_dir, p);
            read_map_file(&full)
                .map_err(|e| format!("{what} {:?}: cannot read {}: {e}", p.display().to_string(), full.display()))
        };
        match self {
            ThicknessSource::Uniform { mm } => {
                check_field("uniform_mm", *mm)?;
                Ok(ThicknessMap::uniform(*mm))
            }
            ThicknessSource::Region { region, mm } => {
                check_field("thickness_mm", *mm)?;
                Ok(region.mask().scaled(*mm))
            }
            ThicknessSource::Mask { path, mm } => {
                check_field("thickness_mm", *mm)?;
                let what = format!("thickness mask {:?}", path.display().to_string());
                let bytes = read("thickness mask", path)?;
                let map = decode_png_unit(&bytes).map_err(|e| {
                    let hint = if bytes.starts_with(EXR_MAGIC) { "; use `map` for OpenEXR thickness maps" } else { "" };
                    format!("{what}: {e}{hint}")
                })?;
                Ok(map.scaled(*mm))
            }
            ThicknessSource::Map { path, scale_mm } => {
                let what = format!("thickness map {:?}", path.display().to_string());
                if let Some(s) = scale_mm {
                    check_field("scale_mm", *s)?;
                }
                let bytes = read("thickness map", path)?;
                if bytes.starts_with(EXR_MAGIC) {
                    let (map, channel) = decode_exr(&bytes).map_err(|e| format!("{what}: {e}"))?;
                    let (map, after) = match scale_mm {
                        Some(s) => (map.scaled(*s), " × `scale_mm`"),
                        None => (map, ""),
                    };
                    check_map(&map, &format!(" of channel {channel:?}{after}")).map_err(|e| format!("{what}: {e}"))?;
                    Ok(map)
                } else if bytes.starts_with(PNG_SIGNATURE) {
                    let s = scale_mm.ok_or_else(|| {
                        format!("{what}: a PNG map needs `scale_mm` (its values run 0..max, not millimetres)")
                    })?;
                    let map = decode_png_unit(&bytes).map_err(|e| format!("{what}: {e}"))?;
                    Ok(map.scaled(s))
                } else {
                    Err(format!("{what}: neither an OpenEXR nor a PNG file ({})", describe_start(&bytes)))
                }
            }
        }
    }
}
