//! `ctc verify --stress --reduced --report DIR` writes the stress matrix
//! with its outcome counts as `DIR/stress.md` (issue 10: the table in the
//! verify report, zero wrong and zero hang).

use std::process::Command;

#[test]
fn stress_report_markdown_has_counts_with_zero_wrong_and_zero_hang() {
    let tmp = tempfile::tempdir().unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_ctc"))
        .args(["verify", "--stress", "--reduced", "--report"])
        .arg(tmp.path())
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stdout}");
    let md = std::fs::read_to_string(tmp.path().join("stress.md")).unwrap();
    assert!(md.starts_with("## Stress matrix"));
    let counts = md
        .lines()
        .find(|l| l.contains(" cells: "))
        .expect("counts line");
    assert!(counts.contains(" 0 wrong, 0 hang"), "{counts}");
    assert!(stdout.contains(counts.trim_matches('*')), "{stdout}");
    let rows = md
        .lines()
        .filter(|l| l.starts_with("| ") && !l.starts_with("| family"))
        .count();
    let cells: usize = counts
        .trim_matches('*')
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert_eq!(rows, cells);
}
