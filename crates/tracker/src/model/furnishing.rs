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
//! distance is [`axis_distance`]: to the nearest surface across axis `i`, a room wall or a
//! box face normal to `i`, the faces at their Euclidean distance from the particle. In front
//! of a face that is the distance along `i`, so the near-wall layer forms at furnishing faces
//! as at walls; beyond a face's edges it grows smoothly, so the profile has no jump at the
//! edge of a box's shadow. (A first version took a face only where the particle's projection
//! fell within it: the distance then jumped at the shadow's edge, from the face's to the
//! floor's, and particles beside a box carried the core's fluctuation normal to its faces
//! into their near-wall layers, right up to the face: ultrafine particles deposited onto a
//! box's sides five times faster than onto the room's walls, a test found.) The well-mixed
//! drift is the slope of the profile along the component's own axis, `d sigma / dd` times
//! `dd / dx_i`, the latter `+-1` in front of a face and the cosine of the direction to the
//! face's edge beyond it. Beside a box, within its extent along `i`, its faces normal to `i`
//! are edge-on and the distance is to their edge. Like the room's profiles near its corners,
//! this is a construction of depo's, not a measured flow.
//!
//! ## Excursions
//! Near-wall excursions ([`crate::excursions`]) start where a particle's gap to the nearest
//! surface falls below their layer and split it by that gap: with furnishings the gap is to
//! the nearest wall or box (the Euclidean distance to the box; for the free-flight gap, the
//! separation along each axis on which the particle lies outside the box less the stop
//! distance of its velocity towards it). So excursions start at a box's faces as at the
//! walls, and their weighted deposits on each face are tallied as on a wall.
//!
//! ## Far from the boxes
//! Each of these tests (the turbulence read, the contact test, the excursions' layer test
//! and splitting level) ignores a box beyond some reach of the point tested. A particle
//! carries a ball that no box reaches into, and a step skips the boxes wherever
//! that ball keeps them beyond the test's reach: most of a room's air and walls are far from
//! its furnishings, and there a furnished room's step costs about a bare room's, with the
//! same numbers.
//!
//! ## Volume
//! Boxes may not overlap one another (they may touch) and lie strictly inside the room (a
//! sofa on the floor stands on short legs: a gap between box and wall), so the free air volume
//! is the room's volume less the boxes' ([`free_volume`]), and it is the volume of the room's
//! well-mixed concentration, its deposition velocities and loss rate.

use crate::model::geometry::{greater, lesser, Orientation, Wall, WALL_AXES};
use crate::model::walls::WallBehaviour;

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
            let axis = WALL_AXES[f / 2];
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

    /// The squared distance from `x` to the box, m^2 (0 within it).
    #[inline(always)]
    #[must_use]
    pub fn squared_distance(&self, x: [f64; 3]) -> f64 {
        let outside = |a: usize| greater(greater(self.low[a] - x[a], x[a] - self.high[a]), 0.0);
        let [ox, oy, oz] = [outside(0), outside(1), outside(2)];
        ox * ox + oy * oy + oz * oz
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

/// For the velocity component along `axis`, the distance (m) from `x` to the nearest surface
/// across that axis, and its rate of change along the axis (the sign of the well-mixed
/// drift): the room's walls at `0` and `length` (`+1` from the lower, `-1` from the upper),
/// and each box's two faces across `axis`, at their Euclidean distance from `x` (module docs).
/// In front of a face (`x`'s projection within its rectangle) that is the distance along the
/// axis; beyond the rectangle's edges it grows smoothly, so that the profile is continuous
/// across the edge of the box's shadow. [`nearest_surfaces`] gives all three axes at once.
#[inline]
#[must_use]
pub fn axis_distance(x: [f64; 3], axis: usize, length: f64, boxes: &[Furnishing]) -> (f64, f64) {
    nearest_surfaces(x, [length; 3], boxes)[axis]
}

/// [`axis_distance`] along each of the three axes of a room of `size` (m), in one pass over
/// the boxes: a box's offsets from `x` along each axis are shared by the three.
#[inline]
#[must_use]
pub fn nearest_surfaces(x: [f64; 3], size: [f64; 3], boxes: &[Furnishing]) -> [(f64, f64); 3] {
    nearest_surfaces_within(x, size, boxes, f64::INFINITY)
}

/// [`nearest_surfaces`], with the boxes farther than `within` (m) from `x` left out: where
/// what is read at the distances is the same beyond `within` (a room's well-mixed core,
/// [`Table::flat_from`](crate::physics::turbulence::Table::flat_from)), such a box changes no read, and the
/// square root and the comparisons it takes are saved.
#[inline]
#[must_use]
pub(crate) fn nearest_surfaces_within(
    x: [f64; 3],
    size: [f64; 3],
    boxes: &[Furnishing],
    within: f64,
) -> [(f64, f64); 3] {
    let mut nearest = std::array::from_fn(|a| {
        let c = x[a];
        if c <= size[a] - c {
            (c, 1.0)
        } else {
            (size[a] - c, -1.0)
        }
    });
    for k in boxes {
        // How far `x` lies beyond the box along each axis, signed (negative below it, positive
        // above it, 0 within its extent): along its own axis the offset from the nearer face
        // across it (beside the box, within its extent, the faces are edge-on: the nearer
        // face's edge, offset 0), across the other two the lateral offsets from the face.
        let along: [f64; 3] = std::array::from_fn(|a| {
            if x[a] <= k.low[a] {
                x[a] - k.low[a]
            } else if x[a] >= k.high[a] {
                x[a] - k.high[a]
            } else {
                0.0
            }
        });
        // The box's distance is the same along every axis (the three offsets' norm); only the
        // nearest surface it is compared with differs. The square root only where the box may
        // be the nearer along some axis: a rounded root below `best` needs an exact one below
        // it, so `squared` at most `best * best` rounded.
        let squared = along[0] * along[0] + along[1] * along[1] + along[2] * along[2];
        let farthest = lesser(greater(nearest[0].0, greater(nearest[1].0, nearest[2].0)), within);
        if squared > farthest * farthest {
            continue;
        }
        let distance = squared.sqrt();
        let inverse = if distance > 0.0 { 1.0 / distance } else { 0.0 };
        for (a, (best, slope)) in nearest.iter_mut().enumerate() {
            if distance < *best {
                *best = distance;
                *slope = along[a] * inverse;
            }
        }
    }
    nearest
}

/// A ball that no furnishing reaches into: around `centre`, of radius the distance from it
/// to the nearest box. Each particle carries one ([`Clearance::around`] a step's start,
/// made anew wherever the old one no longer keeps the boxes beyond the turbulence read's
/// reach), and its step asks it which boxes can lie within some reach of a point
/// ([`Clearance::near`]): far from every box (most of a room's air, and most of its walls)
/// none can, the boxes' loops are skipped, and the step is a bare room's, with the same
/// numbers, bit for bit, as with the loops.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Clearance {
    centre: [f64; 3],
    radius: f64,
}

impl Clearance {
    /// No ball known: every box may matter.
    pub const NONE: Self = Self { centre: [0.0; 3], radius: f64::NEG_INFINITY };

    /// The ball around `x` clear of `boxes` (infinite without any).
    #[must_use]
    pub fn around(x: [f64; 3], boxes: &[Furnishing]) -> Self {
        let squared = boxes.iter().fold(f64::INFINITY, |s, b| lesser(s, b.squared_distance(x)));
        // Shrunk by far more than the rounding of the root and of `keeps`' test.
        Self { centre: x, radius: squared.sqrt() * (1.0 - 1e-9) }
    }

    /// Whether every box lies farther than `reach` (m) from `y`: `y` lies within the ball
    /// shrunk by `reach` (the distance to a box changes no faster than the point moves).
    #[inline(always)]
    #[must_use]
    pub fn keeps(&self, y: [f64; 3], reach: f64) -> bool {
        let room = self.radius - reach;
        let d = [y[0] - self.centre[0], y[1] - self.centre[1], y[2] - self.centre[2]];
        room > 0.0 && d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < room * room
    }

    /// The boxes that may lie within `reach` of `y`: none where the ball keeps them away,
    /// all of `boxes` otherwise.
    #[inline(always)]
    #[must_use]
    pub fn near<'b>(&self, boxes: &'b [Furnishing], y: [f64; 3], reach: f64) -> &'b [Furnishing] {
        if boxes.is_empty() || self.keeps(y, reach) {
            &[]
        } else {
            boxes
        }
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
    fn distance_is_to_the_nearest_surface_across_the_axis() {
        let boxes = [table()];
        // Above the table: the table top, 5 cm down, is nearer than the ceiling.
        let (d, sign) = axis_distance([1.5, 1.2, 0.8], 2, 2.5, &boxes);
        assert!((d - 0.05).abs() < 1e-12 && sign == 1.0);
        // Under it: the table's bottom, 10 cm up, is nearer than the floor 60 cm down.
        let (d, sign) = axis_distance([1.5, 1.2, 0.6], 2, 2.5, &boxes);
        assert!((d - 0.1).abs() < 1e-12 && sign == -1.0);
        // Beside it, half a metre from its edge: the table top's edge, nearer than the floor,
        // at its Euclidean distance; the drift's share along z is its cosine.
        let (d, sign) = axis_distance([0.5, 1.2, 0.8], 2, 2.5, &boxes);
        let r = (0.05f64 * 0.05 + 0.5 * 0.5).sqrt();
        assert!((d - r).abs() < 1e-12 && (sign - 0.05 / r).abs() < 1e-12, "{d} {sign}");
        // Far beside it: the floor.
        let (d, sign) = axis_distance([3.5, 1.2, 0.8], 2, 2.5, &boxes);
        assert!((d - 0.8).abs() < 1e-12 && sign == 1.0);
        // Continuous across the edge of the table's shadow.
        let inside = axis_distance([1.0 - 1e-9, 1.2, 0.8], 2, 2.5, &boxes).0;
        assert!((inside - 0.05).abs() < 1e-8);
        // Level with the table, beside it: its edge.
        let (d, sign) = axis_distance([0.9, 1.2, 0.72], 2, 2.5, &boxes);
        assert!((d - 0.1).abs() < 1e-12 && sign == 0.0);
        // Along x at the table's height: its x0 face, 10 cm on.
        let (d, sign) = axis_distance([0.9, 1.2, 0.72], 0, 4.0, &boxes);
        assert!((d - 0.1).abs() < 1e-12 && sign == -1.0);
        // Without boxes: the nearer wall.
        assert_eq!(axis_distance([0.9, 1.2, 0.72], 0, 4.0, &[]), (0.9, 1.0));
    }

    #[test]
    fn boxes_beyond_the_flat_distance_change_only_distances_beyond_it() {
        // On a grid over the room: leaving out the boxes farther than 0.3 m changes an axis's
        // nearest surface only where both it and the one kept are 0.3 m away or more.
        let size = [4.0, 3.0, 2.5];
        let boxes = [table(), Furnishing::new([3.0, 0.5, 0.001], [3.9, 2.5, 2.0])];
        let within = 0.3;
        let mut changed = 0;
        for i in 0..40 {
            for j in 0..30 {
                for k in 0..25 {
                    let x = [0.05 + 0.1 * f64::from(i), 0.05 + 0.1 * f64::from(j), 0.05 + 0.1 * f64::from(k)];
                    if boxes.iter().any(|b| b.holds(x, 0.0)) {
                        continue;
                    }
                    let (all, near) =
                        (nearest_surfaces(x, size, &boxes), nearest_surfaces_within(x, size, &boxes, within));
                    for a in 0..3 {
                        if all[a] != near[a] {
                            changed += 1;
                            assert!(
                                all[a].0 >= within && near[a].0 >= within,
                                "{x:?} axis {a}: {:?} {:?}",
                                all[a],
                                near[a]
                            );
                        }
                    }
                }
            }
        }
        assert!(changed > 1000, "{changed}: the far boxes are left out somewhere");
        assert_eq!(
            nearest_surfaces_within([1.5, 1.2, 0.8], size, &boxes, f64::INFINITY),
            nearest_surfaces([1.5, 1.2, 0.8], size, &boxes)
        );
    }

    #[test]
    fn nearest_surfaces_are_each_axis_distance_with_its_own_length() {
        let size = [4.0, 3.0, 2.5];
        let boxes = [table(), Furnishing::new([3.0, 0.5, 0.0 + 1e-3], [3.9, 2.5, 2.0])];
        // In front of, beside, on a face, on an edge, and nearer the far walls of each axis.
        for x in
            [[1.5, 1.2, 0.8], [0.5, 2.9, 2.4], [1.0, 1.2, 0.72], [2.0, 1.5, 0.75], [3.95, 2.7, 1.0], [2.5, 2.6, 2.2]]
        {
            let all = nearest_surfaces(x, size, &boxes);
            for (a, nearest) in all.iter().enumerate() {
                assert_eq!(*nearest, axis_distance(x, a, size[a], &boxes), "{x:?} axis {a}");
            }
        }
        // Far from the boxes, along y: the upper wall 0.3 m away, so the slope is -1.
        assert_eq!(nearest_surfaces([0.2, 2.7, 2.4], size, &boxes)[1], (3.0 - 2.7, -1.0));
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
