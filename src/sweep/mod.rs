//! `ctc sweep deck.ctc --vary "PATH = v1, v2" [--vary ..]`: one run per
//! combination of values (cartesian product), locally with `--workers N`
//! or as a Slurm job array (`--slurm`), then one table and one plot of the
//! key figures (`--gather DIR`, automatic after a local sweep).
//!
//! ```text
//! DIR/sweep.json        the deck, the --vary options, the variants
//! DIR/v000/             variant 0: variant.ctc, variant.json (status), log.txt,
//!                       and what `ctc run` writes (summary.json, history.csv, VTU)
//! DIR/sweep.sbatch      with --slurm: the job-array script
//! DIR/sweep.csv|md|svg  the gathered table and plot
//! ```
//!
//! Each variant runs in its own process (a worker or an array task runs
//! `ctc sweep DECK --vary .. --task I`), so a variant that fails, panics or
//! is killed never stops the others; the table says which failed and why.

mod gather;
mod plan;
mod plot;
mod slurm;

use gather::{DECK_ERROR, FINISHED, RUNNING};
use plan::Variant;
use serde_json::json;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// The options of `ctc sweep` (see `main.rs` for their help).
pub struct Args {
    pub deck: Option<PathBuf>,
    pub vary: Vec<String>,
    pub workers: Option<usize>,
    pub slurm: bool,
    pub gather: Option<PathBuf>,
    pub output: Option<PathBuf>,
    pub task: Option<usize>,
    pub quiet: bool,
}

/// Runs `ctc sweep`.
pub fn command(args: Args) -> Result<(), String> {
    if let Some(dir) = &args.gather {
        return gather_dir(dir, args.quiet);
    }
    let Some(deck) = &args.deck else {
        return Err("error: `ctc sweep` needs a deck (or --gather DIR)".into());
    };
    let source = crate::read(deck)?;
    let variants = plan::plan(&source, &args.vary)?;
    let dir = args
        .output
        .clone()
        .unwrap_or_else(|| crate::default_output(deck, "_sweep"));
    if let Some(i) = args.task {
        return task(&source, &variants, i, &dir);
    }
    std::fs::create_dir_all(&dir)
        .map_err(|e| format!("error: cannot create `{}`: {e}", dir.display()))?;
    write(
        &dir.join("sweep.json"),
        &plan_json(deck, &args.vary, &variants),
    )?;
    if args.slurm {
        return write_slurm(deck, &args.vary, &variants, &dir, args.quiet);
    }
    let workers = args
        .workers
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
        .max(1);
    run_local(deck, &args.vary, &variants, &dir, workers, args.quiet)?;
    gather_dir(&dir, args.quiet)
}

fn write(path: &Path, text: &str) -> Result<(), String> {
    std::fs::write(path, text).map_err(|e| format!("error: cannot write `{}`: {e}", path.display()))
}

fn plan_json(deck: &Path, vary: &[String], variants: &[Variant]) -> String {
    let vs: Vec<_> = variants
        .iter()
        .map(|v| json!({"name": v.name(), "overrides": v.overrides}))
        .collect();
    let j = json!({"deck": deck.display().to_string(), "vary": vary, "variants": vs});
    serde_json::to_string_pretty(&j).unwrap_or_default() + "\n"
}

/// Records the state of a variant's task (`variant.json`).
fn record(vdir: &Path, v: &Variant, status: &str, error: Option<&str>) -> Result<(), String> {
    let j = json!({
        "name": v.name(),
        "overrides": v.overrides,
        "status": status,
        "error": error,
    });
    write(
        &vdir.join("variant.json"),
        &(serde_json::to_string_pretty(&j).unwrap_or_default() + "\n"),
    )
}

/// Runs variant `i` in this process into `DIR/v<iii>`.
fn task(deck: &ctc_lang::Source, variants: &[Variant], i: usize, dir: &Path) -> Result<(), String> {
    let v = variants.get(i).ok_or_else(|| {
        format!(
            "error: --task {i}: the sweep has {} variants (0..{})",
            variants.len(),
            variants.len().saturating_sub(1)
        )
    })?;
    let vdir = dir.join(v.name());
    std::fs::create_dir_all(&vdir)
        .map_err(|e| format!("error: cannot create `{}`: {e}", vdir.display()))?;
    let _ = std::fs::remove_file(vdir.join("summary.json")); // of an earlier sweep
    record(&vdir, v, RUNNING, None)?;
    let compiled = v.source(deck).and_then(|src| {
        write(&vdir.join("variant.ctc"), &src.text)?;
        crate::compile_source(&src)
    });
    let model = match compiled {
        Ok(m) => m,
        Err(e) => {
            record(&vdir, v, DECK_ERROR, Some(&e))?;
            return Err(e);
        }
    };
    let outcome = crate::run_model(&model, &vdir, true, false, false);
    record(
        &vdir,
        v,
        FINISHED,
        outcome.as_ref().err().map(String::as_str),
    )?;
    outcome
}

/// Runs every variant, `workers` at a time, each in its own process.
fn run_local(
    deck: &Path,
    vary: &[String],
    variants: &[Variant],
    dir: &Path,
    workers: usize,
    quiet: bool,
) -> Result<(), String> {
    let exe = std::env::current_exe().map_err(|e| format!("error: cannot find ctc itself: {e}"))?;
    if !quiet {
        println!(
            "sweep of {}: {} variants, {} at a time -> {}",
            deck.display(),
            variants.len(),
            workers,
            dir.display()
        );
    }
    let mut pending = variants.iter();
    let mut running: Vec<(&Variant, Child, Instant)> = Vec::new();
    let mut done = 0;
    loop {
        while running.len() < workers {
            let Some(v) = pending.next() else { break };
            let vdir = dir.join(v.name());
            std::fs::create_dir_all(&vdir)
                .map_err(|e| format!("error: cannot create `{}`: {e}", vdir.display()))?;
            let log = std::fs::File::create(vdir.join("log.txt"))
                .map_err(|e| format!("error: cannot write in `{}`: {e}", vdir.display()))?;
            let err = log.try_clone().map_err(|e| format!("error: {e}"))?;
            let mut cmd = Command::new(&exe);
            cmd.arg("sweep").arg(deck);
            for x in vary {
                cmd.arg("--vary").arg(x);
            }
            cmd.arg("--task")
                .arg(v.index.to_string())
                .arg("--output")
                .arg(dir)
                .arg("--quiet")
                .stdin(Stdio::null())
                .stdout(log)
                .stderr(err);
            let child = cmd
                .spawn()
                .map_err(|e| format!("error: cannot start a worker: {e}"))?;
            running.push((v, child, Instant::now()));
        }
        if running.is_empty() {
            break;
        }
        let mut i = 0;
        let mut progressed = false;
        while i < running.len() {
            match running[i].1.try_wait() {
                Ok(None) => i += 1,
                Ok(Some(_)) | Err(_) => {
                    let (v, mut child, t0) = running.swap_remove(i);
                    let _ = child.wait();
                    done += 1;
                    progressed = true;
                    if !quiet {
                        let row = gather::row(v, &dir.join(v.name()));
                        let why = if row.reason.is_empty() {
                            String::new()
                        } else {
                            format!(": {}", row.reason)
                        };
                        println!(
                            "[{done}/{}] {} ({}) {} in {:.1} s{why}",
                            variants.len(),
                            v.name(),
                            v.describe(),
                            row.status,
                            t0.elapsed().as_secs_f64()
                        );
                    }
                }
            }
        }
        if !progressed {
            std::thread::sleep(Duration::from_millis(20));
        }
    }
    Ok(())
}

/// Writes `DIR/sweep.sbatch`.
fn write_slurm(
    deck: &Path,
    vary: &[String],
    variants: &[Variant],
    dir: &Path,
    quiet: bool,
) -> Result<(), String> {
    let exe = std::env::current_exe().map_err(|e| format!("error: cannot find ctc itself: {e}"))?;
    let cwd = std::env::current_dir().map_err(|e| format!("error: {e}"))?;
    let abs_dir = std::fs::canonicalize(dir).map_err(|e| format!("error: {e}"))?;
    let script = slurm::script(&slurm::Job {
        exe: &exe,
        cwd: &cwd,
        deck,
        vary,
        dir: &abs_dir,
        variants: variants.len(),
    });
    let path = dir.join("sweep.sbatch");
    write(&path, &script)?;
    if !quiet {
        println!(
            "{} variants -> {}\nsubmit: sbatch {}\nthen:   ctc sweep --gather {}",
            variants.len(),
            path.display(),
            path.display(),
            dir.display()
        );
    }
    Ok(())
}

/// Reads `DIR/sweep.json` and every variant's directory; writes
/// `sweep.csv`, `sweep.md` and `sweep.svg`; prints the Markdown table.
fn gather_dir(dir: &Path, quiet: bool) -> Result<(), String> {
    let plan_path = dir.join("sweep.json");
    let text = std::fs::read_to_string(&plan_path).map_err(|e| {
        format!(
            "error: `{}` is not a sweep directory (no sweep.json: {e})",
            dir.display()
        )
    })?;
    let j: serde_json::Value = serde_json::from_str(&text)
        .map_err(|e| format!("error: `{}` is not valid: {e}", plan_path.display()))?;
    let variants: Vec<Variant> = j["variants"]
        .as_array()
        .map(|vs| {
            vs.iter()
                .enumerate()
                .map(|(index, v)| Variant {
                    index,
                    overrides: v["overrides"]
                        .as_array()
                        .map(|o| {
                            o.iter()
                                .map(|pv| {
                                    let s = |k: usize| pv[k].as_str().unwrap_or("").to_string();
                                    (s(0), s(1))
                                })
                                .collect()
                        })
                        .unwrap_or_default(),
                })
                .collect()
        })
        .unwrap_or_default();
    let rows: Vec<gather::Row> = variants
        .iter()
        .map(|v| gather::row(v, &dir.join(v.name())))
        .collect();
    write(&dir.join("sweep.csv"), &gather::csv(&rows))?;
    let md = gather::markdown(&rows);
    write(&dir.join("sweep.md"), &md)?;
    let plotted = plot::plot(&rows, &dir.join("sweep.svg"))?;
    if !quiet {
        print!("{md}");
        let ok = rows.iter().filter(|r| r.status == "completed").count();
        println!(
            "{ok} of {} variants completed; table: {}, {}{}",
            rows.len(),
            dir.join("sweep.csv").display(),
            dir.join("sweep.md").display(),
            if plotted {
                format!(", plot: {}", dir.join("sweep.svg").display())
            } else {
                String::new()
            }
        );
    }
    Ok(())
}
