//! `depo room` with a size distribution: where its mass went (per surface, exhausted,
//! airborne), for all of it and for PM2.5 and PM10, as a table, CSV, JSON and a figure.

use std::path::Path;

use depo::tracker::distribution::{first_seen, MassBalance, MassSplit, Portion};
use serde::Serialize;

use super::plot::{self, Series};
use super::room::Measured;
use super::{print_csv, Error};

/// What a figure reads off a class's split: a value and its standard error.
type Pick<'a> = &'a dyn Fn(&Split) -> (f64, f64);

/// A part of the mass: the value, its standard error over the runs' randomness, and the bound
/// on the quadrature's error (`null` where a bin with mass has no neighbour to bound it).
#[derive(Serialize)]
pub struct Part {
    pub value: f64,
    pub error: f64,
    pub quadrature: Option<f64>,
    /// What the bins whose run saw no particle in this fate (counted 0) may hold: the rule of
    /// three's 95 % bound, summed (0 when every run saw it).
    pub unseen_bound: f64,
}

/// Where one class of the mass went, in [`DistributionReport::mass_unit`].
#[derive(Serialize)]
pub struct Split {
    pub injected: f64,
    pub floor: Part,
    pub ceiling: Part,
    pub walls: Part,
    /// On the furnishings' faces (zero in a bare room).
    pub furnishings: Part,
    pub airborne: Part,
    pub exhausted: Part,
    pub escaped: Part,
    /// The deposition loss rate of the mass while its size distribution is the injected
    /// one, at least (the bins without a beta are the fastest-settling ones)... (`null` when
    /// no bin's run measured one)
    pub beta_per_hour: Option<Measured>,
    /// ... over this share of the mass (the bins whose runs measured a beta).
    pub beta_mass_share: f64,
}

/// One bin: its range, its run's diameter, its number and mass, and the shares of its run's
/// particles in each fate.
#[derive(Serialize)]
pub struct BinRow {
    pub lower_um: f64,
    pub upper_um: f64,
    pub diameter_um: f64,
    pub density: f64,
    pub number: f64,
    pub mass: f64,
    pub pm2_5_mass: f64,
    pub pm10_mass: f64,
    pub particles: usize,
    pub floor: f64,
    pub ceiling: f64,
    pub walls: f64,
    pub furnishings: f64,
    pub airborne: f64,
    pub exhausted: f64,
}

/// The distribution's answers.
#[derive(Serialize)]
pub struct DistributionReport {
    /// "kg" (in the room: concentrations times its volume) or "share of the distribution's
    /// mass" (of the modes' whole mass, in the bins and outside them).
    pub mass_unit: MassUnit,
    /// Mass of the modes beyond the bins' range, left out of the splits.
    pub outside_bins: f64,
    pub all: Split,
    pub pm10: Split,
    pub pm2_5: Split,
    pub bins: Vec<BinRow>,
    /// How PM2.5 and PM10 are cut.
    pub pm_definition: &'static str,
    /// Whether the room has furnishings (the tables and CSV then show their part).
    #[serde(skip)]
    pub furnished: bool,
    /// Whether the room is ventilated (the figure then shows what was exhausted, zero or not).
    #[serde(skip)]
    pub ventilated: bool,
}

/// What the masses are in.
#[derive(Clone, Copy, PartialEq, Eq, Serialize)]
pub enum MassUnit {
    /// kg in the room: the modes' concentrations times its volume.
    #[serde(rename = "kg")]
    Kg,
    /// Shares of the distribution's whole mass (in the bins and beyond them).
    #[serde(rename = "share of the distribution's mass")]
    Share,
}

/// How PM2.5 and PM10 are cut, for the outputs.
pub const PM_DEFINITION: &str = "PM2.5 and PM10: mass of particles of aerodynamic diameter (unit density, with slip \
correction) below 2.5 and 10 um, a sharp cut at the 50 % points of the standards' inlets (EN 12341:2014, ISO 7708)";

impl DistributionReport {
    /// The report of `balance` in a room whose air fills `volume` (m^3), `furnished` and
    /// `ventilated` or not.
    pub fn new(balance: &MassBalance, volume: f64, (furnished, ventilated): (bool, bool)) -> Self {
        // Masses in kg in the room, or as shares of the distribution's mass: in the bins and
        // beyond them (shares of the bins' mass alone would make the mass beyond them any
        // multiple of it).
        let total = balance.all.injected + balance.outside;
        let scale = if balance.absolute { volume } else { 1.0 / total.max(f64::MIN_POSITIVE) };
        let part = |p: Portion| Part {
            value: p.value * scale,
            error: p.error * scale,
            quadrature: p.quadrature.is_finite().then_some(p.quadrature * scale),
            unseen_bound: p.unseen_bound * scale,
        };
        let split = |s: &MassSplit| Split {
            injected: s.injected * scale,
            floor: part(s.deposited[0]),
            ceiling: part(s.deposited[1]),
            walls: part(s.deposited[2]),
            furnishings: part(s.furnishings),
            airborne: part(s.airborne),
            exhausted: part(s.exhausted),
            escaped: part(s.escaped),
            beta_per_hour: s.beta.map(|b| Measured::from(b).scaled(3600.0)),
            beta_mass_share: s.beta_share,
        };
        // Numbers per room, or as shares of the number in the bins.
        let total_number: f64 = balance.bins.iter().map(|(b, _)| b.number).sum();
        let number_scale = if balance.absolute { volume } else { 1.0 / total_number.max(f64::MIN_POSITIVE) };
        let bins = balance
            .bins
            .iter()
            .map(|(b, f)| {
                let share = |k: usize| k as f64 / f.particles.max(1) as f64;
                BinRow {
                    lower_um: b.lower * 1e6,
                    upper_um: b.upper * 1e6,
                    diameter_um: b.diameter * 1e6,
                    density: b.density,
                    number: b.number * number_scale,
                    mass: b.mass * scale,
                    pm2_5_mass: b.pm_mass[0] * scale,
                    pm10_mass: b.pm_mass[1] * scale,
                    particles: f.particles,
                    floor: share(f.deposited[0]),
                    ceiling: share(f.deposited[1]),
                    walls: share(f.deposited[2]),
                    furnishings: share(f.furnishings),
                    airborne: share(f.airborne),
                    exhausted: share(f.exhausted),
                }
            })
            .collect();
        Self {
            mass_unit: if balance.absolute { MassUnit::Kg } else { MassUnit::Share },
            outside_bins: balance.outside * scale,
            all: split(&balance.all),
            pm10: split(&balance.pm[1]),
            pm2_5: split(&balance.pm[0]),
            bins,
            pm_definition: PM_DEFINITION,
            furnished,
            ventilated,
        }
    }

    fn classes(&self) -> [(&'static str, &Split); 3] {
        [("all", &self.all), ("PM10", &self.pm10), ("PM2.5", &self.pm2_5)]
    }

    /// The table under the per-size one.
    pub fn table(&self) {
        let absolute = self.mass_unit == MassUnit::Kg;
        // Micrograms read better than kilograms.
        let k = if absolute { 1e9 } else { 1.0 };
        let unit = if absolute { "ug in the room" } else { "share of the distribution's mass" };
        let densities: Vec<String> =
            first_seen(self.bins.iter().map(|b| b.density)).iter().map(f64::to_string).collect();
        out!(
            "Size distribution: {} bins (density {} kg/m^3), each run at its geometric midpoint; mass ({unit}):",
            self.bins.len(),
            densities.join(", ")
        );
        let cell = |p: &Part| match p.quadrature {
            Some(q) => format!("{:.3e} +- {:.1e} ({:.1e})", p.value * k, p.error * k, q * k),
            None => format!("{:.3e} +- {:.1e} (?)", p.value * k, p.error * k),
        };
        let furnished = |text: String| if self.furnished { format!("  {text:>28}") } else { String::new() };
        out!(
            "{:>6}  {:>10}  {:>28}  {:>28}  {:>28}{}  {:>28}  {:>28}  {:>20}",
            "",
            "injected",
            "floor",
            "ceiling",
            "walls",
            furnished("furnishings".into()),
            "airborne (end)",
            "exhausted",
            "beta of mass (1/h)"
        );
        for (name, s) in self.classes() {
            out!(
                "{name:>6}  {:>10.3e}  {:>28}  {:>28}  {:>28}{}  {:>28}  {:>28}  {:>20}",
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
            out!(
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
            out!(
                "Bins whose run had no particle in a fate count 0 there; by the rule of three (95 %) they hold at most: {}.",
                unseen.join(", ")
            );
        }
        out!(
            "+- one standard error over the runs' randomness; (x) a bound on the error of taking each bin's fate from \
             one run at its midpoint, where each share is monotonic in d (?: a bin without neighbours). Mass of the modes beyond the bins' range, left out: {:.3e}. {PM_DEFINITION}. \
             beta of mass: the loss rate of the airborne mass by deposition (not ventilation) while its size \
             distribution is the injected one; over part of the mass, a lower bound on the whole's.",
            self.outside_bins * k
        );
    }

    /// The CSV: one row per class (all, PM10, PM2.5).
    pub fn csv(&self) -> Result<(), Error> {
        // A furnished room's CSV has the furnishings' columns after the walls'.
        let mut parts = vec!["floor", "ceiling", "walls"];
        if self.furnished {
            parts.push("furnishings");
        }
        parts.extend(["airborne", "exhausted"]);
        let mut header = vec!["class".to_string(), "injected".to_string()];
        for p in parts {
            header.extend([
                p.to_string(),
                format!("{p}_error"),
                format!("{p}_quadrature"),
                format!("{p}_unseen_bound"),
            ]);
        }
        header.extend(["beta_per_hour".to_string(), "beta_error".to_string(), "beta_mass_share".to_string()]);
        let header: Vec<&str> = header.iter().map(String::as_str).collect();
        print_csv(
            &header,
            self.classes().into_iter().map(|(name, s)| {
                let mut row = vec![name.to_string(), s.injected.to_string()];
                let mut parts = vec![&s.floor, &s.ceiling, &s.walls];
                if self.furnished {
                    parts.push(&s.furnishings);
                }
                parts.extend([&s.airborne, &s.exhausted]);
                for p in parts {
                    row.extend([
                        p.value.to_string(),
                        p.error.to_string(),
                        p.quadrature.map_or(String::new(), |q| q.to_string()),
                        p.unseen_bound.to_string(),
                    ]);
                }
                let beta = s
                    .beta_per_hour
                    .as_ref()
                    .map_or([String::new(), String::new()], |b| [b.value.to_string(), b.error.to_string()]);
                row.extend(beta);
                row.push(s.beta_mass_share.to_string());
                row
            }),
        )
    }

    /// The PM figure: for all the mass, PM10 and PM2.5, the share of each one's injected mass
    /// on the floor, on the ceiling and walls (their errors combined as if independent, which
    /// can only overstate the sum's), on the furnishings (if any), airborne and, with
    /// ventilation, exhausted at the end, with their standard errors. A class with no mass
    /// injected is left out, and the title says so.
    pub fn plot_pm(&self, path: &Path) -> Result<(), Error> {
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
        plot::bars(path, &title, "share of the class's mass", &groups, &series)
    }

    /// The figure: per bin, the mass per unit `ln d` injected and where it went, against the
    /// bin's diameter; one set of curves per density (the first solid, the others dashed).
    pub fn plot(&self, path: &Path) -> Result<(), Error> {
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
        plot::log_log(path, "Where a size distribution's mass goes", "particle diameter (um)", y, &series)
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
