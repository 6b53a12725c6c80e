//! Writes the problem export of every FEniCSx case (or of one deck) for
//! `verification/fenicsx/solve.py`.
//!
//! Usage: `cargo run -p ctc-verification --example fenicsx_export -- OUT_DIR`
//! (all committed cases), or `... -- OUT_DIR DECK LEVEL NAME` (one deck at a
//! refinement level, e.g. for a timing comparison on a large mesh).

fn main() {
    let args: Vec<String> = std::env::args().collect();
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
