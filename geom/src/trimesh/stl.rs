//! STL reader (ASCII and binary) and a small ASCII writer.
//!
//! Binary: an 80-byte header, a little-endian `u32` triangle count, then 50
//! bytes per triangle (normal, three corners as `f32`, a 2-byte attribute).
//! A file whose size is exactly `84 + 50 n` is binary (some binary files
//! start with the word `solid` too); otherwise it is read as ASCII:
//! `solid name`, then per triangle `facet normal nx ny nz`, `outer loop`,
//! three `vertex x y z`, `endloop`, `endfacet`, and `endsolid`. The stored
//! normals are ignored: the corners' order (counter-clockwise seen from
//! outside) gives the orientation.

use crate::Vec3;

/// An error reading an STL file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct StlError {
    /// 1-based line (ASCII) or triangle (binary) where it went wrong; 0 for
    /// the file as a whole.
    pub line: usize,
    /// What is wrong.
    pub message: String,
}

impl std::fmt::Display for StlError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.line == 0 {
            write!(f, "STL: {}", self.message)
        } else {
            write!(f, "STL line {}: {}", self.line, self.message)
        }
    }
}

impl std::error::Error for StlError {}

fn err(line: usize, message: impl Into<String>) -> StlError {
    StlError {
        line,
        message: message.into(),
    }
}

/// Reads the triangles (three corners each) of an STL file's bytes.
pub fn read(bytes: &[u8]) -> Result<Vec<[Vec3; 3]>, StlError> {
    if bytes.len() >= 84 {
        let n = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as usize;
        if n.checked_mul(50).and_then(|b| b.checked_add(84)) == Some(bytes.len()) {
            return read_binary(bytes, n);
        }
    }
    let text = std::str::from_utf8(bytes).map_err(|_| {
        err(
            0,
            format!(
                "neither a binary STL ({} bytes is not 84 + 50 x the triangle count in the header) nor ASCII text",
                bytes.len()
            ),
        )
    })?;
    read_ascii(text)
}

fn read_binary(bytes: &[u8], n: usize) -> Result<Vec<[Vec3; 3]>, StlError> {
    let f =
        |o: usize| f32::from_le_bytes([bytes[o], bytes[o + 1], bytes[o + 2], bytes[o + 3]]) as f64;
    let mut tris = Vec::with_capacity(n);
    for t in 0..n {
        let base = 84 + 50 * t + 12;
        let c = [0, 1, 2]
            .map(|k| Vec3::new(f(base + 12 * k), f(base + 12 * k + 4), f(base + 12 * k + 8)));
        if !c.iter().all(|p| p.iter().all(|x| x.is_finite())) {
            return Err(err(
                t + 1,
                format!("triangle {} has a non-finite coordinate", t + 1),
            ));
        }
        tris.push(c);
    }
    if tris.is_empty() {
        return Err(err(0, "the file holds no triangle"));
    }
    Ok(tris)
}

fn read_ascii(text: &str) -> Result<Vec<[Vec3; 3]>, StlError> {
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.split_whitespace().collect::<Vec<_>>()))
        .filter(|(_, w)| !w.is_empty());
    let (l0, first) = lines.next().ok_or_else(|| err(0, "the file is empty"))?;
    if first[0] != "solid" {
        return Err(err(l0, format!("expected `solid`, found `{}`", first[0])));
    }
    let mut tris = Vec::new();
    let expect = |item: Option<(usize, Vec<&str>)>,
                  what: &[&str],
                  last: usize|
     -> Result<(usize, Vec<f64>), StlError> {
        let (l, w) = item.ok_or_else(|| {
            err(
                last,
                format!("the file ends where `{}` was expected", what.join(" ")),
            )
        })?;
        if w.len() < what.len() || w[..what.len()] != *what {
            return Err(err(
                l,
                format!("expected `{}`, found `{}`", what.join(" "), w.join(" ")),
            ));
        }
        let nums: Result<Vec<f64>, _> = w[what.len()..].iter().map(|s| s.parse::<f64>()).collect();
        let nums = nums.map_err(|_| err(l, format!("bad number in `{}`", w.join(" "))))?;
        Ok((l, nums))
    };
    let mut last = l0;
    loop {
        let Some((l, w)) = lines.next() else {
            return Err(err(last, "the file ends without `endsolid`"));
        };
        last = l;
        match w[0] {
            "endsolid" => break,
            "facet" => {
                if w.get(1) != Some(&"normal") {
                    return Err(err(l, "expected `facet normal nx ny nz`"));
                }
                expect(lines.next(), &["outer", "loop"], l)?;
                let mut c = [Vec3::zeros(); 3];
                for ck in &mut c {
                    let (lv, v) = expect(lines.next(), &["vertex"], l)?;
                    if v.len() != 3 || !v.iter().all(|x| x.is_finite()) {
                        return Err(err(lv, "a vertex needs three finite coordinates"));
                    }
                    *ck = Vec3::new(v[0], v[1], v[2]);
                    last = lv;
                }
                let (le, _) = expect(lines.next(), &["endloop"], last)?;
                let (lf, _) = expect(lines.next(), &["endfacet"], le)?;
                last = lf;
                tris.push(c);
            }
            other => {
                return Err(err(
                    l,
                    format!("expected `facet` or `endsolid`, found `{other}`"),
                ))
            }
        }
    }
    if tris.is_empty() {
        return Err(err(0, "the file holds no triangle"));
    }
    Ok(tris)
}

/// Writes triangles as ASCII STL.
pub fn write_ascii(name: &str, tris: &[[Vec3; 3]]) -> String {
    let mut s = format!("solid {name}\n");
    for t in tris {
        let n = (t[1] - t[0])
            .cross(&(t[2] - t[0]))
            .try_normalize(0.0)
            .unwrap_or_else(Vec3::zeros);
        s += &format!(
            "  facet normal {:e} {:e} {:e}\n    outer loop\n",
            n.x, n.y, n.z
        );
        for p in t {
            s += &format!("      vertex {:e} {:e} {:e}\n", p.x, p.y, p.z);
        }
        s += "    endloop\n  endfacet\n";
    }
    s += &format!("endsolid {name}\n");
    s
}

/// Writes triangles as binary STL (coordinates rounded to `f32`).
pub fn write_binary(tris: &[[Vec3; 3]]) -> Vec<u8> {
    let mut b = vec![0u8; 80];
    b[..19].copy_from_slice(b"ctc-geom binary STL");
    b.extend_from_slice(&(tris.len() as u32).to_le_bytes());
    for t in tris {
        let n = (t[1] - t[0])
            .cross(&(t[2] - t[0]))
            .try_normalize(0.0)
            .unwrap_or_else(Vec3::zeros);
        for v in std::iter::once(&n).chain(t.iter()) {
            for k in 0..3 {
                b.extend_from_slice(&(v[k] as f32).to_le_bytes());
            }
        }
        b.extend_from_slice(&[0, 0]);
    }
    b
}
