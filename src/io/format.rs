//! The mesh file formats: which one a path names, and what each keeps.

use std::fmt;
use std::path::Path;
use std::str::FromStr;

/// A mesh file format that wingedge reads and writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Format {
    /// Wavefront OBJ (text; polygons, `f64` kept by shortest decimals).
    Obj,
    /// STL, binary or ASCII (triangles; binary holds `f32`).
    Stl,
    /// Stanford PLY, ASCII or binary of either byte order (polygons;
    /// written as binary little-endian `double`).
    Ply,
    /// Object File Format (text; polygons).
    Off,
    /// 3D Manufacturing Format: a zip of XML parts (triangles; text
    /// numbers, so `f64` is kept).
    ThreeMf,
    /// glTF 2.0 as JSON (`.gltf`; triangles, `f32` positions).
    Gltf,
    /// glTF 2.0 as one binary file (`.glb`; triangles, `f32` positions).
    Glb,
}

impl Format {
    /// Every format, in the order documentation lists them.
    pub const ALL: [Format; 7] = [
        Format::Obj,
        Format::Stl,
        Format::Ply,
        Format::Off,
        Format::ThreeMf,
        Format::Gltf,
        Format::Glb,
    ];

    /// The format's name as `--format` takes it (also its usual
    /// extension): `obj`, `stl`, `ply`, `off`, `3mf`, `gltf`, `glb`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Format::Obj => "obj",
            Format::Stl => "stl",
            Format::Ply => "ply",
            Format::Off => "off",
            Format::ThreeMf => "3mf",
            Format::Gltf => "gltf",
            Format::Glb => "glb",
        }
    }

    /// The format a path's extension names (any case), if any.
    #[must_use]
    pub fn from_path(path: &Path) -> Option<Format> {
        let extension = path.extension()?.to_str()?;
        Format::ALL
            .into_iter()
            .find(|f| f.name().eq_ignore_ascii_case(extension))
    }

    /// The format of `path` for reading: named by its extension, else OBJ
    /// (so that a file named anything else reads as it always did).
    #[must_use]
    pub fn of_input(path: &Path) -> Format {
        Format::from_path(path).unwrap_or(Format::Obj)
    }

    /// Whether the format stores every `f64` coordinate exactly as written
    /// (OBJ, PLY `double`, OFF and 3MF text with shortest round-trip
    /// decimals); STL and glTF hold `f32`, so writing them rounds.
    #[must_use]
    pub fn keeps_f64(self) -> bool {
        !matches!(self, Format::Stl | Format::Gltf | Format::Glb)
    }

    /// Whether the format holds only triangles (polygons are triangulated
    /// when written).
    #[must_use]
    pub fn triangles_only(self) -> bool {
        matches!(
            self,
            Format::Stl | Format::ThreeMf | Format::Gltf | Format::Glb
        )
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A format name that is none of [`Format::ALL`].
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown format `{0}` (expected one of obj, stl, ply, off, 3mf, gltf, glb)")]
pub struct UnknownFormat(pub String);

impl FromStr for Format {
    type Err = UnknownFormat;

    fn from_str(s: &str) -> Result<Format, UnknownFormat> {
        let name = s.trim_start_matches('.');
        Format::ALL
            .into_iter()
            .find(|f| f.name().eq_ignore_ascii_case(name))
            .ok_or_else(|| UnknownFormat(s.chars().take(32).collect()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extensions_and_names_pick_the_format() {
        assert_eq!(Format::from_path(Path::new("a/b.STL")), Some(Format::Stl));
        assert_eq!(Format::from_path(Path::new("b.3mf")), Some(Format::ThreeMf));
        assert_eq!(Format::from_path(Path::new("b.txt")), None);
        assert_eq!(Format::of_input(Path::new("b")), Format::Obj);
        assert_eq!("GLB".parse::<Format>(), Ok(Format::Glb));
        assert_eq!(".ply".parse::<Format>(), Ok(Format::Ply));
        assert!("stp".parse::<Format>().is_err());
        for f in Format::ALL {
            assert_eq!(f.name().parse::<Format>(), Ok(f));
        }
    }
}
