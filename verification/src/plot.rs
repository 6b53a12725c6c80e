//! SVG plots of a verification report (plotters, SVG backend, built-in
//! text metrics: no font files involved).
//!
//! Per case: the contact pressure profile of every level against Hertz
//! (normalised `p / p0` against `x / a`, so all levels share one curve),
//! the errors against the mesh size (log-log, with the observed slope
//! visible) and the errors against the solve wall time (log-log).
//! Quantities whose errors are all at round-off level are left out of the
//! error plots (a case with only such quantities gets none).

use crate::case::Quantity;
use crate::report::{CaseReport, LevelReport, ROUND_OFF};
use plotters::prelude::*;
use std::path::Path;

/// Size of every plot, pixels.
const SIZE: (u32, u32) = (800, 560);

/// A plot written to disk.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct PlotFile {
    /// Case name.
    pub case: String,
    /// What it shows: `profile`, `convergence` or `time`.
    pub kind: String,
    /// File name inside the report directory.
    pub file: String,
}

/// Writes every plot of `case` into `dir`; returns the files written.
pub fn case_plots(case: &CaseReport, dir: &Path) -> Result<Vec<PlotFile>, String> {
    let mut files = Vec::new();
    let ok: Vec<&LevelReport> = case.levels.iter().filter(|l| l.failure.is_none()).collect();
    if ok.iter().any(|l| l.profile.is_some()) {
        let file = format!("{}_profile.svg", case.name);
        profile_plot(case, &ok, &dir.join(&file))?;
        files.push(PlotFile {
            case: case.name.clone(),
            kind: "profile".into(),
            file,
        });
    }
    if !ok.is_empty() {
        let file = format!("{}_convergence.svg", case.name);
        if error_plot(case, &ok, &dir.join(&file), Axis::MeshSize)? {
            files.push(PlotFile {
                case: case.name.clone(),
                kind: "convergence".into(),
                file,
            });
        }
        let file = format!("{}_time.svg", case.name);
        if error_plot(case, &ok, &dir.join(&file), Axis::WallTime)? {
            files.push(PlotFile {
                case: case.name.clone(),
                kind: "time".into(),
                file,
            });
        }
    }
    // the figures of a program case (histories of its runs): those of the
    // finest level that measured some
    if let Some(level) = ok.iter().rev().find(|l| !l.figures.is_empty()) {
        for f in &level.figures {
            let file = format!("{}_{}.svg", case.name, f.name);
            if figure_plot(f, level.level, &dir.join(&file))? {
                files.push(PlotFile {
                    case: case.name.clone(),
                    kind: f.name.clone(),
                    file,
                });
            }
        }
    }
    Ok(files)
}

/// One curve of a [`Panel`]: its legend and its points.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize)]
pub struct Curve {
    /// Legend.
    pub label: String,
    /// `(x, y)` points in order (non-finite ones are not drawn).
    pub points: Vec<(f64, f64)>,
}

/// One chart of a [`Figure`]: linear axes, one colour per curve.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize)]
pub struct Panel {
    /// Title of the chart.
    pub title: String,
    /// Abscissa title.
    pub x_desc: String,
    /// Ordinate title.
    pub y_desc: String,
    /// The curves (the i-th in [`colour`] `i` on every panel).
    pub curves: Vec<Curve>,
}

/// A figure a program case measures (e.g. the force histories of its
/// runs), drawn by [`case_plots`] into `{case}_{name}.svg` for the finest
/// level that has it: its panels stacked vertically.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize)]
pub struct Figure {
    /// File suffix and plot kind (`forces`, `iterations`).
    pub name: String,
    /// The panels, top to bottom.
    pub panels: Vec<Panel>,
}

/// Draws `figure` (of level `level`) into `path`. Returns false (and
/// writes nothing) when no panel has a finite point.
fn figure_plot(figure: &Figure, level: usize, path: &Path) -> Result<bool, String> {
    let bounds = |p: &Panel| {
        let pts = p.curves.iter().flat_map(|c| c.points.iter());
        let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for &(x, y) in pts.filter(|q| q.0.is_finite() && q.1.is_finite()) {
            (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
        }
        Some((
            crate::history_plot::axis_range(x0, x1)?,
            crate::history_plot::axis_range(y0, y1)?,
        ))
    };
    let panels: Vec<_> = figure
        .panels
        .iter()
        .filter_map(|p| Some((p, bounds(p)?)))
        .collect();
    if panels.is_empty() {
        return Ok(false);
    }
    let e = err(path);
    let height = SIZE.1 * panels.len() as u32;
    let root = SVGBackend::new(path, (SIZE.0, height)).into_drawing_area();
    root.fill(&WHITE).map_err(&e)?;
    let areas = root.split_evenly((panels.len(), 1));
    for (area, (panel, ((x0, x1), (y0, y1)))) in areas.iter().zip(panels) {
        let mut chart = ChartBuilder::on(area)
            .caption(
                format!("{} (level {level})", panel.title),
                ("sans-serif", 20),
            )
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(70)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(&e)?;
        chart
            .configure_mesh()
            .x_desc(panel.x_desc.as_str())
            .y_desc(panel.y_desc.as_str())
            .x_label_formatter(&|x| tick(*x))
            .y_label_formatter(&|y| tick(*y))
            .draw()
            .map_err(&e)?;
        for (i, c) in panel.curves.iter().enumerate() {
            let colour = colour(i);
            let pts: Vec<(f64, f64)> = c
                .points
                .iter()
                .copied()
                .filter(|q| q.0.is_finite() && q.1.is_finite())
                .collect();
            chart
                .draw_series(LineSeries::new(pts.clone(), colour.stroke_width(2)))
                .map_err(&e)?;
            chart
                .draw_series(
                    pts.into_iter()
                        .map(move |q| Circle::new(q, 3, colour.filled())),
                )
                .map_err(&e)?
                .label(c.label.clone())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2))
                });
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .label_font(("sans-serif", 13))
            .position(SeriesLabelPosition::UpperLeft)
            .draw()
            .map_err(&e)?;
    }
    root.present().map_err(&e)?;
    Ok(true)
}

/// Colour of the i-th series.
pub(crate) fn colour(i: usize) -> RGBColor {
    const C: [RGBColor; 6] = [
        RGBColor(31, 119, 180),
        RGBColor(255, 127, 14),
        RGBColor(44, 160, 44),
        RGBColor(214, 39, 40),
        RGBColor(148, 103, 189),
        RGBColor(140, 86, 75),
    ];
    C[i % C.len()]
}

/// A readable axis tick: plain decimals between 1e-2 and 1e4 (at most
/// three significant digits, no trailing zeros), `2.5e-3` style outside,
/// `1e-3` for powers of ten; the shortest form that tells ticks apart on
/// a log axis.
pub(crate) fn tick(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let a = x.abs();
    if (1e-2..1e4).contains(&a) {
        let digits = (2 - a.log10().floor() as i32).max(0) as usize;
        let s = format!("{x:.digits$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    } else {
        let s = format!("{x:.1e}");
        s.replace(".0e", "e")
    }
}

/// The observed rate of a series of `(h, error)` points: the slope of
/// `log error` against `log h` over its two smallest `h` (the finest
/// pair, as the report's rate table judges it). `None` with fewer than
/// two distinct `h`.
pub(crate) fn finest_slope(points: &[(f64, f64)]) -> Option<f64> {
    let mut p: Vec<(f64, f64)> = points.to_vec();
    p.sort_by(|a, b| a.0.total_cmp(&b.0));
    p.dedup_by(|a, b| a.0 == b.0);
    let (&(h1, e1), &(h2, e2)) = (p.get(1)?, p.first()?);
    let r = (e1 / e2).ln() / (h1 / h2).ln();
    r.is_finite().then_some(r)
}

/// Maps a plotters error to a message.
pub(crate) fn err<E: std::fmt::Debug>(what: &Path) -> impl Fn(E) -> String + '_ {
    move |e| format!("cannot draw {}: {e:?}", what.display())
}

/// `p / p0` against `x / a` for every level, with the Hertz ellipse.
fn profile_plot(case: &CaseReport, levels: &[&LevelReport], path: &Path) -> Result<(), String> {
    let e = err(path);
    let root = SVGBackend::new(path, SIZE).into_drawing_area();
    root.fill(&WHITE).map_err(&e)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            format!("{}: contact pressure vs Hertz", case.name),
            ("sans-serif", 22),
        )
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(60)
        .build_cartesian_2d(0.0..1.5f64, 0.0..1.2f64)
        .map_err(&e)?;
    chart
        .configure_mesh()
        .x_desc("x / a (Hertz a for the computed load)")
        .y_desc("p / p0")
        .draw()
        .map_err(&e)?;
    let hertz: Vec<(f64, f64)> = (0..=300)
        .map(|i| {
            let x = 1.5 * i as f64 / 300.0;
            (x, if x < 1.0 { (1.0 - x * x).sqrt() } else { 0.0 })
        })
        .collect();
    chart
        .draw_series(LineSeries::new(hertz, BLACK.stroke_width(2)))
        .map_err(&e)?
        .label("Hertz")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.stroke_width(2)));
    for (i, l) in levels.iter().enumerate() {
        let Some(p) = &l.profile else { continue };
        let c = colour(i);
        let pts: Vec<(f64, f64)> = p
            .points
            .iter()
            .map(|q| (q[0] / p.a, q[1] / p.p0))
            .filter(|q| q.0 <= 1.5)
            .collect();
        chart
            .draw_series(LineSeries::new(pts.clone(), c.stroke_width(1)))
            .map_err(&e)?;
        chart
            .draw_series(pts.into_iter().map(move |q| Circle::new(q, 3, c.filled())))
            .map_err(&e)?
            .label(format!("level {} (h = {:.2e})", l.level, l.h))
            .legend(move |(x, y)| Circle::new((x + 10, y), 3, c.filled()));
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(&e)?;
    root.present().map_err(&e)?;
    Ok(())
}

/// Abscissa of an error plot.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Axis {
    /// Characteristic mesh size h.
    MeshSize,
    /// Solve wall time.
    WallTime,
}

/// Log-log errors of every quantity against h or wall time. Returns false
/// (and writes nothing) when no positive error/abscissa pair exists.
fn error_plot(
    case: &CaseReport,
    levels: &[&LevelReport],
    path: &Path,
    axis: Axis,
) -> Result<bool, String> {
    let abscissa = |l: &LevelReport| match axis {
        Axis::MeshSize => l.h,
        Axis::WallTime => l.solve_time,
    };
    let series: Vec<(Quantity, Vec<(f64, f64)>)> = case
        .quantities()
        .into_iter()
        .map(|q| {
            let pts = levels
                .iter()
                .filter_map(|l| Some((abscissa(l), l.error_of(q)?)))
                .filter(|(x, y)| *x > 0.0 && *y > 0.0 && x.is_finite() && y.is_finite())
                .collect::<Vec<_>>();
            (q, pts)
        })
        // Round-off-level quantities (force balance, patch tests) would
        // only squash the scale: they are in the tables.
        .filter(|(_, p)| p.iter().any(|&(_, e)| e > ROUND_OFF))
        .collect();
    if series.is_empty() {
        return Ok(false);
    }
    let all = series.iter().flat_map(|(_, p)| p.iter());
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, 0.0f64, f64::INFINITY, 0.0f64);
    for &(x, y) in all {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    let (x0, x1) = (x0 / 1.5, x1 * 1.5);
    let (y0, y1) = (y0 / 3.0, y1 * 3.0);
    let e = err(path);
    let root = SVGBackend::new(path, SIZE).into_drawing_area();
    root.fill(&WHITE).map_err(&e)?;
    let (title, xdesc) = match axis {
        Axis::MeshSize => (
            format!("{}: relative error vs mesh size", case.name),
            "mesh size h [deck length unit]",
        ),
        Axis::WallTime => (
            format!("{}: relative error vs solve time", case.name),
            "wall time [s]",
        ),
    };
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 22))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())
        .map_err(&e)?;
    chart
        .configure_mesh()
        .x_desc(xdesc)
        .y_desc("relative error")
        .x_label_formatter(&|x| tick(*x))
        .y_label_formatter(&|y| tick(*y))
        .draw()
        .map_err(&e)?;
    for (i, (q, pts)) in series.into_iter().enumerate() {
        let c = colour(i);
        // the slope on the finest pair, in the legend: rate against h,
        // error per time against the wall time
        let label = match (finest_slope(&pts), axis) {
            (Some(r), Axis::MeshSize) => format!("{} (rate {r:.2})", q.name()),
            (Some(r), Axis::WallTime) => format!("{} (slope {r:.2})", q.name()),
            (None, _) => q.name().to_string(),
        };
        chart
            .draw_series(LineSeries::new(pts.clone(), c.stroke_width(2)))
            .map_err(&e)?;
        chart
            .draw_series(pts.into_iter().map(move |p| Circle::new(p, 4, c.filled())))
            .map_err(&e)?
            .label(label)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2)));
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .position(SeriesLabelPosition::LowerRight)
        .draw()
        .map_err(&e)?;
    root.present().map_err(&e)?;
    Ok(true)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::measure::ProfileData;
    use crate::report::Judged;

    fn level(level: usize, h: f64, error: f64) -> LevelReport {
        LevelReport {
            level,
            h,
            nodes: 10,
            free_dofs: 16,
            increments: 1,
            newton_total: 2,
            newton_max: 2,
            cutbacks: 0,
            solve_time: 0.01 * (level + 1) as f64,
            compile_time: 0.0,
            values: vec![Judged {
                quantity: Quantity::HalfWidth,
                reference: Some(0.1),
                computed: 0.1 * (1.0 + error),
                error,
                tolerance: None,
                passed: true,
            }],
            failure: None,
            max_penetration: 0.0,
            contact_iterations: 0,
            figures: Vec::new(),
            profile: Some(ProfileData {
                points: (0..20)
                    .map(|i| {
                        [
                            i as f64 * 0.01,
                            (1.0 - (i as f64 * 0.1).powi(2)).max(0.0).sqrt(),
                        ]
                    })
                    .collect(),
                a: 0.1,
                p0: 1.0,
                a_computed: 0.1,
            }),
        }
    }

    #[test]
    fn plots_are_written_as_svg() {
        let dir = tempfile::tempdir().unwrap();
        let case = CaseReport {
            name: "hertz_test".into(),
            title: "t".into(),
            source: "s".into(),
            deck: "d".into(),
            levels: vec![level(0, 0.02, 0.04), level(1, 0.01, 0.01)],
            rates: vec![],
            failure: None,
        };
        let files = case_plots(&case, dir.path()).unwrap();
        let kinds: Vec<&str> = files.iter().map(|f| f.kind.as_str()).collect();
        assert_eq!(kinds, ["profile", "convergence", "time"]);
        for f in files {
            let text = std::fs::read_to_string(dir.path().join(&f.file)).unwrap();
            assert!(text.starts_with("<svg"), "{}", &text[..40.min(text.len())]);
            assert!(text.contains("<circle"), "{} has no data points", f.file);
        }
        // errors 0.04 -> 0.01 as h halves: the legend says rate 2.00
        let conv = std::fs::read_to_string(dir.path().join("hertz_test_convergence.svg")).unwrap();
        assert!(conv.contains("(rate 2.00)"), "{conv}");
        assert!(conv.contains("mesh size h [deck length unit]"));
    }

    /// A program level's figures are drawn from the finest level that has
    /// them, one SVG per figure, every panel and legend in it; a figure
    /// without a finite point gives no file.
    #[test]
    fn figures_of_a_program_case_are_drawn() {
        let dir = tempfile::tempdir().unwrap();
        let curve = |label: &str, k: f64| Curve {
            label: label.into(),
            points: (0..10).map(|i| (i as f64, k * i as f64)).collect(),
        };
        let panel = |title: &str| Panel {
            title: title.into(),
            x_desc: "time".into(),
            y_desc: "force".into(),
            curves: vec![curve("run a", 1.0), curve("run b", 2.0)],
        };
        let mut coarse = level(0, 0.02, 0.04);
        coarse.profile = None;
        let mut fine = level(1, 0.01, 0.01);
        fine.profile = None;
        coarse.figures = vec![Figure {
            name: "forces".into(),
            panels: vec![panel("coarse")],
        }];
        fine.figures = vec![
            Figure {
                name: "forces".into(),
                panels: vec![panel("normal force"), panel("tangential force")],
            },
            Figure {
                name: "empty".into(),
                panels: vec![Panel {
                    curves: vec![Curve {
                        label: "nothing".into(),
                        points: vec![(f64::NAN, 1.0)],
                    }],
                    ..Panel::default()
                }],
            },
        ];
        let case = CaseReport {
            name: "program_test".into(),
            title: "t".into(),
            source: "s".into(),
            deck: String::new(),
            levels: vec![coarse, fine],
            rates: vec![],
            failure: None,
        };
        let files = case_plots(&case, dir.path()).unwrap();
        let kinds: Vec<&str> = files.iter().map(|f| f.kind.as_str()).collect();
        assert_eq!(kinds, ["convergence", "time", "forces"]);
        let svg = std::fs::read_to_string(dir.path().join("program_test_forces.svg")).unwrap();
        for text in [
            "normal force (level 1)",
            "tangential force (level 1)",
            "run a",
            "run b",
        ] {
            assert!(svg.contains(text), "no `{text}` in the figure");
        }
        assert!(
            !svg.contains("coarse"),
            "the coarse level's figure was drawn"
        );
        assert!(!dir.path().join("program_test_empty.svg").exists());
    }

    #[test]
    fn ticks_are_short_and_tell_neighbours_apart() {
        let cases = [
            (1e-3, "1e-3"),
            (2.5e-3, "2.5e-3"),
            (0.01, "0.01"),
            (0.0125, "0.0125"),
            (0.3, "0.3"),
            (0.30000000000000004, "0.3"),
            (1.0, "1"),
            (2.5, "2.5"),
            (12.0, "12"),
            (150.0, "150"),
            (1e4, "1e4"),
            (-0.5, "-0.5"),
            (0.0, "0"),
        ];
        for (x, want) in cases {
            assert_eq!(tick(x), want, "{x}");
        }
    }

    #[test]
    fn finest_slope_takes_the_two_smallest_h() {
        let pts = [(0.04, 0.16), (0.01, 0.01), (0.02, 0.04 * 1.1)];
        let r = finest_slope(&pts).unwrap();
        assert!((r - (4.4f64).ln() / 2f64.ln()).abs() < 1e-12, "{r}");
        assert_eq!(finest_slope(&[(0.1, 1.0)]), None);
        assert_eq!(finest_slope(&[(0.1, 1.0), (0.1, 2.0)]), None);
    }
}
