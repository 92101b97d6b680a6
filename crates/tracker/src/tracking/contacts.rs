//! Wall contacts within a step: the step's trajectory ([`Flight`]), the contact time on it
//! by bisection, and what each wall does to the particle there.

use depo_wall_model::energy::{energy_loss, EnergyLoss};
use glam::DVec3;

use crate::model::furnishing::{Furnishing, ROOM_SURFACES};
use crate::model::geometry::{Wall, WALL_AXES};
use crate::model::openings::Opening;
use crate::model::walls::WallBehaviour;

use super::{relaxed, Body, Fate, Prepared, State, WallTally, BISECTIONS, MAX_CONTACTS};

/// The trajectory of one (part of a) step.
#[derive(Clone, Copy, Debug)]
pub(super) struct Flight<const EULER: bool> {
    pub(super) x0: DVec3,
    pub(super) v0: DVec3,
    pub(super) v_inf: DVec3,
    pub(super) tau: f64,
    pub(super) decay: f64,
    pub(super) relax: f64,
    /// Length of the whole step this flight belongs to, s (the Brownian share is `t / dt`).
    pub(super) dt: f64,
    pub(super) bx: DVec3,
    pub(super) bv: DVec3,
}

impl<const EULER: bool> Flight<EULER> {
    /// Position and velocity at the end of the full step.
    #[inline(always)]
    pub(super) fn end(&self) -> (DVec3, DVec3) {
        if EULER {
            let x = self.x0 + self.v0 * self.dt + self.bx;
            let v = self.v0 + (self.v_inf - self.v0) * (self.dt / self.tau) + self.bv;
            (x, v)
        } else {
            let [x0, v0, v_inf, bx, bv] = [self.x0, self.v0, self.v_inf, self.bx, self.bv].map(|q| q.to_array());
            let axis = |a: usize| relaxed(x0[a], v0[a], v_inf[a], (self.dt, self.decay, self.relax), bx[a], bv[a]);
            let [(x, vx), (y, vy), (z, vz)] = [axis(0), axis(1), axis(2)];
            (DVec3::new(x, y, z), DVec3::new(vx, vy, vz))
        }
    }

    /// Position and velocity `t` (s, `0 < t <= dt`) into the flight.
    pub(super) fn at(&self, t: f64) -> (DVec3, DVec3) {
        let share = t / self.dt;
        if EULER {
            let (_, v1) = self.end();
            (self.x0 + (self.v0 * self.dt + self.bx) * share, self.v0 + (v1 - self.v0) * share)
        } else {
            let e = (-t / self.tau).exp();
            let dv = self.v0 - self.v_inf;
            let relax = if self.tau > 0.0 { self.tau * -(-t / self.tau).exp_m1() } else { 0.0 };
            (self.x0 + self.v_inf * t + dv * relax + self.bx * share, self.v_inf + dv * e + self.bv * share)
        }
    }

    /// The same trajectory restarted at `x, v` for the remaining `left` seconds, without the
    /// Brownian increments.
    pub(super) fn restart(&self, x: DVec3, v: DVec3, left: f64) -> Self {
        let (decay, relax) = if self.tau > 0.0 {
            let h = left / self.tau;
            ((-h).exp(), self.tau * -(-h).exp_m1())
        } else {
            (0.0, 0.0)
        };
        Self { x0: x, v0: v, decay, relax, dt: left, bx: DVec3::ZERO, bv: DVec3::ZERO, ..*self }
    }
}

/// Whether a particle of contact radius `r` at `x` is clear of the domain's walls and of
/// `boxes` (`p.boxes`, or those a [`Clearance`](crate::model::furnishing::Clearance) leaves).
#[inline(always)]
pub(super) fn inside(x: DVec3, r: f64, p: &Prepared<'_>, boxes: &[Furnishing]) -> bool {
    // Periodic axes have no bounds: `[-inf, inf]`.
    let mut ok = true;
    for ((x, lower), upper) in x.to_array().into_iter().zip(p.lower).zip(p.upper) {
        ok &= (x >= lower + r) & (x <= upper - r);
    }
    // Clear of the furnishings too, each grown by `r` (none in most scenes).
    ok && (boxes.is_empty() || !boxes.iter().any(|b| b.holds(x.to_array(), r)))
}

/// The face of box `k` that a trajectory entering the box grown by `r` crosses, from `x`, a
/// point just before the entry: the face across the axis along which `x` lies farthest
/// outside (the face order of [`crate::furnishing`]).
fn entry_face(p: &Prepared<'_>, k: usize, x: DVec3, r: f64) -> Wall {
    let b = &p.boxes[k];
    let (mut best, mut face) = (f64::NEG_INFINITY, 0);
    for (i, axis) in WALL_AXES.into_iter().enumerate() {
        let below = (b.low[axis] - r) - x[axis];
        let above = x[axis] - (b.high[axis] + r);
        if below > best {
            (best, face) = (below, 2 * i);
        }
        if above > best {
            (best, face) = (above, 2 * i + 1);
        }
    }
    p.surfaces[ROOM_SURFACES + 6 * k + face]
}

#[inline(always)]
pub(super) fn wrap(mut x: DVec3, p: &Prepared<'_>) -> DVec3 {
    if !p.periodic {
        return x;
    }
    for a in 0..3 {
        if !p.walled[a] {
            x[a] = wrap_axis(x[a], p.size[a]);
        }
    }
    x
}

/// `x.rem_euclid(length)`, bit for bit, without the division where a step has left
/// `[0, length)` by less than one length (every step but the first after an extreme state):
/// `x - length` is exact there (Sterbenz), as `fmod` is, and `x + length` is what
/// `rem_euclid` computes for `-length <= x < 0`. `fmod` took a noticeable share of a channel
/// study's time (docs/performance-log.md).
#[inline(always)]
fn wrap_axis(x: f64, length: f64) -> f64 {
    if (0.0..length).contains(&x) {
        x
    } else if (length..2.0 * length).contains(&x) {
        x - length
    } else if (-length..0.0).contains(&x) {
        x + length
    } else {
        x.rem_euclid(length)
    }
}

/// How a step with wall contacts ended.
pub(super) enum AfterContacts {
    /// Still in the air, in this state at the step's end.
    Airborne(State),
    /// Gone: its fate, the time into the step and where.
    Left(Fate, f64, DVec3),
}

/// Resolves the wall contacts of a step whose end lies through a wall or inside a
/// furnishing (grown by the contact distance); the step read the flow at `read_at`.
#[cold]
pub(super) fn contacts<const EULER: bool>(
    p: &Prepared<'_>,
    body: &Body,
    mut flight: Flight<EULER>,
    mut s: State,
    read_at: DVec3,
    tally: &mut [WallTally],
) -> AfterContacts {
    // The contact plane: the radius, plus the continuity correction with Brownian motion.
    let r = body.contact;
    let mut elapsed = 0.0;
    let (mut last_wall, mut last_x) = (0, s.x);
    for _ in 0..MAX_CONTACTS {
        let (x1, v1) = flight.end();
        if inside(x1, r, p, p.boxes) {
            s.x = wrap(x1, p);
            s.v = v1;
            return AfterContacts::Airborne(s);
        }
        if !x1.is_finite() {
            return AfterContacts::Left(Fate::Escaped, elapsed, s.x);
        }
        // The earliest plane crossed: a wall's, or a furnishing face's.
        let mut first: Option<(f64, Wall)> = None;
        for wall in &p.walls {
            let plane = if wall.upper { wall.position - r } else { wall.position + r };
            let outside = |x: DVec3| if wall.upper { x[wall.axis] > plane } else { x[wall.axis] < plane };
            if !outside(x1) {
                continue;
            }
            let (mut lo, mut hi) = (0.0, flight.dt);
            for _ in 0..BISECTIONS {
                let mid = 0.5 * (lo + hi);
                if outside(flight.at(mid).0) {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            if first.is_none_or(|(t, _)| hi < t) {
                first = Some((hi, *wall));
            }
        }
        for (k, b) in p.boxes.iter().enumerate() {
            if !b.holds(x1.to_array(), r) {
                continue;
            }
            // When the trajectory enters the grown box (module docs of `furnishing`).
            let (mut lo, mut hi) = (0.0, flight.dt);
            for _ in 0..BISECTIONS {
                let mid = 0.5 * (lo + hi);
                if b.holds(flight.at(mid).0.to_array(), r) {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            if first.is_none_or(|(t, _)| hi < t) {
                let before = if lo > 0.0 { flight.at(lo).0 } else { flight.x0 };
                first = Some((hi, entry_face(p, k, before, r)));
            }
        }
        let (t, wall) = first.expect("a step ending outside crossed a wall plane");
        let (mut x, mut v) = flight.at(t);
        x[wall.axis] = if wall.upper { wall.position - r } else { wall.position + r };
        let x = wrap(x, p);
        elapsed += t;
        // Within an exhaust opening the particle leaves with the air (`crate::openings`): where
        // it reaches the wall, or where the step read the flow that carried it there. A
        // particle beside an opening whose step read the opening's face velocity (half a
        // step on, with the midpoint scheme) reaches the wall just past the edge: counted
        // as deposited, such particles lined the edges in proportion to the step (33, 15
        // and 7 of 4000 at 0.3 um with steps of 0.1, 0.05 and 0.025 s).
        let exhaust = |o: &Opening| o.wall == wall.id && (o.holds(x.to_array()) || o.holds(read_at.to_array()));
        if wall.furnishing.is_none() && p.exhausts.iter().any(exhaust) {
            return AfterContacts::Left(Fate::Exhausted, elapsed, x);
        }
        // Where a deposited particle rests: touching the wall (the contact plane is moved out
        // by the continuity correction with Brownian motion).
        let mut touching = x;
        touching[wall.axis] = if wall.upper { wall.position - body.radius } else { wall.position + body.radius };
        (last_wall, last_x) = (wall.id, touching);
        let n = DVec3::from_array(wall.normal());
        // The trajectory crossed the plane: its normal velocity points into the wall.
        let vn = v.dot(n);
        v -= n * (vn + vn.abs());
        let left = flight.dt - t;
        let w = &mut tally[wall.id];
        w.contacts += 1;
        match p.behaviours[wall.id] {
            WallBehaviour::Sink => {
                w.captures += 1;
                w.energy.deposition += 0.5 * body.aero.mass * v.length_squared();
                return AfterContacts::Left(Fate::Deposited(wall.id), elapsed, touching);
            }
            WallBehaviour::Reflect => {
                w.rebounds += 1;
                v -= 2.0 * n * v.dot(n);
                s.zeta[wall.axis] = -s.zeta[wall.axis];
                let mut v_inf = flight.v_inf;
                v_inf[wall.axis] = body.settling[wall.axis] - (v_inf[wall.axis] - body.settling[wall.axis]);
                flight = Flight { v_inf, ..flight.restart(x, v, left) };
            }
            WallBehaviour::Law { .. } if v.dot(n) >= 0.0 => {
                // Touching without closing in: resting contact.
                w.captures += 1;
                return AfterContacts::Left(Fate::Deposited(wall.id), elapsed, touching);
            }
            WallBehaviour::Law { law, size } => {
                let vc = match size {
                    Some(size) => size.capture_velocity(law.params().vc, body.aero.diameter),
                    None => law.params().vc,
                };
                let result = law.impact_with_capture_velocity(v, n, vc);
                w.energy += in_joules(energy_loss(&result), body.aero.mass);
                if !result.velocity.iter().all(|c| c.is_finite()) {
                    return AfterContacts::Left(Fate::Escaped, elapsed, x);
                }
                if result.coefficients.captured {
                    w.captures += 1;
                    return AfterContacts::Left(Fate::Deposited(wall.id), elapsed, touching);
                }
                w.rebounds += 1;
                flight = flight.restart(x, DVec3::from_array(result.velocity), left);
            }
        }
    }
    // Still bouncing: at rest on the last wall it touched.
    tally[last_wall].resting += 1;
    AfterContacts::Left(Fate::Deposited(last_wall), elapsed, last_x)
}

/// A wall law's energy budget per unit mass (J/kg) for a particle of `mass` (kg), in J.
pub(super) fn in_joules(loss: EnergyLoss<f64>, mass: f64) -> EnergyLoss<f64> {
    EnergyLoss {
        material: mass * loss.material,
        adhesion: mass * loss.adhesion,
        friction: mass * loss.friction,
        deposition: mass * loss.deposition,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The periodic wrap is `rem_euclid` bit for bit: within a length of the box on either
    /// side (where steps leave it) and far beyond, on a sweep of positions including the
    /// ends of each range (only `x = -length`, which `rem_euclid` maps to `-0.0`, gives `+0.0`).
    #[test]
    fn the_periodic_wrap_is_rem_euclid_bit_for_bit() {
        let length = 0.015_f64;
        let mut xs = vec![0.0, -0.0, length, 2.0 * length, -1e-300, length * (1.0 - f64::EPSILON), 1e6, -1e6];
        xs.extend((0..100_000).map(|i| (f64::from(i) / 25_000.0 - 2.0) * length * 1.000_37));
        for x in xs {
            assert_eq!(wrap_axis(x, length).to_bits(), x.rem_euclid(length).to_bits(), "x = {x:e}");
        }
        assert_eq!((-length).rem_euclid(length).to_bits(), (-0.0_f64).to_bits());
        assert_eq!(wrap_axis(-length, length).to_bits(), 0.0_f64.to_bits());
    }

    fn flight<const EULER: bool>(tau: f64, dt: f64) -> Flight<EULER> {
        let h = dt / tau;
        Flight {
            x0: DVec3::new(0.1, 0.2, 0.3),
            v0: DVec3::new(1.0, -2.0, 0.5),
            v_inf: DVec3::new(0.2, 0.0, -0.1),
            tau,
            decay: (-h).exp(),
            relax: tau * -(-h).exp_m1(),
            dt,
            bx: DVec3::ZERO,
            bv: DVec3::ZERO,
        }
    }

    #[test]
    fn exponential_flight_is_the_exact_drag_solution_and_composes() {
        for (tau, dt) in [(1e-3, 0.1), (0.5, 0.1), (10.0, 0.1), (0.0, 0.1)] {
            let f = flight::<false>(tau, dt);
            let (x, v) = f.end();
            let (xa, va) = f.at(dt);
            assert!((x - xa).length() < 1e-14 && (v - va).length() < 1e-14, "tau {tau}");
            // By hand: v(t) = v_inf + (v0 - v_inf) e^(-t/tau).
            let e = if tau > 0.0 { (-dt / tau).exp() } else { 0.0 };
            assert!((v - (f.v_inf + (f.v0 - f.v_inf) * e)).length() < 1e-14);
            // Stopping halfway and flying on from there ends at the same state.
            let (xm, vm) = f.at(0.4 * dt);
            let (x2, v2) = f.restart(xm, vm, 0.6 * dt).end();
            assert!((x2 - x).length() < 1e-13 && (v2 - v).length() < 1e-13, "tau {tau}: {x2} {x}");
            assert!(x.is_finite() && v.is_finite());
        }
        // Euler is first order: its end differs from the exact one by O(dt^2 / tau).
        let f = flight::<false>(0.5, 0.01);
        let (xe, _) = flight::<true>(0.5, 0.01).end();
        let leading = (f.v0 - f.v_inf).length() * 0.01 * 0.01 / (2.0 * 0.5);
        assert!(((xe - f.end().0).length() / leading - 1.0).abs() < 0.01);
    }
}
