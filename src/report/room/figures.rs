//! `depo room`'s figures, into a directory: deposition velocities and the loss rate beside Lai &
//! Nazaroff, the indoor/outdoor ratio when ventilated, the steady state under a continuous
//! source, the decay curves (also as CSV), each size's deposition maps (CSV and SVG), and
//! with a size distribution where its mass went.

use std::path::Path;

use depo_tracker::correlations::LaiNazaroff;
use depo_tracker::distribution::first_seen;
use depo_tracker::studies::{RoomStudy, MAP_BINS};

use super::distribution::{BinRow, DistributionReport, MassUnit, Split};
use super::{density_label, figure_cell, Measured, RoomResult, Row};
use crate::plot::{self, Series};
use crate::report::log_grid;
use crate::text::shown;
use crate::Error;

/// What a figure reads off a class's split: a value and its standard error.
type Pick<'a> = &'a dyn Fn(&Split) -> (f64, f64);

/// The palette's grey: the indoor/outdoor ranges of sizes without a deposit, apart from the
/// measured points' colours.
const NO_DEPOSIT_COLOR: usize = 7;

/// Writes the figures and maps of `r` into `dir` (which must exist), telling `note` a line for
/// each group of files written, as `depo room` prints them.
pub fn figures(dir: &Path, r: &RoomResult, note: &mut dyn FnMut(String)) -> Result<(), Error> {
    plot_room(dir, &r.study, &r.rows, note)?;
    if let Some(d) = &r.distribution {
        let figure = dir.join("room-distribution.svg");
        d.plot(&figure)?;
        let pm = dir.join("room-pm.svg");
        d.plot_pm(&pm)?;
        note(format!("figures: {} and {}", figure.display(), pm.display()));
    }
    Ok(())
}

/// Below this deposition velocity (m/s) a model curve is not drawn: Lai & Nazaroff's ceiling
/// for coarse particles reaches 1e-138 m/s, nothing a room shows. The legend says where.
const MODEL_FLOOR: f64 = 1e-10;

/// What a deposition map of the surface `name` outlines, in its in-plane coordinates in the
/// order x, y, z: the openings in it, and on the floor the furnishings' footprints.
fn outlines(study: &RoomStudy, r: &Row, name: &str) -> Vec<(String, [(f64, f64); 2])> {
    let scene = &study.scene;
    let mut out: Vec<(String, [(f64, f64); 2])> = scene
        .openings
        .iter()
        .filter(|o| scene.surface_name(o.wall) == name)
        .map(|o| {
            let ([c0, c1], [s0, s1]) = (o.center, o.size);
            let kind = format!("{:?}", o.kind).to_lowercase();
            (kind, [(c0 - s0 / 2.0, c1 - s1 / 2.0), (c0 + s0 / 2.0, c1 + s1 / 2.0)])
        })
        .collect();
    if name == "floor" {
        for (box_, row) in scene.furnishings.iter().zip(&r.furnishings) {
            out.push((row.name.clone(), [(box_.low[0], box_.low[1]), (box_.high[0], box_.high[1])]));
        }
    }
    out
}

/// `x` to `n` significant digits (all of its integer part), without trailing zeros: `12.3`
/// for 12.2828.
pub(super) fn significant(x: f64, n: i32) -> String {
    if x == 0.0 || !x.is_finite() {
        return x.to_string();
    }
    let decimals = (n - 1 - x.abs().log10().floor() as i32).max(0) as usize;
    let s = format!("{x:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// The room's figures and deposition maps into `dir`.
fn plot_room(dir: &Path, study: &RoomStudy, rows: &[Row], note: &mut dyn FnMut(String)) -> Result<(), Error> {
    // Lai & Nazaroff on 100 sizes across the study's, from the same model and inputs the
    // study compares with (its air, gravity and friction velocity).
    let u_star = study.scene.flow.friction_velocity().unwrap_or(0.0);
    let g = study.scene.gravity.iter().map(|g| g * g).sum::<f64>().sqrt();
    let size = study.scene.geometry.size();
    // Per density (a size distribution's bins can have several): Lai & Nazaroff for it across
    // its sizes, depo's values in their own colours.
    let mut deposition_series = Vec::new();
    let mut beta_series = Vec::new();
    for (k, rho) in first_seen(rows.iter().map(|r| r.density)).into_iter().enumerate() {
        let own: Vec<&Row> = rows.iter().filter(|r| r.density == rho).collect();
        let of = density_label(rows, rho, ", ", " kg/m^3");
        let (lo, hi) =
            own.iter().fold((f64::INFINITY, 0.0f64), |(a, b), r| (a.min(r.diameter_um), b.max(r.diameter_um)));
        let model: Vec<(f64, LaiNazaroff)> = log_grid(lo * 1e-6, hi * 1e-6, 100)
            .into_iter()
            .map(|d| (d * 1e6, LaiNazaroff::new(d, rho, &study.scene.air, g, u_star)))
            .collect();
        let curve = |name: &str, pick: &dyn Fn(&LaiNazaroff) -> f64, color: usize| {
            let points: Vec<(f64, f64)> =
                model.iter().map(|(d, m)| (*d, pick(m))).filter(|p| p.1 > MODEL_FLOOR).collect();
            let name = if points.len() < model.len() {
                format!("{name} (Lai & Nazaroff{of}; below {MODEL_FLOOR:.0e} m/s not shown)")
            } else {
                format!("{name} (Lai & Nazaroff{of})")
            };
            Series::line(name, points).color(color)
        };
        // depo's values with their standard errors, and where a surface had no deposit its 95 %
        // upper bound.
        let measured = |name: &str, pick: &dyn Fn(&Row) -> &Measured, color: usize| {
            let hit: Vec<&&Row> = own.iter().filter(|r| pick(r).upper_bound.is_none()).collect();
            let bounds: Vec<(f64, f64)> =
                own.iter().filter_map(|r| pick(r).upper_bound.map(|b| (r.diameter_um, b))).collect();
            let mut series = vec![Series::markers(
                format!("{name}{of} (depo, +- 1 s.e.)"),
                hit.iter().map(|r| (r.diameter_um, pick(r).value)).collect(),
            )
            .with_errors(hit.iter().map(|r| pick(r).error).collect())
            .color(color)];
            if !bounds.is_empty() {
                series.push(
                    Series::upper_bounds(format!("{name}{of}: no deposit, 95 % upper bound"), bounds).color(color),
                );
            }
            series
        };
        // Each density in its own colours: three for the room's surfaces, then one for each
        // furnishing's faces together, beside them.
        let boxes = own.first().map_or(0, |r| r.furnishings.len());
        let c = (3 + boxes) * k;
        deposition_series.extend(measured("floor", &|r| &r.floor, c));
        deposition_series.extend(measured("ceiling", &|r| &r.ceiling, c + 1));
        deposition_series.extend(measured("walls", &|r| &r.walls, c + 2));
        for j in 0..boxes {
            let name = format!("{} (all faces)", own[0].furnishings[j].name);
            deposition_series.extend(measured(&name, &|r| &r.furnishings[j].all, c + 3 + j));
        }
        deposition_series.push(curve("floor", &|m| m.floor, c));
        deposition_series.push(curve("ceiling", &|m| m.ceiling, c + 1));
        deposition_series.push(curve("walls", &|m| m.wall, c + 2));
        beta_series.extend(measured("beta", &|r| &r.beta_per_hour, 2 * k));
        beta_series.push(
            Series::line(
                format!("Lai & Nazaroff (2000){of}"),
                model.iter().map(|(d, m)| (*d, m.loss_rate(size) * 3600.0)).collect(),
            )
            .color(2 * k + 1),
        );
    }
    let deposition = dir.join("room-deposition.svg");
    plot::log_log(
        &deposition,
        "Deposition velocity in a room",
        "particle diameter (um)",
        "deposition velocity (m/s)",
        &deposition_series,
    )?;
    let beta = dir.join("room-beta.svg");
    plot::log_log(&beta, "Loss-rate coefficient", "particle diameter (um)", "beta (1/h)", &beta_series)?;
    // With ventilation, the steady indoor/outdoor ratio per size, with its error from beta's.
    let indoor_outdoor = dir.join("room-indoor-outdoor.svg");
    let ventilated = rows.iter().any(|r| r.indoor_outdoor.is_some());
    if ventilated {
        let mut series = Vec::new();
        for (k, rho) in first_seen(rows.iter().map(|r| r.density)).into_iter().enumerate() {
            let of = density_label(rows, rho, ", ", " kg/m^3");
            let own: Vec<&Row> = rows.iter().filter(|r| r.density == rho && r.indoor_outdoor.is_some()).collect();
            // Measured where beta was; where it rests on no deposit, the range it spans drawn
            // as a bar from its low to its high end (no measured point to mark).
            let (bounded, measured): (Vec<&Row>, Vec<&Row>) =
                own.into_iter().partition(|r| r.indoor_outdoor_range(study).is_some());
            let measured: Vec<(f64, &Measured)> =
                measured.iter().filter_map(|r| r.indoor_outdoor.as_ref().map(|m| (r.diameter_um, m))).collect();
            if !measured.is_empty() {
                series.push(
                    Series::markers(
                        format!("C_in / C_out{of} (depo, +- 1 s.e.)"),
                        measured.iter().map(|(d, m)| (*d, m.value)).collect(),
                    )
                    .with_errors(measured.iter().map(|(_, m)| m.error).collect())
                    .color(k),
                );
            }
            let ranges: Vec<(f64, (f64, f64))> =
                bounded.iter().filter_map(|r| r.indoor_outdoor_range(study).map(|x| (r.diameter_um, x))).collect();
            if !ranges.is_empty() {
                // The bar spans the range: centred, half its width either side.
                series.push(
                    Series::markers(
                        format!("C_in / C_out{of}: no deposit, the bar from beta's 95 % bound to no deposition"),
                        ranges.iter().map(|(d, (low, high))| (*d, 0.5 * (low + high))).collect(),
                    )
                    .with_errors(ranges.iter().map(|(_, (low, high))| 0.5 * (high - low)).collect())
                    .color(NO_DEPOSIT_COLOR + k),
                );
            }
        }
        plot::lines(
            &indoor_outdoor,
            "Indoor/outdoor concentration ratio at steady state",
            "particle diameter (um)",
            "C_in / C_out",
            &series,
            true,
        )?;
        note(format!("figure: {}", indoor_outdoor.display()));
    }
    if let Some(steady) = plot_steady(dir, study, rows)? {
        note(format!("figure: {}", steady.display()));
    }
    // The decay curves, a panel per size on shared axes (the sizes' curves, all near 1 where
    // deposition is slow, would hide each other on one chart): the airborne share with its
    // standard error, the fitted line over its window, and what ventilation alone would leave;
    // the curves also as one CSV.
    let decay = dir.join("room-decay.svg");
    let a = study.scene.exchange_rate();
    let end = study.settings.duration;
    let ventilation = |name: &str| Series::line(name, vec![(0.0, 1.0), (end / 60.0, (-a * end).exp())]).color(7);
    let mut panels = Vec::new();
    // One row per size and time; the particle density beside the diameter, since a study
    // of several densities (distribution modes) has sizes of the same diameter.
    let mut text = String::from("diameter_um,density_kg_m3,time_s,airborne,error,count\n");
    for r in rows {
        let c = &r.decay;
        let label = format!("{} um{}", significant(r.diameter_um, 3), density_label(rows, r.density, ", ", " kg/m^3"));
        let minutes: Vec<f64> = c.times_s.iter().map(|t| t / 60.0).collect();
        let mut series =
            vec![Series::markers("depo", minutes.iter().copied().zip(c.airborne.iter().copied()).collect())
                .with_errors(c.error.clone())
                .color(0)];
        let mut notes = Vec::new();
        if let (Some(f), Some(intercept)) = (&r.decay_fit, c.intercept) {
            let k = f.total_per_hour.value / 3600.0;
            let line = f.window_s.iter().map(|&t| (t / 60.0, (intercept - k * t).exp())).collect();
            series.push(Series::line("fit", line).dashed().color(1));
            let beta = match f.beta_per_hour.upper_bound {
                Some(bound) => format!("< {bound:.2e}"),
                None => figure_cell(&f.beta_per_hour),
            };
            notes.push(format!("fitted beta {beta} /h"));
        }
        if let Some(f) = &r.release_fit {
            notes.push(format!(
                "gone before the window; fitted from t = 0 to {} s: beta {} /h",
                significant(f.window_s[1], 2),
                figure_cell(&f.beta_per_hour)
            ));
        }
        if a > 0.0 {
            series.push(ventilation("ventilation"));
        }
        panels.push(plot::Panel { name: label, series, notes });
        for k in 0..c.times_s.len() {
            text.push_str(&format!(
                "{},{},{},{},{},{}\n",
                r.diameter_um, r.density, c.times_s[k], c.airborne[k], c.error[k], c.count[k]
            ));
        }
    }
    let mut key = vec![
        // A point for its error bar's symbol; the key draws no points.
        Series::markers("airborne share (depo, +- 1 s.e.)", vec![(0.0, 1.0)]).with_errors(vec![0.0]).color(0),
        Series::line("exponential fitted over its window, beta = its slope less a", Vec::new()).dashed().color(1),
    ];
    if a > 0.0 {
        key.push(ventilation(&format!("ventilation alone, exp(-a t), a = {} /h", shown(a * 3600.0))));
    }
    plot::small_multiples(
        &decay,
        "Airborne share after a release, per particle size",
        ("time (min)", "N(t) / N(0)"),
        &panels,
        &key,
        (false, true),
    )?;
    let curves = dir.join("room-decay.csv");
    std::fs::write(&curves, text).map_err(|e| format!("cannot write {}: {e}", curves.display()))?;
    // Deposition maps, one CSV per surface (walls, then furnishing faces, named as
    // `table.top`) and size, under a header of `#` lines: the tracked particles' deposits
    // over the whole run, per cell. The figure per size, and its CSV, are the study's own
    // estimator per cell: the deposition velocity over the averaging window.
    for r in rows {
        let label = (r.diameter_um * 1e4).round() / 1e4;
        let of = density_label(rows, r.density, "-", "kgm3");
        for m in &r.maps {
            let ((ra, r0, r1), (ca, c0, c1)) = (m.rows, m.columns);
            let (n, k) = (m.cells.len(), m.cells.first().map_or(0, Vec::len));
            let mut text = format!(
                "# depo room deposition map: {} {} ({} = {} m), particle diameter {label} um, density {} kg/m^3; \
                 deposits of the tracked particles over the whole run, per cell\n\
                 # rows: {ra} from {} to {} m in {n} cells; columns: {ca} from {} to {} m in {k} cells\n\
                 # cell size {} m ({ra}) x {} m ({ca})\n",
                m.kind,
                m.surface,
                m.normal.0,
                shown(m.normal.1),
                shown(r.density),
                shown(r0),
                shown(r1),
                shown(c0),
                shown(c1),
                shown((r1 - r0) / n as f64),
                shown((c1 - c0) / k as f64),
            );
            for row in &m.cells {
                let cells: Vec<String> = row.iter().map(u32::to_string).collect();
                text.push_str(&cells.join(","));
                text.push('\n');
            }
            // Bins of two densities can share a diameter: the density tells their files apart.
            let path = dir.join(format!("room-map-{}-{label}um{of}.csv", m.surface));
            std::fs::write(&path, text).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        }
        let (panels, text) = flux_maps(study, r, rows);
        let path = dir.join(format!("room-flux-{label}um{of}.csv"));
        std::fs::write(&path, text).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        let figure = dir.join(format!("room-map-{label}um{of}.svg"));
        let title = format!(
            "Deposition velocity per cell, {label} um{} (averaged from {} s)",
            density_label(rows, r.density, ", ", " kg/m^3"),
            shown(r.averaged_from_s)
        );
        plot::maps(&figure, &title, "deposition velocity (m/s)", &panels)?;
    }
    note(format!(
        "figures: {}, {} and {}; decay curves: {}; deposits per cell ({}x{} cells per surface): {dir}/room-map-SURFACE-SIZEum{of}.csv; \
         deposition velocity per cell: {dir}/room-flux-SIZEum{of}.csv, drawn per size as room-map-SIZEum{of}.svg",
        deposition.display(),
        beta.display(),
        decay.display(),
        curves.display(),
        MAP_BINS[0],
        MAP_BINS[1],
        dir = dir.display(),
        of = if first_seen(rows.iter().map(|r| r.density)).len() > 1 { "-DENSITYkgm3" } else { "" }
    ));
    Ok(())
}

/// The axes' names.
const AXES: [&str; 3] = ["x", "y", "z"];

/// One size's deposition velocity per cell: the figure's panels (the room's six surfaces and
/// each furnishing's top, the second in-plane axis up: z on a wall, y on the floor and
/// ceiling) and the CSV of every surface's cells, one line each.
fn flux_maps(study: &RoomStudy, r: &Row, rows: &[Row]) -> (Vec<plot::MapPanel>, String) {
    let scene = &study.scene;
    let mut text = format!(
        "# depo room deposition velocity per cell, particle diameter {} um{}: the study's estimator \
         (weighted deposits over the mean concentration) over the averaging window from {} s; \
         a cell without a deposit has value 0 and its 95 % upper bound\n\
         surface,row_axis,row_from_m,row_to_m,column_axis,column_from_m,column_to_m,vd_m_s,error_m_s,events,upper_bound_m_s\n",
        significant(r.diameter_um, 4),
        density_label(rows, r.density, ", ", " kg/m^3"),
        shown(r.averaged_from_s),
    );
    let mut panels = Vec::new();
    for (id, map) in r.flux_maps.iter().enumerate() {
        let name = scene.surface_name(id);
        let drawn = id < 6 || name.ends_with(".top");
        let Some(m) = map else {
            if drawn {
                let w = &scene.surfaces()[id];
                let [a, b] = depo_tracker::geometry::in_plane_axes(w.axis);
                let size = scene.geometry.size();
                panels.push(plot::MapPanel {
                    name,
                    detail: "wall function".into(),
                    cells: Err("no map: the wall function's deposits are expected values without a place".into()),
                    axes: [(AXES[b], 0.0, size[b]), (AXES[a], 0.0, size[a])],
                    outlines: Vec::new(),
                });
            }
            continue;
        };
        let [a, b] = m.axes;
        let [da, db] = m.cell_size();
        for i in 0..m.bins[0] {
            for j in 0..m.bins[1] {
                let c = &m.cells[i * m.bins[1] + j];
                let bound = if c.events == 0 { c.upper_bound.to_string() } else { String::new() };
                text.push_str(&format!(
                    "{name},{},{},{},{},{},{},{},{},{},{bound}\n",
                    AXES[a],
                    m.low[0] + i as f64 * da,
                    m.low[0] + (i + 1) as f64 * da,
                    AXES[b],
                    m.low[1] + j as f64 * db,
                    m.low[1] + (j + 1) as f64 * db,
                    c.value,
                    c.error,
                    c.events,
                ));
            }
        }
        if !drawn {
            continue;
        }
        // Rows of the panel along the second in-plane axis (up), columns along the first.
        let cells = (0..m.bins[1])
            .map(|j| {
                (0..m.bins[0])
                    .map(|i| {
                        let k = i * m.bins[1] + j;
                        plot::MapCell { value: m.cells[k].value, resolved: m.resolved(k) }
                    })
                    .collect()
            })
            .collect();
        let events: usize = m.cells.iter().map(|c| c.events).sum();
        let detail = if events == 0 {
            // One cell: the surface's bound.
            format!("no deposit: < {:.1e} m/s", m.cells[0].upper_bound)
        } else if m.bins == [1, 1] {
            let state = if m.resolved(0) { "resolved" } else { "unresolved" };
            format!("one cell: {:.1e} m/s, {state}", m.cells[0].value)
        } else {
            let side = if (da - db).abs() <= 1e-9 * da {
                format!("{} m", significant(da, 2))
            } else {
                format!("{} x {} m", significant(da, 2), significant(db, 2))
            };
            format!("{side} cells, {} % resolved", (m.resolved_share() * 100.0).round())
        };
        panels.push(plot::MapPanel {
            detail,
            cells: Ok(cells),
            axes: [(AXES[b], m.low[1], m.high[1]), (AXES[a], m.low[0], m.high[0])],
            outlines: outlines(study, r, &name),
            name,
        });
    }
    (panels, text)
}

/// The steady state under the study's continuous source, per size, into
/// `room-steady.svg`: for outdoor air, `C_in/C_out` from the source's own release beside the
/// well-mixed room's mass balance from the release study's `beta`; for an indoor source, the
/// steady concentration per particle emitted a second beside the well-mixed room's
/// `1 / (V (a + beta))`. Sizes the room does not mix well are named in the title. `None`, and
/// no file, where no size has a steady figure above zero to draw.
fn plot_steady(dir: &Path, study: &RoomStudy, rows: &[Row]) -> Result<Option<std::path::PathBuf>, Error> {
    let path = dir.join("room-steady.svg");
    let outdoor = rows.iter().any(|r| r.steady.as_ref().is_some_and(|s| s.indoor_outdoor.is_some()));
    let volume = study.scene.free_volume();
    let a = study.scene.exchange_rate() * 3600.0;
    let mut series = Vec::new();
    let mut steady_points = Vec::new();
    for (k, rho) in first_seen(rows.iter().map(|r| r.density)).into_iter().enumerate() {
        let of = density_label(rows, rho, ", ", " kg/m^3");
        let own: Vec<&Row> = rows.iter().filter(|r| r.density == rho && r.steady.is_some()).collect();
        let steady: Vec<(f64, f64, f64)> = own
            .iter()
            .filter_map(|r| {
                let st = r.steady.as_ref()?;
                if outdoor {
                    st.indoor_outdoor.as_ref().map(|m| (r.diameter_um, m.value, m.error))
                } else {
                    let c = st.concentration_per_emission_s_per_m3;
                    Some((r.diameter_um, c.value, c.error))
                }
            })
            .collect();
        steady_points.extend(steady.iter().map(|&(_, v, _)| v));
        series.push(
            Series::markers(
                format!("steady state of the source{of} (depo, +- 1 s.e.)"),
                steady.iter().map(|&(d, v, _)| (d, v)).collect(),
            )
            .with_errors(steady.iter().map(|&(.., e)| e).collect())
            .color(2 * k),
        );
        let mixed: Vec<(f64, f64)> = own
            .iter()
            .filter_map(|r| {
                let beta = r.beta_per_hour.value;
                if outdoor {
                    r.indoor_outdoor.as_ref().map(|m| (r.diameter_um, m.value))
                } else {
                    (a + beta > 0.0).then(|| (r.diameter_um, 3600.0 / (volume * (a + beta))))
                }
            })
            .collect();
        let name = if outdoor {
            format!("well-mixed room, from the release's beta{of}")
        } else {
            format!("well-mixed room, 1 / (V (a + beta)) from the release's beta{of}")
        };
        series.push(Series::line(name, mixed).color(2 * k + 1));
    }
    let unmixed: Vec<String> =
        rows.iter().filter(|r| r.well_mixed == Some(false)).map(|r| significant(r.diameter_um, 3)).collect();
    let title = if unmixed.is_empty() {
        "Steady state under a continuous source".to_string()
    } else {
        format!("Steady state under a continuous source (not well mixed at {} um)", unmixed.join(", "))
    };
    if !steady_points.iter().any(|&v| v > 0.0 && v.is_finite()) {
        return Ok(None);
    }
    // Logarithmic: coarse sizes' ratios fall by orders of magnitude.
    let y_label = if outdoor { "C_in / C_out" } else { "steady concentration per emission (s/m^3)" };
    plot::log_log(&path, &title, "particle diameter (um)", y_label, &series)?;
    Ok(Some(path))
}

impl DistributionReport {
    /// The PM figure: for all the mass, PM10 and PM2.5, the share of each one's injected mass
    /// on the floor, on the ceiling and walls (their errors combined as if independent, which
    /// can only overstate the sum's), on the furnishings (if any), airborne and, with
    /// ventilation, exhausted at the end, with their standard errors. A class with no mass
    /// injected is left out, and the title says so.
    pub(super) fn plot_pm(&self, path: &Path) -> Result<(), Error> {
        let all = self.classes();
        let classes: Vec<&(&str, &Split)> = all.iter().filter(|(_, s)| s.injected > 0.0).collect();
        let share = |pick: Pick| -> (Vec<f64>, Vec<f64>) {
            classes
                .iter()
                .map(|(_, s)| {
                    let (v, e) = pick(s);
                    (v / s.injected, e / s.injected)
                })
                .unzip()
        };
        let mut fates: Vec<(&str, Pick)> = vec![
            ("floor", &|s: &Split| (s.floor.value, s.floor.error)),
            ("ceiling and walls", &|s: &Split| (s.ceiling.value + s.walls.value, s.ceiling.error.hypot(s.walls.error))),
        ];
        if self.furnished {
            fates.push(("furnishings", &|s: &Split| (s.furnishings.value, s.furnishings.error)));
        }
        fates.push(("airborne at the end", &|s: &Split| (s.airborne.value, s.airborne.error)));
        if self.ventilated {
            fates.push(("exhausted", &|s: &Split| (s.exhausted.value, s.exhausted.error)));
        }
        let series: Vec<plot::Bars> = fates
            .into_iter()
            .map(|(name, pick)| {
                let (values, errors) = share(pick);
                plot::Bars { name: format!("{name} (+- 1 s.e.)"), values, errors }
            })
            .collect();
        let groups: Vec<&str> = classes.iter().map(|(name, _)| *name).collect();
        let none: Vec<&str> = all.iter().filter(|(_, s)| s.injected <= 0.0).map(|(name, _)| *name).collect();
        let title = if none.is_empty() {
            "Where the mass goes: all of it, PM10 and PM2.5".to_string()
        } else {
            format!("Where the mass goes (no {} mass injected)", none.join(" or "))
        };
        Ok(plot::bars(path, &title, "share of the class's mass", &groups, &series)?)
    }

    /// The figure: per bin, the mass per unit `ln d` injected and where it went, against the
    /// bin's diameter; one set of curves per density (the first solid, the others dashed).
    pub(super) fn plot(&self, path: &Path) -> Result<(), Error> {
        let mut series = Vec::new();
        let densities = first_seen(self.bins.iter().map(|b| b.density));
        for &rho in &densities {
            let bins: Vec<&BinRow> = self.bins.iter().filter(|b| b.density == rho).collect();
            let label = |what: &str| {
                if densities.len() > 1 {
                    format!("{what} ({rho} kg/m^3)")
                } else {
                    what.to_string()
                }
            };
            let per_ln_d = |pick: &dyn Fn(&BinRow) -> f64| -> Vec<(f64, f64)> {
                bins.iter().map(|b| (b.diameter_um, b.mass * pick(b) / (b.upper_um / b.lower_um).ln())).collect()
            };
            // The first density's curves solid, the others' dashed, each fate in its colour.
            let first = rho == densities[0];
            let curve = |name: &str, points: Vec<(f64, f64)>, color: usize| {
                let s = Series::line(label(name), points).color(color);
                if first {
                    s
                } else {
                    s.dashed()
                }
            };
            series.push(curve("injected", per_ln_d(&|_| 1.0), 7));
            series.push(curve("floor", per_ln_d(&|b| b.floor), 0));
            series.push(curve("ceiling and walls", per_ln_d(&|b| b.ceiling + b.walls), 2));
            if bins.iter().any(|b| b.furnishings > 0.0) {
                series.push(curve("furnishings", per_ln_d(&|b| b.furnishings), 4));
            }
            series.push(curve("airborne at the end", per_ln_d(&|b| b.airborne), 1));
            if bins.iter().any(|b| b.exhausted > 0.0) {
                series.push(curve("exhausted", per_ln_d(&|b| b.exhausted), 3));
            }
        }
        let y = if self.mass_unit == MassUnit::Kg {
            "mass per unit ln d in the room (kg)"
        } else {
            "share of mass per unit ln d"
        };
        Ok(plot::log_log(path, "Where a size distribution's mass goes", "particle diameter (um)", y, &series)?)
    }
}
