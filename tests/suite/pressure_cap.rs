//! The pressure-cycle controller's cap (`max_pressure`): superplastic free
//! bulging of a clamped Norton-Hoff sheet (`examples/free_bulge.ctc`,
//! coarsened) with the gas pressure capped below the peak the controller
//! reaches uncapped.
//!
//! Reference: Norton-Hoff, `sigma = K (rate)^m` with m = 0.5, so at a
//! given shape the pole's strain rate goes as the pressure to the power
//! `1 / m`: capped at `p_cap` where the shape needs `p(h)` (the uncapped
//! run's pressure at the same pole height `h`) to hold the target, the
//! rate is `target (p_cap / p(h))^(1/m)`.
//!
//! ```text
//!   p ^        uncapped: rises to 0.4465 and falls (the bulge's need)
//!     |      ____ ____
//!     |    /=========== p_cap = 0.42: held, rate below the target
//!     |  /
//!     +----------------> t
//! ```

use std::path::Path;
use std::process::Command;

/// The history columns (time, pole height, pressure, rate) of the coarse
/// free bulge with `control` as its controller.
fn bulge(control: &str, dir: &Path) -> Vec<[f64; 4]> {
    let deck = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/free_bulge.ctc");
    let text = std::fs::read_to_string(deck).unwrap();
    let from = "control = strain_rate { target = 1e-3  exponent = 0.5  at = (0, 0) }";
    assert!(text.contains(from));
    let text = text
        .replace(from, control)
        .replace("divisions = (100, 2)", "divisions = (25, 2)")
        .replace(
            "time = 0 .. 1000  increments = 200",
            "time = 0 .. 600  increments = 30",
        );
    let path = dir.join("bulge.ctc");
    std::fs::write(&path, text).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_ctc"))
        .args(["run", "-q"])
        .arg(&path)
        .arg("-o")
        .arg(dir.join("out"))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = std::fs::read_to_string(dir.join("out/history.csv")).unwrap();
    let mut lines = csv.lines();
    // time, the pole's and the pole's top node's (x, y), pressure, rate
    let head = lines.next().unwrap();
    assert!(head.ends_with(
        "controlled_pressure[pressure sheet.bottom],controlled_rate[pressure sheet.bottom]"
    ));
    lines
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            assert_eq!(v.len(), 7, "{l}");
            [v[0], v[2], v[5], v[6]]
        })
        .collect()
}

#[test]
fn capped_free_bulge_holds_the_cap_and_its_rate_follows_norton_hoff() {
    let (a, b) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    let free = bulge(
        "control = strain_rate { target = 1e-3  exponent = 0.5  at = (0, 0) }",
        a.path(),
    );
    let cap = 0.42;
    let capped = bulge(
        "control = strain_rate { target = 1e-3  exponent = 0.5  max_pressure = 0.42  at = (0, 0) }",
        b.path(),
    );
    let peak = free.iter().map(|r| r[2]).fold(0.0, f64::max);
    assert!(peak > cap * 1.05, "uncapped peak {peak}");
    assert!(capped.iter().all(|r| r[2] <= cap * (1.0 + 1e-12)));
    // the pressure the shape at pole height h needs, from the free run
    let need = |h: f64| {
        let k = free.windows(2).position(|w| w[0][1] <= h && h <= w[1][1])?;
        let (p, q) = (free[k], free[k + 1]);
        Some(p[2] + (q[2] - p[2]) * (h - p[1]) / (q[1] - p[1]))
    };
    let mut held = 0;
    let mut worst = 0.0f64;
    // the rate measured over an increment answers the pressure applied in
    // it: judge the increments after one at the cap
    for w in capped
        .windows(2)
        .filter(|w| w[0][2] == cap && w[1][2] == cap)
    {
        let r = w[1];
        let Some(p) = need(r[1]).filter(|p| *p > cap * 1.02) else {
            continue;
        };
        held += 1;
        let expected = 1e-3 * (cap / p).powi(2);
        worst = worst.max((r[3] / expected - 1.0).abs());
    }
    println!("capped increments judged: {held}, rate vs (p_cap / p(h))^2: {worst:.2e}");
    assert!(held >= 5, "{held} increments at the cap");
    assert!(worst < 0.03, "rate vs Norton-Hoff at the cap: {worst}");
    // the capped bulge lags the free one
    assert!(capped.last().unwrap()[1] < free.last().unwrap()[1]);
}
