//! Furnishings: solid axis-aligned boxes inside a room (tables, shelves, sofas), whose six
//! faces are surfaces like the room's walls, each with its own wall behaviour and its own
//! deposition tally.
//!
//! ## Surfaces
//! Box `k` (from 0, in the order of [`Scene::furnishings`](crate::Scene::furnishings)) adds
//! surfaces `6 + 6k + f` after the room's six walls, its faces `f` numbered as the room's
//! walls are ([`Geometry::walls`](crate::Geometry::walls)): 0 the bottom (`z = low_z`), 1 the
//! top (`z = high_z`), 2 and 3 at `x = low_x` and `high_x`, 4 and 5 at `y = low_y` and
//! `high_y`. A face's normal points out of the box, into the air, so face 1 (the top) faces up
//! like a floor, face 0 (the bottom) down like a ceiling, and the others are vertical (see
//! [`Wall::orientation`]). Their names are the box's name and the face's:
//! `table.top`, `box1.x0`.
//!
//! ## Contacts
//! A particle of radius `r` touches a face when its centre crosses the face's plane offset by
//! `r` into the air at a point within the face's rectangle widened by `r`: the box grown by
//! `r` on every side, with sharp edges and corners (the exact contact surface of a sphere
//! would round them with radius `r`; the difference is a sliver of volume `~ r^2` per unit of
//! edge length). Contacts are searched where a step ends inside a grown box: the time the
//! step's own trajectory enters it is found by bisection, and the face is the one whose plane
//! it crosses there. A step that passes wholly through an edge of a box without ending inside
//! it is missed, as it must then cross a corner region narrower than the step's displacement
//! (millimetres in a room's turbulence at `dt = 0.05 s`).
//!
//! ## Turbulence
//! The room's dispersion model ([`crate::flow`]) gives each velocity component `i` the
//! wall-normal profile of the distance to the surfaces across its axis. With furnishings that
//! distance is [`axis_distance`]: along axis `i`, in both directions from the particle, to the
//! nearest surface, a room wall or a box face whose rectangle holds the particle's projection
//! onto the face's plane. So the near-wall layer forms at furnishing faces as at walls, and
//! the well-mixed drift stays the slope of the profile along the component's own axis, with
//! the sign of the change of this distance along the axis. The distance jumps at the edges of
//! a box's shadow (beside a table, the vertical distance is to the floor; above it, to the
//! table top), where the model, like the room's own near its corners, is a construction of
//! depo's, not a measured flow.
//!
//! ## Volume
//! Boxes may not overlap one another (they may touch) and lie strictly inside the room (a
//! sofa on the floor stands on short legs: a gap between box and wall), so the free air volume
//! is the room's volume less the boxes' ([`free_volume`]), and it is the volume of the room's
//! well-mixed concentration, its deposition velocities and loss rate.

use crate::geometry::{Orientation, Wall};
use crate::scene::WallBehaviour;

/// The names of a box's faces, in face order.
pub const FACE_NAMES: [&str; 6] = ["bottom", "top", "x0", "x1", "y0", "y1"];

/// Surfaces of the room itself, before the furnishings' faces.
pub const ROOM_SURFACES: usize = 6;

/// A solid axis-aligned box inside a room.
#[derive(Clone, Debug, PartialEq)]
pub struct Furnishing {
    /// A name for reports (`table`); `None` for `box1`, `box2`, ... by position.
    pub name: Option<String>,
    /// The corner with the smallest coordinates, m.
    pub low: [f64; 3],
    /// The corner with the largest coordinates, m.
    pub high: [f64; 3],
    /// What each face does with a particle that touches it, in face order (module docs).
    pub faces: [WallBehaviour; 6],
}

impl Furnishing {
    /// A box from `low` to `high` (m) with perfectly absorbing faces.
    #[must_use]
    pub fn new(low: [f64; 3], high: [f64; 3]) -> Self {
        Self { name: None, low, high, faces: [WallBehaviour::Sink; 6] }
    }

    /// The same with every face `behaviour`.
    #[must_use]
    pub fn with_faces(self, behaviour: WallBehaviour) -> Self {
        Self { faces: [behaviour; 6], ..self }
    }

    /// The same named `name`.
    #[must_use]
    pub fn named(self, name: &str) -> Self {
        Self { name: Some(name.to_string()), ..self }
    }

    /// Its name, or `box{k + 1}` for box `k`.
    #[must_use]
    pub fn label(&self, k: usize) -> String {
        self.name.clone().unwrap_or_else(|| format!("box{}", k + 1))
    }

    /// Volume, m^3.
    #[must_use]
    pub fn volume(&self) -> f64 {
        (0..3).map(|a| self.high[a] - self.low[a]).product()
    }

    /// Its six faces as surfaces, box `k`'s, in face order (ids `6 + 6k + f`).
    #[must_use]
    pub fn faces(&self, k: usize) -> [Wall; 6] {
        std::array::from_fn(|f| {
            let axis = [2, 0, 1][f / 2];
            let at_high = f % 2 == 1;
            let extent = |a: usize| self.high[a] - self.low[a];
            Wall {
                id: ROOM_SURFACES + 6 * k + f,
                axis,
                // The face at the box's low end faces down the axis, as a room's upper wall.
                upper: !at_high,
                position: if at_high { self.high[axis] } else { self.low[axis] },
                area: extent((axis + 1) % 3) * extent((axis + 2) % 3),
                furnishing: Some(k),
            }
        })
    }

    /// The faces' area, m^2.
    #[must_use]
    pub fn area(&self) -> f64 {
        self.faces(0).iter().map(|w| w.area).sum()
    }

    /// Whether `x` lies inside the box grown by `r` on every side (its boundary excluded).
    #[inline]
    #[must_use]
    pub fn holds(&self, x: [f64; 3], r: f64) -> bool {
        (0..3).all(|a| x[a] > self.low[a] - r && x[a] < self.high[a] + r)
    }

    /// Whether the interiors of two boxes overlap.
    #[must_use]
    pub fn overlaps(&self, other: &Furnishing) -> bool {
        (0..3).all(|a| self.low[a] < other.high[a] && other.low[a] < self.high[a])
    }

    /// The volume (m^3) the box shares with the box `[low, high]`.
    #[must_use]
    pub fn shared_volume(&self, low: [f64; 3], high: [f64; 3]) -> f64 {
        (0..3).map(|a| (self.high[a].min(high[a]) - self.low[a].max(low[a])).max(0.0)).product()
    }
}

/// The orientation of face `f` of a box (module docs): the top faces up, like a floor.
#[must_use]
pub fn face_orientation(f: usize) -> Orientation {
    match f {
        0 => Orientation::Ceiling,
        1 => Orientation::Floor,
        _ => Orientation::Wall,
    }
}

/// The free air volume of a room of `size` (m) holding `boxes`, m^3: the room's less the
/// boxes' (which do not overlap).
#[must_use]
pub fn free_volume(size: [f64; 3], boxes: &[Furnishing]) -> f64 {
    size.iter().product::<f64>() - boxes.iter().map(Furnishing::volume).sum::<f64>()
}

/// Along `axis`, the distance (m) from `x` to the nearest surface in either direction, and
/// the sign of its change along the axis (+1 where the nearest is below `x`): the room's
/// walls at `0` and `length`, and each box face across `axis` whose rectangle holds `x`'s
/// projection (module docs).
#[inline]
#[must_use]
pub fn axis_distance(x: [f64; 3], axis: usize, length: f64, boxes: &[Furnishing]) -> (f64, f64) {
    let c = x[axis];
    let (mut below, mut above) = (0.0, length);
    let (b, d) = ((axis + 1) % 3, (axis + 2) % 3);
    for k in boxes {
        if x[b] >= k.low[b] && x[b] <= k.high[b] && x[d] >= k.low[d] && x[d] <= k.high[d] {
            if k.high[axis] <= c {
                below = f64::max(below, k.high[axis]);
            } else if k.low[axis] >= c {
                above = f64::min(above, k.low[axis]);
            }
        }
    }
    let (lower, upper) = (c - below, above - c);
    if lower <= upper {
        (lower, 1.0)
    } else {
        (upper, -1.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table() -> Furnishing {
        Furnishing::new([1.0, 1.0, 0.7], [2.0, 1.5, 0.75])
    }

    #[test]
    fn faces_are_numbered_as_the_room_walls_and_face_outwards() {
        let faces = table().faces(1);
        assert_eq!(faces.map(|w| w.id), [12, 13, 14, 15, 16, 17]);
        // The top faces up like a floor; its normal points out of the box.
        assert_eq!(faces[1].normal(), [0.0, 0.0, 1.0]);
        assert_eq!(faces[1].orientation(), Orientation::Floor);
        assert_eq!(faces[1].position, 0.75);
        assert_eq!(faces[0].normal(), [0.0, 0.0, -1.0]);
        assert_eq!(faces[0].orientation(), Orientation::Ceiling);
        assert_eq!(faces[2].normal(), [-1.0, 0.0, 0.0]);
        assert_eq!(faces[2].position, 1.0);
        assert_eq!(faces[5].normal(), [0.0, 1.0, 0.0]);
        for (f, face) in faces.iter().enumerate() {
            assert_eq!(face.orientation(), face_orientation(f));
        }
        assert!((faces[1].area - 0.5).abs() < 1e-12);
        assert!((faces[2].area - 0.5 * 0.05).abs() < 1e-12);
        assert!((table().area() - 2.0 * (0.5 + 0.05 + 0.025)).abs() < 1e-12);
        assert_eq!(table().label(2), "box3");
        assert_eq!(table().named("desk").label(2), "desk");
    }

    #[test]
    fn distance_is_to_the_nearest_surface_in_the_line_of_the_axis() {
        let boxes = [table()];
        // Above the table: the table top, 5 cm down, is nearer than the ceiling.
        let (d, sign) = axis_distance([1.5, 1.2, 0.8], 2, 2.5, &boxes);
        assert!((d - 0.05).abs() < 1e-12 && sign == 1.0);
        // Under it: the table's bottom, 10 cm up, is nearer than the floor 60 cm down.
        let (d, sign) = axis_distance([1.5, 1.2, 0.6], 2, 2.5, &boxes);
        assert!((d - 0.1).abs() < 1e-12 && sign == -1.0);
        // Beside it: the floor.
        let (d, sign) = axis_distance([0.5, 1.2, 0.8], 2, 2.5, &boxes);
        assert!((d - 0.8).abs() < 1e-12 && sign == 1.0);
        // Along x at the table's height: its x0 face, 10 cm on.
        let (d, sign) = axis_distance([0.9, 1.2, 0.72], 0, 4.0, &boxes);
        assert!((d - 0.1).abs() < 1e-12 && sign == -1.0);
        // Without boxes: the nearer wall.
        assert_eq!(axis_distance([0.9, 1.2, 0.72], 0, 4.0, &[]), (0.9, 1.0));
    }

    #[test]
    fn grown_box_holds_what_touches_it() {
        let t = table();
        assert!(t.holds([1.5, 1.2, 0.76], 0.02));
        assert!(!t.holds([1.5, 1.2, 0.76], 0.005));
        assert!(!t.holds([1.5, 1.2, 0.77], 0.02), "the boundary is outside");
        assert!(t.overlaps(&Furnishing::new([1.9, 1.4, 0.0], [3.0, 3.0, 0.71])));
        assert!(!t.overlaps(&Furnishing::new([2.0, 1.0, 0.0], [3.0, 3.0, 1.0])), "touching");
        assert!((free_volume([4.0, 3.0, 2.5], std::slice::from_ref(&t)) - (30.0 - 0.025)).abs() < 1e-12);
        assert!((t.shared_volume([0.0; 3], [1.5, 3.0, 3.0]) - 0.0125).abs() < 1e-12);
    }
}
