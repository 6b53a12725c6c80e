//! Output tests: the files of a run exist, VTU and PVD parse as XML with the
//! right sizes, the PVD index is valid after every increment, history.csv
//! and summary.json hold the run, and a failed run still leaves its last
//! converged increment and a summary.

mod support;

use ctc_engine::model::*;
use ctc_engine::output::vtu_read::{Section, Vtu};
use ctc_engine::output::ResultWriter;
use ctc_engine::solve::{run, IncrementView, Observer};
use std::path::Path;
use support::*;

/// A parsed XML element.
#[derive(Debug, Default)]
struct Element {
    name: String,
    attrs: Vec<(String, String)>,
    children: Vec<Element>,
    text: String,
}

impl Element {
    fn attr(&self, k: &str) -> Option<&str> {
        self.attrs.iter().find(|a| a.0 == k).map(|a| a.1.as_str())
    }
    fn find_all<'a>(&'a self, name: &str, out: &mut Vec<&'a Element>) {
        if self.name == name {
            out.push(self);
        }
        for c in &self.children {
            c.find_all(name, out);
        }
    }
    fn all(&self, name: &str) -> Vec<&Element> {
        let mut v = Vec::new();
        self.find_all(name, &mut v);
        v
    }
}

/// A strict little XML parser (declaration, comments, elements, attributes,
/// text): enough to reject anything malformed that our writers could emit.
fn parse_xml(s: &str) -> Result<Element, String> {
    let b = s.as_bytes();
    let mut i = 0;
    let mut stack: Vec<Element> = vec![Element::default()];
    while i < b.len() {
        if b[i] == b'<' {
            if s[i..].starts_with("<?") {
                i += s[i..].find("?>").ok_or("unterminated declaration")? + 2;
            } else if s[i..].starts_with("<!--") {
                let end = s[i + 4..].find("-->").ok_or("unterminated comment")?;
                if s[i + 4..i + 4 + end].contains("--") {
                    return Err("`--` inside a comment".into());
                }
                i += 4 + end + 3;
            } else if s[i..].starts_with("</") {
                let end = i + s[i..].find('>').ok_or("unterminated end tag")?;
                let name = s[i + 2..end].trim();
                let el = stack.pop().ok_or("unbalanced end tag")?;
                if el.name != name {
                    return Err(format!("end tag </{name}> closes <{}>", el.name));
                }
                stack
                    .last_mut()
                    .ok_or("end tag without parent")?
                    .children
                    .push(el);
                i = end + 1;
            } else {
                let end = i + s[i..].find('>').ok_or("unterminated tag")?;
                let mut body = &s[i + 1..end];
                let selfclose = body.ends_with('/');
                if selfclose {
                    body = &body[..body.len() - 1];
                }
                let name_end = body.find(char::is_whitespace).unwrap_or(body.len());
                let mut el = Element {
                    name: body[..name_end].to_string(),
                    ..Default::default()
                };
                if el.name.is_empty() || !el.name.chars().all(|c| c.is_alphanumeric() || c == '_') {
                    return Err(format!("bad element name `{}`", el.name));
                }
                let mut rest = body[name_end..].trim_start();
                while !rest.is_empty() {
                    let eq = rest
                        .find('=')
                        .ok_or(format!("attribute without value in <{}>", el.name))?;
                    let key = rest[..eq].trim().to_string();
                    let after = rest[eq + 1..].trim_start();
                    if !after.starts_with('"') {
                        return Err(format!("unquoted attribute {key}"));
                    }
                    let close = after[1..].find('"').ok_or("unterminated attribute")?;
                    let val = after[1..1 + close].to_string();
                    if val.contains('<') {
                        return Err("`<` in attribute".into());
                    }
                    el.attrs.push((key, val));
                    rest = after[close + 2..].trim_start();
                }
                if selfclose {
                    stack.last_mut().unwrap().children.push(el);
                } else {
                    stack.push(el);
                }
                i = end + 1;
            }
        } else {
            let next = s[i..].find('<').map_or(b.len(), |k| i + k);
            let text = &s[i..next];
            if text.contains('&') || text.contains('>') {
                return Err("unescaped character in text".into());
            }
            if stack.len() == 1 && !text.trim().is_empty() {
                return Err("text outside the root element".into());
            }
            stack.last_mut().unwrap().text.push_str(text);
            i = next;
        }
    }
    if stack.len() != 1 {
        return Err(format!("{} unclosed elements", stack.len() - 1));
    }
    let mut doc = stack.pop().unwrap();
    if doc.children.len() != 1 {
        return Err(format!("{} root elements", doc.children.len()));
    }
    Ok(doc.children.pop().unwrap())
}

/// Parses a VTU file and checks its structure against the model; returns
/// the names of its point data arrays. The XML part (before the appended
/// binary data, if any) must be well-formed; every array is decoded by
/// `vtu_read` and must have the model's sizes and finite values.
fn check_vtu(path: &Path, model: &Model) -> Vec<String> {
    let bytes = std::fs::read(path).unwrap();
    let xml = match bytes.windows(13).position(|w| w == b"<AppendedData") {
        Some(end) => format!("{}</VTKFile>", std::str::from_utf8(&bytes[..end]).unwrap()),
        None => String::from_utf8(bytes.clone()).unwrap(),
    };
    let root = parse_xml(&xml).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert_eq!(root.name, "VTKFile");
    assert_eq!(root.attr("type"), Some("UnstructuredGrid"));
    let piece = root.all("Piece");
    assert_eq!(piece.len(), 1);
    let (nn, nc) = (model.mesh.nodes.len(), model.mesh.cells.len());
    assert_eq!(
        piece[0].attr("NumberOfPoints"),
        Some(nn.to_string().as_str())
    );
    assert_eq!(
        piece[0].attr("NumberOfCells"),
        Some(nc.to_string().as_str())
    );
    let vtu = Vtu::read(&bytes).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert_eq!((vtu.points, vtu.cells), (nn, nc));
    for a in vtu
        .arrays
        .iter()
        .filter(|a| a.section == Section::PointData)
    {
        assert_eq!(a.values.len(), a.components * nn, "array {}", a.name);
        assert!(a.values.iter().all(|x| x.is_finite()), "array {}", a.name);
    }
    let len = |s: Section, name: &str| vtu.array(s, name).unwrap().values.len();
    assert_eq!(len(Section::Points, "coordinates"), 3 * nn);
    let conn: usize = model.mesh.cells.iter().map(|c| c.kind.node_count()).sum();
    assert_eq!(len(Section::Cells, "connectivity"), conn);
    assert_eq!(len(Section::Cells, "offsets"), nc);
    assert_eq!(len(Section::Cells, "types"), nc);
    vtu.names(Section::PointData)
        .into_iter()
        .map(String::from)
        .collect()
}

/// Parses results.pvd: the listed (time, file) pairs.
fn check_pvd(dir: &Path) -> Vec<(f64, String)> {
    let text = std::fs::read_to_string(dir.join("results.pvd")).unwrap();
    let root = parse_xml(&text).unwrap();
    assert_eq!(root.attr("type"), Some("Collection"));
    root.all("DataSet")
        .iter()
        .map(|d| {
            let f = d.attr("file").unwrap().to_string();
            assert!(dir.join(&f).exists(), "{f} listed but missing");
            (d.attr("timestep").unwrap().parse().unwrap(), f)
        })
        .collect()
}

/// Forwards to a ResultWriter and checks the PVD index after each increment.
struct Checking {
    writer: ResultWriter,
    pvd_sizes: Vec<usize>,
}

impl Observer for Checking {
    fn converged(&mut self, v: &IncrementView<'_>) -> Result<(), String> {
        self.writer.converged(v)?;
        let entries = if self.writer.dir().join("results.pvd").exists() {
            check_pvd(self.writer.dir())
        } else {
            Vec::new()
        };
        self.pvd_sizes.push(entries.len());
        Ok(())
    }
}

/// A clamped plate pulled in y, 4 increments.
fn plate() -> Model {
    let (nx, ny) = (5, 3);
    let mesh = grid(nx, ny, [0.0, 0.0], [2.5, 1.5], 0.2, 11, true);
    let mut m = one_body(
        AnalysisKind::PlaneStrain,
        mesh,
        1000.0,
        0.3,
        Formulation::Full,
    );
    let left: Vec<usize> = (0..=ny).map(|j| grid_node(nx, 0, j)).collect();
    let right: Vec<usize> = (0..=ny).map(|j| grid_node(nx, nx, j)).collect();
    m.constraints = vec![fix(left.clone(), 0, 0.0), fix(left.clone(), 1, 0.0)];
    m.loads = vec![Load::NodalForce {
        label: "pull".into(),
        nodes: right.clone(),
        component: 1,
        value: TimeFunction::Ramp {
            t0: 0.0,
            t1: 1.0,
            v0: 0.0,
            v1: 0.5,
        },
    }];
    m.steps = vec![step(4)];
    m.output = OutputRequest {
        every: 2,
        fields: vec![
            Field::Displacement,
            Field::Stress,
            Field::Strain,
            Field::VonMises,
            Field::Reaction,
        ],
        history: vec![
            HistoryRequest::Reaction {
                label: "reaction(plate.left)".into(),
                nodes: left,
            },
            HistoryRequest::Displacement {
                label: "displacement(plate.right)".into(),
                nodes: right,
            },
        ],
        ..OutputRequest::default()
    };
    m
}

#[test]
fn output_files_vtu_pvd_history_summary() {
    let dir = tempfile::tempdir().unwrap();
    let m = plate();
    let mut obs = Checking {
        writer: ResultWriter::create(dir.path(), &m).unwrap(),
        pvd_sizes: vec![],
    };
    let summary = run(&m, &mut obs).unwrap();
    obs.writer.finish(&summary).unwrap();
    // every = 2: increments 2 and 4 written; the index is valid after each increment
    assert_eq!(obs.pvd_sizes, vec![0, 1, 1, 2]);
    assert!(!dir.path().join("inc_0001.vtu").exists());
    assert!(!dir.path().join("inc_0003.vtu").exists());
    let pvd = check_pvd(dir.path());
    assert_eq!(
        pvd,
        vec![
            (0.5, "inc_0002.vtu".to_string()),
            (1.0, "inc_0004.vtu".to_string())
        ]
    );
    let names = check_vtu(&dir.path().join("inc_0004.vtu"), &m);
    assert_eq!(
        names,
        ["displacement", "stress", "strain", "von_mises", "reaction"]
    );
    let bytes = std::fs::read(dir.path().join("inc_0004.vtu")).unwrap();
    let vtu = String::from_utf8_lossy(&bytes);
    assert!(vtu.contains("ComponentName0=\"xx\"") && vtu.contains("ComponentName3=\"xy\""));
    assert!(vtu.contains("format=\"appended\"") && !vtu.contains("format=\"ascii\""));
    // history: header + one row per increment; reactions balance the pull (4 x 0.5)
    let hist = std::fs::read_to_string(dir.path().join("history.csv")).unwrap();
    let lines: Vec<&str> = hist.lines().collect();
    assert_eq!(
        lines[0],
        "time,reaction(plate.left)_x,reaction(plate.left)_y,displacement(plate.right)_x,displacement(plate.right)_y"
    );
    assert_eq!(lines.len(), 5);
    let last: Vec<f64> = lines[4].split(',').map(|v| v.parse().unwrap()).collect();
    assert_eq!(last[0], 1.0);
    assert!((last[2] + 2.0).abs() < 1e-9, "{last:?}");
    assert!(last[4] > 0.0);
    let mid: Vec<f64> = lines[2].split(',').map(|v| v.parse().unwrap()).collect();
    assert!(
        (mid[4] - 0.5 * last[4]).abs() < 1e-12 * last[4],
        "linear history"
    );
    // summary
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("summary.json")).unwrap())
            .unwrap();
    assert_eq!(json["completed"], true);
    assert_eq!(json["increments"].as_array().unwrap().len(), 4);
    assert_eq!(json["linear_solver"], "cholesky");
    assert!(json["timings"]["factorization"].as_f64().unwrap() >= 0.0);
    // the factorization's size: L holds at least the lower triangle
    let (nnz, free) = (
        json["matrix_nonzeros"].as_u64().unwrap(),
        json["free_dofs"].as_u64().unwrap(),
    );
    let factor = json["factor_nonzeros"].as_u64().unwrap();
    assert!(factor >= (nnz + free) / 2, "{factor} vs {nnz}");
    assert!(json["factor_fill"].as_f64().unwrap() >= 1.0);
    assert!(json["factor_bytes"].as_u64().unwrap() >= 8 * factor);
    // the process holds at least the factorization (Linux reports it)
    if cfg!(target_os = "linux") {
        assert!(json["peak_memory_bytes"].as_u64().unwrap() >= 8 * factor);
    }
    // no temporary files left behind
    for e in std::fs::read_dir(dir.path()).unwrap() {
        let name = e.unwrap().file_name().into_string().unwrap();
        assert!(!name.ends_with(".tmp"), "{name}");
    }
}

/// The same run written in binary (the default) and in ASCII: every array
/// reads back to the same bits, and the binary file is smaller.
#[test]
fn binary_and_ascii_vtu_hold_the_same_values() {
    let mut sizes = Vec::new();
    let mut files = Vec::new();
    for format in [VtuFormat::Binary, VtuFormat::Ascii] {
        let dir = tempfile::tempdir().unwrap();
        let mut m = plate();
        m.output.format = format;
        let mut w = ResultWriter::create(dir.path(), &m).unwrap();
        let s = run(&m, &mut w).unwrap();
        w.finish(&s).unwrap();
        let path = dir.path().join("inc_0004.vtu");
        check_vtu(&path, &m);
        sizes.push(std::fs::metadata(&path).unwrap().len());
        files.push(Vtu::read_file(&path).unwrap());
    }
    let (binary, ascii) = (&files[0], &files[1]);
    assert_eq!(binary.arrays.len(), ascii.arrays.len());
    for (b, a) in binary.arrays.iter().zip(&ascii.arrays) {
        assert_eq!(
            (b.format.as_str(), a.format.as_str()),
            ("appended", "ascii")
        );
        assert_eq!(
            (&b.name, b.section, b.components),
            (&a.name, a.section, a.components)
        );
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&b.values), bits(&a.values), "{}", b.name);
    }
    assert_eq!(binary.field("TIME").unwrap().values, [1.0]);
    assert!(
        sizes[0] < sizes[1],
        "binary {} B, ascii {} B",
        sizes[0],
        sizes[1]
    );
}

#[test]
fn output_after_failure_keeps_last_converged_increment_and_summary() {
    let dir = tempfile::tempdir().unwrap();
    let mut m = plate();
    m.output.every = 100;
    // the second step pulls further (the first one is unchanged)
    let Load::NodalForce { nodes, .. } = m.loads[0].clone() else {
        unreachable!()
    };
    m.loads.push(Load::NodalForce {
        label: "pull more".into(),
        nodes,
        component: 1,
        value: TimeFunction::Ramp {
            t0: 1.0,
            t1: 2.0,
            v0: 0.0,
            v1: 0.5,
        },
    });
    m.steps = vec![step(2), {
        let mut s = step(2);
        s.name = "impossible".into();
        s.t_start = 1.0;
        s.t_end = 2.0;
        // one iteration whose next correction must vanish exactly: a
        // correction at round-off (1e-16) never meets 1e-30
        s.newton.tol_displacement = 1e-30;
        s.newton.max_iter = 1;
        s.min_fraction = 0.5;
        s
    }];
    let mut w = ResultWriter::create(dir.path(), &m).unwrap();
    let e = run(&m, &mut w).unwrap_err();
    assert!(e.message.contains("impossible"));
    w.finish(&e.summary).unwrap();
    // the last converged increment (end of step 1) is written at finish
    assert_eq!(
        check_pvd(dir.path()),
        vec![(1.0, "inc_0002.vtu".to_string())]
    );
    check_vtu(&dir.path().join("inc_0002.vtu"), &m);
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("summary.json")).unwrap())
            .unwrap();
    assert_eq!(json["completed"], false);
    assert!(json["failure"].as_str().unwrap().contains("impossible"));
}

#[test]
fn axisymmetric_outputs_say_forces_are_totals_over_two_pi() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = grid(2, 2, [0.0, 0.0], [1.0, 1.0], 0.0, 1, false);
    let mut m = one_body(
        AnalysisKind::Axisymmetric,
        mesh,
        1.0,
        0.3,
        Formulation::Full,
    );
    m.constraints = vec![
        fix((0..3).collect(), 1, 0.0),
        fix((6..9).collect(), 1, -0.01),
    ];
    m.output.fields = vec![Field::Displacement, Field::Contact];
    let mut w = ResultWriter::create(dir.path(), &m).unwrap();
    let s = run(&m, &mut w).unwrap();
    w.finish(&s).unwrap();
    let bytes = std::fs::read(dir.path().join("inc_0001.vtu")).unwrap();
    assert!(String::from_utf8_lossy(&bytes).contains("totals over the full 2*pi"));
    let names = check_vtu(&dir.path().join("inc_0001.vtu"), &m);
    assert_eq!(
        names,
        [
            "displacement",
            "contact_gap",
            "contact_pressure",
            "contact_status"
        ]
    );
    // no contact pair: every node is "not a slave" (-1)
    let read = Vtu::read(&bytes).unwrap();
    let status = &read.point("contact_status").unwrap().values;
    assert!(status.iter().all(|&s| s == -1.0), "{status:?}");
    let summary = std::fs::read_to_string(dir.path().join("summary.json")).unwrap();
    assert!(summary.contains("totals over the full 2*pi"));
}

#[test]
fn xml_checker_rejects_malformed_documents() {
    assert!(parse_xml("<a><b x=\"1\"/></a>").is_ok());
    for bad in [
        "<a><b></a>",
        "<a x=1></a>",
        "<a></a><b/>",
        "<a>1 & 2</a>",
        "<a><!-- x -- y --></a>",
        "<a>",
        "text<a/>",
    ] {
        assert!(parse_xml(bad).is_err(), "accepted {bad}");
    }
}
