//! SVG line plots of a run's `history.csv` (one column against another):
//! the force against the stroke and the temperature rise of the
//! thermo-mechanical examples (`examples/shock_damper.ctc`,
//! `examples/rivet_forming.ctc`), pressure cycles, surface roughness and
//! the rolling force of a skin pass ([`roughness_plots`]); and of `thickness.csv`
//! (the thickness map along a sheet, [`thickness_plots`]).

use crate::plot::colour;
use plotters::prelude::*;
use std::path::Path;

/// Columns of `history.csv` in `dir`: header names and rows of numbers.
pub fn read_history(dir: &Path) -> Result<(Vec<String>, Vec<Vec<f64>>), String> {
    read_table(&dir.join("history.csv"))
}

/// Columns of a CSV file of numbers with a header line.
fn read_table(path: &Path) -> Result<(Vec<String>, Vec<Vec<f64>>), String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let mut lines = text.lines();
    let header = split_csv(lines.next().unwrap_or_default());
    let rows = lines
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            split_csv(l)
                .iter()
                .map(|v| v.parse::<f64>().map_err(|e| format!("{v}: {e}")))
                .collect::<Result<Vec<f64>, String>>()
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok((header, rows))
}

/// Splits a CSV line (RFC 4180 quoting).
fn split_csv(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut cur = String::new();
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '"' if quoted && chars.peek() == Some(&'"') => {
                cur.push('"');
                chars.next();
            }
            '"' => quoted = !quoted,
            ',' if !quoted => out.push(std::mem::take(&mut cur)),
            _ => cur.push(c),
        }
    }
    out.push(cur);
    out
}

/// Writes `file` (SVG) in `dir`: column `y` (scaled by `y_scale`) against
/// column `x` (scaled by `x_scale`) of the run in `dir`, starting from the
/// point `(0, y0)` (none when `y0` is NaN). Returns whether the plot was
/// written: a history without a finite point (a run that stopped before
/// its first converged increment) or whose values span no drawable range
/// gives no plot, never a hang (the axis ranges are always finite and
/// wide enough for their key points, see [`axis_range`]).
#[allow(clippy::too_many_arguments)]
pub fn history_plot(
    dir: &Path,
    file: &str,
    title: &str,
    (x, x_scale, x_desc): (&str, f64, &str),
    (y, y_scale, y_desc): (&str, f64, &str),
    y0: f64,
) -> Result<bool, String> {
    let (header, rows) = read_history(dir)?;
    table_plot(
        dir,
        (&header, &rows),
        file,
        title,
        (x, x_scale, x_desc),
        (y, y_scale, y_desc),
        y0,
    )
}

/// [`history_plot`] of the columns of any table `(header, rows)`.
#[allow(clippy::too_many_arguments)]
fn table_plot(
    dir: &Path,
    (header, rows): (&[String], &[Vec<f64>]),
    file: &str,
    title: &str,
    (x, x_scale, x_desc): (&str, f64, &str),
    (y, y_scale, y_desc): (&str, f64, &str),
    y0: f64,
) -> Result<bool, String> {
    let col = |name: &str| {
        header
            .iter()
            .position(|h| h == name)
            .ok_or_else(|| format!("history.csv has no column `{name}` ({header:?})"))
    };
    let (ix, iy) = (col(x)?, col(y)?);
    if rows.is_empty() {
        return Ok(false);
    }
    let mut points = if y0.is_nan() { vec![] } else { vec![(0.0, y0)] };
    points.extend(
        rows.iter()
            .filter(|r| r.len() > ix.max(iy))
            .map(|r| (r[ix] * x_scale, r[iy] * y_scale)),
    );
    points.retain(|p| p.0.is_finite() && p.1.is_finite());
    let (mut x_lo, mut x_hi, mut y_lo, mut y_hi) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for &(px, py) in &points {
        x_lo = x_lo.min(px);
        x_hi = x_hi.max(px);
        y_lo = y_lo.min(py);
        y_hi = y_hi.max(py);
    }
    let (Some((x_lo, x_hi)), Some((y_lo, y_hi))) = (axis_range(x_lo, x_hi), axis_range(y_lo, y_hi))
    else {
        return Ok(false);
    };
    let path = dir.join(file);
    let root = SVGBackend::new(&path, (800, 560)).into_drawing_area();
    let e = |e: DrawingAreaErrorKind<std::io::Error>| format!("cannot draw `{title}`: {e:?}");
    root.fill(&WHITE).map_err(e)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 18))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(x_lo..x_hi, y_lo..y_hi)
        .map_err(e)?;
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .x_label_formatter(&|x| crate::plot::tick(*x))
        .y_label_formatter(&|y| crate::plot::tick(*y))
        .draw()
        .map_err(e)?;
    let c = colour(0);
    chart
        .draw_series(LineSeries::new(points.clone(), c.stroke_width(2)))
        .map_err(e)?;
    chart
        .draw_series(points.iter().map(move |&p| Circle::new(p, 3, c.filled())))
        .map_err(e)?;
    root.present().map_err(e)?;
    Ok(true)
}

/// The padded axis range of values between `lo` and `hi`, or `None` when
/// there is nothing drawable (no value: `lo > hi`; non-finite bounds or
/// span). A range narrower than `1e-6` of its magnitude is widened to it:
/// plotters steps its key points from `lo` to `hi` and a step below the
/// spacing of floating-point numbers there never reaches `hi`.
pub fn axis_range(lo: f64, hi: f64) -> Option<(f64, f64)> {
    if !(lo.is_finite() && hi.is_finite() && lo <= hi) {
        return None;
    }
    let magnitude = lo.abs().max(hi.abs());
    if magnitude > 1e300 {
        return None;
    }
    let min_span = (1e-6 * magnitude).max(1e-12);
    let (lo, hi) = if hi - lo < min_span {
        let mid = 0.5 * (lo + hi);
        (mid - 0.5 * min_span, mid + 0.5 * min_span)
    } else {
        (lo, hi)
    };
    let d = 0.05 * (hi - lo);
    Some((lo - d, hi + d))
}

/// The unit of an axis among the deck's declared units.
type Unit = fn(&ctc_engine::model::UnitNames) -> &str;

/// An axis title: `what [unit]` when the deck declares its units.
fn axis_title(what: &str, unit: Unit, units: Option<&ctc_engine::model::UnitNames>) -> String {
    match units {
        Some(u) => format!("{what} [{}]", unit(u)),
        None => what.to_string(),
    }
}

/// The axis (`"_x"`, `"_y"` or `"_z"`) along which the first
/// `displacement(..)` column of the history travels farthest (`"_x"`
/// without one; ties keep the earlier axis).
fn travel_axis(header: &[String], rows: &[Vec<f64>]) -> &'static str {
    let travel = |name: &str| {
        let Some(i) = header.iter().position(|h| h == name) else {
            return 0.0;
        };
        let v = rows.iter().filter_map(|r| r.get(i)).copied();
        let (lo, hi) = v.fold((f64::MAX, f64::MIN), |(a, b), x| (a.min(x), b.max(x)));
        if hi >= lo {
            hi - lo
        } else {
            0.0
        }
    };
    let Some(first) = header.iter().find(|h| h.starts_with("displacement(")) else {
        return "_x";
    };
    let stem = &first[..first.len().saturating_sub(2)];
    let mut best = ("_x", travel(&format!("{stem}_x")));
    for axis in ["_y", "_z"] {
        let t = travel(&format!("{stem}{axis}"));
        if t > best.1 {
            best = (axis, t);
        }
    }
    best.0
}

/// Plots of a thermo-mechanical run in `dir` (called by `ctc run` for
/// thermal scenes): `temperature.svg` (largest temperature against time)
/// and, when the history has a `reaction(..)` (or `contact_force(..)`) and
/// a `displacement(..)` column, `force_stroke.svg` (minus the first
/// reaction's component against minus the first displacement's, along the
/// axis where that displacement travels farthest ([`travel_axis`]): a push
/// downwards in 2D, the axial feed of `examples/tube_hydroforming.ctc`).
/// Returns the files written (none for an empty history: a run that
/// stopped before its first converged increment). Axis titles carry the
/// deck's units when it declares a system.
pub fn thermal_run_plots(
    dir: &Path,
    units: Option<&ctc_engine::model::UnitNames>,
) -> Result<Vec<String>, String> {
    let (header, rows) = read_history(dir)?;
    let with = |what: &str, unit: Unit| axis_title(what, unit, units);
    let mut files = Vec::new();
    if header.iter().any(|h| h == "temperature_max")
        && history_plot(
            dir,
            "temperature.svg",
            "largest temperature",
            ("time", 1.0, &with("time", |u| &u.time)),
            (
                "temperature_max",
                1.0,
                &with("max temperature", |u| &u.temperature),
            ),
            f64::NAN,
        )?
    {
        files.push("temperature.svg".to_string());
    }
    let axis = travel_axis(&header, &rows);
    let find = |prefix: &str| {
        header
            .iter()
            .find(|h| h.starts_with(prefix) && h.ends_with(axis))
            .cloned()
    };
    if let (Some(f), Some(u)) = (
        find("reaction(").or_else(|| find("contact_force(")),
        find("displacement("),
    ) {
        let c = &axis[1..];
        if history_plot(
            dir,
            "force_stroke.svg",
            "force against stroke",
            (&u, -1.0, &with(&format!("stroke (-u_{c})"), |u| &u.length)),
            (&f, -1.0, &with(&format!("force (-F_{c})"), |u| &u.force)),
            0.0,
        )? {
            files.push("force_stroke.svg".to_string());
        }
    }
    Ok(files)
}

/// Plots of a run with a pressure-cycle controller (called by `ctc run`
/// when a follower pressure has `control = strain_rate { .. }`): for each
/// controlled pressure, `pressure_cycle.svg` (the applied pressure against
/// time: the optimised cycle of superplastic forming) and
/// `controlled_rate.svg` (the monitored strain rate against time), numbered
/// `_2`, `_3`, .. after the first controller. Returns the files written.
pub fn pressure_cycle_plots(
    dir: &Path,
    units: Option<&ctc_engine::model::UnitNames>,
) -> Result<Vec<String>, String> {
    let (header, _) = read_history(dir)?;
    let with = |what: &str, unit: Unit| axis_title(what, unit, units);
    let mut files = Vec::new();
    let pressures = header
        .iter()
        .filter(|h| h.starts_with("controlled_pressure["));
    for (k, p) in pressures.enumerate() {
        let label = &p["controlled_pressure".len()..];
        let rate = format!("controlled_rate{label}");
        let time = with("time", |u| &u.time);
        let file = numbered("pressure_cycle", k);
        let title = format!("controlled pressure {label}");
        let y = with("pressure", |u| &u.stress);
        if against_time(dir, &file, &title, &time, p, &y)? {
            files.push(file);
        }
        if header.contains(&rate) {
            let file = numbered("controlled_rate", k);
            let title = format!("monitored strain rate {label}");
            let y = "equivalent plastic strain rate";
            if against_time(dir, &file, &title, &time, &rate, y)? {
                files.push(file);
            }
        }
    }
    Ok(files)
}

/// `STEM.svg` for the first of several plots of one kind (`k = 0`),
/// `STEM_2.svg`, `STEM_3.svg`, .. after it.
fn numbered(stem: &str, k: usize) -> String {
    if k == 0 {
        format!("{stem}.svg")
    } else {
        format!("{stem}_{}.svg", k + 1)
    }
}

/// The `history.csv` column `column` against time into `file` (y axis
/// titled `y`); whether it was written.
fn against_time(
    dir: &Path,
    file: &str,
    title: &str,
    time: &str,
    column: &str,
    y: &str,
) -> Result<bool, String> {
    history_plot(
        dir,
        file,
        title,
        ("time", 1.0, time),
        (column, 1.0, y),
        f64::NAN,
    )
}

/// The plots of `ctc run` for follower pressures driven by a time function
/// (`examples/tube_hydroforming.ctc`): `pressure_time.svg`, each
/// `pressure[label]` column of `history.csv` against time (one file per
/// pressure, numbered `_2`, `_3`, .. after the first). Returns the files
/// written.
pub fn pressure_time_plots(
    dir: &Path,
    units: Option<&ctc_engine::model::UnitNames>,
) -> Result<Vec<String>, String> {
    let (header, _) = read_history(dir)?;
    let with = |what: &str, unit: Unit| axis_title(what, unit, units);
    let mut files = Vec::new();
    let pressures = header.iter().filter(|h| h.starts_with("pressure["));
    for (k, p) in pressures.enumerate() {
        let file = numbered("pressure_time", k);
        let title = format!("applied pressure {}", &p["pressure".len()..]);
        let (time, y) = (with("time", |u| &u.time), with("pressure", |u| &u.stress));
        if against_time(dir, &file, &title, &time, p, &y)? {
            files.push(file);
        }
    }
    Ok(files)
}

/// The plots of `ctc run` for roughness histories (`history = [..,
/// roughness(set)]`, e.g. `examples/skin_pass_rough.ctc`):
/// `roughness.svg`, each `<label>_Ra` column against time (numbered `_2`,
/// .. after the first), and `contact_force.svg`, the first contact force's
/// largest component (the rolling force of a skin pass: along y) against
/// time, negated when it is mostly negative (the force of the tool on the
/// body pushes down). Returns the files written.
pub fn roughness_plots(
    dir: &Path,
    units: Option<&ctc_engine::model::UnitNames>,
) -> Result<Vec<String>, String> {
    let (header, rows) = read_history(dir)?;
    let with = |what: &str, unit: Unit| axis_title(what, unit, units);
    let time = with("time", |u| &u.time);
    let mut files = Vec::new();
    let ras = header
        .iter()
        .filter(|h| h.starts_with("roughness(") && h.ends_with("_Ra"));
    for (k, c) in ras.enumerate() {
        let file = numbered("roughness", k);
        let title = format!("surface roughness {c}");
        if against_time(dir, &file, &title, &time, c, &with("Ra", |u| &u.length))? {
            files.push(file);
        }
    }
    // the contact force component that varies most
    let forces: Vec<usize> = header
        .iter()
        .enumerate()
        .filter(|(_, h)| h.starts_with("contact_force("))
        .map(|(i, _)| i)
        .collect();
    let span = |i: usize| {
        rows.iter()
            .filter_map(|r| r.get(i))
            .fold(0.0f64, |m, v| m.max(v.abs()))
    };
    if let Some(&i) = forces.iter().max_by(|&&a, &&b| span(a).total_cmp(&span(b))) {
        let sum: f64 = rows.iter().filter_map(|r| r.get(i)).sum();
        let sign = if sum < 0.0 { -1.0 } else { 1.0 };
        let name = &header[i];
        let y_desc = if sign < 0.0 {
            format!("-{name}")
        } else {
            name.clone()
        };
        if history_plot(
            dir,
            "contact_force.svg",
            &format!("contact force {name} against time"),
            ("time", 1.0, &time),
            (name, sign, &with(&y_desc, |u| &u.force)),
            0.0,
        )? {
            files.push("contact_force.svg".to_string());
        }
    }
    Ok(files)
}

/// The plot of `ctc run` for a thickness map (`output { thickness = (a, b)
/// }`): `thickness.svg`, the thickness of the first face set's nodes at the
/// last written increment against their reference distance from the
/// origin (`thickness.csv`: the radius of a sheet centred on the origin).
/// Returns the files written (none without `thickness.csv`).
pub fn thickness_plots(
    dir: &Path,
    units: Option<&ctc_engine::model::UnitNames>,
) -> Result<Vec<String>, String> {
    let path = dir.join("thickness.csv");
    if !path.exists() {
        return Ok(Vec::new());
    }
    let (header, rows) = read_table(&path)?;
    let with = |what: &str, unit: Unit| axis_title(what, unit, units);
    let written = table_plot(
        dir,
        (&header, &rows),
        "thickness.svg",
        "thickness at the last written increment",
        (
            "distance0",
            1.0,
            &with("reference distance from the origin", |u| &u.length),
        ),
        ("thickness", 1.0, &with("thickness", |u| &u.length)),
        f64::NAN,
    )?;
    Ok(if written {
        vec!["thickness.svg".to_string()]
    } else {
        Vec::new()
    })
}

/// The plots of `ctc run` for a model with free tools
/// (`rotation = free`, e.g. `examples/blankholder.ctc`):
/// `force_stroke.svg`, the first `reaction(..)` against the first
/// `displacement(..)` along the axis where that displacement travels
/// farthest (the drawing force against the stroke), and `angle.svg`, the
/// first free tool's angle against time. Returns the files written.
pub fn free_tool_run_plots(
    dir: &Path,
    units: Option<&ctc_engine::model::UnitNames>,
) -> Result<Vec<String>, String> {
    let (header, rows) = read_history(dir)?;
    let with = |what: &str, unit: Unit| axis_title(what, unit, units);
    let mut files = Vec::new();
    let first = |prefix: &str, axis: &str| {
        header
            .iter()
            .find(|h| h.starts_with(prefix) && h.ends_with(axis))
            .cloned()
    };
    let axis = travel_axis(&header, &rows);
    if let (Some(f), Some(u)) = (first("reaction(", axis), first("displacement(", axis)) {
        let c = &axis[1..];
        if history_plot(
            dir,
            "force_stroke.svg",
            "drawing force against stroke",
            (&u, 1.0, &with(&format!("stroke (u_{c})"), |u| &u.length)),
            (&f, 1.0, &with(&format!("force (F_{c})"), |u| &u.force)),
            0.0,
        )? {
            files.push("force_stroke.svg".to_string());
        }
    }
    if let Some(a) = header.iter().find(|h| h.starts_with("angle[")).cloned() {
        if history_plot(
            dir,
            "angle.svg",
            &format!("{a} (free tool)"),
            ("time", 1.0, &with("time", |u| &u.time)),
            (&a, 1.0, "angle [rad]"),
            0.0,
        )? {
            files.push("angle.svg".to_string());
        }
    }
    Ok(files)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_stroke_axis_is_where_the_displacement_travels_farthest() {
        let header: Vec<String> = [
            "time",
            "reaction(t.zmax)_x",
            "displacement(t.zmax)_x",
            "displacement(t.zmax)_y",
            "displacement(t.zmax)_z",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        let rows = [
            vec![0.5, 1.0, 0.1, 0.0, -3.0],
            vec![1.0, 2.0, 0.2, 0.1, -6.0],
        ];
        assert_eq!(travel_axis(&header, &rows), "_z");
        assert_eq!(travel_axis(&header[..4], &rows), "_x");
        assert_eq!(travel_axis(&header[..2], &rows), "_x");
    }

    #[test]
    fn the_thickness_plot_reads_thickness_csv() {
        let dir = tempfile::tempdir().unwrap();
        assert!(thickness_plots(dir.path(), None).unwrap().is_empty());
        std::fs::write(
            dir.path().join("thickness.csv"),
            "node,x0,y0,z0,x,y,z,distance0,thickness\n3,0,0,1,0,0,9,1,0.7\n5,10,0,1,10,0,8,10.05,0.8\n",
        )
        .unwrap();
        let units = ctc_lang::units::system("mm_N_s").map(|s| s.names());
        assert_eq!(
            thickness_plots(dir.path(), units.as_ref()).unwrap(),
            ["thickness.svg"]
        );
        let t = std::fs::read_to_string(dir.path().join("thickness.svg")).unwrap();
        assert!(t.contains("thickness [mm]"), "{t}");
    }

    #[test]
    fn the_roughness_plots_read_ra_and_the_rolling_force() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(
            dir.path().join("history.csv"),
            "time,\"contact_force(s.top -> roll)_x\",\"contact_force(s.top -> roll)_y\",\
             roughness(s.rolled)_Ra,roughness(s.rolled)_Rq,roughness(s.rolled)_mean\n\
             1,0.5,-100,0.001,0.0012,0.4\n2,-0.7,-150,0.002,0.0025,0.399\n",
        )
        .unwrap();
        let units = ctc_lang::units::system("mm_N_s").map(|s| s.names());
        assert_eq!(
            roughness_plots(dir.path(), units.as_ref()).unwrap(),
            ["roughness.svg", "contact_force.svg"]
        );
        let t = std::fs::read_to_string(dir.path().join("roughness.svg")).unwrap();
        assert!(t.contains("Ra [mm]"), "{t}");
        // the rolling force: the y component, negated (it pushes down)
        let f = std::fs::read_to_string(dir.path().join("contact_force.svg")).unwrap();
        assert!(
            f.contains("-contact_force(s.top -&gt; roll)_y [N]")
                || f.contains("-contact_force(s.top -> roll)_y [N]"),
            "{f}"
        );
    }

    #[test]
    fn csv_fields_with_quotes_and_arrows_split_right() {
        assert_eq!(split_csv("time,\"a,b\",x -> y"), ["time", "a,b", "x -> y"]);
    }

    #[test]
    fn a_history_column_plot_is_written() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(
            dir.path().join("history.csv"),
            "time,f_y,u_y,temperature_max\n0.5,-10,-1,21\n1,-30,-2,25\n",
        )
        .unwrap();
        assert!(history_plot(
            dir.path(),
            "force.svg",
            "force against stroke",
            ("u_y", -1.0, "stroke"),
            ("f_y", -1.0, "force"),
            0.0,
        )
        .unwrap());
        let svg = std::fs::read_to_string(dir.path().join("force.svg")).unwrap();
        assert!(svg.contains("<polyline") || svg.contains("<path"), "{svg}");
        assert!(history_plot(
            dir.path(),
            "x.svg",
            "x",
            ("nope", 1.0, "x"),
            ("f_y", 1.0, "y"),
            0.0
        )
        .is_err());
    }

    #[test]
    fn thermal_plots_title_their_axes_with_the_deck_units() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(
            dir.path().join("history.csv"),
            "time,temperature_max,reaction(a.b)_y,displacement(a.c)_y\n\
             0.5,300,-10,-0.1\n1,320,-30,-0.2\n",
        )
        .unwrap();
        let units = ctc_lang::units::system("mm_N_s").map(|s| s.names());
        let files = thermal_run_plots(dir.path(), units.as_ref()).unwrap();
        assert_eq!(files, ["temperature.svg", "force_stroke.svg"]);
        let t = std::fs::read_to_string(dir.path().join("temperature.svg")).unwrap();
        assert!(
            t.contains("time [s]") && t.contains("max temperature [K]"),
            "{t}"
        );
        let f = std::fs::read_to_string(dir.path().join("force_stroke.svg")).unwrap();
        assert!(f.contains("stroke (-u_y) [mm]") && f.contains("force (-F_y) [N]"));
        thermal_run_plots(dir.path(), None).unwrap();
        let f = std::fs::read_to_string(dir.path().join("force_stroke.svg")).unwrap();
        assert!(f.contains("stroke (-u_y)") && !f.contains("[mm]"), "{f}");
    }

    #[test]
    fn an_empty_or_degenerate_history_gives_no_plot_and_returns() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("history.csv"), "time,temperature_max\n").unwrap();
        assert_eq!(
            thermal_run_plots(dir.path(), None).unwrap(),
            Vec::<String>::new()
        );
        assert!(!dir.path().join("temperature.svg").exists());
        // one row, a value far above its spread, NaN: drawn or skipped, never a hang
        std::fs::write(
            dir.path().join("history.csv"),
            "time,temperature_max\n1,1e6\n2,NaN\n",
        )
        .unwrap();
        assert_eq!(
            thermal_run_plots(dir.path(), None).unwrap(),
            ["temperature.svg"]
        );
        assert_eq!(axis_range(f64::MAX, f64::MIN), None);
        assert_eq!(axis_range(0.0, f64::INFINITY), None);
        let (lo, hi) = axis_range(1e6, 1e6).unwrap();
        assert!(hi - lo >= 1.0 && lo < 1e6 && hi > 1e6, "{lo} {hi}");
    }
}
