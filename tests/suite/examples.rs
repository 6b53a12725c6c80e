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
    // the blade loss runs its first 10 ms here (its 20 ms cost ~45 s of
    // debug CPU: `crate::blade_loss::deck_to_10_ms`)
    let src = if path.file_stem().is_some_and(|s| s == "blade_loss") {
        crate::blade_loss::deck_to_10_ms()
    } else if path.file_stem().is_some_and(|s| s == "blade_loss_3d") {
        // its spin-up and the release (a run to 13 ms: ~150 s of debug
        // CPU; `crate::blade_loss_3d` runs it to 6.5 / 7 ms)
        crate::blade_loss_3d::deck_3d_to("6.1e-3", 4)
    } else {
        ctc_lang::Source::read(path).expect("readable deck")
    };
    match ctc_lang::compile_any(&src) {
        Ok(m) => m,
        Err(d) => panic!("{}", d.render(&src)),
    }
}

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

#[test]
fn every_example_runs_and_matches_its_summary_snapshot() {
    let decks = examples();
    assert!(decks.len() >= 3, "expected the example decks");
    // The decks are independent: run them on the machine's cores (a shared
    // queue), then compare the snapshots in deck order.
    let jobs = std::thread::available_parallelism().map_or(1, |n| n.get());
    let next = std::sync::atomic::AtomicUsize::new(0);
    let done = std::sync::Mutex::new(vec![None; decks.len()]);
    std::thread::scope(|s| {
        for _ in 0..jobs.min(decks.len()) {
            s.spawn(|| loop {
                let i = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                let Some(deck) = decks.get(i) else { break };
                let lines = match compile(deck) {
                    AnyModel::D2(m) => run_example(deck, &m),
                    AnyModel::D3(m) => run_example(deck, &m),
                };
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
    let dir = tempfile::tempdir().unwrap();
    let mut writer = ctc_engine::output::ResultWriter::create(dir.path(), model).unwrap();
    let mut probe = Probe::default();
    struct Both<'a, const D: usize>(&'a mut Probe, &'a mut ctc_engine::output::ResultWriter<D>);
    impl<const D: usize> Observer<D> for Both<'_, D>
    where
        Const<D>: Dimension<D>,
    {
        fn converged(&mut self, v: &IncrementView<'_, D>) -> Result<(), String> {
            self.0.converged(v)?;
            self.1.converged(v)
        }
    }
    let summary = ctc_engine::solve::run(model, &mut Both(&mut probe, &mut writer))
        .unwrap_or_else(|e| panic!("{}: {}", deck.display(), e.message));
    writer.finish(&summary).unwrap();
    assert!(summary.completed);
    assert!(dir.path().join("results.pvd").exists());
    assert!(dir.path().join("summary.json").exists());
    probe.lines
}
