//! SVG charts for the figures of the command and of the studies' reports (`--plot`): one subject,
//! drawing charts (line and log-log charts, small multiples, maps, bars), hence one file.
//!
//! Every series has its own colour (ten distinct ones before they repeat) unless the caller
//! pairs series on purpose (a measurement and its model in one colour). The legend sits in a
//! band below the plotting area, so it never covers data. A point a logarithmic axis cannot
//! show (a value `<= 0`) is left off and counted in its series' legend entry, never dropped
//! in silence.

use std::path::Path;

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// One line of what went wrong.
type Error = String;

/// Fails with one line where the figure `path` cannot be written, so that a long run is not
/// lost to it at the end. A file that was not there is not left behind.
pub fn check_writable(path: &Path) -> Result<(), Error> {
    let existed = path.exists();
    // Appending to an existing file changes nothing in it.
    std::fs::OpenOptions::new()
        .append(true)
        .create(true)
        .open(path)
        .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    if !existed {
        std::fs::remove_file(path).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    }
    Ok(())
}

/// Creates the directory `dir` for figures and checks that a file can be written in it, before
/// a long run (see [`check_writable`]).
pub fn check_directory(dir: &Path) -> Result<(), Error> {
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    check_writable(&dir.join(format!(".depo-check-{}", std::process::id())))
}

/// How a series is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Style {
    /// A solid line through the points.
    Line,
    /// A dashed line through the points (a curve that would otherwise hide under another).
    Dashed,
    /// A filled circle per point.
    Markers,
    /// A downward triangle per point: the value is at most this (a 95 % upper bound).
    UpperBounds,
}

/// One named series of `(x, y)` points, with a standard error bar per point when `errors` is
/// not empty (drawn as +- one standard error, clipped to the positive part on a log axis).
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
    pub style: Style,
    pub errors: Vec<f64>,
    /// Index into the palette; by default the series' position on the chart.
    pub color: Option<usize>,
    /// A name written beside each point, when not empty (which kernel, which step).
    pub labels: Vec<String>,
}

impl Series {
    /// A solid line.
    pub fn line(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self { name: name.into(), points, style: Style::Line, errors: Vec::new(), color: None, labels: Vec::new() }
    }

    /// A marker per point.
    pub fn markers(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self { style: Style::Markers, ..Self::line(name, points) }
    }

    /// Upper bounds, one triangle per point.
    pub fn upper_bounds(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self { style: Style::UpperBounds, ..Self::line(name, points) }
    }

    /// With one standard error per point.
    pub fn with_errors(self, errors: Vec<f64>) -> Self {
        Self { errors, ..self }
    }

    /// With a name written beside each point.
    pub fn with_labels(self, labels: Vec<String>) -> Self {
        Self { labels, ..self }
    }

    /// Drawn dashed.
    pub fn dashed(self) -> Self {
        Self { style: Style::Dashed, ..self }
    }

    /// In the palette's colour `index`.
    pub fn color(self, index: usize) -> Self {
        Self { color: Some(index), ..self }
    }
}

/// Ten colours told apart on white (the "tab10" palette).
const PALETTE: [RGBColor; 10] = [
    RGBColor(0x1f, 0x77, 0xb4),
    RGBColor(0xd6, 0x27, 0x28),
    RGBColor(0x2c, 0xa0, 0x2c),
    RGBColor(0xff, 0x7f, 0x0e),
    RGBColor(0x94, 0x67, 0xbd),
    RGBColor(0x8c, 0x56, 0x4b),
    RGBColor(0xe3, 0x77, 0xc2),
    RGBColor(0x7f, 0x7f, 0x7f),
    RGBColor(0xbc, 0xbd, 0x22),
    RGBColor(0x17, 0xbe, 0xcf),
];

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

/// A series as drawn: the points the axes can show, and the legend entry that says what was
/// left off.
struct Drawn {
    label: String,
    points: Vec<(f64, f64)>,
    errors: Vec<f64>,
    style: Style,
    color: RGBColor,
    /// Points the axes cannot show.
    hidden: usize,
    /// The names of the points shown, or none.
    labels: Vec<String>,
}

fn plural(n: usize) -> &'static str {
    if n == 1 {
        ""
    } else {
        "s"
    }
}

/// Splits each series into what the axes show and a legend entry naming what they cannot.
fn prepare(series: &[Series], (log_x, log_y): (bool, bool)) -> Vec<Drawn> {
    series
        .iter()
        .enumerate()
        .map(|(i, s)| {
            let (mut points, mut errors, mut labels) = (Vec::new(), Vec::new(), Vec::new());
            let (mut non_positive, mut non_finite) = (0, 0);
            for (k, &(x, y)) in s.points.iter().enumerate() {
                if !(x.is_finite() && y.is_finite()) {
                    non_finite += 1;
                } else if (log_x && x <= 0.0) || (log_y && y <= 0.0) {
                    non_positive += 1;
                } else {
                    points.push((x, y));
                    if let Some(&e) = s.errors.get(k) {
                        errors.push(e);
                    }
                    if let Some(l) = s.labels.get(k) {
                        labels.push(l.clone());
                    }
                }
            }
            let mut notes = Vec::new();
            if non_positive > 0 {
                notes.push(format!("{non_positive} point{} <= 0 not shown", plural(non_positive)));
            }
            if non_finite > 0 {
                notes.push(format!("{non_finite} non-finite point{} not shown", plural(non_finite)));
            }
            let label = if notes.is_empty() { s.name.clone() } else { format!("{} ({})", s.name, notes.join(", ")) };
            let color = PALETTE[s.color.unwrap_or(i) % PALETTE.len()];
            Drawn { label, points, errors, style: s.style, color, hidden: non_positive + non_finite, labels }
        })
        .collect()
}

/// The lower end of an error bar: on a log axis clipped to a hundredth of the value.
fn low(y: f64, e: f64, log_y: bool) -> f64 {
    if log_y {
        (y - e).max(y / 100.0)
    } else {
        y - e
    }
}

/// Height of the plot itself, and of one legend row, in pixels.
const PLOT_HEIGHT: u32 = 500;
const LEGEND_ROW: u32 = 20;
const WIDTH: u32 = 800;

/// The axes' ranges, `((x0, x1), (y0, y1))`, that show every point of `drawn` and its error
/// bars; `None` when there is no point.
fn ranges(drawn: &[&Drawn], (log_x, log_y): (bool, bool)) -> Option<((f64, f64), (f64, f64))> {
    let xs = drawn.iter().flat_map(|s| s.points.iter().map(|p| p.0));
    let ys = drawn.iter().flat_map(|s| {
        let bars = s.points.iter().zip(&s.errors).flat_map(|(&(_, y), &e)| [low(y, e, log_y), y + e]);
        s.points.iter().map(|p| p.1).chain(bars)
    });
    let (x0, x1) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| (a.min(x), b.max(x)));
    let (y0, y1) = ys.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), y| (a.min(y), b.max(y)));
    if !(x0.is_finite() && x1.is_finite()) {
        return None;
    }
    // One x value: widen the axis around it. A log axis reaches a little beyond the points,
    // so that a decade on the edge (0.01 from 1e-8 m in um, 0.009999999) keeps its label.
    let x = match (x0 < x1, log_x) {
        (true, true) => (x0 / 1.1, x1 * 1.1),
        (true, false) => (x0, x1),
        (false, true) => (x0 / 2.0, x1 * 2.0),
        (false, false) => (x0 - 1.0, x1 + 1.0),
    };
    let y = match (log_y, y0 < y1) {
        (true, true) => (y0 / 1.5, y1 * 1.5),
        (true, false) => (y0 / 2.0, y1 * 2.0),
        (false, true) => (y0.min(0.0), y1 * 1.05),
        (false, false) => (0.0, 1.0),
    };
    Some((x, y))
}

/// Draws the series `drawn` on the chart context `$chart` (its error bars, then its points or
/// line), then the points' labels onto `$root` where [`place_labels`] puts them; `$fail` turns
/// a drawing error into the command's.
macro_rules! draw_series {
    ($chart:expr, $root:expr, $drawn:expr, $log_y:expr, $fail:expr) => {{
        let mut marks = Vec::new();
        for s in $drawn {
            let color = s.color;
            if !s.errors.is_empty() {
                $chart
                    .draw_series(s.points.iter().zip(&s.errors).map(|(&(x, y), &e)| {
                        ErrorBar::new_vertical(x, low(y, e, $log_y), y, y + e, color.stroke_width(1), 8)
                    }))
                    .map_err(|e| $fail(&e))?;
            }
            match s.style {
                Style::Markers => {
                    $chart
                        .draw_series(s.points.iter().map(|&p| Circle::new(p, 4, color.filled())))
                        .map_err(|e| $fail(&e))?;
                }
                Style::UpperBounds => {
                    $chart
                        .draw_series(s.points.iter().map(|&p| {
                            EmptyElement::at(p) + Polygon::new(vec![(-5, -4), (5, -4), (0, 5)], color.filled())
                        }))
                        .map_err(|e| $fail(&e))?;
                }
                Style::Line => {
                    $chart
                        .draw_series(LineSeries::new(s.points.iter().copied(), color.stroke_width(2)))
                        .map_err(|e| $fail(&e))?;
                }
                Style::Dashed => {
                    $chart
                        .draw_series(DashedLineSeries::new(s.points.iter().copied(), 8, 5, color.stroke_width(2)))
                        .map_err(|e| $fail(&e))?;
                }
            }
            let marker = matches!(s.style, Style::Markers | Style::UpperBounds);
            for (k, p) in s.points.iter().enumerate() {
                let label = s.labels.get(k).map(|l| (l.clone(), color));
                if marker || label.is_some() {
                    marks.push(Mark { at: $chart.backend_coord(p), marker, label });
                }
            }
        }
        let (xs, ys) = $chart.plotting_area().get_pixel_range();
        for placed in place_labels(&marks, (xs.start, xs.end), (ys.start, ys.end)) {
            let font = TextStyle::from((LABEL_FONT, 11).into_font()).color(&placed.color);
            let (pos, x) = if placed.left { (HPos::Right, placed.area.2) } else { (HPos::Left, placed.area.0) };
            let y = (placed.area.1 + placed.area.3) / 2;
            if placed.leader {
                // A thin line from the point to its label, moved off it to stay clear of others.
                let from = (placed.point.0 + if placed.left { -5 } else { 5 }, placed.point.1);
                $root
                    .draw(&PathElement::new(vec![from, (x, y)], placed.color.stroke_width(1)))
                    .map_err(|e| $fail(&e))?;
            }
            let text = Text::new(placed.text, (x, y), font.pos(Pos::new(pos, VPos::Center)));
            $root.draw(&text).map_err(|e| $fail(&e))?;
        }
    }};
}

/// The font of the points' labels.
const LABEL_FONT: &str = "sans-serif";

/// A point as drawn, in pixels: whether a marker sits on it, and its label with its colour.
struct Mark {
    at: (i32, i32),
    marker: bool,
    label: Option<(String, RGBColor)>,
}

/// A label where [`place_labels`] puts it.
struct Placed {
    text: String,
    color: RGBColor,
    point: (i32, i32),
    /// Its box in pixels: left, top, right, bottom.
    area: (i32, i32, i32, i32),
    /// Whether it sits to the left of its point.
    left: bool,
    /// Whether it is moved up or down from its point, a line leading to it.
    leader: bool,
}

/// A label's box, in pixels: about 5.2 pixels a character of the 11-point labels as an SVG
/// viewer draws them (plotters writes them at 8.9 px), and a line of 11 pixels.
const LABEL_CHAR: f64 = 5.2;
const LABEL_HEIGHT: i32 = 11;

/// A label's width in pixels.
fn label_width(text: &str) -> i32 {
    (text.chars().count() as f64 * LABEL_CHAR).ceil() as i32
}

/// How many square pixels two boxes (left, top, right, bottom) share.
fn overlap(a: (i32, i32, i32, i32), b: (i32, i32, i32, i32)) -> i32 {
    let w = a.2.min(b.2) - a.0.max(b.0);
    let h = a.3.min(b.3) - a.1.max(b.1);
    if w > 0 && h > 0 {
        w * h
    } else {
        0
    }
}

/// Where each label of `marks` goes, inside the plotting area `xs` x `ys` (pixels): beside its
/// point, to the right (to the left in the right third), or where that would cover another
/// label or a marker, on the other side, then moved up or down a few pixels at a time, then
/// further out, until it covers nothing (a line leads to a label moved off its point). Labels
/// are placed from the top down; one that finds no free place takes the place where it covers
/// least. So that points on top of one another (kernels with the same error and speed, a column
/// of zero-error kernels drawn at the axis' floor) keep every label readable.
fn place_labels(marks: &[Mark], xs: (i32, i32), ys: (i32, i32)) -> Vec<Placed> {
    const GAP: i32 = 7;
    const MARKER: i32 = 5;
    // Moves up or down by 3 pixels, up to 240.
    const SHIFT: i32 = 3;
    const SHIFTS: i32 = 80;
    let mut taken: Vec<(i32, i32, i32, i32)> = marks
        .iter()
        .filter(|m| m.marker)
        .map(|m| (m.at.0 - MARKER, m.at.1 - MARKER, m.at.0 + MARKER, m.at.1 + MARKER))
        .collect();
    let mut order: Vec<&Mark> = marks.iter().filter(|m| m.label.is_some()).collect();
    order.sort_by_key(|m| (m.at.1, m.at.0));
    let mut placed = Vec::new();
    for m in order {
        let (text, color) = m.label.clone().expect("labelled");
        let width = label_width(&text);
        let prefer_left = m.at.0 - xs.0 > 7 * (xs.1 - xs.0) / 10;
        let at = |left: bool, dx: i32, dy: i32| {
            let top = m.at.1 + dy - LABEL_HEIGHT / 2;
            let x = if left { m.at.0 - GAP - dx - width } else { m.at.0 + GAP + dx };
            (x, top, x + width, top + LABEL_HEIGHT)
        };
        let inside = |b: (i32, i32, i32, i32)| b.0 >= xs.0 && b.2 <= xs.1 && b.1 >= ys.0 && b.3 <= ys.1;
        // The nearest free place: beside the point, then a few pixels at a time up or down (so
        // that a label fits between two others wherever they are), then further out.
        let mut best: Option<(i32, bool, i32, i32)> = None;
        'search: for dx in [0, 3 * GAP, 6 * GAP] {
            for step in 0..=SHIFTS {
                let shifts = if step == 0 { vec![0] } else { vec![-step * SHIFT, step * SHIFT] };
                for dy in shifts {
                    for left in [prefer_left, !prefer_left] {
                        let b = at(left, dx, dy);
                        if !inside(b) {
                            continue;
                        }
                        let covered: i32 = taken.iter().map(|&t| overlap(b, t)).sum();
                        if best.is_none_or(|(c, ..)| covered < c) {
                            best = Some((covered, left, dx, dy));
                        }
                        if covered == 0 {
                            break 'search;
                        }
                    }
                }
            }
        }
        let (_, left, dx, dy) = best.unwrap_or((0, prefer_left, 0, 0));
        let area = at(left, dx, dy);
        taken.push(area);
        let leader = dx > 0 || dy.abs() > LABEL_HEIGHT / 2;
        placed.push(Placed { text, color, point: m.at, area, left, leader });
    }
    placed
}

/// The legend band's columns and rows for `entries`: two columns when the labels fit.
fn legend_layout(entries: &[&Drawn]) -> (usize, u32) {
    let longest = entries.iter().map(|d| d.label.chars().count()).max().unwrap_or(0);
    let columns = if longest <= 48 { 2 } else { 1 };
    (columns, entries.len().div_ceil(columns) as u32)
}

/// Draws the legend `entries` into the band `lower`, filled column by column.
fn draw_legend<DB: DrawingBackend>(
    lower: &DrawingArea<DB, plotters::coord::Shift>,
    entries: &[&Drawn],
    width: u32,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let (columns, rows) = legend_layout(entries);
    let column_width = (width as i32 - 75) / columns as i32;
    let font = TextStyle::from(("sans-serif", 14).into_font()).pos(Pos::new(HPos::Left, VPos::Center));
    for (k, entry) in entries.iter().enumerate() {
        let (row, column) = (k as u32 % rows.max(1), k as u32 / rows.max(1));
        let x = 75 + column as i32 * column_width;
        let y = (row * LEGEND_ROW + LEGEND_ROW / 2 + 5) as i32;
        legend_symbol(lower, entry, (x, y))?;
        lower.draw(&Text::new(entry.label.as_str(), (x + 40, y), font.clone()))?;
    }
    Ok(())
}

fn chart(
    path: &Path,
    title: &str,
    (x_label, y_label): (&str, &str),
    series: &[Series],
    (log_x, log_y): (bool, bool),
) -> Result<(), Error> {
    let fail = |e: &dyn std::fmt::Display| format!("cannot draw {}: {e}", path.display());
    let mut drawn = prepare(series, (log_x, log_y));
    // The legend: every series, also one with no point to show (its entry says why).
    let entries: Vec<&Drawn> = drawn.iter().collect();
    let Some(((x0, x1), (y0, y1))) = ranges(&entries, (log_x, log_y)) else {
        return Err(format!("cannot draw {}: no range to plot", path.display()));
    };
    let sx = log_scaling(x0, log_x);
    let (x0, x1) = (x0 * sx, x1 * sx);
    for s in &mut drawn {
        s.points.iter_mut().for_each(|p| p.0 *= sx);
    }
    let entries: Vec<&Drawn> = drawn.iter().collect();
    let rows = legend_layout(&entries).1;
    let legend_height = if rows == 0 { 0 } else { rows * LEGEND_ROW + 15 };
    let root = SVGBackend::new(path, (WIDTH, PLOT_HEIGHT + legend_height)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| fail(&e))?;
    let (upper, lower) = root.split_vertically(PLOT_HEIGHT);
    let mut builder = ChartBuilder::on(&upper);
    builder.caption(title, ("sans-serif", 20)).margin(15).x_label_area_size(45).y_label_area_size(60);
    macro_rules! draw {
        ($chart:expr) => {{
            let mut chart = $chart.map_err(|e| fail(&e))?;
            chart
                .configure_mesh()
                .x_desc(x_label)
                .y_desc(y_label)
                .x_label_formatter(&|v| tick(*v / sx))
                .y_label_formatter(&|v| tick(*v))
                .draw()
                .map_err(|e| fail(&e))?;
            draw_series!(chart, root, &drawn, log_y, fail);
        }};
    }
    let (labelled, light) = log_ticks(x0, x1);
    let log_x_axis = || (x0..x1).log_scale().with_key_points(labelled.clone()).with_light_points(light.clone());
    match (log_x, log_y) {
        (true, true) => draw!(builder.build_cartesian_2d(log_x_axis(), (y0..y1).log_scale())),
        (true, false) => draw!(builder.build_cartesian_2d(log_x_axis(), y0..y1)),
        (false, true) => draw!(builder.build_cartesian_2d(x0..x1, (y0..y1).log_scale())),
        (false, false) => draw!(builder.build_cartesian_2d(x0..x1, y0..y1)),
    }
    draw_legend(&lower, &entries, WIDTH).map_err(|e| fail(&e))?;
    root.present().map_err(|e| fail(&e))?;
    Ok(())
}

/// One panel of [`small_multiples`]: its caption, its series, and lines of text written in
/// its lower left corner.
pub struct Panel {
    pub name: String,
    pub series: Vec<Series>,
    pub notes: Vec<String>,
}

/// Draws each of `panels` as a small chart of its own, three or four to a row, all on the same
/// axes (so that the panels compare at a glance), into the SVG file `path`. One legend below
/// them, `key`, says what the series' styles and colours stand for (its series need no
/// points); a panel whose points the axes cannot all show says how many under its notes.
pub fn small_multiples(
    path: &Path,
    title: &str,
    (x_label, y_label): (&str, &str),
    panels: &[Panel],
    key: &[Series],
    (log_x, log_y): (bool, bool),
) -> Result<(), Error> {
    const PANEL: (u32, u32) = (270, 230);
    let fail = |e: &dyn std::fmt::Display| format!("cannot draw {}: {e}", path.display());
    let drawn: Vec<Vec<Drawn>> = panels.iter().map(|p| prepare(&p.series, (log_x, log_y))).collect();
    let all: Vec<&Drawn> = drawn.iter().flatten().collect();
    let Some(((x0, x1), (y0, y1))) = ranges(&all, (log_x, log_y)) else {
        return Err(format!("cannot draw {}: no range to plot", path.display()));
    };
    let columns = if panels.len() <= 9 { panels.len().clamp(1, 3) } else { 4 };
    let rows = panels.len().div_ceil(columns).max(1);
    let width = (columns as u32 * PANEL.0).max(WIDTH);
    let key = prepare(key, (false, false));
    let entries: Vec<&Drawn> = key.iter().collect();
    let legend_rows = legend_layout(&entries).1;
    let legend_height = if legend_rows == 0 { 0 } else { legend_rows * LEGEND_ROW + 15 };
    let root = SVGBackend::new(path, (width, 40 + rows as u32 * PANEL.1 + legend_height)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| fail(&e))?;
    let (head, rest) = root.split_vertically(40);
    let centred = TextStyle::from(("sans-serif", 20).into_font()).pos(Pos::new(HPos::Center, VPos::Center));
    head.draw(&Text::new(title, ((width / 2) as i32, 20), centred)).map_err(|e| fail(&e))?;
    let (grid, lower) = rest.split_vertically(rows as u32 * PANEL.1);
    let grid = grid.margin(0, 0, 0, (width - columns as u32 * PANEL.0) as i32);
    let areas = grid.split_evenly((rows, columns));
    for ((panel, drawn), area) in panels.iter().zip(&drawn).zip(&areas) {
        let hidden: usize = drawn.iter().map(|d| d.hidden).sum();
        let mut notes = panel.notes.clone();
        if hidden > 0 {
            notes.push(format!("{hidden} point{} <= 0 not shown", plural(hidden)));
        }
        let mut builder = ChartBuilder::on(area);
        builder.caption(panel.name.as_str(), ("sans-serif", 14)).margin(8).x_label_area_size(35).y_label_area_size(50);
        macro_rules! draw {
            ($chart:expr) => {{
                let mut chart = $chart.map_err(|e| fail(&e))?;
                chart
                    .configure_mesh()
                    .x_desc(x_label)
                    .y_desc(y_label)
                    .x_labels(5)
                    .y_labels(8)
                    .axis_desc_style(("sans-serif", 12))
                    .label_style(("sans-serif", 11))
                    .x_label_formatter(&|v| tick(*v))
                    .y_label_formatter(&|v| tick(*v))
                    .draw()
                    .map_err(|e| fail(&e))?;
                draw_series!(chart, root, drawn, log_y, fail);
                chart.backend_coord(&(x0, y0))
            }};
        }
        let (left, bottom) = match (log_x, log_y) {
            (true, true) => draw!(builder.build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())),
            (true, false) => draw!(builder.build_cartesian_2d((x0..x1).log_scale(), y0..y1)),
            (false, true) => draw!(builder.build_cartesian_2d(x0..x1, (y0..y1).log_scale())),
            (false, false) => draw!(builder.build_cartesian_2d(x0..x1, y0..y1)),
        };
        let font = TextStyle::from(("sans-serif", 12).into_font()).pos(Pos::new(HPos::Left, VPos::Bottom));
        for (k, note) in notes.iter().rev().enumerate() {
            let at = (left + 6, bottom - 5 - 14 * k as i32);
            root.draw(&Text::new(note.as_str(), at, font.clone())).map_err(|e| fail(&e))?;
        }
    }
    draw_legend(&lower, &entries, width).map_err(|e| fail(&e))?;
    root.present().map_err(|e| fail(&e))?;
    Ok(())
}

/// One series of [`bars`]: a bar per group, each with its standard error.
pub struct Bars {
    pub name: String,
    pub values: Vec<f64>,
    pub errors: Vec<f64>,
}

/// Draws a grouped bar chart into the SVG file `path`: for each of `groups` (named under the
/// axis) one bar per series side by side, in the series' colours, each with a standard
/// error bar; the legend below names the series.
pub fn bars(path: &Path, title: &str, y_label: &str, groups: &[&str], series: &[Bars]) -> Result<(), Error> {
    let fail = |e: &dyn std::fmt::Display| format!("cannot draw {}: {e}", path.display());
    let top = series
        .iter()
        .flat_map(|s| s.values.iter().zip(&s.errors).map(|(v, e)| v + e))
        .fold(0.0f64, f64::max)
        .max(f64::MIN_POSITIVE);
    let rows = series.len().div_ceil(2) as u32;
    let legend_height = rows * LEGEND_ROW + 15;
    let root = SVGBackend::new(path, (WIDTH, PLOT_HEIGHT + legend_height)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| fail(&e))?;
    let (upper, lower) = root.split_vertically(PLOT_HEIGHT);
    let mut chart = ChartBuilder::on(&upper)
        .caption(title, ("sans-serif", 20))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(60)
        .build_cartesian_2d(0.0..groups.len() as f64, 0.0..top * 1.1)
        .map_err(|e| fail(&e))?;
    chart
        .configure_mesh()
        .disable_x_mesh()
        .x_labels(0)
        .y_desc(y_label)
        .y_label_formatter(&|v| tick(*v))
        .draw()
        .map_err(|e| fail(&e))?;
    let width = 0.8 / series.len().max(1) as f64;
    for (k, s) in series.iter().enumerate() {
        let color = PALETTE[k % PALETTE.len()];
        let left = |g: usize| g as f64 + 0.1 + k as f64 * width;
        chart
            .draw_series(
                s.values
                    .iter()
                    .enumerate()
                    .map(|(g, &v)| Rectangle::new([(left(g), 0.0), (left(g) + width * 0.9, v)], color.filled())),
            )
            .map_err(|e| fail(&e))?;
        chart
            .draw_series(s.values.iter().zip(&s.errors).enumerate().map(|(g, (&v, &e))| {
                let x = left(g) + width * 0.45;
                ErrorBar::new_vertical(x, (v - e).max(0.0), v, v + e, BLACK.stroke_width(1), 6)
            }))
            .map_err(|e| fail(&e))?;
    }
    let centred = TextStyle::from(("sans-serif", 15).into_font()).pos(Pos::new(HPos::Center, VPos::Top));
    for (g, name) in groups.iter().enumerate() {
        let (x, y) = chart.backend_coord(&(g as f64 + 0.5, 0.0));
        upper.draw(&Text::new(*name, (x, y + 8), centred.clone())).map_err(|e| fail(&e))?;
    }
    let font = TextStyle::from(("sans-serif", 14).into_font()).pos(Pos::new(HPos::Left, VPos::Center));
    let column_width = (WIDTH as i32 - 75) / 2;
    for (k, s) in series.iter().enumerate() {
        let (row, column) = (k as u32 % rows.max(1), k as u32 / rows.max(1));
        let x = 75 + column as i32 * column_width;
        let y = (row * LEGEND_ROW + LEGEND_ROW / 2 + 5) as i32;
        let color = PALETTE[k % PALETTE.len()];
        lower.draw(&Rectangle::new([(x + 5, y - 6), (x + 25, y + 6)], color.filled())).map_err(|e| fail(&e))?;
        lower.draw(&Text::new(s.name.as_str(), (x + 40, y), font.clone())).map_err(|e| fail(&e))?;
    }
    root.present().map_err(|e| fail(&e))?;
    Ok(())
}

/// One cell of a [`MapPanel`]: its value (0 for none) and whether it is resolved.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MapCell {
    pub value: f64,
    pub resolved: bool,
}

/// One panel of [`maps`]: a named grid of cells, row `i` the `i`-th band from the bottom along
/// the vertical axis `axes[0]`, column `j` the `j`-th along the horizontal axis `axes[1]`,
/// each axis `(name, low, high)` in m, or no grid and a note why; the caption's detail (its
/// cells' size); and outlines drawn over it, each a name and its corners
/// `[(horizontal, vertical); 2]` in m (an opening in the surface, a box on it).
pub struct MapPanel {
    pub name: String,
    pub detail: String,
    pub cells: Result<Vec<Vec<MapCell>>, String>,
    pub axes: [(&'static str, f64, f64); 2],
    pub outlines: Vec<(String, [(f64, f64); 2])>,
}

/// The colour of the share `t` (0 to 1) of a map's logarithmic scale: viridis, dark blue to
/// yellow (its anchors every quarter, linear between), which reads in grey print too.
fn shade(t: f64) -> RGBColor {
    const ANCHORS: [(f64, f64, f64); 5] =
        [(68.0, 1.0, 84.0), (59.0, 82.0, 139.0), (33.0, 145.0, 140.0), (94.0, 201.0, 98.0), (253.0, 231.0, 37.0)];
    let x = t.clamp(0.0, 1.0) * 4.0;
    let k = (x.floor() as usize).min(3);
    let f = x - k as f64;
    let (a, b) = (ANCHORS[k], ANCHORS[k + 1]);
    let mix = |p: f64, q: f64| (p + f * (q - p)).round() as u8;
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// The shade of an unresolved cell in the legend (a cell's own is its colour, paler, hatched).
const UNRESOLVED: RGBColor = RGBColor(0xc8, 0xc8, 0xc8);

/// Diagonal hatching over the pixel box `[(x0, y0), (x1, y1)]` (top left, bottom right), a line
/// every `every` pixels: one path, down and up across the box.
fn hatching((x0, y0): (i32, i32), (x1, y1): (i32, i32), every: i32) -> PathElement<(i32, i32)> {
    let (w, h) = (x1 - x0, y1 - y0);
    let mut points = Vec::new();
    let mut k = every;
    // Lines x + y = const, from the bottom edge or left edge to the top edge or right edge.
    while k < w + h {
        let start = if k <= h { (x0, y0 + k) } else { (x0 + k - h, y1) };
        let end = if k <= w { (x0 + k, y0) } else { (x1, y0 + k - w) };
        if points.len() % 4 == 0 {
            points.extend([start, end]);
        } else {
            points.extend([end, start]);
        }
        k += every;
    }
    PathElement::new(points, RGBColor(0x70, 0x70, 0x70).stroke_width(1))
}

/// The decades a map's colour scale spans below its largest value.
const MAP_DECADES: f64 = 3.0;

/// Draws `panels` side by side, three to a row, each to scale (a metre as long across as up),
/// each resolved cell coloured by its value on one logarithmic scale for all (`unit` names
/// it), from the largest resolved value down to the smallest, at most three decades and at
/// least one; cells below the scale take its lowest colour, unresolved ones are paler and
/// hatched, empty ones white. A colour bar with its ticks labelled goes below, with the legend; each
/// panel's caption names the surface and its detail; its outlines are drawn in red.
pub fn maps(path: &Path, title: &str, unit: &str, panels: &[MapPanel]) -> Result<(), Error> {
    const PANEL: (u32, u32) = (300, 260);
    const CAPTION: u32 = 22;
    const MARGIN: u32 = 8;
    const LABELS: (u32, u32) = (40, 30);
    let fail = |e: &dyn std::fmt::Display| format!("cannot draw {}: {e}", path.display());
    let columns = panels.len().clamp(1, 3) as u32;
    let rows = panels.len().div_ceil(3).max(1) as u32;
    let resolved = || {
        panels
            .iter()
            .filter_map(|p| p.cells.as_ref().ok())
            .flat_map(|c| c.iter().flatten())
            .filter(|c| c.resolved && c.value > 0.0)
            .map(|c| c.value)
    };
    let most = resolved().fold(0.0f64, f64::max);
    let least = resolved().fold(f64::INFINITY, f64::min);
    // The scale's ends, in decades: the resolved values' range, at most MAP_DECADES, at least
    // one decade about its middle (so that cells' noise of tens of percent does not fill it).
    let (bottom, top) = if most > 0.0 {
        let (top, bottom) = (most.log10(), least.log10().max(most.log10() - MAP_DECADES));
        let middle = (top + bottom) / 2.0;
        (bottom.min(middle - 0.5), top.max(middle + 0.5))
    } else {
        (-1.0, 0.0)
    };
    let share = |v: f64| (v.log10() - bottom) / (top - bottom);
    let width = (columns * PANEL.0).max(900);
    let root = SVGBackend::new(path, (width, 40 + rows * PANEL.1 + 70)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| fail(&e))?;
    let (head, rest) = root.split_vertically(40);
    let centred = TextStyle::from(("sans-serif", 18).into_font()).pos(Pos::new(HPos::Center, VPos::Center));
    head.draw(&Text::new(title, ((width / 2) as i32, 20), centred)).map_err(|e| fail(&e))?;
    let (grid, foot) = rest.split_vertically(rows * PANEL.1);
    // The colour bar, its decades labelled, and the legend of the other shades.
    let (bar_x, bar_w): (i32, i32) = (40, 300);
    for k in 0..bar_w {
        let t = f64::from(k) / f64::from(bar_w - 1);
        let x = bar_x + k;
        foot.draw(&Rectangle::new([(x, 8), (x + 1, 22)], shade(t).filled())).map_err(|e| fail(&e))?;
    }
    foot.draw(&Rectangle::new([(bar_x, 8), (bar_x + bar_w, 22)], BLACK.stroke_width(1))).map_err(|e| fail(&e))?;
    let under = TextStyle::from(("sans-serif", 12).into_font()).pos(Pos::new(HPos::Center, VPos::Top));
    // Ticks at the scale's ends, and between them at 1, 2 and 5 times a power of ten (only
    // the powers over more than two decades) clear of the ends.
    let inner = |v: &f64| (bottom + 0.1..=top - 0.1).contains(&v.log10());
    let mut ticks: Vec<f64> = (bottom.floor() as i32..=top.ceil() as i32)
        .flat_map(|k| [1.0, 2.0, 5.0].map(|m| m * 10f64.powi(k)))
        .filter(|v| inner(v) && (top - bottom <= 2.0 || (v.log10() - v.log10().round()).abs() < 1e-9))
        .collect();
    ticks.extend([10f64.powf(bottom), 10f64.powf(top)]);
    for v in ticks {
        let x = bar_x + (f64::from(bar_w) * share(v)).round() as i32;
        foot.draw(&PathElement::new(vec![(x, 22), (x, 26)], BLACK.stroke_width(1))).map_err(|e| fail(&e))?;
        foot.draw(&Text::new(tick(v), (x, 28), under.clone())).map_err(|e| fail(&e))?;
    }
    let note = TextStyle::from(("sans-serif", 13).into_font()).pos(Pos::new(HPos::Left, VPos::Center));
    foot.draw(&Text::new(unit, (bar_x + bar_w + 20, 15), note.clone())).map_err(|e| fail(&e))?;
    let (swatch_y, mut x) = (52, bar_x);
    for (fill, text) in [
        (UNRESOLVED, "hatched, paler: unresolved (relative standard error above 30 %)"),
        (WHITE, "no deposit"),
        (PALETTE[1], "openings and furnishings"),
    ] {
        let outline = if fill == PALETTE[1] { fill } else { BLACK };
        foot.draw(&Rectangle::new([(x, swatch_y - 6), (x + 14, swatch_y + 6)], fill.filled())).map_err(|e| fail(&e))?;
        foot.draw(&Rectangle::new([(x, swatch_y - 6), (x + 14, swatch_y + 6)], outline.stroke_width(1)))
            .map_err(|e| fail(&e))?;
        foot.draw(&Text::new(text, (x + 20, swatch_y), note.clone())).map_err(|e| fail(&e))?;
        x += 20 + 7 * text.len() as i32 + 20;
    }
    let areas = grid.split_evenly((rows as usize, columns as usize));
    let caption = TextStyle::from(("sans-serif", 14).into_font()).pos(Pos::new(HPos::Center, VPos::Center));
    let label = TextStyle::from(("sans-serif", 11).into_font()).pos(Pos::new(HPos::Left, VPos::Top));
    for (panel, area) in panels.iter().zip(&areas) {
        let [(down, d0, d1), (across, a0, a1)] = panel.axes;
        let text = format!("{} ({})", panel.name, panel.detail);
        area.draw(&Text::new(text, ((PANEL.0 / 2) as i32, (CAPTION / 2) as i32), caption.clone()))
            .map_err(|e| fail(&e))?;
        let (_, body) = area.split_vertically(CAPTION);
        // To scale: the plot box shrunk along one axis, centred.
        let (w, h) = body.dim_in_pixel();
        let (room_w, room_h) = (w - 2 * MARGIN - LABELS.0, h - 2 * MARGIN - LABELS.1);
        let scale = (f64::from(room_w) / (a1 - a0)).min(f64::from(room_h) / (d1 - d0));
        let extra_w = ((f64::from(room_w) - scale * (a1 - a0)) / 2.0).max(0.0) as u32;
        let extra_h = ((f64::from(room_h) - scale * (d1 - d0)) / 2.0).max(0.0) as u32;
        let mut chart = ChartBuilder::on(&body)
            .margin_left(MARGIN + extra_w)
            .margin_right(MARGIN + extra_w)
            .margin_top(MARGIN + extra_h)
            .margin_bottom(MARGIN + extra_h)
            .x_label_area_size(LABELS.1)
            .y_label_area_size(LABELS.0)
            .build_cartesian_2d(a0..a1, d0..d1)
            .map_err(|e| fail(&e))?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(format!("{across} (m)"))
            .y_desc(format!("{down} (m)"))
            .x_labels(4)
            .y_labels(4)
            .x_label_formatter(&|v| tick(*v))
            .y_label_formatter(&|v| tick(*v))
            .draw()
            .map_err(|e| fail(&e))?;
        match &panel.cells {
            Ok(cells) => {
                let n = cells.len().max(1);
                let m = cells.first().map_or(1, Vec::len).max(1);
                let (dd, da) = ((d1 - d0) / n as f64, (a1 - a0) / m as f64);
                let filled = |resolved: bool| {
                    cells.iter().enumerate().flat_map(move |(i, row)| {
                        row.iter()
                            .enumerate()
                            .filter(move |(_, c)| c.value > 0.0 && c.resolved == resolved)
                            .map(move |(j, c)| ((d0 + i as f64 * dd, a0 + j as f64 * da), shade(share(c.value))))
                    })
                };
                let solid =
                    filled(true).map(|((y, x), fill)| Rectangle::new([(x, y), (x + da, y + dd)], fill.filled()));
                chart.draw_series(solid).map_err(|e| fail(&e))?;
                // An unresolved cell: its colour paler, hatched.
                for ((y, x), fill) in filled(false) {
                    chart
                        .draw_series([Rectangle::new([(x, y), (x + da, y + dd)], fill.mix(0.45).filled())])
                        .map_err(|e| fail(&e))?;
                    let (px0, py1) = chart.backend_coord(&(x, y));
                    let (px1, py0) = chart.backend_coord(&(x + da, y + dd));
                    let hatch = hatching((px0, py0), (px1, py1), 7);
                    root.draw(&hatch).map_err(|e| fail(&e))?;
                }
                // The surface's outline, so that a white (empty) map still shows its extent.
                chart
                    .draw_series([Rectangle::new([(a0, d0), (a1, d1)], BLACK.stroke_width(1))])
                    .map_err(|e| fail(&e))?;
            }
            Err(why) => {
                let (px, py) = chart.backend_coord(&(a0, d1));
                root.draw(&Text::new(why.as_str(), (px + 4, py + 4), label.clone())).map_err(|e| fail(&e))?;
            }
        }
        let red = PALETTE[1];
        for (name, [(x0, y0), (x1, y1)]) in &panel.outlines {
            chart.draw_series([Rectangle::new([(*x0, *y0), (*x1, *y1)], red.stroke_width(2))]).map_err(|e| fail(&e))?;
            let (px, py) = chart.backend_coord(&(x0.min(*x1), y0.max(*y1)));
            root.draw(&Text::new(name.as_str(), (px + 3, py + 3), label.clone().color(&red))).map_err(|e| fail(&e))?;
        }
    }
    root.present().map_err(|e| fail(&e))?;
    Ok(())
}

/// A series' symbol in the legend, 30 pixels wide from `(x, y)`.
fn legend_symbol<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    entry: &Drawn,
    (x, y): (i32, i32),
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let color = entry.color;
    if !entry.errors.is_empty() {
        area.draw(&PathElement::new(vec![(x + 15, y - 7), (x + 15, y + 7)], color.stroke_width(1)))?;
        for end in [y - 7, y + 7] {
            area.draw(&PathElement::new(vec![(x + 11, end), (x + 19, end)], color.stroke_width(1)))?;
        }
    }
    match entry.style {
        Style::Markers => area.draw(&Circle::new((x + 15, y), 4, color.filled())),
        Style::UpperBounds => {
            area.draw(&Polygon::new(vec![(x + 10, y - 4), (x + 20, y - 4), (x + 15, y + 5)], color.filled()))
        }
        Style::Line => area.draw(&PathElement::new(vec![(x, y), (x + 30, y)], color.stroke_width(2))),
        Style::Dashed => {
            for (a, b) in [(0, 8), (13, 21), (26, 30)] {
                area.draw(&PathElement::new(vec![(x + a, y), (x + b, y)], color.stroke_width(2)))?;
            }
            Ok(())
        }
    }
}

/// The factor a log x axis from `x0` is drawn scaled by, its labels divided by it again:
/// plotters takes a key point below f64::EPSILON (2.2e-16) for its log scale's zero and
/// leaves it out, so the decades 1e-16 and 1e-17, where the bench figures draw their
/// zero-error kernels, had no tick or label. Scaled, the axis starts above 1e-6.
fn log_scaling(x0: f64, log: bool) -> f64 {
    if log && x0 < 1e-6 {
        10f64.powi((-6.0 - x0.log10()).ceil() as i32)
    } else {
        1.0
    }
}

/// A log axis's ticks over `[lo, hi]`, `(labelled, light)`: labelled at every whole mantissa
/// 1-9 of each power of ten where the axis spans up to two and a half decades, at 1, 2 and 5
/// up to five decades, at the powers of ten beyond; a light line at the other whole
/// mantissas. So the axis's first tick, within its first decade, carries a label (the
/// default's ticks left a 0.3-0.9 stretch bare and crowded light lines between its own);
/// where fewer than two ticks would be labelled, its two ends are.
fn log_ticks(lo: f64, hi: f64) -> (Vec<f64>, Vec<f64>) {
    let decades = (hi / lo).log10();
    let labelled: &[u32] = if decades <= 2.5 {
        &[1, 2, 3, 4, 5, 6, 7, 8, 9]
    } else if decades <= 5.0 {
        &[1, 2, 5]
    } else {
        &[1]
    };
    let (mut bold, mut light) = (Vec::new(), Vec::new());
    for e in lo.log10().floor() as i32..=hi.log10().ceil() as i32 {
        for m in 1..=9u32 {
            let v = f64::from(m) * 10f64.powi(e);
            if (lo..=hi).contains(&v) {
                if labelled.contains(&m) {
                    bold.push(v)
                } else {
                    light.push(v)
                }
            }
        }
    }
    if bold.len() < 2 {
        bold = vec![lo, hi];
    }
    (bold, light)
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

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> std::path::PathBuf {
        std::env::temp_dir().join(format!("depo-plot-{}-{name}.svg", std::process::id()))
    }

    /// The texts of an SVG file with their `y` positions.
    fn texts(svg: &str) -> Vec<(String, f64)> {
        svg.split("<text")
            .skip(1)
            .map(|chunk| {
                let y = chunk.split("y=\"").nth(1).unwrap().split('"').next().unwrap().parse().unwrap();
                let body = chunk.split_once('>').unwrap().1.split("</text>").next().unwrap();
                (body.trim().replace("&lt;", "<"), y)
            })
            .collect()
    }

    #[test]
    fn points_a_log_axis_cannot_show_are_counted_in_the_legend() {
        let path = scratch("zeros");
        let series = [
            Series::markers("measured", vec![(1.0, 0.0), (2.0, 1e-3), (3.0, -1.0), (4.0, 2e-3)])
                .with_errors(vec![0.0, 1e-4, 0.0, 2e-4]),
            Series::line("model", vec![(1.0, 1e-3), (4.0, 2e-3)]),
        ];
        log_log(&path, "t", "x", "y", &series).unwrap();
        let labels: Vec<String> = texts(&std::fs::read_to_string(&path).unwrap()).into_iter().map(|t| t.0).collect();
        assert!(labels.contains(&"measured (2 points <= 0 not shown)".to_string()), "{labels:?}");
        assert!(labels.contains(&"model".to_string()), "a series with nothing left off keeps its name");
        // On a linear axis the same zeros are drawn and nothing is said.
        lines(&path, "t", "x", "y", &series, false).unwrap();
        assert!(!std::fs::read_to_string(&path).unwrap().contains("not shown"));
        std::fs::remove_file(path).ok();
    }

    #[test]
    fn a_decade_on_the_edge_of_a_log_axis_is_labelled() {
        let path = scratch("edge");
        let series = [Series::line("s", vec![(1e-8 * 1e6, 200.0), (10.0, 5000.0)])];
        log_log(&path, "t", "x", "y", &series).unwrap();
        let labels: Vec<String> = texts(&std::fs::read_to_string(&path).unwrap()).into_iter().map(|t| t.0).collect();
        for decade in ["0.01", "0.1", "1", "10"] {
            assert!(labels.contains(&decade.to_string()), "{decade} in {labels:?}");
        }
        std::fs::remove_file(path).ok();
    }

    /// Sizes from 0.3 to 20 um, a room study's: less than two decades, so every whole
    /// mantissa is labelled, the axis's first (0.3, below the first power of ten) too, and no
    /// light line crowds between them (each light line at a whole mantissa, none labelled).
    #[test]
    fn a_log_axis_within_two_decades_labels_its_first_tick() {
        let path = scratch("sizes");
        let series = [Series::markers("beta", vec![(0.3, 0.5), (1.0, 0.2), (20.0, 70.0)])];
        log_log(&path, "t", "x", "y", &series).unwrap();
        let labels: Vec<String> = texts(&std::fs::read_to_string(&path).unwrap()).into_iter().map(|t| t.0).collect();
        for tick in ["0.3", "0.5", "1", "2", "5", "10", "20"] {
            assert!(labels.contains(&tick.to_string()), "{tick} in {labels:?}");
        }
        let (labelled, light) = log_ticks(0.3 / 1.1, 20.0 * 1.1);
        assert_eq!(labelled.len(), 7 + 9 + 2, "0.3-0.9, 1-9, 10 and 20: {labelled:?}");
        assert!(light.is_empty(), "{light:?}");
        let (labelled, light) = log_ticks(0.009, 11.0);
        assert_eq!(labelled.len(), 10, "1, 2, 5 per decade from 0.01 to 10: {labelled:?}");
        assert_eq!(light.len(), 1 + 3 * 6, "0.009 and the other mantissas: {light:?}");
        std::fs::remove_file(path).ok();
    }

    /// Twelve decades, as the bench's figures span from the zero-error kernels drawn at 1e-17 to
    /// the f32 kernels' 1e-6: every one labelled, the leftmost too.
    #[test]
    fn every_decade_of_a_wide_log_axis_is_labelled() {
        let path = scratch("wide");
        let series = [Series::markers("kernels", vec![(1e-17, 0.5), (1.2e-6, 0.2)])];
        lines(&path, "t", "x", "y", &series, true).unwrap();
        let labels: Vec<String> = texts(&std::fs::read_to_string(&path).unwrap()).into_iter().map(|t| t.0).collect();
        for exponent in -17..=-6 {
            let decade = format!("1e{exponent}");
            assert!(labels.contains(&decade), "{decade} in {labels:?}");
        }
        std::fs::remove_file(path).ok();
    }

    #[test]
    fn points_carry_their_labels() {
        let path = scratch("labels");
        let series = [Series::markers("kernels", vec![(1e-17, 0.5), (1e-6, 0.2)])
            .with_labels(vec!["exact".to_string(), "fast".to_string()])];
        lines(&path, "t", "x", "y", &series, true).unwrap();
        let labels: Vec<String> = texts(&std::fs::read_to_string(&path).unwrap()).into_iter().map(|t| t.0).collect();
        assert!(labels.contains(&"exact".to_string()) && labels.contains(&"fast".to_string()), "{labels:?}");
        std::fs::remove_file(path).ok();
    }

    /// The points' labels in an SVG file as boxes in pixels (left, top, right, bottom), as
    /// [`place_labels`] reckons them, from their anchor and text; `names` says which texts are.
    fn label_boxes(svg: &str, names: &[String]) -> Vec<(String, (i32, i32, i32, i32))> {
        svg.split("<text")
            .skip(1)
            .filter_map(|chunk| {
                let attribute = |name: &str| chunk.split(&format!("{name}=\"")).nth(1)?.split('"').next();
                let body = chunk.split_once('>')?.1.split("</text>").next()?.trim().to_string();
                if !names.contains(&body) {
                    return None;
                }
                let (x, y): (i32, i32) = (attribute("x")?.parse().ok()?, attribute("y")?.parse().ok()?);
                let width = label_width(&body);
                let left = if attribute("text-anchor")? == "end" { x - width } else { x };
                let top = y - LABEL_HEIGHT / 2;
                Some((body, (left, top, left + width, top + LABEL_HEIGHT)))
            })
            .collect()
    }

    /// Kernels as `depo bench` draws them: a column of reference kernels at the axis' floor (two
    /// of them 0.005 apart), pairs on top of each other, a cluster by the right edge. Every
    /// label is drawn, none covers another or a marker, and each stays by its point.
    #[test]
    fn crowded_points_keep_their_labels_apart() {
        let path = scratch("crowded");
        let column = [1.13, 0.83, 0.75, 0.72, 0.6, 0.55, 0.545, 0.45, 0.40, 0.34, 0.2, 0.075, 0.07];
        let named = |prefix: &str, n: usize| (0..n).map(|i| format!("{prefix} p=1.3 q=0.7 kernel {i}")).collect();
        let cluster = [(1.5e-7, 0.88), (1.6e-7, 0.89), (4.7e-7, 0.91), (4.5e-7, 0.88), (1.7e-7, 0.885), (1.5e-7, 0.7)];
        let series = [
            Series::markers("reference", column.iter().map(|&y| (1e-17, y)).collect())
                .with_labels(named("ref", column.len())),
            Series::markers("pairs", vec![(8e-15, 0.13), (8.1e-15, 0.135), (9e-15, 0.54), (9e-15, 0.54)])
                .with_labels(named("pair", 4)),
            Series::markers("cluster", cluster.to_vec()).with_labels(named("f32", cluster.len())),
        ];
        lines(&path, "t", "x", "y", &series, true).unwrap();
        let svg = std::fs::read_to_string(&path).unwrap();
        let names: Vec<String> = series.iter().flat_map(|s| s.labels.clone()).collect();
        let boxes = label_boxes(&svg, &names);
        assert_eq!(boxes.len(), names.len(), "{boxes:?}");
        for (i, (a, box_a)) in boxes.iter().enumerate() {
            for (b, box_b) in &boxes[i + 1..] {
                assert_eq!(overlap(*box_a, *box_b), 0, "{a} {box_a:?} covers {b} {box_b:?}");
            }
        }
        let circles: Vec<(i32, i32)> = svg
            .split("<circle")
            .skip(1)
            .map(|c| {
                let at = |name: &str| {
                    c.split(&format!("{name}=\"")).nth(1).unwrap().split('"').next().unwrap().parse().unwrap()
                };
                (at("cx"), at("cy"))
            })
            .collect();
        assert!(circles.len() >= 23, "{circles:?}");
        for (name, b) in &boxes {
            for &(x, y) in &circles {
                assert_eq!(overlap(*b, (x - 4, y - 4, x + 4, y + 4)), 0, "{name} {b:?} covers the point at {x}, {y}");
            }
            let nearest = circles
                .iter()
                .map(|&(x, y)| (b.1 + b.3 - 2 * y).abs() / 2 + (x - b.0).abs().min((x - b.2).abs()))
                .min();
            assert!(nearest.unwrap() < 140, "{name} {b:?} far from every point");
        }
        std::fs::remove_file(path).ok();
    }

    #[test]
    fn the_legend_sits_below_the_plot() {
        let path = scratch("legend");
        let series: Vec<Series> =
            (0..12).map(|i| Series::line(format!("s{i}"), vec![(1.0, f64::from(i)), (2.0, 1.0)])).collect();
        lines(&path, "t", "x", "y", &series, false).unwrap();
        let texts = texts(&std::fs::read_to_string(&path).unwrap());
        for i in 0..12 {
            let (_, y) = texts.iter().find(|t| t.0 == format!("s{i}")).expect("legend entry");
            assert!(*y > f64::from(PLOT_HEIGHT), "legend entry s{i} at y = {y}");
        }
        std::fs::remove_file(path).ok();
    }
}
