//! 3MF (3D Manufacturing Format, core specification): a zip archive whose
//! model part is XML. Read: the model part named by the package's
//! relationships, its objects (meshes, and components placing other
//! objects with transforms), the build items with their transforms, units
//! converted to millimetres; each build item becomes its own shells, every
//! triangle located by its XML path. Zip entries are inflated through a
//! guard, so a zip bomb is refused after at most the limit's bytes.
//! Written: one mesh object, coordinates as shortest round-trip decimals
//! (every `f64` bit kept), unit millimetre.

use std::fmt::Write as _;
use std::io::{BufReader, Cursor, Read, Write};
use std::path::Path;
use std::sync::Arc;

use glam::DVec3;

use super::import_error::{ImportError, excerpt};
use super::location::Location;
use super::parsed::Parsed;
use super::threemf_model::{Model, Shape, Transform, parse};
use crate::mesh::{FaceAttributes, Polygon};

/// How many times its compressed size a zip entry may inflate to: XML of
/// meshes compresses about 3 to 10 times; a zip bomb, up to a thousand.
pub(crate) const MAX_INFLATION: u64 = 100;

use super::parsed::MAX_PLACED_TRIANGLES as MAX_TRIANGLES;

/// How deep components may nest.
const MAX_COMPONENT_DEPTH: usize = 32;

/// The relationship type of the model part (3MF Core, 2013/01).
const MODEL_RELATIONSHIP: &str = "http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel";

/// A reader that refuses to give more than `left` bytes.
struct Guard<R> {
    inner: R,
    left: u64,
    tripped: bool,
}

impl<R: Read> Read for Guard<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        if n as u64 > self.left {
            self.tripped = true;
            return Err(std::io::Error::other("the entry inflates beyond its limit"));
        }
        self.left -= n as u64;
        Ok(n)
    }
}

type Archive<'a> = zip::ZipArchive<Cursor<&'a [u8]>>;

/// A guarded zip entry of an archive in memory.
type Entry<'a, 'b> = Guard<zip::read::ZipFile<'a, Cursor<&'b [u8]>>>;

/// The guarded reader of entry `name`, and its limit.
fn entry<'a, 'b>(
    path: &Path,
    archive: &'a mut Archive<'b>,
    name: &str,
) -> Result<(Entry<'a, 'b>, Inflation), ImportError> {
    let at = || Location::Path(name.to_string());
    let file = archive.by_name(name).map_err(|e| {
        ImportError::malformed(path, at(), format!("cannot open the zip entry: {e}"))
    })?;
    let limit = (file.compressed_size().saturating_mul(MAX_INFLATION))
        .saturating_add(1 << 20)
        .min(super::MAX_INPUT_BYTES as u64);
    let inflation = Inflation {
        compressed: file.compressed_size(),
        limit,
    };
    if file.size() > limit {
        return Err(inflation.refuse(
            path,
            name,
            &format!("declares {} bytes inflated", file.size()),
        ));
    }
    Ok((
        Guard {
            inner: file,
            left: limit,
            tripped: false,
        },
        inflation,
    ))
}

/// An entry's compressed size and the most it may inflate to.
#[derive(Clone, Copy)]
struct Inflation {
    compressed: u64,
    limit: u64,
}

impl Inflation {
    /// The refusal of an entry that `does` (declares or inflates to) too
    /// much.
    fn refuse(self, path: &Path, name: &str, does: &str) -> ImportError {
        ImportError::TooLarge {
            path: path.to_path_buf(),
            at: Location::Path(name.to_string()),
            what: format!(
                "a zip entry of {} compressed bytes that {does} (a zip bomb?)",
                self.compressed
            ),
            limit: self.limit,
        }
    }

    fn inflated_too_far(self, path: &Path, name: &str) -> ImportError {
        self.refuse(
            path,
            name,
            &format!("inflates to more than {} bytes", self.limit),
        )
    }
}

/// The model part's name, from `_rels/.rels` (or the usual name).
fn model_name(path: &Path, archive: &mut Archive<'_>) -> Result<String, ImportError> {
    let rels = "_rels/.rels";
    if archive.index_for_name(rels).is_none() {
        return Ok("3D/3dmodel.model".into());
    }
    let (mut guard, inflation) = entry(path, archive, rels)?;
    let mut text = Vec::new();
    if guard.read_to_end(&mut text).is_err() {
        return Err(if guard.tripped {
            inflation.inflated_too_far(path, rels)
        } else {
            ImportError::malformed(
                path,
                Location::Path(rels.into()),
                "cannot inflate the zip entry",
            )
        });
    }
    let mut reader = quick_xml::Reader::from_reader(text.as_slice());
    let mut buf = Vec::new();
    loop {
        match reader.read_event_into(&mut buf) {
            Ok(quick_xml::events::Event::Empty(e) | quick_xml::events::Event::Start(e))
                if e.local_name().as_ref() == "Relationship" =>
            {
                let get = |key: &str| {
                    e.attributes()
                        .flatten()
                        .find(|a| a.key.local_name().as_ref() == key)
                        .and_then(|a| {
                            a.normalized_value(quick_xml::XmlVersion::Implicit1_0)
                                .ok()
                                .map(|v| v.into_owned())
                        })
                };
                if get("Type").as_deref() == Some(MODEL_RELATIONSHIP)
                    && let Some(target) = get("Target")
                {
                    return Ok(target.trim_start_matches('/').to_string());
                }
            }
            Ok(quick_xml::events::Event::Eof) => break,
            Ok(_) => {}
            Err(e) => {
                return Err(ImportError::malformed(
                    path,
                    Location::Path(format!("{rels}: byte {}", reader.error_position())),
                    format!("not well-formed XML: {e}"),
                ));
            }
        }
        buf.clear();
    }
    Ok("3D/3dmodel.model".into())
}

/// Reads a 3MF file.
pub(crate) fn read(path: &Path, bytes: &[u8]) -> Result<Parsed, ImportError> {
    let mut archive = zip::ZipArchive::new(Cursor::new(bytes)).map_err(|e| {
        ImportError::malformed(
            path,
            Location::Byte(0),
            format!("not a 3MF file (a zip archive): {e}"),
        )
    })?;
    let name = model_name(path, &mut archive)?;
    if archive.index_for_name(&name).is_none() {
        return Err(ImportError::malformed(
            path,
            Location::Path(excerpt(name.as_bytes())),
            "the archive has no such model part",
        ));
    }
    let model = {
        let (guard, inflation) = entry(path, &mut archive, &name)?;
        let mut reader = BufReader::with_capacity(1 << 16, guard);
        let model = parse(&mut reader);
        if reader.get_ref().tripped {
            return Err(inflation.inflated_too_far(path, &name));
        }
        model.map_err(|e| {
            ImportError::malformed(path, Location::Path(format!("{name}: {}", e.at)), e.message)
        })?
    };
    assemble(path, &name, &model)
}

/// The build: each item's object placed with the item's transform (and its
/// components' transforms), in millimetres.
fn assemble(path: &Path, part: &str, model: &Model) -> Result<Parsed, ImportError> {
    let mut placer = Placer {
        path,
        part,
        model,
        parsed: Parsed::default(),
        placements: 0,
    };
    for (i, (id, transform)) in model.items.iter().enumerate() {
        let mut chain: Vec<Transform> = transform.iter().copied().collect();
        placer.place(id, &mut chain, i + 1, 0)?;
    }
    let mut parsed = placer.parsed;
    parsed.vertex_numbers = (0..parsed.positions.len()).collect();
    Ok(parsed)
}

/// `m` applied to the row vector `(p, 1)`.
fn apply(m: &Transform, p: DVec3) -> DVec3 {
    DVec3::new(
        p.x * m[0] + p.y * m[3] + p.z * m[6] + m[9],
        p.x * m[1] + p.y * m[4] + p.z * m[7] + m[10],
        p.x * m[2] + p.y * m[5] + p.z * m[8] + m[11],
    )
}

const IDENTITY: Transform = [1., 0., 0., 0., 1., 0., 0., 0., 1., 0., 0., 0.];

/// The state of placing the build's objects.
struct Placer<'a> {
    path: &'a Path,
    part: &'a str,
    model: &'a Model,
    parsed: Parsed,
    /// Objects placed so far (components of components multiply them).
    placements: usize,
}

impl Placer<'_> {
    fn at(&self, item: usize) -> Location {
        Location::Path(format!("{}: /model/build/item[{item}]", self.part))
    }

    /// Places object `id` under the transforms of `chain` (outermost first).
    fn place(
        &mut self,
        id: &str,
        chain: &mut Vec<Transform>,
        item: usize,
        depth: usize,
    ) -> Result<(), ImportError> {
        let path = self.path;
        let Some(object) = self.model.objects.get(id) else {
            return Err(ImportError::malformed(
                path,
                self.at(item),
                format!("no object with id `{}`", excerpt(id.as_bytes())),
            ));
        };
        if depth > MAX_COMPONENT_DEPTH {
            return Err(ImportError::malformed(
                path,
                self.at(item),
                format!(
                    "components nest deeper than {MAX_COMPONENT_DEPTH} levels (or an object contains itself), at object `{}`",
                    excerpt(id.as_bytes())
                ),
            ));
        }
        self.placements += 1;
        if self.placements > MAX_TRIANGLES || self.parsed.polygons.len() > MAX_TRIANGLES {
            return Err(ImportError::TooLarge {
                path: path.to_path_buf(),
                at: self.at(item),
                what: "the objects and triangles the build places".into(),
                limit: MAX_TRIANGLES as u64,
            });
        }
        match &object.shape {
            Shape::Components(components) => {
                for (child, transform) in components {
                    chain.push(transform.unwrap_or(IDENTITY));
                    self.place(child, chain, item, depth + 1)?;
                    chain.pop();
                }
            }
            Shape::Mesh {
                positions,
                triangles,
            } => {
                if self.parsed.polygons.len() + triangles.len() > MAX_TRIANGLES {
                    return Err(ImportError::TooLarge {
                        path: path.to_path_buf(),
                        at: self.at(item),
                        what: "the objects and triangles the build places".into(),
                        limit: MAX_TRIANGLES as u64,
                    });
                }
                let part = self.part;
                let parsed = &mut self.parsed;
                let base = parsed.positions.len();
                let first = parsed.polygons.len();
                let scale = self.model.millimetres;
                parsed.positions.extend(positions.iter().map(|&p| {
                    // Innermost transform first; identity and millimetres
                    // keep the bits.
                    let q = chain
                        .iter()
                        .rev()
                        .filter(|m| **m != IDENTITY)
                        .fold(p, |q, m| apply(m, q));
                    if scale == 1.0 { q } else { q * scale }
                }));
                let object_at = format!(
                    "{part}: /model/resources/object[@id='{}']",
                    excerpt(id.as_bytes())
                );
                if let Some(v) = parsed.positions[base..].iter().position(|p| !p.is_finite()) {
                    return Err(ImportError::NonFinite {
                        path: path.to_path_buf(),
                        at: Location::Path(format!(
                            "{object_at}/mesh/vertices/vertex[{}] (build item {item})",
                            v + 1
                        )),
                        vertex: v,
                        position: parsed.positions[base + v],
                    });
                }
                let group: Arc<str> = object
                    .name
                    .clone()
                    .unwrap_or_else(|| format!("object {id}"))
                    .into();
                parsed
                    .polygons
                    .extend(triangles.iter().enumerate().map(|(k, t)| Polygon {
                        vertices: t.iter().map(|&v| base + v).collect(),
                        attributes: FaceAttributes {
                            source_index: Some(first + k),
                            group: Some(Arc::clone(&group)),
                            ..FaceAttributes::default()
                        },
                    }));
                parsed.sources.push_path(
                    first,
                    format!("{object_at}/mesh/triangles/triangle["),
                    1,
                    format!("] (build item {item})"),
                );
            }
        }
        Ok(())
    }
}

/// A 3MF package of one mesh object: `triangles` of `positions`.
pub(crate) fn write(positions: &[DVec3], triangles: &[[usize; 3]]) -> std::io::Result<Vec<u8>> {
    let mut model = String::with_capacity(positions.len() * 64 + triangles.len() * 48);
    model.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<model unit=\"millimeter\" xml:lang=\"en-US\" xmlns=\"http://schemas.microsoft.com/3dmanufacturing/core/2015/02\">\n <metadata name=\"Application\">wingedge</metadata>\n <resources>\n  <object id=\"1\" type=\"model\">\n   <mesh>\n    <vertices>\n");
    for p in positions {
        let _ = writeln!(
            model,
            "     <vertex x=\"{:?}\" y=\"{:?}\" z=\"{:?}\"/>",
            p.x, p.y, p.z
        );
    }
    model.push_str("    </vertices>\n    <triangles>\n");
    for t in triangles {
        let _ = writeln!(
            model,
            "     <triangle v1=\"{}\" v2=\"{}\" v3=\"{}\"/>",
            t[0], t[1], t[2]
        );
    }
    model.push_str("    </triangles>\n   </mesh>\n  </object>\n </resources>\n <build>\n  <item objectid=\"1\"/>\n </build>\n</model>\n");
    let mut zip = zip::ZipWriter::new(Cursor::new(Vec::new()));
    let options = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated);
    let parts: [(&str, &[u8]); 3] = [
        ("[Content_Types].xml", b"<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<Types xmlns=\"http://schemas.openxmlformats.org/package/2006/content-types\"><Default Extension=\"rels\" ContentType=\"application/vnd.openxmlformats-package.relationships+xml\"/><Default Extension=\"model\" ContentType=\"application/vnd.ms-package.3dmanufacturing-3dmodel+xml\"/></Types>\n"),
        ("_rels/.rels", b"<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<Relationships xmlns=\"http://schemas.openxmlformats.org/package/2006/relationships\"><Relationship Target=\"/3D/3dmodel.model\" Id=\"rel0\" Type=\"http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel\"/></Relationships>\n"),
        ("3D/3dmodel.model", model.as_bytes()),
    ];
    for (name, content) in parts {
        zip.start_file(name, options)
            .map_err(std::io::Error::other)?;
        zip.write_all(content)?;
    }
    Ok(zip.finish().map_err(std::io::Error::other)?.into_inner())
}
