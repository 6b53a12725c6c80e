//! Writes the problem export of every FEniCSx case (or of one deck) for
//! `verification/fenicsx/solve.py`.
//!
//! Usage: `cargo run -p ctc-verification --example fenicsx_export -- OUT_DIR`
//! (all committed cases), or `... -- OUT_DIR DECK LEVEL NAME` (one deck at a
//! refinement level, e.g. for a timing comparison on a large mesh), or
//! `... -- --bench SIZE OUT_DIR` (the exact deck `ctc bench --size SIZE`
//! runs, written by `run_bench` itself, exported as
//! `OUT_DIR/bench_<SIZE>.problem.json`, with `OUT_DIR/bench_<SIZE>.ctc` and
//! ctc's report `OUT_DIR/bench_<SIZE>.ctc.json`; used by
//! `verification/fenicsx/speed.sh`).

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if let [_, flag, size, out] = args.as_slice() {
        if flag == "--bench" {
            if let Err(e) = export_bench(size, std::path::Path::new(out)) {
                eprintln!("error: {e}");
                std::process::exit(1);
            }
            return;
        }
    }
    let out = args
        .get(1)
        .map(std::path::PathBuf::from)
        .unwrap_or_else(ctc_verification::fenicsx::reference_dir);
    if let Err(e) = std::fs::create_dir_all(&out) {
        eprintln!("error: cannot create {}: {e}", out.display());
        std::process::exit(1);
    }
    let crate_dir = ctc_verification::fenicsx::crate_dir();
    let one;
    let cases = if let [_, _, deck, level, name] = args.as_slice() {
        let Ok(level) = level.parse() else {
            eprintln!("error: LEVEL must be a whole number, got `{level}`");
            std::process::exit(2);
        };
        // leak once: the case table holds &'static str
        one = ctc_verification::fenicsx::FenicsxCase {
            name: Box::leak(name.clone().into_boxed_str()),
            deck: Box::leak(deck.clone().into_boxed_str()),
            level,
        };
        vec![one]
    } else {
        ctc_verification::fenicsx::cases()
    };
    for case in cases {
        match ctc_verification::fenicsx::write_problem(&case, &crate_dir, &out) {
            Ok(path) => println!("{}", path.display()),
            Err(e) => {
                eprintln!("error: {}: {e}", case.name);
                std::process::exit(1);
            }
        }
    }
}

/// Runs `ctc bench --size SIZE` through `run_bench` (so the deck is the one
/// the benchmark generates, penalty `10 E / h_min` included), keeps its
/// deck and report, and exports the deck's problem.
fn export_bench(size: &str, out: &std::path::Path) -> Result<(), String> {
    let value: f64 = size
        .parse()
        .map_err(|_| format!("SIZE must be a number, got `{size}`"))?;
    std::fs::create_dir_all(out).map_err(|e| format!("cannot create {}: {e}", out.display()))?;
    let name = format!("bench_{size}");
    let deck = out.join(format!("{name}.ctc"));
    let opts = ctc_verification::BenchOptions {
        size: value,
        deck_out: Some(deck.clone()),
        ..Default::default()
    };
    let report = ctc_verification::run_bench(&opts)?;
    if let Some(failure) = &report.failure {
        return Err(format!("ctc bench failed: {failure}"));
    }
    let report_path = out.join(format!("{name}.ctc.json"));
    std::fs::write(&report_path, report.to_json() + "\n")
        .map_err(|e| format!("cannot write {}: {e}", report_path.display()))?;
    let text = std::fs::read_to_string(&deck)
        .map_err(|e| format!("cannot read {}: {e}", deck.display()))?;
    let model = ctc_verification::deck::compile_text(&deck, &text)?;
    let problem = ctc_verification::fenicsx_export::export(&model, &name)?;
    let path = out.join(format!("{name}.problem.json"));
    let json = serde_json::to_string(&problem).map_err(|e| e.to_string())?;
    std::fs::write(&path, json + "\n")
        .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    println!("{}", path.display());
    Ok(())
}
