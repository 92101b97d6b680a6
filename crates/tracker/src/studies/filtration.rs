//! Filters in a room's air handling: a filtered mechanical supply of outdoor air and a
//! filtered recirculation, and what they do to the indoor/outdoor ratio at steady state.
//!
//! A room exchanges its air with outdoors at the rate `a` ([`crate::Scene::air_exchange`]): a
//! share `s` of it through a mechanical supply whose filter removes a share `eta_s(d)` of the
//! particles of diameter `d` in one pass, the rest `1 - s` by infiltration through the
//! envelope, which lets in a share `P` (the penetration factor). A recirculation moves indoor
//! air through a filter of efficiency `eta_r(d)` at `a_r` room volumes per unit time and
//! returns it. For a well-mixed room the steady mass balance of particles of outdoor origin is
//! then (the balance of Riley et al. 2002, *Environ. Sci. Technol.* 36:200, and Nazaroff 2004,
//! *Indoor Air* 14 Suppl. 7:175, for a room with supply, infiltration and recirculation):
//!
//! ```text
//! C_in / C_out = (P (1 - s) a + (1 - eta_s) s a) / (a + eta_r a_r + beta)
//! ```
//!
//! with `beta` the loss rate by deposition. The recirculation's filter removes particles at
//! the rate `eta_r a_r` wherever they are in a well-mixed room, as the exhaust does at `a`:
//! a room study therefore runs each size with both as one removal rate (a particle removed is
//! counted *exhausted*; a share `eta_r a_r / (a + eta_r a_r)` of those went to the filter, in
//! expectation), and its decay curve falls at `a + eta_r a_r + beta`.

use crate::model::error::SceneError;

/// A filter's single-pass removal efficiency against particle diameter: `(diameter m,
/// efficiency)` points, interpolated linearly in `ln d` between them and held constant beyond
/// the first and the last (a measured efficiency curve, as filter test standards report it
/// per size band, e.g. ISO 16890 or ASHRAE 52.2).
#[derive(Clone, Debug, PartialEq)]
pub struct FilterEfficiency {
    points: Vec<(f64, f64)>,
}

impl FilterEfficiency {
    /// One efficiency for every size, in `[0, 1]`.
    pub fn constant(efficiency: f64) -> Result<Self, SceneError> {
        Self::new(vec![(1e-6, efficiency)])
    }

    /// No filter: efficiency 0 at every size.
    #[must_use]
    pub fn none() -> Self {
        Self { points: vec![(1e-6, 0.0)] }
    }

    /// The curve through `points`: diameters positive, finite and increasing, efficiencies in
    /// `[0, 1]`, at least one point.
    pub fn new(points: Vec<(f64, f64)>) -> Result<Self, SceneError> {
        if points.is_empty() {
            return Err(SceneError::new("filter efficiency", 0.0, "needs at least one point"));
        }
        for (i, &(d, eta)) in points.iter().enumerate() {
            if !(d.is_finite() && d > 0.0) || (i > 0 && d <= points[i - 1].0) {
                return Err(SceneError::new("filter efficiency diameter", d, "must be positive and increasing"));
            }
            if !(0.0..=1.0).contains(&eta) {
                return Err(SceneError::new("filter efficiency", eta, "must be in [0, 1]"));
            }
        }
        Ok(Self { points })
    }

    /// The efficiency at diameter `d` (m).
    #[must_use]
    pub fn at(&self, d: f64) -> f64 {
        let p = &self.points;
        let last = p.len() - 1;
        if d <= p[0].0 {
            return p[0].1;
        }
        if d >= p[last].0 {
            return p[last].1;
        }
        let k = p.partition_point(|&(x, _)| x <= d);
        let ((d0, e0), (d1, e1)) = (p[k - 1], p[k]);
        e0 + (e1 - e0) * (d / d0).ln() / (d1 / d0).ln()
    }
}

/// A room's filtered supply and recirculation (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Filtration {
    /// Share `s` of the air exchange that comes through the mechanical supply, in `[0, 1]`.
    pub supply_share: f64,
    /// The supply filter's efficiency `eta_s(d)`.
    pub supply_filter: FilterEfficiency,
    /// Recirculation rate `a_r` through the recirculation filter, room volumes per second.
    pub recirculation: f64,
    /// The recirculation filter's efficiency `eta_r(d)`.
    pub recirculation_filter: FilterEfficiency,
}

impl Default for Filtration {
    /// No supply share, no recirculation, no filter: infiltration alone.
    fn default() -> Self {
        Self {
            supply_share: 0.0,
            supply_filter: FilterEfficiency::none(),
            recirculation: 0.0,
            recirculation_filter: FilterEfficiency::none(),
        }
    }
}

impl Filtration {
    /// Checks the shares and the rate; the error names the first offending field.
    pub fn validate(&self) -> Result<(), SceneError> {
        if !(0.0..=1.0).contains(&self.supply_share) {
            return Err(SceneError::new("supply_share", self.supply_share, "must be in [0, 1]"));
        }
        if !(self.recirculation.is_finite() && self.recirculation >= 0.0) {
            return Err(SceneError::new("recirculation", self.recirculation, "must be finite and not negative"));
        }
        Ok(())
    }

    /// The recirculation filter's removal rate `eta_r(d) a_r` for diameter `d` (m), 1/s.
    #[must_use]
    pub fn removal(&self, d: f64) -> f64 {
        self.recirculation_filter.at(d) * self.recirculation
    }

    /// The steady indoor/outdoor ratio of particles of diameter `d` (m) for air exchange `a`
    /// (1/s), penetration `P` and deposition loss rate `beta` (1/s) (see the module docs).
    #[must_use]
    pub fn indoor_outdoor(&self, d: f64, a: f64, penetration: f64, beta: f64) -> f64 {
        self.entering(d, a, penetration) / (a + self.removal(d) + beta)
    }

    /// The rate at which outdoor particles of diameter `d` (m) enter per unit volume and
    /// outdoor concentration, `P (1 - s) a + (1 - eta_s) s a`, 1/s, for air exchange `a` (1/s)
    /// and penetration `P`: the source whose steady indoor/outdoor ratio is this times the
    /// particles' mean residence time ([`crate::steady`]).
    #[must_use]
    pub fn entering(&self, d: f64, a: f64, penetration: f64) -> f64 {
        let s = self.supply_share;
        penetration * (1.0 - s) * a + (1.0 - self.supply_filter.at(d)) * s * a
    }

    /// The derivative of [`Filtration::indoor_outdoor`] with respect to `beta`, for carrying
    /// `beta`'s standard error.
    #[must_use]
    pub fn indoor_outdoor_slope(&self, d: f64, a: f64, penetration: f64, beta: f64) -> f64 {
        -self.indoor_outdoor(d, a, penetration, beta) / (a + self.removal(d) + beta)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn efficiency_is_linear_in_ln_d_and_held_beyond_the_ends() {
        let f = FilterEfficiency::new(vec![(0.3e-6, 0.2), (1e-6, 0.5), (10e-6, 0.9)]).unwrap();
        assert_eq!(f.at(0.1e-6), 0.2);
        assert_eq!(f.at(30e-6), 0.9);
        assert!((f.at(1e-6) - 0.5).abs() < 1e-15);
        // sqrt(10) um is halfway in ln d from 1 to 10 um: 0.7.
        assert!((f.at(10f64.sqrt() * 1e-6) - 0.7).abs() < 1e-12);
        assert!(FilterEfficiency::new(vec![(1e-6, 0.5), (1e-6, 0.6)]).is_err());
        assert!(FilterEfficiency::new(vec![(1e-6, 1.5)]).is_err());
        assert!(FilterEfficiency::new(vec![]).is_err());
    }

    /// By hand: a = 1/h, half of it through a supply filter of 80 %, P = 0.9 on the rest,
    /// recirculation 4/h through a 50 % filter, beta = 0.5/h:
    /// (0.9 x 0.5 + 0.2 x 0.5) / (1 + 2 + 0.5) = 0.55 / 3.5.
    #[test]
    fn indoor_outdoor_ratio_by_hand() {
        let h = 1.0 / 3600.0;
        let f = Filtration {
            supply_share: 0.5,
            supply_filter: FilterEfficiency::constant(0.8).unwrap(),
            recirculation: 4.0 * h,
            recirculation_filter: FilterEfficiency::constant(0.5).unwrap(),
        };
        let r = f.indoor_outdoor(1e-6, h, 0.9, 0.5 * h);
        assert!((r - 0.55 / 3.5).abs() < 1e-12, "{r}");
        assert!((f.removal(1e-6) - 2.0 * h).abs() < 1e-18);
        // Without filters or supply it is P a / (a + beta).
        let none = Filtration::default();
        assert!((none.indoor_outdoor(1e-6, h, 0.9, 0.5 * h) - 0.9 / 1.5).abs() < 1e-12);
    }
}
