//! Supply and exhaust openings on a room's walls: what they are, how they are checked, and
//! what happens to a particle that reaches one. The mean flow they drive is
//! [`super::potential_flow`].
//!
//! Without openings a ventilated room exhausts each airborne particle at the exchange rate
//! `a` wherever it is ([`Scene::air_exchange`](crate::Scene::air_exchange)): the well-mixed
//! room. With openings ([`Scene::openings`](crate::Scene::openings)) the air enters through
//! the supply openings and leaves through the exhaust openings, and so do the particles it
//! carries: a particle leaves the room when it reaches the wall within an exhaust opening.
//!
//! ## Openings
//! An opening is a rectangle on one of the room's walls (ids as
//! [`Geometry::walls`](crate::Geometry::walls) numbers them: 0 the floor, 1 the ceiling, 2
//! and 3 at `x = 0` and `Lx`, 4 and 5 at `y = 0` and `Ly`), given by its centre and size in
//! the wall's two in-plane coordinates in the order x, y, z (the floor's and the ceiling's
//! `(x, y)`, the `x` walls' `(y, z)`, the `y` walls' `(x, z)`), and a volume flow `Q`
//! (m^3/s) through it, uniform over its area (face velocity `Q / A`). Openings lie within
//! their wall and do not overlap one another (they may touch); the supply openings' flows sum
//! to the exhaust openings' (the air's mass balance).
//!
//! ## Exchange rate
//! With openings the exchange rate IS theirs: `a = sum Q_exhaust / V`, with `V` the air's
//! volume (the room's less the furnishings'), and [`Scene::air_exchange`](crate::Scene::air_exchange)
//! must be 0 (a scene error otherwise): the uniform exhaust and the openings are two models of
//! the same ventilation, not two ventilations. [`Scene::exchange_rate`](crate::Scene::exchange_rate)
//! gives `a` either way, for what reads it (the decay fit, the indoor/outdoor ratio).
//!
//! ## Particles at the openings
//! A particle that reaches a wall (its contact plane, as for deposition) at a point within an
//! exhaust opening leaves the room: [`Fate::Exhausted`](crate::Fate::Exhausted), counted with
//! the exhausted in the run's balance. So does one that reaches the wall just beside the
//! opening in a step that read the flow within it (half a step on, with the midpoint
//! scheme): the opening's face velocity carried it there, and beside the opening the wall's
//! normal velocity is zero. Counted as deposits, such particles lined the openings' edges in
//! proportion to the step (33, 15 and 7 of 4000 at 0.3 um in a furnished room with steps of
//! 0.1, 0.05 and 0.025 s), and made the walls' deposition velocity in a ventilated room the
//! same at every size. A supply opening is part of its wall for particles (the wall's
//! behaviour acts there); it brings in clean air only.

use crate::model::error::SceneError;
use crate::model::furnishing::Furnishing;
use crate::model::geometry::{in_plane_axes, Geometry, WALL_AXES};

/// Cells of the mean-flow grid along the room's longest side.
pub const CELLS_ALONG_LONGEST: usize = 48;

/// Relative mismatch allowed between the supply and the exhaust openings' total flows.
pub const FLOW_BALANCE: f64 = 1e-9;

/// Whether an opening lets air in or out.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OpeningKind {
    /// Clean air comes in.
    Supply,
    /// Air leaves, and the particles that reach the opening with it.
    Exhaust,
}

/// A rectangular opening on a room's wall (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Opening {
    /// Supply or exhaust.
    pub kind: OpeningKind,
    /// The wall's id ([`Geometry::walls`]).
    pub wall: usize,
    /// Its centre in the wall's two in-plane coordinates, in the order x, y, z, m.
    pub center: [f64; 2],
    /// Its extent along the same two coordinates, m.
    pub size: [f64; 2],
    /// Volume flow through it, m^3/s (positive for either kind).
    pub flow: f64,
}

/// The axis a room wall is normal to and whether it is at the upper end of it, by id (as
/// [`Geometry::walls`] numbers them).
pub(crate) fn wall_axis(wall: usize) -> (usize, bool) {
    (WALL_AXES[wall / 2], wall % 2 == 1)
}

impl Opening {
    /// A supply opening on `wall`, centred at `center` with `size` (m), taking in `flow` (m^3/s).
    #[must_use]
    pub fn supply(wall: usize, center: [f64; 2], size: [f64; 2], flow: f64) -> Self {
        Self { kind: OpeningKind::Supply, wall, center, size, flow }
    }

    /// An exhaust opening on `wall`, centred at `center` with `size` (m), taking out `flow`
    /// (m^3/s).
    #[must_use]
    pub fn exhaust(wall: usize, center: [f64; 2], size: [f64; 2], flow: f64) -> Self {
        Self { kind: OpeningKind::Exhaust, wall, center, size, flow }
    }

    /// Area, m^2.
    #[must_use]
    pub fn area(&self) -> f64 {
        self.size[0] * self.size[1]
    }

    /// The face velocity `Q / A`, m/s.
    #[must_use]
    pub fn face_velocity(&self) -> f64 {
        self.flow / self.area()
    }

    /// Its extent along its wall's two in-plane axes: `[[low, high]; 2]`, m.
    #[must_use]
    pub fn bounds(&self) -> [[f64; 2]; 2] {
        std::array::from_fn(|i| [self.center[i] - 0.5 * self.size[i], self.center[i] + 0.5 * self.size[i]])
    }

    /// Whether the point `x` (on or near its wall) lies within the opening's rectangle
    /// (edges included), judged by its in-plane coordinates.
    #[inline]
    #[must_use]
    pub fn holds(&self, x: [f64; 3]) -> bool {
        let axes = in_plane_axes(wall_axis(self.wall).0);
        let b = self.bounds();
        (0..2).all(|i| x[axes[i]] >= b[i][0] && x[axes[i]] <= b[i][1])
    }

    /// Whether the interiors of two openings on the same wall overlap.
    #[must_use]
    pub fn overlaps(&self, other: &Opening) -> bool {
        let (a, b) = (self.bounds(), other.bounds());
        self.wall == other.wall && (0..2).all(|i| a[i][0] < b[i][1] && b[i][0] < a[i][1])
    }
}

/// The exhaust openings' total flow, m^3/s.
#[must_use]
pub fn exhaust_flow(openings: &[Opening]) -> f64 {
    openings.iter().filter(|o| o.kind == OpeningKind::Exhaust).map(|o| o.flow).sum()
}

/// The supply openings' total flow, m^3/s.
#[must_use]
pub fn supply_flow(openings: &[Opening]) -> f64 {
    openings.iter().filter(|o| o.kind == OpeningKind::Supply).map(|o| o.flow).sum()
}

/// Checks `openings` in `geometry` (module docs); the error names the first offending field,
/// `openings[k].wall`, `.center`, `.size`, `.flow`, or `openings` for the flows' balance.
pub fn validate(openings: &[Opening], geometry: &Geometry) -> Result<(), SceneError> {
    if openings.is_empty() {
        return Ok(());
    }
    let Geometry::Room { size } = *geometry else {
        return Err(SceneError::new("openings", openings.len() as f64, "need a room"));
    };
    for (k, o) in openings.iter().enumerate() {
        let field = |key: &str| format!("openings[{k}].{key}");
        if o.wall >= 6 {
            return Err(SceneError {
                field: field("wall"),
                value: o.wall as f64,
                requirement: "must be a room wall's id, 0 to 5",
            });
        }
        if !(o.flow.is_finite() && o.flow > 0.0) {
            return Err(SceneError { field: field("flow"), value: o.flow, requirement: "must be finite and positive" });
        }
        let axes = in_plane_axes(wall_axis(o.wall).0);
        for i in 0..2 {
            if !(o.size[i].is_finite() && o.size[i] > 0.0) {
                return Err(SceneError {
                    field: field("size"),
                    value: o.size[i],
                    requirement: "must be finite and positive",
                });
            }
            // Larger than its wall: no centre would do, the size is at fault.
            if o.size[i] > size[axes[i]] {
                return Err(SceneError {
                    field: field("size"),
                    value: o.size[i],
                    requirement: "must fit within its wall: at most the wall's extent along that axis",
                });
            }
            let [lo, hi] = o.bounds()[i];
            if !(o.center[i].is_finite() && lo >= 0.0 && hi <= size[axes[i]]) {
                return Err(SceneError {
                    field: field("center"),
                    value: o.center[i],
                    requirement: "must keep the opening (center +- size / 2) within its wall",
                });
            }
        }
        if let Some(other) = openings[..k].iter().position(|p| p.overlaps(o)) {
            // The entry as a whole: its centre and its size place it.
            return Err(SceneError {
                field: format!("openings[{k}]"),
                value: other as f64,
                requirement: "must not overlap another opening (the one at this index) on the same wall",
            });
        }
    }
    let (supply, exhaust) = (supply_flow(openings), exhaust_flow(openings));
    if supply <= 0.0 || exhaust <= 0.0 {
        return Err(SceneError::new(
            "openings",
            if supply <= 0.0 { supply } else { exhaust },
            "need a supply and an exhaust: the air that comes in must go out",
        ));
    }
    if (supply - exhaust).abs() > FLOW_BALANCE * supply.max(exhaust) {
        return Err(SceneError::new(
            "openings",
            supply - exhaust,
            "must balance: the supply openings' flows must sum to the exhaust openings' (this is the difference, m^3/s)",
        ));
    }
    Ok(())
}

/// The mean flow's grid in a room of `size` (m) with `longest` cells along its longest side:
/// cells along x, y, z (at least 2 each) and their size, m.
pub(crate) fn grid(size: [f64; 3], longest: usize) -> ([usize; 3], [f64; 3]) {
    let longest_side = size.iter().copied().fold(0.0, f64::max);
    let cells = size.map(|l| ((l / longest_side * longest as f64).round() as usize).max(2));
    (cells, std::array::from_fn(|a| size[a] / cells[a] as f64))
}

/// Checks that no furnishing covers an opening: a box whose extent overlaps an opening's
/// rectangle must stand at least one cell of the mean flow's grid ([`CELLS_ALONG_LONGEST`])
/// off that opening's wall, or the opening would blow into the box or draw from it. The
/// error names `furnishings[k]` and gives the gap, m.
pub fn validate_clearance(openings: &[Opening], boxes: &[Furnishing], size: [f64; 3]) -> Result<(), SceneError> {
    let (_, h) = grid(size, CELLS_ALONG_LONGEST);
    for (k, b) in boxes.iter().enumerate() {
        for o in openings {
            let (axis, upper) = wall_axis(o.wall);
            let axes = in_plane_axes(axis);
            let bounds = o.bounds();
            let faces = (0..2).all(|i| b.low[axes[i]] < bounds[i][1] && b.high[axes[i]] > bounds[i][0]);
            let gap = if upper { size[axis] - b.high[axis] } else { b.low[axis] };
            if faces && gap < h[axis] {
                return Err(SceneError {
                    field: format!("furnishings[{k}]"),
                    value: gap,
                    requirement: "must not cover an opening: leave a cell of the mean flow's grid (1/48 of the room's longest side) between it and an opening it faces (this is the gap, m)",
                });
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    const SIZE: [f64; 3] = [4.0, 3.0, 2.5];

    fn two_openings() -> Vec<Opening> {
        // Supply high on the x0 wall, exhaust low on the y1 wall: 60 m^3/h.
        let q = 60.0 / 3600.0;
        vec![Opening::supply(2, [1.5, 2.2], [0.4, 0.3], q), Opening::exhaust(5, [3.3, 0.3], [0.5, 0.25], q)]
    }

    #[test]
    fn bad_openings_are_refused_by_name() {
        let room = Geometry::Room { size: SIZE };
        let q = 0.01;
        let field = |openings: &[Opening]| validate(openings, &room).unwrap_err().field;
        assert!(validate(&two_openings(), &room).is_ok());
        assert!(validate(&[], &room).is_ok());
        let mut o = two_openings();
        o[1].wall = 6;
        assert_eq!(field(&o), "openings[1].wall");
        let mut o = two_openings();
        o[0].flow = f64::NAN;
        assert_eq!(field(&o), "openings[0].flow");
        let mut o = two_openings();
        o[1].size = [0.0, 0.1];
        assert_eq!(field(&o), "openings[1].size");
        // Beyond the wall: the x0 wall's in-plane coordinates are (y, z), 3 m by 2.5 m.
        let mut o = two_openings();
        o[0].center = [1.5, 2.4];
        assert_eq!(field(&o), "openings[0].center");
        // Larger than the wall: its size, whatever its centre.
        let mut o = two_openings();
        o[0].size = [3.5, 0.2];
        assert_eq!(field(&o), "openings[0].size");
        let mut o = two_openings();
        o.push(Opening::exhaust(5, [3.0, 0.3], [0.5, 0.25], q));
        assert_eq!(field(&o), "openings[2]", "overlaps the exhaust");
        // Beside it, a second exhaust unbalances the flows.
        o[2].center = [2.5, 0.3];
        let e = validate(&o, &room).unwrap_err();
        assert_eq!(e.field, "openings");
        assert!(e.requirement.contains("balance"), "{e}");
        // A supply alone.
        assert_eq!(field(&[Opening::supply(0, [1.0, 1.0], [0.2, 0.2], q)]), "openings");
        let channel = Geometry::Channel { length: 1.0, width: 1.0, height: 0.1 };
        assert_eq!(validate(&two_openings(), &channel).unwrap_err().field, "openings");
        assert!(two_openings()[1].holds([3.5, 3.0, 0.4]));
        assert!(!two_openings()[1].holds([3.56, 3.0, 0.3]));
    }
}
