//! `ctc._ctc`: the compiled part of the Python package `ctc` (the Python
//! layer `python/ctc/__init__.py` turns its lists into NumPy arrays and
//! reads `summary.json` and `history.csv`). It runs exactly what `ctc check`
//! and `ctc run` run: `ctc_lang::check` / `compile_any`, then
//! `ctc_engine::solve::run_from` into a `ResultWriter`, the dimension chosen
//! once from the compiled model.

use ctc_engine::geom::Dimension;
use ctc_engine::model::{AnyModel, Model};
use ctc_engine::output::ResultWriter;
use ctc_engine::solve::{restart::Checkpoint, IncrementView, IterationInfo, Observer};
use ctc_lang::diagnostics::{LineIndex, Severity};
use ctc_lang::Source;
use nalgebra::Const;
use pyo3::exceptions::PyOSError;
use pyo3::prelude::*;
use std::path::{Path, PathBuf};

pyo3::create_exception!(
    _ctc,
    DeckError,
    pyo3::exceptions::PyValueError,
    "A deck with errors: the message is every diagnostic, rendered as `ctc check` prints them."
);

/// One diagnostic as a tuple: severity (`error` or `warning`), message,
/// file, line (1-based), column (1-based), the rendered text with its caret.
type PyDiagnostic = (String, String, String, usize, usize, String);

/// The deck from a path or from text (`name` labels it and resolves its
/// relative mesh files and includes).
fn source(path: Option<&str>, text: Option<&str>, name: Option<&str>) -> PyResult<Source> {
    match (path, text) {
        (_, Some(t)) => Ok(Source::new(name.or(path).unwrap_or("deck.ctc"), t)),
        (Some(p), None) => {
            Source::read(p).map_err(|e| PyOSError::new_err(format!("cannot read deck `{p}`: {e}")))
        }
        (None, None) => Err(pyo3::exceptions::PyTypeError::new_err(
            "give a deck path or text=",
        )),
    }
}

/// Every diagnostic of a deck, in deck order.
#[pyfunction]
#[pyo3(signature = (path=None, text=None, name=None))]
fn check(path: Option<&str>, text: Option<&str>, name: Option<&str>) -> PyResult<Vec<PyDiagnostic>> {
    let src = source(path, text, name)?;
    let compiled = ctc_lang::check(&src);
    Ok(compiled
        .diagnostics
        .0
        .iter()
        .map(|d| {
            let (file, offset) = src.locate(d.span.start);
            let f = &src.files[file];
            let (line, col) = LineIndex::new(&f.text).line_col(offset);
            let severity = match d.severity {
                Severity::Error => "error",
                Severity::Warning => "warning",
            };
            (
                severity.to_string(),
                d.message.clone(),
                f.path.display().to_string(),
                line,
                col,
                d.render(&src),
            )
        })
        .collect())
}

/// What a run returns to Python: completed, the failure message, the output
/// directory, the dimension, node coordinates, and per converged increment
/// its time, displacements and reactions.
type PyRun = (
    bool,
    Option<String>,
    String,
    usize,
    Vec<Vec<f64>>,
    Vec<f64>,
    Vec<Vec<Vec<f64>>>,
    Vec<Vec<Vec<f64>>>,
);

/// Writes results as `ctc run` does and keeps each converged increment's
/// nodal displacements and reactions for Python.
struct Capture<const D: usize> {
    writer: ResultWriter<D>,
    times: Vec<f64>,
    displacement: Vec<Vec<Vec<f64>>>,
    reaction: Vec<Vec<Vec<f64>>>,
}

impl<const D: usize> Observer<D> for Capture<D>
where
    Const<D>: Dimension<D>,
{
    fn iteration(&mut self, info: &IterationInfo) {
        self.writer.iteration(info)
    }
    fn converged(&mut self, view: &IncrementView<'_, D>) -> Result<(), String> {
        self.times.push(view.time);
        self.displacement
            .push(view.displacement.iter().map(|u| u.to_vec()).collect());
        self.reaction
            .push(view.reaction.iter().map(|r| r.to_vec()).collect());
        self.writer.converged(view)
    }
    fn cutback(&mut self, reason: &str, new_dt: f64) {
        self.writer.cutback(reason, new_dt)
    }
    fn warning(&mut self, message: &str) {
        self.writer.warning(message)
    }
    fn wants_checkpoint(&self) -> bool {
        self.writer.wants_checkpoint()
    }
    fn checkpoint(&mut self, checkpoint: &Checkpoint<D>) -> Result<(), String> {
        self.writer.checkpoint(checkpoint)
    }
}

fn run_model<const D: usize>(model: &Model<D>, dir: &Path) -> Result<PyRun, String>
where
    Const<D>: Dimension<D>,
{
    let writer = ResultWriter::create(dir, model)
        .map_err(|e| format!("cannot create output directory `{}`: {e}", dir.display()))?;
    let mut capture = Capture {
        writer,
        times: Vec::new(),
        displacement: Vec::new(),
        reaction: Vec::new(),
    };
    let outcome = ctc_engine::solve::run_from(model, &mut capture, None);
    let summary = match &outcome {
        Ok(s) => s.clone(),
        Err(e) => e.summary.clone(),
    };
    capture
        .writer
        .finish(&summary)
        .map_err(|e| format!("cannot write summary.json: {e}"))?;
    let coordinates = model.mesh.nodes.iter().map(|p| p.to_vec()).collect();
    Ok((
        outcome.is_ok(),
        outcome.err().map(|e| e.message),
        dir.display().to_string(),
        D,
        coordinates,
        capture.times,
        capture.displacement,
        capture.reaction,
    ))
}

/// Compiles and runs a deck into `out` (default `out/<deck stem>`, as `ctc
/// run`). A deck with errors raises `DeckError`; a run that stops early
/// returns `completed = False` with its diagnosis (the converged
/// increments are written, as `ctc run` writes them).
#[pyfunction]
#[pyo3(signature = (path=None, text=None, name=None, out=None))]
fn run(
    py: Python<'_>,
    path: Option<&str>,
    text: Option<&str>,
    name: Option<&str>,
    out: Option<&str>,
) -> PyResult<PyRun> {
    let src = source(path, text, name)?;
    let model = ctc_lang::compile_any(&src).map_err(|d| DeckError::new_err(d.render(&src)))?;
    let dir = out.map(PathBuf::from).unwrap_or_else(|| {
        let stem = src
            .path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "run".into());
        PathBuf::from("out").join(stem)
    });
    // the solve holds no Python object: other Python threads may run
    let result = py.allow_threads(|| match &model {
        AnyModel::D2(m) => run_model(m, &dir),
        AnyModel::D3(m) => run_model(m, &dir),
    });
    result.map_err(PyOSError::new_err)
}

/// The compiled module.
#[pymodule]
fn _ctc(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(check, m)?)?;
    m.add_function(wrap_pyfunction!(run, m)?)?;
    m.add("DeckError", m.py().get_type::<DeckError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
