//! `depo room`'s text table: the settings, a line per size beside Lai & Nazaroff, the walls and
//! furnishings apart where they differ, the notes, the release read as a decay experiment, the
//! steady state, and with a size distribution where its mass went.

use depo_tracker::decay::MIN_AIRBORNE;
use depo_tracker::distribution::first_seen;
use depo_tracker::studies::RoomStudy;
use depo_tracker::{Flow, Geometry};

use super::distribution::{DistributionReport, MassUnit, Part};
use super::figures::significant;
use super::resolution::{particles_to_resolve, two_figures_up, RESOLVED_ERROR};
use super::rows::{source_label, Share};
use super::{figure_cell, Measured, RoomResult, Row};
use crate::report::outln;
use crate::text::shown;
use depo_tracker::steady::NOT_WELL_MIXED;

/// The table of `r`, each line ended, as `depo room` prints it.
pub fn table(r: &RoomResult) -> String {
    let mut text = String::new();
    let o = &mut text;
    let seconds = r.seconds;
    let study = &r.study;
    let rows = &r.rows[..];
    let Geometry::Room { size } = study.scene.geometry else { unreachable!("a room study has a room") };
    let u_star = match study.scene.flow {
        Flow::TurbulentRoom { friction_velocity, .. } => friction_velocity,
        _ => 0.0,
    };
    let ventilated = study.scene.exchange_rate() > 0.0;
    let furnished = !study.scene.furnishings.is_empty();
    let steps: u64 = rows.iter().map(|r| r.particle_steps).sum();
    let particles: Vec<String> = rows.iter().map(|r| r.particles.to_string()).collect();
    outln!(
        o,
        "Room {} x {} x {} m, u* = {} m/s, {} particles per size, {} s; deposition velocity (m/s) per surface",
        shown(size[0]),
        shown(size[1]),
        shown(size[2]),
        shown(u_star),
        particles.join("/"),
        shown(study.settings.duration)
    );
    if let Some(target) = study.target_error {
        outln!(
            o,
            "({} first, more up to {} where beta or a surface with Lai & Nazaroff's v_d >= 1e-7 m/s was above {} % error.)",
            study.count,
            study.max_count,
            shown(100.0 * target)
        );
    }
    outln!(o, "beside Lai & Nazaroff (2000) for the same u*; ratio = beta / Lai & Nazaroff's beta.");
    if ventilated {
        outln!(
            o,
            "Ventilated: {} air changes per hour, penetration {}; C_in/C_out = P a / (a + beta) at steady state.",
            heading_number(study.scene.exchange_rate() * 3600.0),
            heading_number(study.penetration)
        );
    }
    if !study.scene.openings.is_empty() {
        outln!(
            o,
            "Through {} openings: air and particles from the supply to the exhaust in a potential flow; \
             particles leave at the exhaust (a = exhaust flow / air volume).",
            study.scene.openings.len()
        );
    }
    let f = &study.filtration;
    // Each filter's single-pass efficiency at the sizes run, where it acts.
    let efficiencies = |pick: &dyn Fn(&Row) -> Option<f64>| -> Option<String> {
        let values: Option<Vec<String>> = rows.iter().map(|r| pick(r).map(|e| format!("{e:.3}"))).collect();
        values.map(|v| v.join(", "))
    };
    if let Some(list) = efficiencies(&|r| r.supply_filter_efficiency) {
        outln!(o, "Supply filter efficiency eta_s at the sizes run: {list}.");
    }
    if let Some(list) = efficiencies(&|r| r.recirculation_filter_efficiency) {
        outln!(o, "Recirculation filter efficiency eta_r at the sizes run: {list}.");
    }
    if f.supply_share > 0.0 || f.recirculation > 0.0 {
        outln!(
            o,
            "Filters: a share {} of the exchange through the supply filter, recirculation {} per hour through its \
             filter (its removal eta_r a_r, added to the exhaust: {} per hour at the sizes run); \
             C_in/C_out = (P (1 - s) a + (1 - eta_s) s a) / (a + eta_r a_r + beta).",
            heading_number(f.supply_share),
            heading_number(f.recirculation * 3600.0),
            rows.iter()
                .map(|r| format!("{:.3}", r.filter_removal_per_hour.unwrap_or(0.0)))
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    outln!(
        o,
        "{:>8}  {:>27} {:>9}  {:>27} {:>9}  {:>27} {:>9}  {:>20} {:>9} {:>6} {:>10}{}  method",
        "d (um)",
        "floor (m/s)",
        "L&N (m/s)",
        "ceiling (m/s)",
        "L&N (m/s)",
        "walls (m/s)",
        "L&N (m/s)",
        "beta (1/h)",
        "L&N (1/h)",
        "ratio",
        "near floor",
        if ventilated { format!("  {:>18}", "C_in/C_out") } else { String::new() }
    );
    // A surface's figure, flagged with `*` when unresolved.
    let cell = |r: &Row, name: &str, m: &Measured| {
        format!("{}{}", m.cell(), if r.unresolved.contains(&name) { "*" } else { " " })
    };
    for (i, r) in rows.iter().enumerate() {
        density_heading(o, rows, i);
        let method = match (r.excursions_truncated, r.longest_excursion_s) {
            (Some(t), Some(s)) if t > 1e-3 => format!("excursions ({:.1} % at {s:.0} s)", 100.0 * t),
            (Some(_), _) => "excursions".to_string(),
            (None, _) => r.method.to_string(),
        };
        // Averaged from the release: every particle had left before the window.
        let method = if r.averaged_from_s == 0.0 && study.transient > 0.0 { format!("{method} +") } else { method };
        outln!(
            o,
            "{:>8.3}  {:>27} {:>9}  {:>27} {:>9}  {:>27} {:>9}  {:>20} {:>9.3} {:>6} {:>10}{}  {method}",
            r.diameter_um,
            cell(r, "floor", &r.floor),
            model_cell(r.lai_nazaroff.floor),
            cell(r, "ceiling", &r.ceiling),
            model_cell(r.lai_nazaroff.ceiling),
            cell(r, "walls", &r.walls),
            model_cell(r.lai_nazaroff.walls),
            beta_cell(&r.beta_per_hour),
            r.lai_nazaroff.beta_per_hour,
            ratio_cell(&r.beta_per_hour, r.lai_nazaroff.beta_per_hour),
            near_floor_cell(r),
            r.indoor_outdoor.as_ref().map_or(String::new(), |m| format!("  {:>18}", indoor_outdoor_cell(r, m, study)))
        );
    }
    // The four walls apart where they can differ: in material, or in the openings' flow.
    let walls = &study.scene.walls[2..6];
    if walls.iter().any(|w| *w != walls[0]) || !study.scene.openings.is_empty() {
        walls_table(o, rows);
    }
    // One legend line: the marks the table uses; room --help and docs/commands.md say more.
    let model = |r: &Row| [r.lai_nazaroff.floor, r.lai_nazaroff.ceiling, r.lai_nazaroff.walls];
    let mut legend = vec!["+- 1 s.e.".to_string(), "[n] deposit events".into(), "< 95 % upper bound".into()];
    if rows.iter().any(|r| r.excursions_truncated.is_some()) {
        legend.push("excursions (x % at T s): weight given up at their longest T".into());
    }
    if rows.iter().any(|r| !r.unresolved.is_empty()) {
        legend.push(format!("* unresolved (no event, or error above {} %)", 100.0 * RESOLVED_ERROR));
    }
    if rows.iter().any(|r| r.well_mixed == Some(false)) {
        legend.push(format!("~ not well mixed (near floor above {NOT_WELL_MIXED})"));
    }
    if rows.iter().any(|r| r.indoor_outdoor.is_some() && r.beta_per_hour.upper_bound.is_some()) {
        legend.push("C_in/C_out a-b [0]: from beta's bound to no deposition".into());
    }
    if rows.iter().any(|r| r.averaged_from_s == 0.0) && study.transient > 0.0 {
        legend.push("+ all gone before the window: from t = 0".into());
    }
    if rows.iter().flat_map(model).any(|v| v < MODEL_NONE) {
        legend.push(format!("L&N < {MODEL_NONE:.0e}: none"));
    }
    outln!(o, "{}; room --help says more.", legend.join("; "));
    if rows.iter().any(|r| !r.unresolved.is_empty()) {
        let more: Vec<String> = rows
            .iter()
            .filter_map(|r| {
                let model = &r.lai_nazaroff;
                let figures = [(&r.floor, model.floor), (&r.ceiling, model.ceiling), (&r.walls, model.walls)];
                particles_to_resolve(r.particles, figures)
                    .map(|n| format!("{} particles at {} um", two_figures_up(n), (r.diameter_um * 1e4).round() / 1e4))
            })
            .collect();
        if !more.is_empty() {
            outln!(o, "To resolve to {} %: about {} (particles.max_count).", 100.0 * RESOLVED_ERROR, more.join(", "));
        }
    }
    outln!(
        o,
        "Averages from {} s to {} s; {steps} particle-steps tracked (excursions not counted) in {seconds:.1} s.",
        shown(study.transient * study.settings.duration),
        shown(study.settings.duration)
    );
    // Under the first table's legend, which it shares (its cells read alike), with its own.
    if furnished {
        furnishings_table(o, rows, study);
    }
    decay_table(o, rows, study.scene.exchange_rate() * 3600.0, !study.scene.openings.is_empty());
    steady_table(o, rows, study);
    if let Some(d) = &r.distribution {
        d.table(o);
    }
    text
}

/// Before the first row of each density, where the rows have several: the density.
fn density_heading(o: &mut String, rows: &[Row], i: usize) {
    let several = rows.iter().any(|r| r.density != rows[0].density);
    if several && (i == 0 || rows[i - 1].density != rows[i].density) {
        outln!(o, "particle density {} kg/m^3:", shown(rows[i].density));
    }
}

/// Each vertical wall's deposition velocity, where the walls differ.
fn walls_table(o: &mut String, rows: &[Row]) {
    outln!(o, "Each vertical wall (m/s; x0 at x = 0, x1 opposite it, y0 at y = 0, y1 opposite it):");
    outln!(o, "{:>8}  {:>27}  {:>27}  {:>27}  {:>27}", "d (um)", "x0", "x1", "y0", "y1");
    for r in rows {
        let cells: Vec<String> = r.each_wall.iter().map(|w| w.velocity.cell()).collect();
        outln!(o, "{:>8.3}  {:>27}  {:>27}  {:>27}  {:>27}", r.diameter_um, cells[0], cells[1], cells[2], cells[3]);
    }
}

/// The furnishings' table under the per-size one: per size and furnishing, the deposition
/// velocity (m/s) onto all its faces, its top, its bottom and its sides, and its share of the
/// release.
fn furnishings_table(o: &mut String, rows: &[Row], study: &RoomStudy) {
    let scene = &study.scene;
    outln!(o, "");
    outln!(
        o,
        "Furnishings: {} boxes, {:.3} m^3 of air, surface-to-volume ratio {:.3} 1/m; deposition velocity (m/s) per box:",
        scene.furnishings.len(),
        scene.free_volume(),
        scene.surface_to_volume()
    );
    outln!(
        o,
        "{:>8}  {:>12} {:>8}  {:>27}  {:>27}  {:>27}  {:>27}  {:>24}",
        "d (um)",
        "furnishing",
        "area m^2",
        "all faces",
        "top",
        "bottom",
        "sides",
        "share of release"
    );
    for r in rows {
        for f in &r.furnishings {
            outln!(
                o,
                "{:>8.3}  {:>12} {:>8.3}  {:>27}  {:>27}  {:>27}  {:>27}  {:>24}",
                r.diameter_um,
                f.name,
                f.area_m2,
                f.all.cell(),
                f.top.cell(),
                f.bottom.cell(),
                f.sides.cell(),
                share_cell(&f.deposited, r.release.particles)
            );
        }
    }
    // One legend line; room --help and docs/commands.md say more.
    outln!(
        o,
        "sides: the four vertical faces; share of release: of the released number, [n] particles, < 95 % bound; \
         L&N's beta above is the bare room's; room --help says more."
    );
}

/// A share of the release in the furnishings' table: `value +- error [count]`, or where no
/// tracked particle ended there `< bound [0]`, the 95 % upper bound on a binomial share with
/// no event in `released` trials by the rule of three, 3 / n (Hanley & Lippman-Hand 1983,
/// JAMA 249:1743), as the surfaces' cells bound a velocity with no event: never a `0 +- 0`
/// that reads as a measured zero.
fn share_cell(s: &Share, released: usize) -> String {
    if s.count == 0 {
        format!("< {:.1e} [0]", 3.0 / released.max(1) as f64)
    } else {
        format!("{:.2e} +- {:.1e} [{}]", s.share, s.share_error, s.count)
    }
}

/// A rate per hour or a share an input gives, in a heading: to four significant figures,
/// trailing zeros dropped (`2.003`, not `2.003205128205128`; `0.7`, not `0.7000000000000001`).
/// With openings the exchange rate is a flow over a volume, which has no round value.
fn heading_number(x: f64) -> String {
    significant(x, 4)
}

/// Fewer deposits than this within the decay fit's window are flagged in the table: the
/// fitted `beta` then rests on a handful of events (a relative Poisson error above 30 %) and
/// its delta-method error is itself uncertain.
const FEW_DEPOSITS: usize = 10;

/// A share in % (of a release, or of a steady source): `95.5` (a share below 0.1 % to one
/// significant figure, never a `0.0` that reads as none); where `none_there` (no tracked
/// particle ended there), `< b [0]`: the 95 % upper bound on a binomial share with no event
/// in `released` trials by the rule of three, 300 / n % (as the furnishings' table bounds its
/// shares).
fn percent_cell(share: f64, none_there: bool, released: usize) -> String {
    let percent = 100.0 * share;
    if none_there {
        format!("< {} [0]", significant(300.0 / released.max(1) as f64, 2))
    } else if percent < 0.1 {
        significant(percent, 1)
    } else {
        format!("{percent:.1}")
    }
}

/// The fitted `beta` per hour: `value +- error [deposits]`, flagged `?` with fewer than
/// [`FEW_DEPOSITS`], or `< bound [0]` (the 95 % upper bound) with none.
fn fitted_cell(m: &Measured) -> String {
    match m.upper_bound {
        Some(bound) => format!("< {bound:.2e} [0]"),
        None => format!("{} [{}]{}", figure_cell(m), m.events, if m.events < FEW_DEPOSITS { "?" } else { "" }),
    }
}

/// The table's second part: each size read as a decay experiment (the fitted `beta` beside
/// the study's) and where the release ends; `ach` the air changes per hour, `openings`
/// whether the exhaust is through openings (whose air need not be the room's mean).
fn decay_table(o: &mut String, rows: &[Row], ach: f64, openings: bool) {
    outln!(o, "");
    outln!(
        o,
        "After the release at t = 0: its decay fitted (beta less a = {} /h), and where the particles are at the end:",
        heading_number(ach)
    );
    outln!(
        o,
        "{:>8}  {:>28} {:>6} {:>12}  {:>12} {:>12} {:>12}{} {:>12} {:>12}  {:>20}  {:>28}",
        "d (um)",
        "beta fitted (1/h)",
        "z",
        "window (s)",
        "floor %",
        "ceiling %",
        "walls %",
        // A furnished room's release has a part on the furnishings.
        if rows.iter().any(|r| r.release.furnishings.is_some()) {
            format!(" {:>13}", "furnishings %")
        } else {
            String::new()
        },
        "exhausted %",
        "airborne %",
        "floor (ug/m2 per mg)",
        "50 % / 90 % deposited by (s)"
    );
    for (i, r) in rows.iter().enumerate() {
        density_heading(o, rows, i);
        let (fitted, z, window) = match &r.decay_fit {
            Some(f) => (
                fitted_cell(&f.beta_per_hour),
                f.z.map_or("-".to_string(), |z| format!("{z:.1}")),
                format!("{:.0}-{:.0}", f.window_s[0], f.window_s[1]),
            ),
            None => match &r.release_fit {
                // Gone before the window: fitted from the release on.
                Some(f) => (
                    format!("{} ^", fitted_cell(&f.beta_per_hour)),
                    f.z.map_or("-".to_string(), |z| format!("{z:.1}")),
                    format!("{}-{}", significant(f.window_s[0], 2), significant(f.window_s[1], 2)),
                ),
                None => ("none (too few particles)".to_string(), "-".to_string(), "-".to_string()),
            },
        };
        let release = &r.release;
        let pct = |s: &Share| percent_cell(s.share, s.count == 0, release.particles);
        // Nothing leaves a room with no exchange and no recirculation filter: exactly none.
        let exhaust = ach > 0.0 || r.filter_removal_per_hour.is_some_and(|f| f > 0.0);
        outln!(
            o,
            "{:>8.3}  {:>28} {:>6} {:>12}  {:>12} {:>12} {:>12}{} {:>12} {:>12}  {:>20}  {:>28}",
            r.diameter_um,
            fitted,
            z,
            window,
            pct(&release.floor),
            pct(&release.ceiling),
            pct(&release.walls),
            release.furnishings.as_ref().map_or(String::new(), |s| format!(" {:>13}", pct(s))),
            if exhaust { pct(&release.exhausted) } else { "none".to_string() },
            pct(&release.airborne),
            // kg/m^2 per kg released, for 1 mg released, in ug/m^2; none deposited, "-".
            release.floor.loading_per_m2.filter(|&l| l > 0.0).map_or("-".to_string(), |l| format!("{:.3e}", l * 1e3)),
            r.deposited_by_s.map(|t| t.map_or("-".to_string(), |t| format!("{t:.0}"))).join(" / ")
        );
    }
    // One legend line; room --help says more.
    let mut legend = vec![
        format!("[n] deposits in the window, ? fewer than {FEW_DEPOSITS}"),
        "z: (fitted - beta) / paired s.e.".to_string(),
        "% of the number released, < 95 % bound [0]".to_string(),
        "- none".to_string(),
    ];
    if rows.iter().any(|r| r.release_fit.is_some()) {
        legend.push(format!(
            "^ gone before the window: fitted from t = 0 while {MIN_AIRBORNE} airborne (how fast, not a well-mixed rate)"
        ));
    }
    outln!(o, "{}; room --help says more.", legend.join("; "));
    let apart = rows.iter().filter_map(|r| r.decay_fit.as_ref()?.z).any(|z| z.abs() > 3.0);
    if openings && apart {
        outln!(
            o,
            "! beta fitted differs from the study's beta by more than 3 standard errors: through openings the exhaust \
             draws the air near it, older or fresher than the room's mean, so the decay less a holds that difference \
             too and is no deposition rate; the study's beta (deposits over airborne time) is (docs/tracker.md, \
             \"What it means\")."
        );
    }
}

/// The steady state under a continuous source, per size (`depo_tracker::steady`).
fn steady_table(o: &mut String, rows: &[Row], study: &RoomStudy) {
    outln!(o, "");
    outln!(o, "Steady state under a continuous source ({}), per size:", source_label(study));
    let ventilated = rows.iter().any(|r| r.steady.as_ref().is_some_and(|s| s.indoor_outdoor.is_some()));
    outln!(
        o,
        "{:>8}  {:>18}  {:>27} {:>27} {:>27}  {:>11} {:>11} {:>11} {:>11} {:>11} {:>8} {:>13}{}",
        "d (um)",
        "time in air (h)",
        "floor (m/s)",
        "ceiling (m/s)",
        "walls (m/s)",
        "floor %",
        "ceiling %",
        "walls %",
        "furnish %",
        "exhausted %",
        "beyond %",
        "near floor",
        if ventilated { format!("  {:>18}", "C_in/C_out") } else { String::new() }
    );
    for (i, r) in rows.iter().enumerate() {
        density_heading(o, rows, i);
        let Some(st) = &r.steady else {
            outln!(o, "{:>8.3}  nothing removes these particles: no steady state", r.diameter_um);
            continue;
        };
        // A share of exactly 0: none of the particles the steady state is drawn from ended
        // there, and no late rate leads there.
        let pct = |x: f64| percent_cell(x, x == 0.0, r.release.particles);
        // A fate the scene has no means to reach is none by construction, not a bound.
        let furnished = !study.scene.furnishings.is_empty();
        let exhaust = study.scene.exchange_rate() > 0.0 || r.filter_removal_per_hour.is_some_and(|f| f > 0.0);
        let possible = |can: bool, x: f64| if can { pct(x) } else { "none".to_string() };
        outln!(
            o,
            "{:>8.3}  {:>18}  {:>27} {:>27} {:>27}  {:>11} {:>11} {:>11} {:>11} {:>11} {:>8} {:>13}{}",
            r.diameter_um,
            figure_cell(&st.residence_h),
            st.floor_velocity.cell(),
            st.ceiling_velocity.cell(),
            st.walls_velocity.cell(),
            pct(st.floor),
            pct(st.ceiling),
            pct(st.walls),
            possible(furnished, st.furnishings),
            possible(exhaust, st.exhausted),
            // Not a fate: exactly 0 where every particle had ended within the run.
            if st.beyond_run == 0.0 { "0".to_string() } else { pct(st.beyond_run) },
            format!("{:.2} +- {:.2}", st.near_floor_over_mean.value, st.near_floor_over_mean.error),
            st.indoor_outdoor.as_ref().map_or(String::new(), |m| format!("  {:>18}", figure_cell(m)))
        );
    }
    // One legend line; room --help and docs/commands.md say more.
    outln!(
        o,
        "time in air: airborne number per particle emitted an hour; % of the source, < 95 % bound [0], none: no way \
         there; beyond %: of the time in air \
         from past the run; near floor: lowest tenth of the height over the mean; room --help says more."
    );
}

/// The near-floor concentration over the mean under a source spread over the room, `1.02`,
/// marked `~` where the room is not well mixed for the size; `-` where there is none.
fn near_floor_cell(r: &Row) -> String {
    match (r.near_floor_over_mean, r.well_mixed) {
        (Some(m), Some(false)) => format!("{:.2} ~", m.value),
        (Some(m), _) => format!("{:.2}  ", m.value),
        (None, _) => "-  ".to_string(),
    }
}

/// Below this deposition velocity (m/s) the table prints Lai & Nazaroff's as `< 1e-30`: their
/// ceiling velocity for coarse particles falls to 1e-138 m/s and to 0 in double precision,
/// no deposit a room could show.
const MODEL_NONE: f64 = 1e-30;

/// Lai & Nazaroff's deposition velocity (m/s) in the table: `1.78e-5`, or `< 1e-30` below
/// [`MODEL_NONE`].
pub(super) fn model_cell(v: f64) -> String {
    if v < MODEL_NONE {
        format!("< {MODEL_NONE:.0e}")
    } else {
        format!("{v:.2e}")
    }
}

impl DistributionReport {
    /// The table under the per-size one.
    pub(super) fn table(&self, o: &mut String) {
        let absolute = self.mass_unit == MassUnit::Kg;
        // Micrograms read better than kilograms.
        let k = if absolute { 1e9 } else { 1.0 };
        let unit = if absolute { "ug in the room" } else { "share of the distribution's mass" };
        // Each header's unit: micrograms, or a share (of the distribution's whole mass).
        let short = if absolute { "ug" } else { "share" };
        let densities: Vec<String> =
            first_seen(self.bins.iter().map(|b| b.density)).iter().map(|&d| shown(d)).collect();
        outln!(
            o,
            "Size distribution: {} bins (density {} kg/m^3), each run at its geometric midpoint; mass ({unit}), {:.3e} \
             beyond the bins' range left out:",
            self.bins.len(),
            densities.join(", "),
            self.outside_bins * k
        );
        let cell = |p: &Part| match p.quadrature {
            Some(q) => format!("{:.3e} +- {:.1e} ({:.1e})", p.value * k, p.error * k, q * k),
            None => format!("{:.3e} +- {:.1e} (?)", p.value * k, p.error * k),
        };
        let furnished = |text: String| if self.furnished { format!("  {text:>28}") } else { String::new() };
        outln!(
            o,
            "{:>6}  {:>16}  {:>28}  {:>28}  {:>28}{}  {:>28}  {:>28}  {:>20}",
            "",
            format!("injected ({short})"),
            format!("floor ({short})"),
            format!("ceiling ({short})"),
            format!("walls ({short})"),
            furnished(format!("furnishings ({short})")),
            format!("airborne, end ({short})"),
            format!("exhausted ({short})"),
            "beta of mass (1/h)"
        );
        for (name, s) in self.classes() {
            outln!(
                o,
                "{name:>6}  {:>16.3e}  {:>28}  {:>28}  {:>28}{}  {:>28}  {:>28}  {:>20}",
                s.injected * k,
                cell(&s.floor),
                cell(&s.ceiling),
                cell(&s.walls),
                furnished(cell(&s.furnishings)),
                cell(&s.airborne),
                cell(&s.exhausted),
                s.beta_per_hour.as_ref().map_or("none measured".to_string(), beta_cell)
            );
        }
        let partial: Vec<String> = self
            .classes()
            .iter()
            .filter(|(_, s)| s.beta_mass_share < 1.0)
            .map(|(name, s)| format!("{name} {:.1} %", 100.0 * s.beta_mass_share))
            .collect();
        if !partial.is_empty() {
            outln!(
                o,
                "beta of mass over part of the mass only ({}): the rest is in bins whose particles all settled before the averaging window, with no beta to measure.",
                partial.join(", ")
            );
        }
        let unseen: Vec<String> = [
            ("floor", &self.all.floor),
            ("ceiling", &self.all.ceiling),
            ("walls", &self.all.walls),
            ("airborne", &self.all.airborne),
            ("exhausted", &self.all.exhausted),
        ]
        .into_iter()
        .filter(|(_, p)| p.unseen_bound > 0.0)
        .map(|(name, p)| format!("{name} < {:.1e}", p.unseen_bound * k))
        .collect();
        if !unseen.is_empty() {
            outln!(
                o,
                "Bins whose run had no particle in a fate count 0 there; by the rule of three (95 %) they hold at most: {}.",
                unseen.join(", ")
            );
        }
        // One legend line; room --help and docs/commands.md say more.
        outln!(
            o,
            "+- 1 s.e.; (x) bound on the error of one run per bin (? no neighbour); PM2.5, PM10: aerodynamic \
             diameter below 2.5, 10 um; beta of mass: its deposition loss rate; room --help says more."
        );
    }
}

/// The steady `C_in/C_out` from the release's `beta`: `value +- error`; where `beta` rests on
/// no deposit, the range it spans ([`Row::indoor_outdoor_range`]), `low-high [0]`, never a
/// `1.000 +- 0.000` that reads as measured.
fn indoor_outdoor_cell(r: &Row, m: &Measured, study: &RoomStudy) -> String {
    match r.indoor_outdoor_range(study) {
        None => figure_cell(m),
        Some((low, high)) => format!("{low:.3}-{high:.3} [0]"),
    }
}

/// `beta` over Lai & Nazaroff's `model` to two decimals; with no deposit event, its 95 %
/// upper bound's ratio, `< 3.94`, never a ratio of 0.
fn ratio_cell(beta: &Measured, model: f64) -> String {
    match beta.upper_bound {
        Some(bound) => format!("< {:.2}", bound / model),
        None => format!("{:.2}", beta.value / model),
    }
}

/// A rate per hour: with deposit events `value +- error` (fixed-point from 0.1/h), without
/// its 95 % upper bound.
fn beta_cell(m: &Measured) -> String {
    match m.upper_bound {
        Some(bound) => format!("< {bound:.2e} [0]"),
        None if m.value.abs() >= 0.1 => format!("{:.3} +- {:.3}", m.value, m.error),
        None => format!("{:.2e} +- {:.1e}", m.value, m.error),
    }
}
