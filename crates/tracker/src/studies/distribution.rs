//! Particle size distributions as aerosol science states them, and what a room does to their
//! mass: deposited per surface, exhausted and still airborne, for all of it and for PM2.5 and
//! PM10.
//!
//! A distribution is one or more lognormal modes (each given by its count or mass median
//! diameter, geometric standard deviation, particle density and a share or concentration of
//! number or mass), or a list of size classes (diameter bins with the number or mass in each,
//! as measured size distributions come).
//!
//! ## Quadrature
//! A room study tracks one size at a time, so a distribution is cut into bins in `ln d`
//! ([`Distribution::bins`]): the modes of one particle density share [`DEFAULT_BINS`] equal
//! steps in `ln d` from their smallest count median over `sigma_g^3` to their largest mass
//! median times `sigma_g^3` (for a mode alone, from 3 standard deviations below the median
//! to `3 + 3 ln sigma_g` above it for its number, and the mirror for its mass: at least
//! 99.73 % of each, more than 99.8 % for `sigma_g` above 1.08), or the range given; a class list's bins are its classes. A bin holding next to none of its
//! density's number and mass ([`NEGLIGIBLE`]) is not run. Each
//! bin's number and mass are integrated exactly (for a mode from its lognormal distribution
//! function; in a class, number or mass as given, spread uniformly in `ln d`), and the bin's
//! particles all share the fate of one run at its geometric midpoint `sqrt(lower upper)`:
//! `X = sum_i M_i f_i`, with `M_i` the bin's mass and `f_i` the run's share of particles in a
//! fate ([`integrate`]). Mass outside the bins is left out and reported
//! ([`MassBalance::outside`]).
//!
//! Its error has two parts, both reported ([`Portion`]): the runs' randomness (each `f_i` a
//! share of `n_i` independent particles, binomial variance `f_i (1 - f_i) / n_i`), and the
//! quadrature's, from taking `f` constant across a bin. A bin reaches halfway (in `ln d`) to
//! its neighbours' midpoints, so where `f` is monotonic from one neighbour's midpoint to the
//! other's, `f` within the bin lies between `f_i` and the neighbours' values: the bound
//! reported is `sum_i M_i max_j |f_j - f_i|` over the bin's neighbours `j` (of the same
//! density). An outer bin reaches the range's edge, beyond its run: there `f` goes on
//! monotonically away from its neighbour's value, bounded only by 0 or 1, and its bound
//! takes that too. It is a bound under monotonicity only (a share with a minimum or maximum
//! across a bin, like the walls' or the airborne one, may exceed it there), and a loose one:
//! where `f` is smooth the midpoint error is second order, far smaller (0.0013 under a bound
//! of 0.32 in the test on 8 bins). Narrower bins shrink it. A fate no particle of a bin's run
//! took counts 0 with no error for that bin; the rule of three bounds what it may hold there,
//! `M_i 3 / n_i` at 95 % ([`Portion::unseen_bound`]).
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

use crate::estimation::run::Estimate;
use crate::model::air::{slip_correction, Air};
use crate::model::error::SceneError;
use crate::studies::study::{RoomPoint, RoomStudy};

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

/// Where one bin's run put its particles: counts of the tracked particles at the end of the
/// run, and its loss-rate coefficient.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fates {
    /// Particles run.
    pub particles: usize,
    /// Deposited on the floor, the ceiling, the vertical walls.
    pub deposited: [usize; 3],
    /// Deposited on the furnishings' faces.
    pub furnishings: usize,
    /// Still airborne at the end.
    pub airborne: usize,
    /// Exhausted by ventilation.
    pub exhausted: usize,
    /// Escaped the domain (none in a room; kept for the balance).
    pub escaped: usize,
    /// Loss-rate coefficient `beta`, 1/s.
    pub beta: Estimate,
}

impl From<&RoomPoint> for Fates {
    fn from(p: &RoomPoint) -> Self {
        Self {
            particles: p.balance.injected,
            deposited: p.deposited.map(|(n, _)| n),
            furnishings: p.furnishings.iter().map(|f| f.deposited.0).sum(),
            airborne: p.balance.airborne,
            exhausted: p.balance.exhausted,
            escaped: p.balance.escaped,
            beta: p.beta,
        }
    }
}

/// A part of a distribution's mass with its errors (units of [`Bin::mass`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Portion {
    /// The mass.
    pub value: f64,
    /// Its standard error over the runs' randomness.
    pub error: f64,
    /// The bound on the quadrature's error where each fate's share is monotonic across the
    /// bins (see the module docs); NaN where a bin with mass has no neighbour to bound it by.
    pub quadrature: f64,
    /// The bins whose run had no particle in this fate count 0 with no error; by the rule of
    /// three, a 95 % upper bound on what each holds is `M_i 3 / n_i`: their sum (0 when every
    /// bin's run saw the fate).
    pub unseen_bound: f64,
}

/// Where a distribution's mass (or its PM2.5 or PM10 part) went.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MassSplit {
    /// Injected mass.
    pub injected: f64,
    /// Deposited on the floor, the ceiling and the vertical walls.
    pub deposited: [Portion; 3],
    /// Deposited on the furnishings' faces.
    pub furnishings: Portion,
    /// Airborne at the end of the run.
    pub airborne: Portion,
    /// Exhausted by ventilation.
    pub exhausted: Portion,
    /// Escaped the domain.
    pub escaped: Portion,
    /// The deposition loss rate of the mass, 1/s: `sum_i M_i beta_i / sum_i M_i`, the rate
    /// at which deposition (not ventilation) removes airborne mass while its size
    /// distribution is the injected one (deposition then takes the fast-depositing sizes
    /// first and the rate falls). Its `events` are the runs' together; its error carried from
    /// theirs; its upper bound the runs' bounds weighted alike. Only over the bins whose run
    /// measured a `beta` (see [`MassSplit::beta_share`]): the bins left out are the
    /// fastest-settling ones, so over all the mass the rate is at least this. None when no
    /// bin's run measured one.
    pub beta: Option<Estimate>,
    /// The share of the mass whose bins' runs measured a `beta`: a run whose particles all
    /// settled before its averaging window began has none (coarse particles in a short
    /// room), and its mass is left out of [`MassSplit::beta`].
    pub beta_share: f64,
}

impl MassSplit {
    /// The sum of the parts: the injected mass, but for rounding.
    #[must_use]
    pub fn accounted(&self) -> f64 {
        self.deposited.iter().map(|p| p.value).sum::<f64>()
            + self.furnishings.value
            + self.airborne.value
            + self.exhausted.value
            + self.escaped.value
    }
}

/// A distribution through a room.
#[derive(Clone, Debug, PartialEq)]
pub struct MassBalance {
    /// The bins and their runs' fates.
    pub bins: Vec<(Bin, Fates)>,
    /// All the mass in the bins.
    pub all: MassSplit,
    /// PM2.5 and PM10 ([`PM_CUTS`]).
    pub pm: [MassSplit; 2],
    /// Mass outside the bins (left out of the splits).
    pub outside: f64,
    /// Whether masses are concentrations (kg/m^3) rather than shares.
    pub absolute: bool,
}

/// The variance of a share `f` of `n` independent particles, `f (1 - f) / n`.
#[must_use]
pub fn binomial_variance(f: f64, n: f64) -> f64 {
    f * (1.0 - f) / n
}

/// The bound on `|f(d) - f_i|` across a bin whose run found the share `f_i`, from its
/// neighbours' shares, where `f` is monotonic from one neighbour's midpoint to the other's:
/// within the bin `f` lies between `f_i` and each neighbour's, so the full step to the
/// farther one bounds it. An outer bin (one neighbour) reaches on its other side to the
/// range's edge, where nothing bounds `f` but monotonicity: it goes on away from the
/// neighbour's value, at most to 0 (or 1). None without a neighbour.
fn quadrature_bound(f: f64, neighbours: impl Iterator<Item = f64>) -> Option<f64> {
    let neighbours: Vec<f64> = neighbours.collect();
    let step =
        neighbours.iter().map(|g| (g - f).abs()).fold(None, |m: Option<f64>, s| Some(m.map_or(s, |m| m.max(s))))?;
    Some(match neighbours[..] {
        // Rising towards the neighbour, so falling towards the edge (at most to 0), or the
        // other way; level, either way.
        [g] if g > f => step.max(f),
        [g] if g < f => step.max(1.0 - f),
        [_] => step.max(f).max(1.0 - f),
        _ => step,
    })
}

/// The split of `weights[i]` (each bin's mass, or a part of it) by the fates of each bin's run
/// (module docs: `X = sum_i M_i f_i` with its statistical error and quadrature bound).
/// `bins` and `fates` pair up; neighbours for the bound are adjacent bins of one density.
#[must_use]
pub fn integrate(bins: &[Bin], fates: &[Fates], weights: &[f64]) -> MassSplit {
    let n = bins.len();
    let shares: Vec<[f64; 7]> = fates
        .iter()
        .map(|f| {
            let p = f.particles.max(1) as f64;
            let [a, b, c] = f.deposited;
            [a, b, c, f.airborne, f.exhausted, f.escaped, f.furnishings].map(|k| k as f64 / p)
        })
        .collect();
    let neighbours = |i: usize| {
        let before = (i > 0 && bins[i - 1].density == bins[i].density).then(|| i - 1);
        let after = (i + 1 < n && bins[i + 1].density == bins[i].density).then_some(i + 1);
        [before, after].into_iter().flatten()
    };
    let portion = |k: usize| {
        let mut p = Portion::default();
        let mut variance = 0.0;
        for i in 0..n {
            let (w, f) = (weights[i], shares[i][k]);
            let n = fates[i].particles.max(1) as f64;
            p.value += w * f;
            variance += w * w * binomial_variance(f, n);
            if f == 0.0 {
                p.unseen_bound += w * 3.0 / n;
            }
            p.quadrature += match quadrature_bound(f, neighbours(i).map(|j| shares[j][k])) {
                Some(s) => w * s,
                None if w > 0.0 => f64::NAN,
                None => 0.0,
            };
        }
        p.error = variance.sqrt();
        p
    };
    let injected: f64 = weights.iter().sum();
    // Over the bins whose run measured a beta: a run whose particles all deposited before its
    // averaging window has no exposure to measure it by (its upper bound is infinite).
    let (mut rate, mut variance, mut events, mut measured, mut bound) = (0.0, 0.0, 0, 0.0, 0.0);
    for (w, f) in weights.iter().zip(fates).filter(|(_, f)| f.beta.upper_bound.is_finite()) {
        rate += w * f.beta.value;
        variance += (w * f.beta.error).powi(2);
        events += f.beta.events;
        measured += w;
        bound += w * f.beta.upper_bound;
    }
    // The runs' bounds (value plus two errors, or the rule of three without events), weighted
    // as their values are.
    let beta = (measured > 0.0).then(|| Estimate {
        value: rate / measured,
        error: variance.sqrt() / measured,
        events,
        upper_bound: bound / measured,
    });
    MassSplit {
        injected,
        deposited: [portion(0), portion(1), portion(2)],
        furnishings: portion(6),
        airborne: portion(3),
        exhausted: portion(4),
        escaped: portion(5),
        beta,
        beta_share: if injected > 0.0 { measured / injected } else { 0.0 },
    }
}

/// A room study of a size distribution: the room study's runs at the distribution's bins
/// (one study per particle density), their fates weighted by the bins' mass.
///
/// ```
/// use depo_tracker::distribution::{Amount, Distribution, DistributionStudy, Median, Mode};
/// use depo_tracker::studies::RoomStudy;
///
/// // 20 ug/m^3 of a mode of mass median 3 um, in 6 bins; a short run of few particles.
/// let mode = Mode {
///     median: Median::Mass(3e-6),
///     geometric_sd: 2.0,
///     density: 1500.0,
///     amount: Amount::MassConcentration(20e-9),
/// };
/// let mut study = RoomStudy { count: 20, target_error: None, excursions: false, ..RoomStudy::default() };
/// study.scene.duration = 10.0;
/// let distribution = Distribution::Modes { modes: vec![mode], bins: 6, range: None };
/// let (_, balance) = DistributionStudy { study, distribution }.run(|_| {}).unwrap();
/// let floor = balance.all.deposited[0]; // kg/m^3 of the room's air, with its errors
/// let pm2_5 = &balance.pm[0];
/// assert!((balance.all.accounted() / balance.all.injected - 1.0).abs() < 1e-12);
/// assert!(pm2_5.injected < balance.all.injected && floor.value >= 0.0);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct DistributionStudy {
    /// The room, its runs and their resolution; its `diameters` and `density` are the bins'.
    pub study: RoomStudy,
    /// The particles.
    pub distribution: Distribution,
}

impl DistributionStudy {
    /// The bins the study runs and the mass outside them.
    pub fn bins(&self) -> Result<(Vec<Bin>, f64), SceneError> {
        self.distribution.bins(&self.study.scene.air)
    }

    /// Runs every bin; `progress` is told after each run (of [`DistributionStudy::bins`]'s
    /// length). The points are in the bins' order.
    pub fn run(&self, mut progress: impl FnMut(usize)) -> Result<(Vec<RoomPoint>, MassBalance), SceneError> {
        let (bins, outside) = self.bins()?;
        let mut points: Vec<RoomPoint> = Vec::with_capacity(bins.len());
        let mut start = 0;
        while start < bins.len() {
            let density = bins[start].density;
            let end = start + bins[start..].iter().take_while(|b| b.density == density).count();
            let study = RoomStudy {
                diameters: bins[start..end].iter().map(|b| b.diameter).collect(),
                density,
                ..self.study.clone()
            };
            let done = points.len();
            points.extend(study.run(|k| progress(done + k)).map_err(|mut e| {
                // The sizes are the distribution's, not a list of diameters: the value is a
                // bin's diameter.
                if e.field == "particles.diameters" {
                    e.field = match self.distribution {
                        Distribution::Modes { .. } => "particles.modes (a bin's diameter, m)",
                        Distribution::Classes(_) => "particles.size_bins (a bin's diameter, m)",
                    }
                    .into();
                }
                e
            })?);
            start = end;
        }
        let fates: Vec<Fates> = points.iter().map(Fates::from).collect();
        let mass: Vec<f64> = bins.iter().map(|b| b.mass).collect();
        let pm = [0, 1].map(|k| {
            let w: Vec<f64> = bins.iter().map(|b| b.pm_mass[k]).collect();
            integrate(&bins, &fates, &w)
        });
        let all = integrate(&bins, &fates, &mass);
        let balance = MassBalance {
            bins: bins.into_iter().zip(fates).collect(),
            all,
            pm,
            outside,
            absolute: self.distribution.is_absolute(),
        };
        Ok((points, balance))
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

    fn fates(particles: usize, deposited: [usize; 3], airborne: usize, exhausted: usize, beta: f64) -> Fates {
        let beta = Estimate { value: beta, error: 0.1 * beta, events: deposited.iter().sum(), upper_bound: 1.2 * beta };
        Fates { particles, deposited, furnishings: 0, airborne, exhausted, escaped: 0, beta }
    }

    fn bin(diameter: f64, mass: f64) -> Bin {
        Bin { lower: diameter, upper: diameter, diameter, density: 1000.0, number: 0.0, mass, pm_mass: [mass; 2] }
    }

    /// The split by hand: two bins of mass 2 and 1, their runs putting 10 % and 40 % of 100
    /// particles on the floor: 0.2 + 0.4 = 0.6 on the floor, binomial error
    /// `sqrt(4 (0.1 0.9) / 100 + 1 (0.4 0.6) / 100)` = 0.07746. Quadrature bound: both bins
    /// are outer ones; the first's share rises towards its neighbour (0.1 to 0.4), so towards
    /// the edge it may fall to 0: `max(0.3, 0.1)`; the second's falls towards its neighbour,
    /// so towards the edge it may rise to 1: `max(0.3, 0.6)`; `2 0.3 + 1 0.6` = 1.2. A middle
    /// bin of share 0.2 between them bounds by its full step to the farther, 0.2. Every part adds up to the injected 3 again, and the
    /// mass-weighted beta is `(2 1e-4 + 1 5e-4) / 3`.
    #[test]
    fn integration_matches_hand_values_and_balances() {
        let bins = [bin(1e-6, 2.0), bin(3e-6, 1.0)];
        let runs = [fates(100, [10, 2, 3], 60, 25, 1e-4), fates(100, [40, 0, 5], 30, 25, 5e-4)];
        let split = integrate(&bins, &runs, &[2.0, 1.0]);
        let floor = split.deposited[0];
        assert!((floor.value - 0.6).abs() < 1e-12, "{floor:?}");
        assert!((floor.error - 0.077_459_7).abs() < 1e-6, "{floor:?}");
        assert!((floor.quadrature - 1.2).abs() < 1e-12, "{floor:?}");
        // Every run saw the floor; the second saw no ceiling deposit (1 3 / 100), neither an
        // escape ((2 + 1) 3 / 100).
        assert_eq!(floor.unseen_bound, 0.0);
        assert!((split.deposited[1].unseen_bound - 0.03).abs() < 1e-15, "{:?}", split.deposited[1]);
        assert!((split.escaped.unseen_bound - 0.09).abs() < 1e-15, "{:?}", split.escaped);
        let three = [bin(1e-6, 2.0), bin(2e-6, 1.0), bin(3e-6, 1.0)];
        let middle = fates(100, [20, 0, 0], 80, 0, 1e-4);
        let inner = integrate(&three, &[runs[0], middle, runs[1]], &[0.0, 1.0, 0.0]).deposited[0];
        assert!((inner.quadrature - 0.2).abs() < 1e-12, "{inner:?}");
        assert!((split.airborne.value - (2.0 * 0.6 + 0.3)).abs() < 1e-12);
        assert!((split.exhausted.value - 0.75).abs() < 1e-12);
        assert!((split.accounted() - split.injected).abs() <= 1e-15 * split.injected);
        let beta = split.beta.unwrap();
        assert!((beta.value - 7e-4 / 3.0).abs() < 1e-18);
        // The runs' upper bounds 1.2e-4 and 6e-4, weighted by 2 and 1: 8.4e-4 / 3.
        assert!((beta.upper_bound - 8.4e-4 / 3.0).abs() < 1e-18, "{beta:?}");
        assert_eq!(split.beta_share, 1.0);
        // One bin alone has no neighbour to bound its quadrature by.
        assert!(integrate(&bins[..1], &runs[..1], &[2.0]).deposited[0].quadrature.is_nan());
        // A run that measured no beta (all settled before its window) is left out of the
        // mass's beta, and says how much mass that is.
        let mut unmeasured = runs;
        unmeasured[1].beta = Estimate { value: 0.0, error: 0.0, events: 0, upper_bound: f64::INFINITY };
        let split = integrate(&bins, &unmeasured, &[2.0, 1.0]);
        assert!((split.beta.unwrap().value - 1e-4).abs() < 1e-18 && (split.beta_share - 2.0 / 3.0).abs() < 1e-15);
        // With no run measuring one, the mass has no beta: none, not 0 +- 0.
        unmeasured[0].beta = unmeasured[1].beta;
        let split = integrate(&bins, &unmeasured, &[2.0, 1.0]);
        assert_eq!((split.beta, split.beta_share), (None, 0.0));
    }

    /// The quadrature bound holds: a smooth settling-like share `f(d) = 1 - exp(-(d / 3 um)^2)`
    /// (as counts of a million particles per bin) over a mode of MMD 3 um, sigma_g 2:
    /// integrated on 8 and 16 bins, the error against 4000 bins is within the bound, and the
    /// bound halves with the bins' width.
    #[test]
    fn quadrature_error_is_within_its_bound_and_halves_with_the_bins() {
        let mode = Mode {
            median: Median::Mass(3e-6),
            geometric_sd: 2.0,
            density: 1000.0,
            amount: Amount::MassConcentration(1.0),
        };
        let share = |d: f64| 1.0 - (-(d / 3e-6).powi(2)).exp();
        let floor = |bins: usize| {
            let distribution = Distribution::Modes { modes: vec![mode], bins, range: Some([0.3e-6, 30e-6]) };
            let (bins, _) = distribution.bins(&Air::standard()).unwrap();
            let n = 1_000_000;
            let runs: Vec<Fates> = bins
                .iter()
                .map(|b| {
                    let k = (share(b.diameter) * n as f64).round() as usize;
                    fates(n, [k, 0, 0], n - k, 0, 1e-4)
                })
                .collect();
            let mass: Vec<f64> = bins.iter().map(|b| b.mass).collect();
            integrate(&bins, &runs, &mass).deposited[0]
        };
        let exact = floor(4000).value;
        let (coarse, fine) = (floor(8), floor(16));
        for p in [coarse, fine] {
            assert!((p.value - exact).abs() <= p.quadrature, "{p:?} against {exact}");
        }
        let ratio = fine.quadrature / coarse.quadrature;
        assert!((0.4..0.6).contains(&ratio), "{ratio}");
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
