//! `ctc run --solver petsc`: the run under MPI with the tangent solved by
//! PETSc (crate `ctc-petsc`, cargo feature `petsc`).
//!
//! Every rank compiles the deck and runs the same Newton loop; each rank
//! assembles the cells of its METIS part (distributed assembly,
//! `ctc_engine::solve::share`, for the models it accepts; the others are
//! assembled whole by every rank), the internal forces are summed over the
//! ranks, the tangent's rows are shared among the ranks and solved by a
//! PETSc KSP ([`ctc_petsc::PetscSystem`]), whose solution every rank
//! receives whole, so all ranks take the same decisions. Each rank writes
//! its cells' piece of every written increment (`inc_NNNN_p<rank>.vtu`);
//! rank 0 the rest of the results (the `inc_NNNN.pvtu` listing the pieces,
//! results.pvd, histories, contact CSVs, summary.json with a `distributed`
//! section, restart points) and prints; the other ranks print nothing, and
//! all exit with the same status.

use std::path::Path;

/// Without the `petsc` feature: a clear error saying how to get it.
#[cfg(not(feature = "petsc"))]
pub fn run(
    _deck: &Path,
    _output: Option<&Path>,
    _quiet: bool,
    _verbose: bool,
    _restart: bool,
    _options: &[String],
) -> Result<(), String> {
    Err(
        "error: `--solver petsc` needs a ctc built with the `petsc` feature: install PETSc \
         and MPI with `bash petsc/install.sh`, then `cargo build --release --features petsc` \
         and run `mpirun -n N target/release/ctc run DECK --solver petsc`"
            .into(),
    )
}

/// Runs `deck` on every rank of `mpirun`, the tangent solved by PETSc.
#[cfg(feature = "petsc")]
pub fn run(
    deck: &Path,
    output: Option<&Path>,
    quiet: bool,
    verbose: bool,
    restart: bool,
    options: &[String],
) -> Result<(), String> {
    use ctc_engine::model::AnyModel;
    let env = ctc_petsc::Environment::initialize(&options.join(" "))
        .map_err(|e| format!("error: cannot start MPI and PETSc: {e}"))?;
    let rank = env.world().rank();
    ctc_engine::solve::memory::trace("mpi + petsc initialized");
    // every rank compiles the deck; only rank 0 reports the errors
    let model = crate::read(deck)
        .and_then(|source| ctc_lang::compile_any(&source).map_err(|diags| diags.render(&source)));
    ctc_engine::solve::memory::trace("model compiled");
    let dir = output.map_or_else(|| crate::default_output(deck, ""), Path::to_path_buf);
    let r = model.and_then(|model| match &model {
        AnyModel::D2(m) => run_model(&env, m, &dir, quiet, verbose, restart),
        AnyModel::D3(m) => run_model(&env, m, &dir, quiet, verbose, restart),
    });
    // rank 0 prints its diagnosis before any rank leaves: a rank exiting
    // with a failure makes `mpirun` kill the others, and could kill rank 0
    // before its text is out
    if let Err(e) = &r {
        if rank == 0 && !e.is_empty() {
            use std::io::Write;
            eprintln!("{e}");
            let _ = std::io::stderr().flush();
        }
        env.leave_together(std::time::Duration::from_secs(30));
        return Err(String::new());
    }
    r
}

#[cfg(feature = "petsc")]
fn run_model<const D: usize>(
    env: &ctc_petsc::Environment,
    model: &ctc_engine::model::Model<D>,
    dir: &Path,
    quiet: bool,
    verbose: bool,
    restart: bool,
) -> Result<(), String>
where
    nalgebra::Const<D>: ctc_engine::geom::Dimension<D>,
{
    use ctc_petsc::{PetscSystem, SolverChoice};
    if model.tools.iter().any(|t| t.free_rotation.is_some()) {
        // the pilot node of a free tool is attached to no cell: the
        // PETSc layout gives ownership by cells
        return Err(
            "error: `--solver petsc` does not solve tools with `rotation = free` yet; use the \
             default solver"
                .into(),
        );
    }
    let system = PetscSystem::new(env, model, SolverChoice::MumpsLu, "")
        .map_err(|e| format!("error: cannot set up PETSc for this model: {e}"))?;
    ctc_engine::solve::memory::trace("petsc system built");
    // each rank writes its cells' piece of every written increment
    let pieces = ctc_engine::output::Pieces {
        rank: system.rank(),
        ranks: system.ranks(),
        cells: system.cells().to_vec(),
    };
    if system.rank() == 0 {
        return crate::run_model_with(
            model,
            dir,
            quiet,
            verbose,
            restart,
            Some(Box::new(system)),
            Some(pieces),
        );
    }
    // the other ranks: the same run, silent, writing their pieces only
    let from = if restart {
        let path = dir.join(ctc_engine::output::RESTART_FILE);
        let file = ctc_engine::solve::restart::RestartFile::<D>::read(&path)
            .map_err(|e| format!("error: {e}"))?;
        Some(file.checkpoint)
    } else {
        None
    };
    let mut writer = ctc_engine::output::PieceWriter::new(dir, model, pieces);
    let outcome =
        ctc_engine::solve::run_with(model, &mut writer, from.as_ref(), Some(Box::new(system)));
    // the last converged increment's piece also after a failure, as rank 0
    // writes its part of it
    writer.finish().map_err(|e| format!("error: {e}"))?;
    outcome.map(|_| ()).map_err(|e| e.message)
}
