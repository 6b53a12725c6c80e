//! The IGES reader: Global section (delimiters, units, resolution),
//! Directory entries, Parameter data, and the entities that carry trimmed
//! NURBS geometry, turned into [`Face`]s.

use super::error::{IgesError, IgesErrorKind};
use super::params::{self, Cursor, Located, Param};
use super::records::{self, Record};
use crate::brep::Face;
use crate::nurbs::{NurbsCurve, NurbsSurface};
use crate::trim::{Boundary, Loop, TrimCurve};
use crate::{Mat3, Vec2, Vec3};

/// Entity types the reader understands.
pub const SUPPORTED: [i64; 10] = [100, 102, 110, 124, 126, 128, 141, 142, 143, 144];

/// The Global section's fields the reader uses.
#[derive(Debug, Clone, PartialEq)]
pub struct Global {
    /// Parameter delimiter (default `,`).
    pub parameter_delimiter: u8,
    /// Record delimiter (default `;`).
    pub record_delimiter: u8,
    /// Model space scale (field 13).
    pub scale: f64,
    /// Units flag (field 14: 1 inch, 2 mm, ...).
    pub units: i64,
    /// Minimum user-intended resolution (field 19).
    pub resolution: f64,
}

/// One directory entry (two Directory lines).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Entry {
    /// Entity type number.
    pub kind: i64,
    /// Form number.
    pub form: i64,
    /// First Parameter line (sequence number).
    pub parameter: usize,
    /// Number of Parameter lines.
    pub parameter_lines: usize,
    /// Directory pointer of a transformation matrix (124), or 0.
    pub transform: usize,
    /// Entity label (columns 57-64 of the second line).
    pub label: String,
    /// File line of the entry's first Directory line.
    pub line: usize,
}

/// An entity the reader does not support (reported, never skipped
/// silently).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Unsupported {
    /// Entity type number.
    pub kind: i64,
    /// Directory entry number.
    pub de: usize,
    /// File line of its directory entry.
    pub line: usize,
}

/// A face imported from an IGES entity.
#[derive(Debug, Clone, PartialEq)]
pub struct ImportedFace {
    /// The face (orientation `+1`: free space on the side of `S_u x S_v`).
    pub face: Face,
    /// Directory entry number of the entity (144, 143 or 128).
    pub de: usize,
    /// Entity type (144, 143 or 128).
    pub kind: i64,
    /// File line of its directory entry.
    pub line: usize,
    /// Entity label.
    pub label: String,
}

/// A read IGES file.
#[derive(Debug, Clone, PartialEq)]
pub struct IgesFile {
    /// Global fields.
    pub global: Global,
    /// Directory entries, in order (DE number `2 i + 1`).
    pub entries: Vec<Entry>,
    /// Parameters of each entry (the entity type first).
    pub params: Vec<Vec<Param>>,
    /// Entities of unsupported types that no face needs.
    pub unsupported: Vec<Unsupported>,
}

/// Reads an IGES file's text.
pub fn read(text: &str) -> Result<IgesFile, IgesError> {
    let s = records::split(text)?;
    let global = read_global(&s.global)?;
    let mut entries = Vec::with_capacity(s.directory.len() / 2);
    for pair in s.directory.chunks(2) {
        entries.push(read_entry(&pair[0], &pair[1])?);
    }
    let mut all_params = Vec::with_capacity(entries.len());
    for (i, e) in entries.iter().enumerate() {
        let first = e.parameter;
        let last = first + e.parameter_lines - 1;
        if first == 0 || last > s.parameter.len() {
            return Err(IgesError::new(
                e.line,
                IgesErrorKind::Directory,
                format!(
                    "entity {} (DE {}): its parameters are on lines P{first}..P{last} but the Parameter section has {} lines",
                    e.kind,
                    2 * i + 1,
                    s.parameter.len()
                ),
            ));
        }
        let recs = &s.parameter[first - 1..last];
        let located = Located::new(recs.iter().map(|r| (&r.data[..64], r.line)));
        let (ps, _) = params::split(
            &located,
            0,
            global.parameter_delimiter,
            global.record_delimiter,
        )?;
        let head = ps.first().map(|p| p.text.as_str()).unwrap_or("");
        if head.parse::<i64>().ok() != Some(e.kind) {
            return Err(IgesError::new(
                recs[0].line,
                IgesErrorKind::Parameter,
                format!(
                    "entity DE {}: the parameter data starts with `{head}`, not its type {}",
                    2 * i + 1,
                    e.kind
                ),
            ));
        }
        all_params.push(ps);
    }
    let mut file = IgesFile {
        global,
        entries,
        params: all_params,
        unsupported: Vec::new(),
    };
    let referenced = file.referenced()?;
    file.unsupported = file
        .entries
        .iter()
        .enumerate()
        .filter(|(i, e)| !SUPPORTED.contains(&e.kind) && !referenced.contains(&(2 * i + 1)))
        .map(|(i, e)| Unsupported {
            kind: e.kind,
            de: 2 * i + 1,
            line: e.line,
        })
        .collect();
    Ok(file)
}

fn read_global(recs: &[Record<'_>]) -> Result<Global, IgesError> {
    let located = Located::new(recs.iter().map(|r| (&r.data[..72], r.line)));
    let c = &located.chars;
    let line0 = recs[0].line;
    let gerr = |m: &str| IgesError::new(line0, IgesErrorKind::Global, m.to_string());
    // Delimiters: `1Hx` or empty (the default).
    let mut i = 0;
    while i < c.len() && c[i] == b' ' {
        i += 1;
    }
    let pd = if c.get(i..i + 2) == Some(b"1H") {
        let d = *c
            .get(i + 2)
            .ok_or_else(|| gerr("the Global section ends inside the parameter delimiter"))?;
        i += 3;
        d
    } else {
        b','
    };
    while i < c.len() && c[i] == b' ' {
        i += 1;
    }
    if c.get(i) != Some(&pd) {
        // `,;` style with an empty first field is handled: c[i] is pd.
        return Err(gerr(
            "the Global section must start with the parameter delimiter field (`1H,,` or `,`)",
        ));
    }
    i += 1;
    while i < c.len() && c[i] == b' ' {
        i += 1;
    }
    let rd = if c.get(i..i + 2) == Some(b"1H") {
        let d = *c
            .get(i + 2)
            .ok_or_else(|| gerr("the Global section ends inside the record delimiter"))?;
        i += 3;
        d
    } else {
        b';'
    };
    if pd == rd || pd == b' ' || rd == b' ' {
        return Err(gerr(
            "the parameter and record delimiters must be two different non-blank characters",
        ));
    }
    while i < c.len() && c[i] == b' ' {
        i += 1;
    }
    let rest = match c.get(i) {
        Some(&d) if d == pd => params::split(&located, i + 1, pd, rd)?.0,
        Some(&d) if d == rd => Vec::new(),
        _ => {
            return Err(gerr(
                "expected a delimiter after the record delimiter field",
            ))
        }
    };
    // rest[k] is Global field k + 3.
    let field = |n: usize| rest.get(n - 3);
    let real = |n: usize, default: f64| -> Result<f64, IgesError> {
        match field(n) {
            Some(p) if !p.text.is_empty() => params::parse_real(&p.text).ok_or_else(|| {
                IgesError::new(
                    p.line,
                    IgesErrorKind::Global,
                    format!("Global field {n} must be a real number, found `{}`", p.text),
                )
            }),
            _ => Ok(default),
        }
    };
    let units = match field(14) {
        Some(p) if !p.text.is_empty() => p.text.parse::<i64>().map_err(|_| {
            IgesError::new(
                p.line,
                IgesErrorKind::Global,
                format!(
                    "Global field 14 (units flag) must be an integer, found `{}`",
                    p.text
                ),
            )
        })?,
        _ => 1,
    };
    Ok(Global {
        parameter_delimiter: pd,
        record_delimiter: rd,
        scale: real(13, 1.0)?,
        units,
        resolution: real(19, 0.0)?,
    })
}

fn read_entry(a: &Record<'_>, b: &Record<'_>) -> Result<Entry, IgesError> {
    let field = |r: &Record<'_>, k: usize| r.data[8 * k..8 * k + 8].trim().to_string();
    let int = |r: &Record<'_>, k: usize, what: &str| -> Result<i64, IgesError> {
        let f = field(r, k);
        if f.is_empty() {
            return Ok(0);
        }
        f.parse::<i64>().map_err(|_| {
            IgesError::new(
                r.line,
                IgesErrorKind::Directory,
                format!(
                    "directory field {} ({what}) must be an integer, found `{f}`",
                    k + 1
                ),
            )
        })
    };
    let kind = int(a, 0, "entity type")?;
    if int(b, 0, "entity type")? != kind {
        return Err(IgesError::new(
            b.line,
            IgesErrorKind::Directory,
            "the two lines of a directory entry give different entity types",
        ));
    }
    let pos = |v: i64, r: &Record<'_>, what: &str| -> Result<usize, IgesError> {
        if v < 0 {
            Err(IgesError::new(
                r.line,
                IgesErrorKind::Directory,
                format!("directory field {what} is negative ({v})"),
            ))
        } else {
            Ok(v as usize)
        }
    };
    let parameter = pos(
        int(a, 1, "parameter data pointer")?,
        a,
        "parameter data pointer",
    )?;
    let transform = pos(
        int(a, 6, "transformation matrix pointer")?,
        a,
        "transformation matrix pointer",
    )?;
    let parameter_lines = pos(
        int(b, 3, "parameter line count")?,
        b,
        "parameter line count",
    )?;
    if parameter == 0 || parameter_lines == 0 {
        return Err(IgesError::new(
            a.line,
            IgesErrorKind::Directory,
            format!("entity {kind}: the parameter data pointer and line count must be >= 1"),
        ));
    }
    Ok(Entry {
        kind,
        form: int(b, 4, "form number")?,
        parameter,
        parameter_lines,
        transform,
        label: field(b, 7),
        line: a.line,
    })
}

/// An affine map `x -> r x + t`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Affine {
    r: Mat3,
    t: Vec3,
}

impl Affine {
    fn identity() -> Self {
        Affine {
            r: Mat3::identity(),
            t: Vec3::zeros(),
        }
    }
    fn apply(&self, p: &Vec3) -> Vec3 {
        self.r * p + self.t
    }
    fn then(&self, outer: &Affine) -> Affine {
        Affine {
            r: outer.r * self.r,
            t: outer.r * self.t + outer.t,
        }
    }
}

/// Nesting limit of composite curves and transformation chains.
const DEPTH: usize = 32;

impl IgesFile {
    /// Index of the entry at directory pointer `de` (odd, 1-based).
    fn index(&self, de: usize, line: usize, what: &str) -> Result<usize, IgesError> {
        if de % 2 == 1 && de / 2 < self.entries.len() {
            Ok(de / 2)
        } else {
            Err(IgesError::new(
                line,
                IgesErrorKind::Pointer,
                format!(
                    "{what}: pointer {de} is not a directory entry (odd numbers 1..{})",
                    2 * self.entries.len()
                ),
            ))
        }
    }

    fn cursor(&self, i: usize) -> Cursor<'_> {
        let e = &self.entries[i];
        let ps = &self.params[i];
        Cursor {
            params: ps,
            at: 1,
            line: ps.first().map_or(e.line, |p| p.line),
            what: format!("entity {} (DE {})", e.kind, 2 * i + 1),
        }
    }

    /// The entry at `de`, checked to be of one of `kinds`.
    fn expect(
        &self,
        de: usize,
        kinds: &[i64],
        line: usize,
        what: &str,
    ) -> Result<usize, IgesError> {
        let i = self.index(de, line, what)?;
        let k = self.entries[i].kind;
        if kinds.contains(&k) {
            return Ok(i);
        }
        let kind = if SUPPORTED.contains(&k) {
            IgesErrorKind::Pointer
        } else {
            IgesErrorKind::Unsupported
        };
        Err(IgesError::new(
            line,
            kind,
            format!(
                "{what}: DE {de} is an entity {k} (directory line {}), expected one of {kinds:?}{}",
                self.entries[i].line,
                if kind == IgesErrorKind::Unsupported {
                    "; entity type not supported"
                } else {
                    ""
                }
            ),
        ))
    }

    /// Directory pointers referenced by the supported entities.
    fn referenced(&self) -> Result<Vec<usize>, IgesError> {
        let mut refs = Vec::new();
        for (i, e) in self.entries.iter().enumerate() {
            if e.transform != 0 {
                refs.push(e.transform);
            }
            let mut c = self.cursor(i);
            match e.kind {
                102 => {
                    let n = c.count("number of curves", c.remaining())?;
                    for _ in 0..n {
                        refs.push(c.pointer("curve")?);
                    }
                }
                142 => {
                    c.int("creation flag")?;
                    for w in ["surface", "parameter-space curve", "model-space curve"] {
                        refs.push(c.pointer(w)?);
                    }
                }
                144 => {
                    refs.push(c.pointer("surface")?);
                    c.int("N1")?;
                    let n2 = c.count("number of holes", c.remaining())?;
                    refs.push(c.pointer("outer boundary")?);
                    for _ in 0..n2 {
                        refs.push(c.pointer("hole")?);
                    }
                }
                143 => {
                    c.int("type")?;
                    refs.push(c.pointer("surface")?);
                    let n = c.count("number of boundaries", c.remaining())?;
                    for _ in 0..n {
                        refs.push(c.pointer("boundary")?);
                    }
                }
                141 => {
                    c.int("type")?;
                    c.int("preferred representation")?;
                    refs.push(c.pointer("surface")?);
                    let n = c.count("number of curves", c.remaining())?;
                    for _ in 0..n {
                        refs.push(c.pointer("model-space curve")?);
                        c.int("sense")?;
                        let k = c.count("number of parameter-space curves", c.remaining())?;
                        for _ in 0..k {
                            refs.push(c.pointer("parameter-space curve")?);
                        }
                    }
                }
                _ => {}
            }
        }
        refs.retain(|&r| r != 0);
        refs.sort_unstable();
        refs.dedup();
        Ok(refs)
    }

    /// The transformation of entry `i` (its 124 chain), identity if none.
    fn transform(&self, i: usize) -> Result<Affine, IgesError> {
        let mut total = Affine::identity();
        let mut de = self.entries[i].transform;
        let mut line = self.entries[i].line;
        for _ in 0..DEPTH {
            if de == 0 {
                return Ok(total);
            }
            let j = self.expect(de, &[124], line, "transformation matrix")?;
            let mut c = self.cursor(j);
            let mut r = Mat3::zeros();
            let mut t = Vec3::zeros();
            for row in 0..3 {
                for col in 0..3 {
                    r[(row, col)] = c.real("matrix entry")?;
                }
                t[row] = c.real("translation")?;
            }
            total = total.then(&Affine { r, t });
            line = self.entries[j].line;
            de = self.entries[j].transform;
        }
        Err(IgesError::new(
            line,
            IgesErrorKind::Pointer,
            "the chain of transformation matrices is circular or deeper than 32",
        ))
    }

    /// The entity 128 at entry `i` as a surface, moved by `outer`; and the
    /// parameter range (U0, U1, V0, V1) it declares.
    fn surface(
        &self,
        i: usize,
        outer: &Affine,
    ) -> Result<(NurbsSurface, [[f64; 2]; 2]), IgesError> {
        let e = &self.entries[i];
        let tr = self.transform(i)?.then(outer);
        let mut c = self.cursor(i);
        let k1 = c.count("K1 (upper index in u)", c.remaining())?;
        let k2 = c.count("K2 (upper index in v)", c.remaining())?;
        let m1 = c.count("M1 (degree in u)", 64)?;
        let m2 = c.count("M2 (degree in v)", 64)?;
        for p in ["PROP1", "PROP2", "PROP3", "PROP4", "PROP5"] {
            c.int(p)?;
        }
        let (nu, nv) = (k1 + 1, k2 + 1);
        let need = (nu + m1 + 1) + (nv + m2 + 1) + nu * nv * 4 + 4;
        if c.remaining() < need {
            return Err(IgesError::new(
                c.line_here(),
                IgesErrorKind::Parameter,
                format!("entity 128 (DE {}): {nu} x {nv} control points of degree ({m1}, {m2}) need {need} more parameters, found {}", 2 * i + 1, c.remaining()),
            ));
        }
        let mut ku = Vec::with_capacity(nu + m1 + 1);
        for _ in 0..nu + m1 + 1 {
            ku.push(c.real("knot (u)")?);
        }
        let mut kv = Vec::with_capacity(nv + m2 + 1);
        for _ in 0..nv + m2 + 1 {
            kv.push(c.real("knot (v)")?);
        }
        let mut w = Vec::with_capacity(nu * nv);
        for _ in 0..nu * nv {
            w.push(c.real("weight")?);
        }
        let mut pts = Vec::with_capacity(nu * nv);
        for _ in 0..nu * nv {
            let p = Vec3::new(c.real("x")?, c.real("y")?, c.real("z")?);
            pts.push(tr.apply(&p));
        }
        let range = [
            [c.real("U0")?, c.real("U1")?],
            [c.real("V0")?, c.real("V1")?],
        ];
        let s = NurbsSurface::new([m1, m2], [nu, nv], [ku, kv], pts, w).map_err(|m| {
            IgesError::new(
                e.line,
                IgesErrorKind::Geometry,
                format!("entity 128 (DE {}): {m}", 2 * i + 1),
            )
        })?;
        Ok((s, range))
    }

    /// A parameter-space curve (110, 100, 126, or a 102 of those) as
    /// trimming curves, in order.
    fn param_curves(
        &self,
        de: usize,
        line: usize,
        depth: usize,
        out: &mut Vec<TrimCurve>,
    ) -> Result<(), IgesError> {
        if depth > DEPTH {
            return Err(IgesError::new(
                line,
                IgesErrorKind::Pointer,
                "composite curves nested deeper than 32 (circular?)",
            ));
        }
        let i = self.expect(de, &[100, 102, 110, 126], line, "parameter-space curve")?;
        let e = &self.entries[i];
        let tr = self.transform(i)?;
        let to2 = |p: Vec3| {
            let q = tr.apply(&p);
            Vec2::new(q.x, q.y)
        };
        let mut c = self.cursor(i);
        let geo = |m: String| {
            IgesError::new(
                e.line,
                IgesErrorKind::Geometry,
                format!("entity {} (DE {de}): {m}", e.kind),
            )
        };
        match e.kind {
            102 => {
                let n = c.count("number of curves", c.remaining())?;
                for _ in 0..n {
                    let l = c.line_here();
                    let p = c.pointer("curve")?;
                    self.param_curves(p, l, depth + 1, out)?;
                }
            }
            110 => {
                let a = Vec3::new(c.real("X1")?, c.real("Y1")?, c.real("Z1")?);
                let b = Vec3::new(c.real("X2")?, c.real("Y2")?, c.real("Z2")?);
                out.push(TrimCurve::line(to2(a), to2(b)).map_err(geo)?);
            }
            100 => {
                let zt = c.real("ZT")?;
                let cen = to2(Vec3::new(c.real("X1")?, c.real("Y1")?, zt));
                let s = to2(Vec3::new(c.real("X2")?, c.real("Y2")?, zt));
                let f = to2(Vec3::new(c.real("X3")?, c.real("Y3")?, zt));
                let r = (s - cen).norm();
                let r2 = (f - cen).norm();
                if r.is_nan() || r <= 0.0 || (r - r2).abs() > 1e-6 * r.max(r2) {
                    return Err(geo(format!("the arc's start and end are at different distances from its centre ({r} and {r2})")));
                }
                let a0 = (s.y - cen.y).atan2(s.x - cen.x);
                let a1 = (f.y - cen.y).atan2(f.x - cen.x);
                // Counter-clockwise in the definition plane; a reflecting
                // transformation makes it clockwise.
                let ccw = tr.r[(0, 0)] * tr.r[(1, 1)] - tr.r[(0, 1)] * tr.r[(1, 0)] >= 0.0;
                let mut sweep = if ccw {
                    (a1 - a0).rem_euclid(std::f64::consts::TAU)
                } else {
                    -(a0 - a1).rem_euclid(std::f64::consts::TAU)
                };
                if sweep.abs() <= 1e-12 {
                    sweep = if ccw {
                        std::f64::consts::TAU
                    } else {
                        -std::f64::consts::TAU
                    };
                }
                out.push(TrimCurve::arc(cen, r, a0, sweep).map_err(geo)?);
            }
            _ => {
                let curve = self.curve126(i, &tr)?;
                let pts = curve.points.iter().map(|p| Vec2::new(p.x, p.y)).collect();
                let c2 =
                    NurbsCurve::new(curve.degree, curve.knots, pts, curve.weights).map_err(geo)?;
                out.push(TrimCurve::Nurbs(c2));
            }
        }
        Ok(())
    }

    /// Entity 126 as a 3D curve moved by `tr`, restricted to its declared
    /// parameter range when that is the knot range.
    fn curve126(&self, i: usize, tr: &Affine) -> Result<NurbsCurve<3>, IgesError> {
        let e = &self.entries[i];
        let mut c = self.cursor(i);
        let k = c.count("K (upper index)", c.remaining())?;
        let m = c.count("M (degree)", 64)?;
        for p in ["PROP1", "PROP2", "PROP3", "PROP4"] {
            c.int(p)?;
        }
        let n = k + 1;
        let need = (n + m + 1) + 4 * n + 2;
        if c.remaining() < need {
            return Err(IgesError::new(
                c.line_here(),
                IgesErrorKind::Parameter,
                format!("entity 126 (DE {}): {n} control points of degree {m} need {need} more parameters, found {}", 2 * i + 1, c.remaining()),
            ));
        }
        let knots = (0..n + m + 1)
            .map(|_| c.real("knot"))
            .collect::<Result<Vec<_>, _>>()?;
        let w = (0..n)
            .map(|_| c.real("weight"))
            .collect::<Result<Vec<_>, _>>()?;
        let mut pts = Vec::with_capacity(n);
        for _ in 0..n {
            pts.push(tr.apply(&Vec3::new(c.real("x")?, c.real("y")?, c.real("z")?)));
        }
        let (v0, v1) = (c.real("V0")?, c.real("V1")?);
        let curve = NurbsCurve::new(m, knots, pts, w).map_err(|msg| {
            IgesError::new(
                e.line,
                IgesErrorKind::Geometry,
                format!("entity 126 (DE {}): {msg}", 2 * i + 1),
            )
        })?;
        let [a, b] = curve.domain();
        if v0 > a + 1e-9 * (b - a).abs() || v1 < b - 1e-9 * (b - a).abs() {
            return Err(IgesError::new(
                e.line,
                IgesErrorKind::Unsupported,
                format!("entity 126 (DE {}): a curve restricted to [{v0}, {v1}] inside its knot range [{a}, {b}] is not supported", 2 * i + 1),
            ));
        }
        Ok(curve)
    }

    /// The loop of the 142 curve-on-surface at `de` on surface entry `surf`.
    fn loop142(&self, de: usize, surf: usize, line: usize, gap: f64) -> Result<Loop, IgesError> {
        let i = self.expect(de, &[142], line, "boundary curve on the surface")?;
        let e = &self.entries[i];
        let mut c = self.cursor(i);
        c.int("creation flag")?;
        let l = c.line_here();
        let sptr = c.pointer("surface")?;
        let bptr = c.pointer("parameter-space curve")?;
        if sptr != 2 * surf + 1 {
            return Err(IgesError::new(
                l,
                IgesErrorKind::Pointer,
                format!(
                    "entity 142 (DE {de}): it lies on DE {sptr}, not on the trimmed surface DE {}",
                    2 * surf + 1
                ),
            ));
        }
        if bptr == 0 {
            return Err(IgesError::new(
                e.line,
                IgesErrorKind::Unsupported,
                format!("entity 142 (DE {de}): only a model-space curve is given; projecting it onto the surface is not supported (export parameter-space curves)"),
            ));
        }
        let mut curves = Vec::new();
        self.param_curves(bptr, l, 0, &mut curves)?;
        Loop::new(curves, gap).map_err(|m| {
            IgesError::new(
                e.line,
                IgesErrorKind::Geometry,
                format!("entity 142 (DE {de}): {m}"),
            )
        })
    }

    /// The loop of the 141 boundary at `de`.
    fn loop141(&self, de: usize, surf: usize, line: usize, gap: f64) -> Result<Loop, IgesError> {
        let i = self.expect(de, &[141], line, "boundary")?;
        let e = &self.entries[i];
        let mut c = self.cursor(i);
        let ty = c.int("type")?;
        c.int("preferred representation")?;
        let l = c.line_here();
        let sptr = c.pointer("surface")?;
        if sptr != 2 * surf + 1 {
            return Err(IgesError::new(
                l,
                IgesErrorKind::Pointer,
                format!(
                    "entity 141 (DE {de}): it bounds DE {sptr}, not the surface DE {}",
                    2 * surf + 1
                ),
            ));
        }
        if ty != 1 {
            return Err(IgesError::new(
                e.line,
                IgesErrorKind::Unsupported,
                format!("entity 141 (DE {de}): type {ty} has model-space curves only; parameter-space curves (type 1) are needed"),
            ));
        }
        let n = c.count("number of curves", c.remaining())?;
        let mut curves = Vec::new();
        for _ in 0..n {
            c.pointer("model-space curve")?;
            let sense = c.int("sense")?;
            let k = c.count("number of parameter-space curves", c.remaining())?;
            let mut these = Vec::new();
            for _ in 0..k {
                let l = c.line_here();
                let p = c.pointer("parameter-space curve")?;
                self.param_curves(p, l, 0, &mut these)?;
            }
            if sense == 2 {
                these = these.iter().rev().map(|t| t.reversed()).collect();
            }
            curves.extend(these);
        }
        Loop::new(curves, gap).map_err(|m| {
            IgesError::new(
                e.line,
                IgesErrorKind::Geometry,
                format!("entity 141 (DE {de}): {m}"),
            )
        })
    }

    /// Every face of the file: trimmed surfaces (144), bounded surfaces
    /// (143) and the B-spline surfaces (128) no other entity uses.
    pub fn faces(&self) -> Result<Vec<ImportedFace>, IgesError> {
        let referenced = self.referenced()?;
        let mut out = Vec::new();
        for (i, e) in self.entries.iter().enumerate() {
            let de = 2 * i + 1;
            let face = match e.kind {
                128 if !referenced.contains(&de) => {
                    let (s, range) = self.surface(i, &Affine::identity())?;
                    let dom = s.domain();
                    let boundary = if range_inside(&range, &dom) && range != dom {
                        Some(Boundary::new(
                            Loop::rectangle(range[0], range[1]),
                            Vec::new(),
                        ))
                    } else {
                        None
                    };
                    Face::new(s, boundary, 1.0)
                }
                144 => {
                    let tr = self.transform(i)?;
                    let mut c = self.cursor(i);
                    let l = c.line_here();
                    let pts = c.pointer("surface")?;
                    let n1 = c.int("N1 (outer boundary flag)")?;
                    let n2 = c.count("N2 (number of holes)", c.remaining())?;
                    let lo = c.line_here();
                    let pto = c.pointer("outer boundary")?;
                    let si = self.expect(pts, &[128], l, "trimmed surface")?;
                    let (s, _) = self.surface(si, &tr)?;
                    let gap = loop_gap(&s);
                    let outer = if n1 == 0 {
                        let [u, v] = s.domain();
                        Loop::rectangle(u, v)
                    } else {
                        self.loop142(pto, si, lo, gap)?
                    };
                    let mut holes = Vec::with_capacity(n2);
                    for _ in 0..n2 {
                        let lh = c.line_here();
                        let p = c.pointer("hole")?;
                        holes.push(self.loop142(p, si, lh, gap)?);
                    }
                    let boundary = if n1 == 0 && holes.is_empty() {
                        None
                    } else {
                        Some(Boundary::new(outer, holes))
                    };
                    Face::new(s, boundary, 1.0)
                }
                143 => {
                    let tr = self.transform(i)?;
                    let mut c = self.cursor(i);
                    c.int("type")?;
                    let l = c.line_here();
                    let sptr = c.pointer("surface")?;
                    let n = c.count("number of boundaries", c.remaining())?;
                    let si = self.expect(sptr, &[128], l, "bounded surface")?;
                    let (s, _) = self.surface(si, &tr)?;
                    let gap = loop_gap(&s);
                    let mut loops = Vec::with_capacity(n);
                    for _ in 0..n {
                        let lb = c.line_here();
                        let p = c.pointer("boundary")?;
                        loops.push(self.loop141(p, si, lb, gap)?);
                    }
                    if loops.is_empty() {
                        Face::new(s, None, 1.0)
                    } else {
                        let outer = loops.remove(0);
                        Face::new(s, Some(Boundary::new(outer, loops)), 1.0)
                    }
                }
                _ => continue,
            };
            out.push(ImportedFace {
                face,
                de,
                kind: e.kind,
                line: e.line,
                label: e.label.clone(),
            });
        }
        Ok(out)
    }

    /// Every model-space curve 126 of the file as a 3D NURBS (with its
    /// transformation), by directory entry number.
    pub fn curves(&self) -> Result<Vec<(usize, NurbsCurve<3>)>, IgesError> {
        let mut out = Vec::new();
        for (i, e) in self.entries.iter().enumerate() {
            if e.kind == 126 {
                let tr = self.transform(i)?;
                out.push((2 * i + 1, self.curve126(i, &tr)?));
            }
        }
        Ok(out)
    }
}

/// Whether `r` lies inside the domain `d`.
fn range_inside(r: &[[f64; 2]; 2], d: &[[f64; 2]; 2]) -> bool {
    (0..2).all(|k| r[k][0] >= d[k][0] && r[k][1] <= d[k][1] && r[k][0] < r[k][1])
}

/// Tolerance on the gaps between consecutive trimming curves: 1e-6 of the
/// parameter domain's size.
fn loop_gap(s: &NurbsSurface) -> f64 {
    let [u, v] = s.domain();
    1e-6 * ((u[1] - u[0]).powi(2) + (v[1] - v[0]).powi(2)).sqrt()
}
