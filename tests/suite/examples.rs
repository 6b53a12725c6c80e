//! Every example deck compiles, runs to the end, and its rounded run summary
//! matches the reviewed snapshot (increments, iterations, contact state,
//! resultant forces to 4 significant digits).

use ctc_engine::geom::Dimension;
use ctc_engine::model::{AnyModel, Model};
use ctc_engine::solve::{IncrementView, Observer};
use nalgebra::Const;
use std::path::{Path, PathBuf};

/// Rounds to `digits` significant digits (for snapshots).
fn sig(x: f64, digits: i32) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    let p = digits - 1 - x.abs().log10().floor() as i32;
    let s = 10f64.powi(p);
    (x * s).round() / s
}

/// Keeps what the snapshot needs from each converged increment.
#[derive(Default)]
struct Probe {
    lines: Vec<String>,
}

impl<const D: usize> Observer<D> for Probe {
    fn converged(&mut self, v: &IncrementView<'_, D>) -> Result<(), String> {
        let mut reaction = [0.0; D];
        let mut reaction_abs = 0.0f64;
        for r in v.reaction {
            for k in 0..D {
                reaction[k] += r[k];
            }
            reaction_abs += r.iter().map(|x| x.abs()).sum::<f64>();
        }
        let mut contact = [0.0; D];
        let mut closed = 0;
        for pair in v.contact {
            for n in pair {
                for (c, f) in contact.iter_mut().zip(&n.force) {
                    *c += f;
                }
                if n.status == ctc_engine::contact::ContactStatus::Closed {
                    closed += 1;
                }
            }
        }
        // Round-off below 1e-9 of the force scale is noise, not a regression.
        let scale = contact.iter().fold(reaction_abs, |m, x| m.max(x.abs()));
        let clean = |x: f64| {
            if x.abs() <= 1e-9 * scale {
                0.0
            } else {
                sig(x, 4)
            }
        };
        let umax = v
            .displacement
            .iter()
            .map(|u| {
                if D == 2 {
                    u[0].hypot(u[1])
                } else {
                    u.iter().map(|x| x * x).sum::<f64>().sqrt()
                }
            })
            .fold(0.0, f64::max);
        let reaction: Vec<String> = reaction.iter().map(|r| clean(*r).to_string()).collect();
        let contact: Vec<String> = contact.iter().map(|c| clean(*c).to_string()).collect();
        self.lines.push(format!(
            "inc {} t={} iters={} closed={} |u|max={} reaction=({}) contact=({})",
            v.increment,
            sig(v.time, 6),
            v.residuals.len(),
            closed,
            sig(umax, 4),
            reaction.join(", "),
            contact.join(", "),
        ));
        Ok(())
    }
}

fn examples() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let mut decks: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("examples/ exists")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "ctc"))
        .collect();
    decks.sort();
    decks
}

fn compile(path: &Path) -> AnyModel {
    let mut src = ctc_lang::Source::read(path).expect("readable deck");
    let stem = path.file_stem().unwrap_or_default().to_string_lossy();
    if let Some((_, lines)) = SHORTENED.iter().find(|(name, _)| *name == stem) {
        let mut text = src.text.clone();
        for (line, short) in lines.iter() {
            assert!(
                text.contains(line),
                "{}: no line `{line}` to shorten",
                path.display()
            );
            text = text.replacen(line, short, 1);
        }
        src = ctc_lang::Source::new(src.path.clone(), text);
    }
    match ctc_lang::compile_any(&src) {
        Ok(m) => m,
        Err(d) => panic!("{}", d.render(&src)),
    }
}

/// The example decks this test runs shortened, by replacing their `let`
/// lines (their full run is a catalogue level, run by `ctc verify
/// --max-level 1`, too long for the test's budget in the debug profile):
/// `dynamic_buckling_3d` to its first increment (the impact, 10 us; its
/// 4.7 ms are `dynamic_buckling_tube_3d`'s level 1).
const SHORTENED: &[(&str, &[(&str, &str)])] = &[(
    "dynamic_buckling_3d",
    &[
        ("let t_end = 4.7e-3", "let t_end = 1e-5"),
        ("let steps = 470", "let steps = 1"),
    ],
)];

#[test]
fn every_example_opens_with_goal_reference_and_run_command() {
    for deck in examples() {
        let text = std::fs::read_to_string(&deck).unwrap();
        let header: String = text
            .lines()
            .take_while(|l| l.starts_with('#'))
            .collect::<Vec<_>>()
            .join("\n");
        assert!(
            !header.is_empty(),
            "{} has no opening comment",
            deck.display()
        );
        assert!(
            header.contains("Reference"),
            "{}: opening comment names no reference",
            deck.display()
        );
        assert!(
            header.contains("Run: cargo run"),
            "{}: opening comment has no run command",
            deck.display()
        );
    }
}

/// The example decks that run longest here (debug), started first so
/// that none of them starts last and runs alone while the other core
/// idles (longest-first; the decks are independent, the snapshots are
/// compared in deck order whatever the order of the runs). Measured
/// (wall under load 13-18, where wall is ~10x CPU): this test's own
/// lines (`cargo test --workspace -- examples:: --nocapture`: each deck
/// prints its time) ironing_3d 293 s, taylor_bar 42 s; the decks whose
/// run is shared with their own test ([`SharedRun`]): blade_loss_3d 140 s
/// to 7 ms, two_cylinders_mixed_3d over 60 s (with its hex8 twin, which
/// that test runs alone), blade_loss 43 s to 10 ms, superplastic_forming_3d
/// 39 s, tube_hydroforming 29 s; blankholder 22 s (the catalogue's level
/// 0, both roller kinds).
/// In file-name order ironing_3d started 24th of 40 and ended the test
/// alone (867 s).
const SLOW_EXAMPLES_FIRST: &[&str] = &[
    "ironing_3d",
    "blade_loss_3d",
    "two_cylinders_mixed_3d",
    "taylor_bar",
    "blade_loss",
    "superplastic_forming_3d",
    "tube_hydroforming",
    "blankholder",
];

/// The order in which the examples test starts `decks`: the
/// [`SLOW_EXAMPLES_FIRST`] present, then the others in file-name order.
fn start_order(decks: &[PathBuf]) -> Vec<usize> {
    let slow = |p: &Path| {
        let stem = p.file_stem().unwrap_or_default().to_string_lossy();
        SLOW_EXAMPLES_FIRST
            .iter()
            .position(|n| *n == stem)
            .unwrap_or(SLOW_EXAMPLES_FIRST.len())
    };
    let mut order: Vec<usize> = (0..decks.len()).collect();
    order.sort_by_key(|&i| slow(&decks[i]));
    order
}

#[test]
fn the_slow_examples_exist_and_start_first() {
    let decks = examples();
    let stems: Vec<String> = decks
        .iter()
        .map(|p| p.file_stem().unwrap().to_string_lossy().into_owned())
        .collect();
    for name in SLOW_EXAMPLES_FIRST {
        assert!(
            stems.iter().any(|s| s == name),
            "examples/{name}.ctc does not exist"
        );
    }
    let order = start_order(&decks);
    let first: Vec<&str> = order[..SLOW_EXAMPLES_FIRST.len()]
        .iter()
        .map(|&i| stems[i].as_str())
        .collect();
    assert_eq!(first, SLOW_EXAMPLES_FIRST);
    let mut all = order.clone();
    all.sort_unstable();
    assert_eq!(all, (0..decks.len()).collect::<Vec<_>>());
}

#[test]
fn every_example_runs_and_matches_its_summary_snapshot() {
    let decks = examples();
    assert!(decks.len() >= 3, "expected the example decks");
    // The decks are independent: run them on the machine's cores (a shared
    // queue, the slowest first), then compare the snapshots in deck order.
    let jobs = std::thread::available_parallelism().map_or(1, |n| n.get());
    let order = start_order(&decks);
    let next = std::sync::atomic::AtomicUsize::new(0);
    let done = std::sync::Mutex::new(vec![None; decks.len()]);
    std::thread::scope(|s| {
        for _ in 0..jobs.min(decks.len()) {
            s.spawn(|| loop {
                let k = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                let Some(&i) = order.get(k) else { break };
                let deck = &decks[i];
                let start = std::time::Instant::now();
                let stem = deck.file_stem().unwrap().to_string_lossy();
                let lines = shared_lines(&stem).unwrap_or_else(|| match compile(deck) {
                    AnyModel::D2(m) => run_example(deck, &m),
                    AnyModel::D3(m) => run_example(deck, &m),
                });
                // the time budget of this test (docs/ARCHITECTURE.md, "CI
                // time budget"): `-- --nocapture` lists each deck's wall
                eprintln!(
                    "example {}: {:.1} s",
                    deck.file_stem().unwrap().to_string_lossy(),
                    start.elapsed().as_secs_f64()
                );
                done.lock().unwrap()[i] = Some(lines);
            });
        }
    });
    for (deck, lines) in decks.iter().zip(done.into_inner().unwrap()) {
        let lines = lines.expect("every deck ran");
        let name = deck.file_stem().unwrap().to_string_lossy().into_owned();
        insta::assert_snapshot!(format!("summary_{name}"), lines.join("\n"));
    }
}

/// Runs one example deck into a temporary directory; the probe's lines.
fn run_example<const D: usize>(deck: &Path, model: &Model<D>) -> Vec<String>
where
    Const<D>: Dimension<D>,
{
    run_example_with(deck, model, Nothing).lines
}

/// An observer that keeps nothing.
struct Nothing;

impl<const D: usize> Observer<D> for Nothing {}

/// One run of an example deck, shared by the examples test (its summary
/// snapshot: [`SharedRun::lines`]) and the deck's own test (its physics:
/// [`SharedRun::probe`]), so that `cargo test` runs the deck once (the CI
/// time budget of `docs/ARCHITECTURE.md`). A deck's module keeps it in a
/// `OnceLock`; [`shared_lines`] lists those decks.
pub(crate) struct SharedRun<P> {
    /// The deck's own observer after the run.
    pub probe: P,
    /// The run's summary.
    pub summary: ctc_engine::solve::RunSummary,
    /// The examples test's snapshot lines.
    pub lines: Vec<String>,
    /// Wall seconds of the run (results written included).
    pub seconds: f64,
}

/// Runs one example deck into a temporary directory (results and summary
/// written as `ctc run` does) with `probe` observing it too.
pub(crate) fn run_example_with<const D: usize, P: Observer<D>>(
    deck: &Path,
    model: &Model<D>,
    mut probe: P,
) -> SharedRun<P>
where
    Const<D>: Dimension<D>,
{
    let start = std::time::Instant::now();
    let dir = tempfile::tempdir().unwrap();
    let mut writer = ctc_engine::output::ResultWriter::create(dir.path(), model).unwrap();
    let mut lines = Probe::default();
    struct All<'a, const D: usize> {
        lines: &'a mut Probe,
        writer: &'a mut ctc_engine::output::ResultWriter<D>,
        probe: &'a mut dyn Observer<D>,
    }
    impl<const D: usize> Observer<D> for All<'_, D>
    where
        Const<D>: Dimension<D>,
    {
        fn iteration(&mut self, info: &ctc_engine::solve::IterationInfo) {
            self.probe.iteration(info)
        }
        fn converged(&mut self, v: &IncrementView<'_, D>) -> Result<(), String> {
            self.lines.converged(v)?;
            self.writer.converged(v)?;
            self.probe.converged(v)
        }
        fn cutback(&mut self, reason: &str, new_dt: f64) {
            self.probe.cutback(reason, new_dt)
        }
        fn warning(&mut self, message: &str) {
            self.probe.warning(message)
        }
    }
    let summary = ctc_engine::solve::run(
        model,
        &mut All {
            lines: &mut lines,
            writer: &mut writer,
            probe: &mut probe,
        },
    )
    .unwrap_or_else(|e| panic!("{}: {}", deck.display(), e.message));
    writer.finish(&summary).unwrap();
    assert!(
        summary.completed,
        "{}: the run did not complete",
        deck.display()
    );
    assert!(dir.path().join("results.pvd").exists());
    assert!(dir.path().join("summary.json").exists());
    SharedRun {
        probe,
        summary,
        lines: lines.lines,
        seconds: start.elapsed().as_secs_f64(),
    }
}

/// The snapshot lines of the example decks whose run is shared with the
/// deck's own test ([`SharedRun`]), `None` for the others.
fn shared_lines(stem: &str) -> Option<Vec<String>> {
    Some(match stem {
        "blade_loss" => crate::blade_loss::shared_10_ms().lines.clone(),
        "blade_loss_3d" => crate::blade_loss_3d::shared_7_ms().lines.clone(),
        "two_cylinders_mixed_3d" => crate::example_two_cylinders_mixed_3d::shared()
            .lines
            .clone(),
        "superplastic_forming_3d" => crate::example_superplastic_forming::shared().lines.clone(),
        "tube_hydroforming" => crate::example_tube_hydroforming::shared().lines.clone(),
        _ => return None,
    })
}
