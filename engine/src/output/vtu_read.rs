//! A small reader of the VTK XML files ctc writes (`.vtu`), independent of
//! the writer's code paths: it parses the tags of the XML part, then
//! decodes each `<DataArray>` by its own attributes — `format="ascii"`
//! (inline text) or `format="appended"` (an offset into a raw
//! `<AppendedData>` section, zlib-compressed in blocks when the file names
//! `compressor="vtkZLibDataCompressor"`, with `UInt32` or `UInt64` headers
//! as `header_type` says). Inline base64 (`format="binary"`) is not read.
//!
//! Used by the tests of every crate that reads ctc's results back; a
//! malformed file is an error, never a panic.

use std::path::Path;

/// Where an array sits in the file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Section {
    /// `<PointData>`.
    PointData,
    /// `<CellData>`.
    CellData,
    /// `<FieldData>`.
    FieldData,
    /// `<Points>`.
    Points,
    /// `<Cells>`.
    Cells,
    /// Anywhere else.
    Other,
}

/// One `<DataArray>`, its values as `f64` (integers up to 2^53 are exact).
#[derive(Debug, Clone, PartialEq)]
pub struct DataArray {
    /// The section holding it.
    pub section: Section,
    /// `Name`.
    pub name: String,
    /// `type` (`Float64`, `Int32`, ...).
    pub ty: String,
    /// `NumberOfComponents` (1 when absent).
    pub components: usize,
    /// `format` as written (`ascii`, `appended`).
    pub format: String,
    /// Every value, tuple by tuple.
    pub values: Vec<f64>,
}

/// A VTU file as read.
#[derive(Debug, Clone, PartialEq)]
pub struct Vtu {
    /// `NumberOfPoints` of the piece.
    pub points: usize,
    /// `NumberOfCells` of the piece.
    pub cells: usize,
    /// Every data array in file order.
    pub arrays: Vec<DataArray>,
}

impl Vtu {
    /// Reads the file at `path`.
    pub fn read_file(path: &Path) -> Result<Vtu, String> {
        let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
        Vtu::read(&bytes).map_err(|e| format!("{}: {e}", path.display()))
    }

    /// Reads a file's bytes.
    pub fn read(bytes: &[u8]) -> Result<Vtu, String> {
        let (head, _) = split(bytes)?;
        let piece = tags(head)?
            .into_iter()
            .find(|t| t.name == "Piece")
            .ok_or("no <Piece>")?;
        let count = |key: &str| -> Result<usize, String> {
            piece
                .attr(key)
                .ok_or(format!("<Piece> without {key}"))?
                .parse()
                .map_err(|_| format!("<Piece> {key} is not a count"))
        };
        Ok(Vtu {
            points: count("NumberOfPoints")?,
            cells: count("NumberOfCells")?,
            arrays: arrays(bytes)?,
        })
    }

    /// The array `name` of `section`.
    pub fn array(&self, section: Section, name: &str) -> Option<&DataArray> {
        self.arrays
            .iter()
            .find(|a| a.section == section && a.name == name)
    }

    /// Point data `name`.
    pub fn point(&self, name: &str) -> Option<&DataArray> {
        self.array(Section::PointData, name)
    }

    /// Cell data `name`.
    pub fn cell(&self, name: &str) -> Option<&DataArray> {
        self.array(Section::CellData, name)
    }

    /// Field data `name`.
    pub fn field(&self, name: &str) -> Option<&DataArray> {
        self.array(Section::FieldData, name)
    }

    /// The names of the arrays of `section`, in file order.
    pub fn names(&self, section: Section) -> Vec<&str> {
        self.arrays
            .iter()
            .filter(|a| a.section == section)
            .map(|a| a.name.as_str())
            .collect()
    }
}

/// The whole mesh of the pieces of a parallel file (`.pvtu`; each piece
/// written with the point data `node` and the cell data `cell`, the global
/// numbers of its points and cells, as `ctc run --solver petsc` under
/// `mpirun` writes them): every point and cell array at its global
/// numbers, the connectivity in global node numbers, in the order of the
/// first piece's arrays (without `node` and `cell`), as a VTU of the whole
/// mesh holds them. A node of several pieces must have the same values in
/// each; a node or cell no piece holds is an error.
pub fn join_pieces(pieces: &[Vtu]) -> Result<Vtu, String> {
    let first = pieces.first().ok_or("no pieces")?;
    let ids = |v: &Vtu, section: Section, name: &str| -> Result<Vec<usize>, String> {
        let a = v
            .array(section, name)
            .ok_or(format!("a piece without the {name} numbers"))?;
        Ok(a.values.iter().map(|&x| x as usize).collect())
    };
    let mut node_ids = Vec::new();
    let mut cell_ids = Vec::new();
    for v in pieces {
        node_ids.push(ids(v, Section::PointData, "node")?);
        cell_ids.push(ids(v, Section::CellData, "cell")?);
    }
    let total = |all: &[Vec<usize>]| all.iter().flatten().max().map_or(0, |m| m + 1);
    let (points, cells) = (total(&node_ids), total(&cell_ids));
    let mut arrays = Vec::new();
    for a in &first.arrays {
        let per_node = matches!(a.section, Section::PointData | Section::Points);
        let per_cell = a.section == Section::CellData;
        if (a.section == Section::PointData && a.name == "node")
            || (per_cell && a.name == "cell")
            || a.section == Section::Cells
        {
            continue;
        }
        if !(per_node || per_cell) {
            arrays.push(a.clone());
            continue;
        }
        let k = a.components.max(1);
        let n = if per_node { points } else { cells };
        let mut values = vec![f64::NAN; k * n];
        let mut seen = vec![false; n];
        for (p, v) in pieces.iter().enumerate() {
            let b = v
                .array(a.section, &a.name)
                .ok_or(format!("piece {p} has no array {}", a.name))?;
            let ids = if per_node { &node_ids[p] } else { &cell_ids[p] };
            if b.values.len() != k * ids.len() {
                return Err(format!("piece {p}: array {} has the wrong length", a.name));
            }
            for (i, &g) in ids.iter().enumerate() {
                let new = &b.values[k * i..k * (i + 1)];
                let old = &mut values[k * g..k * (g + 1)];
                if seen[g] && old.iter().zip(new).any(|(x, y)| x.to_bits() != y.to_bits()) {
                    return Err(format!("{} differs between pieces at {g}", a.name));
                }
                old.copy_from_slice(new);
                seen[g] = true;
            }
        }
        if let Some(g) = seen.iter().position(|s| !s) {
            return Err(format!(
                "no piece holds {} {g}",
                if per_node { "node" } else { "cell" }
            ));
        }
        arrays.push(DataArray {
            values,
            ..a.clone()
        });
    }
    // the cells: connectivity in global node numbers, in global cell order
    let mut conn: Vec<Vec<f64>> = vec![Vec::new(); cells];
    let mut types = vec![0.0; cells];
    for (p, v) in pieces.iter().enumerate() {
        let get = |name: &str| {
            v.array(Section::Cells, name)
                .ok_or(format!("piece {p} has no {name}"))
        };
        let (c, o, t) = (get("connectivity")?, get("offsets")?, get("types")?);
        let mut start = 0;
        for (i, &g) in cell_ids[p].iter().enumerate() {
            let end = *o.values.get(i).ok_or("offsets too short")? as usize;
            let local = c.values.get(start..end).ok_or("connectivity too short")?;
            conn[g] = local
                .iter()
                .map(|&l| node_ids[p].get(l as usize).map(|&n| n as f64))
                .collect::<Option<_>>()
                .ok_or("a cell names a point outside its piece")?;
            types[g] = *t.values.get(i).ok_or("types too short")?;
            start = end;
        }
    }
    for (name, values) in [
        ("connectivity", conn.concat()),
        (
            "offsets",
            conn.iter()
                .scan(0.0, |o, c| {
                    *o += c.len() as f64;
                    Some(*o)
                })
                .collect(),
        ),
        ("types", types),
    ] {
        let a = first
            .array(Section::Cells, name)
            .ok_or(format!("no {name}"))?;
        arrays.push(DataArray {
            values,
            ..a.clone()
        });
    }
    Ok(Vtu {
        points,
        cells,
        arrays,
    })
}

/// An XML tag of the head.
#[derive(Debug)]
struct Tag<'a> {
    name: &'a str,
    attrs: Vec<(&'a str, &'a str)>,
    closing: bool,
    empty: bool,
    /// Byte just after the tag's `>`.
    end: usize,
}

impl Tag<'_> {
    fn attr(&self, key: &str) -> Option<&str> {
        self.attrs.iter().find(|(k, _)| *k == key).map(|(_, v)| *v)
    }
}

/// The XML text before `<AppendedData` and the appended bytes after its
/// `_` marker (empty without appended data).
fn split(bytes: &[u8]) -> Result<(&str, &[u8]), String> {
    let at = find(bytes, b"<AppendedData");
    let head = &bytes[..at.unwrap_or(bytes.len())];
    let head = std::str::from_utf8(head).map_err(|_| "the XML part is not UTF-8".to_string())?;
    let Some(at) = at else {
        return Ok((head, &[]));
    };
    let rest = &bytes[at..];
    let close = find(rest, b">").ok_or("<AppendedData> is not closed")?;
    let tag = std::str::from_utf8(&rest[..close]).map_err(|_| "bad <AppendedData> tag")?;
    if !tag.contains("encoding=\"raw\"") {
        return Err("only raw appended data is read".into());
    }
    let marker = find(&rest[close..], b"_").ok_or("appended data without its `_` marker")?;
    Ok((head, &rest[close + marker + 1..]))
}

fn find(hay: &[u8], needle: &[u8]) -> Option<usize> {
    hay.windows(needle.len()).position(|w| w == needle)
}

/// The tags of `head` (comments and processing instructions skipped).
fn tags(head: &str) -> Result<Vec<Tag<'_>>, String> {
    let mut out = Vec::new();
    let mut i = 0;
    while let Some(lt) = head[i..].find('<').map(|k| k + i) {
        let rest = &head[lt..];
        if rest.starts_with("<!--") {
            i = lt + rest.find("-->").ok_or("unclosed comment")? + 3;
            continue;
        }
        let gt = lt + rest.find('>').ok_or("unclosed tag")?;
        let inner = &head[lt + 1..gt];
        i = gt + 1;
        if inner.starts_with('?') {
            continue;
        }
        let (closing, inner) = match inner.strip_prefix('/') {
            Some(x) => (true, x),
            None => (false, inner),
        };
        let (empty, inner) = match inner.strip_suffix('/') {
            Some(x) => (true, x),
            None => (false, inner),
        };
        let name_end = inner
            .find(|c: char| c.is_whitespace())
            .unwrap_or(inner.len());
        let mut attrs = Vec::new();
        let mut a = &inner[name_end..];
        while let Some(eq) = a.find('=') {
            let key = a[..eq].trim();
            let after = a[eq + 1..].trim_start();
            let body = after
                .strip_prefix('"')
                .ok_or(format!("attribute {key} is not quoted"))?;
            let q = body.find('"').ok_or(format!("attribute {key} unclosed"))?;
            attrs.push((key, &body[..q]));
            a = &body[q + 1..];
        }
        out.push(Tag {
            name: &inner[..name_end],
            attrs,
            closing,
            empty,
            end: i,
        });
    }
    Ok(out)
}

/// Every `<DataArray>` of a file, decoded, in file order.
pub fn arrays(bytes: &[u8]) -> Result<Vec<DataArray>, String> {
    let (head, appended) = split(bytes)?;
    let tags = tags(head)?;
    let file = tags
        .iter()
        .find(|t| t.name == "VTKFile")
        .ok_or("no <VTKFile>")?;
    let header = match file.attr("header_type").unwrap_or("UInt32") {
        "UInt32" => 4,
        "UInt64" => 8,
        h => return Err(format!("header_type {h} is not read")),
    };
    let compressed = match file.attr("compressor") {
        None => false,
        Some("vtkZLibDataCompressor") => true,
        Some(c) => return Err(format!("compressor {c} is not read")),
    };
    let mut section = Section::Other;
    let mut out = Vec::new();
    for (k, t) in tags.iter().enumerate() {
        let s = match t.name {
            "PointData" => Some(Section::PointData),
            "CellData" => Some(Section::CellData),
            "FieldData" => Some(Section::FieldData),
            "Points" => Some(Section::Points),
            "Cells" => Some(Section::Cells),
            _ => None,
        };
        if let Some(s) = s {
            if t.closing {
                section = Section::Other;
            } else if !t.empty {
                section = s;
            }
            continue;
        }
        if t.name != "DataArray" || t.closing {
            continue;
        }
        let name = t.attr("Name").unwrap_or("").to_string();
        let what = |e: String| format!("array `{name}`: {e}");
        let ty = t.attr("type").ok_or_else(|| what("no type".into()))?;
        let components = match t.attr("NumberOfComponents") {
            Some(c) => c
                .parse()
                .map_err(|_| what("bad NumberOfComponents".into()))?,
            None => 1,
        };
        let format = t.attr("format").unwrap_or("ascii");
        let values = match (format, t.empty) {
            ("ascii", false) => {
                let next = tags.get(k + 1).ok_or_else(|| what("not closed".into()))?;
                let text_end = head[..next.end]
                    .rfind('<')
                    .ok_or_else(|| what("not closed".into()))?;
                head[t.end..text_end]
                    .split_whitespace()
                    .map(|v| {
                        v.parse::<f64>()
                            .map_err(|_| what(format!("`{v}` is not a number")))
                    })
                    .collect::<Result<Vec<_>, _>>()?
            }
            ("appended", true) => {
                let offset: usize = t
                    .attr("offset")
                    .and_then(|o| o.parse().ok())
                    .ok_or_else(|| what("no offset".into()))?;
                let data = appended
                    .get(offset..)
                    .ok_or_else(|| what("offset past the data".into()))?;
                let raw = if compressed {
                    decompress(data, header)
                } else {
                    uncompressed(data, header)
                }
                .ok_or_else(|| what("truncated or corrupt data".into()))?;
                decode(ty, &raw).map_err(what)?
            }
            (f, _) => return Err(what(format!("format {f} is not read"))),
        };
        if values.len() % components.max(1) != 0 {
            return Err(what(format!(
                "{} values for {components} components",
                values.len()
            )));
        }
        out.push(DataArray {
            section,
            name,
            ty: ty.to_string(),
            components,
            format: format.to_string(),
            values,
        });
    }
    Ok(out)
}

/// Reads header integer `i` of `size` bytes.
fn int(data: &[u8], size: usize, i: usize) -> Option<usize> {
    let b = data.get(size * i..size * (i + 1))?;
    Some(match size {
        4 => u32::from_le_bytes(b.try_into().ok()?) as usize,
        _ => u64::from_le_bytes(b.try_into().ok()?) as usize,
    })
}

/// zlib blocks behind `[blocks, block size, last size, compressed sizes..]`.
pub(crate) fn decompress(data: &[u8], size: usize) -> Option<Vec<u8>> {
    use std::io::Read as _;
    let n = int(data, size, 0)?;
    let (block, last) = (int(data, size, 1)?, int(data, size, 2)?);
    let mut pos = size * (3 + n);
    let mut out = Vec::new();
    for k in 0..n {
        let len = int(data, size, 3 + k)?;
        let before = out.len();
        let mut z = flate2::read::ZlibDecoder::new(data.get(pos..pos.checked_add(len)?)?);
        z.read_to_end(&mut out).ok()?;
        let expected = if k + 1 == n && last > 0 { last } else { block };
        if out.len() - before != expected {
            return None;
        }
        pos += len;
    }
    Some(out)
}

/// `[byte count]` then the bytes.
fn uncompressed(data: &[u8], size: usize) -> Option<Vec<u8>> {
    let n = int(data, size, 0)?;
    Some(data.get(size..size.checked_add(n)?)?.to_vec())
}

// the byte types make `len % 1` in the macro
#[allow(clippy::modulo_one)]
fn decode(ty: &str, raw: &[u8]) -> Result<Vec<f64>, String> {
    macro_rules! le {
        ($t:ty) => {{
            const N: usize = std::mem::size_of::<$t>();
            if raw.len() % N != 0 {
                return Err(format!("{} bytes is not a whole number of {ty}", raw.len()));
            }
            raw.chunks_exact(N)
                .map(|c| {
                    let mut b = [0u8; N];
                    b.copy_from_slice(c);
                    <$t>::from_le_bytes(b) as f64
                })
                .collect()
        }};
    }
    Ok(match ty {
        "Float64" => le!(f64),
        "Float32" => le!(f32),
        "Int64" => le!(i64),
        "UInt64" => le!(u64),
        "Int32" => le!(i32),
        "UInt32" => le!(u32),
        "Int16" => le!(i16),
        "UInt16" => le!(u16),
        "Int8" => le!(i8),
        "UInt8" => le!(u8),
        t => return Err(format!("type {t} is not read")),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ascii_file_with_comments_and_sections() {
        let text = "<?xml version=\"1.0\"?>\n<!-- a <comment> -->\n<VTKFile type=\"UnstructuredGrid\">\n\
             <UnstructuredGrid><Piece NumberOfPoints=\"2\" NumberOfCells=\"1\">\n\
             <PointData><DataArray type=\"Float64\" Name=\"u\" NumberOfComponents=\"3\" format=\"ascii\">\n\
             1 2 3\n4 5 6e-300\n</DataArray></PointData>\n\
             <CellData><DataArray type=\"Int32\" Name=\"body\" format=\"ascii\">7</DataArray></CellData>\n\
             </Piece></UnstructuredGrid></VTKFile>\n";
        let v = Vtu::read(text.as_bytes()).unwrap();
        assert_eq!((v.points, v.cells), (2, 1));
        let u = v.point("u").unwrap();
        assert_eq!(u.components, 3);
        assert_eq!(u.values, [1.0, 2.0, 3.0, 4.0, 5.0, 6e-300]);
        assert_eq!(v.cell("body").unwrap().values, [7.0]);
        assert!(v.point("body").is_none());
    }

    #[test]
    fn malformed_files_are_errors() {
        for bad in [
            &b"<VTKFile><Piece NumberOfPoints=\"1\" NumberOfCells=\"0\"><PointData><DataArray type=\"Float64\" Name=\"u\" format=\"ascii\">x</DataArray>"[..],
            b"<VTKFile header_type=\"UInt64\"><Piece NumberOfPoints=\"1\" NumberOfCells=\"0\"><DataArray type=\"Float64\" Name=\"u\" format=\"appended\" offset=\"99\"/><AppendedData encoding=\"raw\">_abc",
            b"<VTKFile><Piece NumberOfPoints=\"1\"",
            b"no xml at all",
        ] {
            assert!(Vtu::read(bad).is_err(), "{}", String::from_utf8_lossy(bad));
        }
    }
}
