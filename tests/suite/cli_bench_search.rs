//! `ctc bench --search` runs the contact search benchmark and its JSON
//! says every search agreed with brute force.

use std::process::Command;

#[test]
fn cli_bench_search_json_agrees_with_brute_force() {
    let out = Command::new(env!("CARGO_BIN_EXE_ctc"))
        .args(["bench", "--search", "--max-nodes", "1000", "--json"])
        .output()
        .expect("ctc runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON output");
    let sizes = v["sizes"].as_array().expect("sizes");
    let nodes: Vec<u64> = sizes.iter().map(|s| s["nodes"].as_u64().unwrap()).collect();
    assert_eq!(nodes, vec![100, 1000]);
    for s in sizes {
        for phase in ["memory", "circle", "rigid"] {
            assert_eq!(s[phase]["mismatches"], 0, "{phase}: {s}");
        }
        let n = s["nodes"].as_u64().unwrap();
        assert_eq!(s["brute"]["projection_tests"].as_u64(), Some(n * n));
        assert!(s["memory"]["tests_per_node"].as_f64().unwrap() < 3.0);
    }
    assert!(v["exponents"]["brute"].as_f64().is_some());
}
