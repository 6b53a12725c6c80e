//! meshio cross-checks through pyo3 (feature `meshio`, issue 9): ctc's VTU
//! output read back by Python's meshio must equal what ctc wrote; a
//! corrupted VTU must be detected; ctc's gmsh reader must agree with
//! meshio on every test mesh of `engine/tests/data`.
//!
//! Run: `pip install meshio && cargo test -p ctc-verification --features meshio`
#![cfg(feature = "meshio")]

use ctc_engine::output::ResultWriter;
use ctc_engine::solve::{run, IncrementView, IterationInfo, Observer};
use ctc_verification::capture::Capture;
use ctc_verification::deck::compile_text;
use ctc_verification::meshio::{compare_gmsh, compare_vtu, WrittenState};
use std::path::{Path, PathBuf};

/// Writes results and keeps the final state.
struct Both {
    writer: ResultWriter,
    capture: Capture,
}

impl Observer for Both {
    fn iteration(&mut self, info: &IterationInfo) {
        self.writer.iteration(info);
        self.capture.iteration(info);
    }
    fn converged(&mut self, view: &IncrementView<'_>) -> Result<(), String> {
        self.writer.converged(view)?;
        self.capture.converged(view)
    }
}

/// Runs the rigid-cylinder case (all output fields, VTU `format`) into
/// `dir`; returns the model, the final state and the path of the last VTU
/// file.
fn rigid_cylinder_run(
    dir: &Path,
    format: &str,
) -> (
    ctc_engine::model::Model,
    ctc_verification::capture::FinalState,
    PathBuf,
) {
    let deck = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/rigid_cylinder_block.ctc");
    let text = std::fs::read_to_string(&deck).unwrap().replace(
        "fields = [displacement, stress, contact]",
        &format!("fields = [displacement, stress, strain, von_mises, reaction, contact]\n  format = {format}"),
    );
    assert!(
        text.contains("reaction, contact]"),
        "deck output block changed"
    );
    let model = compile_text(&deck, &text).unwrap();
    let mut obs = Both {
        writer: ResultWriter::create(dir, &model).unwrap(),
        capture: Capture::default(),
    };
    let summary = run(&model, &mut obs).unwrap();
    obs.writer.finish(&summary).unwrap();
    let state = obs.capture.last.unwrap();
    let vtu = dir.join(format!("inc_{:04}.vtu", state.increment));
    assert!(vtu.is_file(), "{} not written", vtu.display());
    (model, state, vtu)
}

#[test]
fn meshio_reads_back_ctc_vtu_rigid_cylinder() {
    for format in ["binary", "ascii"] {
        meshio_reads_back(format);
    }
}

/// meshio reads the VTU of `format` (binary: appended raw zlib) exactly.
fn meshio_reads_back(format: &str) {
    let dir = tempfile::tempdir().unwrap();
    let (model, state, vtu) = rigid_cylinder_run(dir.path(), format);
    let head = std::fs::read(&vtu).unwrap();
    let appended = head.windows(13).any(|w| w == b"<AppendedData");
    assert_eq!(appended, format == "binary", "{format}");
    let check = compare_vtu(
        &vtu,
        &WrittenState {
            model: &model,
            displacement: &state.displacement,
            reaction: Some(&state.reaction),
            contact: Some(&state.contact),
        },
    )
    .unwrap();
    eprintln!("{format}: compared {} values", check.compared);
    assert!(check.passed(), "{:#?}", check.mismatches);
    // points x3, cells, displacement x2, reaction x2, 3 contact fields
    let n = model.mesh.nodes.len();
    assert_eq!(
        check.compared,
        3 * n + model.mesh.cells.len() + 4 * n + 3 * n
    );
}

#[test]
fn meshio_detects_corrupted_vtu() {
    let dir = tempfile::tempdir().unwrap();
    // the text of an ASCII file is edited
    let (model, state, vtu) = rigid_cylinder_run(dir.path(), "ascii");
    let text = std::fs::read_to_string(&vtu).unwrap();
    // Change one displacement value of the last node in the file's text.
    let start = text.find("Name=\"displacement\"").unwrap();
    let end = start + text[start..].find("</DataArray>").unwrap();
    let block = &text[start..end];
    let last_line = block.trim_end().rsplit('\n').next().unwrap();
    let first_number = last_line.split_whitespace().next().unwrap();
    let value: f64 = first_number.parse().unwrap();
    let corrupted_line = last_line.replacen(first_number, &format!("{}", value + 1e-9), 1);
    let corrupted = format!(
        "{}{}{}",
        &text[..start],
        block.replacen(last_line, &corrupted_line, 1),
        &text[end..]
    );
    assert_ne!(corrupted, text);
    let bad = dir.path().join("corrupted.vtu");
    std::fs::write(&bad, corrupted).unwrap();
    let written = WrittenState {
        model: &model,
        displacement: &state.displacement,
        reaction: None,
        contact: None,
    };
    let check = compare_vtu(&bad, &written).unwrap();
    assert_eq!(check.mismatches.len(), 1, "{:#?}", check.mismatches);
    assert!(
        check.mismatches[0].starts_with("displacement["),
        "{:?}",
        check.mismatches
    );
    // A swapped cell connectivity is detected too.
    let swapped = text.clone();
    let conn = swapped
        .find("Name=\"connectivity\"")
        .expect("connectivity array");
    let body_start = conn + swapped[conn..].find('>').unwrap() + 1;
    let nums: Vec<&str> = swapped[body_start..].split_whitespace().take(2).collect();
    let mut broken = swapped.clone();
    let first = body_start + swapped[body_start..].find(nums[0]).unwrap();
    broken.replace_range(first..first + nums[0].len(), nums[1]);
    std::fs::write(&bad, broken).unwrap();
    let check = compare_vtu(&bad, &written).unwrap();
    assert!(
        check.mismatches.iter().any(|m| m.starts_with("cell 0:")),
        "{:#?}",
        check.mismatches
    );
    // The intact file still passes with the same comparison.
    assert!(compare_vtu(&vtu, &written).unwrap().passed());
}

#[test]
fn meshio_reads_gmsh_test_meshes_like_ctc() {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("../engine/tests/data");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&data)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "msh"))
        .collect();
    files.sort();
    assert!(
        files.len() >= 6,
        "test meshes missing in {}",
        data.display()
    );
    for f in files {
        let mesh = ctc_engine::mesh::gmsh::parse(&std::fs::read_to_string(&f).unwrap())
            .unwrap_or_else(|e| panic!("{}: {e:?}", f.display()));
        let check = compare_gmsh(&f, &mesh).unwrap();
        eprintln!("{}: {} values compared", f.display(), check.compared);
        assert!(check.passed(), "{}: {:#?}", f.display(), check.mismatches);
        assert!(check.compared >= mesh.nodes.len() + mesh.cells.len());
    }
}
