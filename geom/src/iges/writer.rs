//! A small IGES writer (fixed 80-column ASCII form) for the entities the
//! reader supports, so the reader is checked on files the project makes and
//! the examples can ship generated CAD files.

use crate::nurbs::{NurbsCurve, NurbsSurface};
use crate::trim::TrimCurve;
use crate::{Mat3, Vec3};

/// One parameter to write.
#[derive(Debug, Clone, PartialEq)]
enum Value {
    /// Integer.
    Int(i64),
    /// Real.
    Real(f64),
    /// Hollerith string.
    Str(String),
}

/// An entity to write.
#[derive(Debug, Clone, PartialEq)]
struct Item {
    kind: i64,
    form: i64,
    values: Vec<Value>,
    transform: usize,
    /// Physically dependent (status "01"): used by another entity.
    dependent: bool,
    label: String,
}

/// Builds an IGES file entity by entity; each `add_*` returns the new
/// entity's directory entry number (its pointer).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Writer {
    items: Vec<Item>,
    /// Text of the Start section.
    pub start: String,
}

impl Writer {
    /// An empty file with a Start section saying what made it.
    pub fn new(start: &str) -> Self {
        Writer {
            items: Vec::new(),
            start: start.to_string(),
        }
    }

    fn push(&mut self, kind: i64, form: i64, values: Vec<Value>, dependent: bool) -> usize {
        self.items.push(Item {
            kind,
            form,
            values,
            transform: 0,
            dependent,
            label: String::new(),
        });
        2 * self.items.len() - 1
    }

    /// Sets the label (8 characters at most) of entity `de`.
    pub fn label(&mut self, de: usize, label: &str) {
        self.items[de / 2].label = label.chars().take(8).collect();
    }

    /// Applies the transformation entity `t` (from [`Writer::add_transform`])
    /// to entity `de`.
    pub fn set_transform(&mut self, de: usize, t: usize) {
        self.items[de / 2].transform = t;
    }

    /// Entity 124: `x -> r x + t`.
    pub fn add_transform(&mut self, r: &Mat3, t: &Vec3) -> usize {
        let mut v = Vec::new();
        for row in 0..3 {
            for col in 0..3 {
                v.push(Value::Real(r[(row, col)]));
            }
            v.push(Value::Real(t[row]));
        }
        self.push(124, 0, v, true)
    }

    /// Entity 128 (independent: a face by itself unless a trimmed surface
    /// uses it; see [`Writer::add_trimmed`]).
    pub fn add_surface(&mut self, s: &NurbsSurface) -> usize {
        let [nu, nv] = s.counts;
        let [p, q] = s.degree;
        let rational = s.weights.iter().any(|w| *w != s.weights[0]);
        let mut v = vec![
            Value::Int(nu as i64 - 1),
            Value::Int(nv as i64 - 1),
            Value::Int(p as i64),
            Value::Int(q as i64),
            Value::Int(s.closed[0] as i64),
            Value::Int(s.closed[1] as i64),
            Value::Int(!rational as i64),
            Value::Int(0),
            Value::Int(0),
        ];
        v.extend(
            s.knots[0]
                .iter()
                .chain(&s.knots[1])
                .map(|k| Value::Real(*k)),
        );
        v.extend(s.weights.iter().map(|w| Value::Real(*w)));
        for pt in &s.points {
            v.extend([pt.x, pt.y, pt.z].map(Value::Real));
        }
        let [u, w] = s.domain();
        v.extend([u[0], u[1], w[0], w[1]].map(Value::Real));
        self.push(128, 0, v, false)
    }

    /// Entity 126, a curve in 3D (a parameter-space curve has `z = 0`).
    pub fn add_curve(&mut self, c: &NurbsCurve<3>) -> usize {
        let n = c.points.len();
        let rational = c.weights.iter().any(|w| *w != c.weights[0]);
        let planar = c.points.iter().all(|p| p.z == 0.0);
        let mut v = vec![
            Value::Int(n as i64 - 1),
            Value::Int(c.degree as i64),
            Value::Int(planar as i64),
            Value::Int(0),
            Value::Int(!rational as i64),
            Value::Int(0),
        ];
        v.extend(c.knots.iter().map(|k| Value::Real(*k)));
        v.extend(c.weights.iter().map(|w| Value::Real(*w)));
        for p in &c.points {
            v.extend([p.x, p.y, p.z].map(Value::Real));
        }
        let [a, b] = c.domain();
        v.extend([a, b, 0.0, 0.0, 1.0].map(Value::Real));
        self.push(126, 0, v, true)
    }

    /// Entity 110, a line segment.
    pub fn add_line(&mut self, a: &Vec3, b: &Vec3) -> usize {
        let v = [a.x, a.y, a.z, b.x, b.y, b.z].map(Value::Real).to_vec();
        self.push(110, 0, v, true)
    }

    /// Entity 100, a circular arc in the plane `z = zt`, counter-clockwise
    /// from `start` to `end` about `center`.
    pub fn add_arc(&mut self, zt: f64, center: [f64; 2], start: [f64; 2], end: [f64; 2]) -> usize {
        let v = [zt, center[0], center[1], start[0], start[1], end[0], end[1]]
            .map(Value::Real)
            .to_vec();
        self.push(100, 0, v, true)
    }

    /// A trimming curve as a parameter-space entity (110, 100 or 126); a
    /// clockwise arc is written as its 126 rational equivalent.
    pub fn add_trim_curve(&mut self, c: &TrimCurve) -> usize {
        match c {
            TrimCurve::Line { a, b } => {
                self.add_line(&Vec3::new(a.x, a.y, 0.0), &Vec3::new(b.x, b.y, 0.0))
            }
            TrimCurve::Arc {
                center,
                radius,
                start,
                sweep,
            } if *sweep > 0.0 => {
                let s = center + crate::Vec2::new(start.cos(), start.sin()) * *radius;
                let e = center
                    + crate::Vec2::new((start + sweep).cos(), (start + sweep).sin()) * *radius;
                self.add_arc(0.0, [center.x, center.y], [s.x, s.y], [e.x, e.y])
            }
            TrimCurve::Arc {
                center,
                radius,
                start,
                sweep,
            } => {
                let c = arc_nurbs(*center, *radius, *start, *sweep);
                self.add_curve(&c)
            }
            TrimCurve::Nurbs(n) => {
                let pts = n.points.iter().map(|p| Vec3::new(p.x, p.y, 0.0)).collect();
                let c = NurbsCurve::new(n.degree, n.knots.clone(), pts, n.weights.clone())
                    .expect("a valid curve stays valid");
                self.add_curve(&c)
            }
        }
    }

    /// Entity 102, a composite curve of the curves `parts`.
    pub fn add_composite(&mut self, parts: &[usize]) -> usize {
        let mut v = vec![Value::Int(parts.len() as i64)];
        v.extend(parts.iter().map(|p| Value::Int(*p as i64)));
        self.push(102, 0, v, true)
    }

    /// Entity 142: the parameter-space curve `param` on surface `surface`
    /// (no model-space curve; preferred representation: parameter space).
    pub fn add_curve_on_surface(&mut self, surface: usize, param: usize) -> usize {
        let v = vec![
            Value::Int(0),
            Value::Int(surface as i64),
            Value::Int(param as i64),
            Value::Int(0),
            Value::Int(2),
        ];
        self.push(142, 0, v, true)
    }

    /// Entity 144: surface `surface` trimmed by the loop `outer` (a 142, or
    /// `None` for the surface's own boundary) and the holes `holes` (142s).
    /// Marks the surface as used by it.
    pub fn add_trimmed(&mut self, surface: usize, outer: Option<usize>, holes: &[usize]) -> usize {
        self.items[surface / 2].dependent = true;
        let mut v = vec![
            Value::Int(surface as i64),
            Value::Int(outer.is_some() as i64),
            Value::Int(holes.len() as i64),
            Value::Int(outer.unwrap_or(0) as i64),
        ];
        v.extend(holes.iter().map(|h| Value::Int(*h as i64)));
        self.push(144, 0, v, false)
    }

    /// A loop of trimming curves on `surface` as a 142 over a 102 (or over
    /// the single curve).
    pub fn add_loop(&mut self, surface: usize, curves: &[TrimCurve]) -> usize {
        let parts: Vec<usize> = curves.iter().map(|c| self.add_trim_curve(c)).collect();
        let param = if parts.len() == 1 {
            parts[0]
        } else {
            self.add_composite(&parts)
        };
        self.add_curve_on_surface(surface, param)
    }

    /// An entity of any type with integer and real parameters (to write
    /// files with entities the reader does not support, for tests).
    pub fn add_raw(&mut self, kind: i64, ints: &[i64], reals: &[f64], text: Option<&str>) -> usize {
        let mut v: Vec<Value> = ints.iter().map(|i| Value::Int(*i)).collect();
        v.extend(reals.iter().map(|r| Value::Real(*r)));
        if let Some(t) = text {
            v.push(Value::Str(t.to_string()));
        }
        self.push(kind, 0, v, false)
    }

    /// The file's text.
    pub fn finish(&self) -> String {
        let mut out = String::new();
        let nline = |out: &mut String, data: &str, letter: char, seq: usize| {
            out.push_str(&format!("{data:<72}{letter}{seq:>7}\n"));
        };
        // Start.
        let start: Vec<String> = wrap_text(
            if self.start.is_empty() {
                "ctc-geom"
            } else {
                &self.start
            },
            72,
        );
        for (i, l) in start.iter().enumerate() {
            nline(&mut out, l, 'S', i + 1);
        }
        // Global.
        let g = vec![
            Value::Str(",".into()),
            Value::Str(";".into()),
            Value::Str("ctc".into()),
            Value::Str("ctc.igs".into()),
            Value::Str("ctc-geom".into()),
            Value::Str("1".into()),
            Value::Int(32),
            Value::Int(38),
            Value::Int(6),
            Value::Int(308),
            Value::Int(15),
            Value::Str("ctc".into()),
            Value::Real(1.0),
            Value::Int(2),
            Value::Str("MM".into()),
            Value::Int(1),
            Value::Real(1.0),
            Value::Str("20260101.000000".into()),
            Value::Real(1e-9),
            Value::Real(1e4),
            Value::Str("ctc".into()),
            Value::Str("ctc".into()),
            Value::Int(11),
            Value::Int(0),
        ];
        let glines = wrap_values(&g, 72);
        for (i, l) in glines.iter().enumerate() {
            nline(&mut out, l, 'G', i + 1);
        }
        // Parameters first (their line numbers go into the directory).
        let mut plines: Vec<(String, usize)> = Vec::new();
        let mut dir = Vec::new();
        for (k, it) in self.items.iter().enumerate() {
            let de = 2 * k + 1;
            let mut vals = vec![Value::Int(it.kind)];
            vals.extend(it.values.iter().cloned());
            let lines = wrap_values(&vals, 64);
            let first = plines.len() + 1;
            for l in &lines {
                plines.push((l.clone(), de));
            }
            dir.push((first, lines.len()));
        }
        for (k, it) in self.items.iter().enumerate() {
            let (first, count) = dir[k];
            let status = if it.dependent { "00010000" } else { "00000000" };
            let l1 = format!(
                "{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}",
                it.kind, first, 0, 1, 0, 0, it.transform, 0, status
            );
            let l2 = format!(
                "{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}",
                it.kind, 0, 0, count, it.form, "", "", it.label, 0
            );
            nline(&mut out, &l1, 'D', 2 * k + 1);
            nline(&mut out, &l2, 'D', 2 * k + 2);
        }
        for (i, (l, de)) in plines.iter().enumerate() {
            out.push_str(&format!("{l:<64}{de:>8}P{:>7}\n", i + 1));
        }
        let t = format!(
            "S{:>7}G{:>7}D{:>7}P{:>7}",
            start.len(),
            glines.len(),
            2 * self.items.len(),
            plines.len()
        );
        nline(&mut out, &t, 'T', 1);
        out
    }
}

/// The arc as a rational quadratic NURBS (z = 0), pieces of at most 90
/// degrees.
fn arc_nurbs(center: crate::Vec2, r: f64, start: f64, sweep: f64) -> NurbsCurve<3> {
    let n = ((sweep.abs() / std::f64::consts::FRAC_PI_2).ceil() as usize).max(1);
    let d = sweep / n as f64;
    let w = (d / 2.0).cos();
    let mut pts = Vec::new();
    let mut wts = Vec::new();
    let mut knots = vec![0.0; 3];
    let at =
        |a: f64, s: f64| Vec3::new(center.x + s * r * a.cos(), center.y + s * r * a.sin(), 0.0);
    for i in 0..n {
        let a0 = start + d * i as f64;
        if i == 0 {
            pts.push(at(a0, 1.0));
            wts.push(1.0);
        }
        pts.push(at(a0 + d / 2.0, 1.0 / w));
        wts.push(w);
        pts.push(at(a0 + d, 1.0));
        wts.push(1.0);
        if i + 1 < n {
            let k = (i + 1) as f64 / n as f64;
            knots.extend([k, k]);
        }
    }
    knots.extend([1.0; 3]);
    NurbsCurve::new(2, knots, pts, wts).expect("an arc is a valid NURBS")
}

/// Formats values as free-format parameters, wrapped at `width` columns
/// without splitting a value, ended by `;`.
fn wrap_values(values: &[Value], width: usize) -> Vec<String> {
    let toks: Vec<String> = values
        .iter()
        .enumerate()
        .map(|(i, v)| {
            let s = match v {
                Value::Int(i) => i.to_string(),
                Value::Real(r) => format_real(*r),
                Value::Str(s) => format!("{}H{s}", s.len()),
            };
            s + if i + 1 == values.len() { ";" } else { "," }
        })
        .collect();
    let mut lines = vec![String::new()];
    for t in toks {
        if lines.last().unwrap().len() + t.len() > width {
            lines.push(String::new());
        }
        lines.last_mut().unwrap().push_str(&t);
    }
    lines
}

/// A real with 17 significant digits and an explicit decimal point
/// (`1.5E0`), so it reads back to the same `f64`.
fn format_real(r: f64) -> String {
    let s = format!("{r:.16E}");
    // Trim trailing zeros of the mantissa (keep one digit after the point).
    let (m, e) = s.split_once('E').unwrap_or((&s, "0"));
    let m = if m.contains('.') {
        let t = m.trim_end_matches('0');
        if t.ends_with('.') {
            format!("{t}0")
        } else {
            t.to_string()
        }
    } else {
        m.to_string()
    };
    format!("{m}E{e}")
}

fn wrap_text(t: &str, width: usize) -> Vec<String> {
    let mut v = Vec::new();
    let mut cur = String::new();
    for ch in t.chars().filter(|c| c.is_ascii() && *c != '\n') {
        if cur.len() == width {
            v.push(std::mem::take(&mut cur));
        }
        cur.push(ch);
    }
    v.push(cur);
    v
}
