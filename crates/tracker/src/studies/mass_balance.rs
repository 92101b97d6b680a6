//! What a room does to a size distribution's mass: each bin's run gives the fates of its
//! particles ([`Fates`]), and their integral over the bins splits the distribution's mass
//! between the surfaces, the exhaust and the air, with its errors, for all of it and for
//! PM2.5 and PM10 ([`integrate`], [`DistributionStudy`]). The distributions and their bins are
//! [`super::distribution`].
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

use crate::estimation::run::Estimate;
use crate::model::error::SceneError;
use crate::studies::distribution::*;
use crate::studies::room::{RoomPoint, RoomStudy};

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
/// study.settings.duration = 10.0;
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
    use crate::model::air::Air;

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
}
