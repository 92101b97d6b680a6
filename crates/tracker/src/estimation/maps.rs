//! Deposition maps of a run's own estimator: the deposition velocity of each cell of a grid
//! over a surface, from the same weighted deposits and exposure as the surface's figure.
//!
//! A cell `c` of area `A_c` on a surface gets `v_c = (V / A_c) sum_i X_ic / sum_i E_i`: `X_ic`
//! particle `i`'s deposits within the averaging window that landed in the cell (with
//! excursions, their weighted deposits), `E_i` its airborne time within the window, `V` the
//! air's volume. It is [`Run::deposition_velocity`]'s ratio restricted to the cell, so the
//! cells' `v_c A_c` summed over the surface, over the surface's area, is the surface's `v_d`
//! (to rounding), and each cell's standard error is the same delta method's over the
//! independent particles (see [`mod@crate::run`]). A cell that straddles an opening's edge counts
//! its whole area.
//!
//! The grid's cells are square (or as near as the surface's sides allow), as fine as leaves
//! most cells resolved: [`Run::resolved_flux_map`] takes the finest grid, up to
//! [`MAP_MOST_CELLS`] cells along the surface's longer side, on which at least
//! [`MAP_RESOLVED_SHARE`] of the cells have a relative standard error of at most
//! [`MAP_RESOLVED_ERROR`]; failing that, the whole surface as one cell. A map shows its
//! unresolved cells as such ([`FluxMap::resolved`]).
//!
//! The wall function's walls keep expected deposits that have no place
//! ([`crate::wall_function`]): they have no map.

use crate::estimation::run::{Estimate, Run};
use crate::model::geometry::in_plane_axes;

/// The largest relative standard error of a resolved cell.
pub const MAP_RESOLVED_ERROR: f64 = 0.3;

/// The share of a map's cells that must be resolved for [`Run::resolved_flux_map`] to take
/// its grid: three in four (cells under a box on the floor, or those an opening leaves
/// empty, need not hold the finer grid back).
pub const MAP_RESOLVED_SHARE: f64 = 0.75;

/// The most cells a map has along its surface's longer side.
pub const MAP_MOST_CELLS: usize = 24;

/// A surface's deposition velocity per cell.
#[derive(Clone, Debug, PartialEq)]
pub struct FluxMap {
    /// The surface's id ([`Run::walls`]).
    pub surface: usize,
    /// Its two in-plane axes (0 = x, 1 = y, 2 = z), in that order: rows along the first,
    /// columns along the second.
    pub axes: [usize; 2],
    /// Where the grid starts along each in-plane axis, m.
    pub low: [f64; 2],
    /// Where it ends, m.
    pub high: [f64; 2],
    /// Cells along each in-plane axis.
    pub bins: [usize; 2],
    /// Each cell's deposition velocity over the averaging window (m/s), with its standard
    /// error, events and, without an event, its 95 % upper bound; row-major.
    pub cells: Vec<Estimate>,
}

impl FluxMap {
    /// A cell's sides along the two in-plane axes, m.
    #[must_use]
    pub fn cell_size(&self) -> [f64; 2] {
        std::array::from_fn(|k| (self.high[k] - self.low[k]) / self.bins[k] as f64)
    }

    /// A cell's area, m^2.
    #[must_use]
    pub fn cell_area(&self) -> f64 {
        let [a, b] = self.cell_size();
        a * b
    }

    /// Whether cell `k` is resolved: at least one deposit event, and a relative standard
    /// error of at most [`MAP_RESOLVED_ERROR`].
    #[must_use]
    pub fn resolved(&self, k: usize) -> bool {
        let c = &self.cells[k];
        c.events > 0 && c.error <= MAP_RESOLVED_ERROR * c.value
    }

    /// The share of the cells that are resolved.
    #[must_use]
    pub fn resolved_share(&self) -> f64 {
        (0..self.cells.len()).filter(|&k| self.resolved(k)).count() as f64 / self.cells.len() as f64
    }

    /// The cells' deposition velocities integrated over the grid, over `area` (m^2): the
    /// surface's own deposition velocity when `area` is its area.
    #[must_use]
    pub fn integrated(&self, area: f64) -> f64 {
        self.cells.iter().map(|c| c.value).sum::<f64>() * self.cell_area() / area
    }
}

/// A deposit on the mapped surface: its particle, where in the surface's plane, its weight.
type Hit = (usize, [f64; 2], f64);

impl Run {
    /// The deposits of the averaging window on surface `wall` spread over a `bins` grid of
    /// the box `[low, high]` (m; the room's `[0, size]`, or a furnishing's extent) across the
    /// surface's two in-plane axes: each cell's deposition velocity (see the module docs).
    /// `None` where the run's deposits on the surface have no place (the wall function's
    /// walls) or the run has no exposure.
    #[must_use]
    pub fn flux_map(&self, wall: usize, low: [f64; 3], high: [f64; 3], bins: [usize; 2]) -> Option<FluxMap> {
        let hits = self.hits(wall)?;
        self.map_of(wall, &hits, low, high, bins)
    }

    /// [`Run::flux_map`] on the finest grid of near-square cells, up to [`MAP_MOST_CELLS`]
    /// along the longer side, on which at least [`MAP_RESOLVED_SHARE`] of the cells are
    /// resolved; the whole surface as one cell where none is (or nothing deposited).
    #[must_use]
    pub fn resolved_flux_map(&self, wall: usize, low: [f64; 3], high: [f64; 3]) -> Option<FluxMap> {
        let hits = self.hits(wall)?;
        let [a, b] = in_plane_axes(self.walls[wall].axis);
        let sides = [high[a] - low[a], high[b] - low[b]];
        let longer = sides[0].max(sides[1]);
        let mut tried = Vec::new();
        if !hits.is_empty() {
            for k in (2..=MAP_MOST_CELLS).rev() {
                let bins = sides.map(|s| ((s / longer * k as f64).round() as usize).max(1));
                if tried.contains(&bins) {
                    continue;
                }
                tried.push(bins);
                let map = self.map_of(wall, &hits, low, high, bins)?;
                if map.resolved_share() >= MAP_RESOLVED_SHARE {
                    return Some(map);
                }
            }
        }
        self.map_of(wall, &hits, low, high, [1, 1])
    }

    /// The deposits on `wall` within the window, with their particles, in particle order;
    /// `None` where they do not hold all that the surface's figure counts.
    fn hits(&self, wall: usize) -> Option<Vec<Hit>> {
        let [a, b] = in_plane_axes(self.walls[wall].axis);
        let mut hits = Vec::new();
        let (mut placed, mut counted) = (0.0, 0.0);
        for (i, p) in self.particles.iter().enumerate() {
            counted += p.deposited_on(wall);
            for l in p.landed.iter().filter(|l| l.surface as usize == wall) {
                placed += l.weight;
                hits.push((i, [f64::from(l.at[a]), f64::from(l.at[b])], l.weight));
            }
        }
        ((placed - counted).abs() <= 1e-9 * counted.abs()).then_some(hits)
    }

    /// The map of `hits` on a `bins` grid over `[low, high]`.
    fn map_of(&self, wall: usize, hits: &[Hit], low: [f64; 3], high: [f64; 3], bins: [usize; 2]) -> Option<FluxMap> {
        let axes = in_plane_axes(self.walls[wall].axis);
        let (low, high) = (axes.map(|a| low[a]), axes.map(|a| high[a]));
        let n = self.particles.len();
        let exposure: f64 = self.particles.iter().map(|p| p.exposure).sum();
        if exposure.is_nan() || exposure <= 0.0 || n < 2 {
            return None;
        }
        let squares: f64 = self.particles.iter().map(|p| p.exposure * p.exposure).sum();
        let cells = bins[0] * bins[1];
        // Per cell: sum X, sum X^2, sum X E over the particles, and the events.
        let (mut sx, mut sxx, mut sxe) = (vec![0.0; cells], vec![0.0; cells], vec![0.0; cells]);
        let mut events = vec![0usize; cells];
        let cell = |at: [f64; 2]| {
            let [i, j] = std::array::from_fn(|k| {
                (((at[k] - low[k]) / (high[k] - low[k]) * bins[k] as f64).max(0.0) as usize).min(bins[k] - 1)
            });
            i * bins[1] + j
        };
        // One particle's deposits per cell, added to the sums when its last deposit is read.
        let mut own: Vec<(usize, f64)> = Vec::new();
        let mut flush = |own: &mut Vec<(usize, f64)>, e: f64| {
            for (c, x) in own.drain(..) {
                sx[c] += x;
                sxx[c] += x * x;
                sxe[c] += x * e;
            }
        };
        for (k, &(i, at, w)) in hits.iter().enumerate() {
            let c = cell(at);
            events[c] += 1;
            match own.iter_mut().find(|(o, _)| *o == c) {
                Some(entry) => entry.1 += w,
                None => own.push((c, w)),
            }
            if hits.get(k + 1).is_none_or(|next| next.0 != i) {
                flush(&mut own, self.particles[i].exposure);
            }
        }
        let area = (high[0] - low[0]) / bins[0] as f64 * (high[1] - low[1]) / bins[1] as f64;
        let scale = self.volume / area;
        let correction = n as f64 / (n - 1) as f64;
        let cells = (0..cells)
            .map(|c| {
                // The delta method's sum of (X_i - r E_i)^2, expanded over the sums kept.
                let r = sx[c] / exposure;
                let spread = (sxx[c] - 2.0 * r * sxe[c] + r * r * squares).max(0.0);
                let error = (spread * correction).sqrt() / exposure;
                let upper_bound = if events[c] == 0 { 3.0 * self.smallest_weight / exposure } else { r + 2.0 * error };
                Estimate { value: r * scale, error: error * scale, events: events[c], upper_bound: upper_bound * scale }
            })
            .collect();
        Some(FluxMap { surface: wall, axes, low, high, bins, cells })
    }
}
