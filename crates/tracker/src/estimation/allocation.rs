//! Excursions per class of crossing: fewer where a study's figures have room to spare.
//!
//! A room study runs its first particles with the same sampling for every crossing into the
//! near-wall layer, and then more particles until its worst figure reaches the target error
//! ([`RoomStudy`](crate::studies::room::RoomStudy)). The other figures then come out better than
//! they need, and the excursions that resolve them (the four walls' at 0.1 um, the floor's at
//! 1 um, the ceiling's where its figure is too small to need resolving) take time for
//! nothing. [`class_sampling`] lowers the sampling of each class of crossing
//! ([`crossing_class`](crate::model::excursions::crossing_class): floor, ceiling, walls,
//! furnishings) as far as every figure allows, from what the first particles showed, for the
//! particles that follow.
//!
//! The estimate stays unbiased whatever the multipliers (each excursion weighs one over its
//! own sampling). What they change is the spread: with `m` excursions per crossing, a
//! particle's deposits from a class vary as `V_between + V_within / m`, and only the second
//! part grows when `m` falls. The first particles give the whole variance of each class's
//! deposits per particle, `V_c >= V_within / m`; a figure's relative variance with
//! multipliers `s_c` is bounded by
//!
//! ```text
//! e^2(s) <= e^2 + sum_c C_c (1 / s_c - 1),    C_c = sum_i (d_ci - mean d_c)^2 / (sum_i D_i)^2
//! ```
//!
//! with `d_ci` particle `i`'s deposits on the figure's surfaces from crossings of class `c`
//! and `D_i` their sum over the classes. The bound takes all of `V_c` as within-crossing, so
//! it holds in expectation; but its `e` and `C_c` are themselves estimates from the first
//! particles (a class whose deposits onto a figure were never seen there counts nothing
//! against it), and a fractional number of excursions per crossing (the whole part, and one
//! more by chance) adds a little spread it leaves out, small where deposits are rare. The
//! study's rounds check the figures the particles actually give.

use crate::estimation::run::{Estimate, Run};
use crate::model::excursions::CROSSING_CLASSES;
use crate::tracking::ParticleTally;

/// A figure a study must resolve, as its first particles give it: its relative variance and
/// each class of crossing's share of it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Figure {
    /// `(error / value)^2` of the estimate.
    pub relative_variance: f64,
    /// `C_c` of the module docs: the relative variance of the deposits from crossings of
    /// each class, were all of it within-crossing.
    pub contributions: [f64; CROSSING_CLASSES],
}

impl Figure {
    /// The figure `estimate` of `run`, made of the deposits on the surfaces of the classes
    /// `onto` marks; `None` without a deposit to go by.
    #[must_use]
    pub fn of(run: &Run, estimate: &Estimate, onto: [bool; CROSSING_CLASSES]) -> Option<Self> {
        if estimate.events == 0 || estimate.value <= 0.0 || run.particles.len() < 2 {
            return None;
        }
        let from = |c: usize, p: &ParticleTally| -> f64 {
            (0..CROSSING_CLASSES).filter(|&k| onto[k]).map(|k| p.class_deposits[c][k]).sum()
        };
        let n = run.particles.len() as f64;
        let total: f64 = run.particles.iter().map(|p| (0..CROSSING_CLASSES).map(|c| from(c, p)).sum::<f64>()).sum();
        if total <= 0.0 {
            return None;
        }
        let contributions = std::array::from_fn(|c| {
            let mean = run.particles.iter().map(|p| from(c, p)).sum::<f64>() / n;
            let spread: f64 = run.particles.iter().map(|p| (from(c, p) - mean).powi(2)).sum();
            spread * n / (n - 1.0) / (total * total)
        });
        Some(Self { relative_variance: (estimate.error / estimate.value).powi(2), contributions })
    }
}

/// The excursions' steps with multipliers `s`, from each class's `steps` at full sampling.
fn excursion_steps(s: [f64; CROSSING_CLASSES], steps: [f64; CROSSING_CLASSES]) -> f64 {
    (0..CROSSING_CLASSES).map(|c| s[c] * steps[c]).sum()
}

/// The multipliers a class's sampling may take, from none to an eighth.
pub const MULTIPLIERS: [f64; 7] = [1.0, 0.7, 0.5, 0.35, 0.25, 0.18, 0.125];

/// The particle counts [`plan`] weighs, as multiples of the count the worst figure needs.
pub const MORE_PARTICLES: [f64; 6] = [1.0, 1.05, 1.1, 1.2, 1.35, 1.5];

/// The particles to run and the sampling multipliers per class of crossing for them that
/// cost least: each count of [`MORE_PARTICLES`] times `needed` (at most `max`) with its
/// cheapest multipliers ([`class_sampling`]), at `tracked + sum_c s_c steps_c` steps per
/// `first` particles (`tracked` the tracked particles' steps, `steps` each class's
/// excursions' steps, both of the first particles). A few more particles than the worst
/// figure needs can pay: they give that figure room to spare too, where without them every
/// class that adds to it, however little, keeps all its excursions.
///
/// The figures are held to `target / sqrt(margin)`, the margin a study keeps for the spread
/// of the errors it plans from; at `max` particles, where no later round can make up for a
/// figure the cuts left short, to `target / margin`.
#[must_use]
pub fn plan(
    figures: &[Option<Figure>],
    (tracked, steps): (f64, [f64; CROSSING_CLASSES]),
    first: usize,
    (needed, max): (usize, usize),
    (target, margin): (f64, f64),
) -> (usize, [f64; CROSSING_CLASSES]) {
    let max = max.max(needed);
    let mut best = (needed, [1.0; CROSSING_CLASSES], f64::INFINITY);
    for more in MORE_PARTICLES {
        let count = ((needed as f64 * more).ceil() as usize).min(max);
        let held = if count == max { target / margin } else { target / margin.sqrt() };
        let s = class_sampling(figures, steps, first, count, held);
        let cost = count as f64 * (tracked + excursion_steps(s, steps));
        if cost < best.2 {
            best = (count, s, cost);
        }
    }
    (best.0, best.1)
}

/// The sampling multiplier of each class of crossing ([`Excursions::class_sampling`]) that
/// costs least, `sum_c s_c steps_c` with `steps` each class's excursions' steps at the
/// first particles' sampling, while every figure's bounded relative variance (module docs),
/// scaled from the `first` particles it was measured on to the `count` a study runs, stays
/// within `target^2`, or within its own where it is above that already. Multipliers from
/// [`MULTIPLIERS`]; all 1 where no smaller choice fits or a figure is missing (`None`).
///
/// [`Excursions::class_sampling`]: crate::Excursions::class_sampling
#[must_use]
pub fn class_sampling(
    figures: &[Option<Figure>],
    steps: [f64; CROSSING_CLASSES],
    first: usize,
    count: usize,
    target: f64,
) -> [f64; CROSSING_CLASSES] {
    let mut best = ([1.0; CROSSING_CLASSES], excursion_steps([1.0; CROSSING_CLASSES], steps));
    let Some(figures) = figures.iter().copied().collect::<Option<Vec<Figure>>>() else { return best.0 };
    // Each figure's bound on the scale of the first particles.
    let scale = count as f64 / first as f64;
    let bounds: Vec<f64> = figures.iter().map(|f| (target * target * scale).max(f.relative_variance)).collect();
    let choices = MULTIPLIERS.len();
    for k in 0..choices.pow(CROSSING_CLASSES as u32) {
        let s: [f64; CROSSING_CLASSES] = std::array::from_fn(|c| MULTIPLIERS[k / choices.pow(c as u32) % choices]);
        let cost = excursion_steps(s, steps);
        if cost >= best.1 {
            continue;
        }
        let fits = figures.iter().zip(&bounds).all(|(f, &bound)| {
            let grown: f64 = (0..CROSSING_CLASSES).map(|c| f.contributions[c] * (1.0 / s[c] - 1.0)).sum();
            f.relative_variance + grown <= bound
        });
        if fits {
            best = (s, cost);
        }
    }
    best.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_figure_with_room_to_spare_gives_up_its_class_s_excursions() {
        // Two figures from 1000 particles, a study of 4000 at 5 %: bound 0.0025 * 4 = 0.01 on
        // the first particles' scale. The walls' figure (class 2) is at 0.01 already: none of
        // its class's sampling may go. The floor's (class 0) is at 0.004, all of it from its
        // own class: 0.004 + 0.004 (1/s - 1) <= 0.01 takes s >= 0.4, so 0.5 of the
        // multipliers. The ceiling and furnishings add to neither figure: an eighth.
        let walls = Figure { relative_variance: 0.01, contributions: [0.0, 0.0, 0.008, 0.0] };
        let floor = Figure { relative_variance: 0.004, contributions: [0.004, 0.0, 0.0, 0.0] };
        let s = class_sampling(&[Some(walls), Some(floor)], [1.0, 1.0, 1.0, 1.0], 1000, 4000, 0.05);
        assert_eq!(s, [0.5, 0.125, 1.0, 0.125]);
        // A class that costs nothing is left alone, and a missing figure leaves every class.
        let s = class_sampling(&[Some(walls), Some(floor)], [1.0, 0.0, 1.0, 1.0], 1000, 4000, 0.05);
        assert_eq!(s, [0.5, 1.0, 1.0, 0.125]);
        assert_eq!(class_sampling(&[Some(floor), None], [1.0; 4], 1000, 4000, 0.05), [1.0; 4]);
    }

    #[test]
    fn a_few_more_particles_buy_room_for_the_worst_figure_s_neighbours() {
        // The ceiling needs 5000 particles (0.0125 on 1000's scale at 5 %: bound 0.0025 per
        // 1000 particles run); the walls' class adds a little to it and costs most. Steps: 1
        // tracked, 4 in the walls' excursions, 1 in each other class's.
        // - 5000: the ceiling is at its bound, so the walls keep all their excursions;
        //   5 (1 + 0.125 + 1 + 4 + 0.125) = 31.25.
        // - 5250: bound 0.013125. The ceiling's slack 0.000625 takes 0.0002 (1/s - 1) down to
        //   s = 0.2424, so 0.25; the walls' own 0.002 / s, down to 0.152. 5.25 x 3.25 = 17.06.
        // - 5500: bound 0.01375; the ceiling allows 0.138, the walls 0.145: 0.18, and
        //   5.5 (2.25 + 0.72) = 16.34, the least.
        // - 6000 (0.18 again, as the walls allow 0.133): 17.8; 6750 and 7500 (0.125): 18.6
        //   and 20.6.
        let ceiling = Figure { relative_variance: 0.0125, contributions: [0.0, 0.0125, 0.0002, 0.0] };
        let walls = Figure { relative_variance: 0.002, contributions: [0.0, 0.0, 0.002, 0.0] };
        let figures = [Some(ceiling), Some(walls)];
        let steps = [1.0, 1.0, 4.0, 1.0];
        assert_eq!(class_sampling(&figures, steps, 1000, 5000, 0.05), [0.125, 1.0, 1.0, 0.125]);
        assert_eq!(class_sampling(&figures, steps, 1000, 5250, 0.05), [0.125, 1.0, 0.25, 0.125]);
        assert_eq!(plan(&figures, (1.0, steps), 1000, (5000, 8000), (0.05, 1.0)), (5500, [0.125, 1.0, 0.18, 0.125]));
        // At most `max` particles: no room to buy.
        assert_eq!(plan(&figures, (1.0, steps), 1000, (5000, 5000), (0.05, 1.0)), (5000, [0.125, 1.0, 1.0, 0.125]));
        // With a margin of 1.2, figures held to 0.05 / sqrt(1.2) below `max`: 5500 then
        // bounds them at 0.0114583, the ceiling above it, so nothing is cut there; 6000
        // (0.0125, the ceiling's own) cuts as 5000 did without a margin; 6750 (bound
        // 0.0140625) lets the walls go to 0.18 (0.002 / 0.0140625 = 0.142): 6.75 x 2.97 =
        // 20.05, against 7500 (0.015625: 0.128, still 0.18) and 6000's 6 x 6.25.
        assert_eq!(plan(&figures, (1.0, steps), 1000, (5000, 8000), (0.05, 1.2)), (6750, [0.125, 1.0, 0.18, 0.125]));
    }

    #[test]
    fn at_the_most_particles_the_cuts_keep_the_margin_twice() {
        // The first test's figures, 4000 particles the most: with a margin of 1.2 the floor
        // is held to (0.05 / 1.2)^2 x 4 = 0.006944 rather than 0.0025 x 4 / 1.2 = 0.008333,
        // so 0.004 / s takes s >= 0.576 (0.7) rather than 0.48 (0.5).
        let walls = Figure { relative_variance: 0.01, contributions: [0.0, 0.0, 0.008, 0.0] };
        let floor = Figure { relative_variance: 0.004, contributions: [0.004, 0.0, 0.0, 0.0] };
        let figures = [Some(walls), Some(floor)];
        assert_eq!(plan(&figures, (1.0, [1.0; 4]), 1000, (4000, 4000), (0.05, 1.2)), (4000, [0.7, 0.125, 1.0, 0.125]));
        assert_eq!(class_sampling(&figures, [1.0; 4], 1000, 4000, 0.05 / 1.2f64.sqrt()), [0.5, 0.125, 1.0, 0.125]);
    }

    #[test]
    fn a_figure_above_its_target_keeps_what_it_has() {
        // At the most particles a study may run the walls stay at 8 % (0.0064 from 1000 over
        // 0.0025 * 2 = 0.005 from 2000): their class keeps all its excursions, and the
        // furnishings, which add a little to the walls' figure, keep theirs too.
        let walls = Figure { relative_variance: 0.0064, contributions: [0.0, 0.0, 0.005, 1e-6] };
        let s = class_sampling(&[Some(walls)], [1.0; 4], 1000, 2000, 0.05);
        assert_eq!(s, [0.125, 0.125, 1.0, 1.0]);
    }
}
