//! glTF 2.0, as JSON (`.gltf`) or binary (`.glb`). Read: the default
//! scene's nodes with their transforms (a matrix, or translation, rotation
//! and scale), each mesh primitive of triangles (also strips and fans;
//! points and lines are skipped with a note), indexed or not; each placed
//! primitive its own vertices, every triangle located by its JSON path.
//! Written: one mesh of `f32` positions and `u32` indices, its buffer in a
//! `data:` URI (`.gltf`) or the binary chunk (`.glb`).

use std::borrow::Cow;
use std::path::Path;
use std::sync::Arc;

use base64::Engine as _;
use glam::{DMat4, DQuat, DVec3};
use serde_json::{Value, json};

use super::gltf_buffers::{Elements, accessor, buffer, refuse, split_glb, uint};
use super::import_error::ImportError;
use super::location::Location;
use super::parsed::{MAX_PLACED_TRIANGLES, Parsed};
use crate::mesh::{FaceAttributes, Polygon};

/// The GLB magic, `glTF`.
const MAGIC: &[u8; 4] = b"glTF";

/// Reads a glTF document, JSON or GLB (told apart by the GLB magic).
pub(crate) fn read(path: &Path, bytes: &[u8]) -> Result<Parsed, ImportError> {
    let (json, bin) = if bytes.starts_with(MAGIC) {
        split_glb(path, bytes)?
    } else {
        (bytes, None)
    };
    let doc: Value = serde_json::from_slice(json).map_err(|e| {
        let message = if e.to_string().starts_with("recursion limit exceeded") {
            format!(
                "nested deeper than {} levels (the limit)",
                super::json_value::MAX_JSON_DEPTH
            )
        } else {
            e.to_string()
        };
        refuse(
            path,
            format!("JSON line {}, column {}", e.line(), e.column()),
            format!("not valid JSON: {message}"),
        )
    })?;
    if !doc.is_object() {
        return Err(refuse(path, "(root)", "not a JSON object"));
    }
    let buffer_count = doc
        .get("buffers")
        .and_then(Value::as_array)
        .map_or(0, Vec::len);
    let buffers: Vec<Cow<'_, [u8]>> = (0..buffer_count)
        .map(|i| buffer(path, &doc, i, bin))
        .collect::<Result<_, _>>()?;
    let mut reader = Reader {
        path,
        doc: &doc,
        buffers: &buffers,
        parsed: Parsed::default(),
        visited: vec![
            false;
            doc.get("nodes")
                .and_then(Value::as_array)
                .map_or(0, Vec::len)
        ],
        skipped: 0,
    };
    let has_nodes = doc
        .get("nodes")
        .and_then(Value::as_array)
        .is_some_and(|n| !n.is_empty());
    if has_nodes {
        for (node, at) in reader.roots()? {
            reader.node(node, &at, DMat4::IDENTITY)?;
        }
    } else {
        // No nodes: every mesh as it is.
        let meshes = doc
            .get("meshes")
            .and_then(Value::as_array)
            .map_or(0, Vec::len);
        for m in 0..meshes {
            reader.mesh(m, "(no node)", DMat4::IDENTITY)?;
        }
    }
    if reader.skipped > 0 {
        let note = format!("{} primitives of points or lines skipped", reader.skipped);
        reader.parsed.notes.push(note);
    }
    let mut parsed = reader.parsed;
    parsed.vertex_numbers = (0..parsed.positions.len()).collect();
    Ok(parsed)
}

/// The state of walking a document's nodes.
struct Reader<'a> {
    path: &'a Path,
    doc: &'a Value,
    buffers: &'a [Cow<'a, [u8]>],
    parsed: Parsed,
    visited: Vec<bool>,
    skipped: usize,
}

impl Reader<'_> {
    /// The root nodes with their JSON paths: the default scene's (or the
    /// first scene's), else every node no other node lists as a child.
    fn roots(&self) -> Result<Vec<(usize, String)>, ImportError> {
        let scenes = self.doc.get("scenes").and_then(Value::as_array);
        if let Some(scenes) = scenes.filter(|s| !s.is_empty()) {
            let index = uint(self.path, self.doc, "scene", "")?.unwrap_or(0) as usize;
            let scene = scenes
                .get(index)
                .ok_or_else(|| refuse(self.path, "scene", format!("no such scene: {index}")))?;
            let nodes = scene
                .get("nodes")
                .and_then(Value::as_array)
                .cloned()
                .unwrap_or_default();
            return nodes
                .iter()
                .enumerate()
                .map(|(i, n)| {
                    let at = format!("scenes[{index}].nodes[{i}]");
                    n.as_u64()
                        .map(|n| (n as usize, at.clone()))
                        .ok_or_else(|| refuse(self.path, at, "not a node index"))
                })
                .collect();
        }
        let nodes = self
            .doc
            .get("nodes")
            .and_then(Value::as_array)
            .cloned()
            .unwrap_or_default();
        let mut child = vec![false; nodes.len()];
        for n in &nodes {
            for c in n
                .get("children")
                .and_then(Value::as_array)
                .into_iter()
                .flatten()
            {
                if let Some(c) = c.as_u64().and_then(|c| child.get_mut(c as usize)) {
                    *c = true;
                }
            }
        }
        Ok((0..nodes.len())
            .filter(|&i| !child[i])
            .map(|i| (i, format!("nodes[{i}]")))
            .collect())
    }

    /// Node `index` under the world transform `parent`.
    fn node(&mut self, index: usize, at: &str, parent: DMat4) -> Result<(), ImportError> {
        let path = self.path;
        let here = format!("nodes[{index}]");
        let node = self
            .doc
            .get("nodes")
            .and_then(|n| n.get(index))
            .ok_or_else(|| refuse(path, at, format!("no such node: {index}")))?;
        if std::mem::replace(&mut self.visited[index], true) {
            return Err(refuse(
                path,
                at,
                format!("{here} is reached twice (a cycle, or a node with two parents)"),
            ));
        }
        let world = parent * transform(path, node, &here)?;
        if let Some(mesh) = uint(path, node, "mesh", &here)? {
            self.mesh(mesh as usize, &here, world)?;
        }
        for (i, child) in node
            .get("children")
            .and_then(Value::as_array)
            .into_iter()
            .flatten()
            .enumerate()
        {
            let child_at = format!("{here}.children[{i}]");
            let child = child
                .as_u64()
                .ok_or_else(|| refuse(path, &child_at, "not a node index"))?;
            self.node(child as usize, &child_at, world)?;
        }
        Ok(())
    }

    /// Every primitive of mesh `index`, placed by `node` with `world`.
    fn mesh(&mut self, index: usize, node: &str, world: DMat4) -> Result<(), ImportError> {
        let path = self.path;
        let here = format!("meshes[{index}]");
        let mesh = self
            .doc
            .get("meshes")
            .and_then(|m| m.get(index))
            .ok_or_else(|| {
                refuse(
                    path,
                    format!("{node}.mesh"),
                    format!("no such mesh: {index}"),
                )
            })?;
        let group: Arc<str> = mesh
            .get("name")
            .and_then(Value::as_str)
            .map_or_else(|| here.clone(), str::to_string)
            .into();
        for (p, primitive) in mesh
            .get("primitives")
            .and_then(Value::as_array)
            .into_iter()
            .flatten()
            .enumerate()
        {
            let at = format!("{here}.primitives[{p}]");
            let mode = uint(path, primitive, "mode", &at)?.unwrap_or(4);
            if mode < 4 {
                self.skipped += 1;
                continue;
            }
            if mode > 6 {
                return Err(refuse(
                    path,
                    format!("{at}.mode"),
                    format!("unknown mode {mode}"),
                ));
            }
            let position = primitive
                .get("attributes")
                .and_then(|a| uint(path, a, "POSITION", &format!("{at}.attributes")).transpose())
                .transpose()?
                .ok_or_else(|| refuse(path, format!("{at}.attributes"), "no POSITION"))?;
            let positions = accessor(path, self.doc, position as usize, "VEC3", self.buffers)?;
            let indices = uint(path, primitive, "indices", &at)?
                .map(|i| {
                    accessor(path, self.doc, i as usize, "SCALAR", self.buffers).map(|e| (i, e))
                })
                .transpose()?;
            let corners = indices.as_ref().map_or(positions.count, |(_, e)| e.count);
            let source = match &indices {
                Some((i, _)) => format!("accessors[{i}]"),
                None => format!("accessors[{position}]"),
            };
            self.primitive(
                &at,
                &source,
                node,
                world,
                &positions,
                indices.as_ref().map(|(_, e)| e),
                corners,
                mode,
                &group,
            )?;
        }
        Ok(())
    }

    /// One placed primitive: its positions moved by `world`, its triangles.
    #[allow(clippy::too_many_arguments)]
    fn primitive(
        &mut self,
        at: &str,
        source: &str,
        node: &str,
        world: DMat4,
        positions: &Elements<'_>,
        indices: Option<&Elements<'_>>,
        corners: usize,
        mode: u64,
        group: &Arc<str>,
    ) -> Result<(), ImportError> {
        let path = self.path;
        let parsed = &mut self.parsed;
        let base = parsed.positions.len();
        let identity = world == DMat4::IDENTITY;
        for k in 0..positions.count {
            let p = DVec3::from_array(positions.vec3(k).map(f64::from));
            let p = if identity {
                p
            } else {
                world.transform_point3(p)
            };
            if !p.is_finite() {
                return Err(ImportError::NonFinite {
                    path: path.to_path_buf(),
                    at: Location::Path(format!(
                        "{at}.attributes.POSITION ({source}), element {k}, placed by {node}"
                    )),
                    vertex: k,
                    position: p,
                });
            }
            parsed.positions.push(p);
        }
        let corner = |k: usize| -> Result<usize, ImportError> {
            let Some(e) = indices else { return Ok(k) };
            let i = e.index(k);
            if i >= positions.count as u64 {
                return Err(ImportError::IndexOutOfRange {
                    path: path.to_path_buf(),
                    at: Location::Path(format!("{at}.indices ({source}), element {k}")),
                    index: i as i64,
                    available: positions.count,
                });
            }
            Ok(i as usize)
        };
        let triangles = match mode {
            4 if !corners.is_multiple_of(3) => {
                return Err(refuse(
                    path,
                    at,
                    format!("{corners} corners of triangles: not a multiple of 3"),
                ));
            }
            4 => corners / 3,
            _ => corners.saturating_sub(2),
        };
        if parsed.polygons.len() + triangles > MAX_PLACED_TRIANGLES {
            return Err(ImportError::TooLarge {
                path: path.to_path_buf(),
                at: Location::Path(format!("{at}, placed by {node}")),
                what: "the triangles the scene places".into(),
                limit: MAX_PLACED_TRIANGLES as u64,
            });
        }
        let first = parsed.polygons.len();
        for t in 0..triangles {
            let [a, b, c] = match mode {
                4 => [3 * t, 3 * t + 1, 3 * t + 2],
                5 if t % 2 == 0 => [t, t + 1, t + 2],
                5 => [t + 1, t, t + 2],
                _ => [0, t + 1, t + 2],
            };
            let vertices = [corner(a)?, corner(b)?, corner(c)?];
            // Strips and fans repeat a corner to restart: no triangle there.
            if mode != 4
                && (vertices[0] == vertices[1]
                    || vertices[1] == vertices[2]
                    || vertices[0] == vertices[2])
            {
                continue;
            }
            let number = parsed.polygons.len();
            parsed.polygons.push(Polygon {
                vertices: vertices.iter().map(|&v| base + v).collect(),
                attributes: FaceAttributes {
                    source_index: Some(number),
                    group: Some(Arc::clone(group)),
                    ..FaceAttributes::default()
                },
            });
        }
        parsed.sources.push_path(
            first,
            format!("{at} triangle "),
            0,
            format!(" ({source}, placed by {node})"),
        );
        Ok(())
    }
}

/// A node's local transform: `matrix` (column-major), or translation,
/// rotation (a quaternion `x y z w`) and scale.
fn transform(path: &Path, node: &Value, at: &str) -> Result<DMat4, ImportError> {
    let numbers = |key: &str, n: usize| -> Result<Option<Vec<f64>>, ImportError> {
        let Some(v) = node.get(key) else {
            return Ok(None);
        };
        let values: Option<Vec<f64>> = v
            .as_array()
            .map(|a| a.iter().filter_map(Value::as_f64).collect());
        match values {
            Some(values)
                if values.len() == n
                    && v.as_array().is_some_and(|a| a.len() == n)
                    && values.iter().all(|x| x.is_finite()) =>
            {
                Ok(Some(values))
            }
            _ => Err(refuse(
                path,
                format!("{at}.{key}"),
                format!("expected {n} finite numbers"),
            )),
        }
    };
    if let Some(m) = numbers("matrix", 16)? {
        return Ok(DMat4::from_cols_slice(&m));
    }
    let t = numbers("translation", 3)?.map_or(DVec3::ZERO, |v| DVec3::from_slice(&v));
    let r = numbers("rotation", 4)?.map_or(DQuat::IDENTITY, |v| DQuat::from_slice(&v));
    let s = numbers("scale", 3)?.map_or(DVec3::ONE, |v| DVec3::from_slice(&v));
    if t == DVec3::ZERO && r == DQuat::IDENTITY && s == DVec3::ONE {
        return Ok(DMat4::IDENTITY);
    }
    Ok(DMat4::from_scale_rotation_translation(s, r.normalize(), t))
}

/// The document of one mesh: `triangles` of `positions` (already `f32`),
/// its buffer as given by `uri` (`None`: the GLB binary chunk).
fn document(
    positions: &[[f32; 3]],
    triangles: &[[usize; 3]],
    uri: Option<String>,
) -> (Value, Vec<u8>) {
    let mut data = Vec::with_capacity(triangles.len() * 12 + positions.len() * 12);
    for t in triangles {
        for &v in t {
            data.extend_from_slice(&(v as u32).to_le_bytes());
        }
    }
    let index_bytes = data.len();
    let mut min = [f32::INFINITY; 3];
    let mut max = [f32::NEG_INFINITY; 3];
    for p in positions {
        for k in 0..3 {
            min[k] = min[k].min(p[k]);
            max[k] = max[k].max(p[k]);
            data.extend_from_slice(&p[k].to_le_bytes());
        }
    }
    let mut buffer = json!({"byteLength": data.len()});
    if let Some(uri) = uri {
        buffer["uri"] = Value::String(format!(
            "{uri}{}",
            base64::engine::general_purpose::STANDARD.encode(&data)
        ));
    }
    let doc = json!({
        "asset": {"version": "2.0", "generator": "wingedge"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 1}, "indices": 0, "mode": 4}]}],
        "buffers": [buffer],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": index_bytes, "target": 34963},
            {"buffer": 0, "byteOffset": index_bytes, "byteLength": data.len() - index_bytes, "target": 34962}
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5125, "count": triangles.len() * 3, "type": "SCALAR"},
            {"bufferView": 1, "componentType": 5126, "count": positions.len(), "type": "VEC3",
             "min": min.map(f64::from), "max": max.map(f64::from)}
        ]
    });
    (doc, data)
}

/// A `.gltf` file: JSON with the buffer in a `data:` URI.
pub(crate) fn write_gltf(positions: &[[f32; 3]], triangles: &[[usize; 3]]) -> Vec<u8> {
    let (doc, _) = document(
        positions,
        triangles,
        Some("data:application/octet-stream;base64,".into()),
    );
    let mut text = doc.to_string().into_bytes();
    text.push(b'\n');
    text
}

/// A `.glb` file: the JSON chunk and the binary chunk.
pub(crate) fn write_glb(positions: &[[f32; 3]], triangles: &[[usize; 3]]) -> Vec<u8> {
    let (doc, mut data) = document(positions, triangles, None);
    let mut json = doc.to_string().into_bytes();
    while json.len() % 4 != 0 {
        json.push(b' ');
    }
    while data.len() % 4 != 0 {
        data.push(0);
    }
    let total = 12 + 8 + json.len() + 8 + data.len();
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(&0x4E4F_534Au32.to_le_bytes());
    out.extend_from_slice(&json);
    out.extend_from_slice(&(data.len() as u32).to_le_bytes());
    out.extend_from_slice(&0x004E_4942u32.to_le_bytes());
    out.extend_from_slice(&data);
    out
}
