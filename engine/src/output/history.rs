//! `history.csv`: one row per converged increment — the time, then `D`
//! columns (x, y[, z]) per history request: reaction sums over a node set, mean
//! displacement over a node set, total contact force of a pair (force of
//! the tool on the body); a roughness request has the three columns
//! `<label>_Ra`, `_Rq`, `_mean` of the deformed set ([`super::roughness`]).
//! Then, for each pair with friction, the work
//! dissipated by friction over the increment (`friction_work[<pair>]`;
//! the cumulative work is the column's running sum, also in
//! `summary.json`). Follower pressures from a time function: the applied
//! pressure (`pressure[label]`). Models with a dynamic step: the energy audit
//! ([`ENERGY_COLUMNS`]). Pressure controllers: the applied pressure and
//! the rate. Free tools (`rotation = free`): `angle[tool]`,
//! `angular_velocity[tool]`, `moment[tool]` (of the contact forces on the
//! tool) and `applied_moment[tool]`. Flushed after every row.

use crate::contact::NodeContact;
use crate::model::{HistoryRequest, Model};
use std::io::Write;

/// The energy-audit columns of models with a dynamic step
/// (`crate::solve::dynamics::Energy`).
pub const ENERGY_COLUMNS: [&str; 9] = [
    "kinetic_energy",
    "internal_work",
    "external_work",
    "contact_work",
    "damping_work",
    "energy_balance",
    "energy_gain",
    "numerical_dissipation",
    "energy_error",
];

/// The columns of a `roughness(set)` request, after its label
/// ([`super::roughness`]).
pub const ROUGHNESS_COLUMNS: [&str; 3] = ["Ra", "Rq", "mean"];

/// CSV field quoting (RFC 4180).
pub fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// The header row for `model`'s history requests (the [`columns`], CSV
/// quoted: a label may hold commas, e.g. `reaction(b.nodes(box((0, 0), (1,
/// 1))))_x`).
pub fn header<const D: usize>(model: &Model<D>) -> String {
    let cols: Vec<String> = columns(model).iter().map(|c| csv_field(c)).collect();
    cols.join(",")
}

/// The column names of `history.csv`, unquoted, `time` first.
pub fn columns<const D: usize>(model: &Model<D>) -> Vec<String> {
    let mut cols = vec!["time".to_string()];
    for h in &model.output.history {
        let label = match h {
            HistoryRequest::Reaction { label, .. }
            | HistoryRequest::Displacement { label, .. }
            | HistoryRequest::ContactForce { label, .. } => label,
            HistoryRequest::Roughness { label, .. } => {
                for c in ROUGHNESS_COLUMNS {
                    cols.push(format!("{label}_{c}"));
                }
                continue;
            }
        };
        for axis in ["x", "y", "z"].iter().take(D) {
            cols.push(format!("{label}_{axis}"));
        }
    }
    for cp in model.contacts.iter().filter(|c| c.friction.is_some()) {
        cols.push(format!("friction_work[{}]", cp.name));
    }
    for label in time_pressures(model).map(|(label, _)| label) {
        cols.push(format!("pressure[{label}]"));
    }
    if model.steps.iter().any(|s| s.dynamic.is_some()) {
        // appended by the writer from the energy audit
        for c in ENERGY_COLUMNS {
            cols.push(c.into());
        }
    }
    for (i, _) in crate::solve::control::controls(model) {
        // appended by the writer from the controllers' records
        let label = match &model.loads[i] {
            crate::model::Load::FollowerPressure { label, .. } => label.as_str(),
            _ => "",
        };
        cols.push(format!("controlled_pressure[{label}]"));
        cols.push(format!("controlled_rate[{label}]"));
    }
    // appended by the writer from the free tools' records
    cols.extend(crate::solve::free_tool::columns(model));
    if model.thermal.is_some() {
        // appended by the writer from the thermal increment
        cols.push("temperature_max".into());
        cols.push("temperature_min".into());
    }
    if D == 3 && model.output.thickness.is_some() {
        // appended by the writer: the thinnest node of the first face set
        // and its reference position (`super::thickness`)
        for c in [
            "thickness_min",
            "thickness_min_x",
            "thickness_min_y",
            "thickness_min_z",
        ] {
            cols.push(c.into());
        }
    }
    cols
}

/// The values of one row.
pub fn row<const D: usize>(
    model: &Model<D>,
    time: f64,
    displacement: &[[f64; D]],
    reaction: &[[f64; D]],
    contact: &[Vec<NodeContact<D>>],
) -> Vec<f64> {
    let mut out = vec![time];
    let sum = |nodes: &[usize], v: &[[f64; D]]| {
        nodes.iter().fold([0.0; D], |mut a, &n| {
            for (ac, vc) in a.iter_mut().zip(&v[n]) {
                *ac += vc;
            }
            a
        })
    };
    for h in &model.output.history {
        let v = match h {
            HistoryRequest::Reaction { nodes, .. } => sum(nodes, reaction),
            HistoryRequest::Displacement { nodes, .. } => {
                let k = nodes.len().max(1) as f64;
                sum(nodes, displacement).map(|s| s / k)
            }
            HistoryRequest::ContactForce { pair, .. } => {
                let mut a = [0.0; D];
                for c in contact.get(*pair).into_iter().flatten() {
                    for (ac, fc) in a.iter_mut().zip(&c.force) {
                        *ac += fc;
                    }
                }
                a
            }
            HistoryRequest::Roughness { nodes, axis, .. } => {
                let current: Vec<[f64; D]> = nodes
                    .iter()
                    .map(|&n| {
                        let mut p = model.mesh.nodes[n];
                        for (pc, uc) in p.iter_mut().zip(&displacement[n]) {
                            *pc += uc;
                        }
                        p
                    })
                    .collect();
                let r = super::roughness::roughness(&current, *axis);
                out.extend([r.ra, r.rq, r.mean]);
                continue;
            }
        };
        out.extend(v);
    }
    for (cp, list) in model.contacts.iter().zip(contact) {
        if cp.friction.is_some() {
            out.push(crate::contact::friction::pair_dissipation(list));
        }
    }
    out.extend(time_pressures(model).map(|(_, value)| value.eval(time)));
    out
}

/// The follower pressures driven by their time function alone (no
/// controller; a controlled one has `controlled_pressure[..]`): their
/// labels and functions, in the order of the `pressure[label]` columns.
fn time_pressures<const D: usize>(
    model: &Model<D>,
) -> impl Iterator<Item = (&str, &crate::model::TimeFunction)> {
    model.loads.iter().filter_map(|l| match l {
        crate::model::Load::FollowerPressure {
            label,
            value,
            control: None,
            ..
        } => Some((label.as_str(), value)),
        _ => None,
    })
}

/// Appends rows to `history.csv`.
#[derive(Debug)]
pub struct HistoryWriter {
    file: std::io::BufWriter<std::fs::File>,
}

impl HistoryWriter {
    /// Creates the file and writes the header.
    pub fn create<const D: usize>(
        path: &std::path::Path,
        model: &Model<D>,
    ) -> std::io::Result<Self> {
        let mut file = std::io::BufWriter::new(std::fs::File::create(path)?);
        writeln!(file, "{}", header(model))?;
        file.flush()?;
        Ok(HistoryWriter { file })
    }

    /// Reopens an existing `history.csv` to continue a restarted run: keeps
    /// the header and the first `rows` complete rows (rows written after
    /// the restart point are dropped, the file is replaced atomically),
    /// then appends. The header must be the one of `model`.
    pub fn resume<const D: usize>(
        path: &std::path::Path,
        model: &Model<D>,
        rows: usize,
    ) -> std::io::Result<Self> {
        let text = std::fs::read_to_string(path)?;
        let mut lines = text.split_inclusive('\n');
        let head = header(model);
        if lines.next().map(str::trim_end) != Some(head.as_str()) {
            return Err(std::io::Error::other(format!(
                "{} does not belong to this deck (different header)",
                path.display()
            )));
        }
        let mut kept = format!("{head}\n");
        for _ in 0..rows {
            match lines.next() {
                Some(l) if l.ends_with('\n') => kept.push_str(l),
                _ => {
                    return Err(std::io::Error::other(format!(
                        "{} has fewer than the {rows} rows of the restart point",
                        path.display()
                    )))
                }
            }
        }
        super::atomic::write_atomic(path, kept.as_bytes())?;
        let file = std::fs::OpenOptions::new().append(true).open(path)?;
        Ok(HistoryWriter {
            file: std::io::BufWriter::new(file),
        })
    }

    /// Writes and flushes one row (numbers in their shortest round-trip
    /// form, [`super::encode::fmt_f64`]).
    pub fn append(&mut self, values: &[f64]) -> std::io::Result<()> {
        let cols: Vec<String> = values.iter().map(|&v| super::encode::fmt_f64(v)).collect();
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
