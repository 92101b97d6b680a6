//! SVG line charts for the subcommands' `--plot` option.

use std::path::Path;

use plotters::prelude::*;

use super::Error;

/// One named series of `(x, y)` points, drawn as a line or as markers, with a standard error
/// bar per point when `errors` is not empty (drawn as +- one standard error, clipped to the
/// positive part on a log axis).
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
    pub markers: bool,
    pub errors: Vec<f64>,
}

/// Draws `series` on one chart, logarithmic in x when `log_x`, into the SVG file `path`.
pub fn lines(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
    log_x: bool,
) -> Result<(), Error> {
    chart(path, title, (x_label, y_label), series, (log_x, false))
}

/// [`lines`] with both axes logarithmic.
pub fn log_log(path: &Path, title: &str, x_label: &str, y_label: &str, series: &[Series]) -> Result<(), Error> {
    chart(path, title, (x_label, y_label), series, (true, true))
}

fn chart(
    path: &Path,
    title: &str,
    (x_label, y_label): (&str, &str),
    series: &[Series],
    (log_x, log_y): (bool, bool),
) -> Result<(), Error> {
    let fail = |e: &dyn std::fmt::Display| format!("cannot draw {}: {e}", path.display());
    let xs = series.iter().flat_map(|s| s.points.iter().map(|p| p.0));
    let ys = series.iter().flat_map(|s| s.points.iter().map(|p| p.1));
    let (x0, x1) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| (a.min(x), b.max(x)));
    let (y0, y1) = ys.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), y| (a.min(y), b.max(y)));
    if !(x0.is_finite() && x1.is_finite()) {
        return Err(format!("cannot draw {}: no range to plot", path.display()));
    }
    // One x value: widen the axis around it.
    let (x0, x1) = match (x0 < x1, log_x) {
        (true, _) => (x0, x1),
        (false, true) => (x0 / 2.0, x1 * 2.0),
        (false, false) => (x0 - 1.0, x1 + 1.0),
    };
    let (y0, y1) = match (log_y, y0 < y1) {
        (true, true) => (y0 / 1.5, y1 * 1.5),
        (false, true) => (y0.min(0.0), y1 * 1.05),
        (_, false) => (0.0, 1.0),
    };
    let root = SVGBackend::new(path, (800, 500)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| fail(&e))?;
    let colors = [BLUE, RED, GREEN, MAGENTA, CYAN, BLACK];
    let mut builder = ChartBuilder::on(&root);
    builder.caption(title, ("sans-serif", 20)).margin(15).x_label_area_size(45).y_label_area_size(60);
    macro_rules! draw {
        ($chart:expr) => {{
            let mut chart = $chart.map_err(|e| fail(&e))?;
            chart
                .configure_mesh()
                .x_desc(x_label)
                .y_desc(y_label)
                .x_label_formatter(&|v| tick(*v))
                .y_label_formatter(&|v| tick(*v))
                .draw()
                .map_err(|e| fail(&e))?;
            for (i, s) in series.iter().enumerate() {
                let color = colors[i % colors.len()];
                if !s.errors.is_empty() {
                    let low = |y: f64, e: f64| if log_y { (y - e).max(y / 100.0) } else { y - e };
                    chart
                        .draw_series(s.points.iter().zip(&s.errors).map(|(&(x, y), &e)| {
                            ErrorBar::new_vertical(x, low(y, e), y, y + e, color.stroke_width(1), 8)
                        }))
                        .map_err(|e| fail(&e))?;
                }
                if s.markers {
                    chart
                        .draw_series(s.points.iter().map(|&p| Circle::new(p, 4, color.filled())))
                        .map_err(|e| fail(&e))?
                        .label(s.name.as_str())
                        .legend(move |(x, y)| Circle::new((x + 10, y), 4, color.filled()));
                } else {
                    chart
                        .draw_series(LineSeries::new(s.points.iter().copied(), color.stroke_width(2)))
                        .map_err(|e| fail(&e))?
                        .label(s.name.as_str())
                        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2)));
                }
            }
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.8))
                .border_style(BLACK)
                .draw()
                .map_err(|e| fail(&e))?;
        }};
    }
    match (log_x, log_y) {
        (true, true) => draw!(builder.build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())),
        (true, false) => draw!(builder.build_cartesian_2d((x0..x1).log_scale(), y0..y1)),
        (false, true) => draw!(builder.build_cartesian_2d(x0..x1, (y0..y1).log_scale())),
        (false, false) => draw!(builder.build_cartesian_2d(x0..x1, y0..y1)),
    }
    root.present().map_err(|e| fail(&e))?;
    Ok(())
}

/// A tick label: plain for moderate values, otherwise in e-notation with the rounding noise of
/// log-scale tick positions (`9.999999e-5`) removed.
fn tick(v: f64) -> String {
    let a = v.abs();
    if a == 0.0 || (1e-2..1e4).contains(&a) {
        let s = format!("{v:.3}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        let s = format!("{v:.2e}");
        let (mantissa, exponent) = s.split_once('e').expect("e-notation");
        format!("{}e{exponent}", mantissa.trim_end_matches('0').trim_end_matches('.'))
    }
}
