//! `ctc`: check, run, verify and benchmark `.ctc` contact decks.

mod heap;
mod petsc_run;
mod progress;
mod sweep;

use clap::{Parser, Subcommand};
use ctc_engine::model::AnyModel;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Nonlinear finite-element simulation of solids in contact.
#[derive(Parser, Debug)]
#[command(name = "ctc", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// The linear solver of `ctc run`.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
enum Solver {
    /// faer sparse direct (Cholesky, L D L^T, LU), serial.
    Faer,
    /// PETSc KSP/PC over MPI.
    Petsc,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Parse and validate a deck; print every error at once.
    Check {
        /// The `.ctc` deck.
        deck: PathBuf,
        /// Print the lowered plan: what the scene contains and what it leaves out.
        #[arg(long)]
        explain: bool,
    },
    /// Run a deck and write VTU/PVD, CSV histories and a JSON summary.
    Run {
        /// The `.ctc` deck.
        deck: PathBuf,
        /// Output directory (default: out/<deck name>).
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// Print nothing but errors.
        #[arg(short, long)]
        quiet: bool,
        /// Print every Newton iteration (residual, displacement norm, line search).
        #[arg(short, long)]
        verbose: bool,
        /// Continue a stopped run from the restart point (`restart.bin`) of
        /// its output directory, appending to the same results.
        #[arg(long)]
        restart: bool,
        /// Linear solver of the Newton tangent: `faer` (serial direct,
        /// the default) or `petsc` (PETSc over MPI: `mpirun -n N ctc run
        /// deck.ctc --solver petsc [-- PETSc options]`; needs a ctc built
        /// with `--features petsc`). The preset is MUMPS LU; options such
        /// as `-- -ksp_type cg -pc_type gamg -ksp_rtol 1e-10` replace it.
        #[arg(long, value_enum, default_value_t = Solver::Faer)]
        solver: Solver,
        /// Write the first tangent the run factorizes (free dofs) to FILE in
        /// Matrix Market, and ctc's time to factorize it to FILE.json
        /// (`verification/fenicsx/factor_compare.py` times other solvers on
        /// it).
        #[arg(long, value_name = "FILE")]
        export_matrix: Option<PathBuf>,
        /// Threads of the element assembly and of the low-rank solves
        /// (default: `CTC_THREADS`, else the cores); the results do not
        /// depend on it, bit for bit.
        #[arg(long, value_name = "N")]
        threads: Option<usize>,
        /// PETSc options (after `--`, with --solver petsc).
        #[arg(last = true, allow_hyphen_values = true, value_name = "PETSC OPTIONS")]
        petsc_options: Vec<String>,
    },
    /// Run the verification cases against their references.
    Verify {
        /// Only cases whose name contains this text.
        filter: Option<String>,
        /// List the cases (name, levels, tags, tolerances) instead of running them.
        #[arg(long)]
        list: bool,
        /// Only cases with this tag (repeat for several: all must match).
        #[arg(long = "tag", value_name = "TAG")]
        tags: Vec<String>,
        /// Write a Markdown report with plots into this directory (with
        /// --stress: the stress matrix as `stress.md`).
        #[arg(long)]
        report: Option<PathBuf>,
        /// Print the results as JSON instead of a table.
        #[arg(long)]
        json: bool,
        /// Highest refinement level to run (0 = coarsest only).
        #[arg(long)]
        max_level: Option<usize>,
        /// Run the stress matrix (stiff and extreme cases) instead of the cases.
        #[arg(long)]
        stress: bool,
        /// With --stress: only the quick subset run by the tests.
        #[arg(long, requires = "stress")]
        reduced: bool,
        /// Cases run at the same time (default: the cores); the results do
        /// not depend on it.
        #[arg(long, short = 'j')]
        jobs: Option<usize>,
    },
    /// Run a deck for every combination of varied values (penalty
    /// sensitivity, mesh, material...), locally or as a Slurm job array,
    /// and gather the key figures into one table and plot.
    Sweep {
        /// The `.ctc` deck (not needed with --gather).
        #[arg(required_unless_present = "gather")]
        deck: Option<PathBuf>,
        /// `PATH = v1, v2, ..`: a deck value and the values it takes
        /// (`contact.method.stiffness = 1e4, 1e5`, `contact[1]...`,
        /// `material[steel].elastic.E = ..`, a `let` name). Several
        /// --vary: the cartesian product.
        #[arg(long = "vary", value_name = "PATH = VALUES")]
        vary: Vec<String>,
        /// Variants run at the same time (local sweep; default: the cores).
        #[arg(long)]
        workers: Option<usize>,
        /// Write a Slurm job-array script (one variant per array task)
        /// instead of running.
        #[arg(long, conflicts_with = "gather")]
        slurm: bool,
        /// Only gather the results of a sweep directory into the table and plot.
        #[arg(long, value_name = "DIR")]
        gather: Option<PathBuf>,
        /// Sweep directory (default: out/<deck name>_sweep).
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// Run only variant N in-process (what each worker and Slurm task does).
        #[arg(long, hide = true)]
        task: Option<usize>,
        /// Print nothing but errors.
        #[arg(short, long)]
        quiet: bool,
    },
    /// Print the keyword reference: every item, block and key (type,
    /// default, range, dimension, meaning). Without an item: the index.
    Doc {
        /// An item (`contact`, `material`, ...), `mesh`, a generator, or `units`.
        item: Option<String>,
        /// Print the whole reference as Markdown (docs/DECK.md).
        #[arg(long)]
        markdown: bool,
    },
    /// Rewrite decks in the canonical layout (comments kept).
    Fmt {
        /// The decks.
        decks: Vec<PathBuf>,
        /// Only check: exit 1 if a deck is not formatted.
        #[arg(long)]
        check: bool,
    },
    /// Run the performance benchmark (rigid cylinder on an elastic block).
    Bench {
        /// Problem size as a fraction of the full ~80k-dof mesh (0.1 = ~8k dofs).
        #[arg(long, default_value_t = 1.0)]
        size: f64,
        /// Number of increments to reach the final indentation.
        #[arg(long, default_value_t = 4)]
        increments: usize,
        /// Print the results as JSON instead of a table.
        #[arg(long)]
        json: bool,
        /// Without the increment predictor (`newton { predictor = false }`):
        /// each increment starts from the converged state.
        #[arg(long)]
        no_predictor: bool,
        /// Without low-rank (Woodbury) updates: every tangent factorized.
        #[arg(long)]
        no_low_rank: bool,
        /// Run the contact search benchmark instead (n = 10^2 .. 10^5 contact
        /// nodes against a surface of n segments).
        #[arg(long)]
        search: bool,
        /// With --search: largest number of contact nodes.
        #[arg(long, requires = "search", default_value_t = 100_000)]
        max_nodes: usize,
        /// Run the projection robustness benchmark instead (random points
        /// against a revolved NURBS surface with a pole and a periodic seam).
        #[arg(long, conflicts_with = "search")]
        projection: bool,
        /// With --projection: number of random points.
        #[arg(long, requires = "projection", default_value_t = 1_000_000)]
        points: usize,
        /// Run the 3D direct-solver benchmark instead: a linear-elastic
        /// block of N x N x N hex8 (32: ~100k dofs, 46: ~300k): time per
        /// Newton iteration, factorization time, fill, peak memory.
        #[arg(long, value_name = "N", conflicts_with_all = ["search", "projection"])]
        solid: Option<usize>,
        /// With --solid: the symbolic analysis only (factor size, fill; no
        /// numeric factorization): how large a model fits in memory.
        #[arg(long, requires = "solid")]
        symbolic: bool,
        /// Threads of the element assembly and of the low-rank solves
        /// (default: `CTC_THREADS`, else the cores); the results do not
        /// depend on it, bit for bit.
        #[arg(long, value_name = "N")]
        threads: Option<usize>,
    },
}

/// The system allocator, counting the live heap when `CTC_MEMORY_TRACE`
/// is set (the memory of each phase of a run, `solve::memory::trace`).
#[global_allocator]
static TRACE_ALLOC: ctc_engine::solve::memory::CountingAllocator =
    ctc_engine::solve::memory::CountingAllocator;

fn main() -> ExitCode {
    ctc_engine::solve::memory::trace_start();
    // A closed output pipe (`ctc verify --list | head`) ends the process
    // quietly, as it does any Unix filter, instead of a panic in
    // `println!`.
    #[cfg(unix)]
    // SAFETY: restoring the default action of SIGPIPE at start-up, before
    // any thread exists; no handler is installed.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    heap::keep_freed_memory();
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Check { deck, explain } => check(&deck, explain),
        Command::Run {
            deck,
            output,
            quiet,
            verbose,
            restart,
            solver,
            export_matrix,
            threads,
            petsc_options,
        } => match (solver, set_threads(threads)) {
            (_, Err(e)) => Err(e),
            (Solver::Faer, _) if !petsc_options.is_empty() => Err(format!(
                "error: `{}` after `--` are PETSc options: they need `--solver petsc`",
                petsc_options.join(" ")
            )),
            (Solver::Petsc, _) if export_matrix.is_some() => {
                Err("error: --export-matrix needs the faer solver (`--solver faer`)".into())
            }
            (Solver::Faer, _) => run(
                &deck,
                output.as_deref(),
                (quiet, verbose, restart),
                export_matrix.as_deref(),
            ),
            (Solver::Petsc, _) => petsc_run::run(
                &deck,
                output.as_deref(),
                quiet,
                verbose,
                restart,
                &petsc_options,
            ),
        },
        Command::Verify {
            filter,
            list,
            tags,
            report,
            json,
            max_level,
            stress,
            reduced,
            jobs,
        } => {
            if list {
                verify_list(filter.as_deref(), &tags, json)
            } else if stress {
                verify_stress(reduced, json, report.as_deref())
            } else {
                verify(filter, tags, report, json, max_level, jobs)
            }
        }
        Command::Sweep {
            deck,
            vary,
            workers,
            slurm,
            gather,
            output,
            task,
            quiet,
        } => sweep::command(sweep::Args {
            deck,
            vary,
            workers,
            slurm,
            gather,
            output,
            task,
            quiet,
        }),
        Command::Doc { item, markdown } => doc(item.as_deref(), markdown),
        Command::Fmt { decks, check } => fmt(&decks, check),
        Command::Bench {
            size,
            increments,
            json,
            no_predictor,
            no_low_rank,
            search,
            max_nodes,
            projection,
            points,
            solid,
            symbolic,
            threads,
        } => {
            if let Err(e) = set_threads(threads) {
                Err(e)
            } else if let Some(n) = solid {
                bench_solid(n, symbolic, json)
            } else if projection {
                bench_projection(points, json)
            } else if search {
                bench_search(max_nodes, json)
            } else {
                bench(size, increments, (!no_predictor, !no_low_rank), json)
            }
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            if !message.is_empty() {
                eprintln!("{message}");
            }
            ExitCode::FAILURE
        }
    }
}

/// Reads a deck.
fn read(deck: &Path) -> Result<ctc_lang::Source, String> {
    ctc_lang::Source::read(deck)
        .map_err(|e| format!("error: cannot read deck `{}`: {e}", deck.display()))
}

/// Compiles a deck's text, rendering every diagnostic on failure.
fn compile_source(source: &ctc_lang::Source) -> Result<ctc_engine::model::Model, String> {
    ctc_lang::compile(source).map_err(|diags| diags.render(source))
}

fn check(deck: &Path, explain: bool) -> Result<(), String> {
    let source = read(deck)?;
    let model = ctc_lang::compile_any(&source).map_err(|diags| diags.render(&source))?;
    // the checks `ctc run` makes before solving (rigid-body modes left free
    // by the conditions and the contact pairs, indices, settings)
    let errors = match &model {
        AnyModel::D2(m) => ctc_engine::solve::check::check_model(m),
        AnyModel::D3(m) => ctc_engine::solve::check::check_model(m),
    };
    if !errors.is_empty() {
        return Err(format!(
            "error: {}: the model cannot be solved:\n  - {}",
            deck.display(),
            errors.join("\n  - ")
        ));
    }
    if let AnyModel::D2(m) = &model {
        for w in ctc_engine::solve::health::start_inside(m) {
            eprintln!("warning: {w}");
        }
    }
    if explain {
        match &model {
            AnyModel::D2(m) => print!("{}", ctc_lang::explain(m)),
            AnyModel::D3(m) => print!("{}", ctc_lang::explain::explain_solid(m)),
        }
    } else {
        println!("{}: ok", deck.display());
    }
    Ok(())
}

/// `out/<deck stem><suffix>`, the default output directory.
fn default_output(deck: &Path, suffix: &str) -> PathBuf {
    let stem = deck
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "run".into());
    PathBuf::from("out").join(format!("{stem}{suffix}"))
}

/// The thread count of `--threads N`, else `CTC_THREADS`, else the cores
/// (`ctc_engine::solve::parallel`); an invalid value is an error.
fn set_threads(threads: Option<usize>) -> Result<(), String> {
    use ctc_engine::solve::parallel;
    match threads {
        Some(0) => Err("error: --threads must be at least 1".into()),
        Some(n) => {
            parallel::set_threads(n);
            Ok(())
        }
        None => parallel::threads_from_env()
            .map(|n| {
                if let Some(n) = n {
                    parallel::set_threads(n);
                }
            })
            .map_err(|e| format!("error: {e}")),
    }
}

fn run(
    deck: &Path,
    output: Option<&Path>,
    (quiet, verbose, restart): (bool, bool, bool),
    export_matrix: Option<&Path>,
) -> Result<(), String> {
    let source = read(deck)?;
    let model = ctc_lang::compile_any(&source).map_err(|diags| diags.render(&source))?;
    let dir = output.map_or_else(|| default_output(deck, ""), Path::to_path_buf);
    let linear =
        |_: ()| -> Result<Option<Box<dyn ctc_engine::solve::linalg::LinearSystem>>, String> {
            let Some(path) = export_matrix else {
                return Ok(None);
            };
            // the file is created here so that a bad path is an error before the run
            std::fs::File::create(path)
                .map_err(|e| format!("error: cannot write {}: {e}", path.display()))?;
            Ok(Some(Box::new(
                ctc_engine::solve::linalg::export::ExportFirst::new(
                    Box::new(ctc_engine::solve::linalg::direct::LinearSolver::new()),
                    path.to_path_buf(),
                ),
            )))
        };
    // the dimension is chosen once, here
    match &model {
        AnyModel::D2(m) => run_model_with(m, &dir, quiet, verbose, restart, linear(())?, None),
        AnyModel::D3(m) => run_model_with(m, &dir, quiet, verbose, restart, linear(())?, None),
    }
}

/// Runs a compiled deck into `dir` (the body of `ctc run`, also each
/// variant of `ctc sweep`).
fn run_model<const D: usize>(
    model: &ctc_engine::model::Model<D>,
    dir: &Path,
    quiet: bool,
    verbose: bool,
    restart: bool,
) -> Result<(), String>
where
    nalgebra::Const<D>: ctc_engine::geom::Dimension<D>,
{
    run_model_with(model, dir, quiet, verbose, restart, None, None)
}

/// [`run_model`] with the tangent solved by `linear` (`None`: faer), the
/// VTU of each increment written as `pieces` (`mpirun`, rank 0's).
fn run_model_with<'m, const D: usize>(
    model: &'m ctc_engine::model::Model<D>,
    dir: &Path,
    quiet: bool,
    verbose: bool,
    restart: bool,
    linear: Option<Box<dyn ctc_engine::solve::linalg::LinearSystem + 'm>>,
    pieces: Option<ctc_engine::output::Pieces>,
) -> Result<(), String>
where
    nalgebra::Const<D>: ctc_engine::geom::Dimension<D>,
{
    let (mut writer, from) = if restart {
        let (w, cp) = ctc_engine::output::ResultWriter::resume(dir, model)
            .map_err(|e| format!("error: {e}"))?;
        if !quiet {
            println!(
                "restarting from increment {} (t = {}) in {}",
                cp.increment,
                cp.resume.time,
                dir.display()
            );
        }
        (w, Some(cp))
    } else {
        let w = ctc_engine::output::ResultWriter::create(dir, model).map_err(|e| {
            format!(
                "error: cannot create output directory `{}`: {e}",
                dir.display()
            )
        })?;
        if !quiet && w.removed() > 0 {
            println!(
                "removed {} result file(s) of a previous run in {}",
                w.removed(),
                dir.display()
            );
        }
        (w, None)
    };
    if let Some(pieces) = pieces {
        writer.set_pieces(pieces);
    }
    let mut observer = progress::Progress::new(model, &mut writer, quiet, verbose);
    let outcome = ctc_engine::solve::run_with(model, &mut observer, from.as_ref(), linear);
    observer.finish();
    let figures = observer.figures().clone();
    drop(observer);
    let summary = match &outcome {
        Ok(s) => s.clone(),
        Err(e) => e.summary.clone(),
    };
    writer
        .finish(&summary)
        .map_err(|e| format!("error: cannot write summary.json: {e}"))?;
    let plots = if model.thermal.is_some() {
        // thermo-mechanical runs: force-stroke and temperature plots
        Some(ctc_verification::history_plot::thermal_run_plots(
            dir,
            model.output.units.as_ref(),
        ))
    } else if model.tools.iter().any(|t| t.free_rotation.is_some()) {
        // free rollers: drawing force against stroke, roller angle
        Some(ctc_verification::history_plot::free_tool_run_plots(
            dir,
            model.output.units.as_ref(),
        ))
    } else {
        None
    };
    if let Some(plots) = plots {
        match plots {
            Ok(files) if !quiet && !files.is_empty() => {
                println!("plots: {} in {}", files.join(", "), dir.display())
            }
            Ok(_) => {}
            Err(e) => eprintln!("warning: no plots: {e}"),
        }
    }
    if model.loads.iter().any(|l| {
        matches!(
            l,
            ctc_engine::model::Load::FollowerPressure { control: None, .. }
        )
    }) {
        // hydroforming: the applied pressure against time
        match ctc_verification::history_plot::pressure_time_plots(dir, model.output.units.as_ref())
        {
            Ok(files) if !quiet && !files.is_empty() => {
                println!("plots: {} in {}", files.join(", "), dir.display())
            }
            Ok(_) => {}
            Err(e) => eprintln!("warning: no plots: {e}"),
        }
    }
    if model
        .output
        .history
        .iter()
        .any(|h| matches!(h, ctc_engine::model::HistoryRequest::Roughness { .. }))
    {
        // skin pass: the surface roughness and the rolling force against time
        match ctc_verification::history_plot::roughness_plots(dir, model.output.units.as_ref()) {
            Ok(files) if !quiet && !files.is_empty() => {
                println!("plots: {} in {}", files.join(", "), dir.display())
            }
            Ok(_) => {}
            Err(e) => eprintln!("warning: no plots: {e}"),
        }
    }
    if model.output.thickness.is_some() {
        // sheets and tubes: the thickness along the first face set
        match ctc_verification::history_plot::thickness_plots(dir, model.output.units.as_ref()) {
            Ok(files) if !quiet && !files.is_empty() => {
                println!("plots: {} in {}", files.join(", "), dir.display())
            }
            Ok(_) => {}
            Err(e) => eprintln!("warning: no plots: {e}"),
        }
    }
    if !ctc_engine::solve::control::controls(model).is_empty() {
        // superplastic forming: the optimised pressure cycle
        match ctc_verification::history_plot::pressure_cycle_plots(dir, model.output.units.as_ref())
        {
            Ok(files) if !quiet && !files.is_empty() => {
                println!("plots: {} in {}", files.join(", "), dir.display())
            }
            Ok(_) => {}
            Err(e) => eprintln!("warning: no plots: {e}"),
        }
    }
    match outcome {
        Ok(s) => {
            if !quiet {
                println!(
                    "done: {} increments, {} Newton iterations, {} cutbacks, {:.3} s -> {}",
                    s.increments.len(),
                    s.newton_iterations,
                    s.cutbacks,
                    s.timings.total,
                    dir.display()
                );
                if let Some(d) = &s.distributed {
                    println!(
                        "  linear solver: {} on {} ranks (rows {:?}, {} assembly): {} set-ups, {} \
                         solves, {} Krylov iterations (at most {} per solve); times: insertion \
                         {:.3} s, set-up {:.3} s, solve {:.3} s",
                        d.solver,
                        d.ranks,
                        d.rows_per_rank,
                        d.assembly,
                        d.setups,
                        d.solves,
                        d.krylov_iterations,
                        d.max_krylov_iterations,
                        d.assembly_seconds,
                        d.setup_seconds,
                        d.solve_seconds
                    );
                    for r in &d.per_rank {
                        println!(
                            "  rank {}: {} cells ({} assembled), {} owned + {} ghost nodes, halo {} \
                             columns from {} rank(s); wall (CPU) s: assembly {:.3} ({:.3}), \
                             contact {:.3} ({:.3}), tangent {:.3} ({:.3}), solve {:.3} ({:.3}); \
                             process CPU {:.1} s; peak memory {:.1} MiB",
                            r.rank,
                            r.cells,
                            r.assembled_cells,
                            r.owned_nodes,
                            r.ghost_nodes,
                            r.halo_columns,
                            r.neighbours,
                            r.assembly_seconds,
                            r.assembly_cpu_seconds,
                            r.contact_seconds,
                            r.contact_cpu_seconds,
                            r.tangent_seconds,
                            r.tangent_cpu_seconds,
                            r.solve_seconds,
                            r.solve_cpu_seconds,
                            r.process_cpu_seconds,
                            r.peak_memory_bytes as f64 / (1024.0 * 1024.0)
                        );
                    }
                }
                for line in figures.lines() {
                    println!("{line}");
                }
                for st in &s.stabilization {
                    println!(
                        "  stabilization (step `{}`, stabilize = {:e}, bodies {}): energy {:.3e} = \
                         {:.2e} x the internal work {:.3e}; force at the step end {:.1e}",
                        st.step,
                        st.factor,
                        st.bodies.join(", "),
                        st.energy,
                        st.ratio,
                        st.internal_energy,
                        st.end_force
                    );
                }
            }
            Ok(())
        }
        Err(e) => Err(format!(
            "error: the analysis stopped before the end\n{}\nresults of the converged increments are in {} (summary.json: completed = false)",
            e.message,
            dir.display()
        )),
    }
}

fn doc(item: Option<&str>, markdown: bool) -> Result<(), String> {
    let text = if markdown {
        ctc_lang::reference::markdown()
    } else {
        ctc_lang::reference::doc(item).map_err(|e| format!("error: {e}"))?
    };
    print!("{text}");
    Ok(())
}

fn fmt(decks: &[PathBuf], check: bool) -> Result<(), String> {
    if decks.is_empty() {
        return Err("error: name the decks to format, e.g. `ctc fmt examples/*.ctc`".into());
    }
    let mut unformatted = Vec::new();
    for d in decks {
        let text = std::fs::read_to_string(d)
            .map_err(|e| format!("error: cannot read deck `{}`: {e}", d.display()))?;
        let out = ctc_lang::format::format(&text).map_err(|e| {
            format!(
                "error: `{}` does not parse ({e}); run `ctc check` on it",
                d.display()
            )
        })?;
        if out != text {
            if check {
                unformatted.push(d.display().to_string());
            } else {
                std::fs::write(d, &out)
                    .map_err(|e| format!("error: cannot write `{}`: {e}", d.display()))?;
                println!("formatted {}", d.display());
            }
        }
    }
    if unformatted.is_empty() {
        Ok(())
    } else {
        Err(format!("not formatted: {}", unformatted.join(", ")))
    }
}

fn verify_list(filter: Option<&str>, tags: &[String], json: bool) -> Result<(), String> {
    let rows = ctc_verification::registry::list(filter, tags);
    if json {
        println!(
            "{}",
            serde_json::to_string_pretty(&rows).map_err(|e| e.to_string())?
        );
    } else {
        print!("{}", ctc_verification::registry::list_table(&rows));
        println!("tags: {}", ctc_verification::registry::tags().join(", "));
    }
    if rows.is_empty() {
        return Err("no case matches".into());
    }
    Ok(())
}

fn verify(
    filter: Option<String>,
    tags: Vec<String>,
    report: Option<PathBuf>,
    json: bool,
    max_level: Option<usize>,
    jobs: Option<usize>,
) -> Result<(), String> {
    if jobs == Some(0) {
        return Err("error: --jobs must be at least 1".into());
    }
    if ctc_verification::registry::list(filter.as_deref(), &tags).is_empty() {
        let names: Vec<String> = ctc_verification::registry::list(None, &[])
            .into_iter()
            .map(|r| r.name)
            .collect();
        let what = match &filter {
            Some(f) => format!("no verification case matches `{f}`"),
            None => "no verification case matches".to_string(),
        };
        let tags_note = if tags.is_empty() {
            String::new()
        } else {
            format!(" with tags {}", tags.join(", "))
        };
        let close: Vec<&String> = filter
            .as_deref()
            .map(|f| {
                let stem = &f[..f.len().min(4)];
                names.iter().filter(|n| n.contains(stem)).take(5).collect()
            })
            .unwrap_or_default();
        let hint = if close.is_empty() {
            "`ctc verify --list` lists the cases and their tags".to_string()
        } else {
            format!(
                "close names: {}; `ctc verify --list` lists them all",
                close
                    .iter()
                    .map(|n| format!("`{n}`"))
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        };
        return Err(format!("error: {what}{tags_note}\n  = help: {hint}"));
    }
    let opts = ctc_verification::VerifyOptions {
        filter,
        tags,
        report_dir: report,
        max_level,
        progress: true,
        jobs,
        ..Default::default()
    };
    let report = ctc_verification::run(&opts)?;
    if json {
        println!(
            "{}",
            serde_json::to_string_pretty(&report).map_err(|e| e.to_string())?
        );
    } else {
        print!("{}", report.table());
    }
    if report.passed() {
        Ok(())
    } else {
        Err("verification failed: see the table above".into())
    }
}

fn verify_stress(reduced: bool, json: bool, report_dir: Option<&Path>) -> Result<(), String> {
    let report = ctc_verification::run_stress(reduced);
    if let Some(dir) = report_dir {
        std::fs::create_dir_all(dir)
            .map_err(|e| format!("error: cannot create `{}`: {e}", dir.display()))?;
        let path = dir.join("stress.md");
        std::fs::write(&path, report.markdown())
            .map_err(|e| format!("error: cannot write `{}`: {e}", path.display()))?;
    }
    if json {
        println!(
            "{}",
            serde_json::to_string_pretty(&report).map_err(|e| e.to_string())?
        );
    } else {
        print!("{}", report.table());
    }
    if report.passed() {
        Ok(())
    } else {
        Err("stress matrix: some cells did not meet their expectation (see above)".into())
    }
}

fn bench_search(max_nodes: usize, json: bool) -> Result<(), String> {
    let defaults = ctc_verification::SearchBenchOptions::default();
    let mut sizes: Vec<usize> = defaults
        .sizes
        .iter()
        .copied()
        .filter(|&n| n <= max_nodes)
        .collect();
    if sizes.is_empty() {
        sizes.push(max_nodes.max(2));
    }
    let opts = ctc_verification::SearchBenchOptions { sizes, ..defaults };
    print_report(&ctc_verification::run_search_bench(&opts), json)
}

fn bench_projection(points: usize, json: bool) -> Result<(), String> {
    if points == 0 {
        return Err("bench --projection: --points must be at least 1".into());
    }
    let figures = ctc_geom::bench::run(points);
    if json {
        let rows: Vec<serde_json::Value> = figures
            .iter()
            .map(|f| {
                serde_json::json!({
                    "seeds": f.mode,
                    "points": f.points,
                    "converged": f.converged,
                    "wrong_minimum": f.wrong_minimum,
                    "max_distance_error": f.max_distance_error,
                    "mean_newton_iterations": f.mean_iterations,
                    "max_newton_iterations": f.max_iterations,
                    "ns_per_projection": f.ns_per_projection,
                })
            })
            .collect();
        println!(
            "{}",
            serde_json::to_string_pretty(&rows).map_err(|e| e.to_string())?
        );
    } else {
        println!("projection on a revolved NURBS dome (pole at the top, periodic seam, free edge), {points} random points");
        println!("{}", ctc_geom::bench::HEADER);
        for f in &figures {
            println!("{f}");
        }
    }
    Ok(())
}

fn bench_solid(n: usize, symbolic: bool, json: bool) -> Result<(), String> {
    use ctc_verification::solid_bench::{run_solid_bench, run_solid_symbolic};
    if symbolic {
        print_report(&run_solid_symbolic(n)?, json)
    } else {
        print_report(&run_solid_bench(n)?, json)
    }
}

/// Prints a benchmark report as its table or as JSON.
fn print_report<R: std::fmt::Display + serde::Serialize>(
    report: &R,
    json: bool,
) -> Result<(), String> {
    if json {
        println!(
            "{}",
            serde_json::to_string_pretty(report).map_err(|e| e.to_string())?
        );
    } else {
        print!("{report}");
    }
    Ok(())
}

fn bench(
    size: f64,
    increments: usize,
    (predictor, low_rank): (bool, bool),
    json: bool,
) -> Result<(), String> {
    let opts = ctc_verification::BenchOptions {
        size,
        increments,
        predictor,
        low_rank,
        ..Default::default()
    };
    print_report(&ctc_verification::run_bench(&opts)?, json)
}
