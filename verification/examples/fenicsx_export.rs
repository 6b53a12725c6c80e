//! Writes the problem exports of the FEniCSx cases (mesh, numbering,
//! boundary conditions, contact) into a directory, default
//! `verification/reference/`: the input of `verification/fenicsx/solve.py`.
//!
//! Run: `cargo run -p ctc-verification --example fenicsx_export -- [out_dir]`

fn main() {
    let out = std::env::args()
        .nth(1)
        .map(std::path::PathBuf::from)
        .unwrap_or_else(ctc_verification::fenicsx::reference_dir);
    if let Err(e) = std::fs::create_dir_all(&out) {
        eprintln!("error: cannot create {}: {e}", out.display());
        std::process::exit(1);
    }
    let crate_dir = ctc_verification::fenicsx::crate_dir();
    for case in ctc_verification::fenicsx::cases() {
        match ctc_verification::fenicsx::write_problem(&case, &crate_dir, &out) {
            Ok(path) => println!("{}", path.display()),
            Err(e) => {
                eprintln!("error: {}: {e}", case.name);
                std::process::exit(1);
            }
        }
    }
}
