//! SVG plots of the method studies: the work-precision plot (p0 error
//! against solve wall time, one curve per method across the refinement
//! levels), the penalty sweep (p0 error, penetration, Newton iterations
//! against k) and the penalty mesh scaling (gap and pressure error
//! against h).

use crate::case::Quantity;
use crate::methods::MethodComparison;
use crate::penalty::{PenaltyScaling, PenaltySweep, ScalingFlavour};
use crate::plot::{colour, PlotFile};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// One curve of a log-log panel.
struct Series {
    /// Legend label.
    label: String,
    /// Points (x, y), both > 0.
    points: Vec<(f64, f64)>,
    /// Draw the connecting line (false: markers only).
    line: bool,
}

/// Bounds of all positive finite points, widened for the log axes.
fn bounds(series: &[Series]) -> Option<(f64, f64, f64, f64)> {
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, 0.0f64, f64::INFINITY, 0.0f64);
    for &(x, y) in series.iter().flat_map(|s| s.points.iter()) {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    (x1 > 0.0 && y1 > 0.0).then_some((x0 / 1.5, x1 * 1.5, y0 / 2.0, y1 * 2.0))
}

/// Keeps the positive finite points (log axes).
fn positive(points: impl IntoIterator<Item = (f64, f64)>) -> Vec<(f64, f64)> {
    points
        .into_iter()
        .filter(|&(x, y)| x > 0.0 && y > 0.0 && x.is_finite() && y.is_finite())
        .collect()
}

/// Draws a log-log panel with a legend into `area`.
fn loglog(
    area: &DrawingArea<SVGBackend<'_>, Shift>,
    title: &str,
    xdesc: &str,
    ydesc: &str,
    series: &[Series],
) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<std::io::Error>| format!("cannot draw `{title}`: {e:?}");
    let Some((x0, x1, y0, y1)) = bounds(series) else {
        return Ok(());
    };
    let mut chart = ChartBuilder::on(area)
        .caption(title, ("sans-serif", 18))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(65)
        .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())
        .map_err(e)?;
    chart
        .configure_mesh()
        .x_desc(xdesc)
        .y_desc(ydesc)
        .x_label_formatter(&|x| crate::plot::tick(*x))
        .y_label_formatter(&|y| crate::plot::tick(*y))
        .draw()
        .map_err(e)?;
    for (i, s) in series.iter().enumerate() {
        let c = colour(i);
        if s.line {
            chart
                .draw_series(LineSeries::new(s.points.clone(), c.stroke_width(2)))
                .map_err(e)?;
        }
        chart
            .draw_series(s.points.iter().map(move |&p| Circle::new(p, 4, c.filled())))
            .map_err(e)?
            .label(s.label.clone())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2)));
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .label_font(("sans-serif", 13))
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(e)?;
    Ok(())
}

/// `{case}_work_precision.svg`: p0 error against solve time, one curve per
/// method through its refinement levels.
pub fn work_precision_plot(c: &MethodComparison, dir: &Path) -> Result<Option<PlotFile>, String> {
    let series: Vec<Series> = c
        .labels()
        .into_iter()
        .map(|label| {
            let points = positive(
                c.runs_of(&label)
                    .filter(|r| r.result.failure.is_none())
                    .filter_map(|r| {
                        Some((
                            r.result.solve_time,
                            r.result.error_of(Quantity::PeakPressure)?,
                        ))
                    }),
            );
            Series {
                label,
                points,
                line: true,
            }
        })
        .filter(|s| !s.points.is_empty())
        .collect();
    if series.is_empty() {
        return Ok(None);
    }
    let file = format!("{}_work_precision.svg", c.case);
    let path = dir.join(&file);
    let root = SVGBackend::new(&path, (900, 620)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| format!("{e:?}"))?;
    loglog(
        &root,
        &format!(
            "{}: p0 error vs solve time (one curve per method, levels 0..)",
            c.case
        ),
        "solve wall time [s]",
        "relative error of p0",
        &series,
    )?;
    root.present()
        .map_err(|e| format!("cannot write {}: {e:?}", path.display()))?;
    Ok(Some(PlotFile {
        case: c.case.clone(),
        kind: "work-precision".into(),
        file,
    }))
}

/// `hertz_quadratic_{deck}_work_precision.svg` (issue 23): the Hertz
/// `deck` ("cylinder" or "sphere": quad8 against quad4 through the levels
/// of `hertz_quadratic`; "sphere_3d": hex20 and hex27 against hex8
/// through those of `hertz_sphere_3d_quadratic`); two panels, the p0 and
/// L2(p) errors against the free dofs and against the solve wall time, one
/// line per error and cell kind.
pub fn quadratic_work_precision_plot(
    deck: &str,
    rows: &[crate::studies::QuadraticRow],
    dir: &Path,
) -> Result<Option<PlotFile>, String> {
    let mut kinds: Vec<&str> = Vec::new();
    for r in rows.iter().filter(|r| r.deck == deck) {
        if !kinds.contains(&r.cells.as_str()) {
            kinds.push(&r.cells);
        }
    }
    let series = |x: &dyn Fn(&crate::studies::QuadraticRow) -> f64| -> Vec<Series> {
        let mut out = Vec::new();
        for (what, y) in [
            (
                "p0",
                (|r: &crate::studies::QuadraticRow| r.p0) as fn(&_) -> f64,
            ),
            ("L2(p)", |r| r.l2),
        ] {
            for cells in &kinds {
                let points = positive(
                    rows.iter()
                        .filter(|r| r.deck == deck && r.cells == *cells)
                        .map(|r| (x(r), y(r))),
                );
                if !points.is_empty() {
                    out.push(Series {
                        label: format!("{what} {cells}"),
                        points,
                        line: true,
                    });
                }
            }
        }
        out
    };
    let (by_dofs, by_time) = (series(&|r| r.dofs as f64), series(&|r| r.seconds));
    if by_dofs.is_empty() {
        return Ok(None);
    }
    let file = format!("hertz_quadratic_{deck}_work_precision.svg");
    let path = dir.join(&file);
    let root = SVGBackend::new(&path, (1400, 560)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| format!("{e:?}"))?;
    let panels = root.split_evenly((1, 2));
    loglog(
        &panels[0],
        &format!("Hertz {deck}: error vs free dofs"),
        "free dofs",
        "relative error",
        &by_dofs,
    )?;
    loglog(
        &panels[1],
        &format!("Hertz {deck}: error vs solve time"),
        "solve wall time [s]",
        "relative error",
        &by_time,
    )?;
    root.present()
        .map_err(|e| format!("cannot write {}: {e:?}", path.display()))?;
    Ok(Some(PlotFile {
        case: if deck == "sphere_3d" {
            "hertz_sphere_3d_quadratic"
        } else {
            "hertz_quadratic"
        }
        .into(),
        kind: "work-precision".into(),
        file,
    }))
}

/// `penalty_sweep_{case}.svg`: three panels against k: p0 error (with the
/// Lagrange value), max penetration (with p0 / k), Newton iterations.
pub fn sweep_plot(s: &PenaltySweep, dir: &Path) -> Result<Option<PlotFile>, String> {
    let ok: Vec<_> = s
        .points
        .iter()
        .filter(|p| p.result.failure.is_none())
        .collect();
    if ok.is_empty() {
        return Ok(None);
    }
    let file = format!("penalty_sweep_{}.svg", s.case);
    let path = dir.join(&file);
    let root = SVGBackend::new(&path, (1500, 500)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| format!("{e:?}"))?;
    let panels = root.split_evenly((1, 3));
    let ks: Vec<f64> = ok.iter().map(|p| p.stiffness).collect();
    let (kmin, kmax) = (ks[0], ks[ks.len() - 1]);
    let mut err = vec![Series {
        label: "penalty".into(),
        points: positive(
            ok.iter()
                .filter_map(|p| Some((p.stiffness, p.result.error_of(Quantity::PeakPressure)?))),
        ),
        line: true,
    }];
    if let Some(e) = s
        .lagrange
        .as_ref()
        .and_then(|l| l.error_of(Quantity::PeakPressure))
    {
        err.push(Series {
            label: "Lagrange (same mesh)".into(),
            points: positive([(kmin, e), (kmax, e)]),
            line: true,
        });
    }
    loglog(
        &panels[0],
        "p0 error vs penalty",
        "area penalty k",
        "relative error of p0",
        &err,
    )?;
    let pen = vec![
        Series {
            label: "max penetration".into(),
            points: positive(ok.iter().map(|p| (p.stiffness, p.result.max_penetration))),
            line: true,
        },
        Series {
            label: "p0 / k".into(),
            points: positive(ok.iter().filter_map(|p| {
                let p0 = p
                    .result
                    .values
                    .iter()
                    .find(|v| v.quantity == Quantity::PeakPressure)?
                    .computed;
                Some((p.stiffness, p0 / p.stiffness))
            })),
            line: false,
        },
        Series {
            label: "indentation".into(),
            points: positive([(kmin, s.indentation), (kmax, s.indentation)]),
            line: true,
        },
    ];
    loglog(
        &panels[1],
        "penetration vs penalty",
        "area penalty k",
        "length",
        &pen,
    )?;
    let newton = vec![Series {
        label: "Newton iterations (all increments)".into(),
        points: positive(
            ok.iter()
                .map(|p| (p.stiffness, p.result.newton_total as f64)),
        ),
        line: true,
    }];
    loglog(
        &panels[2],
        "Newton iterations vs penalty",
        "area penalty k",
        "iterations",
        &newton,
    )?;
    root.present()
        .map_err(|e| format!("cannot write {}: {e:?}", path.display()))?;
    Ok(Some(PlotFile {
        case: s.case.clone(),
        kind: "penalty sweep".into(),
        file,
    }))
}

/// `penalty_scaling.svg`: middle gap and pressure error against h for the
/// three penalty flavours.
pub fn scaling_plot(s: &PenaltyScaling, dir: &Path) -> Result<Option<PlotFile>, String> {
    if s.points.is_empty() {
        return Ok(None);
    }
    let file = "penalty_scaling.svg".to_string();
    let path = dir.join(&file);
    let root = SVGBackend::new(&path, (1200, 520)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| format!("{e:?}"))?;
    let panels = root.split_evenly((1, 2));
    let of = |f: ScalingFlavour, y: &dyn Fn(&crate::penalty::ScalingPoint) -> f64| Series {
        label: f.label().into(),
        points: positive(
            s.points
                .iter()
                .filter(|p| p.flavour == f)
                .map(|p| (p.h, y(p))),
        ),
        line: true,
    };
    let gaps: Vec<Series> = ScalingFlavour::ALL
        .iter()
        .map(|&f| of(f, &|p| -p.gap_middle))
        .collect();
    loglog(
        &panels[0],
        "penetration at the middle node vs h",
        "h",
        "-gap",
        &gaps,
    )?;
    let errs: Vec<Series> = ScalingFlavour::ALL
        .iter()
        .map(|&f| of(f, &|p| p.pressure_error))
        .collect();
    loglog(
        &panels[1],
        "pressure error vs rigid contact (E d / H)",
        "h",
        "relative error",
        &errs,
    )?;
    root.present()
        .map_err(|e| format!("cannot write {}: {e:?}", path.display()))?;
    Ok(Some(PlotFile {
        case: "penalty_scaling".into(),
        kind: "penalty scaling".into(),
        file,
    }))
}
