//! `history.csv`: one row per converged increment — the time, then two
//! columns (x, y) per history request: reaction sums over a node set, mean
//! displacement over a node set, total contact force of a pair (force of
//! the tool on the body). Flushed after every row.

use crate::contact::NodeContact;
use crate::model::{HistoryRequest, Model};
use std::io::Write;

/// CSV field quoting (RFC 4180).
pub fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// The header row for `model`'s history requests.
pub fn header(model: &Model) -> String {
    let mut cols = vec!["time".to_string()];
    for h in &model.output.history {
        let label = match h {
            HistoryRequest::Reaction { label, .. }
            | HistoryRequest::Displacement { label, .. }
            | HistoryRequest::ContactForce { label, .. } => label,
        };
        cols.push(csv_field(&format!("{label}_x")));
        cols.push(csv_field(&format!("{label}_y")));
    }
    cols.join(",")
}

/// The values of one row.
pub fn row(
    model: &Model,
    time: f64,
    displacement: &[[f64; 2]],
    reaction: &[[f64; 2]],
    contact: &[Vec<NodeContact>],
) -> Vec<f64> {
    let mut out = vec![time];
    for h in &model.output.history {
        let v = match h {
            HistoryRequest::Reaction { nodes, .. } => nodes.iter().fold([0.0, 0.0], |a, &n| {
                [a[0] + reaction[n][0], a[1] + reaction[n][1]]
            }),
            HistoryRequest::Displacement { nodes, .. } => {
                let s = nodes.iter().fold([0.0, 0.0], |a, &n| {
                    [a[0] + displacement[n][0], a[1] + displacement[n][1]]
                });
                let k = nodes.len().max(1) as f64;
                [s[0] / k, s[1] / k]
            }
            HistoryRequest::ContactForce { pair, .. } => contact
                .get(*pair)
                .map(|l| {
                    l.iter()
                        .fold([0.0, 0.0], |a, c| [a[0] + c.force[0], a[1] + c.force[1]])
                })
                .unwrap_or([0.0, 0.0]),
        };
        out.extend(v);
    }
    out
}

/// Appends rows to `history.csv`.
#[derive(Debug)]
pub struct HistoryWriter {
    file: std::io::BufWriter<std::fs::File>,
}

impl HistoryWriter {
    /// Creates the file and writes the header.
    pub fn create(path: &std::path::Path, model: &Model) -> std::io::Result<Self> {
        let mut file = std::io::BufWriter::new(std::fs::File::create(path)?);
        writeln!(file, "{}", header(model))?;
        file.flush()?;
        Ok(HistoryWriter { file })
    }

    /// Writes and flushes one row.
    pub fn append(&mut self, values: &[f64]) -> std::io::Result<()> {
        let cols: Vec<String> = values.iter().map(|v| v.to_string()).collect();
        writeln!(self.file, "{}", cols.join(","))?;
        self.file.flush()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_quoting() {
        assert_eq!(csv_field("a"), "a");
        assert_eq!(csv_field("a,b"), "\"a,b\"");
        assert_eq!(csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
    }
}
