//! The encoding layer of the VTK XML writers: how a data array's values
//! are stored, separate from which arrays a file has (cell types and
//! fields live in `vtu.rs`).
//!
//! - [`Encoding::Binary`] (the default): every array is `format="appended"`
//!   at an offset into one `<AppendedData encoding="raw">` section, each
//!   compressed with zlib in 32 KiB blocks behind a `UInt64` block header
//!   (`vtkZLibDataCompressor`: number of blocks, block size, size of the
//!   last block, compressed size of each block) — what ParaView writes.
//!   zlib at its fastest level: on the ~80k-dof bench with stress, strain,
//!   von Mises, reactions and contact (40,186 nodes) a file is 5.35 MB
//!   against 5.13 MB at the default level and 21.5 MB as ASCII, and the
//!   output phase of 4 increments takes 0.8-1.4 s against 2.7-3.9 s at the
//!   default level and 2.1-2.4 s as ASCII (`docs/ARCHITECTURE.md`, output).
//! - [`Encoding::Ascii`]: values inline, numbers in their shortest
//!   round-trip form ([`fmt_f64`]: `0.1`, `1e-300`, never
//!   `0.30000000000000004` unless that is the value).
//!
//! A writer calls [`Arrays::array`] for each array while it builds the XML
//! text, then [`Arrays::finish`] to get the file's bytes.

use std::fmt::Write as _;
use std::io::Write as _;

pub use crate::model::VtuFormat as Encoding;

/// Uncompressed bytes per zlib block (VTK's default).
pub const BLOCK: usize = 1 << 15;

/// A value type of a VTK data array.
pub trait Scalar: Copy {
    /// VTK type name (`Float64`, `Int32`, ...).
    const VTK: &'static str;
    /// Appends the little-endian bytes.
    fn bytes(self, out: &mut Vec<u8>);
    /// Appends the ASCII text.
    fn text(self, out: &mut String);
}

impl Scalar for f64 {
    const VTK: &'static str = "Float64";
    fn bytes(self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_le_bytes());
    }
    fn text(self, out: &mut String) {
        out.push_str(&fmt_f64(self));
    }
}

impl Scalar for i32 {
    const VTK: &'static str = "Int32";
    fn bytes(self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_le_bytes());
    }
    fn text(self, out: &mut String) {
        let _ = write!(out, "{self}");
    }
}

impl Scalar for i64 {
    const VTK: &'static str = "Int64";
    fn bytes(self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_le_bytes());
    }
    fn text(self, out: &mut String) {
        let _ = write!(out, "{self}");
    }
}

impl Scalar for u8 {
    const VTK: &'static str = "UInt8";
    fn bytes(self, out: &mut Vec<u8>) {
        out.push(self);
    }
    fn text(self, out: &mut String) {
        let _ = write!(out, "{self}");
    }
}

/// The shortest text that reads back as exactly `x` (Rust's `{}` for
/// doubles is the shortest round-trip form), with an exponent for very
/// large or small magnitudes (`1e-300`, not 300 zeros).
pub fn fmt_f64(x: f64) -> String {
    let a = x.abs();
    if x == 0.0 || !x.is_finite() || (1e-5..1e16).contains(&a) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// Displays an `f64` as [`fmt_f64`] (for `write!` into CSV rows).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shortest(pub f64);

impl std::fmt::Display for Shortest {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&fmt_f64(self.0))
    }
}

/// The arrays of one file.
#[derive(Debug)]
pub struct Arrays {
    encoding: Encoding,
    appended: Vec<u8>,
}

impl Arrays {
    /// No arrays yet.
    pub fn new(encoding: Encoding) -> Self {
        Arrays {
            encoding,
            appended: Vec::new(),
        }
    }

    /// The encoding.
    pub fn encoding(&self) -> Encoding {
        self.encoding
    }

    /// The `compressor` attribute of `<VTKFile>` (empty for ASCII).
    pub fn compressor_attribute(&self) -> &'static str {
        match self.encoding {
            Encoding::Binary => " compressor=\"vtkZLibDataCompressor\"",
            Encoding::Ascii => "",
        }
    }

    /// Writes a `<DataArray>` element of `values` (`comps` per tuple) into
    /// `xml` at `indent`; `extra` are further attributes (e.g. component
    /// names, with a leading space).
    pub fn array<T: Scalar>(
        &mut self,
        xml: &mut String,
        indent: &str,
        name: &str,
        comps: usize,
        extra: &str,
        values: impl IntoIterator<Item = T>,
    ) {
        let comps_attr = if comps > 0 {
            format!(" NumberOfComponents=\"{comps}\"")
        } else {
            String::new()
        };
        match self.encoding {
            Encoding::Ascii => {
                let _ = writeln!(
                    xml,
                    "{indent}<DataArray type=\"{}\" Name=\"{name}\"{comps_attr}{extra} format=\"ascii\">",
                    T::VTK
                );
                let per_line = 3 * comps.max(1);
                for (i, v) in values.into_iter().enumerate() {
                    if i % per_line == 0 {
                        if i > 0 {
                            xml.push('\n');
                        }
                        xml.push_str(indent);
                        xml.push_str("  ");
                    } else {
                        xml.push(' ');
                    }
                    v.text(xml);
                }
                xml.push('\n');
                let _ = writeln!(xml, "{indent}</DataArray>");
            }
            Encoding::Binary => {
                let offset = self.appended.len();
                let mut raw = Vec::new();
                for v in values {
                    v.bytes(&mut raw);
                }
                compress_into(&raw, &mut self.appended);
                let _ = writeln!(
                    xml,
                    "{indent}<DataArray type=\"{}\" Name=\"{name}\"{comps_attr}{extra} format=\"appended\" offset=\"{offset}\"/>",
                    T::VTK
                );
            }
        }
    }

    /// The file's bytes: `xml` (which must end just before
    /// `</VTKFile>`), the appended data, and the closing tag.
    pub fn finish(self, mut xml: String) -> Vec<u8> {
        match self.encoding {
            Encoding::Ascii => {
                xml.push_str("</VTKFile>\n");
                xml.into_bytes()
            }
            Encoding::Binary => {
                xml.push_str("  <AppendedData encoding=\"raw\">\n   _");
                let mut out = xml.into_bytes();
                out.extend_from_slice(&self.appended);
                out.extend_from_slice(b"\n  </AppendedData>\n</VTKFile>\n");
                out
            }
        }
    }
}

/// Arrays at least this large (bytes) are remembered by [`compress_into`].
const MEMO_MIN: usize = 1 << 16;

/// Most arrays remembered by [`compress_into`] (per thread).
const MEMO_ENTRIES: usize = 16;

thread_local! {
    /// The last large arrays compressed on this thread, raw and
    /// compressed (header included), newest last.
    static MEMO: std::cell::RefCell<std::collections::VecDeque<(Vec<u8>, Vec<u8>)>> =
        const { std::cell::RefCell::new(std::collections::VecDeque::new()) };
}

/// Appends `raw` compressed in [`BLOCK`]-byte zlib blocks behind the
/// `UInt64` header `[blocks, BLOCK, last block size, compressed sizes..]`.
///
/// A large array equal byte for byte to one of the last ones compressed on
/// this thread (the coordinates, connectivity, offsets, cell types and
/// bodies of every increment's file) takes the remembered bytes: the same
/// output as compressing it again (zlib is a function of its input), at a
/// comparison's cost (issue 20: the mesh arrays were half the output phase
/// of the tutorial deck).
fn compress_into(raw: &[u8], out: &mut Vec<u8>) {
    if raw.len() < MEMO_MIN {
        return compress_blocks(raw, out);
    }
    let hit = MEMO.with_borrow(|memo| {
        memo.iter()
            .find(|(r, _)| r[..] == raw[..])
            .map(|(_, z)| out.extend_from_slice(z))
            .is_some()
    });
    if hit {
        return;
    }
    let start = out.len();
    compress_blocks(raw, out);
    let z = out[start..].to_vec();
    MEMO.with_borrow_mut(|memo| {
        if memo.len() == MEMO_ENTRIES {
            memo.pop_front();
        }
        memo.push_back((raw.to_vec(), z));
    });
}

/// [`compress_into`] without the memo.
fn compress_blocks(raw: &[u8], out: &mut Vec<u8>) {
    let blocks: Vec<&[u8]> = raw.chunks(BLOCK).collect();
    let compressed: Vec<Vec<u8>> = blocks
        .iter()
        .map(|b| {
            let mut z = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::fast());
            // writing into a Vec cannot fail
            let _ = z.write_all(b);
            z.finish().unwrap_or_default()
        })
        .collect();
    let last = blocks.last().map_or(0, |b| b.len());
    for h in [blocks.len(), BLOCK, last] {
        out.extend_from_slice(&(h as u64).to_le_bytes());
    }
    for c in &compressed {
        out.extend_from_slice(&(c.len() as u64).to_le_bytes());
    }
    for c in &compressed {
        out.extend_from_slice(c);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shortest_round_trip_numbers() {
        assert_eq!(fmt_f64(0.1), "0.1");
        assert_eq!(fmt_f64(0.1 + 0.2), "0.30000000000000004");
        assert_eq!(fmt_f64(3.5940786e-300), "3.5940786e-300");
        assert_eq!(fmt_f64(-2.5e20), "-2.5e20");
        assert_eq!(fmt_f64(0.0), "0");
        assert_eq!(fmt_f64(-0.0), "-0");
        assert_eq!(format!("{}", Shortest(3.5940786e-300)), "3.5940786e-300");
        assert_eq!(fmt_f64(1e16), "1e16");
        assert_eq!(fmt_f64(12345.5), "12345.5");
        assert_eq!(fmt_f64(2e-5), "0.00002");
        assert_eq!(fmt_f64(9e-6), "9e-6");
        for x in [1.0 / 3.0, 1e-7, 123456.789, -4.2e-12, f64::MAX] {
            assert_eq!(fmt_f64(x).parse::<f64>().unwrap(), x);
        }
    }

    #[test]
    fn binary_and_ascii_arrays_read_back_identically() {
        let values: Vec<f64> = (0..10_000).map(|i| (i as f64).sin() * 1e-3).collect();
        for enc in [Encoding::Binary, Encoding::Ascii] {
            let mut a = Arrays::new(enc);
            let mut xml = format!(
                "<VTKFile type=\"UnstructuredGrid\" header_type=\"UInt64\"{}>\n",
                a.compressor_attribute()
            );
            a.array(&mut xml, "  ", "first", 1, "", [1.0f64, 2.0]);
            a.array(&mut xml, "  ", "u", 2, "", values.iter().copied());
            let file = a.finish(xml);
            let read = super::super::vtu_read::arrays(&file).unwrap();
            assert_eq!(read[0].name, "first");
            assert_eq!(read[0].values, vec![1.0, 2.0]);
            assert_eq!(
                (read[1].components, &read[1].values),
                (2, &values),
                "{enc:?}"
            );
        }
    }

    #[test]
    fn a_remembered_array_gives_the_bytes_of_a_new_compression() {
        let raw: Vec<u8> = (0..(3 * MEMO_MIN + 7))
            .map(|i| (i * 7 % 253) as u8)
            .collect();
        let mut fresh = Vec::new();
        compress_blocks(&raw, &mut fresh);
        let (mut first, mut second) = (vec![1u8], vec![2u8, 3]);
        compress_into(&raw, &mut first);
        compress_into(&raw, &mut second);
        assert_eq!(&first[1..], &fresh[..]);
        assert_eq!(&second[2..], &fresh[..]);
        // one byte changed: compressed again, not the remembered bytes
        let mut other = raw.clone();
        other[MEMO_MIN + 3] ^= 0xff;
        let (mut memo, mut plain) = (Vec::new(), Vec::new());
        compress_into(&other, &mut memo);
        compress_blocks(&other, &mut plain);
        assert_eq!(memo, plain);
        assert_ne!(memo, fresh);
        assert_eq!(super::super::vtu_read::decompress(&memo, 8).unwrap(), other);
    }

    #[test]
    fn zlib_blocks_have_the_vtk_header() {
        let raw: Vec<u8> = (0..(2 * BLOCK + 10)).map(|i| (i % 251) as u8).collect();
        let mut out = Vec::new();
        compress_into(&raw, &mut out);
        let h = |i: usize| u64::from_le_bytes(out[8 * i..8 * i + 8].try_into().unwrap());
        assert_eq!((h(0), h(1), h(2)), (3, BLOCK as u64, 10));
        assert_eq!(super::super::vtu_read::decompress(&out, 8).unwrap(), raw);
    }
}
