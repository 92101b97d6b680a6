//! Where particles fly: a room (a box with six walls) or a plane channel (two walls, periodic
//! along and across the flow). `z` is up in a room and wall-normal in a channel; a channel's
//! flow runs along `x`.
//!
//! Walls are numbered so that the same number means the same thing in both: 0 is the floor
//! (`z = 0`, normal `+z`) and 1 the ceiling (`z = Lz`, normal `-z`); a room adds 2 and 3 at
//! `x = 0` and `x = Lx`, 4 and 5 at `y = 0` and `y = Ly`. A particle of radius `r` touches a
//! wall when its centre is `r` from the plane.

/// Shape and size of the domain, m.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Geometry {
    /// A closed box: floor, ceiling and four side walls. `size = [Lx, Ly, Lz]`.
    Room { size: [f64; 3] },
    /// Two parallel walls `height` apart (`z`), periodic over `length` (`x`, the flow
    /// direction) and `width` (`y`).
    Channel { length: f64, width: f64, height: f64 },
}

/// How a wall faces, for deposition velocities per orientation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Orientation {
    /// Upward-facing (a floor).
    Floor,
    /// Downward-facing (a ceiling).
    Ceiling,
    /// Vertical.
    Wall,
}

impl Orientation {
    /// `"floor"`, `"ceiling"` or `"walls"`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Orientation::Floor => "floor",
            Orientation::Ceiling => "ceiling",
            Orientation::Wall => "walls",
        }
    }
}

/// The axes the pairs of a room's walls are normal to, in id order: z (the floor, 0, and the
/// ceiling, 1), x (2 and 3), y (4 and 5); a furnishing's faces follow the same order.
pub const WALL_AXES: [usize; 3] = [2, 0, 1];

/// The two axes in the plane of a surface normal to `axis`, in the order x, y, z.
#[must_use]
pub fn in_plane_axes(axis: usize) -> [usize; 2] {
    match axis {
        0 => [1, 2],
        1 => [0, 2],
        _ => [0, 1],
    }
}

/// One wall, or one face of a furnishing ([`crate::furnishing`]): the axis it is normal to,
/// the side it faces and its plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wall {
    /// Its number (see the module docs).
    pub id: usize,
    /// The coordinate axis it is normal to (0 = x, 1 = y, 2 = z).
    pub axis: usize,
    /// True when it faces down its axis (its normal into the air is `-axis`): a room's wall
    /// at the upper end of its axis, or a furnishing's face at the lower end of its box.
    pub upper: bool,
    /// Coordinate of its plane, m.
    pub position: f64,
    /// Area, m^2.
    pub area: f64,
    /// The furnishing it is a face of, by index into
    /// [`Scene::furnishings`](crate::Scene::furnishings); `None` for the room's own walls.
    pub furnishing: Option<usize>,
}

impl Wall {
    /// Unit normal pointing into the domain.
    #[must_use]
    pub fn normal(&self) -> [f64; 3] {
        let mut n = [0.0; 3];
        n[self.axis] = if self.upper { -1.0 } else { 1.0 };
        n
    }

    /// Floor, ceiling or vertical wall (gravity along `-z`).
    #[must_use]
    pub fn orientation(&self) -> Orientation {
        match (self.axis, self.upper) {
            (2, false) => Orientation::Floor,
            (2, true) => Orientation::Ceiling,
            _ => Orientation::Wall,
        }
    }

    /// A short name: floor, ceiling, x0, x1, y0, y1 (lower and upper in a channel).
    #[must_use]
    pub fn name(&self, geometry: &Geometry) -> &'static str {
        match (geometry, self.id) {
            (Geometry::Channel { .. }, 0) => "lower",
            (Geometry::Channel { .. }, _) => "upper",
            (_, 0) => "floor",
            (_, 1) => "ceiling",
            (_, 2) => "x0",
            (_, 3) => "x1",
            (_, 4) => "y0",
            _ => "y1",
        }
    }
}

impl Geometry {
    /// `[Lx, Ly, Lz]`, m.
    #[must_use]
    pub fn size(&self) -> [f64; 3] {
        match *self {
            Geometry::Room { size } => size,
            Geometry::Channel { length, width, height } => [length, width, height],
        }
    }

    /// Which axes end in walls (the others are periodic).
    #[must_use]
    pub fn walled(&self) -> [bool; 3] {
        match self {
            Geometry::Room { .. } => [true; 3],
            Geometry::Channel { .. } => [false, false, true],
        }
    }

    /// Volume, m^3.
    #[must_use]
    pub fn volume(&self) -> f64 {
        self.size().iter().product()
    }

    /// The walls, in id order.
    #[must_use]
    pub fn walls(&self) -> Vec<Wall> {
        let size = self.size();
        let walled = self.walled();
        let mut walls = Vec::new();
        for axis in WALL_AXES {
            if !walled[axis] {
                continue;
            }
            let area = size[(axis + 1) % 3] * size[(axis + 2) % 3];
            for upper in [false, true] {
                let id = walls.len();
                walls.push(Wall {
                    id,
                    axis,
                    upper,
                    position: if upper { size[axis] } else { 0.0 },
                    area,
                    furnishing: None,
                });
            }
        }
        walls
    }

    /// The id of the wall normal to `axis` on the given side.
    #[must_use]
    pub fn wall_id(&self, axis: usize, upper: bool) -> usize {
        let base = match axis {
            2 => 0,
            0 => 2,
            _ => 4,
        };
        base + usize::from(upper)
    }

    /// Half the distance between the walls of a channel, or half the smallest room size, m.
    #[must_use]
    pub fn half_height(&self) -> f64 {
        match *self {
            Geometry::Channel { height, .. } => 0.5 * height,
            Geometry::Room { size } => 0.5 * size.iter().copied().fold(f64::INFINITY, f64::min),
        }
    }
}

/// The smaller of two distances that are not NaN (as `f64::min`, whose NaN handling costs
/// four more instructions each in the gap checks' chains of minima, run every step of an
/// excursion).
#[inline(always)]
pub(crate) fn lesser(a: f64, b: f64) -> f64 {
    if b < a {
        b
    } else {
        a
    }
}

/// The larger of two distances that are not NaN (as `f64::max`; see [`lesser`]).
#[inline(always)]
pub(crate) fn greater(a: f64, b: f64) -> f64 {
    if b > a {
        b
    } else {
        a
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn room_walls_are_numbered_floor_first_and_face_inwards() {
        let room = Geometry::Room { size: [4.0, 5.0, 2.5] };
        let walls = room.walls();
        assert_eq!(walls.len(), 6);
        assert_eq!(walls[0].normal(), [0.0, 0.0, 1.0]);
        assert_eq!(walls[1].normal(), [0.0, 0.0, -1.0]);
        assert_eq!(walls[1].position, 2.5);
        assert_eq!(walls[3].normal(), [-1.0, 0.0, 0.0]);
        assert_eq!(walls[3].area, 5.0 * 2.5);
        assert_eq!(walls[4].area, 4.0 * 2.5);
        for w in &walls {
            assert_eq!(room.wall_id(w.axis, w.upper), w.id);
        }
        let total: f64 = walls.iter().map(|w| w.area).sum();
        assert_eq!(total, 2.0 * (20.0 + 10.0 + 12.5));
        assert_eq!(walls[0].orientation(), Orientation::Floor);
        assert_eq!(walls[5].orientation(), Orientation::Wall);
    }

    #[test]
    fn channel_has_two_walls() {
        let ch = Geometry::Channel { length: 1.0, width: 0.5, height: 0.02 };
        let walls = ch.walls();
        assert_eq!(walls.len(), 2);
        assert_eq!(walls[1].position, 0.02);
        assert_eq!(walls[0].area, 0.5);
        assert_eq!(walls[0].name(&ch), "lower");
        assert_eq!(ch.half_height(), 0.01);
    }
}
