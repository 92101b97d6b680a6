//! depo beside measured rooms: the tables and figures of docs/validation.md, "Measured
//! rooms", from the JSON of five `depo room` runs of the example scenes.
//!
//! ```sh
//! for s in thatcher2002-bare-slow thatcher2002-bare-fast thatcher2002-furnished-slow \
//!          thatcher2002-furnished-fast lai2005-chamber; do
//!     target/release/depo room examples/$s.toml --format json --no-plot > $s.json
//! done
//! target/release/examples/measured_rooms thatcher2002-bare-slow.json thatcher2002-bare-fast.json \
//!     thatcher2002-furnished-slow.json thatcher2002-furnished-fast.json lai2005-chamber.json \
//!     docs/figures
//! ```
//!
//! It prints the tables as Markdown and writes `measured-thatcher2002.svg`,
//! `measured-thatcher2002-furnished.svg` and `measured-lai2005.svg` into the directory. What
//! is measured comes from the papers' abstracts, cited where it is used; nothing here is
//! fitted.

use std::path::{Path, PathBuf};

use depo::tracker::correlations::LaiNazaroff;
use depo::tracker::Air;
use serde_json::Value;

// The command's own chart code, so that these figures look like `depo room`'s.
use depo::plot::{self, Series};
type Error = String;

/// Thatcher et al. (2002), abstract: raising the mean air speed "from <5 to 19 cm/s ...
/// increased the deposition rate for all particle sizes studied by factors ranging from 1.3 to
/// 2.4 with larger particles exhibiting greater effects than smaller particles".
const THATCHER_RATIO: (f64, f64) = (1.3, 2.4);
/// Thatcher et al. (2002), abstract: "Increasing the surface area from bare (35 m2 nominal
/// surface area) to fully furnished (12 m2 additional surface area) increased the deposition
/// loss rate by as much as a factor of 2.6 with the largest increase seen for the smallest
/// particles".
const THATCHER_FURNISHED_MOST: f64 = 2.6;
/// The sizes they measured, um.
const THATCHER_SIZES: (f64, f64) = (0.5, 10.0);
/// Unit-density spheres, as the scenes have them.
const DENSITY: f64 = 1000.0;
const GRAVITY: f64 = 9.80665;

/// One size of a `depo room --format json` report.
struct Size {
    d_um: f64,
    beta: (f64, f64),
    walls: (f64, f64),
    walls_bound: Option<f64>,
    walls_events: u64,
}

struct Report {
    side: f64,
    u_star: f64,
    /// Walls and furnishings' faces over the air's volume, 1/m.
    surface_to_volume: f64,
    sizes: Vec<Size>,
}

fn read(path: &Path) -> Result<Report, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let json: Value = serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
    let num = |v: &Value, what: &str| v.as_f64().ok_or(format!("{}: no number at {what}", path.display()));
    let size: Vec<f64> = json["size_m"].as_array().ok_or("no size_m")?.iter().filter_map(Value::as_f64).collect();
    if size.len() != 3 || size.iter().any(|&s| (s / size[0] - 1.0).abs() > 1e-9) {
        return Err(format!("{}: the measured rooms are cubes, not {size:?}", path.display()));
    }
    let mut sizes = Vec::new();
    for s in json["sizes"].as_array().ok_or("no sizes")? {
        sizes.push(Size {
            d_um: num(&s["diameter_um"], "diameter_um")?,
            beta: (num(&s["beta_per_hour"]["value"], "beta")?, num(&s["beta_per_hour"]["error"], "beta error")?),
            walls: (num(&s["walls"]["value"], "walls")?, num(&s["walls"]["error"], "walls error")?),
            walls_bound: s["walls"]["upper_bound"].as_f64(),
            walls_events: s["walls"]["events"].as_u64().unwrap_or(0),
        });
    }
    Ok(Report {
        side: size[0],
        u_star: num(&json["friction_velocity"], "friction_velocity")?,
        surface_to_volume: num(&json["surface_to_volume_per_m"], "surface_to_volume_per_m")?,
        sizes,
    })
}

/// Lai & Nazaroff (2000) for a cube of side `side` (m): `beta` in 1/h and the wall's `v_d`.
fn model(d_um: f64, side: f64, u_star: f64) -> (f64, f64) {
    let m = LaiNazaroff::new(d_um * 1e-6, DENSITY, &Air::standard(), GRAVITY, u_star);
    // Floor and ceiling each A / V = 1 / side, the four walls 4 / side.
    ((m.floor + m.ceiling + 4.0 * m.wall) / side * 3600.0, m.wall)
}

/// Hussein et al. (2012) onto a vertical wall with friction velocity `u_star` (m/s): the
/// deposition velocity, m/s, of a correlation with turbophoresis (`correlations::hussein`).
fn hussein_wall(d_um: f64, u_star: f64) -> f64 {
    use depo::tracker::geometry::Orientation;
    use depo::tracker::wall_function::{deposition_velocity, Correlation};
    let air = Air::standard();
    let aero = depo::tracker::Aerodynamics::new(d_um * 1e-6, DENSITY, &air, GRAVITY);
    deposition_velocity(Correlation::Hussein, &aero, &air, u_star, Orientation::Wall)
}

/// Cunningham-corrected Stokes settling over the cube's height, 1/h: the loss rate settling
/// alone gives a well-mixed room.
fn settling_beta(d_um: f64, side: f64) -> f64 {
    depo::tracker::Aerodynamics::new(d_um * 1e-6, DENSITY, &Air::standard(), GRAVITY).settling_speed / side * 3600.0
}

/// `beta` of `top` over `beta` of `bottom`, and its standard error. The runs are separate
/// scenes; their errors are combined as independent.
fn beta_ratio(top: &Size, bottom: &Size) -> (f64, f64) {
    let r = top.beta.0 / bottom.beta.0;
    (r, r * ((top.beta.1 / top.beta.0).powi(2) + (bottom.beta.1 / bottom.beta.0).powi(2)).sqrt())
}

fn log_grid(from: f64, to: f64, n: usize) -> Vec<f64> {
    (0..n).map(|i| from * (to / from).powf(i as f64 / (n - 1) as f64)).collect()
}

fn main() -> Result<(), Error> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [slow, fast, furnished_slow, furnished_fast, chamber, out] = args.as_slice() else {
        return Err("usage: measured_rooms SLOW.json FAST.json FURNISHED_SLOW.json FURNISHED_FAST.json \
                    CHAMBER.json OUT_DIR"
            .into());
    };
    let (slow, fast, chamber) = (read(Path::new(slow))?, read(Path::new(fast))?, read(Path::new(chamber))?);
    let furnished = [read(Path::new(furnished_slow))?, read(Path::new(furnished_fast))?];
    let out = PathBuf::from(out);
    std::fs::create_dir_all(&out).map_err(|e| format!("cannot create {}: {e}", out.display()))?;

    // Thatcher et al. (2002): beta at both air speeds and their ratio.
    println!(
        "Thatcher et al. (2002) bare room, cube of {:.4} m; u* = {} m/s (< 5 cm/s) and {} m/s (19 cm/s)\n",
        slow.side, slow.u_star, fast.u_star
    );
    println!("| d (um) | settling alone (1/h) | beta, < 5 cm/s (1/h) | beta, 19 cm/s (1/h) | ratio depo | ratio Lai & Nazaroff (2000) | ratio measured |");
    println!("|---:|---:|---:|---:|---:|---:|---:|");
    let mut ratio = Vec::new();
    for (s, f) in slow.sizes.iter().zip(&fast.sizes) {
        if s.d_um != f.d_um {
            return Err(format!("the two Thatcher runs differ in size: {} and {} um", s.d_um, f.d_um));
        }
        let (r, e) = beta_ratio(f, s);
        let model_ratio = model(s.d_um, fast.side, fast.u_star).0 / model(s.d_um, slow.side, slow.u_star).0;
        println!(
            "| {} | {:.3} | {:.3} +- {:.3} | {:.3} +- {:.3} | {:.2} +- {:.2} | {:.2} | {}-{} (all sizes) |",
            (s.d_um * 1e3).round() / 1e3,
            settling_beta(s.d_um, slow.side),
            s.beta.0,
            s.beta.1,
            f.beta.0,
            f.beta.1,
            r,
            e,
            model_ratio,
            THATCHER_RATIO.0,
            THATCHER_RATIO.1
        );
        ratio.push((s.d_um, r, e));
    }
    let grid = log_grid(THATCHER_SIZES.0, THATCHER_SIZES.1, 100);
    let band = |v: f64| vec![(THATCHER_SIZES.0, v), (THATCHER_SIZES.1, v)];
    let series = vec![
        Series::markers("depo (+- 1 s.e.)", ratio.iter().map(|r| (r.0, r.1)).collect())
            .with_errors(ratio.iter().map(|r| r.2).collect())
            .color(0),
        Series::line(
            "Lai & Nazaroff (2000) model",
            grid.iter()
                .map(|&d| (d, model(d, fast.side, fast.u_star).0 / model(d, slow.side, slow.u_star).0))
                .collect(),
        )
        .color(0),
        Series::line("measured, least: 1.3 (Thatcher et al. 2002; per size not in the abstract)", band(1.3))
            .dashed()
            .color(1),
        Series::line("measured, most: 2.4 (larger particles more)", band(2.4)).dashed().color(1),
    ];
    plot::lines(
        &out.join("measured-thatcher2002.svg"),
        "Bare room, 14.2 m3: beta at 19 cm/s over beta at < 5 cm/s",
        "aerodynamic diameter (um)",
        "loss-rate ratio, fast / slow air",
        &series,
        true,
    )?;

    // Thatcher et al. (2002): beta furnished over beta bare, at both air speeds: each
    // furnished run must be its bare twin's room and air, with one set of furniture.
    for (bare, room) in [(&slow, &furnished[0]), (&fast, &furnished[1])] {
        if room.side != bare.side || room.u_star != bare.u_star || room.sizes.len() != bare.sizes.len() {
            return Err("a furnished run is not its bare twin's room, air speed and sizes (order: slow, fast)".into());
        }
    }
    if slow.sizes.len() != fast.sizes.len() || furnished[0].surface_to_volume != furnished[1].surface_to_volume {
        return Err("the slow and fast runs differ in their sizes or their furniture".into());
    }
    let same_velocity = furnished[0].surface_to_volume / slow.surface_to_volume;
    println!(
        "\nThatcher et al. (2002) room fully furnished: {:.3} 1/m of surface per volume of air against {:.3} \
         bare\n",
        furnished[0].surface_to_volume, slow.surface_to_volume
    );
    println!("| d (um) | beta furnished, < 5 cm/s (1/h) | gain, < 5 cm/s | beta furnished, 19 cm/s (1/h) | gain, 19 cm/s | measured |");
    println!("|---:|---:|---:|---:|---:|---|");
    let mut gains = [Vec::new(), Vec::new()];
    for (k, s) in slow.sizes.iter().enumerate() {
        let mut row = format!("| {} |", (s.d_um * 1e3).round() / 1e3);
        for (speed, (bare, room)) in [(&slow, &furnished[0]), (&fast, &furnished[1])].into_iter().enumerate() {
            let (b, f) = (&bare.sizes[k], &room.sizes[k]);
            if b.d_um != f.d_um {
                return Err(format!("the bare and furnished runs differ in size: {} and {} um", b.d_um, f.d_um));
            }
            let (r, e) = beta_ratio(f, b);
            row += &format!(" {:.3} +- {:.3} | {:.2} +- {:.2} |", f.beta.0, f.beta.1, r, e);
            gains[speed].push((s.d_um, r, e));
        }
        println!("{row} up to {THATCHER_FURNISHED_MOST}, most for the smallest |");
    }
    let [slow_gains, fast_gains] = gains;
    let series = vec![
        Series::markers("depo, < 5 cm/s (+- 1 s.e.)", slow_gains.iter().map(|r| (r.0, r.1)).collect())
            .with_errors(slow_gains.iter().map(|r| r.2).collect())
            .color(0),
        Series::markers("depo, 19 cm/s (+- 1 s.e.)", fast_gains.iter().map(|r| (r.0, r.1)).collect())
            .with_errors(fast_gains.iter().map(|r| r.2).collect())
            .color(2),
        Series::line(
            format!("every surface at one deposition velocity: {same_velocity:.2} (surface per volume)"),
            band(same_velocity),
        )
        .color(4),
        Series::line(
            "measured, most: 2.6, smallest particles (Thatcher et al. 2002; per size not in the abstract)",
            band(THATCHER_FURNISHED_MOST),
        )
        .dashed()
        .color(1),
    ];
    plot::lines(
        &out.join("measured-thatcher2002-furnished.svg"),
        "14.2 m3 room: beta fully furnished (12 m2 more surface) over beta bare",
        "aerodynamic diameter (um)",
        "loss-rate ratio, furnished / bare",
        &series,
        true,
    )?;

    // Lai & Nazaroff (2005): deposition onto the vertical walls.
    println!("\nLai & Nazaroff (2005) chamber, cube of {:.4} m; u* = {} m/s\n", chamber.side, chamber.u_star);
    println!(
        "| d (um) | walls, depo (m/s) | walls, Lai & Nazaroff (2000) (m/s) | walls, Hussein et al. (2012) (m/s) | measured |"
    );
    println!("|---:|---:|---:|---:|---|");
    for s in &chamber.sizes {
        let depo = match s.walls_bound {
            Some(b) => format!("< {b:.1e} [0]"),
            None => format!("{:.2e} +- {:.1e} [{}]", s.walls.0, s.walls.1, s.walls_events),
        };
        println!(
            "| {} | {depo} | {:.2e} | {:.2e} | rising with size; values not in the abstract |",
            (s.d_um * 1e3).round() / 1e3,
            model(s.d_um, chamber.side, chamber.u_star).1,
            hussein_wall(s.d_um, chamber.u_star)
        );
    }
    // The chamber's u* is not in the abstract: both models' walls at other friction velocities.
    println!("\nWalls at other friction velocities (the chamber's is not in the abstract): Hussein et al. (2012), m/s, and over Lai & Nazaroff (2000)\n");
    println!(
        "| u* (m/s) | {} |",
        chamber.sizes.iter().map(|s| format!("{} um", (s.d_um * 1e3).round() / 1e3)).collect::<Vec<_>>().join(" | ")
    );
    println!("|---:|{}", "---:|".repeat(chamber.sizes.len()));
    for u_star in [0.01, 0.03, 0.1, 0.2, 0.3] {
        let cells: Vec<String> = chamber
            .sizes
            .iter()
            .map(|s| {
                let h = hussein_wall(s.d_um, u_star);
                format!("{h:.2e} ({:.2})", h / model(s.d_um, chamber.side, u_star).1)
            })
            .collect();
        println!("| {u_star} | {} |", cells.join(" | "));
    }
    let hit: Vec<&Size> = chamber.sizes.iter().filter(|s| s.walls_bound.is_none()).collect();
    let bounds: Vec<(f64, f64)> = chamber.sizes.iter().filter_map(|s| s.walls_bound.map(|b| (s.d_um, b))).collect();
    let (lo, hi) = (chamber.sizes[0].d_um, chamber.sizes[chamber.sizes.len() - 1].d_um);
    let mut series =
        vec![Series::markers("walls, depo (+- 1 s.e.)", hit.iter().map(|s| (s.d_um, s.walls.0)).collect())
            .with_errors(hit.iter().map(|s| s.walls.1).collect())
            .color(0)];
    if !bounds.is_empty() {
        series.push(Series::upper_bounds("walls, depo: no deposit, 95 % upper bound", bounds).color(0));
    }
    series.push(
        Series::line(
            "walls, Lai & Nazaroff (2000) model",
            log_grid(lo, hi, 100).into_iter().map(|d| (d, model(d, chamber.side, chamber.u_star).1)).collect(),
        )
        .color(0),
    );
    series.push(
        Series::line(
            "walls, Hussein et al. (2012) model (turbophoresis)",
            log_grid(lo, hi, 100).into_iter().map(|d| (d, hussein_wall(d, chamber.u_star))).collect(),
        )
        .color(2)
        .dashed(),
    );
    series.push(
        Series::markers("measured (Lai & Nazaroff 2005): rising with size; values not in the abstract", vec![])
            .color(1),
    );
    plot::log_log(
        &out.join("measured-lai2005.svg"),
        "1.8 m3 chamber: deposition onto vertical walls",
        "particle diameter (um)",
        "deposition velocity (m/s)",
        &series,
    )?;
    Ok(())
}
