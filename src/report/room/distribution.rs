//! A room study with a size distribution: where its mass went (per surface, exhausted,
//! airborne), for all of it and for PM2.5 and PM10. The table, CSV and figures render it beside
//! the per-size ones.

use depo_tracker::distribution::{MassBalance, MassSplit, Portion};
use serde::Serialize;

use crate::report::Measured;

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

    pub(super) fn classes(&self) -> [(&'static str, &Split); 3] {
        [("all", &self.all), ("PM10", &self.pm10), ("PM2.5", &self.pm2_5)]
    }
}
