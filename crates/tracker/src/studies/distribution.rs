//! One subject, hence one file over 700 lines: size distributions (modes, classes, bins, PM cuts).
//!
//! Particle size distributions as aerosol science states them, and what a room does to their
//! mass: deposited per surface, exhausted and still airborne, for all of it and for PM2.5 and
//! PM10.
//!
//! A distribution is one or more lognormal modes (each given by its count or mass median
//! diameter, geometric standard deviation, particle density and a share or concentration of
//! number or mass), or a list of size classes (diameter bins with the number or mass in each,
//! as measured size distributions come).
//!
//! ## PM2.5 and PM10
//! PM2.5 and PM10 are the mass of particles of aerodynamic diameter below 2.5 um and 10 um.
//! The standards define them by size-selective inlets of 50 % efficiency at those aerodynamic
//! diameters (EU Directive 2008/50/EC, Art. 2, with the reference method of EN 12341:2014,
//! which replaced EN 12341:1998 for PM10 and EN 14907:2005 for PM2.5; the conventions of ISO
//! 7708:1995); depo takes the idealised sharp cut at the 50 % point: all particles below,
//! none above. A particle's aerodynamic diameter (Hinds 1999, Sec. 3.6; a sphere) is the diameter of the unit-density sphere (1000 kg/m^3) that settles
//! as fast, with the slip correction of each: `d_a^2 Cc(d_a) 1000 = d^2 Cc(d) rho_p`
//! ([`aerodynamic_diameter`]). The cut falls within a bin; the bin's mass below it is
//! integrated exactly and shares the bin's fate.
//!
//! References: Hinds, *Aerosol Technology* (2nd ed., 1999), Sec. 4.4-4.5 (lognormal
//! distribution, the Hatch-Choate equations, the diameters of average) and Sec. 3.6
//! (aerodynamic diameter).

use std::f64::consts::{PI, SQRT_2};

use crate::model::air::{slip_correction, Air};
use crate::model::error::SceneError;

/// The PM2.5 and PM10 cuts, aerodynamic diameter, m.
pub const PM_CUTS: [f64; 2] = [2.5e-6, 10e-6];

/// The density that defines the aerodynamic diameter, kg/m^3.
pub const UNIT_DENSITY: f64 = 1000.0;

/// Bins per density unless given (the modes of one density share them).
pub const DEFAULT_BINS: usize = 12;

/// A bin holding no more than this share of its density's number and of its mass is not run.
pub const NEGLIGIBLE: f64 = 1e-9;

/// The largest geometric standard deviation a mode may have. Measured aerosol modes stay
/// well below (2 to 3 is broad); at 30, `sigma_g^3` takes the bins to 3e11 m.
pub const MAX_GEOMETRIC_SD: f64 = 5.0;

/// The Hatch-Choate equation (Hinds 1999, Sec. 4.5): the median of the `q`-th moment
/// distribution of a lognormal count distribution with count median `count_median` and
/// geometric standard deviation `geometric_sd`, `d_q = CMD exp(q ln^2 sigma_g)` (`q = 2`: the
/// surface median; `q = 3`: the mass median, for particles of one density).
#[must_use]
pub fn hatch_choate(count_median: f64, geometric_sd: f64, q: f64) -> f64 {
    count_median * (q * geometric_sd.ln().powi(2)).exp()
}

/// Mass median diameter of a lognormal count distribution, `MMD = CMD exp(3 ln^2 sigma_g)`
/// (Hinds 1999, Sec. 4.5).
#[must_use]
pub fn mass_median(count_median: f64, geometric_sd: f64) -> f64 {
    hatch_choate(count_median, geometric_sd, 3.0)
}

/// Count median diameter of a lognormal distribution of mass median `mass_median`,
/// `CMD = MMD exp(-3 ln^2 sigma_g)`.
#[must_use]
pub fn count_median(mass_median: f64, geometric_sd: f64) -> f64 {
    hatch_choate(mass_median, geometric_sd, -3.0)
}

/// The diameter of average `p`-th power of a lognormal count distribution, `(mean d^p)^(1/p)
/// = CMD exp(p ln^2 sigma_g / 2)` (Hinds 1999, Sec. 4.5, the Hatch-Choate equation for the
/// diameter of average property; not the `q`-th moment median of [`hatch_choate`]): `p = 2`
/// the diameter of average surface, `p = 3` of average mass.
#[must_use]
pub fn average_diameter(count_median: f64, geometric_sd: f64, p: f64) -> f64 {
    count_median * (p / 2.0 * geometric_sd.ln().powi(2)).exp()
}

/// Mean mass of a particle of a lognormal count distribution, kg: `rho pi d_m^3 / 6` with the
/// diameter of average mass `d_m = CMD exp(1.5 ln^2 sigma_g)` ([`average_diameter`], `p = 3`).
#[must_use]
pub fn mean_particle_mass(count_median: f64, geometric_sd: f64, density: f64) -> f64 {
    density * PI / 6.0 * average_diameter(count_median, geometric_sd, 3.0).powi(3)
}

/// Share of a lognormal distribution of median `median` and geometric standard deviation
/// `geometric_sd` below `diameter`: `Phi(ln(d / median) / ln sigma_g)`, `Phi` the standard
/// normal distribution function (a step at the median for `sigma_g = 1`).
#[must_use]
pub fn lognormal_below(diameter: f64, median: f64, geometric_sd: f64) -> f64 {
    if diameter <= 0.0 {
        return 0.0;
    }
    let spread = geometric_sd.ln();
    if spread <= 0.0 {
        return if diameter < median { 0.0 } else { 1.0 };
    }
    0.5 * libm::erfc(-(diameter / median).ln() / (spread * SQRT_2))
}

/// The diameter of a sphere of density `to` (kg/m^3) that settles as fast in `air` as one of
/// `diameter` (m) and density `from`: the root of `x^2 Cc(x) to = d^2 Cc(d) from` (Stokes
/// settling with slip), by bisection in `ln x`.
fn equal_settling(diameter: f64, from: f64, to: f64, air: &Air) -> f64 {
    let lambda = air.mean_free_path();
    let target = diameter * diameter * slip_correction(diameter, lambda) * from;
    let (mut lo, mut hi) = (1e-12f64.ln(), 1.0f64.ln());
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        let x = mid.exp();
        if x * x * slip_correction(x, lambda) * to < target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    (0.5 * (lo + hi)).exp()
}

/// Aerodynamic diameter of a sphere of `diameter` (m) and `density` (kg/m^3) in `air` (Hinds
/// 1999, Sec. 3.6): `d_a` with `d_a^2 Cc(d_a) 1000 kg/m^3 = d^2 Cc(d) rho_p`.
#[must_use]
pub fn aerodynamic_diameter(diameter: f64, density: f64, air: &Air) -> f64 {
    equal_settling(diameter, density, UNIT_DENSITY, air)
}

/// The geometric diameter (m) of a sphere of `density` whose aerodynamic diameter in `air` is
/// `aerodynamic` (m): the inverse of [`aerodynamic_diameter`].
#[must_use]
pub fn diameter_of_aerodynamic(aerodynamic: f64, density: f64, air: &Air) -> f64 {
    equal_settling(aerodynamic, UNIT_DENSITY, density, air)
}

/// Which median a mode is given by.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Median {
    /// Count median diameter, m: the mode is a lognormal number distribution.
    Count(f64),
    /// Mass median diameter, m: the mode is a lognormal mass distribution.
    Mass(f64),
}

/// How much of a mode there is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Amount {
    /// A share of the distribution's number (the shares of all modes are scaled to sum to 1).
    NumberShare(f64),
    /// A share of the distribution's mass (scaled likewise).
    MassShare(f64),
    /// Number concentration, 1/m^3.
    NumberConcentration(f64),
    /// Mass concentration, kg/m^3.
    MassConcentration(f64),
}

impl Amount {
    fn value(self) -> f64 {
        match self {
            Self::NumberShare(v) | Self::MassShare(v) | Self::NumberConcentration(v) | Self::MassConcentration(v) => v,
        }
    }

    fn is_share(self) -> bool {
        matches!(self, Self::NumberShare(_) | Self::MassShare(_))
    }
}

/// One lognormal mode.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mode {
    /// Its count or mass median diameter.
    pub median: Median,
    /// Geometric standard deviation, from 1 to [`MAX_GEOMETRIC_SD`] (the same for number and
    /// mass).
    pub geometric_sd: f64,
    /// Particle density, kg/m^3.
    pub density: f64,
    /// Its share or concentration.
    pub amount: Amount,
}

impl Mode {
    /// Count median diameter, m (by [`count_median`] from a mass median).
    #[must_use]
    pub fn count_median(&self) -> f64 {
        match self.median {
            Median::Count(d) => d,
            Median::Mass(d) => count_median(d, self.geometric_sd),
        }
    }

    /// Mass median diameter, m (by [`mass_median`] from a count median).
    #[must_use]
    pub fn mass_median(&self) -> f64 {
        match self.median {
            Median::Count(d) => mass_median(d, self.geometric_sd),
            Median::Mass(d) => d,
        }
    }

    /// Checks the mode; the error's field is the mode's own key (`geometric_sd`).
    pub fn validate(&self) -> Result<(), SceneError> {
        let (key, median) = match self.median {
            Median::Count(d) => ("count_median", d),
            Median::Mass(d) => ("mass_median", d),
        };
        positive(key, median)?;
        if !((1.0..=MAX_GEOMETRIC_SD).contains(&self.geometric_sd)) {
            return Err(SceneError::new("geometric_sd", self.geometric_sd, "must be from 1 to 5"));
        }
        positive("density", self.density)?;
        let key = match self.amount {
            Amount::NumberShare(_) => "number_share",
            Amount::MassShare(_) => "mass_share",
            Amount::NumberConcentration(_) => "number_concentration",
            Amount::MassConcentration(_) => "mass_concentration",
        };
        let v = self.amount.value();
        if !(v.is_finite() && v >= 0.0) {
            return Err(SceneError::new(key, v, "must be finite and not negative"));
        }
        Ok(())
    }
}

/// What a size class's amount is of.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Quantity {
    /// Number concentration, 1/m^3.
    Number,
    /// Mass concentration, kg/m^3.
    Mass,
}

/// One size class of a measured distribution: its number or mass, spread uniformly in
/// `ln d` between its edges.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SizeClass {
    /// Lower edge, m.
    pub lower: f64,
    /// Upper edge, m.
    pub upper: f64,
    /// Number (1/m^3) or mass (kg/m^3) concentration in the class.
    pub amount: f64,
    /// What `amount` is.
    pub quantity: Quantity,
    /// Particle density, kg/m^3.
    pub density: f64,
}

impl SizeClass {
    /// Mass (per unit of the class's number or mass, as given) below `cut` and in all, for
    /// the class's amount spread uniformly in `ln d`: number `dN/dln d` constant gives mass
    /// `~ d^3`, integrated as `(b^3 - a^3) / 3`.
    fn mass_and_number(&self) -> (f64, f64) {
        let (a, b) = (self.lower, self.upper);
        let width = (b / a).ln();
        // Mean of d^3 over the class, number uniform in ln d.
        let mean_cube = if width > 0.0 { (b.powi(3) - a.powi(3)) / (3.0 * width) } else { a.powi(3) };
        let particle = self.density * PI / 6.0 * mean_cube;
        match self.quantity {
            Quantity::Number => (self.amount * particle, self.amount),
            // Mass uniform in ln d: number dN/dln d = dM/dln d / (rho pi d^3 / 6), mean of d^-3.
            Quantity::Mass => {
                let mean_inverse_cube =
                    if width > 0.0 { (a.powi(-3) - b.powi(-3)) / (3.0 * width) } else { a.powi(-3) };
                (self.amount, self.amount * mean_inverse_cube / (self.density * PI / 6.0))
            }
        }
    }

    /// The share of the class's mass below the diameter `cut` (m).
    fn mass_below(&self, cut: f64) -> f64 {
        let (a, b) = (self.lower, self.upper);
        if cut <= a {
            return 0.0;
        }
        if cut >= b {
            return 1.0;
        }
        match self.quantity {
            Quantity::Number => (cut.powi(3) - a.powi(3)) / (b.powi(3) - a.powi(3)),
            Quantity::Mass => (cut / a).ln() / (b / a).ln(),
        }
    }
}

/// A size distribution.
#[derive(Clone, Debug, PartialEq)]
pub enum Distribution {
    /// Lognormal modes, cut into `bins` bins in `ln d` per density over `range` (m; by
    /// default from the density's modes' smallest count median over `sigma_g^3` to their
    /// largest mass median times `sigma_g^3`).
    Modes { modes: Vec<Mode>, bins: usize, range: Option<[f64; 2]> },
    /// Measured size classes, each its own bin.
    Classes(Vec<SizeClass>),
}

/// One bin of a distribution: one run of the room study at `diameter`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bin {
    /// Lower edge, m.
    pub lower: f64,
    /// Upper edge, m.
    pub upper: f64,
    /// The diameter its run takes, `sqrt(lower upper)`, m.
    pub diameter: f64,
    /// Particle density, kg/m^3.
    pub density: f64,
    /// Number of particles in it (per m^3 with concentrations; a share of the number or mass
    /// units of the modes otherwise).
    pub number: f64,
    /// Their mass (kg/m^3 with concentrations).
    pub mass: f64,
    /// The mass of its particles of aerodynamic diameter below 2.5 um and 10 um ([`PM_CUTS`]).
    pub pm_mass: [f64; 2],
}

impl Distribution {
    /// Whether the amounts are concentrations (per m^3) rather than shares.
    #[must_use]
    pub fn is_absolute(&self) -> bool {
        match self {
            Self::Modes { modes, .. } => modes.iter().all(|m| !m.amount.is_share()),
            Self::Classes(_) => true,
        }
    }

    /// Checks the distribution; a mode's error names `modes[i].key`, a class's
    /// `size_bins[i].key`.
    pub fn validate(&self) -> Result<(), SceneError> {
        match self {
            Self::Modes { modes, bins, range } => {
                if modes.is_empty() {
                    return Err(SceneError::new("modes", 0.0, "must hold at least one mode"));
                }
                for (i, m) in modes.iter().enumerate() {
                    m.validate().map_err(|mut e| {
                        e.field = format!("modes[{i}].{}", e.field);
                        e
                    })?;
                }
                let shares = modes.iter().filter(|m| m.amount.is_share()).count();
                if shares != 0 && shares != modes.len() {
                    return Err(SceneError::new(
                        "modes",
                        shares as f64,
                        "modes with shares cannot mix with modes of absolute concentration",
                    ));
                }
                let numbers = modes.iter().filter(|m| matches!(m.amount, Amount::NumberShare(_))).count();
                if shares != 0 && numbers != 0 && numbers != shares {
                    return Err(SceneError::new(
                        "modes",
                        numbers as f64,
                        "shares must all be of number or all of mass",
                    ));
                }
                if modes.iter().map(|m| m.amount.value()).sum::<f64>() <= 0.0 {
                    return Err(SceneError::new("modes", 0.0, "must have some particles"));
                }
                if *bins == 0 {
                    return Err(SceneError::new("bins", 0.0, "must be at least 1"));
                }
                if let Some([lo, hi]) = range {
                    positive("bin_range", *lo)?;
                    if !(hi.is_finite() && hi > lo) {
                        return Err(SceneError::new("bin_range", *hi, "must be finite and above the lower edge"));
                    }
                }
            }
            Self::Classes(classes) => {
                if classes.is_empty() {
                    return Err(SceneError::new("size_bins", 0.0, "must hold at least one size class"));
                }
                for (i, c) in classes.iter().enumerate() {
                    let field = |k: &str| format!("size_bins[{i}].{k}");
                    let bad =
                        |k: &str, v: f64, r: &'static str| SceneError { field: field(k), value: v, requirement: r };
                    if !(c.lower.is_finite() && c.lower > 0.0) {
                        return Err(bad("lower", c.lower, "must be finite and positive"));
                    }
                    if !(c.upper.is_finite() && c.upper > c.lower) {
                        return Err(bad("upper", c.upper, "must be finite and above the lower edge"));
                    }
                    if !(c.amount.is_finite() && c.amount >= 0.0) {
                        return Err(bad("amount", c.amount, "must be finite and not negative"));
                    }
                    if !(c.density.is_finite() && c.density > 0.0) {
                        return Err(bad("density", c.density, "must be finite and positive"));
                    }
                    // Classes of one density must not overlap; another density's may.
                    let previous = classes[..i].iter().rev().find(|p| p.density == c.density);
                    if previous.is_some_and(|p| c.lower < p.upper * (1.0 - 1e-9)) {
                        return Err(bad(
                            "lower",
                            c.lower,
                            "must not be below the upper edge of the previous class of its density",
                        ));
                    }
                }
                if classes.iter().all(|c| c.amount == 0.0) {
                    return Err(SceneError::new("size_bins", 0.0, "must have some particles"));
                }
            }
        }
        Ok(())
    }

    /// The bins the study runs, grouped by density (in the order the densities first come)
    /// and by diameter within a density, with their number, mass and PM mass in `air`; and
    /// the mass outside them (the modes' tails beyond the range).
    pub fn bins(&self, air: &Air) -> Result<(Vec<Bin>, f64), SceneError> {
        self.validate()?;
        let cuts = |density: f64| PM_CUTS.map(|c| diameter_of_aerodynamic(c, density, air));
        match self {
            Self::Classes(classes) => {
                let densities = first_seen(classes.iter().map(|c| c.density));
                let mut bins = Vec::new();
                for &rho in &densities {
                    let cut = cuts(rho);
                    for c in classes.iter().filter(|c| c.density == rho) {
                        let (mass, number) = c.mass_and_number();
                        bins.push(Bin {
                            lower: c.lower,
                            upper: c.upper,
                            diameter: (c.lower * c.upper).sqrt(),
                            density: rho,
                            number,
                            mass,
                            pm_mass: cut.map(|d| mass * c.mass_below(d)),
                        });
                    }
                }
                Ok((bins, 0.0))
            }
            Self::Modes { modes, bins: count, range } => {
                // Totals per mode: number and mass, as concentrations or as shares.
                let share_total: f64 = modes.iter().filter(|m| m.amount.is_share()).map(|m| m.amount.value()).sum();
                let totals: Vec<(f64, f64)> = modes
                    .iter()
                    .map(|m| {
                        let particle = mean_particle_mass(m.count_median(), m.geometric_sd, m.density);
                        match m.amount {
                            Amount::NumberShare(s) => (s / share_total, s / share_total * particle),
                            Amount::MassShare(s) => (s / share_total / particle, s / share_total),
                            Amount::NumberConcentration(n) => (n, n * particle),
                            Amount::MassConcentration(c) => (c / particle, c),
                        }
                    })
                    .collect();
                let densities = first_seen(modes.iter().map(|m| m.density));
                // Each density's bins span its own modes, unless a range is given.
                let edges = |rho: f64| -> Vec<f64> {
                    let [lo, hi] = range.unwrap_or_else(|| {
                        let own = || modes.iter().filter(|m| m.density == rho);
                        let lo = own().map(|m| m.count_median() / m.geometric_sd.powi(3)).fold(f64::INFINITY, f64::min);
                        let hi = own().map(|m| m.mass_median() * m.geometric_sd.powi(3)).fold(0.0, f64::max);
                        // A monodisperse mode (sigma_g = 1) still needs a bin of some width.
                        if hi / lo < 1.0001 {
                            [lo / 1.0001, hi * 1.0001]
                        } else {
                            [lo, hi]
                        }
                    });
                    (0..=*count).map(|i| lo * (hi / lo).powf(i as f64 / *count as f64)).collect()
                };
                let mut bins = Vec::new();
                let mut inside = 0.0;
                for &rho in &densities {
                    let cut = cuts(rho);
                    // The density's number and mass, to tell the bins that hold none of them.
                    let own = modes.iter().zip(&totals).filter(|(m, _)| m.density == rho);
                    let (number_total, mass_total) = own.fold((0.0, 0.0), |(n, m), (_, t)| (n + t.0, m + t.1));
                    for w in edges(rho).windows(2) {
                        let (a, b) = (w[0], w[1]);
                        let mut bin = Bin {
                            lower: a,
                            upper: b,
                            diameter: (a * b).sqrt(),
                            density: rho,
                            number: 0.0,
                            mass: 0.0,
                            pm_mass: [0.0; 2],
                        };
                        for (m, &(number, mass)) in modes.iter().zip(&totals).filter(|(m, _)| m.density == rho) {
                            let (cmd, mmd, s) = (m.count_median(), m.mass_median(), m.geometric_sd);
                            bin.number += number * (lognormal_below(b, cmd, s) - lognormal_below(a, cmd, s));
                            let below = |d: f64| lognormal_below(d, mmd, s);
                            bin.mass += mass * (below(b) - below(a));
                            for (k, &c) in cut.iter().enumerate() {
                                bin.pm_mass[k] += mass * (below(b.min(c)) - below(a)).max(0.0);
                            }
                        }
                        // A bin with next to nothing in it is not run (sigma_g 1 puts all in
                        // one of them); its crumbs count as outside.
                        if bin.mass <= NEGLIGIBLE * mass_total && bin.number <= NEGLIGIBLE * number_total {
                            continue;
                        }
                        inside += bin.mass;
                        bins.push(bin);
                    }
                }
                let total: f64 = totals.iter().map(|t| t.1).sum();
                Ok((bins, (total - inside).max(0.0)))
            }
        }
    }
}

/// The distinct densities (or any values) of `values`, in the order they first come.
#[must_use]
pub fn first_seen(values: impl IntoIterator<Item = f64>) -> Vec<f64> {
    let mut seen: Vec<f64> = Vec::new();
    for v in values {
        if !seen.contains(&v) {
            seen.push(v);
        }
    }
    seen
}

fn positive(field: &str, v: f64) -> Result<(), SceneError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(SceneError::new(field, v, "must be finite and positive"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Hatch-Choate by hand: CMD 1 um, sigma_g 2, `ln^2 2 = 0.480453`: MMD `exp(1.441359)` =
    /// 4.226436 um, the diameter of average mass `exp(0.720680)` = 2.055830 um.
    #[test]
    fn hatch_choate_matches_hand_values() {
        let (cmd, s) = (1e-6, 2.0);
        assert!((mass_median(cmd, s) / 4.226436e-6 - 1.0).abs() < 1e-6, "{}", mass_median(cmd, s));
        assert!((count_median(4.226436e-6, s) / 1e-6 - 1.0).abs() < 1e-6);
        // Surface median, q = 2: exp(0.960906) = 2.614063 um.
        assert!((hatch_choate(cmd, s, 2.0) / 2.614063e-6 - 1.0).abs() < 1e-6);
        // Diameters of average surface and mass: exp(0.480453) = 1.616807 um, 2.055830 um.
        assert!((average_diameter(cmd, s, 2.0) / 1.616807e-6 - 1.0).abs() < 1e-6);
        assert!((average_diameter(cmd, s, 3.0) / 2.055830e-6 - 1.0).abs() < 1e-6);
        // Mean particle mass at 1000 kg/m^3: pi / 6 (2.055830e-6)^3 1000 = 4.549462e-15 kg.
        let m = mean_particle_mass(cmd, s, 1000.0);
        assert!((m / 4.549462e-15 - 1.0).abs() < 1e-5, "{m}");
        // A mode given by its mass median has the same count median back.
        let mode = Mode {
            median: Median::Mass(4.226436e-6),
            geometric_sd: s,
            density: 1000.0,
            amount: Amount::MassShare(1.0),
        };
        assert!((mode.count_median() / cmd - 1.0).abs() < 1e-6);
    }

    /// Bin weights by hand: CMD 1 um, sigma_g 2 over [0.5, 2] um (one sigma either side):
    /// 68.2689 % of the number; of the mass (about MMD 4.2264 um: `z` from -3.0794 to
    /// -1.0794) 13.9159 %. Half the number lies below the count median.
    #[test]
    fn bin_weights_match_hand_values() {
        let mode = Mode {
            median: Median::Count(1e-6),
            geometric_sd: 2.0,
            density: 1000.0,
            amount: Amount::NumberConcentration(1e9),
        };
        let distribution = Distribution::Modes { modes: vec![mode], bins: 2, range: Some([0.5e-6, 2e-6]) };
        let (bins, outside) = distribution.bins(&Air::standard()).unwrap();
        assert_eq!(bins.len(), 2);
        assert!((bins[0].number / 1e9 - (0.682689 / 2.0)).abs() < 1e-6, "{:?}", bins[0]);
        let number: f64 = bins.iter().map(|b| b.number).sum();
        assert!((number / 1e9 - 0.682689).abs() < 1e-6);
        let total = 1e9 * mean_particle_mass(1e-6, 2.0, 1000.0);
        let mass: f64 = bins.iter().map(|b| b.mass).sum();
        assert!((mass / total - 0.139159).abs() < 1e-6, "{}", mass / total);
        assert!((outside / total - (1.0 - 0.139159)).abs() < 1e-6);
        assert!((bins[0].diameter - 0.5e-6 * 2f64.sqrt()).abs() < 1e-15);
        // Every bin is below 2.5 um aerodynamic (2 um of unit density): all of it PM2.5.
        assert!(bins.iter().all(|b| b.pm_mass == [b.mass, b.mass]));
    }

    /// PM2.5 and PM10 of a unit-density mode (aerodynamic diameter = geometric) by hand: MMD
    /// 3 um, sigma_g 2: `Phi(ln(2.5 / 3) / ln 2)` = 39.6262 % and `Phi(ln(10 / 3) / ln 2)` =
    /// 95.8803 % of the mass, whichever bin the cuts fall in.
    #[test]
    fn pm_shares_of_a_mode_match_hand_values() {
        let mode =
            Mode { median: Median::Mass(3e-6), geometric_sd: 2.0, density: 1000.0, amount: Amount::MassShare(1.0) };
        for bins in [1, 5, 7] {
            let distribution = Distribution::Modes { modes: vec![mode], bins, range: Some([1e-9, 1e-3]) };
            let (bins, outside) = distribution.bins(&Air::standard()).unwrap();
            assert!(outside < 1e-12);
            let pm = |k: usize| bins.iter().map(|b| b.pm_mass[k]).sum::<f64>();
            assert!((pm(0) - 0.396_262).abs() < 1e-6 && (pm(1) - 0.958_803).abs() < 1e-6, "{} {}", pm(0), pm(1));
        }
    }

    /// PM2.5 and PM10 of a dense mode cut at the geometric diameter of the aerodynamic cut, by
    /// hand: MMD 3 um, sigma_g 2, 2500 kg/m^3, `lambda = 0.066434 um` (standard air). 2.5 um
    /// aerodynamic is `d = 2.5 um sqrt(1000 Cc(2.5 um) / (2500 Cc(d)))`, iterated from
    /// `2.5 um sqrt(0.4)` = 1.5811 um: 1.5549, 1.5537, 1.55368 um; its `z = ln(1.55368 / 3) /
    /// ln 2` = -0.94927 and `Phi(z)` = 17.1240 % of the mass. 10 um aerodynamic: 6.29627 um,
    /// `z` = 1.06954, 85.7586 %. (Ignoring the density, the cuts would take 39.6 % and 95.9 %.)
    #[test]
    fn pm_shares_of_a_dense_mode_match_hand_values() {
        let mode =
            Mode { median: Median::Mass(3e-6), geometric_sd: 2.0, density: 2500.0, amount: Amount::MassShare(1.0) };
        for bins in [1, 5, 7] {
            let distribution = Distribution::Modes { modes: vec![mode], bins, range: Some([1e-9, 1e-3]) };
            let (bins, outside) = distribution.bins(&Air::standard()).unwrap();
            assert!(outside < 1e-12);
            let pm = |k: usize| bins.iter().map(|b| b.pm_mass[k]).sum::<f64>();
            assert!((pm(0) - 0.171_240).abs() < 2e-6 && (pm(1) - 0.857_586).abs() < 2e-6, "{} {}", pm(0), pm(1));
        }
    }

    /// A size class of mass uniform in `ln d` from 1 to 4 um: a cut at 2 um takes half its
    /// mass; given by number instead, `(2^3 - 1) / (4^3 - 1) = 7 / 63` of it.
    #[test]
    fn size_classes_split_at_a_cut_by_hand() {
        let class = SizeClass { lower: 1e-6, upper: 4e-6, amount: 1.0, quantity: Quantity::Mass, density: 1000.0 };
        assert!((class.mass_below(2e-6) - 0.5).abs() < 1e-12);
        let by_number = SizeClass { quantity: Quantity::Number, ..class };
        assert!((by_number.mass_below(2e-6) - 7.0 / 63.0).abs() < 1e-12);
        // By number: mass = N rho pi / 6 (4^3 - 1) um^3 / (3 ln 4).
        let (mass, number) = by_number.mass_and_number();
        assert_eq!(number, 1.0);
        assert!((mass / (1000.0 * PI / 6.0 * 63e-18 / (3.0 * 4f64.ln())) - 1.0).abs() < 1e-12);
    }

    /// Aerodynamic diameter: the same as the geometric one at unit density; a 4000 kg/m^3
    /// sphere of 2.5 um aerodynamic diameter is 1.2129 um (iterating `d = 1.25 um
    /// sqrt(Cc(2.5 um) / Cc(d))` by hand with `lambda = 0.0664 um`: 1.2150, 1.2130, 1.2129).
    #[test]
    fn aerodynamic_diameter_matches_hand_values() {
        let air = Air::standard();
        assert!((aerodynamic_diameter(3e-6, 1000.0, &air) / 3e-6 - 1.0).abs() < 1e-9);
        let d = diameter_of_aerodynamic(2.5e-6, 4000.0, &air);
        assert!((d / 1.2129e-6 - 1.0).abs() < 2e-4, "{d}");
        assert!((aerodynamic_diameter(d, 4000.0, &air) / 2.5e-6 - 1.0).abs() < 1e-9);
    }

    /// Classes of two densities may cover the same sizes; classes of one density may not
    /// overlap, whatever comes between them.
    #[test]
    fn classes_overlap_only_across_densities() {
        let class = |lower: f64, upper: f64, density: f64| SizeClass {
            lower,
            upper,
            amount: 1e-9,
            quantity: Quantity::Mass,
            density,
        };
        let ok = Distribution::Classes(vec![class(1e-6, 2e-6, 1000.0), class(1e-6, 2e-6, 2000.0)]);
        assert!(ok.validate().is_ok());
        let overlap = Distribution::Classes(vec![
            class(1e-6, 2e-6, 1000.0),
            class(3e-6, 4e-6, 2000.0),
            class(1.5e-6, 3e-6, 1000.0),
        ]);
        assert_eq!(overlap.validate().unwrap_err().field, "size_bins[2].lower");
    }

    /// A monodisperse mode (sigma_g 1) puts all its particles in one of its 12 bins: only that
    /// one is run, holding all the mass; two far-apart modes of one density leave the bins
    /// between them empty, and those are not run either.
    #[test]
    fn empty_bins_are_not_run() {
        let mode =
            Mode { median: Median::Mass(2e-6), geometric_sd: 1.0, density: 1000.0, amount: Amount::MassShare(1.0) };
        let one = Distribution::Modes { modes: vec![mode], bins: DEFAULT_BINS, range: None };
        let (bins, outside) = one.bins(&Air::standard()).unwrap();
        assert_eq!(bins.len(), 1, "{bins:?}");
        assert!((bins[0].mass - 1.0).abs() < 1e-12 && outside < 1e-12);
        // 2 and 100 um, sigma_g 1.1, over 12 bins from 1.46 to 133 um (0.38 in ln d each); the
        // modes (3 ln sigma_g = 0.29 either side) fill two or three bins each, of the twelve.
        let far = Mode { median: Median::Mass(100e-6), ..mode };
        let narrow = |m: Mode| Mode { geometric_sd: 1.1, ..m };
        let two = Distribution::Modes { modes: vec![narrow(mode), narrow(far)], bins: 12, range: None };
        let (bins, _) = two.bins(&Air::standard()).unwrap();
        assert!(bins.len() <= 6, "{}", bins.len());
    }

    /// Modes mixing shares of number and of mass, or shares and concentrations, are errors
    /// naming them; so is a mode's bad value, by its index and key.
    #[test]
    fn bad_modes_are_errors_that_name_them() {
        let mode =
            Mode { median: Median::Count(1e-6), geometric_sd: 2.0, density: 1000.0, amount: Amount::NumberShare(1.0) };
        let modes = |m: Vec<Mode>| Distribution::Modes { modes: m, bins: 4, range: None };
        let mass = Mode { amount: Amount::MassShare(1.0), ..mode };
        assert_eq!(modes(vec![mode, mass]).validate().unwrap_err().field, "modes");
        let absolute = Mode { amount: Amount::MassConcentration(1e-8), ..mode };
        assert_eq!(modes(vec![mode, absolute]).validate().unwrap_err().field, "modes");
        let narrow = Mode { geometric_sd: 0.5, ..mode };
        assert_eq!(modes(vec![mode, narrow]).validate().unwrap_err().field, "modes[1].geometric_sd");
        // sigma_g 30 would take the bins to 3e11 m; 5 is the most.
        let broad = Mode { geometric_sd: 30.0, ..mode };
        assert_eq!(modes(vec![mode, broad]).validate().unwrap_err().field, "modes[1].geometric_sd");
        assert!(modes(vec![Mode { geometric_sd: 5.0, ..mode }]).validate().is_ok());
        assert!(modes(vec![mode, mode]).validate().is_ok());
    }
}
