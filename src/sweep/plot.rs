//! The plot of a sweep (`sweep.svg`): key figures against the first varied
//! value, one panel per figure (final contact or reaction force, largest
//! penetration, Newton iterations, wall time), one series per combination
//! of the other varied values. Log scale on x when the values are positive
//! and span a decade or more (a penalty sweep). Variants that did not
//! complete are left out (the table says why).

use super::gather::Row;
use plotters::prelude::*;
use std::path::Path;

const COLOURS: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
];

/// How a panel reads its figure from a row.
type Figure = Box<dyn Fn(&Row) -> Option<f64>>;

/// A figure plotted against the varied value.
struct Panel {
    title: String,
    value: Figure,
}

fn panels(rows: &[Row]) -> Vec<Panel> {
    let mut out = Vec::new();
    // the force columns that are not zero: the ones a reader looks at
    for col in super::gather::history_columns(rows) {
        if !(col.starts_with("contact_force") || col.starts_with("reaction")) {
            continue;
        }
        let c = col.clone();
        let get = move |r: &Row| r.history.iter().find(|(h, _)| *h == c).map(|(_, v)| *v);
        let big = rows.iter().filter_map(&get).any(|v| v.abs() > 1e-9);
        if big && out.len() < 2 {
            out.push(Panel {
                title: format!("final {col}"),
                value: Box::new(get),
            });
        }
    }
    out.push(Panel {
        title: "max penetration".into(),
        value: Box::new(|r: &Row| r.max_penetration),
    });
    out.push(Panel {
        title: "Newton iterations".into(),
        value: Box::new(|r: &Row| r.newton_iterations.map(|n| n as f64)),
    });
    out.push(Panel {
        title: "wall time [s]".into(),
        value: Box::new(|r: &Row| r.wall_time),
    });
    out
}

/// Writes `sweep.svg`; `Ok(false)` when there is nothing to plot (the first
/// varied value is not a number, or no variant completed).
pub fn plot(rows: &[Row], path: &Path) -> Result<bool, String> {
    let done: Vec<&Row> = rows.iter().filter(|r| r.status == "completed").collect();
    let Some(first) = rows.first().and_then(|r| r.overrides.first()) else {
        return Ok(false);
    };
    let x_of = |r: &Row| r.overrides.first().and_then(|(_, v)| v.parse::<f64>().ok());
    let xs: Vec<f64> = done.iter().filter_map(|r| x_of(r)).collect();
    if xs.is_empty() || xs.len() != done.len() {
        return Ok(false);
    }
    let (x0, x1) = xs
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    let log_x = x0 > 0.0 && x1 / x0 >= 10.0;
    // series: the other varied values
    let key = |r: &Row| {
        r.overrides[1..]
            .iter()
            .map(|(p, v)| format!("{p} = {v}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let mut keys: Vec<String> = Vec::new();
    for r in &done {
        let k = key(r);
        if !keys.contains(&k) {
            keys.push(k);
        }
    }
    let panels = panels(rows);
    let e = |err: DrawingAreaErrorKind<std::io::Error>| {
        format!("cannot draw {}: {err:?}", path.display())
    };
    let root = SVGBackend::new(path, (800, 260 * panels.len() as u32)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let areas = root.split_evenly((panels.len(), 1));
    for (panel, area) in panels.iter().zip(areas.iter()) {
        let mut series: Vec<(String, Vec<(f64, f64)>)> = Vec::new();
        for k in &keys {
            let mut pts: Vec<(f64, f64)> = done
                .iter()
                .filter(|r| key(r) == *k)
                .filter_map(|r| Some((x_of(r)?, (panel.value)(r)?)))
                .filter(|(_, y)| y.is_finite())
                .collect();
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            series.push((k.clone(), pts));
        }
        let ys = series.iter().flat_map(|(_, p)| p.iter().map(|q| q.1));
        let (y0, y1) = ys.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), y| {
            (a.min(y), b.max(y))
        });
        if !y0.is_finite() {
            continue;
        }
        let pad = ((y1 - y0).abs() * 0.1).max(y1.abs() * 0.05).max(1e-12);
        let (ya, yb) = (y0 - pad, y1 + pad);
        let caption = (panel.title.clone(), ("sans-serif", 18));
        let mut builder = ChartBuilder::on(area);
        builder
            .caption(caption.0, caption.1)
            .margin(12)
            .x_label_area_size(35)
            .y_label_area_size(80);
        let xdesc = first.0.clone();
        macro_rules! draw {
            ($chart:expr) => {{
                let mut chart = $chart.map_err(e)?;
                chart
                    .configure_mesh()
                    .x_desc(xdesc.as_str())
                    .x_label_formatter(&|x| format!("{x:.1e}"))
                    .y_label_formatter(&|y| format!("{y:.3e}"))
                    .draw()
                    .map_err(e)?;
                for (i, (k, pts)) in series.iter().enumerate() {
                    let c = COLOURS[i % COLOURS.len()];
                    chart
                        .draw_series(LineSeries::new(pts.clone(), c.stroke_width(2)))
                        .map_err(e)?;
                    let s = chart
                        .draw_series(pts.iter().map(move |p| Circle::new(*p, 4, c.filled())))
                        .map_err(e)?;
                    if !k.is_empty() {
                        s.label(k.clone()).legend(move |(x, y)| {
                            PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2))
                        });
                    }
                }
                if keys.len() > 1 {
                    chart
                        .configure_series_labels()
                        .background_style(WHITE.mix(0.8))
                        .border_style(BLACK)
                        .draw()
                        .map_err(e)?;
                }
            }};
        }
        if log_x {
            draw!(builder.build_cartesian_2d((x0 / 1.5..x1 * 1.5).log_scale(), ya..yb));
        } else {
            let px = ((x1 - x0) * 0.05).max(x1.abs() * 0.05).max(1e-12);
            draw!(builder.build_cartesian_2d(x0 - px..x1 + px, ya..yb));
        }
    }
    root.present().map_err(e)?;
    Ok(true)
}
