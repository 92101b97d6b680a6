//! One subject, hence one file over 700 lines: the openings' potential flow, its solvers and the cell a particle reads it from.
//!
//! The mean flow between a room's openings ([`super::openings`]): a potential flow solved once
//! per study on a staggered grid, and the cell a particle carries to read it from step to step.
//!
//! One subject, kept whole though long: the potential flow's solve and its reads (its unit
//! tests are a quarter of it).
//!
//! ## Mean flow
//! The air between the openings moves in a potential flow: irrotational and divergence-free,
//! `u = grad phi` with
//!
//! ```text
//! lap phi = 0 in the room,   d phi / dn = Q / A on an opening (outward on an exhaust,
//!                            inward on a supply),   d phi / dn = 0 on the rest of the walls
//! ```
//!
//! (a Neumann problem, solvable because the flows balance). It has no jets, no separation and
//! no recirculation: it is the crudest flow that carries air, and the particles in it, from
//! the supply to the exhaust while conserving volume. That is enough for its purpose: a
//! supply's jet decays within a metre or so, and away from the openings the potential flow's
//! speed, `Q / (room cross-section)`, is millimetres per second (a 30 m^3 room at 2 air
//! changes per hour, 3 m wide and 2.5 m high: 2.2 mm/s), dwarfed by the core's turbulent
//! fluctuations, centimetres per second, which mix the room. What matters for deposition and
//! removal is that the exhaust takes air, and the particles in it, at the right rate from
//! where it is; near the exhaust the flow converges on it as the real flow does. The room's
//! turbulence (near-wall layers at every wall, blended into the well-mixed core,
//! [`crate::flow`]) acts on top of the mean flow, as it does without openings; at an exhaust
//! opening the wall's near-wall profile is kept (the fluctuations normal to it vanish at the
//! wall plane), so in its last millimetres a particle reaches the exhaust by the mean flow,
//! whose normal velocity there is the face velocity. The mean flow goes round the
//! furnishings (below). How well mixed the room then
//! is, and so how fast the exhaust removes particles against `a` (faster where the supply
//! displaces old air towards it, slower where supply air short-circuits to it), is the
//! turbulence's doing; docs/tracker.md gives what it measured.
//!
//! **Solution.** Cell-centred finite volumes on a uniform grid of [`CELLS_ALONG_LONGEST`]
//! cells along the room's longest side (about as wide along the others): each cell's
//! outflows sum to zero, those through the walls prescribed (an opening's face velocity
//! times the part of the cell's wall face it covers), those between cells `(phi_j - phi_i) /
//! h` times the face. The discrete Laplacian with these walls is diagonalised by the cosine
//! transform (the cell-centred DCT-II along each axis), so the system is solved exactly, to
//! rounding, by three transforms, a division by its eigenvalues and three transforms back
//! (done as dense matrix products along each axis: a few tens of millions of operations,
//! milliseconds, once per run). The velocities live on the cell faces (a staggered, "MAC",
//! grid) and are interpolated to a particle face-wise: each component linearly along its own
//! axis between the two faces of the particle's cell, constant across it (the lowest-order
//! Raviart-Thomas field), whose divergence within every cell is the cell's discrete one,
//! zero to rounding, so the interpolated flow neither gathers nor thins out particles. The
//! one exception is the normal component in a cell on a wall with openings: its value on the
//! wall is taken at the particle's own position, the opening's face velocity within an
//! opening and zero outside, rather than the wall face's average. Where an opening's edge
//! cuts a wall face, the average would push air, and the particles in it, against the solid
//! wall beside the opening, and a sink wall would collect them there. With the
//! wall's own value the normal flow on a wall is exactly the prescribed one, and only those
//! few cells are not divergence-free within themselves (they are on the whole).
//!
//! **Round furnishings.** A furnishing's box shuts every face between two cells whose
//! centres' segment crosses it (so a table top thinner than a cell still blocks the flow
//! across it), and the cells inside it are out of the problem; the Laplacian over the open
//! faces is no longer diagonalised by the cosine transform, and is solved by conjugate
//! gradients (Jacobi-preconditioned, to a residual of 1e-10 of the walls' outflows; a few
//! hundred iterations and a fifth of a second on the default grid, once per study: the runs
//! of a study share it, [`PotentialFlow::shared`]). Every cell of air keeps a zero
//! divergence. Boxes that cut a part of the room off from the rest on this grid (a gap
//! narrower than a cell counts as shut) so that the air coming in there could not leave,
//! or a solve that does not converge, are errors naming the furnishings, not a flow; so is
//! a box that covers an opening ([`validate_clearance`]). A box's face lies up to half a cell from the shut faces, so within one cell
//! of a face the interpolated component heading into it is scaled down linearly to zero at
//! the face itself: no mean flow carries particles into a box (a test: a plate under an
//! exhaust, whose underside a flow that ignored it fed at a third of `Q / A`). A cell an
//! opening feeds keeps its faces open even where a box's edge reaches into it, so that a
//! box within half a cell of an opening cannot shut the opening's flow in.
//!
//! [`CELLS_ALONG_LONGEST`]: super::openings::CELLS_ALONG_LONGEST
//! [`FLOW_BALANCE`]: super::openings::FLOW_BALANCE
//! [`validate_clearance`]: super::openings::validate_clearance

use std::sync::{Arc, Mutex};

use crate::model::error::SceneError;
use crate::model::furnishing::Furnishing;
use crate::model::geometry::in_plane_axes;
use crate::model::openings::{grid, wall_axis, Opening, OpeningKind};

/// The most conjugate-gradient iterations of the solve round furnishings (a few hundred
/// suffice on the default grid).
const MASKED_ITERATIONS: usize = 5000;

/// The potential flow between a room's openings on a staggered grid (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct PotentialFlow {
    /// Cells along x, y, z.
    cells: [usize; 3],
    /// Cell size along x, y, z, m.
    h: [f64; 3],
    /// Per axis `a`, the velocity component along `a` on the faces normal to `a`, m/s: `cells`
    /// with `cells[a] + 1` along `a`, x fastest.
    faces: [Vec<f64>; 3],
    /// Per room wall, its openings: their extent along the wall's in-plane axes and the
    /// velocity along the wall's axis within them, m/s.
    openings: [Vec<([[f64; 2]; 2], f64)>; 6],
    /// The furnishings' boxes the flow goes round, `[low, high]`, m.
    boxes: Vec<[[f64; 3]; 2]>,
}

/// A cell of a [`PotentialFlow`]'s grid, with the velocity over it where that is affine, as
/// a particle carries it from step to step ([`PotentialFlow::velocity_in`]);
/// [`FlowCell::NONE`] holds no point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlowCell {
    /// The cell's lower and upper corners, m.
    low: [f64; 3],
    high: [f64; 3],
    /// Each component at the lower corner, m/s, and its slope along its own axis, 1/s.
    base: [f64; 3],
    slope: [f64; 3],
    /// Whether `base` and `slope` give the velocity over the cell; if not,
    /// [`PotentialFlow::velocity`] does.
    affine: bool,
}

impl FlowCell {
    /// No cell yet.
    pub const NONE: Self =
        Self { low: [f64::INFINITY; 3], high: [f64::NEG_INFINITY; 3], base: [0.0; 3], slope: [0.0; 3], affine: false };

    /// Whether `x` lies within the cell (its faces included).
    #[inline]
    fn holds(&self, x: [f64; 3]) -> bool {
        (0..3).all(|a| x[a] >= self.low[a] && x[a] <= self.high[a])
    }
}

/// The inputs a flow was solved for, bit for bit.
type FlowKey = Vec<u64>;

/// The last flow solved, which the runs of a study share (one room, its openings and its
/// furnishings): solving it round furnishings takes a good part of a second.
static LAST_FLOW: Mutex<Option<(FlowKey, Arc<PotentialFlow>)>> = Mutex::new(None);

impl PotentialFlow {
    /// As [`PotentialFlow::new`], reusing the last flow solved when it was for the same
    /// inputs.
    ///
    /// # Errors
    ///
    /// As [`PotentialFlow::new`].
    pub fn shared(
        size: [f64; 3],
        openings: &[Opening],
        boxes: &[Furnishing],
        longest: usize,
    ) -> Result<Arc<Self>, SceneError> {
        let mut key: FlowKey = size.iter().map(|v| v.to_bits()).collect();
        key.push(longest as u64);
        for o in openings {
            key.extend([o.kind as u64, o.wall as u64]);
            key.extend(o.center.iter().chain(&o.size).chain([&o.flow]).map(|v| v.to_bits()));
        }
        for b in boxes {
            key.extend(b.low.iter().chain(&b.high).map(|v| v.to_bits()));
        }
        let mut last = LAST_FLOW.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        if let Some((k, flow)) = last.as_ref() {
            if *k == key {
                return Ok(Arc::clone(flow));
            }
        }
        let flow = Arc::new(Self::new(size, openings, boxes, longest)?);
        *last = Some((key, Arc::clone(&flow)));
        Ok(flow)
    }

    /// Solves the flow in a room of `size` (m) between `openings` (validated, balanced),
    /// round the furnishings `boxes`, on a grid of `longest` cells along the longest side (at
    /// least 2 along each).
    ///
    /// # Errors
    ///
    /// An error naming `furnishings` where on this grid they cut a part of the room with
    /// openings off from the rest so that its openings' flows do not balance (the air that
    /// comes in there could not leave; a gap narrower than a cell between a box and a wall
    /// counts as shut), or where the solve round them does not converge.
    pub fn new(size: [f64; 3], openings: &[Opening], boxes: &[Furnishing], longest: usize) -> Result<Self, SceneError> {
        let (cells, h) = grid(size, longest);
        let [nx, ny, nz] = cells;
        let cell_volume = h[0] * h[1] * h[2];
        let mut faces: [Vec<f64>; 3] = std::array::from_fn(|a| {
            let mut dims = cells;
            dims[a] += 1;
            vec![0.0; dims.iter().product()]
        });
        // The walls' outflows: onto the wall faces, and into the cells' balances, each
        // `L phi = -(its outflow through the walls) / V_cell` (module docs).
        let mut rhs = vec![0.0; nx * ny * nz];
        for o in openings {
            let (axis, upper) = wall_axis(o.wall);
            let [b, c] = in_plane_axes(axis);
            let bounds = o.bounds();
            let outward = match o.kind {
                OpeningKind::Exhaust => o.face_velocity(),
                OpeningKind::Supply => -o.face_velocity(),
            };
            let overlap = |j: usize, axis: usize, [lo, hi]: [f64; 2]| {
                let (a0, a1) = (j as f64 * h[axis], (j + 1) as f64 * h[axis]);
                (a1.min(hi) - a0.max(lo)).max(0.0)
            };
            for jc in 0..cells[c] {
                let oc = overlap(jc, c, bounds[1]);
                if oc <= 0.0 {
                    continue;
                }
                for jb in 0..cells[b] {
                    let ob = overlap(jb, b, bounds[0]);
                    if ob <= 0.0 {
                        continue;
                    }
                    let flux = outward * ob * oc;
                    let mut cell = [0; 3];
                    cell[axis] = if upper { cells[axis] - 1 } else { 0 };
                    cell[b] = jb;
                    cell[c] = jc;
                    rhs[cell[0] + nx * (cell[1] + ny * cell[2])] -= flux / cell_volume;
                    let mut face = cell;
                    face[axis] = if upper { cells[axis] } else { 0 };
                    let face_area = h[b] * h[c];
                    // The component along +axis: outward at the upper wall, inward at the lower.
                    let along = if upper { flux } else { -flux } / face_area;
                    faces[axis][face_index(cells, axis, face)] += along;
                }
            }
        }
        let boxes: Vec<[[f64; 3]; 2]> = boxes.iter().map(|b| [b.low, b.high]).collect();
        let open = Connections::round(cells, h, &boxes, &rhs);
        let phi = if boxes.is_empty() {
            solve_neumann(cells, h, rhs)
        } else {
            solve_masked(&open, h, &rhs)
                .map_err(|requirement| SceneError::new("furnishings", boxes.len() as f64, requirement))?
        };
        for a in 0..3 {
            for k in 0..nz {
                for j in 0..ny {
                    for i in 0..nx {
                        let cell = [i, j, k];
                        if cell[a] == 0 {
                            continue;
                        }
                        let mut below = cell;
                        below[a] -= 1;
                        let at = |c: [usize; 3]| phi[c[0] + nx * (c[1] + ny * c[2])];
                        let index = face_index(cells, a, cell);
                        faces[a][index] = if open.faces[a][index] { (at(cell) - at(below)) / h[a] } else { 0.0 };
                    }
                }
            }
        }
        let mut on_walls: [Vec<([[f64; 2]; 2], f64)>; 6] = Default::default();
        for o in openings {
            let upper = wall_axis(o.wall).1;
            let outward = if o.kind == OpeningKind::Exhaust { o.face_velocity() } else { -o.face_velocity() };
            on_walls[o.wall].push((o.bounds(), if upper { outward } else { -outward }));
        }
        Ok(Self { cells, h, faces, openings: on_walls, boxes })
    }

    /// Cells along x, y, z.
    #[must_use]
    pub fn cells(&self) -> [usize; 3] {
        self.cells
    }

    /// The velocity component along `axis` on the face normal to it at the low side of
    /// `cell` (`cell[axis]` may be `cells[axis]`, the upper wall), m/s.
    #[must_use]
    pub fn face_velocity(&self, axis: usize, cell: [usize; 3]) -> f64 {
        self.faces[axis][face_index(self.cells, axis, cell)]
    }

    /// The net outflow of cell `cell` over its volume, 1/s: the discrete divergence.
    #[must_use]
    pub fn divergence(&self, cell: [usize; 3]) -> f64 {
        (0..3)
            .map(|a| {
                let mut next = cell;
                next[a] += 1;
                (self.face_velocity(a, next) - self.face_velocity(a, cell)) / self.h[a]
            })
            .sum()
    }

    /// The outflow through room wall `wall` (its faces' velocities times their areas), m^3/s.
    #[must_use]
    pub fn wall_outflow(&self, wall: usize) -> f64 {
        let (axis, upper) = wall_axis(wall);
        let [b, c] = in_plane_axes(axis);
        let mut sum = 0.0;
        for jc in 0..self.cells[c] {
            for jb in 0..self.cells[b] {
                let mut face = [0; 3];
                face[axis] = if upper { self.cells[axis] } else { 0 };
                face[b] = jb;
                face[c] = jc;
                sum += self.face_velocity(axis, face);
            }
        }
        let outward = if upper { sum } else { -sum };
        outward * self.h[b] * self.h[c]
    }

    /// The mean velocity at `x` (m), interpolated from the faces (module docs), m/s.
    #[inline]
    #[must_use]
    pub fn velocity(&self, x: [f64; 3]) -> [f64; 3] {
        let cell = self.cell_index(x);
        let mut u: [f64; 3] = std::array::from_fn(|a| self.component(a, x, cell));
        for b in &self.boxes {
            // Most of the room is more than a cell from any box.
            if (0..3).any(|a| x[a] < b[0][a] - self.h[a] || x[a] > b[1][a] + self.h[a]) {
                continue;
            }
            for (a, ua) in u.iter_mut().enumerate() {
                let [p, q] = in_plane_axes(a);
                if x[p] < b[0][p] || x[p] > b[1][p] || x[q] < b[0][q] || x[q] > b[1][q] {
                    continue;
                }
                // Within one cell of a face the flow heads into: scaled down to zero at it.
                let gap = if *ua > 0.0 { b[0][a] - x[a] } else { x[a] - b[1][a] };
                if gap >= 0.0 && gap < self.h[a] {
                    *ua *= gap / self.h[a];
                }
            }
        }
        u
    }

    /// [`PotentialFlow::velocity`] at `x`, the same to rounding, read from `cell` where it
    /// holds `x` and the velocity is affine over it; where it does not hold `x`, `cell`
    /// becomes the grid cell that does. A particle keeps its own `cell` from step to step:
    /// it stays in one for many steps (a cell is centimetres wide, a step moves it
    /// millimetres), so most reads are six comparisons and three multiply-adds instead of
    /// locating the cell and loading its six faces.
    #[inline]
    pub fn velocity_in(&self, x: [f64; 3], cell: &mut FlowCell) -> [f64; 3] {
        if !cell.holds(x) {
            *cell = self.cell(x);
            if !cell.holds(x) {
                // Outside the grid (not a particle in the room): clamped as `velocity` does.
                *cell = FlowCell::NONE;
                return self.velocity(x);
            }
        }
        if !cell.affine {
            return self.velocity(x);
        }
        std::array::from_fn(|a| cell.base[a] + (x[a] - cell.low[a]) * cell.slope[a])
    }

    /// The indices of the grid cell holding `x` (clamped to the grid).
    #[inline]
    fn cell_index(&self, x: [f64; 3]) -> [usize; 3] {
        std::array::from_fn(|a| ((x[a] / self.h[a]).max(0.0) as usize).min(self.cells[a] - 1))
    }

    /// The grid cell holding `x`, with the velocity over it where that is affine (each
    /// component linear along its own axis): not where a furnishing's face damps the flow
    /// (within a cell of a box), nor in a cell on a wall with openings whose wall face an
    /// opening's edge cuts (the wall's value there changes across the face).
    fn cell(&self, x: [f64; 3]) -> FlowCell {
        let cell = self.cell_index(x);
        let low: [f64; 3] = std::array::from_fn(|a| cell[a] as f64 * self.h[a]);
        let high: [f64; 3] = std::array::from_fn(|a| (cell[a] + 1) as f64 * self.h[a]);
        let mut affine = FlowCell { low, high, base: [0.0; 3], slope: [0.0; 3], affine: false };
        for b in &self.boxes {
            if (0..3).all(|a| high[a] >= b[0][a] - self.h[a] && low[a] <= b[1][a] + self.h[a]) {
                return affine;
            }
        }
        for axis in 0..3 {
            let across = |wall| self.across_wall_face(wall, axis, low, high);
            let Some((below, above)) = self.faces_across(axis, cell, across) else { return affine };
            affine.base[axis] = below;
            affine.slope[axis] = (above - below) / self.h[axis];
        }
        affine.affine = true;
        affine
    }

    /// The velocity along `axis` on the two faces of `cell` normal to it; where one of them
    /// is a wall with openings, `on_wall(wall)` instead of the face's average (`None` from it
    /// gives `None`).
    #[inline]
    fn faces_across(
        &self,
        axis: usize,
        cell: [usize; 3],
        on_wall: impl Fn(usize) -> Option<f64>,
    ) -> Option<(f64, f64)> {
        let cells = self.cells;
        let low = face_index(cells, axis, cell);
        // Along `axis` in its own face array (`cells` but one more along `axis`).
        let stride = [1, cells[0], cells[0] * cells[1]][axis];
        let f = &self.faces[axis];
        let (mut below, mut above) = (f[low], f[low + stride]);
        let wall = [2, 4, 0][axis];
        if cell[axis] == 0 && !self.openings[wall].is_empty() {
            below = on_wall(wall)?;
        }
        if cell[axis] == cells[axis] - 1 && !self.openings[wall + 1].is_empty() {
            above = on_wall(wall + 1)?;
        }
        Some((below, above))
    }

    /// [`PotentialFlow::at_wall`] over the whole wall face of the cell from `low` to `high`
    /// (m): an opening's velocity where the face lies within it, zero where it meets none,
    /// `None` where an opening's edge cuts it.
    fn across_wall_face(&self, wall: usize, axis: usize, low: [f64; 3], high: [f64; 3]) -> Option<f64> {
        let [b, c] = in_plane_axes(axis);
        let mut value = 0.0;
        for (r, u) in &self.openings[wall] {
            let within = low[b] >= r[0][0] && high[b] <= r[0][1] && low[c] >= r[1][0] && high[c] <= r[1][1];
            let apart = high[b] <= r[0][0] || low[b] >= r[0][1] || high[c] <= r[1][0] || low[c] >= r[1][1];
            if within {
                value = *u;
            } else if !apart {
                return None;
            }
        }
        Some(value)
    }

    /// The component along `axis` at `x`: linear along `axis` between the two faces of the
    /// cell holding `x` normal to it, constant across it within the cell; where one of those
    /// faces is a wall with openings, the wall's value there is the opening's velocity at
    /// `x`'s in-plane position, or zero outside the openings (not the face's average).
    #[inline]
    fn component(&self, axis: usize, x: [f64; 3], cell: [usize; 3]) -> f64 {
        let t = (x[axis] / self.h[axis] - cell[axis] as f64).clamp(0.0, 1.0);
        let (below, above) =
            self.faces_across(axis, cell, |wall| Some(self.at_wall(wall, axis, x))).unwrap_or_default();
        (1.0 - t) * below + t * above
    }

    /// The velocity along `axis` on room wall `wall` (normal to it) at `x`'s in-plane
    /// position: an opening's there, zero elsewhere.
    fn at_wall(&self, wall: usize, axis: usize, x: [f64; 3]) -> f64 {
        let [b, c] = in_plane_axes(axis);
        self.openings[wall]
            .iter()
            .find(|(r, _)| x[b] >= r[0][0] && x[b] <= r[0][1] && x[c] >= r[1][0] && x[c] <= r[1][1])
            .map_or(0.0, |&(_, u)| u)
    }
}

/// Which faces between cells are open to the flow: per axis, in the face layout of
/// [`PotentialFlow::faces`] (the wall faces, never between cells, are left open).
struct Connections {
    cells: [usize; 3],
    faces: [Vec<bool>; 3],
}

impl Connections {
    /// The faces between cells whose centres' segment crosses none of `boxes`; a cell a
    /// wall's opening feeds (a nonzero `rhs`) keeps its faces open, so that a box within half
    /// a cell of an opening cannot shut the opening's flow in.
    fn round(cells: [usize; 3], h: [f64; 3], boxes: &[[[f64; 3]; 2]], rhs: &[f64]) -> Self {
        let [nx, ny, _] = cells;
        let centre = |a: usize, i: usize| (i as f64 + 0.5) * h[a];
        let faces = std::array::from_fn(|a| {
            let mut dims = cells;
            dims[a] += 1;
            let mut open = vec![true; dims.iter().product()];
            if boxes.is_empty() {
                return open;
            }
            let [p, q] = in_plane_axes(a);
            for k in 0..cells[2] {
                for j in 0..cells[1] {
                    for i in 0..cells[0] {
                        let cell = [i, j, k];
                        if cell[a] == 0 {
                            continue;
                        }
                        let mut below = cell;
                        below[a] -= 1;
                        let fed = |c: [usize; 3]| rhs[c[0] + nx * (c[1] + ny * c[2])] != 0.0;
                        if fed(cell) || fed(below) {
                            continue;
                        }
                        let (xp, xq) = (centre(p, cell[p]), centre(q, cell[q]));
                        let (from, to) = (centre(a, below[a]), centre(a, cell[a]));
                        let crosses = boxes.iter().any(|b| {
                            xp >= b[0][p]
                                && xp <= b[1][p]
                                && xq >= b[0][q]
                                && xq <= b[1][q]
                                && b[0][a] < to
                                && b[1][a] > from
                        });
                        if crosses {
                            open[face_index(cells, a, cell)] = false;
                        }
                    }
                }
            }
            open
        });
        Self { cells, faces }
    }

    /// Whether the face at the low side of `cell` along `axis` is open.
    fn open(&self, axis: usize, cell: [usize; 3]) -> bool {
        self.faces[axis][face_index(self.cells, axis, cell)]
    }
}

/// Solves `L phi = rhs` as [`solve_neumann`] does, with only the `open` faces between cells
/// carrying flow: conjugate gradients on `-L` (symmetric, positive semi-definite) with its
/// diagonal as the preconditioner, from zero, to a residual of `1e-10` of `rhs`'s, after each
/// connected part's sources are brought to a zero sum ([`balanced_parts`]). Cells with no
/// open face (inside a box) keep `phi = 0`.
///
/// # Errors
///
/// What the furnishings must do, where a part of the grid the open faces connect has sources
/// that do not sum to zero (no solution), or where the residual is not reached within
/// [`MASKED_ITERATIONS`].
fn solve_masked(open: &Connections, h: [f64; 3], rhs: &[f64]) -> Result<Vec<f64>, &'static str> {
    let cells = open.cells;
    let [nx, ny, nz] = cells;
    let n = nx * ny * nz;
    let stride = [1, nx, nx * ny];
    let weight = h.map(|h| 1.0 / (h * h));
    // Per cell, its open neighbours' offsets (signed by direction) and weights.
    let mut links: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n];
    for k in 0..nz {
        for j in 0..ny {
            for i in 0..nx {
                let cell = [i, j, k];
                let index = i + nx * (j + ny * k);
                for a in 0..3 {
                    if cell[a] > 0 && open.open(a, cell) {
                        links[index].push((index - stride[a], weight[a]));
                        links[index - stride[a]].push((index, weight[a]));
                    }
                }
            }
        }
    }
    let Some(rhs) = balanced_parts(&links, rhs) else {
        return Err("must not cut openings off from the rest of the room on the flow's grid: the air coming in there could not leave (leave a gap of at least a grid cell, 1/48 of the room's longest side, between a box and the walls)");
    };
    let apply = |x: &[f64], out: &mut [f64]| {
        for (index, l) in links.iter().enumerate() {
            out[index] = l.iter().map(|&(other, w)| w * (x[index] - x[other])).sum();
        }
    };
    let diagonal: Vec<f64> = links.iter().map(|l| l.iter().map(|&(_, w)| w).sum()).collect();
    let precondition = |r: &[f64], z: &mut [f64]| {
        for ((z, r), d) in z.iter_mut().zip(r).zip(&diagonal) {
            *z = if *d > 0.0 { r / d } else { 0.0 };
        }
    };
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(a, b)| a * b).sum::<f64>();
    // -L phi = -rhs.
    let mut r: Vec<f64> = rhs.iter().map(|v| -v).collect();
    let tolerance = 1e-10 * dot(&r, &r).sqrt();
    let mut phi = vec![0.0; n];
    let mut z = vec![0.0; n];
    precondition(&r, &mut z);
    let mut d = z.clone();
    let mut rz = dot(&r, &z);
    let mut ad = vec![0.0; n];
    for _ in 0..MASKED_ITERATIONS {
        if dot(&r, &r).sqrt() <= tolerance {
            return Ok(phi);
        }
        apply(&d, &mut ad);
        let step = rz / dot(&d, &ad);
        for ((phi, r), (d, ad)) in phi.iter_mut().zip(r.iter_mut()).zip(d.iter().zip(&ad)) {
            *phi += step * d;
            *r -= step * ad;
        }
        precondition(&r, &mut z);
        let next = dot(&r, &z);
        let beta = next / rz;
        rz = next;
        for (d, z) in d.iter_mut().zip(&z) {
            *d = z + beta * *d;
        }
    }
    if dot(&r, &r).sqrt() <= tolerance {
        Ok(phi)
    } else {
        Err("must leave a flow the solve can find: the flow round them did not converge")
    }
}

/// The sources `rhs` with each part of the grid that the `links` connect brought to a zero sum
/// (its mean taken off its cells: what the openings' flows may miss their balance by, up to
/// [`FLOW_BALANCE`], a solution needs exactly); `None` where a part's sum is beyond `1e-9` of
/// the sources' total size, a part that air comes into and cannot leave, or the reverse.
fn balanced_parts(links: &[Vec<(usize, f64)>], rhs: &[f64]) -> Option<Vec<f64>> {
    let scale: f64 = rhs.iter().map(|v| v.abs()).sum();
    let mut balanced = rhs.to_vec();
    let mut seen = vec![false; links.len()];
    let (mut stack, mut part) = (Vec::new(), Vec::new());
    for start in 0..links.len() {
        if seen[start] {
            continue;
        }
        seen[start] = true;
        stack.push(start);
        part.clear();
        let mut sum = 0.0;
        while let Some(cell) = stack.pop() {
            sum += rhs[cell];
            part.push(cell);
            for &(other, _) in &links[cell] {
                if !seen[other] {
                    seen[other] = true;
                    stack.push(other);
                }
            }
        }
        if sum.abs() > 1e-9 * scale {
            return None;
        }
        let mean = sum / part.len() as f64;
        for &cell in &part {
            balanced[cell] -= mean;
        }
    }
    Some(balanced)
}

/// Index of the face normal to `axis` at the low side of `cell` in the face array of `axis`.
fn face_index(cells: [usize; 3], axis: usize, cell: [usize; 3]) -> usize {
    let mut dims = cells;
    dims[axis] += 1;
    cell[0] + dims[0] * (cell[1] + dims[1] * cell[2])
}

/// Solves `L phi = rhs` for the cell-centred Laplacian with zero-flux walls on a grid of
/// `cells` of size `h` (m), `rhs` summing to zero: the solution of zero mean.
///
/// The 1-D Laplacian `(phi_{i-1} - 2 phi_i + phi_{i+1}) / h^2` with mirror ghost cells has
/// the eigenvectors `cos(pi k (i + 1/2) / n)` and eigenvalues `-4 / h^2 sin^2(pi k / (2 n))`,
/// `k = 0..n`: the cosine transform (DCT-II) along each axis diagonalises the 3-D one, whose
/// eigenvalues are the sums of the axes'.
fn solve_neumann(cells: [usize; 3], h: [f64; 3], mut rhs: Vec<f64>) -> Vec<f64> {
    let bases: [Vec<f64>; 3] = std::array::from_fn(|a| cosine_basis(cells[a]));
    for (a, basis) in bases.iter().enumerate() {
        transform_along(&mut rhs, cells, a, basis, false);
    }
    let eigen: [Vec<f64>; 3] = std::array::from_fn(|a| {
        let n = cells[a];
        (0..n)
            .map(|k| {
                let s = (std::f64::consts::PI * k as f64 / (2.0 * n as f64)).sin();
                -4.0 * s * s / (h[a] * h[a])
            })
            .collect()
    });
    let [nx, ny, _] = cells;
    for (index, value) in rhs.iter_mut().enumerate() {
        let (i, j, k) = (index % nx, (index / nx) % ny, index / (nx * ny));
        let lambda = eigen[0][i] + eigen[1][j] + eigen[2][k];
        // The constant mode: phi is defined up to a constant (its mean is set to zero).
        *value = if index == 0 { 0.0 } else { *value / lambda };
    }
    for (a, basis) in bases.iter().enumerate() {
        transform_along(&mut rhs, cells, a, basis, true);
    }
    rhs
}

/// The orthonormal DCT-II matrix of size `n`, row `k`: `w_k cos(pi k (i + 1/2) / n)` with
/// `w_0 = sqrt(1/n)`, `w_k = sqrt(2/n)`.
fn cosine_basis(n: usize) -> Vec<f64> {
    let mut m = vec![0.0; n * n];
    for k in 0..n {
        let w = if k == 0 { (1.0 / n as f64).sqrt() } else { (2.0 / n as f64).sqrt() };
        for i in 0..n {
            m[k * n + i] = w * (std::f64::consts::PI * k as f64 * (i as f64 + 0.5) / n as f64).cos();
        }
    }
    m
}

/// Applies the matrix `basis` (or its transpose, the inverse) along `axis` of `data`.
fn transform_along(data: &mut [f64], cells: [usize; 3], axis: usize, basis: &[f64], transpose: bool) {
    let n = cells[axis];
    let stride = match axis {
        0 => 1,
        1 => cells[0],
        _ => cells[0] * cells[1],
    };
    let mut line = vec![0.0; n];
    let mut out = vec![0.0; n];
    for start in 0..data.len() {
        // Each line once: from its first cell along `axis`.
        if (start / stride) % n != 0 {
            continue;
        }
        for (i, l) in line.iter_mut().enumerate() {
            *l = data[start + i * stride];
        }
        for (k, o) in out.iter_mut().enumerate() {
            *o = (0..n).map(|i| if transpose { basis[i * n + k] } else { basis[k * n + i] } * line[i]).sum();
        }
        for (i, o) in out.iter().enumerate() {
            data[start + i * stride] = *o;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::openings::{validate_clearance, CELLS_ALONG_LONGEST};

    const SIZE: [f64; 3] = [4.0, 3.0, 2.5];

    /// The largest discrete divergence over the flow's cells, 1/s.
    fn worst_divergence(flow: &PotentialFlow) -> f64 {
        let [nx, ny, nz] = flow.cells();
        let cells = (0..nz).flat_map(|k| (0..ny).flat_map(move |j| (0..nx).map(move |i| [i, j, k])));
        cells.map(|c| flow.divergence(c).abs()).fold(0.0, f64::max)
    }

    fn two_openings() -> Vec<Opening> {
        // Supply high on the x0 wall, exhaust low on the y1 wall: 60 m^3/h.
        let q = 60.0 / 3600.0;
        vec![Opening::supply(2, [1.5, 2.2], [0.4, 0.3], q), Opening::exhaust(5, [3.3, 0.3], [0.5, 0.25], q)]
    }

    #[test]
    fn divergence_vanishes_and_walls_carry_only_their_openings() {
        let openings = two_openings();
        let flow = PotentialFlow::new(SIZE, &openings, &[], CELLS_ALONG_LONGEST).unwrap();
        assert_eq!(flow.cells(), [48, 36, 30]);
        let q = openings[0].flow;
        // A cell's inflow is up to q / (its wall face): the scale of the divergence.
        let scale = q / (flow.h[0] * flow.h[1] * flow.h[2]);
        let worst = worst_divergence(&flow);
        assert!(worst < 1e-10 * scale, "{worst} against {scale}");
        // Through each wall: its openings' outflow, to rounding; none through the others.
        let outflows: Vec<f64> = (0..6).map(|w| flow.wall_outflow(w)).collect();
        assert!((outflows[2] + q).abs() < 1e-14, "{outflows:?}");
        assert!((outflows[5] - q).abs() < 1e-14, "{outflows:?}");
        for w in [0, 1, 3, 4] {
            assert_eq!(outflows[w], 0.0, "wall {w}");
        }
        // No flow through a solid wall, anywhere on it: the interpolated normal velocity on
        // the floor, the ceiling and the x1 wall is exactly zero.
        for (x, y) in [(0.3, 0.4), (2.0, 1.5), (3.9, 2.9)] {
            assert_eq!(flow.velocity([x, y, 0.0])[2], 0.0);
            assert_eq!(flow.velocity([x, y, 2.5])[2], 0.0);
            assert_eq!(flow.velocity([4.0, y, x.min(2.5)])[0], 0.0);
        }
        // Nor beside an opening, within the wall face its edge cuts: the exhaust spans x from
        // 3.05 to 3.55 m and z from 0.175 to 0.425 m on the y1 wall, whose faces are 1/12 m.
        for (x, z) in [(3.0, 0.3), (3.6, 0.3), (3.3, 0.15), (3.3, 0.45)] {
            assert_eq!(flow.velocity([x, 3.0, z])[1], 0.0, "{x} {z}");
            assert!(flow.velocity([x, 2.99, z])[1] > 0.0, "the air moves towards the exhaust there");
        }
        // In the middle of each opening the normal velocity is its face velocity.
        let supply = flow.velocity([0.0, 1.5, 2.2]);
        assert!((supply[0] / openings[0].face_velocity() - 1.0).abs() < 1e-9, "{supply:?}");
        let exhaust = flow.velocity([3.3, 3.0, 0.3]);
        assert!((exhaust[1] / openings[1].face_velocity() - 1.0).abs() < 1e-9, "{exhaust:?}");
        // In the core the flow is slow: millimetres per second at 60 m^3/h.
        let core = flow.velocity([2.0, 1.5, 1.25]);
        let speed = core.iter().map(|c| c * c).sum::<f64>().sqrt();
        assert!(speed > 1e-4 && speed < 1e-2, "{core:?}");
    }

    /// Openings on cell faces: the faces they cover carry exactly their flow each.
    #[test]
    fn each_opening_carries_its_flow() {
        // 48 x 36 x 30 cells of 1/12 m: openings with edges on cell faces.
        let h = 1.0 / 12.0;
        let openings = vec![
            Opening::supply(0, [6.0 * h, 6.0 * h], [4.0 * h, 4.0 * h], 0.02),
            Opening::supply(1, [30.0 * h, 18.0 * h], [6.0 * h, 2.0 * h], 0.01),
            Opening::exhaust(3, [24.0 * h, 15.0 * h], [8.0 * h, 6.0 * h], 0.03),
        ];
        let flow = PotentialFlow::new(SIZE, &openings, &[], CELLS_ALONG_LONGEST).unwrap();
        for o in &openings {
            let (axis, upper) = wall_axis(o.wall);
            let [b, c] = in_plane_axes(axis);
            let mut through = 0.0;
            for jc in 0..flow.cells[c] {
                for jb in 0..flow.cells[b] {
                    let centre = {
                        let mut x = [0.0; 3];
                        x[axis] = if upper { SIZE[axis] } else { 0.0 };
                        x[b] = (jb as f64 + 0.5) * flow.h[b];
                        x[c] = (jc as f64 + 0.5) * flow.h[c];
                        x
                    };
                    if !o.holds(centre) {
                        continue;
                    }
                    let mut face = [0; 3];
                    face[axis] = if upper { flow.cells[axis] } else { 0 };
                    face[b] = jb;
                    face[c] = jc;
                    let outward = if upper { 1.0 } else { -1.0 } * flow.face_velocity(axis, face);
                    through += outward * flow.h[b] * flow.h[c];
                }
            }
            let expected = if o.kind == OpeningKind::Exhaust { o.flow } else { -o.flow };
            assert!((through - expected).abs() < 1e-12 * o.flow, "{o:?}: {through}");
        }
    }

    /// A partition from wall to wall between the supply and the exhaust (gaps of 1 cm, an
    /// eighth of a grid cell) leaves no way out for the air that comes in: an error naming
    /// the furnishings, not a silently wrong flow; a box that covers an opening is refused by
    /// the scene's check. With a gap of two cells at one side the flow is found and goes
    /// through the gap. Openings whose flows miss their balance by what validation allows
    /// still solve round a box.
    #[test]
    fn a_partition_that_shuts_the_supply_in_is_an_error() {
        let q = 60.0 / 3600.0;
        let openings =
            vec![Opening::supply(1, [1.0, 1.5], [0.6, 0.6], q), Opening::exhaust(3, [1.5, 0.3], [0.5, 0.3], q)];
        let shut = [Furnishing::new([2.0, 0.01, 0.01], [2.2, 2.99, 2.49])];
        let err = PotentialFlow::new(SIZE, &openings, &shut, CELLS_ALONG_LONGEST).unwrap_err();
        assert_eq!(err.field, "furnishings", "{err}");
        assert!(err.requirement.starts_with("must not cut openings off"), "{err}");
        assert!(validate_clearance(&openings, &shut, SIZE).is_ok());
        // The same partition under a supply that it covers (1 cm below the ceiling): the
        // supply's cells keep their faces open, so the flow would cross the box there; the
        // scene's check refuses the box instead.
        let covered = vec![Opening::supply(1, [2.1, 1.5], [0.6, 0.6], q), openings[1]];
        let err = validate_clearance(&covered, &shut, SIZE).unwrap_err();
        assert_eq!(err.field, "furnishings[0]", "{err}");
        assert!((err.value - 0.01).abs() < 1e-12, "{err}");
        let gap = [Furnishing::new([2.0, 0.01, 0.01], [2.2, 2.83, 2.49])];
        let flow = PotentialFlow::new(SIZE, &openings, &gap, CELLS_ALONG_LONGEST).unwrap();
        let scale = q / (flow.h[0] * flow.h[1] * flow.h[2]);
        assert!(worst_divergence(&flow) < 1e-8 * scale);
        // All the air crosses x = 2.1 through the gap: the faces there beyond y = 2.83.
        let [_, ny, nz] = flow.cells();
        let i = (2.1 / flow.h[0]).round() as usize;
        let through = |gap: bool| -> f64 {
            (0..nz)
                .flat_map(|k| (0..ny).map(move |j| [i, j, k]))
                .filter(|c| ((c[1] as f64 + 0.5) * flow.h[1] > 2.83) == gap)
                .map(|c| flow.face_velocity(0, c) * flow.h[1] * flow.h[2])
                .sum()
        };
        assert!(
            (through(true) - q).abs() < 1e-9 * q && through(false).abs() < 1e-9 * q,
            "{} {}",
            through(true),
            through(false)
        );
        // Floor to ceiling through whole walls, 9e-10 apart (validation allows 1e-9), round a
        // small box.
        let whole = [
            Opening::supply(0, [2.0, 1.5], [4.0, 3.0], q),
            Opening::exhaust(1, [2.0, 1.5], [4.0, 3.0], q * (1.0 + 9e-10)),
        ];
        let small = [Furnishing::new([1.0, 1.0, 1.0], [1.5, 1.5, 1.5])];
        assert!(PotentialFlow::new(SIZE, &whole, &small, CELLS_ALONG_LONGEST).is_ok());
    }

    /// The furnished example room's shelf (0.1 m in front of the `x1` wall) and table top.
    fn shelf_and_table() -> [Furnishing; 2] {
        [Furnishing::new([3.5, 0.2, 0.3], [3.9, 2.8, 2.0]), Furnishing::new([1.0, 1.0, 0.7], [2.2, 1.8, 0.75])]
    }

    /// A shelf standing 0.1 m in front of the exhaust, and a thin table top under the
    /// supply: the flow goes round them. Every cell of air keeps a zero divergence, each
    /// opening its flow, and no air crosses a box: no face between cells whose centres a box
    /// separates carries any, and the interpolated velocity into a box vanishes at its face.
    #[test]
    fn the_flow_goes_round_furnishings() {
        let q = 60.0 / 3600.0;
        let openings =
            vec![Opening::supply(1, [1.0, 1.5], [0.6, 0.6], q), Opening::exhaust(3, [1.5, 0.3], [0.5, 0.3], q)];
        let boxes = shelf_and_table();
        let started = std::time::Instant::now();
        let flow = PotentialFlow::new(SIZE, &openings, &boxes, CELLS_ALONG_LONGEST).unwrap();
        let solve = started.elapsed();
        let bare = PotentialFlow::new(SIZE, &openings, &[], CELLS_ALONG_LONGEST).unwrap();
        let scale = q / (flow.h[0] * flow.h[1] * flow.h[2]);
        let worst = worst_divergence(&flow);
        assert!(worst < 1e-8 * scale, "{worst} against {scale} ({solve:?})");
        assert!((flow.wall_outflow(1) + q).abs() < 1e-12 && (flow.wall_outflow(3) - q).abs() < 1e-12);
        // Between cells 41 and 42 along x (centres 3.458 and 3.542 m) at the shelf's height
        // and width: shut; the bare room's flow crosses there.
        let (j, k) = (18, 12); // y 1.54 m, z 1.04 m
        assert_eq!(flow.face_velocity(0, [42, j, k]), 0.0);
        assert_eq!(flow.face_velocity(0, [46, j, k]), 0.0);
        assert!(bare.face_velocity(0, [42, j, k]) != 0.0);
        // Just in front of the shelf's face towards the room and the table top's face towards
        // the supply: no velocity into them.
        for y in [0.5, 1.5, 2.5] {
            for z in [0.5, 1.0, 1.9] {
                assert!(flow.velocity([3.5 - 1e-9, y, z])[0] <= 1e-12, "{y} {z}");
            }
        }
        for (x, y) in [(1.1, 1.1), (1.6, 1.4), (2.1, 1.7)] {
            let top = flow.velocity([x, y, 0.75 + 1e-9])[2];
            assert!(top >= -1e-12, "{x} {y}: {top}");
            assert!(bare.velocity([x, y, 0.75])[2] < 0.0, "the bare room's flow goes down through it");
        }
        // Below the shelf the air still reaches the exhaust.
        assert!(flow.velocity([3.95, 1.5, 0.2])[0] > 0.0);
    }

    /// A particle's cached cell gives the direct read's velocity, to rounding, at every point
    /// of random walks through a furnished room whose openings' edges cut wall faces (the
    /// supply's centre is off the grid's lines), in cells it caches and cells it does not.
    #[test]
    fn a_cached_cell_reads_the_flow_as_the_direct_read() {
        use rand::RngExt;
        let q = 60.0 / 3600.0;
        let openings =
            vec![Opening::supply(1, [1.03, 1.51], [0.6, 0.6], q), Opening::exhaust(3, [1.5, 0.3], [0.5, 0.3], q)];
        let flow = PotentialFlow::new(SIZE, &openings, &shelf_and_table(), CELLS_ALONG_LONGEST).unwrap();
        let mut rng = crate::physics::noise::particle_rng(7, 0);
        let (mut cached, mut reads) = (0, 0);
        for _ in 0..200 {
            let mut x: [f64; 3] = std::array::from_fn(|a| rng.random_range(0.0..SIZE[a]));
            let mut cell = FlowCell::NONE;
            for _ in 0..500 {
                let direct = flow.velocity(x);
                let read = flow.velocity_in(x, &mut cell);
                for a in 0..3 {
                    assert!(
                        (read[a] - direct[a]).abs() <= 1e-12 * (1.0 + direct[a].abs()),
                        "{x:?}: {read:?} {direct:?}"
                    );
                }
                reads += 1;
                cached += usize::from(cell.affine && cell.holds(x));
                for a in 0..3 {
                    x[a] = (x[a] + rng.random_range(-0.01..0.01)).clamp(0.0, SIZE[a]);
                }
            }
        }
        // Most reads come from a cached affine cell; some (by boxes, at openings' edges) not.
        assert!(cached > reads * 8 / 10 && cached < reads, "{cached} of {reads}");
        // Just under the ceiling, across the supply's edge at x = 0.73 m, which cuts a cell's
        // ceiling face: zero beside the supply, its face velocity under it.
        let mut cell = FlowCell::NONE;
        for i in 0..=600 {
            let x = [0.6 + 3e-4 * f64::from(i), 1.51, 2.499];
            let (read, direct) = (flow.velocity_in(x, &mut cell), flow.velocity(x));
            assert!((read[2] - direct[2]).abs() <= 1e-12, "{x:?}: {read:?} {direct:?}");
        }
    }

    /// Supply over the whole x0 wall, exhaust over the whole x1 wall: plug flow,
    /// `Q / (Ly Lz)` along x everywhere.
    #[test]
    fn whole_walls_give_uniform_flow() {
        let q = 0.15;
        let openings =
            vec![Opening::supply(2, [1.5, 1.25], [3.0, 2.5], q), Opening::exhaust(3, [1.5, 1.25], [3.0, 2.5], q)];
        let flow = PotentialFlow::new(SIZE, &openings, &[], 40).unwrap();
        let u = q / (3.0 * 2.5);
        for x in [[0.0, 0.0, 0.0], [0.01, 2.9, 1.0], [2.0, 1.5, 1.25], [3.99, 0.2, 2.49], [4.0, 3.0, 2.5]] {
            let v = flow.velocity(x);
            assert!((v[0] / u - 1.0).abs() < 1e-12, "{x:?}: {v:?}");
            assert!(v[1].abs() < 1e-14 && v[2].abs() < 1e-14, "{x:?}: {v:?}");
        }
    }
}
