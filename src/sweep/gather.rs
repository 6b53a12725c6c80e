//! Gathering a sweep: each variant's key figures, read from its directory
//! (`variant.json`, `summary.json`, `history.csv`), into one table written
//! as `sweep.csv` and `sweep.md` (and plotted by `plot.rs`).
//!
//! A variant that did not complete is a row too, with the reason: a deck
//! error (a value the deck rejects), a failed analysis (the engine's
//! diagnosis from `summary.json`), a run that never finished (killed, out
//! of time: `variant.json` still says `running`), or never started.

use super::plan::Variant;
use serde_json::Value;
use std::path::Path;

/// The key figures of one variant.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// `v000`, ...
    pub name: String,
    /// `(path, value)` of the variant.
    pub overrides: Vec<(String, String)>,
    /// `completed`, `failed`, `deck error`, `did not finish`, `not run`.
    pub status: String,
    /// Why it did not complete (first line), empty otherwise.
    pub reason: String,
    /// Converged increments.
    pub increments: Option<usize>,
    /// Newton iterations over the run.
    pub newton_iterations: Option<usize>,
    /// Cutbacks.
    pub cutbacks: Option<usize>,
    /// Wall time of the analysis, s.
    pub wall_time: Option<f64>,
    /// Largest penetration over the converged increments.
    pub max_penetration: Option<f64>,
    /// Last row of `history.csv`: (column, value), e.g. reaction and contact
    /// force components.
    pub history: Vec<(String, f64)>,
}

/// What a variant's task records in `variant.json`.
pub const RUNNING: &str = "running";
/// The analysis ran (see `summary.json` for how it ended).
pub const FINISHED: &str = "finished";
/// The variant deck did not compile.
pub const DECK_ERROR: &str = "deck error";

fn first_line(s: &str) -> String {
    s.lines()
        .find(|l| !l.trim().is_empty())
        .unwrap_or("")
        .trim()
        .to_string()
}

fn read_json(path: &Path) -> Option<Value> {
    serde_json::from_str(&std::fs::read_to_string(path).ok()?).ok()
}

/// The fields of a CSV line, RFC 4180 quotes removed (a history label may
/// hold commas: `reaction(b.nodes(box((0, 0), (1, 1))))_x`).
fn csv_fields(line: &str) -> Vec<String> {
    let mut out = vec![String::new()];
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '"' if quoted && chars.peek() == Some(&'"') => {
                chars.next();
                out.last_mut().expect("a field").push('"');
            }
            '"' => quoted = !quoted,
            ',' if !quoted => out.push(String::new()),
            c => out.last_mut().expect("a field").push(c),
        }
    }
    out
}

/// The last row of a `history.csv`.
fn last_history(path: &Path) -> Vec<(String, f64)> {
    let Ok(text) = std::fs::read_to_string(path) else {
        return Vec::new();
    };
    let mut lines = text.lines().filter(|l| !l.trim().is_empty());
    let Some(header) = lines.next() else {
        return Vec::new();
    };
    let Some(last) = lines.next_back() else {
        return Vec::new();
    };
    csv_fields(header)
        .into_iter()
        .zip(last.split(','))
        .skip(1) // time
        .filter_map(|(h, v)| Some((h.trim().to_string(), v.trim().parse::<f64>().ok()?)))
        .collect()
}

/// The row of `variant` from its directory `dir`.
pub fn row(variant: &Variant, dir: &Path) -> Row {
    let mut row = Row {
        name: variant.name(),
        overrides: variant.overrides.clone(),
        status: "not run".into(),
        reason: String::new(),
        increments: None,
        newton_iterations: None,
        cutbacks: None,
        wall_time: None,
        max_penetration: None,
        history: Vec::new(),
    };
    let Some(record) = read_json(&dir.join("variant.json")) else {
        return row;
    };
    let state = record["status"].as_str().unwrap_or("");
    if state == DECK_ERROR {
        row.status = DECK_ERROR.into();
        row.reason = first_line(record["error"].as_str().unwrap_or(""));
        return row;
    }
    let summary = read_json(&dir.join("summary.json"));
    let Some(s) = summary.filter(|_| state == FINISHED) else {
        row.status = "did not finish".into();
        row.reason = "the task stopped before writing its summary (killed or out of time?)".into();
        return row;
    };
    let completed = s["completed"].as_bool().unwrap_or(false);
    row.status = if completed { "completed" } else { "failed" }.into();
    if !completed {
        row.reason = first_line(
            s["failure"]
                .as_str()
                .or(record["error"].as_str())
                .unwrap_or("the analysis stopped early"),
        );
    }
    let incs = s["increments"].as_array();
    row.increments = incs.map(Vec::len);
    row.newton_iterations = s["newton_iterations"].as_u64().map(|n| n as usize);
    row.cutbacks = s["cutbacks"].as_u64().map(|n| n as usize);
    row.wall_time = s["timings"]["total"].as_f64();
    row.max_penetration = incs.map(|v| {
        v.iter()
            .filter_map(|i| i["max_penetration"].as_f64())
            .fold(0.0, f64::max)
    });
    row.history = last_history(&dir.join("history.csv"));
    row
}

/// History columns over all rows, in order of first appearance.
pub fn history_columns(rows: &[Row]) -> Vec<String> {
    let mut cols: Vec<String> = Vec::new();
    for r in rows {
        for (h, _) in &r.history {
            if !cols.contains(h) {
                cols.push(h.clone());
            }
        }
    }
    cols
}

fn opt<T: ToString>(v: Option<T>) -> String {
    v.map(|x| x.to_string()).unwrap_or_default()
}

fn num(v: Option<f64>) -> String {
    v.map(|x| format!("{x:.6e}")).unwrap_or_default()
}

fn history_value(r: &Row, col: &str) -> Option<f64> {
    r.history.iter().find(|(h, _)| h == col).map(|(_, v)| *v)
}

fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// The table as CSV (one row per variant).
pub fn csv(rows: &[Row]) -> String {
    let paths: Vec<&str> = rows
        .first()
        .map(|r| r.overrides.iter().map(|(p, _)| p.as_str()).collect())
        .unwrap_or_default();
    let cols = history_columns(rows);
    let mut head: Vec<String> = vec!["variant".into()];
    head.extend(paths.iter().map(|p| p.to_string()));
    head.extend(
        [
            "status",
            "increments",
            "newton_iterations",
            "cutbacks",
            "wall_time_s",
            "max_penetration",
        ]
        .map(String::from),
    );
    head.extend(cols.iter().cloned());
    head.push("reason".into());
    let mut out = head
        .iter()
        .map(|h| csv_field(h))
        .collect::<Vec<_>>()
        .join(",")
        + "\n";
    for r in rows {
        let mut f: Vec<String> = vec![r.name.clone()];
        f.extend(r.overrides.iter().map(|(_, v)| v.clone()));
        f.push(r.status.clone());
        f.push(opt(r.increments));
        f.push(opt(r.newton_iterations));
        f.push(opt(r.cutbacks));
        f.push(num(r.wall_time));
        f.push(num(r.max_penetration));
        f.extend(cols.iter().map(|c| num(history_value(r, c))));
        f.push(r.reason.clone());
        out += &(f.iter().map(|x| csv_field(x)).collect::<Vec<_>>().join(",") + "\n");
    }
    out
}

/// The table as Markdown.
pub fn markdown(rows: &[Row]) -> String {
    let paths: Vec<&str> = rows
        .first()
        .map(|r| r.overrides.iter().map(|(p, _)| p.as_str()).collect())
        .unwrap_or_default();
    let cols = history_columns(rows);
    let mut head: Vec<String> = vec!["variant".into()];
    head.extend(paths.iter().map(|p| format!("`{p}`")));
    head.extend(
        [
            "status",
            "incr.",
            "Newton its",
            "cutbacks",
            "wall [s]",
            "max penetration",
        ]
        .map(String::from),
    );
    head.extend(cols.iter().map(|c| format!("`{c}`")));
    head.push("reason".into());
    let mut out = format!("| {} |\n", head.join(" | "));
    out += &format!("|{}\n", " --- |".repeat(head.len()));
    let short = |v: Option<f64>| v.map(|x| format!("{x:.4e}")).unwrap_or_default();
    for r in rows {
        let mut f: Vec<String> = vec![r.name.clone()];
        f.extend(r.overrides.iter().map(|(_, v)| v.clone()));
        f.push(r.status.clone());
        f.push(opt(r.increments));
        f.push(opt(r.newton_iterations));
        f.push(opt(r.cutbacks));
        f.push(r.wall_time.map(|x| format!("{x:.3}")).unwrap_or_default());
        f.push(short(r.max_penetration));
        f.extend(cols.iter().map(|c| short(history_value(r, c))));
        f.push(r.reason.replace('|', "\\|"));
        out += &format!("| {} |\n", f.join(" | "));
    }
    out
}

#[cfg(test)]
mod tests {
    #[test]
    fn csv_fields_keep_commas_inside_quotes() {
        assert_eq!(
            super::csv_fields(
                "time,\"reaction(b.nodes(box((0, 0), (1, 1))))_x\",\"say \"\"hi\"\"\""
            ),
            [
                "time",
                "reaction(b.nodes(box((0, 0), (1, 1))))_x",
                "say \"hi\""
            ]
        );
        assert_eq!(super::csv_fields("a,,b"), ["a", "", "b"]);
    }

    use super::*;

    fn variant() -> Variant {
        Variant {
            index: 2,
            overrides: vec![("contact.method.stiffness".into(), "1e5".into())],
        }
    }

    #[test]
    fn a_missing_directory_is_not_run_and_a_killed_task_did_not_finish() {
        let dir = tempfile::tempdir().unwrap();
        let r = row(&variant(), &dir.path().join("v002"));
        assert_eq!(r.status, "not run");
        std::fs::write(dir.path().join("variant.json"), r#"{"status": "running"}"#).unwrap();
        let r = row(&variant(), dir.path());
        assert_eq!(r.status, "did not finish");
    }

    #[test]
    fn figures_come_from_summary_and_history() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        std::fs::write(d.join("variant.json"), r#"{"status": "finished"}"#).unwrap();
        std::fs::write(
            d.join("summary.json"),
            r#"{"completed": false, "failure": "no convergence at t = 0.5\nmore",
                "newton_iterations": 17, "cutbacks": 3, "timings": {"total": 1.5},
                "increments": [{"max_penetration": 1e-3}, {"max_penetration": 4e-3}]}"#,
        )
        .unwrap();
        std::fs::write(
            d.join("history.csv"),
            "time,reaction(b.top)_x,contact_force(b.s -> t)_y\n0.5,0,1\n1,0.25,2.5\n",
        )
        .unwrap();
        let r = row(&variant(), d);
        assert_eq!(r.status, "failed");
        assert_eq!(r.reason, "no convergence at t = 0.5");
        assert_eq!(
            (r.increments, r.newton_iterations, r.cutbacks),
            (Some(2), Some(17), Some(3))
        );
        assert_eq!(r.max_penetration, Some(4e-3));
        assert_eq!(r.history[1], ("contact_force(b.s -> t)_y".to_string(), 2.5));
        let t = csv(std::slice::from_ref(&r));
        let mut lines = t.lines();
        assert_eq!(
            lines.next().unwrap(),
            "variant,contact.method.stiffness,status,increments,newton_iterations,cutbacks,wall_time_s,max_penetration,reaction(b.top)_x,contact_force(b.s -> t)_y,reason"
        );
        assert_eq!(
            lines.next().unwrap(),
            "v002,1e5,failed,2,17,3,1.500000e0,4.000000e-3,2.500000e-1,2.500000e0,no convergence at t = 0.5"
        );
        assert!(markdown(&[r]).contains("| v002 | 1e5 | failed | 2 | 17 | 3 | 1.500 |"));
    }
}
